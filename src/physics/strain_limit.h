#pragma once

// Provot's strain limit after a dynamic step of the mass-spring model (Provot, Graphics
// Interface 1995): Gauss–Seidel sweeps over the structural springs, colour by colour,
// each shortening the springs stretched beyond (1 + τ) L back to that length (and, if
// asked, lengthening those below (1 - τ) L), moving both ends in proportion to their
// inverse masses; each move is added to the velocities as move/dt.

#include "physics/spring_network.h"
#include "physics/term.h"

namespace clothsim::mesh
{
  class Discretization;
}

namespace clothsim::physics
{
  struct StrainLimit
  {
    double       limit;             // τ, dimensionless; 0: off
    bool         limit_compression; // also keep (ℓ - L)/L >= -τ
    unsigned int max_sweeps;
  };

  struct StrainLimitResult
  {
    types::global_dof_index remaining = 0; // springs still beyond the limit (all ranks)
    double                  largest_strain = 0.; // largest |strain| among them
  };

  // `u`, `v` owned; `inverse_masses` ghosted (0 on pinned dofs); `u_ghosted` a ghosted
  // work vector of the same layout; all made by `discretization`, which fills the ghosts.
  StrainLimitResult
  limit_strain(const SpringNetwork        &springs,
               const StrainLimit          &limits,
               const VectorType           &inverse_masses,
               const double                dt,
               VectorType                 &u,
               VectorType                 &v,
               VectorType                 &u_ghosted,
               const mesh::Discretization &discretization);
} // namespace clothsim::physics
