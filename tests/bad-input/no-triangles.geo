// Bad input: a line and no surface, so gmsh meshes no triangle. The test reads a copy in
// the build tree: the .msh generated from it must not be left behind.
Point(1) = {0, 0, 0, 0.1};
Point(2) = {1, 0, 0, 0.1};
Line(1) = {1, 2};
