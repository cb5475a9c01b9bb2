#pragma once

// The barrier of one contact pair (physics/pair_distance.h) with its derivatives in the
// coordinates of the pair's moving points: κ m(x) s(d), with s IPC's log barrier
// (physics/contact_potential.h) of the pair's distance d, and for edge-edge pairs IPC's
// mollifier (Li et al. 2020, eq. 22) of x = |ea × eb|²,
//   m(x) = -x²/ε_x² + 2 x/ε_x  (x < ε_x),  1 otherwise,
// which takes the barrier smoothly to zero as the edges turn parallel, where the pair's
// distance type switches (ε_x = 1e-3 |ea|²|eb|² at rest). Derivatives by forward-mode
// automatic differentiation (Sacado) of the distance's form. A tangent's Hessian is
// positive semi-definite either way below (PairHessian):
// - Gauss-Newton's κ s''(d) ∇d ∇dᵀ, s'' > 0: the part κ s'(d) ∇²d dropped, as for the
//   analytic obstacles. While the mollifier acts it is the exact Hessian with its
//   negative eigenvalues set to zero, or (`gauss_newton_mollified`, for self-contact,
//   where stacked layers make thousands of such pairs and the projection would dominate
//   the assembly) κ m(x) s''(d) ∇d ∇dᵀ, the mollifier's derivatives dropped too.
// - the exact Hessian with its negative eigenvalues set to zero. It keeps what
//   Gauss-Newton drops where that is positive: where the distance's form is a point
//   against a plane or line (or a line against a line), D = n̂·v, turning the plane or
//   line by θ about its closest point brings it D (1 - cos θ) closer, so ∇²D holds
//   -D |δn̂|² and κ s'(d) ∇²D (s' < 0) resists the turn with κ |s'| D. With the distance
//   less an offset r (an obstacle's core inflated by r) D = d + r is large, and a tangent
//   without it lets a cloth triangle turn into a sphere at no cost in the model.

#include "physics/pair_distance.h"

#include <array>

namespace clothsim::physics
{
  struct PairBarrier
  {
    double                 value    = 0.;
    double                 distance = 0.; // d, m (less the offset)
    unsigned int           n = 0; // derivative entries: 3 per moving point, in order
    std::array<double, 12> gradient{};
    // n x n, row-major; only those entries are set (a pair beyond d̂ has n = 0 and costs
    // no zeroing of the whole array).
    std::array<double, 144> hessian;
  };

  // How the Hessian (order 2) is formed.
  enum class PairHessian
  {
    exact,
    projected,   // the exact one with its negative eigenvalues set to zero
    gauss_newton // κ s''(d) ∇d ∇dᵀ (mollified pairs: above)
  };

  // κ (N/m), d̂ (m), `mollifier_threshold` ε_x (m⁴; 0: no mollifier). `moving`: which
  // of the four points are unknowns. `order`: 0 the value, 1 also the gradient, 2 also
  // the Hessian, formed as `form` says. Zero beyond d̂, infinite at d = 0. With an
  // `offset` r (m), d is the pair's distance less r: the pair of an obstacle's core
  // inflated by r.
  PairBarrier
  pair_barrier(const PairKind             kind,
               const PairPoints          &x,
               const std::array<bool, 4> &moving,
               const double               kappa,
               const double               d_hat,
               const double               mollifier_threshold,
               const unsigned int         order,
               const PairHessian          form,
               const bool                 gauss_newton_mollified = false,
               const double               offset                 = 0.);

  // m(x) for x = |ea × eb|² (m⁴) and its threshold ε_x.
  inline double
  mollifier(const double x, const double threshold)
  {
    return x < threshold ? (2. - x / threshold) * x / threshold : 1.;
  }

  // The mollifier's threshold for edges of rest lengths la, lb (m).
  inline double
  mollifier_threshold(const double la, const double lb)
  {
    return 1e-3 * la * la * lb * lb;
  }

  // Sets the negative eigenvalues of the symmetric n x n matrix A (row-major) to zero
  // (cyclic Jacobi rotations).
  void
  project_to_positive_semidefinite(double *A, const unsigned int n);
} // namespace clothsim::physics
