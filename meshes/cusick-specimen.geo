// The Cusick drape test's specimen (ISO 9073-9, BS 5058): a circular disc of fabric of
// 30 cm diameter, centred at the origin in the plane z = 0, unstructured triangles of
// size about lc (0.01 m: about 800 vertices).
// Groups: "cloth" = the surface.
lc = 0.01;
Point(1) = {0, 0, 0, lc};
Point(2) = {0.15, 0, 0, lc};
Point(3) = {0, 0.15, 0, lc};
Point(4) = {-0.15, 0, 0, lc};
Point(5) = {0, -0.15, 0, lc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point{1} In Surface{1};
Physical Surface("cloth") = {1};
Mesh.MshFileVersion = 4.1;
