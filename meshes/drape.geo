// Drape scene: a 1 m x 1 m sheet lying horizontally in the plane z = 0, unstructured
// triangles (about 1,300 vertices).
// Groups: "pinned" = the corners (0, 1, 0) and (1, 1, 0); "cloth" = the surface.
lc = 0.03;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {1, 1, 0, lc};
Point(4) = {0, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Point("pinned") = {3, 4};
Physical Surface("cloth") = {1};
Mesh.MshFileVersion = 4.1;
