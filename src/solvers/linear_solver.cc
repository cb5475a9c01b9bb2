#include "solvers/linear_solver.h"

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_solver.h>

#include <Amesos.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <sstream>

namespace clothsim
{
  LinearSolver::LinearSolver(const LinearSolverParameters &parameters,
                             NearNullSpace                 near_null_space)
    : parameters(parameters)
    , near_null_space(std::move(near_null_space))
  {
    const NearNullSpace &space = this->near_null_space;
    if (space.displacement_dofs.size() > 0)
      {
        // Block mode: the modes restricted to the displacement dofs, in their order.
        for (const std::vector<double> &mode : space.modes)
          for (const types::global_dof_index dof : space.displacement_dofs)
            null_space_storage.push_back(mode[space.owned_dofs.index_within_set(dof)]);
      }
    else
      for (const std::vector<double> &mode : space.modes)
        null_space_storage.insert(null_space_storage.end(), mode.begin(), mode.end());
  }


  void
  LinearSolver::sparsity_changed()
  {
    if (mumps)
      mumps->reanalyse();
    direct_solver.reset();
    direct_problem.reset();
    block_preconditioner.reset();
    preconditioner.reset();
    amg           = nullptr;
    force_rebuild = true;
  }


  void
  LinearSolver::update_preconditioner(const TrilinosWrappers::SparseMatrix &matrix,
                                      const TrilinosWrappers::MPI::Vector  *rhs)
  {
    if (parameters.method == "direct")
      {
        if (parameters.direct_solver == "mumps")
          {
            // The tangent is symmetric (constraints are applied symmetrically): LDLᵀ.
            // The projected tangent with a mass term is positive definite: LDLᵀ without
            // pivoting (MUMPS SYM = 1) takes 13 % less time than with it (swing, N = 81,
            // the same operations). A tangent that is not definite (a negative or zero
            // pivot: the exact Hessian, a static step) switches to the pivoting LDLᵀ
            // (SYM = 2) for the rest of the run; MUMPS' pivot count is global, so every
            // rank switches alike.
            const auto make = [&](const MumpsFactorization::Symmetry symmetry) {
              mumps = std::make_unique<MumpsFactorization>(
                matrix.get_mpi_communicator(),
                symmetry,
                MumpsFactorization::default_ordering,
                parameters.factor_precision == "single"
                  ? MumpsFactorization::Precision::single_refined
                  : MumpsFactorization::Precision::double_precision);
              if (!near_null_space.mesh_dofs.empty())
                mumps->set_mesh_unknowns(near_null_space.mesh_dofs,
                                         near_null_space.mesh_vertices);
            };
            if (!mumps)
              make(definite ? MumpsFactorization::Symmetry::positive_definite
                            : MumpsFactorization::Symmetry::indefinite);
            const Epetra_Vector *b =
              rhs != nullptr ? (*rhs).trilinos_vector()(0) : nullptr;
            factorization_ok = mumps->factorize(matrix.trilinos_matrix(), b);
            if (definite && (!factorization_ok || mumps->negative_pivots() > 0))
              {
                definite = false;
                make(MumpsFactorization::Symmetry::indefinite);
                factorization_ok = mumps->factorize(matrix.trilinos_matrix(), b);
              }
            if (!factorization_ok)
              last_failure = mumps->failure();
            return;
          }
        if (!direct_solver)
          {
            direct_problem = std::make_unique<Epetra_LinearProblem>();
            direct_problem->SetOperator(
              const_cast<Epetra_CrsMatrix *>(&matrix.trilinos_matrix()));
            Amesos factory;
            direct_solver.reset(factory.Create("Amesos_Klu", *direct_problem));
            AssertThrow(direct_solver != nullptr, ExcMessage("this Trilinos has no KLU"));
            AssertThrow(direct_solver->SymbolicFactorization() == 0,
                        ExcMessage("symbolic factorisation failed"));
          }
        factorization_ok = direct_solver->NumericFactorization() == 0;
        if (!factorization_ok)
          last_failure = "the direct solver's factorisation failed";
        return;
      }
    // Aggregates built from an early tangent (the unstressed sheet has no out-of-plane
    // stiffness) stop fitting as the sheet deforms: reuse them only while CG needs at
    // most 30 % more iterations than right after they were built.
    const bool aggregates_fit =
      !force_rebuild && last_iterations <= 1.3 * iterations_after_rebuild + 1;
    const bool block_mode = near_null_space.displacement_dofs.size() > 0;
    force_rebuild         = false;
    reused = parameters.preconditioner == "amg" && amg != nullptr && !block_mode &&
             parameters.amg_reuse_aggregates && aggregates_fit;
    if (reused)
      {
        // Same sparsity, new entries: keep the aggregates, rebuild the smoothed
        // prolongators and coarse operators (ML's ReComputePreconditioner), several times
        // cheaper.
        amg->reinit();
      }
    else if (parameters.preconditioner == "amg")
      {
        // deal.II's ML settings for an elliptic problem, then our near-null space (ML's
        // "pre-computed" null space, column-major on the owned rows).
        TrilinosWrappers::PreconditionAMG::AdditionalData data;
        data.elliptic              = true;
        data.higher_order_elements = false;
        data.n_cycles              = 1;
        data.aggregation_threshold = parameters.amg_aggregation_threshold;
        data.smoother_sweeps       = parameters.amg_smoother_sweeps;
        data.smoother_type         = "Chebyshev";
        data.coarse_type           = "Amesos-KLU";
        Teuchos::ParameterList              ml_parameters;
        std::unique_ptr<Epetra_MultiVector> unused_constant_modes;
        data.set_parameters(ml_parameters,
                            unused_constant_modes,
                            matrix.trilinos_matrix());
        ml_parameters.set("PDE equations",
                          static_cast<int>(block_mode ? 3
                                                      : near_null_space.pde_equations));
        ml_parameters.set("null space: type", "pre-computed");
        ml_parameters.set("null space: dimension",
                          static_cast<int>(near_null_space.modes.size()));
        ml_parameters.set("null space: vectors", null_space_storage.data());
        ml_parameters.set("null space: add default vectors", false);
        ml_parameters.set("smoother: Chebyshev alpha", parameters.amg_chebyshev_range);
        ml_parameters.set("coarse: max size",
                          static_cast<int>(parameters.amg_coarse_size));
        if (parameters.amg_smoother == "block gauss-seidel")
          {
            // Each vertex's three displacements relaxed together, in whatever frame its
            // surface turns to. Only on the finest level: the coarser ones hold as many
            // unknowns per aggregate as the null space has modes, and ML's blocks there
            // would still be of 3.
            ml_parameters.set("smoother: type (level 0)",
                              std::string("symmetric block Gauss-Seidel"));
            ml_parameters.set("smoother: sweeps (level 0)",
                              static_cast<int>(parameters.amg_smoother_sweeps));
          }
        if (block_mode)
          {
            if (!block_preconditioner)
              block_preconditioner =
                std::make_unique<BlockPreconditioner>(near_null_space.owned_dofs,
                                                      near_null_space.relevant_dofs,
                                                      near_null_space.displacement_dofs,
                                                      matrix.get_mpi_communicator());
            block_preconditioner->initialize(matrix, ml_parameters);
            return;
          }
        auto amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
        amg->initialize(matrix, ml_parameters);
        this->amg            = amg.get();
        awaiting_first_solve = true;
        preconditioner       = std::move(amg);
      }
    else
      {
        auto jacobi = std::make_unique<TrilinosWrappers::PreconditionJacobi>();
        jacobi->initialize(matrix);
        preconditioner = std::move(jacobi);
      }
  }


  bool
  LinearSolver::solve(const TrilinosWrappers::SparseMatrix &matrix,
                      TrilinosWrappers::MPI::Vector        &x,
                      const TrilinosWrappers::MPI::Vector  &b,
                      unsigned int                         &iterations,
                      const std::optional<double>           relative_tolerance) const
  {
    x                   = 0.;
    const double b_norm = b.l2_norm();
    if (b_norm == 0.)
      {
        iterations = 0;
        return true;
      }
    SolverControl control(parameters.max_iterations,
                          relative_tolerance.value_or(parameters.relative_tolerance) *
                            b_norm,
                          /*log_history=*/false,
                          /*log_result=*/false);
    try
      {
        if (parameters.method == "direct")
          {
            iterations = 1;
            if (!factorization_ok)
              return false; // last_failure says why
            if (mumps)
              {
                const bool solved = mumps->solve(*b.trilinos_vector()(0),
                                                 *x.trilinos_vector()(0),
                                                 &matrix.trilinos_matrix(),
                                                 relative_tolerance.value_or(
                                                   parameters.relative_tolerance));
                iterations += mumps->refinements();
                if (!solved)
                  last_failure = mumps->failure();
                return solved;
              }
            Assert(direct_problem->GetOperator() == &matrix.trilinos_matrix(),
                   ExcInternalError());
            direct_problem->SetLHS(&x.trilinos_vector());
            direct_problem->SetRHS(const_cast<Epetra_MultiVector *>(
              static_cast<const Epetra_MultiVector *>(&b.trilinos_vector())));
            const bool solved = direct_solver->Solve() == 0;
            if (!solved)
              last_failure = "the direct solve failed";
            return solved;
          }
        if (block_preconditioner && parameters.preconditioner == "amg")
          {
            if (parameters.method == "cg")
              {
                SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
                cg.solve(matrix, x, b, *block_preconditioner);
              }
            else
              {
                SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
                  control,
                  SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(100));
                gmres.solve(matrix, x, b, *block_preconditioner);
              }
          }
        else if (parameters.method == "cg")
          {
            TrilinosWrappers::SolverCG cg(control);
            cg.solve(matrix, x, b, *preconditioner);
          }
        else
          {
            TrilinosWrappers::SolverGMRES::AdditionalData data(false, 100);
            TrilinosWrappers::SolverGMRES                 gmres(control, data);
            gmres.solve(matrix, x, b, *preconditioner);
          }
      }
    catch (const SolverControl::NoConvergence &)
      {
        iterations    = control.last_step();
        force_rebuild = true;
        last_failure  = parameters.method + " did not converge in " +
                       std::to_string(iterations) + " iterations";
        return false;
      }
    catch (const std::exception &e)
      {
        // AztecOO reports breakdowns (e.g. CG on an indefinite matrix) as exceptions too,
        // possibly before the first iteration; deal.II's text without its stack trace.
        iterations =
          control.last_step() == numbers::invalid_unsigned_int ? 0 : control.last_step();
        force_rebuild      = true;
        std::string reason = e.what();
        if (const auto *deal_ii = dynamic_cast<const ExceptionBase *>(&e))
          {
            std::ostringstream info;
            deal_ii->print_info(info);
            reason = info.str();
          }
        reason.erase(0, reason.find_first_not_of(" \n"));
        reason.erase(reason.find_last_not_of(" \n") + 1);
        last_failure = parameters.method + " failed (" + reason + ")";
        return false;
      }
    iterations      = control.last_step();
    last_iterations = iterations;
    if (awaiting_first_solve)
      {
        iterations_after_rebuild = iterations;
        awaiting_first_solve     = false;
      }
    return true;
  }
} // namespace clothsim
