// Obstacle: a round table top, a closed cylinder of radius 0.5 m and thickness 0.04 m,
// centred on the z axis, top face at z = 0.7 m, sharp rim (no rounding). Triangles of
// about 2 cm on its whole surface (top, bottom and the 4 cm band of the rim).
// Read as a rigid surface with mesh::read_surface_mesh(); no physical groups needed.
SetFactory("OpenCASCADE");

radius    = 0.5;
thickness = 0.04;
top       = 0.7;
lc        = 0.02;

Cylinder(1) = {0, 0, top - thickness, 0, 0, thickness, radius};

Mesh.MeshSizeMin = lc;
Mesh.MeshSizeMax = lc;
