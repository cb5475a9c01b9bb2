#pragma once

// Preconditioner for shells (displacements plus director angles):
//   P⁻¹ = diag( AMG(K_uu)⁻¹, D_ψψ⁻¹ )
// ML smoothed-aggregation AMG on the displacement block K_uu, extracted from the tangent
// into its own matrix so that ML sees 3 unknowns per vertex and the rigid-body modes,
// and point Jacobi on the angles (and on any other non-displacement unknown). For an
// SPD tangent P is SPD, so CG applies. The angles carry no mass, but each couples only
// to the displacements and angles of its two triangles; K_uu holds the mass, membrane
// and (at fixed angles) bending stiffness, which is where multigrid is needed.

#include <deal.II/base/index_set.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_CrsMatrix.h>
#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <vector>

namespace clothsim
{
  using namespace dealii;

  class BlockPreconditioner
  {
  public:
    // `displacement_dofs`: the locally owned displacement dofs (3 per vertex, components
    // consecutive); `owned_dofs`, `relevant_dofs`: the tangent's layout.
    BlockPreconditioner(const IndexSet &owned_dofs,
                        const IndexSet &relevant_dofs,
                        const IndexSet &displacement_dofs,
                        const MPI_Comm  communicator);

    // The layout of the displacement block (for its near-null space).
    const IndexSet &
    block_dofs() const
    {
      return block_owned;
    }
    // Position of owned dof `dof` in the displacement block's numbering (-1: none).
    long long
    block_index(const types::global_dof_index dof) const;

    // Extracts K_uu and the angle diagonal from `matrix` and builds the AMG hierarchy
    // with `ml_parameters` (null space vectors in the block's local numbering).
    void
    initialize(const TrilinosWrappers::SparseMatrix &matrix,
               const Teuchos::ParameterList         &ml_parameters);

    void
    vmult(TrilinosWrappers::MPI::Vector       &dst,
          const TrilinosWrappers::MPI::Vector &src) const;

  private:
    MPI_Comm communicator;
    IndexSet owned;
    IndexSet block_owned; // 0 .. n_displacements, this rank's contiguous range
    // Local index in the full vector of each owned displacement dof, in block order.
    std::vector<int> displacement_local;
    // Local index and inverse diagonal of every other owned dof.
    std::vector<int>    other_local;
    std::vector<double> other_inverse_diagonal;
    // Block index of every column (relevant dof) of the tangent, -1 if not a displacement.
    TrilinosWrappers::MPI::Vector block_index_ghosted;

    std::unique_ptr<Epetra_CrsMatrix>                  block_matrix;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    mutable TrilinosWrappers::MPI::Vector              block_src, block_dst;
  };
} // namespace clothsim
