// Cantilever strip of Sze, Liu & Lo (2004): L = 10, b = 1 in the plane z = 0 (x along the
// strip), unstructured triangles. The loaded end x = 10 has a vertex at mid-width (probe).
// Groups: "clamped" = the edge x = 0; "tip_edge" = the edge x = 10; "tip" = (10, 0.5);
// "strip" = the surface.
lc = 0.5;
Point(1) = {0, 0, 0, lc};
Point(2) = {10, 0, 0, lc};
Point(3) = {10, 0.5, 0, lc};
Point(4) = {10, 1, 0, lc};
Point(5) = {0, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Physical Curve("clamped") = {5};
Physical Curve("tip_edge") = {2, 3};
Physical Point("tip") = {3};
Physical Surface("strip") = {1};
Mesh.MshFileVersion = 4.1;
