// A long cloth strip held upright, for the pile scene (params/contact/strip-pile.prm): 1 m
// long, 10 cm wide, its lower end 5 cm above the ground plane z = 0 and its upper end
// leaning 5 cm towards +y, so that it folds one way when it lands. Structured, 6 x 51
// vertices (2 cm triangles), alternating diagonals. Group "cloth" = the surface.
Point(1) = {0, 0, 0.05};
Point(2) = {0.1, 0, 0.05};
Point(3) = {0.1, 0.05, 1.05};
Point(4) = {0, 0.05, 1.05};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 6;
Transfinite Curve{2, 4} = 51;
Transfinite Surface{1} Alternate;
Physical Surface("cloth") = {1};
Mesh.MshFileVersion = 4.1;
