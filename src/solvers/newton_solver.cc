#include "solvers/newton_solver.h"

#include "solvers/energy_line_search.h"
#include "solvers/tangent_monitor.h"

#include <NOX.H>
#include <NOX_Epetra_Group.H>
#include <NOX_Epetra_Interface_Required.H>
#include <NOX_Epetra_LinearSystem.H>
#include <NOX_Epetra_Vector.H>
#include <NOX_Solver_LineSearchBased.H>
#include <NOX_StatusTest_Combo.H>
#include <NOX_StatusTest_Divergence.H>
#include <NOX_StatusTest_FiniteValue.H>
#include <NOX_StatusTest_MaxIters.H>
#include <NOX_StatusTest_NormF.H>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_oblackholestream.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

namespace clothsim
{
  namespace
  {
    using TrilinosVector = TrilinosWrappers::MPI::Vector;

    void
    copy(const Epetra_Vector &from, TrilinosVector &to)
    {
      std::copy(from.Values(), from.Values() + from.MyLength(), to.begin());
    }

    void
    copy(const TrilinosVector &from, Epetra_Vector &to)
    {
      std::copy(from.begin(), from.end(), to.Values());
    }

    const Epetra_Vector &
    epetra(const NOX::Abstract::Vector &vector)
    {
      return dynamic_cast<const NOX::Epetra::Vector &>(vector).getEpetraVector();
    }

    // Shared state of one solve: the problem and work vectors in deal.II's layout.
    struct Context
    {
      NonlinearProblem                &problem;
      TrilinosWrappers::SparseMatrix  &matrix;
      LinearSolver                    &linear_solver;
      const NonlinearSolverParameters &parameters;
      NewtonSolver::TangentState      &tangent; // outlives the solve
      TimerOutput                     &timer;
      // In u's layout; iterate: where the direction is computed; update: the last one.
      TrilinosVector u, rhs, solution, iterate, update, direction;
      unsigned int   linear_iterations   = 0;
      unsigned int   projected_fallbacks = 0;
      unsigned int   tangents            = 0;
      std::string    failure             = std::string();
      // Tangents assembled with Φ (NonlinearProblem::speculate_tangents), and the
      // convergence test's step tolerance (m).
      bool   speculate      = false;
      double step_tolerance = 0.;
      bool   has_direction  = false; // `direction` holds the last line search's update
    };

    // NOX's residual callback.
    class Interface : public NOX::Epetra::Interface::Required
    {
    public:
      explicit Interface(Context &context)
        : context(context)
      {}

      bool
      computeF(const Epetra_Vector &x,
               Epetra_Vector       &F,
               const NOX::Epetra::Interface::Required::FillType) override
      {
        copy(x, context.u);
        context.problem.residual(context.u, context.rhs);
        copy(context.rhs, F);
        return true;
      }

    private:
      Context &context;
    };

    // NOX's linear system: the tangent (TrilinosWrappers), solved by LinearSolver.
    class LinearSystem : public NOX::Epetra::LinearSystem
    {
    public:
      explicit LinearSystem(Context &context)
        : context(context)
      {}

      bool
      applyJacobian(const NOX::Epetra::Vector &input,
                    NOX::Epetra::Vector       &result) const override
      {
        return context.matrix.trilinos_matrix().Apply(input.getEpetraVector(),
                                                      result.getEpetraVector()) == 0;
      }

      bool
      applyJacobianTranspose(const NOX::Epetra::Vector &input,
                             NOX::Epetra::Vector       &result) const override
      {
        // The tangent is symmetric.
        return applyJacobian(input, result);
      }

      bool
      applyJacobianInverse(Teuchos::ParameterList    &linear_parameters,
                           const NOX::Epetra::Vector &input,
                           NOX::Epetra::Vector       &result) override
      {
        copy(input.getEpetraVector(), context.rhs);
        // Inexact Newton: NOX puts the forcing term η_k into "Tolerance".
        std::optional<double> tolerance;
        if (context.parameters.method == NewtonMethod::inexact)
          tolerance = linear_parameters.get<double>("Tolerance");
        bool ok = solve(tolerance);
        // Adaptive tangent: an exact Hessian that the solver cannot handle, or whose step
        // is no descent direction of the objective (indefinite), is replaced by the
        // projected one at the current iterate.
        if (context.parameters.tangent == "adaptive" && !context.tangent.projected &&
            (!ok || context.solution * context.rhs <= 0.))
          {
            context.problem.tangent(context.iterate, context.matrix, true);
            context.tangent.projected              = true;
            context.tangent.preconditioner_current = false;
            context.tangent.uses                   = 1;
            ++context.tangents;
            ++context.projected_fallbacks;
            ok = solve(tolerance);
          }
        if (!ok)
          return false;
        copy(context.solution, result.getEpetraVector());
        // An update that passes the convergence test already at this iterate will most
        // likely end the solve: no tangent at its end then.
        if (context.speculate)
          {
            const bool last =
              context.problem.update_size(context.solution) < context.step_tolerance ||
              context.problem.update_ratio(context.solution, context.iterate) < 1.;
            context.problem.speculate_tangents(last ? nullptr : &context.matrix,
                                               context.parameters.tangent == "projected");
          }
        return true;
      }

      bool
      solve(const std::optional<double> tolerance)
      {
        if (!context.tangent.preconditioner_current)
          {
            TimerOutput::Scope scope(context.timer, "preconditioner setup");
            context.linear_solver.update_preconditioner(context.matrix, &context.rhs);
            context.tangent.preconditioner_current = true;
          }
        unsigned int iterations = 0;
        bool         ok         = false;
        {
          TimerOutput::Scope scope(context.timer, "linear solve");
          ok = context.linear_solver.solve(
            context.matrix, context.solution, context.rhs, iterations, tolerance);
        }
        context.linear_iterations += iterations;
        // A hierarchy on old aggregates can fail where a fresh one converges: one retry.
        if (!ok && context.linear_solver.reuses_aggregates())
          {
            {
              TimerOutput::Scope scope(context.timer, "preconditioner setup");
              context.linear_solver.update_preconditioner(context.matrix);
            }
            TimerOutput::Scope scope(context.timer, "linear solve");
            ok = context.linear_solver.solve(
              context.matrix, context.solution, context.rhs, iterations, tolerance);
            context.linear_iterations += iterations;
          }
        if (!ok)
          context.failure = "linear solver: " + context.linear_solver.failure();
        return ok;
      }

      bool
      applyRightPreconditioning(bool,
                                Teuchos::ParameterList &,
                                const NOX::Epetra::Vector &input,
                                NOX::Epetra::Vector       &result) const override
      {
        result = input;
        return true;
      }

      Teuchos::RCP<NOX::Epetra::Scaling>
      getScaling() override
      {
        return Teuchos::null;
      }

      void
      resetScaling(const Teuchos::RCP<NOX::Epetra::Scaling> &) override
      {}

      bool
      computeJacobian(const NOX::Epetra::Vector &x) override
      {
        copy(x.getEpetraVector(), context.iterate);
        NewtonSolver::TangentState &tangent = context.tangent;
        // Modified Newton keeps the tangent while it contracts well and is not worn out.
        if (context.parameters.method == NewtonMethod::modified && tangent.reusable &&
            !tangent.refresh && tangent.uses < context.parameters.jacobian_reuse)
          {
            ++tangent.uses;
            return true;
          }
        tangent.projected = context.parameters.tangent == "projected";
        context.problem.tangent(context.iterate, context.matrix, tangent.projected);
        tangent.preconditioner_current = false;
        tangent.reusable               = true;
        tangent.refresh                = false;
        tangent.uses                   = 1;
        ++context.tangents;
        return true;
      }

      bool
      createPreconditioner(const NOX::Epetra::Vector &,
                           Teuchos::ParameterList &,
                           bool) const override
      {
        return true;
      }

      bool
      destroyPreconditioner() const override
      {
        return true;
      }

      bool
      recomputePreconditioner(const NOX::Epetra::Vector &,
                              Teuchos::ParameterList &) const override
      {
        return true;
      }

      PreconditionerReusePolicyType
      getPreconditionerPolicy(bool) override
      {
        // The preconditioner is rebuilt in applyJacobianInverse after each new tangent.
        return PRPT_REUSE;
      }

      bool
      isPreconditionerConstructed() const override
      {
        return true;
      }

      bool
      hasPreconditioner() const override
      {
        return false;
      }

      Teuchos::RCP<const Epetra_Operator>
      getJacobianOperator() const override
      {
        return Teuchos::rcp(&context.matrix.trilinos_matrix(), false);
      }

      Teuchos::RCP<Epetra_Operator>
      getJacobianOperator() override
      {
        return Teuchos::rcp(
          const_cast<Epetra_CrsMatrix *>(&context.matrix.trilinos_matrix()), false);
      }

      Teuchos::RCP<const Epetra_Operator>
      getGeneratedPrecOperator() const override
      {
        return Teuchos::null;
      }

      Teuchos::RCP<Epetra_Operator>
      getGeneratedPrecOperator() override
      {
        return Teuchos::null;
      }

      void
      setJacobianOperatorForSolve(const Teuchos::RCP<const Epetra_Operator> &) override
      {}

      void
      setPrecOperatorForSolve(const Teuchos::RCP<const Epetra_Operator> &) override
      {}

    private:
      Context &context;
    };

    // Converged when a full Newton step (no line-search cut: a cut proves nothing) moved
    // no dof by more than the tolerance (m), the next correction then being smaller; or
    // when the problem's own test of the step at the new iterate passes (update_ratio).
    class SmallFullStep : public NOX::StatusTest::Generic
    {
    public:
      SmallFullStep(const double tolerance, Context &context)
        : tolerance(tolerance)
        , context(context)
      {}

      NOX::StatusTest::StatusType
      checkStatus(const NOX::Solver::Generic &solver, NOX::StatusTest::CheckType) override
      {
        status = NOX::StatusTest::Unconverged;
        if (solver.getNumIterations() == 0)
          return status;
        const auto *line_search =
          dynamic_cast<const NOX::Solver::LineSearchBased *>(&solver);
        if (line_search == nullptr || line_search->getStepSize() != 1.)
          return status;
        auto update = solver.getSolutionGroup().getX().clone(NOX::DeepCopy);
        update->update(-1., solver.getPreviousSolutionGroup().getX(), 1.);
        copy(epetra(*update), context.update);
        const double size = context.problem.update_size(context.update);
        if (size < tolerance)
          status = NOX::StatusTest::Converged;
        else
          {
            copy(epetra(solver.getSolutionGroup().getX()), context.iterate);
            last_ratio = context.problem.update_ratio(context.update, context.iterate);
            if (last_ratio < 1.)
              status = NOX::StatusTest::Converged;
          }
        return status;
      }

      NOX::StatusTest::StatusType
      getStatus() const override
      {
        return status;
      }

      std::ostream &
      print(std::ostream &stream, int indent = 0) const override
      {
        return stream << std::string(indent, ' ') << status << "full Newton step below "
                      << tolerance << " m, or at " << last_ratio
                      << " (below 1) of the problem's own test\n";
      }

    private:
      const double                tolerance;
      double                      last_ratio = 0.;
      Context                    &context;
      NOX::StatusTest::StatusType status = NOX::StatusTest::Unevaluated;
    };
  } // namespace


  void
  NewtonSolver::invalidate_tangent(const bool rescaled)
  {
    tangent_state.reusable = false;
    if (rescaled)
      linear_solver.rebuild_next();
  }


  NewtonSolver::NewtonSolver(const NonlinearSolverParameters &nonlinear,
                             const LinearSolverParameters    &linear,
                             NearNullSpace                    near_null_space,
                             TrilinosWrappers::SparseMatrix  &tangent_matrix,
                             TimerOutput                     &timer)
    : parameters(nonlinear)
    , linear_solver(linear, std::move(near_null_space))
    , tangent_matrix(tangent_matrix)
    , timer(timer)
  {
    // 'automatic' depends on the integrator: Parameters::parse_parameters resolves it.
    AssertThrow(parameters.tangent != "automatic",
                ExcMessage(
                  "Nonlinear solver/Tangent = automatic reached Newton unresolved"));
  }


  NewtonResult
  NewtonSolver::solve(NonlinearProblem              &problem,
                      TrilinosWrappers::MPI::Vector &u,
                      const double                   minimum_displacement_tolerance)
  {
    Context    context{problem,
                    tangent_matrix,
                    linear_solver,
                    parameters,
                    tangent_state,
                    timer,
                    u,
                    u,
                    u,
                    u,
                    u,
                    u};
    const bool single_step = parameters.method == NewtonMethod::single_step;

    auto interface     = Teuchos::rcp(new Interface(context));
    auto linear_system = Teuchos::rcp(new LinearSystem(context));

    auto nox_parameters = Teuchos::rcp(new Teuchos::ParameterList);
    nox_parameters->set("Nonlinear Solver", "Line Search Based");
    // NOX prints "line search failed" at any print level: discarded unless printing
    // iterations (the stepper reports every failed solve with result.failure).
    Teuchos::ParameterList &printing = nox_parameters->sublist("Printing");
    printing.set("Output Information",
                 parameters.print_iterations
                   ? NOX::Utils::Error + NOX::Utils::OuterIteration +
                       NOX::Utils::InnerIteration
                   : NOX::Utils::Error);
    if (!parameters.print_iterations)
      printing.set<Teuchos::RCP<std::ostream>>(
        "Output Stream", Teuchos::rcp(new Teuchos::oblackholestream));
    nox_parameters->sublist("Direction").set("Method", "Newton");
    Teuchos::ParameterList &newton_parameters =
      nox_parameters->sublist("Direction").sublist("Newton");
    newton_parameters.set("Rescue Bad Newton Solve", false);
    if (parameters.method == NewtonMethod::inexact)
      {
        // Eisenstat & Walker's choice 2 with their γ = 0.9, α = 1.5 (NOX's "Type 2"),
        // never tighter than the fixed linear tolerance.
        newton_parameters.set("Forcing Term Method", "Type 2");
        newton_parameters.set("Forcing Term Initial Tolerance",
                              parameters.forcing_term_maximum);
        newton_parameters.set("Forcing Term Maximum Tolerance",
                              parameters.forcing_term_maximum);
        newton_parameters.set("Forcing Term Minimum Tolerance",
                              linear_solver.default_tolerance());
        newton_parameters.set("Forcing Term Alpha", 1.5);
        newton_parameters.set("Forcing Term Gamma", 0.9);
      }
    Teuchos::ParameterList &line_search_parameters =
      nox_parameters->sublist("Line Search");
    auto line_search = Teuchos::rcp(new EnergyLineSearch(
      [&context](const NOX::Abstract::Vector &x) {
        copy(epetra(x), context.u);
        return context.problem.objective(context.u);
      },
      [&context](const NOX::Abstract::Vector &x, const NOX::Abstract::Vector &direction) {
        copy(epetra(x), context.u);
        copy(epetra(direction), context.direction);
        context.has_direction = true;
        return context.problem.largest_step(context.u, context.direction);
      },
      context.problem.adapts()
        ? EnergyLineSearch::Adapt([&context](const NOX::Abstract::Vector &x) {
            copy(epetra(x), context.u);
            return context.problem.adapt(context.u);
          })
        : EnergyLineSearch::Adapt(),
      /*max_halvings=*/30));
    if (parameters.line_search == "full step" || single_step)
      line_search_parameters.set("Method", "Full Step");
    else
      {
        line_search_parameters.set("Method", "User Defined");
        line_search_parameters.set<Teuchos::RCP<NOX::LineSearch::UserDefinedFactory>>(
          "User Defined Line Search Factory",
          Teuchos::rcp(new EnergyLineSearchFactory(line_search)));
      }
    nox_parameters->sublist("Solver Options").set("Status Test Check Type", "Complete");

    Epetra_Vector             initial(Copy, u.trilinos_vector(), 0);
    const NOX::Epetra::Vector initial_guess(initial);
    auto                      group = Teuchos::rcp(new NOX::Epetra::Group(
      nox_parameters->sublist("Printing"), interface, initial_guess, linear_system));
    // NOX's ‖J d + F‖ after each solve (a product with the tangent) is read only by
    // the Eisenstat–Walker forcing term.
    group->disableLinearResidualComputation(parameters.method != NewtonMethod::inexact);

    // Full Newton's tangents come with Φ at the line search's accepted points.
    context.speculate =
      parameters.method == NewtonMethod::full && parameters.tangent != "adaptive";
    problem.speculate_tangents(context.speculate ? &tangent_matrix : nullptr,
                               parameters.tangent == "projected");

    // Converged when ||F|| < absolute or < relative * ||F(u_0)||; failed on NaN or too
    // many iterations.
    group->computeF();
    const double initial_norm   = group->getNormF();
    const double tolerance      = std::max(parameters.absolute_tolerance,
                                      parameters.relative_tolerance * initial_norm);
    auto         residual_small = Teuchos::rcp(new NOX::StatusTest::NormF(tolerance));
    auto converged = Teuchos::rcp(new NOX::StatusTest::Combo(NOX::StatusTest::Combo::OR));
    converged->addStatusTest(residual_small);
    const double step_tolerance =
      std::max(parameters.displacement_tolerance, minimum_displacement_tolerance);
    context.step_tolerance = step_tolerance;
    if (step_tolerance > 0. || parameters.truncation_error_fraction > 0.)
      converged->addStatusTest(Teuchos::rcp(new SmallFullStep(step_tolerance, context)));
    auto max_iterations = Teuchos::rcp(
      new NOX::StatusTest::MaxIters(single_step ? 1 : parameters.max_iterations));
    auto finite = Teuchos::rcp(new NOX::StatusTest::FiniteValue);
    // Divergence: a residual 1e10 times the initial one (or the tolerance) is no
    // approach to a solution; failing at once lets the step be halved instead of
    // iterating on numbers that only grow.
    const double divergence_threshold =
      divergence_factor * std::max(initial_norm, parameters.absolute_tolerance);
    auto divergence = Teuchos::rcp(new NOX::StatusTest::Divergence(divergence_threshold));
    auto status = Teuchos::rcp(new NOX::StatusTest::Combo(NOX::StatusTest::Combo::OR));
    status->addStatusTest(finite);
    status->addStatusTest(divergence);
    status->addStatusTest(converged);
    status->addStatusTest(max_iterations);
    if (parameters.method == NewtonMethod::modified)
      status->addStatusTest(Teuchos::rcp(new TangentMonitor(tangent_state)));

    NewtonResult result;
    if (!std::isfinite(initial_norm))
      {
        result.failure = "residual is not finite at the initial guess";
        return result;
      }

    auto solver = NOX::Solver::buildSolver(group, status, nox_parameters);
    NOX::StatusTest::StatusType outcome = NOX::StatusTest::Unconverged;
    // Any other exception (a defect, memory) goes on to the application, which stops
    // every rank: thrown on one rank only, a retry would leave the others waiting.
    try
      {
        outcome = solver->solve();
      }
    catch (const char *message)
      {
        // NOX throws C strings, e.g. when the Newton system cannot be solved.
        if (context.failure.empty())
          context.failure = message;
        outcome = NOX::StatusTest::Failed;
      }

    const auto &final_group =
      dynamic_cast<const NOX::Epetra::Group &>(solver->getSolutionGroup());
    copy(epetra(final_group.getX()), u);
    problem.speculate_tangents(nullptr, false);
    result.iterations          = solver->getNumIterations();
    result.linear_iterations   = context.linear_iterations;
    result.projected_fallbacks = context.projected_fallbacks;
    result.tangents            = context.tangents;
    result.residual_norm       = final_group.isF() ? final_group.getNormF() : -1.;
    result.converged =
      outcome == NOX::StatusTest::Converged && std::isfinite(result.residual_norm);
    // A single linearised step is accepted as it is, unless it failed outright.
    if (single_step && context.failure.empty() &&
        finite->getStatus() != NOX::StatusTest::Failed &&
        std::isfinite(result.residual_norm))
      result.converged = true;
    if (!result.converged)
      {
        // The tangent may be why it failed: the retry starts with a new one.
        invalidate_tangent();
        if (!context.failure.empty())
          result.failure = context.failure;
        else if (finite->getStatus() == NOX::StatusTest::Failed)
          result.failure = "residual became NaN or infinite";
        else if (divergence->getStatus() == NOX::StatusTest::Failed)
          {
            std::ostringstream message;
            message << "diverged: the residual grew from " << initial_norm << " to "
                    << result.residual_norm << " N";
            result.failure = message.str();
          }
        else
          {
            result.failure =
              max_iterations->getStatus() == NOX::StatusTest::Failed
                ? line_search->iteration_cap_message(parameters.max_iterations)
                : line_search->failure_message();
            // Where the last update pushed hardest: e.g. a director angle turning at a
            // crease (README, "Contact with obstacles").
            const std::string largest =
              context.has_direction ? problem.describe_update(context.direction) : "";
            if (!largest.empty())
              result.failure += "; the last update's largest entry: " + largest;
          }
      }
    return result;
  }
} // namespace clothsim
