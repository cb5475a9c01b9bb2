#include "solvers/linear_solver.h"

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>

namespace clothsim
{
  LinearSolver::LinearSolver(const LinearSolverParameters  &parameters,
                             std::vector<std::vector<bool>> constant_modes)
      : parameters(parameters)
      , constant_modes(std::move(constant_modes))
  {}


  void
    LinearSolver::update_preconditioner(const TrilinosWrappers::SparseMatrix &matrix)
  {
    if (parameters.method == "direct")
      return;
    if (parameters.preconditioner == "amg")
      {
        TrilinosWrappers::PreconditionAMG::AdditionalData data;
        data.elliptic              = true;
        data.higher_order_elements = false;
        data.n_cycles              = 1;
        data.aggregation_threshold = parameters.amg_aggregation_threshold;
        data.constant_modes        = constant_modes;
        data.smoother_sweeps       = parameters.amg_smoother_sweeps;
        data.smoother_type         = "Chebyshev";
        data.coarse_type           = "Amesos-KLU";
        auto amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
        amg->initialize(matrix, data);
        preconditioner = std::move(amg);
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
                        unsigned int                         &iterations) const
  {
    x                   = 0.;
    const double b_norm = b.l2_norm();
    if (b_norm == 0.)
      {
        iterations = 0;
        return true;
      }
    SolverControl control(parameters.max_iterations,
                          parameters.relative_tolerance * b_norm,
                          /*log_history=*/false,
                          /*log_result=*/false);
    try
      {
        if (parameters.method == "direct")
          {
            TrilinosWrappers::SolverDirect::AdditionalData data(false, "Amesos_Klu");
            TrilinosWrappers::SolverDirect                 direct(control, data);
            direct.solve(matrix, x, b);
            iterations = 1;
            return true;
          }
        Assert(preconditioner, ExcMessage("update_preconditioner() was not called"));
        if (parameters.method == "cg")
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
        iterations = control.last_step();
        return false;
      }
    catch (const std::exception &)
      {
        // AztecOO reports breakdowns (e.g. CG on an indefinite matrix) as exceptions too.
        iterations = control.last_step();
        return false;
      }
    iterations = control.last_step();
    return true;
  }
} // namespace clothsim
