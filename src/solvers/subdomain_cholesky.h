#pragma once

// Cholesky factorisation of a symmetric positive definite matrix whose rows are
// distributed over several ranks, by substructuring: one level of nested dissection
// (George, SIAM J. Numer. Anal. 10, 1973) at the ranks' interface, the Schur complement
// method (Saad, "Iterative Methods for Sparse Linear Systems", 2nd ed., §14.2) solved
// directly. The rows a rank owns that couple to a row of a higher rank form the
// separator S; a rank's other rows (its interior I_r) then couple only to its own rows
// and to S. Each rank factorises A_{I_r I_r} with its own SupernodalCholesky (METIS
// orders it, by the mesh's vertices where it can: solvers/vertex_order.h) and forms its
// share of the Schur complement
//   C = A_SS - Σ_r A_{S I_r} A_{I_r I_r}⁻¹ A_{I_r S},
// which one reduction sums on every rank; each factorises C densely (LAPACK). A solve
// substitutes forward through each rank's interior, sums the separator's right-hand
// sides, solves with C's factor and substitutes backward: two reductions of |S| numbers
// in all. All but C's factorisation runs in parallel; C's order is about the length of
// the ranks' interface, in degrees of freedom.

#include <deal.II/base/types.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Vector.h>
#include <mpi.h>

#include "solvers/supernodal_cholesky.h"

#include <array>
#include <string>
#include <vector>

namespace clothsim
{
  class SubdomainCholesky
  {
  public:
    // The factors (the interiors' and C's) in single or double precision.
    SubdomainCholesky(MPI_Comm communicator, bool single_precision);

    // Finds the separator and analyses the sparsity of `matrix` (collective; its storage
    // optimised, its sparsity symmetric). False with failure() set otherwise. Each
    // interior is ordered by METIS' nested dissection: of its vertices if every row is
    // on the mesh (`mesh_dofs` and `mesh_vertices` as NearNullSpace's, or null;
    // vertex_nested_dissection_order, UFACTOR = 500), else of its rows.
    bool
    analyse(
      const Epetra_CrsMatrix                                            &matrix,
      const std::vector<dealii::types::global_dof_index>                *mesh_dofs,
      const std::vector<std::array<dealii::types::global_dof_index, 2>> *mesh_vertices);

    // Factorises `matrix` (collective; the sparsity analysed), reading its value array in
    // place. False with failure() set if it is not positive definite. With `rhs`, its
    // forward substitution through the interior is done while factorising
    // (SupernodalCholesky::factorize), and the next solve() with the same b only
    // substitutes backward.
    bool
    factorize(const Epetra_CrsMatrix &matrix, const Epetra_Vector *rhs = nullptr);

    // x = A⁻¹ b with the last factors (collective; b and x on the matrix's rows). Bit for
    // bit the same whether factorize() was given b or not.
    void
    solve(const Epetra_Vector &b, Epetra_Vector &x);

    // The separator's size (over all ranks) and the interiors' factorisation's
    // floating-point operations on this rank.
    int
    separator_size() const
    {
      return n_separator;
    }
    double
    interior_operations() const
    {
      return cholesky.operations();
    }

    const std::string &
    failure() const
    {
      return last_failure;
    }

  private:
    MPI_Comm           communicator;
    SupernodalCholesky cholesky; // this rank's interior, then the whole separator
    // This rank's rows (local indices): interior ones in the Cholesky's order 0, 1, ...;
    // its separator rows and their index in the separator; rows holding only their
    // diagonal, solved x_i = b_i / a_ii (not in the Cholesky: each would be a
    // supernode of its own).
    std::vector<int>    interior_rows, separator_rows, separator_index;
    std::vector<int>    decoupled_rows, decoupled_offsets; // offsets in the value array
    std::vector<double> decoupled_diagonal;
    int                 n_separator = 0;
    // The right-hand side given to the last factorize() (its local entries), while its
    // forward substitution waits for solve().
    std::vector<double> forwarded_rhs;
    // This rank's term of C (n_separator², column-major), and C's Cholesky factor
    // (lower), its packed sum and a solve's right-hand side, in the factors' precision.
    bool                single;
    std::vector<double> schur, local;
    template <typename Number>
    struct Separator
    {
      std::vector<Number> factor, packed, rhs;
    };
    Separator<double> separator;
    Separator<float>  separator_single;
    template <typename Number>
    bool
    factorize_separator(Separator<Number> &in, MPI_Datatype type);
    // The interior's and separator's right-hand sides in `local`; x_S = C⁻¹ rhs_S in
    // place, after summing rhs_S over the ranks.
    void
    gather_local(const Epetra_Vector &b);
    void
                solve_separator(double *rhs);
    std::string last_failure;
  };
} // namespace clothsim
