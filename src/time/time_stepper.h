#pragma once

// The implicit time loop. Each step goes through named stages:
//   predict  the step's weights, centres and Newton's initial guess (predict_step)
//   solve    Newton on the step's incremental potential (physics/term.h)
//   check    a failed solve, or a result with NaN or a collapsed or hundredfold grown
//            triangle, halves the step (up to 'Maximum step halvings', and says so)
//   accept or reject   the local error estimate against the tolerance (adaptive steps)
//   commit   shift the state, strain limit, the terms' after-step hooks
//   record   statistics.csv, and the VTK frame and probes at output times; a checkpoint
//            at checkpoint times (time/time_stepper_checkpoint.cc)
// Backward Euler (Gast & Schroeder 2014's optimisation form):
//   û = u_n + dt v_n,   u_{n+1} = argmin Φ(u) with w_i = 1/dt², w_d = 1/dt,   v_{n+1} =
//   (u_{n+1} - u_n)/dt.
// BDF2 (variable step) and the implicit midpoint rule are the same minimisation with
// other weights and centres (see predict_step); the average vector field step averages
// the midpoint rule's potential along the step's path (time/step_problem.h). Adaptive
// time steps: every dynamic step gets a local error estimate (error_estimate); with
// 'Adaptive time steps' a step above the tolerance is rejected and retried with dt
// (tol/err)^(1/(p+1)) 0.9 (factor 0.2 to 2), and accepted steps propose the next dt the
// same way. Static mode: the load factor λ goes 1/N, 2/N, ..., 1 (or adaptive
// increments); each increment minimises W - λ fᵀ u, starting from the secant predictor
// along the load path.

#include "solvers/newton_solver.h"
#include "time/stepper_core.h"

#include <algorithm>
#include <cmath>

namespace clothsim
{
  class TimeStepper : public StepperCore
  {
  public:
    TimeStepper(const Parameters   &parameters,
                ModelInterface     &model,
                OutputWriter       &output,
                ConditionalOStream &pcout,
                TimerOutput        &timer);

    // Runs the whole simulation from the initial state, or from the checkpoint given to
    // restore().
    RunSummary
    run();

    // Checkpoints (io/checkpoint.h; time/time_stepper_checkpoint.cc): every `interval`
    // of simulated time (0: none) and at the end if so, and when the run is interrupted,
    // into `directory`, each with the records of `run_record` (the run's parameters).
    // After writing one the solver renews its tangent and AMG hierarchy, as a restart
    // does.
    void
    enable_checkpoints(const std::string        &directory,
                       const double              interval,
                       const io::CheckpointData &run_record);

    // Continue from a checkpoint (before run()): the state, the step controller and the
    // loop's counters. The output writer continues from the same records itself.
    void
    restore(const io::CheckpointData &run, const io::CheckpointData &rank);

  private:
    // The outcome of one attempted step.
    struct Attempt
    {
      NewtonResult newton;
      double       error_estimate = 0.; // m
      unsigned int order          = 1;  // of the estimate
    };

    // predict: the step's terms and Newton's initial guess u_new for the step of size dt
    // to time_new from state n.
    StepTerms
    predict_step(const double time_new, const double dt, const double load_factor);

    // predict, solve and check one step; leaves u_new (and v_new).
    Attempt
    attempt_step(const double time_new, const double dt, const double load_factor);

    // After a failed attempt: the step is halved (or, after 'Maximum step halvings',
    // the run stops with a SimulationError), and the log says so.
    void
    halve_step(const NewtonResult &result,
               const double        time,
               const double        time_new,
               const unsigned int  step,
               RunSummary         &summary);

    // accept or reject (adaptive steps): the error estimate against the step's
    // tolerance; proposes the next step size. A rejected step restarts the nominal step
    // from `time` with the proposed size.
    bool
    accept_step(const Attempt &attempt,
                const double   time,
                const double   time_new,
                const double   end,
                RunSummary    &summary);

    // commit: the accepted step of size dt becomes state n.
    void
    commit_step(const unsigned int step, const double dt);

    // Local error estimate (m, largest over the displacement dofs) of the step just
    // solved (u_new from u_n, v_n over dt) and the order it assumes: the difference to
    // an explicit Taylor predictor of the method's order, times the ratio of the error
    // constants (Milne's device): backward Euler ½ |u₊ - u - dt v|; with an
    // acceleration a = (v - v₋)/dt₋ from the last step, second order
    // κ |u₊ - u - dt v - dt²/2 a| with κ from the step ratio (at constant steps 1/6 for
    // the midpoint rule, error dt³/12 u⁽³⁾, and 8/7 for BDF2, error 2/9 dt³ u⁽³⁾).
    // `u` is the end state, or with `u_is_midpoint` the midpoint rule's unknown.
    // `kinetic`: in the kinetic norm instead of the largest component.
    std::pair<double, unsigned int>
    error_estimate(const double      dt,
                   const VectorType &u,
                   const bool        u_is_midpoint = false,
                   const bool        kinetic       = false) const;

    // The kinetic norm sqrt(Σ m_i x_i² / Σ m_i) over the displacement dofs (m): the root
    // mean square weighted by the lumped masses (`masses`, set before use).
    double
    kinetic_norm(const VectorType &x) const;

    // The local error a step of size dt may make (m): 'Error tolerance' + 'Relative
    // error tolerance' x the largest displacement, or with an accuracy target T_a the
    // share T_a dt / 'End time' of it.
    double
    step_tolerance(const double dt, const double largest_displacement) const;

    // The step sizes of the loop: the nominal step, the time it aims for, the next size
    // the error control proposes, and the halvings and rejections on the way.
    struct StepControl
    {
      double       nominal  = 0.; // s (load factor in static mode)
      double       target   = 0.;
      double       next     = 0.;
      unsigned int halvings = 0;
      unsigned int rejected = 0;
      // BDF2 at fixed steps: halvings carried over from the last nominal step, one fewer
      // (the step at most doubles: variable-step BDF2 is zero-stable only for step
      // ratios below 1 + √2).
      unsigned int carried = 0;

      double span = 0.; // this step's length: target - its start

      // A new nominal step of the given size from `time`, no halvings. Less than two
      // steps before `end`, the rest is split into two equal steps instead of a full one
      // and a sliver (a last step of 4e-7 s after 400 of 4.7e-3 s stalled Newton on a
      // residual floor set by the 1/dt² inertia).
      void
      restart(const double time, const double size, const double end)
      {
        nominal           = size;
        halvings          = 0;
        const double rest = end - time;
        if (rest <= size * (1. + 1e-9))
          span = rest; // the last step, to the end exactly
        else if (rest < 2. * size)
          span = rest / 2.;
        else
          span = size;
        target = (span == rest) ? end : time + span;
      }

      // The sub-step size: this step halved for its failures and the carried halvings,
      // so that sub-steps divide the step evenly (the retry uses the size reported).
      double
      size() const
      {
        return span / std::pow(2., carried + halvings);
      }
    };

    // Writes a checkpoint of the state at the top of the step loop (collective).
    void
    write_checkpoint();

    // Where the step loop is: what a checkpoint stores besides the vectors and the step
    // control, so that a restart enters the loop where the run left it.
    struct LoopState
    {
      double       time            = 0.; // s (load factor in static mode)
      unsigned int step            = 0;
      double       next_output     = 0.; // s: the next frame's time
      double       next_checkpoint = 0.; // s
      unsigned int last_iterations = 0;  // Newton's, of the last attempt
      unsigned int failed_attempts = 0;  // since the last accepted step
    };
    LoopState  loop;
    RunSummary summary;
    bool       resumed = false; // restore() was called
    // Checkpoints: the directory (empty: none), the interval, the run's own records.
    std::string        checkpoint_directory;
    double             checkpoint_interval = 0.;
    io::CheckpointData checkpoint_record;

    MatrixType   tangent;
    MatrixType   path_tangent; // the average vector field's second node (step_problem.h)
    NewtonSolver newton;
    bool         dynamic;
    StepControl  control;
    double       first_step     = 0.; // s: 'Time step' (static mode: 1/'Load steps')
    double       reference_size = 0.; // m: ModelInterface::reference_size()

    VectorType         u_n, v_n, u_new, v_new; // owned
    VectorType         masses;                 // owned: lumped, for the kinetic norm
    mutable VectorType difference;             // owned: scratch of error_estimate
    // The owned displacement dofs' local indices in the owned vectors (set on first use:
    // global indices cost a map lookup per entry).
    mutable std::vector<unsigned int> displacement_local;
    const std::vector<unsigned int>            &
    local_displacement_dofs() const;
    VectorType centre; // owned: ũ, the step's damping centre
    // BDF2: the state before u_n and the step that led from it to u_n (0: none yet).
    VectorType u_nm1, v_nm1; // owned
    double     previous_step = 0.;
    // The inertia and damping weights of the last step's tangent.
    std::pair<double, double> tangent_weights = {-1., -1.};
    // Static mode: the last load increment's displacement change and size, for the
    // secant predictor u_n + (Δλ/Δλ_last) Δu_last.
    VectorType last_increment; // owned
    double     last_load_increment = 0.;
    VectorType predictor_ghosted, centre_ghosted; // ghosted: û and ũ of the step
    VectorType check_ghosted;                     // ghosted: u_new for the check
    double     gamma = 1.; // the step's BDF2 factor γ (1: backward Euler, midpoint)
    StepTerms  last_terms; // of the last solved step
    VectorType solved;     // owned: its solved iterate (the midpoint's x)
  };
} // namespace clothsim
