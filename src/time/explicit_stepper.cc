#include "time/explicit_stepper.h"

#include "io/progress.h"

#include <Epetra_CrsMatrix.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace clothsim
{
  namespace
  {
    // Steps above this fraction of the critical step get a warning: the linear stability
    // bound does not cover large nonlinear motions.
    constexpr double safe_fraction = 0.9;

    // Lumped masses inverted, zero on constrained (pinned) dofs. Owned.
    void
    free_inverse_masses(const ModelInterface &model, VectorType &inverse_mass)
    {
      model.lumped_masses(inverse_mass);
      const AffineConstraints<double> &constraints = model.get_constraints();
      for (const types::global_dof_index i : model.owned_dofs())
        {
          const double m  = inverse_mass[i];
          inverse_mass[i] = (m > 0. && !constraints.is_constrained(i)) ? 1. / m : 0.;
        }
      inverse_mass.compress(VectorOperation::insert);
    }
  } // namespace


  CriticalStepEstimator::CriticalStepEstimator(const ModelInterface &model,
                                               const Parameters     &parameters)
    : model(model)
    , parameters(parameters)
  {
    free_inverse_masses(model, inverse_mass);
    model.initialize_matrix(stiffness);
    model.initialize_owned(free_masses);
    model.initialize_owned(mode);
    model.initialize_owned(Kz);
    model.initialize_owned(Mz);
    for (const types::global_dof_index i : model.owned_dofs())
      {
        free_masses[i] = inverse_mass[i] > 0. ? 1. / inverse_mass[i] : 0.;
        // Start vector: depends on the global dof index only (any number of ranks).
        mode[i] = inverse_mass[i] > 0. ? 1. + 0.5 * std::sin(1.618 * double(i)) : 0.;
      }
    free_masses.compress(VectorOperation::insert);
    mode.compress(VectorOperation::insert);
  }


  CriticalStep
  CriticalStepEstimator::estimate(const VectorType &u)
  {
    // K: the elastic part of the projected tangent (no inertia, no damping).
    StepTerms terms;
    terms.projected_tangent = true;
    model.assemble(u, terms, nullptr, &stiffness);

    // Gershgorin: λ_max(M⁻¹K) ≤ max_i Σ_j |K_ij| / m_i over the free rows (Epetra's local
    // rows, in the order of the owned vectors' entries).
    const Epetra_CrsMatrix &K            = stiffness.trilinos_matrix();
    const double           *inverse_data = inverse_mass.trilinos_vector()[0];
    Assert(K.RowMap().SameAs(inverse_mass.trilinos_partitioner()), ExcInternalError());
    double row_bound = 0.;
    for (int row = 0; row < K.NumMyRows(); ++row)
      if (inverse_data[row] > 0.)
        {
          int     length;
          double *values;
          int    *columns;
          K.ExtractMyRowView(row, length, values, columns);
          double row_sum = 0.;
          for (int k = 0; k < length; ++k)
            row_sum += std::abs(values[k]);
          row_bound = std::max(row_bound, row_sum * inverse_data[row]);
        }
    row_bound = Utilities::MPI::max(row_bound, model.get_communicator());

    // Power iteration z <- M⁻¹ K z (z = mode, zero on pinned dofs), warm-started from the
    // last call; Rayleigh quotient zᵀKz / zᵀMz.
    VectorType  &z      = mode;
    double       lambda = 0.;
    const double limit  = warm ? 100 : 500;
    for (unsigned int iteration = 0; iteration < limit; ++iteration)
      {
        stiffness.vmult(Kz, z);
        Mz = z;
        Mz.scale(free_masses);
        const double zMz        = Mz * z;
        const double new_lambda = zMz > 0. ? (Kz * z) / zMz : 0.;
        const bool   converged  = std::abs(new_lambda - lambda) <= 1e-5 * new_lambda;
        lambda                  = new_lambda;
        if (converged && iteration > 10)
          break;
        z = Kz;
        z.scale(inverse_mass);
        const double norm = z.l2_norm();
        if (norm == 0.)
          break;
        z /= norm;
      }
    warm = true;

    const auto critical = [&](const double omega) {
      const double zeta = parameters.damping.mass_proportional / (2. * omega) +
                          parameters.damping.stiffness_proportional * omega / 2.;
      return std::make_pair((2. / omega) * (std::sqrt(1. + zeta * zeta) - zeta), zeta);
    };
    CriticalStep result;
    result.omega_max                                = std::sqrt(lambda);
    std::tie(result.estimate, result.damping_ratio) = critical(result.omega_max);
    result.gershgorin_bound = critical(std::sqrt(row_bound)).first;
    return result;
  }


  CriticalStep
  estimate_critical_step(const ModelInterface &model,
                         const Parameters     &parameters,
                         const VectorType     &u)
  {
    return CriticalStepEstimator(model, parameters).estimate(u);
  }


  ExplicitStepper::ExplicitStepper(const Parameters   &parameters,
                                   ModelInterface     &model,
                                   OutputWriter       &output,
                                   ConditionalOStream &pcout,
                                   TimerOutput        &timer)
    : StepperCore(parameters, model, output, pcout, timer)
  {
    free_inverse_masses(model, inverse_mass);
    model.initialize_owned(gradient);
    model.initialize_owned(centre);
    model.initialize_ghosted(centre_ghosted);
    model.initialize_ghosted(work_ghosted);
  }


  StepTerms
  ExplicitStepper::damping_terms(const VectorType &u, const VectorType &v)
  {
    StepTerms terms;
    terms.damping_weight = 1.;
    centre               = u;
    centre -= v;
    model.import_ghosts(centre, centre_ghosted);
    terms.previous = &centre_ghosted;
    return terms;
  }


  void
  ExplicitStepper::acceleration(const VectorType    &u,
                                const VectorType    &v,
                                VectorType          &a,
                                physics::RankVector *damping_force)
  {
    TimerOutput::Scope scope(timer, "assemble forces");
    // ∇Φ with no inertia and the damping term centred at u - v: its gradient is
    // ∇W - f_g - f_ext + (α M + β K(u)) v, zero on pinned dofs; its dissipative part
    // alone is the damping force (α M + β K(u)) v.
    const StepTerms terms = damping_terms(u, v);
    model.import_ghosts(u, work_ghosted);
    if (parameters.damping.stiffness_proportional > 0.)
      model.prepare_step(work_ghosted);
    if (damping_force != nullptr)
      model.assemble_gradient(work_ghosted, terms, gradient, *damping_force);
    else
      model.assemble(work_ghosted, terms, &gradient, nullptr);
    a = gradient;
    a.scale(inverse_mass);
    a *= -1.;
  }


  void
  ExplicitStepper::add_step_prescribed_work(const VectorType &u,
                                            const VectorType &u_old,
                                            const VectorType &v_old,
                                            const double      t_n,
                                            const double      t_new)
  {
    const double h = t_new - t_n;
    centre         = u_old;
    centre.add(h, v_old); // the predictor
    model.import_ghosts(centre, work_ghosted);
    model.import_ghosts(u_old, centre_ghosted);
    StepTerms terms;
    terms.inertia_weight = 1. / (h * h);
    terms.damping_weight = 1. / h;
    terms.predictor      = &work_ghosted;
    terms.previous       = &centre_ghosted;
    terms.time           = t_new;
    add_prescribed_work(u, terms, u, u_old, t_n, t_new, /*trapezoid=*/true);
  }


  RunSummary
  ExplicitStepper::run()
  {
    const bool   verlet   = parameters.time.integrator == Integrator::velocity_verlet;
    const double end      = parameters.time.end_time;
    const double dt       = parameters.time.time_step;
    const double interval = parameters.output.interval;
    const double epsilon  = 1e-9 * dt;

    VectorType u, v, a, u_old, v_old;
    for (VectorType *vector : {&u, &v, &a, &u_old, &v_old})
      model.initialize_owned(*vector);
    model.initial_state(u, v);
    model.import_ghosts(u, work_ghosted);

    CriticalStepEstimator estimator(model, parameters);
    critical = estimator.estimate(work_ghosted);
    pcout << "  explicit " << (verlet ? "velocity Verlet" : "symplectic Euler")
          << ": critical step " << critical.estimate << " s (omega_max "
          << critical.omega_max << " 1/s, damping ratio " << critical.damping_ratio
          << " there; Gershgorin's safe bound " << critical.gershgorin_bound
          << " s); time step " << dt << " s = " << dt / critical.estimate << " x critical"
          << std::endl;
    if (dt > critical.estimate)
      pcout << "warning: the time step " << dt
            << " s exceeds the estimated critical step " << critical.estimate
            << " s: the explicit run is likely to diverge (it stops when it does)"
            << std::endl;
    else if (dt > safe_fraction * critical.estimate)
      pcout << "warning: the time step " << dt << " s is within "
            << 100. * (1. - safe_fraction)
            << " % of the critical step: large motions can still make the run diverge "
               "(on the hanging sheet 0.98 x critical diverged after 0.94 s)"
            << std::endl;

    RunSummary summary;
    Progress   progress(std::cout,
                      parameters.output.progress,
                      Utilities::MPI::this_mpi_process(model.get_communicator()) == 0);
    write_first_frame(u, v);
    double next_output      = interval > 0. ? interval : end;
    double checked_activity = 0.; // K + W at the last area check, J

    StepTimes  step_times(timer);
    const bool dissipation = model.has_dissipation();
    if (verlet)
      acceleration(u, v, a, dissipation ? &damping_force : nullptr);
    double       time   = 0.;
    unsigned int step   = 0;
    bool         warned = dt > safe_fraction * critical.estimate;
    while (time < end - epsilon)
      {
        stop_if_interrupted(step, time);
        // Land on output times and the end exactly.
        const double time_new = std::min({time + dt, next_output, end});
        const double h        = time_new - time;
        u_old                 = u;
        v_old                 = v;
        // The energy budget needs the damping force at the step's start, D(u_n) v_n:
        // symplectic Euler's force evaluation gives it; Verlet's last one saw v_{n-1/2},
        // so there the energies of (u_n, v_n) gave it (below; at the start, the first
        // force evaluation).
        if (verlet)
          {
            v.add(0.5 * h, a); // v_{n+1/2}
            u.add(h, v);
          }
        else
          {
            acceleration(u, v, a, dissipation ? &damping_force : nullptr);
            v.add(h, a);
            u.add(h, v);
          }
        // Pinned dofs: prescribed positions, velocities by finite difference.
        model.apply_pinned_displacement(time_new, u);
        for (const types::global_dof_index i : model.owned_dofs())
          if (inverse_mass[i] == 0.)
            v[i] = (u[i] - u_old[i]) / h;
        v.compress(VectorOperation::insert);
        // The work against damping: its force at the step's start, D(u_n) v_n, over the
        // step's displacement (exact for symplectic Euler, first order for Verlet).
        if (dissipation)
          add_dissipation(damping_force, u, u_old);
        if (model.has_prescribed_motion())
          add_step_prescribed_work(u, u_old, v_old, time, time_new);
        if (verlet)
          {
            acceleration(u, v, a);
            v.add(0.5 * h, a);
            for (const types::global_dof_index i : model.owned_dofs())
              if (inverse_mass[i] == 0.)
                v[i] = (u[i] - u_old[i]) / h;
            v.compress(VectorOperation::insert);
          }
        if (model.has_strain_limit())
          {
            limit_strain(step + 1, u, v, h);
            if (verlet)
              acceleration(u, v, a);
          }
        time = time_new;
        ++step;

        model.import_ghosts(u, u_ghosted);
        model.import_ghosts(v, v_ghosted);
        // Verlet: with D(u_{n+1}) v_{n+1} for the next step (K was last prepared at
        // u_{n+1}).
        const EnergyReport energies =
          verlet && dissipation ? current_energies(damping_force) : current_energies();
        const bool output_now =
          interval == 0. || time >= next_output - epsilon || time >= end - epsilon;
        // Blow-up: a non-finite energy every step; a collapsed or hundredfold grown
        // triangle every 10 steps, at output times, and whenever K + W has more than
        // quadrupled since the last area check (a diverging run grows exponentially; the
        // area check every step would cost 10 % of a step).
        std::string  failure;
        const double activity = energies.kinetic + energies.elastic;
        if (!std::isfinite(activity))
          failure = "the energy is not finite";
        else if (step % 10 == 0 || output_now || activity > 4. * checked_activity)
          {
            checked_activity = activity;
            failure          = blow_up(u_ghosted);
          }
        if (!failure.empty())
          {
            progress.finish();
            std::ostringstream message;
            message
              << "the explicit integration diverged at t = " << time << " (step " << step
              << ", dt = " << dt << " s, estimated critical step " << critical.estimate
              << " s): " << failure
              << "; reduce 'Time/Time step' or use 'backward euler'. Output up to the "
                 "last written frame is kept";
            throw SimulationError(message.str());
          }

        record(step, time, h, StepFigures(), energies, step_times);
        if (output_now)
          write_frame(step, time);
        if (output_now && interval > 0. && time < end - epsilon)
          {
            // The deformed sheet's critical step; warn once when dt comes to exceed it.
            TimerOutput::Scope scope(timer, "critical step");
            const CriticalStep current = estimator.estimate(u_ghosted);
            if (dt > safe_fraction * current.estimate && !warned)
              {
                progress.finish();
                pcout << "warning: at t = " << time
                      << " s the critical step has fallen to " << current.estimate
                      << " s (the deformed sheet is stiffer): the time step " << dt
                      << " s is now within " << 100. * (1. - safe_fraction)
                      << " % of it or beyond, and the run may diverge" << std::endl;
                warned = true;
              }
            while (interval > 0. && next_output <= time + epsilon)
              next_output += interval;
          }
        if (step % 16 == 0 || output_now)
          {
            std::ostringstream state;
            state << "step " << step << "  t = " << std::setprecision(4) << time << " s";
            progress.update(time / end, state.str());
          }
      }
    progress.finish();
    summary.steps = step;
    return summary;
  }
} // namespace clothsim
