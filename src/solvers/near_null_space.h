#pragma once

// The AMG near-null space of a sheet, from its reference triangles: the three
// translations on the displacements and, for a nearly planar sheet, the rotation about
// its mean normal through its centroid (the membrane's in-plane elasticity has it in its
// kernel). Rotations about in-plane axes are left out: they bend, and a tensioned
// membrane resists them like a Laplacian (with all six rigid modes ML's CG diverged on
// the hanging sheet). Other unknowns (director angles) get zero. It also lists each owned
// unknown's vertex or edge (NearNullSpace::mesh_dofs), for the direct solver's order.

#include "solvers/linear_solver.h"

#include <array>
#include <vector>

namespace clothsim
{
  struct ReferenceTriangle
  {
    std::array<Point<3>, 3>                vertices; // m
    std::array<types::global_dof_index, 9> dofs;     // (vertex v, component c) at 3v + c
    double                                 area;     // m²
    // With director angles: the angle dof of the edge opposite vertex v at v.
    std::array<types::global_dof_index, 3> angle_dofs = {};
  };

  // `triangles`: the locally owned ones. `other_unknowns`: the owned dofs include more
  // than displacements (AMG then works on the displacement block).
  NearNullSpace
  make_near_null_space(const std::vector<ReferenceTriangle> &triangles,
                       const IndexSet                       &owned_dofs,
                       const IndexSet                       &relevant_dofs,
                       const bool                            other_unknowns,
                       const MPI_Comm                        communicator);
} // namespace clothsim
