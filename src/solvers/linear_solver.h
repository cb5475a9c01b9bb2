#pragma once

// Linear solves of the Newton steps: CG or GMRES preconditioned by ML algebraic multigrid
// or Jacobi, or a direct solve (MUMPS' LDLᵀ, or Amesos KLU), as the parameter file
// selects.

#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include "io/parameters.h"
#include "solvers/block_preconditioner.h"
#include "solvers/mumps_factorization.h"

#include <Amesos_BaseSolver.h>
#include <Epetra_LinearProblem.h>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace clothsim
{
  // The AMG near-null space: one vector per mode over the locally owned dofs, and the
  // number of unknowns per mesh node ML may block together (3 for displacements only; 1
  // when other unknowns, e.g. director angles, are interleaved with them).
  struct NearNullSpace
  {
    std::vector<std::vector<double>> modes;
    unsigned int                     pde_equations = 3;
    // If some owned dofs are not displacements (director angles): the owned
    // displacement dofs, and the tangent's owned and relevant dofs. AMG then works on
    // the displacement block alone (BlockPreconditioner).
    IndexSet displacement_dofs, owned_dofs, relevant_dofs;
    // The owned unknowns on the mesh (increasing) and each one's vertex, or its edge's
    // two vertices (a vertex named by its first displacement dof), for the direct
    // solver's order (MumpsFactorization::set_mesh_unknowns); empty if not known.
    std::vector<types::global_dof_index>                mesh_dofs;
    std::vector<std::array<types::global_dof_index, 2>> mesh_vertices;
  };

  class LinearSolver
  {
  public:
    LinearSolver(const LinearSolverParameters &parameters, NearNullSpace near_null_space);
    // Not copied or moved: the direct solver keeps references into near_null_space.
    LinearSolver(const LinearSolver &) = delete;
    LinearSolver &
    operator=(const LinearSolver &) = delete;

    // Builds the preconditioner for `matrix` (call after every new tangent). `rhs`: the
    // right-hand side of the next solve(), if known; the direct solver's Cholesky then
    // does part of that solve with the factorisation (MumpsFactorization::factorize).
    void
    update_preconditioner(const TrilinosWrappers::SparseMatrix &matrix,
                          const TrilinosWrappers::MPI::Vector  *rhs = nullptr);

    // The next update_preconditioner builds the AMG hierarchy afresh (a changed time step
    // scales the tangent, and a hierarchy recomputed on old aggregates can then fail).
    // A failed solve does the same by itself.
    void
    rebuild_next()
    {
      force_rebuild = true;
    }

    // Whether MUMPS still uses the definite factorisation (see `definite`), and setting
    // it (a restart continues with the run's choice; before the first factorisation).
    bool
    definite_factorization() const
    {
      return definite;
    }
    void
    set_definite_factorization(const bool is_definite)
    {
      Assert(!mumps, ExcInternalError());
      definite = is_definite;
    }
    // The matrix's sparsity changed (self-contact pairs): the next
    // update_preconditioner analyses it afresh.
    void
    sparsity_changed();

    // Why the last solve failed: no convergence within the iteration limit, a Krylov
    // breakdown (CG on an indefinite tangent), or a failed factorisation.
    const std::string &
    failure() const
    {
      return last_failure;
    }

    // The negative pivots of the last MUMPS factorisation (the tangent's negative
    // eigenvalues, by Sylvester's law of inertia; constrained rows have a positive unit
    // diagonal), or -1 with another solver.
    int
    negative_pivots() const
    {
      return mumps ? mumps->negative_pivots() : -1;
    }

    // Whether the current preconditioner reuses aggregates of an earlier tangent.
    bool
    reuses_aggregates() const
    {
      return reused;
    }

    // Solves A x = b to |b - A x| <= relative_tolerance |b| ('Relative tolerance' unless
    // given: an inexact Newton's forcing term). Returns false if the Krylov method did
    // not converge; `iterations` gets the iteration count (1 for the direct solver).
    // 'Relative tolerance' of the parameter file.
    double
    default_tolerance() const
    {
      return parameters.relative_tolerance;
    }

    bool
    solve(const TrilinosWrappers::SparseMatrix &matrix,
          TrilinosWrappers::MPI::Vector        &x,
          const TrilinosWrappers::MPI::Vector  &b,
          unsigned int                         &iterations,
          std::optional<double>                 relative_tolerance = {}) const;

  private:
    const LinearSolverParameters parameters;
    const NearNullSpace          near_null_space;
    std::vector<double> null_space_storage; // the modes column-major, as ML reads them
    std::unique_ptr<TrilinosWrappers::PreconditionBase> preconditioner;
    // The AMG hierarchy, if `preconditioner` is one: later tangents reuse its aggregates.
    TrilinosWrappers::PreconditionAMG *amg = nullptr;
    // With director angles: AMG on the displacement block, Jacobi on the angles.
    std::unique_ptr<BlockPreconditioner> block_preconditioner;
    // Direct solver: the symbolic factorisation of the first tangent serves all later
    // ones (same sparsity); each new tangent is factorised numerically once. MUMPS
    // directly (symmetric), KLU through Amesos. MUMPS starts with the definite
    // factorisation (`definite`) and keeps the pivoting one from the first tangent that
    // is not positive definite on.
    std::unique_ptr<MumpsFactorization>   mumps;
    bool                                  definite = true;
    std::unique_ptr<Epetra_LinearProblem> direct_problem;
    std::unique_ptr<Amesos_BaseSolver>    direct_solver;
    // CG iterations of the last solve, and of the first solve after the aggregates were
    // built.
    mutable unsigned int last_iterations          = 0;
    mutable unsigned int iterations_after_rebuild = 0;
    mutable bool         awaiting_first_solve     = false;
    mutable bool         force_rebuild            = false;
    mutable std::string  last_failure;
    bool                 reused           = false;
    bool                 factorization_ok = false;
  };
} // namespace clothsim
