// Two stacked sheets (params/contact/stacked-sheets.prm): "bottom", 1.5 m x 0.5 m in the
// plane z = 0 (31 x 11 vertices), and "top", 0.3 m x 0.3 m 1 mm above it (7 x 7
// vertices), shifted off the bottom's grid lines. Both 5 cm triangles, alternating
// diagonals; two pieces of one mesh.
Point(1) = {0, 0, 0};
Point(2) = {1.5, 0, 0};
Point(3) = {1.5, 0.5, 0};
Point(4) = {0, 0.5, 0};
Point(5) = {0.113, 0.121, 0.001};
Point(6) = {0.413, 0.121, 0.001};
Point(7) = {0.413, 0.421, 0.001};
Point(8) = {0.113, 0.421, 0.001};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Transfinite Curve{1, 3} = 31;
Transfinite Curve{2, 4} = 11;
Transfinite Curve{5, 6, 7, 8} = 7;
Transfinite Surface{1} Alternate;
Transfinite Surface{2} Alternate;
Physical Surface("bottom") = {1};
Physical Surface("top") = {2};
Mesh.MshFileVersion = 4.1;
