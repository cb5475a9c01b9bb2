#include "time/time_stepper.h"

#include "io/progress.h"
#include "time/step_problem.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace clothsim
{
  TimeStepper::TimeStepper(const Parameters   &parameters,
                           ModelInterface     &model,
                           OutputWriter       &output,
                           ConditionalOStream &pcout,
                           TimerOutput        &timer)
    : StepperCore(parameters, model, output, pcout, timer)
    , newton(parameters.nonlinear_solver,
             parameters.linear_solver,
             model.near_null_space(),
             tangent,
             timer)
    , dynamic(!is_static(parameters.time.integrator))
  {
    model.initialize_matrix(tangent);
    for (VectorType *vector :
         {&u_n, &v_n, &u_new, &v_new, &centre, &u_nm1, &v_nm1, &last_increment})
      model.initialize_owned(*vector);
    model.initialize_owned(solved);
    model.initialize_ghosted(predictor_ghosted);
    model.initialize_ghosted(centre_ghosted);
    model.initialize_ghosted(check_ghosted);
  }


  StepTerms
  TimeStepper::predict_step(const double time_new,
                            const double dt,
                            const double load_factor)
  {
    const Integrator integrator = parameters.time.integrator;
    const bool       bdf2       = integrator == Integrator::bdf2 && previous_step > 0.;
    const bool       midpoint   = solves_for_midpoint(integrator);
    StepTerms        terms;
    terms.load_factor = load_factor;
    terms.time        = time_new;
    if (!dynamic)
      {
        // Secant predictor along the load path (angles included: the last increment's
        // angles are the director rotation it took, relative to the re-based
        // references).
        u_new = u_n;
        if (last_load_increment > 0.)
          u_new.add(dt / last_load_increment, last_increment);
        model.apply_pinned_displacement(load_factor, u_new);
        return terms;
      }

    // BDF2 with step ratio ω = dt/dt_{n-1}, γ = (1+2ω)/(1+ω):
    //   v_{n+1} = γ/dt (u_{n+1} - ũ),  a_{n+1} = γ/dt (v_{n+1} - ṽ),
    //   ũ = ((1+ω) u_n - ω²/(1+ω) u_{n-1}) / γ, likewise ṽ;
    // so the step minimises the incremental potential with w_i = γ²/dt², û = ũ + dt/γ ṽ,
    // w_d = γ/dt and damping centre ũ. Backward Euler is γ = 1, ũ = u_n, ṽ = v_n; the
    // implicit midpoint rule is backward Euler over dt/2 to the midpoint x, then
    // u_{n+1} = 2x - u_n, v_{n+1} = 2(u_{n+1} - u_n)/dt - v_n.
    gamma          = 1.;
    const double h = midpoint ? dt / 2. : dt;
    centre         = u_n; // ũ
    VectorType rate(v_n); // ṽ
    if (bdf2)
      {
        const double omega = dt / previous_step;
        gamma              = (1. + 2. * omega) / (1. + omega);
        const double c_n   = (1. + omega) / gamma;
        const double c_nm1 = omega * omega / ((1. + omega) * gamma);
        centre.sadd(c_n, -c_nm1, u_nm1);
        rate.sadd(c_n, -c_nm1, v_nm1);
      }
    terms.inertia_weight = gamma * gamma / (h * h);
    terms.damping_weight = gamma / h;
    VectorType predictor(centre);
    predictor.add(h / gamma, rate);
    model.import_ghosts(predictor, predictor_ghosted);
    model.import_ghosts(centre, centre_ghosted);
    terms.predictor = &predictor_ghosted;
    terms.previous  = &centre_ghosted;
    u_new           = predictor; // Newton's initial guess
    model.apply_pinned_displacement(time_new, u_new);
    if (midpoint)
      {
        // The pins' midpoint positions, so that 2x - u_n lands on them at t_{n+1}.
        u_new.add(1., u_n);
        u_new *= 0.5;
        for (const types::global_dof_index i : model.owned_dofs())
          if (!model.get_constraints().is_constrained(i))
            u_new[i] = predictor[i];
        u_new.compress(VectorOperation::insert);
      }
    return terms;
  }


  TimeStepper::Attempt
  TimeStepper::attempt_step(const double time_new,
                            const double dt,
                            const double load_factor)
  {
    const bool midpoint = solves_for_midpoint(parameters.time.integrator);
    Attempt    attempt;

    // predict (u_ghosted holds the state n)
    if (dynamic)
      model.prepare_step(u_ghosted);
    const StepTerms terms = predict_step(time_new, dt, load_factor);
    last_terms            = terms;
    // Contact: Newton starts off the obstacles (and friction is lagged); a bending
    // barrier: with no tilt across it.
    std::string infeasible;
    if (model.caps_steps())
      {
        TimerOutput::Scope scope(timer, "feasible start");
        infeasible =
          model.begin_step(time_new - dt, time_new, u_n, u_new, midpoint ? 2. : 1.);
      }
    if (!infeasible.empty())
      throw SimulationError("contact: " + infeasible +
                            "; the run stops here, output up to t = " +
                            std::to_string(time_new - dt) + " s is kept");
    // Self-contact: pairs that may touch during the step couple vertices that share no
    // triangle; the tangent's sparsity grows with them.
    if (model.update_couplings(u_n, u_new))
      {
        TimerOutput::Scope scope(timer, "sparsity update");
        model.initialize_matrix(tangent);
        newton.sparsity_changed();
      }

    // solve. A tangent kept by 'modified newton' is one of these weights only. ML's
    // hierarchy recomputed on the aggregates of a differently scaled tangent can fail
    // (measured: a step ratio of 0.54 made CG fail in 2000 iterations): a new step size
    // gets a new hierarchy. With adaptive steps Newton stops once its updates are a
    // tenth of the time-error tolerance: solving further would be below the truncation
    // error.
    StepProblem problem(model, terms, timer);
    if (parameters.time.integrator == Integrator::average_vector_field)
      problem.average_along_path_from(u_n, path_tangent);
    if (parameters.nonlinear_solver.mixed_stress_tangent)
      problem.linearise_stress_from(u_n);
    if (terms.inertia_weight != tangent_weights.first ||
        terms.damping_weight != tangent_weights.second)
      newton.invalidate_tangent(/*rescaled=*/true);
    tangent_weights = {terms.inertia_weight, terms.damping_weight};
    // Round-off floor: a full Newton update below 1e3 ε times the positions' scale
    // changes nothing the residual can resolve (its round-off, set by the largest force
    // term, e.g. the 1/dt² inertia of a short step, may lie above 'Absolute
    // tolerance'), so the step is converged there.
    const double roundoff_floor =
      1e3 * std::numeric_limits<double>::epsilon() * (reference_size + u_n.linfty_norm());
    const double newton_floor = std::max(roundoff_floor,
                                         dynamic && parameters.time.adaptive_time_steps
                                           ? 0.1 * step_tolerance(dt, 0.)
                                           : 0.);
    // 'Truncation error fraction': an update below that share of the step's own error
    // estimate at the iterate changes the answer by less than the step's discretisation
    // does (Hairer & Wanner, "Solving ODEs II", IV.8: stop Newton at a fraction of the
    // local error). 'Truncation error norm': both measured by their largest component,
    // or in the kinetic norm (a root mean square, as Hairer & Wanner's error norms are).
    // A fold's last Newton updates are local (a free edge buckling within the step):
    // mm at a few vertices, 1e-7 J of the step's potential.
    const double fraction = parameters.nonlinear_solver.truncation_error_fraction;
    if (dynamic && fraction > 0.)
      {
        const bool kinetic =
          parameters.nonlinear_solver.truncation_error_norm == "kinetic";
        if (kinetic && masses.size() == 0)
          model.lumped_masses(masses);
        problem.set_update_ratio(
          [this, dt, fraction, midpoint, kinetic, &problem](const VectorType &update,
                                                            const VectorType &u) {
            const double size =
              kinetic ? kinetic_norm(update) : problem.update_size(update);
            return size / (fraction * error_estimate(dt, u, midpoint, kinetic).first);
          });
      }
    attempt.newton = newton.solve(problem, u_new, newton_floor);
    if (!attempt.newton.converged)
      return attempt;
    if (parameters.time.integrator == Integrator::linear_static)
      {
        // f = -F(0): the residual at the reference state is the loads' (no stress).
        VectorType reference(u_new), residual(u_new);
        reference = 0.;
        problem.residual(reference, residual);
        const double work = -(residual * u_new);
        linear_energies   = std::make_pair(0.5 * work, -work);
      }
    // 'Contact/Friction updates': friction's normal forces taken again at the solution
    // and the step solved again, until they settle (0.1 %).
    for (unsigned int update = 1; update < parameters.contact.friction_updates; ++update)
      {
        model.import_ghosts(u_new, check_ghosted);
        if (model.relag_friction(check_ghosted) < 1e-3)
          break;
        problem.forget_cached_values();
        newton.invalidate_tangent();
        const NewtonResult again = newton.solve(problem, u_new, newton_floor);
        attempt.newton.iterations += again.iterations;
        attempt.newton.linear_iterations += again.linear_iterations;
        attempt.newton.tangents += again.tangents;
        attempt.newton.converged     = again.converged;
        attempt.newton.residual_norm = again.residual_norm;
        attempt.newton.failure       = again.failure;
        if (!again.converged)
          return attempt;
      }

    // The work against damping and by prescribed motion is taken at the solved iterate
    // (the midpoint's x).
    if (dynamic && (model.has_dissipation() || model.has_prescribed_motion()))
      solved = u_new;
    if (dynamic)
      {
        if (midpoint)
          {
            u_new.sadd(2., -1., u_n);
            v_new = u_new;
            v_new -= u_n;
            v_new.sadd(2. / dt, -1., v_n);
          }
        else
          {
            v_new = u_new;
            v_new -= centre;
            v_new *= gamma / dt;
          }
      }

    // check: a collapsed or hundredfold grown triangle is no cloth state (the explicit
    // stepper's divergence test too): the step is cut like a failed Newton solve. A
    // single linearised step of a stiff, fast-rotating sheet can stretch it that far.
    model.import_ghosts(u_new, check_ghosted);
    const std::string failure = blow_up(check_ghosted);
    if (!failure.empty())
      {
        attempt.newton.converged = false;
        attempt.newton.failure   = failure;
        return attempt;
      }
    if (dynamic)
      std::tie(attempt.error_estimate, attempt.order) = error_estimate(dt, u_new);
    return attempt;
  }


  void
  TimeStepper::commit_step(const unsigned int step, const double dt)
  {
    // What the barrier stiffness's raises in this step added, at its end (check_ghosted
    // holds u_new since the attempt's check).
    if (model.adapts_stiffness())
      stiffness_raised += model.stiffness_raise_energy(check_ghosted, last_terms.time);
    // The work of prescribed motion: the steps that solve for their end state take the
    // trapezoidal rule over their end forces, the midpoint rules their midpoint's.
    if (dynamic)
      add_prescribed_work(solved,
                          last_terms,
                          u_new,
                          u_n,
                          last_terms.time - dt,
                          last_terms.time,
                          !solves_for_midpoint(parameters.time.integrator));
    else
      add_static_prescribed_work(u_new,
                                 u_n,
                                 last_terms.load_factor - dt,
                                 last_terms.load_factor);
    if (dynamic)
      {
        add_dissipation(solved, last_terms, u_new, u_n);
        u_nm1         = u_n;
        v_nm1         = v_n;
        previous_step = dt;
        v_n           = v_new;
        limit_strain(step, u_new, v_n, dt);
      }
    last_increment = u_new;
    last_increment -= u_n;
    last_load_increment = dt;
    u_n                 = u_new;
    // The terms' after-step hooks (shell directors re-based, angles back to zero); a
    // linear solution keeps its angles about the reference directors, so that its
    // reactions are taken about the reference state (ClothModel::support_reactions).
    model.import_ghosts(u_n, u_ghosted);
    if (parameters.time.integrator != Integrator::linear_static)
      model.commit_step(u_ghosted, u_n);
    model.import_ghosts(u_n, u_ghosted);
    model.import_ghosts(v_n, v_ghosted);
  }


  double
  TimeStepper::step_tolerance(const double dt, const double largest_displacement) const
  {
    const TimeParameters &time = parameters.time;
    if (time.accuracy_target > 0.)
      return time.accuracy_target * dt / time.end_time;
    return time.error_tolerance + time.relative_error_tolerance * largest_displacement;
  }


  const std::vector<unsigned int> &
  TimeStepper::local_displacement_dofs() const
  {
    if (displacement_local.empty())
      {
        const IndexSet owned = u_n.locally_owned_elements();
        for (const types::global_dof_index i : model.displacement_dofs())
          displacement_local.push_back(owned.index_within_set(i));
      }
    return displacement_local;
  }


  double
  TimeStepper::kinetic_norm(const VectorType &x) const
  {
    double        sum = 0., mass = 0.;
    const double *m_local = masses.begin(), *x_local = x.begin(); // owned entries
    for (const unsigned int i : local_displacement_dofs())
      {
        const double m = m_local[i], value = x_local[i];
        sum += m * value * value;
        mass += m;
      }
    const MPI_Comm communicator = model.get_communicator();
    return std::sqrt(Utilities::MPI::sum(sum, communicator) /
                     Utilities::MPI::sum(mass, communicator));
  }


  std::pair<double, unsigned int>
  TimeStepper::error_estimate(const double      dt,
                              const VectorType &u,
                              const bool        u_is_midpoint,
                              const bool        kinetic) const
  {
    const Integrator   integrator = parameters.time.integrator;
    const unsigned int order =
      (integrator != Integrator::backward_euler && previous_step > 0.) ? 2 : 1;
    double kappa    = 0.5;
    double a_weight = 0.; // dt²/2 / dt₋ on (v - v₋)
    if (order == 2)
      {
        // Local errors per dt³ u⁽³⁾ with ω = dt/dt₋: the Taylor predictor (its
        // acceleration (v - v₋)/dt₋ lags by dt₋/2) 1/6 + 1/(4ω); the midpoint rule -1/12;
        // variable-step BDF2 (1+ω)²/(6ω(1+2ω)), 2/9 at ω = 1. Milne's device: the step's
        // error is its constant over the difference of the two.
        const double omega     = dt / previous_step;
        const double predictor = 1. / 6. + 1. / (4. * omega);
        if (solves_for_midpoint(integrator))
          kappa = (1. / 12.) / (predictor + 1. / 12.);
        else
          {
            const double bdf2 =
              (1. + omega) * (1. + omega) / (6. * omega * (1. + 2. * omega));
            kappa = bdf2 / (predictor - bdf2);
          }
        a_weight = 0.5 * dt * dt / previous_step;
      }
    // The end state u₊: u itself, or 2 u - u_n from the midpoint rule's midpoint.
    const bool midpoint = u_is_midpoint && solves_for_midpoint(integrator);
    double     largest  = 0.;
    if (kinetic)
      difference.reinit(u_n, /*omit_zeroing_entries=*/true);
    // Owned entries by local index.
    const double *start = u_n.begin(), *velocity = v_n.begin(), *earlier = v_nm1.begin(),
                 *solved = u.begin();
    double *error        = kinetic ? difference.begin() : nullptr;
    for (const unsigned int i : local_displacement_dofs())
      {
        const double predicted =
          start[i] + dt * velocity[i] + a_weight * (velocity[i] - earlier[i]);
        const double end = midpoint ? 2. * solved[i] - start[i] : solved[i];
        largest          = std::max(largest, std::abs(end - predicted));
        if (kinetic)
          error[i] = end - predicted;
      }
    return {kappa * (kinetic ? kinetic_norm(difference)
                             : Utilities::MPI::max(largest, model.get_communicator())),
            order};
  }


  void
  TimeStepper::halve_step(const NewtonResult &result,
                          const double        time,
                          const double        time_new,
                          const unsigned int  step,
                          RunSummary         &summary)
  {
    if (control.halvings == parameters.time.max_step_halvings)
      {
        std::ostringstream message;
        message << "Newton failed at t = " << time_new << " with dt = " << time_new - time
                << " after " << control.halvings << " step halvings (" << result.failure
                << "); the run stops here, output up to t = " << time << " is kept";
        throw SimulationError(message.str());
      }
    ++control.halvings;
    ++summary.retries;
    check_step_floor(control.size(),
                     first_step,
                     time,
                     "Newton's failure (" + result.failure + ")");
    pcout << "step " << step + 1 << ": Newton failed at t = " << time_new << " ("
          << result.failure << "); retrying with dt = " << control.size() << std::endl;
  }


  bool
  TimeStepper::accept_step(const Attempt &attempt,
                           const double   time,
                           const double   time_new,
                           const double   end,
                           RunSummary    &summary)
  {
    const double error     = attempt.error_estimate;
    const double dt        = time_new - time;
    const double tolerance = step_tolerance(dt, u_new.linfty_norm());
    const double factor =
      error > 0.
        ? std::clamp(0.9 * std::pow(tolerance / error, 1. / (attempt.order + 1.)),
                     0.2,
                     2.)
        : 2.;
    control.next = std::min(factor * dt, parameters.time.maximum_time_step);
    // (A step cut short by the end proposes a small next step that is never taken.)
    if (time_new < end &&
        control.next < parameters.time.minimum_step_fraction * first_step)
      {
        std::ostringstream why;
        why << "the error control (local error estimate " << error << " m against the "
            << "tolerance " << tolerance << " m)";
        check_step_floor(control.next, first_step, time, why.str());
      }
    if (error <= tolerance)
      return true;
    ++control.rejected;
    ++summary.rejected;
    control.restart(time, control.next, end);
    return false;
  }


  RunSummary
  TimeStepper::run()
  {
    const double end = dynamic ? parameters.time.end_time : 1.;
    first_step = dynamic ? parameters.time.time_step : 1. / parameters.time.load_steps;
    reference_size = model.reference_size();
    if (!resumed)
      control.nominal = first_step;
    const bool adaptive_increments = !dynamic && parameters.time.adaptive_load_steps;
    const bool adaptive            = dynamic && parameters.time.adaptive_time_steps;
    const bool bdf2_fixed_steps =
      !adaptive && parameters.time.integrator == Integrator::bdf2;
    const double largest_increment = 4. / parameters.time.load_steps;
    const double output_interval   = dynamic ? parameters.output.interval : 0.;
    const double epsilon           = 1e-9 * first_step;
    const auto   checkpoint        = [this]() { write_checkpoint(); };
    const std::function<void()> checkpoint_on_interruption =
      checkpoint_directory.empty() ? std::function<void()>() : checkpoint;

    Progress progress(std::cout,
                      parameters.output.progress,
                      Utilities::MPI::this_mpi_process(model.get_communicator()) == 0);

    if (!resumed)
      {
        // Initial state (static mode: the reference configuration, pins at λ = 0).
        if (dynamic)
          model.initial_state(u_n, v_n);
        else
          {
            u_n = 0.;
            v_n = 0.;
            model.apply_pinned_displacement(0., u_n);
          }
        previous_step = 0.;
        write_first_frame(u_n, v_n);
        summary              = RunSummary();
        loop                 = LoopState();
        loop.next_output     = output_interval;
        loop.next_checkpoint = checkpoint_interval;
      }

    double       &time = loop.time;
    unsigned int &step = loop.step;
    StepTimes     step_times(timer);
    step_times.since_last();
    // A restart enters the loop of sub-steps where the checkpoint was taken.
    bool enter_sub_steps = resumed;
    while (time < end - epsilon)
      {
        // One nominal step, in 2^k sub-steps if Newton needs smaller ones (BDF2 at fixed
        // steps: k starts one below the last nominal step's).
        if (!enter_sub_steps)
          {
            control.carried =
              bdf2_fixed_steps ? std::max(control.carried + control.halvings, 1u) - 1 : 0;
            control.restart(time, control.nominal, end);
            control.next         = control.nominal;
            loop.last_iterations = 0;
            loop.failed_attempts = 0;
          }
        enter_sub_steps = false;
        while (time < control.target - epsilon)
          {
            stop_if_interrupted(step, time, checkpoint_on_interruption);
            const double dt = std::min(control.target - time, control.size());
            const double time_new =
              (control.target - time - dt < epsilon) ? control.target : time + dt;

            // predict, solve, check
            const Attempt attempt =
              attempt_step(time_new, time_new - time, dynamic ? 1. : time_new);
            const NewtonResult &result = attempt.newton;
            summary.newton_iterations += result.iterations;
            summary.linear_iterations += result.linear_iterations;
            summary.tangents += result.tangents;
            loop.last_iterations = result.iterations;
            if (!result.converged)
              {
                progress.finish();
                halve_step(result, time, time_new, step, summary);
                ++loop.failed_attempts;
                continue;
              }

            // accept or reject (the estimate is written for every dynamic step)
            if (adaptive && !accept_step(attempt, time, time_new, end, summary))
              continue;

            // commit
            const double dt_taken = time_new - time;
            time                  = time_new;
            ++step;
            commit_step(step, dt_taken);

            // record
            StepFigures figures;
            figures.newton_iterations = result.iterations;
            figures.linear_iterations = result.linear_iterations;
            figures.residual          = result.residual_norm;
            figures.retries           = loop.failed_attempts;
            figures.rejected          = control.rejected;
            figures.error_estimate    = attempt.error_estimate;
            record(step, time, dt_taken, figures, current_energies(), step_times);
            control.rejected     = 0;
            loop.failed_attempts = 0;
            summary.estimated_error += attempt.error_estimate;
            if (adaptive) // the controller's step replaces any halvings of this one
              control.restart(time, control.next, end);
            if (time >= end - epsilon || output_interval == 0. ||
                time >= loop.next_output - epsilon)
              {
                write_frame(step, time);
                while (loop.next_output <= time + epsilon && output_interval > 0.)
                  loop.next_output += output_interval;
              }
            // A checkpoint every 'Checkpoint interval' and at the end.
            if (checkpoint_interval > 0. &&
                (time >= end - epsilon || time >= loop.next_checkpoint - epsilon))
              {
                while (loop.next_checkpoint <= time + epsilon)
                  loop.next_checkpoint += checkpoint_interval;
                write_checkpoint();
              }
            std::ostringstream state;
            state << "step " << step << "  " << (dynamic ? "t = " : "load = ")
                  << std::setprecision(4) << time << (dynamic ? " s" : "");
            progress.update(time / end, state.str());
          }
        // Adaptive load increments: keep the size that worked, grow it when Newton had an
        // easy time.
        if (adaptive_increments)
          {
            if (control.halvings > 0)
              control.nominal /= std::pow(2., control.halvings);
            else if (loop.last_iterations <= 6)
              control.nominal = std::min(1.5 * control.nominal, largest_increment);
          }
      }
    progress.finish();
    summary.steps = step;
    return summary;
  }
} // namespace clothsim
