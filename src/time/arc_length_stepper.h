#pragma once

// Static equilibrium paths by arc-length continuation ('Time/Integrator = arc length').
// The equilibria of R(u, λ) = ∇W(u) - λ f(u) = 0 (W the stored energy, f the loads at
// full value: linear in λ, and f depends on u for follower pressure) form a curve in (u,
// λ) that load control cannot follow past a limit point, where dλ/ds = 0. Each step of
// length Δs goes from the last equilibrium (u_n, λ_n):
//   predictor  along the path's tangent: K b = f, (Δu, Δλ) = ±Δs (b, 1) / √(|b|² + ψ²),
//              the sign keeping the last step's direction (a positive scaled dot product
//              with the last increment; Crisfield 1991, §9.5);
//   corrector  Newton on R = 0 with its corrections in the hyperplane normal to the
//              predictor (Riks 1979; Crisfield 1991, §9.3): K a = -R, K b = f,
//                δλ = -(g + t·a) / (t·b + ψ² t_λ),   δu = a + δλ b,
//              g = t·(u - u_n) + ψ² t_λ (λ - λ_n) - Δs² the constraint's residual,
//              (t, t_λ) the predictor's increment.
// |·| and the dot products take the displacement dofs only (m; director angles are no
// lengths); ψ = |K₀⁻¹ f| at the start (m per unit λ) weighs load and displacement
// equally. Crisfield, "Non-linear finite element analysis of solids and structures",
// vol. 1, Wiley 1991, ch. 9.
// The first step has Δλ = 1/'Load steps'. With 'Adaptive load steps' Δs then grows or
// shrinks by √(5 / corrector iterations) (factor 0.5 to 2, at most 4 Δs₀); a failed
// corrector halves it ('Maximum step halvings' in a row). The path ends where it crosses
// λ = 1: that step is solved again at λ = 1 exactly (the corrector with λ held, from the
// point interpolated on the step). The tangent is the exact Hessian, indefinite past a
// limit point; with MUMPS its number of negative pivots at each equilibrium (the
// unstable modes, by Sylvester's law of inertia) is reported when it changes.

#include "time/stepper_core.h"

namespace clothsim
{
  class ArcLengthStepper : public StepperCore
  {
  public:
    ArcLengthStepper(const Parameters   &parameters,
                     ModelInterface     &model,
                     OutputWriter       &output,
                     ConditionalOStream &pcout,
                     TimerOutput        &timer);

    // Follows the path from the reference state at λ = 0 to λ = 1.
    RunSummary
    run();

  private:
    // The linear constraint of a corrector, g(u, λ) = t·(u - u_n) + c_λ (λ - λ_n) - c₀:
    // the arc's hyperplane (t the predictor's increment, c_λ = ψ² t_λ, c₀ = Δs²), or λ
    // held (t = 0, c_λ = 1, c₀ = λ_target - λ_n).
    struct Constraint
    {
      const VectorType *direction = nullptr; // t (owned), or null: none
      double            load      = 1.;      // c_λ
      double            target    = 0.;      // c₀
    };

    struct Correction
    {
      bool         converged         = false;
      unsigned int iterations        = 0;
      unsigned int linear_iterations = 0;
      double       residual          = 0.; // N, root mean square as Newton's
      std::string  failure;
    };

    // Newton from (u, λ) on R = 0 and g = 0 (u owned; both updated).
    Correction
    correct(VectorType &u, double &lambda, const Constraint &constraint);

    // R(u, λ) and f(u) into `residual` and `load` (u owned).
    void
    evaluate_forces(const VectorType &u, const double lambda);

    // K(u, λ) into `tangent`, factorised or preconditioned (u owned).
    void
    evaluate_tangent(const VectorType &u, const double lambda);

    // The static step's terms at load factor λ, with the exact Hessian.
    static StepTerms
    static_terms(const double lambda);

    // The dot product over the displacement dofs (owned vectors), summed over ranks.
    double
    displacement_dot(const VectorType &a, const VectorType &b) const;

    // The predictor of the step of length Δs from (u_n, λ_n): its increment
    // (predictor_increment, predictor_load). Returns false if K b = f failed.
    bool
    predict(const double arc, unsigned int &linear_iterations);

    MatrixType   tangent;
    LinearSolver linear_solver;
    VectorType   u_n, u_new;           // owned
    VectorType   residual, load, a, b; // owned: R, f and the two solutions
    VectorType   ghosted;              // the point of evaluation
    VectorType   last_increment;       // owned: the last step's u_new - u_n
    VectorType   predictor_increment;  // owned: t
    double       lambda_n = 0., last_load_increment = 0., predictor_load = 0.;
    double       psi_squared    = 0.; // ψ², m²
    int          unstable_modes = 0;  // negative pivots at the last equilibrium
  };
} // namespace clothsim
