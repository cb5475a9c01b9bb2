// The performance bar's sheet: 1 m x 1 m hanging in the plane y = 0 like sheet.geo, as a
// structured 81 x 81-vertex grid (6,561 vertices, 12,800 triangles).
// Groups: "pinned" = the two top corners (z = 1); "top" = the top edge; "cloth" = the surface.
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
Transfinite Curve{1, 2, 3, 4} = 81;
Transfinite Surface{1};
Physical Point("pinned") = {3, 4};
Physical Curve("top") = {3};
Physical Surface("cloth") = {1};
Mesh.MshFileVersion = 4.1;
