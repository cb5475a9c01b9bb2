// Default scene: a 1 m x 1 m sheet hanging in the plane y = 0 (x to the right, z up),
// unstructured triangles (about 2,800 vertices).
// Groups: "pinned" = the two top corners (z = 1); "top" = the top edge; "cloth" = the surface.
lc = 0.021;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {1, 0, 1, lc};
Point(4) = {0, 0, 1, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Point("pinned") = {3, 4};
Physical Curve("top") = {3};
Physical Surface("cloth") = {1};
Mesh.MshFileVersion = 4.1;
