// Obstacle: a square table top with sharp edges and corners, 50 cm x 50 cm and 3 cm
// thick, centred under (0.5, 0.5) (the centre of the 1 m sheets in z = 0), its top face
// at z = -1 cm. Triangles of about 2.5 cm. A rigid obstacle surface
// (mesh::read_surface_mesh); no physical groups needed.
SetFactory("OpenCASCADE");

side      = 0.5;
thickness = 0.03;
top       = -0.01;
lc        = 0.025;

Box(1) = {0.5 - side / 2, 0.5 - side / 2, top - thickness, side, side, thickness};

Mesh.MeshSizeMin = lc;
Mesh.MeshSizeMax = lc;
