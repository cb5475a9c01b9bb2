#pragma once

// Point, line and surface forces of a scene resolved on the mesh: a point force acts on
// every vertex of its point group (each vertex once); a line force q (N/m) puts q ℓ/2 on
// both ends of every boundary edge of its line group (exact for P1 elements under
// uniform q); a surface force f(X) (N/m²) puts A (2 f_i + f_j + f_k) / 12 on vertex i of
// every triangle (the consistent load of f interpolated linearly); a line moment acts on
// the director angles of its group's edges; a point moment is a couple of forces on the
// triangles around each vertex of its point group.

#include "io/parameters.h"
#include "mesh/discretization.h"
#include "mesh/gmsh_reader.h"

#include <string>

namespace clothsim
{
  // Whether the scene has any of these loads.
  bool
  has_group_loads(const LoadParameters &loads);

  // The nodal forces (owned vector, N, zero at constrained dofs). Throws InputError
  // (naming `parameter_file`) for unknown or empty groups and surface forces that do
  // not parse or are not finite at a vertex.
  VectorType
  resolve_group_loads(const mesh::Discretization      &discretization,
                      const LoadParameters            &loads,
                      const AffineConstraints<double> &constraints,
                      const std::string               &parameter_file,
                      const mesh::MeshGroups          &groups);
} // namespace clothsim
