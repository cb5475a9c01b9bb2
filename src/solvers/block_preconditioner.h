#pragma once

// Preconditioner for shells (displacements u plus director angles ψ): the block LDLᵀ
// factorisation of the tangent [[A, B], [Bᵀ, C]] (u first) with C replaced by its
// diagonal D and the Schur complement by
//   S̃ = A - B D⁻¹ Bᵀ  (each angle's row of Bᵀ spans the 4 vertices of its edge's two
//                       triangles, so S̃ has the hinge stencil)
// solved by one ML smoothed-aggregation V-cycle (3 unknowns per vertex, rigid-body
// near-null space):
//   y_ψ = D⁻¹ r_ψ,  z_u = S̃⁻¹ (r_u - B y_ψ),  z_ψ = D⁻¹ (r_ψ - Bᵀ z_u).
// P⁻¹ is symmetric, and positive definite for an SPD tangent, so CG applies. The
// angles carry no mass: the displacements feel the bending stiffness only through the
// Schur complement, which is why a block-diagonal preconditioner (AMG on A alone) needs
// hundreds of CG iterations on cloth.

#include <deal.II/base/index_set.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_FECrsMatrix.h>
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

    // Builds D and S̃ from `matrix` (kept by reference for the products with B) and the
    // AMG hierarchy of S̃ with `ml_parameters` (null space vectors in the block's local
    // numbering).
    void
    initialize(const TrilinosWrappers::SparseMatrix &matrix,
               const Teuchos::ParameterList         &ml_parameters);

    void
    vmult(TrilinosWrappers::MPI::Vector       &dst,
          const TrilinosWrappers::MPI::Vector &src) const;

  private:
    // S̃ (and D) from the tangent A through Epetra's sums: building its profile, or
    // (`refill`) adding into it.
    void
    fill_by_sums(const Epetra_CrsMatrix &A, bool refill);
    // A later tangent on one rank: S̃'s values replaced in place, row by row.
    void
    refill_in_place(const Epetra_CrsMatrix &A);
    // D's inverse for angle `angle`, refusing a non-positive diagonal.
    void
    set_inverse_diagonal(unsigned int angle, double diagonal);

    MPI_Comm communicator;
    IndexSet owned;
    IndexSet block_owned; // 0 .. n_displacements, this rank's contiguous range
    // Local index in the full vector of each owned displacement dof, in block order.
    std::vector<int> displacement_local;
    // Local index and inverse diagonal of every other owned dof.
    std::vector<int>    other_local;
    std::vector<double> other_inverse_diagonal;
    // Block index of every column (relevant dof) of the tangent, -1 if not a
    // displacement; and the same by the tangent's local column index (its sparsity never
    // changes).
    TrilinosWrappers::MPI::Vector block_index_ghosted;
    std::vector<int>              column_block;

    // For refill_in_place: each tangent column's row, each row's angle index (-1 for
    // displacements), each tangent column's local column in S̃, and a scatter of S̃'s
    // columns within a row (-1 outside it).
    std::vector<int> column_row, angle_of_row, block_column, scatter;

    const TrilinosWrappers::SparseMatrix              *tangent = nullptr;
    std::unique_ptr<Epetra_FECrsMatrix>                block_matrix; // S̃
    mutable TrilinosWrappers::MPI::Vector              full_in, full_out;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    mutable TrilinosWrappers::MPI::Vector              block_src, block_dst;
  };
} // namespace clothsim
