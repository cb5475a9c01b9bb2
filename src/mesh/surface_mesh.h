#pragma once

// Rigid obstacles given as triangle surfaces: reading STL, OBJ and gmsh files into one
// indexed triangle mesh with its edges.

#include <deal.II/base/point.h>

#include <array>
#include <string>
#include <vector>

namespace clothsim::mesh
{
  using namespace dealii;

  // A triangle surface in space [m]: shared vertices, triangles as vertex triples
  // (orientation as in the file), and the edges.
  struct SurfaceMesh
  {
    std::vector<Point<3>>                    vertices;  // m
    std::vector<std::array<unsigned int, 3>> triangles; // indices into vertices
    // The unique undirected edges (each as sorted vertex pair), computed by the reader.
    std::vector<std::array<unsigned int, 2>> edges;
  };

  // Reads a triangle surface from `file` by its extension (case-insensitive):
  // - .stl: ASCII or binary (binary if the size is 84 + 50 n for the n in its header);
  // - .obj: v and f lines (f entries i, i/t, i//n, i/t/n; negative indices count back
  //   from the last v line; polygons fan-triangulated); other lines ignored;
  // - .msh: gmsh 2.2 or 4.x, all its 3-node triangles (no physical groups needed);
  // - .geo: meshed in 2D by gmsh in this process (no .msh is written).
  // `scale` multiplies every coordinate (STL and OBJ files are often in mm: 1e-3).
  // Vertices with exactly equal coordinates are merged (STL repeats them per facet),
  // unused ones dropped; vertices are numbered in the order the triangles first use
  // them, edges sorted. Throws InputError naming the file and the line, facet or
  // element on: a missing or unreadable file, an unknown extension, a malformed line or
  // truncated binary STL, an index out of range, a non-finite coordinate, a zero-area
  // triangle, other surface elements than 3-node triangles in a gmsh mesh, no triangles.
  SurfaceMesh
  read_surface_mesh(const std::string &file, const double scale = 1.);
} // namespace clothsim::mesh
