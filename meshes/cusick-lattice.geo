// The Cusick drape test's specimen (ISO 9073-9) on an equilateral lattice: a circular
// disc of fabric of 30 cm diameter centred at the origin in the plane z = 0, its
// interior an equilateral triangular lattice of spacing h (default 1 cm: 841 vertices;
// -setnumber h 0.005 for 3,295, 0.0025 for 13,143), joined to boundary nodes about h
// apart on the circle by a band of Delaunay triangles. The shell's bending energy is
// accurate on equilateral lattices in every direction (../shared/BENDING.md: 0.97-0.99 of
// the exact energy), where on unstructured meshes it converges from below at O(h), so the
// drape's folds are resolved with less refinement. The lattice points are embedded in
// the surface and every mesh size is h, so gmsh adds no point inside.
// With hb > 0 (-setnumber hb 0.0025) the band |r - 9 cm| < 1 cm, where the specimen leaves
// the disc and its strain concentrates, is meshed with unstructured triangles of about hb
// instead (README, "Contact with obstacles": with hb = h/2 the drape coefficient converges).
// Groups: "cloth" = the surface.
DefineConstant[ h = 0.01, hb = 0 ];
rb   = 0.09; // the rim's radius, m
band = 0.01; // the band's half-width, m
R = 0.15;
Point(1) = {0, 0, 0, h};
Point(2) = {R, 0, 0, h};
Point(3) = {0, R, 0, h};
Point(4) = {-R, 0, 0, h};
Point(5) = {0, -R, 0, h};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point{1} In Surface{1};

// Lattice points (i + j/2) h e_x + j (√3/2) h e_y inside the circle of radius R - 0.7 h
// (the band keeps boundary triangles from becoming slivers); the origin is point 1.
s  = Sqrt(3) / 2;
ni = Ceil(R / h) + 1;
nj = Ceil(R / (s * h)) + 1;
p  = 10;
For j In {-nj : nj}
  For i In {-2 * ni : 2 * ni}
    x = (i + j / 2) * h;
    y = j * s * h;
    r = Sqrt(x * x + y * y);
    If (r < R - 0.7 * h && (hb <= 0 || Fabs(r - rb) > band) && (i != 0 || j != 0))
      p += 1;
      Point(p) = {x, y, 0, h};
      Point{p} In Surface{1};
    EndIf
  EndFor
EndFor

// The band's size field: hb inside, growing to 1.5 h (more than the lattice needs, so
// gmsh adds nothing there) over h outside it.
If (hb > 0)
  Field[1] = MathEval;
  Field[1].F = Sprintf("%g + (%g - %g) * Min(1, Max(0, Abs(Sqrt(x*x + y*y) - %g) - %g) / %g)",
                       hb, 1.5 * h, hb, rb, band, h);
  Background Field = 1;
  Mesh.MeshSizeFromPoints = 0;
Else
  Mesh.MeshSizeFromPoints = 1;
EndIf

Physical Surface("cloth") = {1};
Mesh.Algorithm = 5;                   // Delaunay: the lattice's own triangles
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MshFileVersion = 4.1;
