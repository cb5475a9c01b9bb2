// A 1 m x 1 m square plate, [0, 1]² in the plane z = 0, for symmetry tests: four
// quadrants of n x n cells each with alternating diagonals, each the mirror image of its
// neighbours (every transfinite pattern starts at the plate's corner), so that the mesh
// is symmetric about x = 0.5 and y = 0.5 and its lower-left quadrant is plate-quarter.geo.
// Groups: "edges" = the four edges; "plate" = the surface.
n = 8;
Point(1) = {0, 0, 0};
Point(2) = {0.5, 0, 0};
Point(3) = {1, 0, 0};
Point(4) = {0, 0.5, 0};
Point(5) = {0.5, 0.5, 0};
Point(6) = {1, 0.5, 0};
Point(7) = {0, 1, 0};
Point(8) = {0.5, 1, 0};
Point(9) = {1, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {4, 5};
Line(4) = {5, 6};
Line(5) = {7, 8};
Line(6) = {8, 9};
Line(7) = {1, 4};
Line(8) = {4, 7};
Line(9) = {2, 5};
Line(10) = {5, 8};
Line(11) = {3, 6};
Line(12) = {6, 9};
Curve Loop(1) = {1, 9, -3, -7};
Curve Loop(2) = {2, 11, -4, -9};
Curve Loop(3) = {3, 10, -5, -8};
Curve Loop(4) = {4, 12, -6, -10};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Plane Surface(3) = {3};
Plane Surface(4) = {4};
Transfinite Curve{1:12} = n + 1;
Transfinite Surface{1} = {1, 2, 5, 4} Alternate;
Transfinite Surface{2} = {3, 2, 5, 6} Alternate;
Transfinite Surface{3} = {7, 8, 5, 4} Alternate;
Transfinite Surface{4} = {9, 8, 5, 6} Alternate;
Physical Curve("edges") = {1, 2, 11, 12, 5, 6, 7, 8};
Physical Surface("plate") = {1, 2, 3, 4};
Mesh.MshFileVersion = 4.1;
