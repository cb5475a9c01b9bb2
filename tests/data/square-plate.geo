// Square plate a = 1 in the plane z = 0, unstructured triangles, for the linear plate test
// (tests/bending_plate.cc). The centre (0.5, 0.5) is a mesh vertex (probe).
// Groups: "edges" = all four sides; "centre" = (0.5, 0.5); "plate" = the surface.
lc = 0.2;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {1, 1, 0, lc};
Point(4) = {0, 1, 0, lc};
Point(5) = {0.5, 0.5, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point{5} In Surface{1};
Physical Curve("edges") = {1, 2, 3, 4};
Physical Point("centre") = {5};
Physical Surface("plate") = {1};
Mesh.MshFileVersion = 4.1;
