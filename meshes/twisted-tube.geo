// A tube of cloth for the twisted-tube scene (params/contact/twisted-tube.prm): a
// cylinder of radius 8 cm about the z axis from z = 0 to z = 0.5 m, open at both ends.
// Structured: 32 vertices around (1.6 cm), 25 rings along (2.1 cm), each quad split
// along one diagonal. Groups: "cloth" = the surface, "bottom" and "top" = the end rings.
r = 0.08;
L = 0.5;
Point(1) = {0, 0, 0};
Point(2) = {r, 0, 0};
Point(3) = {0, r, 0};
Point(4) = {-r, 0, 0};
Point(5) = {0, -r, 0};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Transfinite Curve{1, 2, 3, 4} = 9;
a[] = Extrude {0, 0, L} { Curve{1}; Layers{24}; };
b[] = Extrude {0, 0, L} { Curve{2}; Layers{24}; };
c[] = Extrude {0, 0, L} { Curve{3}; Layers{24}; };
d[] = Extrude {0, 0, L} { Curve{4}; Layers{24}; };
Physical Surface("cloth") = {a[1], b[1], c[1], d[1]};
Physical Curve("bottom") = {1, 2, 3, 4};
Physical Curve("top") = {a[0], b[0], c[0], d[0]};
Mesh.MshFileVersion = 4.1;
