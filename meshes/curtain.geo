// Curtain: a 1.2 m x 2 m rectangle hanging in the plane y = 0 (x across, z up), its top
// edge z = 2 on the rail, unstructured triangles (about 560 vertices).
// Groups: "rail" = the top edge z = 2; "curtain" = the surface.
lc = 0.075;
Point(1) = {0, 0, 0, lc};
Point(2) = {1.2, 0, 0, lc};
Point(3) = {1.2, 0, 2, lc};
Point(4) = {0, 0, 2, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("rail") = {3};
Physical Surface("curtain") = {1};
Mesh.MshFileVersion = 4.1;
