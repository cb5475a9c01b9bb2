#pragma once

// Reading gmsh triangle meshes into a deal.II Triangulation<2,3>, with the mesh's
// physical groups kept by name so that parameter files can refer to them ("pinned",
// "loaded", ...).

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include "mesh/dealii_declarations.h"

#include <map>
#include <string>
#include <vector>

namespace clothsim::mesh
{
  using namespace dealii;

  // The named physical groups of a gmsh mesh.
  struct MeshGroups
  {
    // Physical groups of dimension 1 (lines): each becomes the boundary id of the
    // boundary faces it covers; boundary ids survive refinement, so refined children stay
    // in the group.
    std::map<std::string, types::boundary_id> line_groups;

    // Physical groups of dimension 0 (points): reference coordinates of their vertices.
    // Coarse vertices remain vertices under refinement, so the coordinates identify them.
    std::map<std::string, std::vector<Point<3>>> point_groups;

    // Physical groups of dimension 2 (surfaces): each becomes the material id (= its
    // physical tag) of the triangles it holds; material ids survive refinement, so
    // refined children stay in the group. A triangle can be in one surface group only;
    // triangles in none keep material id 0.
    std::map<std::string, types::material_id> surface_groups;

    // Names of all groups of any dimension (for error messages listing what exists).
    std::vector<std::string>
    all_names() const;
  };

  // Reads `msh_file` (gmsh format 2.2 or 4.x, ASCII or binary) into `triangulation`
  // (which must be empty). If `msh_file` does not exist but a `.geo` of the same stem
  // does, generates the `.msh` from it with gmsh first. Checks: only 3-node triangles
  // (lines and points only as physical groups), no zero-area cells, a consistently
  // oriented surface, no triangle in two surface groups. Throws InputError (naming the
  // file and the offending entity) on any failure.
  MeshGroups
  read_gmsh(const std::string &msh_file, Triangulation<2, 3> &triangulation);
} // namespace clothsim::mesh
