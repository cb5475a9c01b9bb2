// Unit square sheet [0, 1]² in the plane z = 0, unstructured triangles, for the isometric
// bending test (tests/bending_isometric.cc), whose every vertex is prescribed.
// Groups: "sheet" = the surface.
lc = 0.1;
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
Physical Surface("sheet") = {1};
Mesh.MshFileVersion = 4.1;
