// Flag: a 1.5 m x 1 m rectangle hanging in the plane y = 0 (x along the flag, z up),
// its short edge x = 0 on the pole, unstructured triangles (about 430 vertices).
// Groups: "pole" = the edge x = 0; "free_corner" = (1.5, 0, 1); "flag" = the surface.
lc = 0.07;
Point(1) = {0, 0, 0, lc};
Point(2) = {1.5, 0, 0, lc};
Point(3) = {1.5, 0, 1, lc};
Point(4) = {0, 0, 1, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("pole") = {4};
Physical Point("free_corner") = {3};
Physical Surface("flag") = {1};
Mesh.MshFileVersion = 4.1;
