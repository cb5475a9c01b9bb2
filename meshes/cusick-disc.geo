// The Cusick drape test's support (ISO 9073-9): a disc of 18 cm diameter with a sharp
// rim, as a closed cylinder 1 cm thick centred on the z axis, its top face at
// z = -1.6 mm (below a specimen in the plane z = 0). Triangles of about lc (5 mm: the
// rim's polygon is within 35 µm of the circle). A rigid obstacle surface
// (mesh::read_surface_mesh); no physical groups needed.
SetFactory("OpenCASCADE");

radius    = 0.09;
thickness = 0.01;
top       = -0.0016;
lc        = 0.005;

Cylinder(1) = {0, 0, top - thickness, 0, 0, thickness, radius};

Mesh.MeshSizeMin = lc;
Mesh.MeshSizeMax = lc;
