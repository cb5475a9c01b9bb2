#include "time/arc_length_stepper.h"

#include "io/progress.h"
#include "solvers/newton_solver.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace clothsim
{
  namespace
  {
    // Corrector iterations per step that 'Adaptive load steps' aims for (Crisfield
    // 1991, §9.5.1: Δs_new = Δs (I_d / I)^½).
    constexpr double desired_iterations = 5.;
  } // namespace


  ArcLengthStepper::ArcLengthStepper(const Parameters   &parameters,
                                     ModelInterface     &model,
                                     OutputWriter       &output,
                                     ConditionalOStream &pcout,
                                     TimerOutput        &timer)
    : StepperCore(parameters, model, output, pcout, timer)
    , linear_solver(parameters.linear_solver, model.near_null_space())
  {
    model.initialize_matrix(tangent);
    for (VectorType *vector :
         {&u_n, &u_new, &residual, &load, &a, &b, &last_increment, &predictor_increment})
      model.initialize_owned(*vector);
    model.initialize_ghosted(ghosted);
  }


  double
  ArcLengthStepper::displacement_dot(const VectorType &x, const VectorType &y) const
  {
    double sum = 0.;
    for (const types::global_dof_index i : model.displacement_dofs())
      sum += x[i] * y[i];
    return Utilities::MPI::sum(sum, model.get_communicator());
  }


  void
  ArcLengthStepper::evaluate_forces(const VectorType &u, const double lambda)
  {
    TimerOutput::Scope scope(timer, "assemble residual");
    model.import_ghosts(u, ghosted);
    StepTerms terms = static_terms(lambda);
    model.assemble(ghosted, terms, &residual, nullptr);
    // f = R(u, λ) - R(u, λ + 1): the loads are linear in λ.
    terms.load_factor = lambda + 1.;
    model.assemble(ghosted, terms, &load, nullptr);
    load.sadd(-1., 1., residual);
  }


  void
  ArcLengthStepper::evaluate_tangent(const VectorType &u, const double lambda)
  {
    {
      TimerOutput::Scope scope(timer, "assemble tangent");
      model.import_ghosts(u, ghosted);
      model.assemble(ghosted, static_terms(lambda), nullptr, &tangent);
    }
    TimerOutput::Scope scope(timer, "preconditioner setup");
    linear_solver.update_preconditioner(tangent);
  }


  StepTerms
  ArcLengthStepper::static_terms(const double lambda)
  {
    StepTerms terms;
    terms.load_factor       = lambda;
    terms.time              = lambda;
    terms.projected_tangent = false; // the exact Hessian: limit points are in it
    return terms;
  }


  bool
  ArcLengthStepper::predict(const double arc, unsigned int &linear_iterations)
  {
    evaluate_forces(u_n, lambda_n);
    evaluate_tangent(u_n, lambda_n);
    unsigned int iterations = 0;
    {
      TimerOutput::Scope scope(timer, "linear solve");
      if (!linear_solver.solve(tangent, b, load, iterations))
        return false;
    }
    linear_iterations += iterations;
    const double b_squared = displacement_dot(b, b);
    if (psi_squared == 0.)
      {
        if (!(b_squared > 0.))
          throw SimulationError("arc length: the loads move nothing (K⁻¹f = 0 at the "
                                "reference state); the path has no direction");
        psi_squared = b_squared;
      }
    // The first step: Δλ = 1/'Load steps' (arc <= 0 asks for it).
    const double norm = std::sqrt(b_squared + psi_squared);
    double       step_load =
      arc > 0. ? arc / norm : 1. / static_cast<double>(parameters.time.load_steps);
    if (displacement_dot(b, last_increment) + psi_squared * last_load_increment < 0.)
      step_load = -step_load;
    predictor_increment = b;
    predictor_increment *= step_load;
    predictor_load = step_load;

    // The tangent's inertia at the equilibrium (u_n, λ_n).
    const int negative = linear_solver.negative_pivots();
    if (negative >= 0 && negative != unstable_modes)
      {
        pcout << "  at load factor " << lambda_n << ": the tangent has " << negative
              << " negative eigenvalue(s), " << unstable_modes << " before: "
              << (negative > unstable_modes ? "past a limit or bifurcation point, the "
                                              "path goes on through unstable equilibria"
                                            : "stable again")
              << std::endl;
        unstable_modes = negative;
      }
    return true;
  }


  ArcLengthStepper::Correction
  ArcLengthStepper::correct(VectorType &u, double &lambda, const Constraint &constraint)
  {
    const NonlinearSolverParameters &newton = parameters.nonlinear_solver;
    const double                     root_n = std::sqrt(static_cast<double>(u.size()));
    // Round-off floor: an update below 1e3 ε times the positions' scale changes nothing
    // the residual can resolve (as in the time steps).
    const double step_tolerance = std::max(newton.displacement_tolerance,
                                           1e3 * std::numeric_limits<double>::epsilon() *
                                             (model.reference_size() + u.linfty_norm()));
    Correction   result;
    double       tolerance = 0., initial = 0.;
    double       last_update = std::numeric_limits<double>::infinity();
    VectorType   update(u);
    for (unsigned int iteration = 0;; ++iteration)
      {
        evaluate_forces(u, lambda);
        result.residual = residual.l2_norm() / root_n;
        if (!std::isfinite(result.residual))
          {
            result.failure = "residual became NaN or infinite";
            return result;
          }
        if (iteration == 0)
          {
            initial = result.residual;
            tolerance =
              std::max(newton.absolute_tolerance, newton.relative_tolerance * initial);
          }
        if (result.residual <= tolerance || last_update < step_tolerance)
          {
            result.converged = true;
            return result;
          }
        if (result.residual >
            divergence_factor * std::max(initial, newton.absolute_tolerance))
          {
            std::ostringstream message;
            message << "diverged: the residual grew from " << initial << " to "
                    << result.residual << " N";
            result.failure = message.str();
            return result;
          }
        if (iteration == newton.max_iterations)
          {
            result.failure = "no convergence in " +
                             std::to_string(newton.max_iterations) + " iterations";
            return result;
          }

        // K a = -R, K b = f, and δλ from the constraint.
        evaluate_tangent(u, lambda);
        unsigned int iterations_a = 0, iterations_b = 0;
        residual *= -1.;
        {
          TimerOutput::Scope scope(timer, "linear solve");
          if (!linear_solver.solve(tangent, a, residual, iterations_a) ||
              !linear_solver.solve(tangent, b, load, iterations_b))
            {
              result.failure = "linear solve: " + linear_solver.failure();
              return result;
            }
        }
        result.linear_iterations += iterations_a + iterations_b;
        ++result.iterations;
        double g   = constraint.load * (lambda - lambda_n) - constraint.target;
        double t_a = 0., t_b = 0.;
        if (constraint.direction != nullptr)
          {
            update = u;
            update -= u_n;
            g += displacement_dot(*constraint.direction, update);
            t_a = displacement_dot(*constraint.direction, a);
            t_b = displacement_dot(*constraint.direction, b);
          }
        const double denominator = t_b + constraint.load;
        if (!(std::abs(denominator) > 0.))
          {
            result.failure =
              "the constraint is tangent to the path (t·K⁻¹f + ψ² t_λ = 0)";
            return result;
          }
        const double delta_lambda = -(g + t_a) / denominator;
        update                    = a;
        update.add(delta_lambda, b);
        // Contact or a bending barrier may cap the update (no crossing).
        double alpha = 1.;
        if (model.caps_steps())
          {
            TimerOutput::Scope scope(timer, "line search: step cap");
            VectorType         direction;
            model.initialize_ghosted(direction);
            direction = update;
            model.import_ghosts(u, ghosted);
            alpha = model.largest_step(ghosted, direction, lambda);
          }
        u.add(alpha, update);
        lambda += alpha * delta_lambda;
        double largest = 0.;
        for (const types::global_dof_index i : model.displacement_dofs())
          largest = std::max(largest, std::abs(update[i]));
        largest     = Utilities::MPI::max(largest, model.get_communicator());
        last_update = alpha == 1. ? largest : std::numeric_limits<double>::infinity();
      }
  }


  RunSummary
  ArcLengthStepper::run()
  {
    RunSummary   summary;
    unsigned int step = 0, halvings = 0;
    const bool   adaptive      = parameters.time.adaptive_load_steps;
    const auto   max_steps     = parameters.time.maximum_arc_length_steps;
    double       arc           = 0.; // Δs, m (0: the first step's, from 'Load steps')
    double       first_arc     = 0.;
    VectorType   zero_velocity = u_n;
    zero_velocity              = 0.;
    u_n                        = 0.;
    lambda_n                   = 0.;
    write_first_frame(u_n, zero_velocity);
    Progress  progress(std::cout,
                      parameters.output.progress,
                      Utilities::MPI::this_mpi_process(model.get_communicator()) == 0);
    StepTimes step_times(timer);
    step_times.since_last();

    while (true)
      {
        stop_if_interrupted(step, lambda_n);
        Correction result;
        double     lambda_new = lambda_n;
        bool       final      = false;
        u_new                 = u_n;
        if (predict(arc, result.linear_iterations))
          {
            ++summary.tangents; // the predictor's
            if (arc <= 0.)
              {
                arc = std::abs(predictor_load) *
                      std::sqrt(displacement_dot(b, b) + psi_squared);
                first_arc = arc;
              }
            u_new.add(1., predictor_increment);
            lambda_new += predictor_load;
            const Constraint   on_arc{&predictor_increment,
                                    psi_squared * predictor_load,
                                    arc * arc};
            const unsigned int predictor_linear = result.linear_iterations;
            result                              = correct(u_new, lambda_new, on_arc);
            result.linear_iterations += predictor_linear;
            // The path crosses λ = 1: that point, solved at λ = 1 with λ held, from
            // the point interpolated on the step.
            if (result.converged && lambda_n < 1. && lambda_new >= 1.)
              {
                const double theta = (1. - lambda_n) / (lambda_new - lambda_n);
                a                  = u_new;
                a -= u_n;
                u_new = u_n;
                u_new.add(theta, a);
                lambda_new = 1.;
                const Correction at_one =
                  correct(u_new, lambda_new, Constraint{nullptr, 1., 1. - lambda_n});
                result.converged = at_one.converged;
                result.failure   = at_one.failure;
                result.residual  = at_one.residual;
                result.iterations += at_one.iterations;
                result.linear_iterations += at_one.linear_iterations;
                final = true;
              }
          }
        else
          result.failure = "linear solve of the predictor: " + linear_solver.failure();
        summary.newton_iterations += result.iterations;
        summary.linear_iterations += result.linear_iterations;
        summary.tangents += result.iterations;
        if (result.converged)
          {
            model.import_ghosts(u_new, ghosted);
            const std::string failure = blow_up(ghosted);
            if (!failure.empty())
              {
                result.converged = false;
                result.failure   = failure;
              }
          }
        if (!result.converged)
          {
            progress.finish();
            std::ostringstream where;
            where << "the corrector failed at load factor " << lambda_new
                  << " with arc length " << arc << " m (" << result.failure << ")";
            if (halvings == parameters.time.max_step_halvings)
              throw SimulationError("arc length: " + where.str() + " after " +
                                    std::to_string(halvings) +
                                    " halvings; the run stops here, output up to load "
                                    "factor " +
                                    std::to_string(lambda_n) + " is kept");
            ++halvings;
            ++summary.retries;
            arc /= 2.;
            check_step_floor(arc, first_arc, lambda_n, "arc length: " + where.str());
            pcout << "step " << step + 1 << ": " << where.str()
                  << "; retrying with arc length " << arc << " m" << std::endl;
            continue;
          }

        // commit: the directors are re-based on the new state (angles back to zero).
        add_static_prescribed_work(u_new, u_n, lambda_n, lambda_new);
        last_increment = u_new;
        last_increment -= u_n;
        last_load_increment = lambda_new - lambda_n;
        u_n                 = u_new;
        lambda_n            = lambda_new;
        ++step;
        model.import_ghosts(u_n, u_ghosted);
        model.commit_step(u_ghosted, u_n);
        model.import_ghosts(u_n, u_ghosted);

        // record: the load factor in the time columns of every file.
        StepFigures figures;
        figures.newton_iterations = result.iterations;
        figures.linear_iterations = result.linear_iterations;
        figures.residual          = result.residual;
        figures.retries           = halvings;
        record(
          step, lambda_n, last_load_increment, figures, current_energies(), step_times);
        write_frame(step, lambda_n);
        std::ostringstream state;
        state << "step " << step << "  load = " << std::setprecision(4) << lambda_n;
        progress.update(std::clamp(lambda_n, 0., 1.), state.str());
        if (final)
          break;
        if (step == max_steps)
          {
            progress.finish();
            std::ostringstream message;
            message << "arc length: 'Time/Maximum arc-length steps' = " << max_steps
                    << " reached at load factor " << lambda_n
                    << " before the path crossed 1; the run stops here, its output is "
                       "kept";
            throw SimulationError(message.str());
          }

        // The next step's length.
        if (adaptive)
          arc = std::min(arc * std::clamp(std::sqrt(desired_iterations /
                                                    std::max(result.iterations, 1u)),
                                          0.5,
                                          2.),
                         4. * first_arc);
        else
          arc = first_arc;
        halvings = 0;
      }
    progress.finish();
    summary.steps = step;
    return summary;
  }
} // namespace clothsim
