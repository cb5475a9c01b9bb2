// Heavy cantilever (the fabric bending-length test, ASTM D1388 / Peirce): a strip L = 1 m
// by b = 0.1 m in the plane z = 0 (x along the strip), unstructured triangles. The free end
// x = 1 has a vertex at mid-width (probe).
// Groups: "clamped" = the edge x = 0; "tip" = (1, 0.05); "strip" = the surface.
lc = 0.05;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {1, 0.05, 0, lc};
Point(4) = {1, 0.1, 0, lc};
Point(5) = {0, 0.1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Physical Curve("clamped") = {5};
Physical Point("tip") = {3};
Physical Surface("strip") = {1};
Mesh.MshFileVersion = 4.1;
