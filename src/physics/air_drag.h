#pragma once

// Air drag and wind as a dissipative term of the step: the Newtonian flat-plate
// ("sine-squared") law on each triangle's normal relative velocity plus skin friction on
// its tangential one, quadratic in the speed (Hoerner, "Fluid-Dynamic Drag", 1965, ch. 3
// and 2; the per-triangle form of cloth codes, e.g. Wilson et al., "Simulating wind
// effects on cloth and hair", 2014).
//
// On a triangle T, with the geometry lagged at the step's damping centre y = X + u_n
// (StepTerms::previous: u_n for backward Euler, ũ for BDF2):
//   n = (y1 - y0) x (y2 - y0) / |...|,  A = |(y1 - y0) x (y2 - y0)| / 2,
//   x_c = (y0 + y1 + y2)/3,
// its velocity v_T = (v0 + v1 + v2)/3 with the step's v = w_d (u - u_n) (w_d =
// StepTerms::damping_weight, as Rayleigh damping, physics/damping.h), relative to the
// wind w(x_c, t) at StepTerms::time:
//   v_r = v_T - w,  v_n = v_r·n,  v_t = P v_r,  P = I - n⊗n.
// Dissipation potential (W) and the drag force on the triangle (N), f = -∂ψ/∂v_r:
//   ψ(v_r) = ρ_air A [C_n |v_n|³ + C_t |v_t|³] / 6,
//   f      = -½ ρ_air A [C_n |v_n| v_n n + C_t |v_t| v_t],
// a third of it on each vertex. ρ_air in kg/m³, C_n the flat plate's drag coefficient
// face-on (about 1.17 to 1.28), C_t a skin-friction coefficient of both faces together
// (dimensionless). The step's term Φ(u) = ψ(v_r(u)) / w_d has, as ∂v_r/∂u_i = w_d/3 I,
//   ∇_{u_i} Φ = ψ'(v_r)/3,  ∇²_{u_i u_j} Φ = (w_d/9) ψ''(v_r)  (every vertex pair),
//   ψ'' = ρ_air A [C_n |v_n| n⊗n + ½ C_t (|v_t| P + v_t⊗v_t / |v_t|)]  (0 at v_t = 0).
// ψ is convex in v_r and v_r affine in u (the geometry is lagged): Φ is convex, its
// Hessian positive semi-definite, the same for the projected and the exact tangent.
// It stores no energy: the stepper sums the work done against it, ∇Φ·(u_{n+1} - u_n) =
// Σ_T ψ'(v_r)·v_T dt, into statistics.csv's damping_dissipated (with Rayleigh damping
// and friction). In still air that is Σ_T (C_n |v_n|³ + C_t |v_t|³) ρ_air A dt/2 >= 0;
// a wind that drives the cloth makes it negative.
//
// The lagged geometry needs the state u_n in StepTerms::previous: the implicit
// integrators give it; the explicit ones centre their damping at u - v instead, which is
// no position (io/parameters.cc refuses Air with them). The average-vector-field step
// averages the gradient along the step's path u_n + s (u_{n+1} - u_n), where this term
// sees the velocity 2 s v̄ (v̄ the step's mean): right for the linear Rayleigh damping,
// but (ψ' homogeneous of degree 2) 4/3 of the drag in still air: refused too. The
// implicit midpoint rule solves for the midpoint but takes the wind at t_{n+1}
// (StepTerms::time): with a wind that changes in time it loses its second order in the
// wind's phase.

#include "physics/term.h"

#include <functional>

namespace clothsim::physics
{
  // The flow: density ρ_air (kg/m³), coefficients C_n and C_t (dimensionless).
  struct AirProperties
  {
    double density;
    double normal_drag;
    double tangential_drag;
  };

  // The wind velocity (m/s) at a point (m) and time (s).
  using WindField = std::function<Tensor<1, 3>(const Point<3> &, const double)>;

  // ψ and its derivatives with respect to v_r on a triangle of area A (m²) and unit
  // normal n, at relative velocity v_r (m/s): returns ψ (W); `first` (N) and `second`
  // (N s/m) may be null.
  double
  air_dissipation(const AirProperties &air,
                  const double         area,
                  const Tensor<1, 3>  &normal,
                  const Tensor<1, 3>  &relative_velocity,
                  Tensor<1, 3>        *first,
                  Tensor<2, 3>        *second);

  class AirDrag : public ElementTerm
  {
  public:
    // `wind`: empty for still air.
    AirDrag(const AirProperties &air, const WindField &wind);

    // The work done against the air shares the column of all dissipated work.
    std::string
    report_column() const override
    {
      return "damping_dissipated";
    }

    void
    add_to_step(const ElementState &element,
                const StepTerms    &step,
                double             &value,
                LocalVector        *gradient,
                LocalMatrix        *hessian) const override;

    double
    energy(const ElementState &, const std::array<double, 9> &) const override
    {
      return 0.;
    }

  private:
    const AirProperties air;
    const WindField     wind;
  };
} // namespace clothsim::physics
