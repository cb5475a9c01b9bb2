// Poorly shaped triangles: the default scene's 1 m x 1 m sheet (plane y = 0, x to the
// right, z up) as a structured 100 x 5 grid of 0.01 m x 0.2 m cells, each split into two
// right triangles of legs 0.01 and 0.2 m: aspect ratio (longest edge over shortest
// altitude) about 20. 606 vertices, 1,000 triangles. For tests/stability_extremes.cc.
// Groups as in sheet.geo: "pinned" = the two top corners (z = 1); "top" = the top edge;
// "cloth" = the surface.
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 0, 1};
Point(4) = {0, 0, 1};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve {1, 3} = 101; // 100 cells along x
Transfinite Curve {2, 4} = 6;   // 5 cells along z
Transfinite Surface {1};
Physical Point("pinned") = {3, 4};
Physical Curve("top") = {3};
Physical Surface("cloth") = {1};
Mesh.MshFileVersion = 4.1;
