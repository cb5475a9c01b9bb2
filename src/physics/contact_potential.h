#pragma once

// The scalar potentials of contact, as functions of one distance or slip.
//
// Barrier (Li et al., "Incremental Potential Contact", ACM TOG 39(4), 2020, eq. 6), in
// m²:
//   s(d) = -(d - d̂)² ln(d/d̂)   for 0 < d < d̂,   0 for d >= d̂,   +inf for d <= 0;
// C² at d̂, convex and decreasing on (0, d̂). A vertex of mass m pays κ s(d) with
// κ = m a_b / d̂ (a_b: 'Barrier stiffness', m/s²), so the barrier pushes with 1.19 m a_b
// at d = d̂/2 and a vertex resting under gravity g sits where |s'(d)|/d̂ = g/a_b.
//
// Friction (IPC, eq. 14-16): a lagged normal force λ and a slip y = |u_T| (m, the
// tangential displacement over the step relative to the obstacle) give the dissipative
// potential μ λ f0(y), with f0 smooth from static to kinetic over a slip ε = ε_v dt:
//   f0(y) = -y³/(3ε²) + y²/ε + ε/3 (y < ε), y (y >= ε);   f1 = f0' = 2y/ε - y²/ε² or 1.
// Force μ λ f1(y) û (Coulomb once sliding); its Hessian in the slip plane
// μ λ (f1'(y) ûûᵀ + f1(y)/y (I - ûûᵀ)) is positive semi-definite.

#include <cmath>
#include <limits>

namespace clothsim::physics::contact
{
  inline double
  barrier(const double d, const double d_hat)
  {
    if (d <= 0.)
      return std::numeric_limits<double>::infinity();
    if (d >= d_hat)
      return 0.;
    return -(d - d_hat) * (d - d_hat) * std::log(d / d_hat);
  }

  inline double
  barrier_first(const double d, const double d_hat)
  {
    if (d >= d_hat)
      return 0.;
    return -2. * (d - d_hat) * std::log(d / d_hat) - (d - d_hat) * (d - d_hat) / d;
  }

  inline double
  barrier_second(const double d, const double d_hat)
  {
    if (d >= d_hat)
      return 0.;
    const double r = (d - d_hat) / d;
    return -2. * std::log(d / d_hat) - 4. * r + r * r;
  }

  inline double
  friction_f0(const double y, const double epsilon)
  {
    if (y >= epsilon)
      return y;
    return -y * y * y / (3. * epsilon * epsilon) + y * y / epsilon + epsilon / 3.;
  }

  // f1(y)/y, finite at y = 0.
  inline double
  friction_f1_over_y(const double y, const double epsilon)
  {
    if (y >= epsilon)
      return 1. / y;
    return 2. / epsilon - y / (epsilon * epsilon);
  }

  inline double
  friction_f1_prime(const double y, const double epsilon)
  {
    if (y >= epsilon)
      return 0.;
    return 2. / epsilon - 2. * y / (epsilon * epsilon);
  }
} // namespace clothsim::physics::contact
