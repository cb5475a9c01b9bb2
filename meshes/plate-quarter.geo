// A quarter of the 1 m x 1 m square plate of plate-full.geo: [0, 0.5]² in the plane z = 0,
// n x n cells with alternating diagonals, exactly the lower-left quadrant of that mesh.
// Groups: "outer" = the plate's edges x = 0 and y = 0; "sym_x" = the symmetry line
// x = 0.5; "sym_y" = the symmetry line y = 0.5; "plate" = the surface.
n = 8;
Point(1) = {0, 0, 0};
Point(2) = {0.5, 0, 0};
Point(3) = {0.5, 0.5, 0};
Point(4) = {0, 0.5, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n + 1;
Transfinite Surface{1} = {1, 2, 3, 4} Alternate;
Physical Curve("outer") = {1, 4};
Physical Curve("sym_x") = {2};
Physical Curve("sym_y") = {3};
Physical Surface("plate") = {1};
Mesh.MshFileVersion = 4.1;
