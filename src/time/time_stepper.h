#pragma once

// The time loop: predict, solve the step's incremental potential with Newton, accept or
// cut the step, write output. Backward Euler (Gast & Schroeder 2014's optimisation form):
//   û = u_n + dt v_n,   u_{n+1} = argmin Φ(u) with w_i = 1/dt², w_d = 1/dt,   v_{n+1} =
//   (u_{n+1} - u_n)/dt.
// BDF2 (variable step) and the implicit midpoint rule are the same minimisation with
// other weights and centres (see solve_step). Adaptive time steps: every dynamic step
// gets a local error estimate (error_estimate); with 'Adaptive time steps' a step above
// the tolerance is rejected and retried with dt (tol/err)^(1/(p+1)) 0.9 (factor 0.2 to
// 2), and accepted steps propose the next dt the same way. Static mode: the load factor λ
// goes 1/N, 2/N, ..., 1 (or adaptive increments); each increment minimises W - λ fᵀ u,
// starting from the secant predictor along the load path. A step whose Newton solve fails
// (or whose result holds NaN or a collapsed triangle) is retried with half the step, up
// to 'Maximum step halvings' times, and the log says so.

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include "io/output_writer.h"
#include "scene/cloth_model.h"
#include "solvers/newton_solver.h"

#include <stdexcept>

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

  class TimeStepper
  {
  public:
    TimeStepper(const Parameters   &parameters,
                ClothModel         &model,
                OutputWriter       &output,
                ConditionalOStream &pcout,
                TimerOutput        &timer);

    // Runs the whole simulation from the reference state at rest.
    RunSummary
    run();

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

  private:
    // Local error estimate (m, largest over the displacement dofs) of the step just
    // solved (u_new from u_n, v_n over dt) and the order it assumes: the difference to
    // an explicit Taylor predictor of the method's order, times the ratio of the error
    // constants (Milne's device): backward Euler ½ |u₊ - u - dt v|; with an
    // acceleration a = (v - v₋)/dt₋ from the last step, second order
    // κ |u₊ - u - dt v - dt²/2 a| with κ from the step ratio (at constant steps 1/6 for
    // the midpoint rule, error dt³/12 u⁽³⁾, and 8/7 for BDF2, error 2/9 dt³ u⁽³⁾).
    std::pair<double, unsigned int>
    error_estimate(const double dt) const;

    // The local error a step of size dt may make (m): 'Error tolerance' + 'Relative
    // error tolerance' x the largest displacement, or with an accuracy target T_a the
    // share T_a dt / 'End time' of it.
    double
    step_tolerance(const double dt, const double largest_displacement) const;

    // Solves one step of size dt from state n; returns the Newton result, leaves u_new.
    NewtonResult
    solve_step(const double time_new, const double dt, const double load_factor);

    const Parameters   &parameters;
    ClothModel         &model;
    OutputWriter       &output;
    ConditionalOStream &pcout;
    TimerOutput        &timer;

    MatrixType   tangent;
    NewtonSolver newton;

    VectorType u_n, v_n, u_new, v_new; // owned
    VectorType centre;                 // owned: ũ, the step's damping centre
    // BDF2: the state before u_n and the step that led from it to u_n (0: none yet).
    VectorType u_nm1, v_nm1; // owned
    double     previous_step = 0.;
    // The inertia and damping weights of the last step's tangent.
    std::pair<double, double> tangent_weights = {-1., -1.};
    IndexSet displacement_dofs; // owned displacement dofs (no director angles)
    // Static mode: the last load increment's displacement change and size, for the
    // secant predictor u_n + (Δλ/Δλ_last) Δu_last.
    VectorType last_increment; // owned
    double     last_load_increment = 0.;
    VectorType u_ghosted, v_ghosted, u_n_ghosted, predictor_ghosted; // ghosted
    VectorType centre_ghosted; // ghosted: the damping term's centre (ũ)
  };
} // namespace clothsim
