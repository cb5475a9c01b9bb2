// A shallow sinusoidal arch: a strip of span L = 1 m and width b = 0.05 m whose rest shape
// is z = e sin(pi x / L), rise e = 0.01 m, x along the span. n x m cells with alternating
// diagonals (n along the span: -setnumber n 128 for a finer mesh); the long edges are
// splines through n + 1 points of the sine, so the vertices lie on it to ~1e-9 m.
// Groups: "left" = the end x = 0; "right" = the end x = L; "arch" = the surface.
DefineConstant[ n = 64 ];
m = 2;
L = 1;
b = 0.05;
e = 0.01;
For i In {0 : n}
  Point(1 + i) = {i * L / n, 0, e * Sin(Pi * i / n)};
  Point(1001 + i) = {i * L / n, b, e * Sin(Pi * i / n)};
EndFor
Spline(1) = {1 : n + 1};
Line(2) = {n + 1, 1001 + n};
Spline(3) = {1001 + n : 1001 : -1};
Line(4) = {1001, 1};
Curve Loop(1) = {1, 2, 3, 4};
Surface(1) = {1};
Transfinite Curve{1, 3} = n + 1;
Transfinite Curve{2, 4} = m + 1;
Transfinite Surface{1} = {1, n + 1, 1001 + n, 1001} Alternate;
Physical Curve("left") = {4};
Physical Curve("right") = {2};
Physical Surface("arch") = {1};
Mesh.MshFileVersion = 4.1;
