#pragma once

// Explicit time integration with the lumped mass M (no Newton solve; one force
// evaluation per step), f(u, v) = -∇W(u) + f_g + f_ext - (α M + β K(u)) v:
//   symplectic Euler  v_{n+1} = v_n + dt M⁻¹ f(u_n, v_n),  u_{n+1} = u_n + dt v_{n+1}
//                     (first order; symplectic: no energy drift without damping)
//   velocity Verlet   v_{n+½} = v_n + dt/2 M⁻¹ f_n,  u_{n+1} = u_n + dt v_{n+½},
//                     v_{n+1} = v_{n+½} + dt/2 M⁻¹ f(u_{n+1}, v_{n+½})
//                     (second order, symplectic; the damping force uses v_{n+½})
// Both are stable for dt below the critical step of the stiffest mode ω_max (λ_max of
// M⁻¹K) with damping ratio ζ = α/(2ω) + βω/2 there:
//   dt_crit = (2/ω_max) (√(1 + ζ²) - ζ)
// (the stability boundary of the mode equation ẍ + 2ζωẋ + ω²x = 0 under symplectic
// Euler). ω_max comes from power iteration on M⁻¹K at the rest state (a lower bound
// of λ_max, so dt_crit is slightly optimistic), with Gershgorin's bound
// λ_max ≤ max_i Σ_j |K_ij| / m_i as the safe side. The linear bound does not cover large
// nonlinear motions (on the hanging sheet without β, 0.98 dt_crit diverged after 0.94 s),
// so the run warns when 'Time step' exceeds 0.9 of the estimate; it re-estimates at every
// output time (a deformed sheet can be stiffer; 0.7 % on the hanging sheet) and warns
// when the step comes within that margin, and stops with a SimulationError when the state
// blows up (a non-finite energy, a triangle grown a hundredfold or collapsed), keeping
// the output so far. Steps are shortened to land on output times.

#include "time/stepper_core.h"

namespace clothsim
{
  struct CriticalStep
  {
    double omega_max;        // 1/s, power-iteration estimate of √λ_max(M⁻¹K)
    double damping_ratio;    // ζ at ω_max
    double estimate;         // s, dt_crit from omega_max
    double gershgorin_bound; // s, dt_crit from Gershgorin's λ bound (≤ estimate)
  };

  // The critical step of the explicit integrators at a displacement u (ghosted), from
  // the projected tangent and the lumped masses (pinned dofs excluded). Keeps its matrix
  // and the power iteration's vector, so that later estimates (at output times) start
  // warm and cost a few matrix-vector products.
  class CriticalStepEstimator
  {
  public:
    CriticalStepEstimator(const ModelInterface &model, const Parameters &parameters);

    CriticalStep
    estimate(const VectorType &u);

  private:
    const ModelInterface &model;
    const Parameters     &parameters;
    MatrixType            stiffness;
    VectorType            inverse_mass, free_masses; // owned; 0 on pinned dofs
    VectorType            mode, Kz, Mz;              // owned
    bool                  warm = false;
  };

  // One estimate from the start vector.
  CriticalStep
  estimate_critical_step(const ModelInterface &model,
                         const Parameters     &parameters,
                         const VectorType     &u);

  class ExplicitStepper : public StepperCore
  {
  public:
    ExplicitStepper(const Parameters   &parameters,
                    ModelInterface     &model,
                    OutputWriter       &output,
                    ConditionalOStream &pcout,
                    TimerOutput        &timer);

    // Runs the whole simulation from the initial state.
    RunSummary
    run();

    // The critical step estimated at the start of run().
    const CriticalStep &
    critical_step() const
    {
      return critical;
    }

  private:
    // a = M⁻¹ f(u, v) on the free dofs, zero on pinned ones. u, v owned. If
    // `damping_force` is non-null, it gets the damping force D(u) v of the same
    // evaluation (rank-local, physics/term.h) for the energy budget.
    void
    acceleration(const VectorType    &u,
                 const VectorType    &v,
                 VectorType          &a,
                 physics::RankVector *damping_force = nullptr);

    // The damping force of the state (u, v) (owned) as a step's damping term: weight 1,
    // centre u - v. Sets `centre` and `centre_ghosted`.
    StepTerms
    damping_terms(const VectorType &u, const VectorType &v);

    // The work of the prescribed motion over the step from (u_old, v_old) at t_n to u
    // at t_new (owned): the pins' forces as backward Euler's equations need them at u
    // (inertia m (u - u_old - h v_old)/h², damping centred at u_old).
    void
    add_step_prescribed_work(const VectorType &u,
                             const VectorType &u_old,
                             const VectorType &v_old,
                             const double      t_n,
                             const double      t_new);

    VectorType inverse_mass;   // owned, 0 on pinned dofs
    VectorType gradient;       // owned
    VectorType centre;         // owned: u - v, the damping term's centre
    VectorType centre_ghosted, // ghosted
      work_ghosted;
    // The damping force at the current step's start, D(u_n) v_n (rank-local).
    physics::RankVector damping_force;
    CriticalStep        critical{};
  };
} // namespace clothsim
