#pragma once

// Point and line forces of a scene resolved on the mesh: a point force acts on every
// vertex of its point group (each vertex once); a line force q (N/m) puts q ℓ/2 on both
// ends of every boundary edge of its line group (exact for P1 elements under uniform q).

#include "io/parameters.h"
#include "mesh/discretization.h"
#include "mesh/gmsh_reader.h"

#include <string>

namespace clothsim
{
  // The nodal forces (owned vector, N, zero at constrained dofs). Throws InputError
  // (naming `parameter_file`) for unknown or empty groups.
  VectorType
  resolve_group_loads(const mesh::Discretization      &discretization,
                      const LoadParameters            &loads,
                      const AffineConstraints<double> &constraints,
                      const std::string               &parameter_file,
                      const mesh::MeshGroups          &groups);
} // namespace clothsim
