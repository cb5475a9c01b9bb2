#pragma once

// What the implicit and explicit steppers share: their set-up, the first frame, the
// blow-up check, Provot's strain-limit stage and the record of an accepted step
// (statistics.csv with the energy budget, the VTK frame and probes).

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include "io/checkpoint.h"
#include "io/output_writer.h"
#include "io/parameters.h"
#include "time/interruption.h"
#include "time/model_interface.h"

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

namespace clothsim
{
  // The run cannot go on (Newton failed at the smallest step, NaN, collapsed triangles).
  // Everything written before it stays.
  class SimulationError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // Wall time spent in assembly ("assemble ..." sections) and in linear solves ("linear
  // solve", "preconditioner setup") since the last call, from `timer`'s totals.
  class StepTimes
  {
  public:
    explicit StepTimes(const TimerOutput &timer)
      : timer(timer)
    {}

    // {assembly, linear solve} seconds since the last call.
    std::pair<double, double>
    since_last();

  private:
    const TimerOutput &timer;
    double             assembly = 0., linear_solve = 0.;
  };

  // Totals of a finished run.
  struct RunSummary
  {
    unsigned int steps             = 0;
    unsigned int newton_iterations = 0;
    unsigned int linear_iterations = 0;
    unsigned int retries           = 0;
    unsigned int rejected          = 0; // steps rejected by the error control
    unsigned int tangents          = 0; // tangents assembled
    double estimated_error = 0.; // m: the accepted steps' local error estimates, summed
  };

  // The solver's figures of one accepted step, for its statistics row.
  struct StepFigures
  {
    unsigned int newton_iterations = 0;
    unsigned int linear_iterations = 0;
    double       residual          = 0.; // N
    unsigned int retries           = 0;
    unsigned int rejected          = 0;
    double       error_estimate    = 0.; // m
  };

  class StepperCore
  {
  public:
    // The displacement and velocity at the end (ghosted).
    const VectorType &
    displacement() const
    {
      return u_ghosted;
    }
    const VectorType &
    velocity() const
    {
      return v_ghosted;
    }

  protected:
    StepperCore(const Parameters   &parameters,
                ModelInterface     &model,
                OutputWriter       &output,
                ConditionalOStream &pcout,
                TimerOutput        &timer);

    // Frame 0 and the statistics' first row for the state (u, v) (owned).
    void
    write_first_frame(const VectorType &u, const VectorType &v);

    // Why the state u (ghosted) is no cloth any more: a NaN, a collapsed or a
    // hundredfold grown triangle; empty if it is one.
    std::string
    blow_up(const VectorType &u) const;

    // Provot's strain limit after a dynamic step of size dt (u, v owned), if the model
    // has one; says so when springs stay beyond it. Adds the energy its corrections
    // change (K + W + P after less before) to `strain_limited`.
    void
    limit_strain(const unsigned int step, VectorType &u, VectorType &v, const double dt);

    // Adds the work done against the dissipative terms over a step: their gradient at
    // the solved iterate `solved` (ghosted) of the step `terms`, dotted with the step's
    // displacement u_new - u_old (owned vectors).
    void
    add_dissipation(const VectorType &solved,
                    const StepTerms  &terms,
                    const VectorType &u_new,
                    const VectorType &u_old);

    // The same with the dissipative terms' gradient given (rank-local, physics/term.h;
    // the explicit steps' damping force at the step's start, from their force
    // evaluation).
    void
    add_dissipation(const physics::RankVector &dissipative_gradient,
                    const VectorType          &u_new,
                    const VectorType          &u_old);

    // Adds the work the scene's prescribed motion did on the cloth over a step from u_old
    // at t_n to u_new at t_new (owned vectors), if the scene prescribes motion: at the
    // constrained dofs that moved, the step's force there (ModelInterface::step_forces of
    // the step `terms` at `solved`, owned) times their change; with `trapezoid`, the
    // mean of that force and the one of the step before (the steps that solve for their
    // end state: the work's trapezoidal rule, second order); plus the moving obstacles'
    // work (ModelInterface::obstacle_work).
    void
    add_prescribed_work(const VectorType &solved,
                        const StepTerms  &terms,
                        const VectorType &u_new,
                        const VectorType &u_old,
                        const double      t_n,
                        const double      t_new,
                        const bool        trapezoid);

    // The same for a static step from load factor λ_old to λ_new: the trapezoidal rule
    // over the reactions of its two equilibria (exact where they are linear in the
    // prescribed values).
    void
    add_static_prescribed_work(const VectorType &u_new,
                               const VectorType &u_old,
                               const double      lambda_old,
                               const double      lambda_new);

    // The energies at (u_ghosted, v_ghosted), with the dissipation and prescribed work
    // so far.
    EnergyReport
    current_energies() const
    {
      return reported(model.energies(u_ghosted, v_ghosted, dissipated));
    }
    // The same and the state's damping force (ModelInterface::energies).
    EnergyReport
    current_energies(physics::RankVector &damping_force) const
    {
      return reported(model.energies(u_ghosted, v_ghosted, dissipated, damping_force));
    }
    // A linear static solution's elastic energy ½ uᵀK0u = ½ f·u (Clapeyron's theorem,
    // with zero prescribed displacements) and the loads' potential -f·u, J, in place of
    // the nonlinear model's (the terms' own columns stay the model's).
    std::optional<std::pair<double, double>> linear_energies;
    // The model's report with the linear energies, the prescribed work, the strain
    // limit's and the stiffness raises' energies (its last columns) set.
    EnergyReport
    reported(EnergyReport report) const
    {
      if (linear_energies)
        std::tie(report.elastic, report.potential) = *linear_energies;
      std::size_t column = report.columns.size();
      if (model.adapts_stiffness())
        report.columns[--column] = stiffness_raised;
      if (model.has_strain_limit())
        report.columns[--column] = strain_limited;
      if (model.has_prescribed_motion())
        report.columns[--column] = prescribed;
      return report;
    }

    // The statistics row of an accepted step with the energies of its state.
    void
    record(const unsigned int  step,
           const double        time,
           const double        dt,
           const StepFigures  &figures,
           const EnergyReport &energies,
           StepTimes          &step_times);

    // The VTK frame and probes at (u_ghosted, v_ghosted).
    void
    write_frame(const unsigned int step, const double time);

    // After every step attempt: if SIGINT or SIGTERM arrived on any rank, calls
    // `checkpoint` (if given: the state to continue from), writes the frame of the last
    // accepted state (step, time; u_ghosted, v_ghosted) unless it is written, and throws
    // Interrupted. Collective.
    void
    stop_if_interrupted(const unsigned int           step,
                        const double                 time,
                        const std::function<void()> &checkpoint = {});

    // The shared part of a checkpoint (io/checkpoint.h): the dissipated work, the frame
    // bookkeeping, the wall time so far; and its restoration (a restart: the state
    // then continues from u_ghosted, v_ghosted as set by the stepper, and the wall time
    // of statistics.csv from the checkpoint's).
    void
    save_core(io::CheckpointData &run) const;
    void
    restore_core(const io::CheckpointData &run);

    // Stops the run (SimulationError) when the step size `dt` that the run would take
    // next falls below the floor 'Minimum time step fraction' x the nominal step
    // `nominal`: the run could not make progress. `why`: what asks for such a step.
    void
    check_step_floor(const double       dt,
                     const double       nominal,
                     const double       time,
                     const std::string &why) const;

    const Parameters   &parameters;
    ModelInterface     &model;
    OutputWriter       &output;
    ConditionalOStream &pcout;
    TimerOutput        &timer;
    Timer               wall_clock;
    double              wall_offset = 0.; // s: the wall time before a restart

    VectorType u_ghosted, v_ghosted; // the current state
    double     dissipated     = 0.;  // J, work done against damping so far
    double     prescribed     = 0.;  // J, work done on the cloth by prescribed motion
    double     strain_limited = 0.;  // J, energy added by the strain limit's corrections
    double stiffness_raised   = 0.;  // J, ... by raises of the adaptive barrier stiffness
    // Owned: the step forces of the last step added with `trapezoid` (empty before
    // it), for the next one's trapezoidal rule (add_prescribed_work); checkpointed by
    // the steppers.
    VectorType previous_forces;

  private:
    // increment = u_new - u_old, ghosted (the work vectors made on first use).
    void
    set_increment(const VectorType &u_new, const VectorType &u_old);

    VectorType   increment, solved_ghosted;  // ghosted work vectors of add_dissipation
    VectorType   start_ghosted, end_ghosted; // ... and of add_prescribed_work
    VectorType   step_forces;                // owned: its forces of the step
    unsigned int frame_step = 0;             // the step of the last written frame
    bool         any_frame  = false;
  };
} // namespace clothsim
