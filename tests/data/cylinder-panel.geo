// Cylindrical panel for the curved-rest-shape test (tests/bending_curved_rest.cc): radius
// R = 1 about the y axis (axis through the origin), opening angle 60° (θ from -30° to 30°,
// x = R sin θ, z = R cos θ), length 1 along y; unstructured triangles. The arc is a gmsh
// Circle and the surface its extrusion along y, so every mesh vertex lies on the exact
// cylinder.
// Groups: "arc_start" = the arc y = 0, "arc_end" = the arc y = 1, "sides" = the two
// straight edges θ = ±30°; "panel" = the surface.
R     = 1;
angle = Pi / 6;
lc    = 0.2;
Point(1) = {0, 0, 0, lc};
Point(2) = {-R * Sin(angle), 0, R * Cos(angle), lc};
Point(3) = {R * Sin(angle), 0, R * Cos(angle), lc};
Circle(1) = {2, 1, 3};
panel[] = Extrude {0, 1, 0} { Curve{1}; };
// panel[0]: the arc y = 1, panel[1]: the surface, panel[2], panel[3]: the straight sides.
Physical Curve("arc_start") = {1};
Physical Curve("arc_end") = {panel[0]};
Physical Curve("sides") = {panel[2], panel[3]};
Physical Surface("panel") = {panel[1]};
Mesh.MshFileVersion = 4.1;
