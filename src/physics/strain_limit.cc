#include "physics/strain_limit.h"

#include "mesh/discretization.h"

#include <deal.II/base/mpi.h>

namespace clothsim::physics
{
  StrainLimitResult
  limit_strain(const SpringNetwork        &springs,
               const StrainLimit          &limits,
               const VectorType           &inverse_masses,
               const double                dt,
               VectorType                 &u,
               VectorType                 &v,
               VectorType                 &u_ghosted,
               const mesh::Discretization &discretization)
  {
    StrainLimitResult result;
    if (limits.limit == 0.)
      return result;
    const MPI_Comm communicator = u.get_mpi_communicator();
    VectorType     moves(u);
    // Gauss–Seidel sweeps colour by colour; the last sweep only counts.
    for (unsigned int sweep = 0; sweep <= limits.max_sweeps; ++sweep)
      {
        const bool count_only = sweep == limits.max_sweeps;
        result.remaining      = 0;
        result.largest_strain = 0.;
        for (unsigned int color = 0; color < springs.n_colors(); ++color)
          {
            discretization.import_ghosts(u, u_ghosted);
            moves = 0.;
            result.remaining += Utilities::MPI::sum(
              static_cast<types::global_dof_index>(
                springs.add_strain_limit_moves(u_ghosted,
                                               inverse_masses,
                                               limits.limit,
                                               limits.limit_compression,
                                               color,
                                               moves,
                                               result.largest_strain)),
              communicator);
            if (count_only)
              continue;
            moves.compress(VectorOperation::add);
            u.add(1., moves);
            v.add(1. / dt, moves);
          }
        if (result.remaining == 0)
          break;
      }
    result.largest_strain = Utilities::MPI::max(result.largest_strain, communicator);
    return result;
  }
} // namespace clothsim::physics
