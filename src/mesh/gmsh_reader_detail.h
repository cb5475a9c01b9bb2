#pragma once

// The parts of mesh/gmsh_reader shared by its files: the mesh as gmsh gives it (plain
// data, taken while gmsh runs, checked after it is closed), and the steps from it to a
// Triangulation and MeshGroups. Not part of the interface.

#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include "mesh/gmsh_reader.h"

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace clothsim::mesh::detail
{
  // What we take from gmsh's model, as plain data: the checks run after gmsh is closed.
  struct RawTriangle
  {
    std::size_t                tag;
    std::array<std::size_t, 3> nodes;
  };

  struct RawLine
  {
    std::size_t                tag;
    std::array<std::size_t, 2> nodes;
  };

  struct RawLineGroup
  {
    std::string          name;
    int                  tag;
    std::vector<RawLine> lines;
  };

  struct RawPointGroup
  {
    std::string              name;
    std::vector<std::size_t> nodes;
  };

  struct RawSurfaceGroup
  {
    std::string              name;
    int                      tag;
    std::vector<std::size_t> triangles; // element tags
  };

  struct RawMesh
  {
    std::unordered_map<std::size_t, Point<3>> node_coordinates;
    std::vector<RawTriangle>                  triangles;
    std::vector<RawLineGroup>                 line_groups;
    std::vector<RawPointGroup>                point_groups;
    std::vector<RawSurfaceGroup>              surface_groups;
    bool generated = false; // this read generated `msh_file` from its .geo
  };


  // The mesh of `msh_file` as gmsh reads it, in a gmsh session of its own; if the file
  // does not exist but a .geo of the same stem does, gmsh generates it first
  // (mesh/gmsh_session.cc). Throws InputError; a .msh it generated and could not read
  // is removed.
  RawMesh
  load_with_gmsh(const std::string &msh_file);

  // Removes a .msh that this read generated but that turned out unusable, so that the
  // next read does not take it for a mesh the user made (errors ignored: nothing to add
  // to the input error on its way).
  void
  remove_generated_msh(const std::string &msh_file);

  // The checks of read_gmsh() on `raw` and the triangulation with its groups built from
  // it (mesh/gmsh_reader.cc).
  MeshGroups
  build_triangulation(const std::string   &msh_file,
                      const RawMesh       &raw,
                      Triangulation<2, 3> &triangulation);

  // Reads the mesh of the current gmsh model; rejects elements other than 3-node
  // triangles, and 2-node lines in line groups (mesh/gmsh_model.cc). `msh_file` names
  // the file in errors.
  RawMesh
  read_model(const std::string &msh_file);


  // "(nodes a-b)", for error messages.
  std::string
  edge_text(const std::size_t node_0, const std::size_t node_1);

  // An edge as the sorted pair of its vertex indices.
  std::pair<unsigned int, unsigned int>
  edge_key(const unsigned int a, const unsigned int b);

  // A cell using an edge, and whether it runs through it from the lower vertex index to
  // the higher.
  struct EdgeUse
  {
    unsigned int cell;
    bool         ascending;
  };

  // Each edge (sorted vertex pair) with the cells using it.
  using Edges = std::map<std::pair<unsigned int, unsigned int>, std::vector<EdgeUse>>;


  // Line groups: boundary id = physical tag, on boundary edges only. Adds them to
  // `groups.line_groups`, and returns the boundary id of each edge (sorted vertex pair)
  // in a group. `edges`: the cells using each edge of the triangulation's cells.
  std::map<std::pair<unsigned int, unsigned int>, types::boundary_id>
  add_line_groups(const std::string                                   &msh_file,
                  const RawMesh                                       &raw,
                  const std::unordered_map<std::size_t, unsigned int> &vertex_of_node,
                  const Edges                                         &edges,
                  MeshGroups                                          &groups);

  // Surface groups: material id = physical tag, on the triangles they hold (`cells`,
  // one per raw triangle). Adds them to `groups.surface_groups`.
  void
  add_surface_groups(const std::string        &msh_file,
                     const RawMesh            &raw,
                     std::vector<CellData<2>> &cells,
                     MeshGroups               &groups);

  // Point groups: coordinates of their nodes, which must be vertices of the triangles.
  // Adds them to `groups.point_groups`.
  void
  add_point_groups(const std::string                                   &msh_file,
                   const RawMesh                                       &raw,
                   const std::unordered_map<std::size_t, unsigned int> &vertex_of_node,
                   const std::vector<Point<3>>                         &vertices,
                   MeshGroups                                          &groups);
} // namespace clothsim::mesh::detail
