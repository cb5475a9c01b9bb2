// Membrane element: gradient and exact Hessian against central finite differences on
// random triangles and random deformations (stretched, compressed, sheared, rotated), of
// isotropic and (every other trial) orthotropic materials with a random warp, and the
// projected tangent's positive semi-definiteness. Asserts relative errors < 1e-6.
// The mixed-stress tangent (linearised from a point x_p) against the exact Hessian plus
// the geometric stiffness of the stress difference, each stress read off the gradient of
// a flat triangle with the metric in question, the linearised metric taken by central
// differences (exact for the quadratic metric).

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include "physics/membrane.h"
#include "test_support.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <random>

using namespace clothsim::physics;
using namespace clothsim::test;

namespace
{
  // The metric a_ab = a_a · a_b of the edge basis a_1 = x1 - x0, a_2 = x2 - x0.
  std::array<double, 3> // a_11, a_12, a_22
  metric_of(const TrianglePositions &x)
  {
    const auto a1 = x[1] - x[0], a2 = x[2] - x[0];
    return {{a1 * a1, a1 * a2, a2 * a2}};
  }

  // The stress S^ab (contravariant, N/m) at the metric `m`: the gradient of a flat
  // triangle with that metric is x1: f_1 = |T̄| S^1b a_b, x2: f_2 = |T̄| S^2b a_b, solved
  // in the plane's basis.
  std::array<std::array<double, 2>, 2>
  stress_at_metric(const MembraneStiffness    &material,
                   const MembraneRestData     &rest,
                   const std::array<double, 3> m)
  {
    // a_1 = (p, 0), a_2 = (q, r) with p² = m11, pq = m12, q² + r² = m22.
    const double      p = std::sqrt(m[0]), q = m[1] / p, r = std::sqrt(m[2] - q * q);
    TrianglePositions flat;
    flat[1][0] = p;
    flat[2][0] = q;
    flat[2][1] = r;
    ElementVector g;
    membrane_energy_gradient_hessian(material, rest, flat, 0., g, nullptr);
    std::array<std::array<double, 2>, 2> S;
    for (unsigned int a = 0; a < 2; ++a)
      {
        // f_a = |T̄| (S^a1 (p, 0) + S^a2 (q, r))
        const double fx = g[3 + 3 * a] / rest.area, fy = g[4 + 3 * a] / rest.area;
        S[a][1] = fy / r;
        S[a][0] = (fx - S[a][1] * q) / p;
      }
    return S;
  }
} // namespace

int
main()
{
  std::mt19937                           generator(42);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  const double infinity   = std::numeric_limits<double>::infinity();
  unsigned int n_failures = 0;
  double worst_gradient = 0., worst_hessian = 0., most_negative = 0., worst_mixed = 0.;

  for (unsigned int trial = 0; trial < 200; ++trial)
    {
      MembraneMaterial  law{50. + 100. * std::abs(uniform(generator)),
                           0.45 * std::abs(uniform(generator))};
      TrianglePositions reference;
      for (auto &p : reference)
        for (unsigned int d = 0; d < 3; ++d)
          p[d] = 0.1 * uniform(generator);
      const MembraneRestData rest = membrane_rest_data(reference);
      if (rest.area < 1e-4)
        continue;
      if (trial % 2 == 1)
        {
          // Orthotropic: a weft 1 to 20 times softer, a soft bias, a random warp
          // (ν_12² k_2 < k_1 holds for ν_12 < 0.45).
          law.weft_stretch_stiffness =
            law.stretch_stiffness / (1. + 19. * std::abs(uniform(generator)));
          law.shear_stiffness =
            0.01 * law.stretch_stiffness +
            0.3 * law.stretch_stiffness * std::abs(uniform(generator));
          for (unsigned int d = 0; d < 3; ++d)
            law.warp_direction[d] = uniform(generator);
        }
      const MembraneStiffness material = membrane_stiffness(law, reference, rest);

      // Random deformation gradient-like map: scale in (0.5, 1.5) (compression included),
      // plus a perturbation of each vertex.
      const double      scale = 1. + 0.5 * uniform(generator);
      TrianglePositions current;
      for (unsigned int v = 0; v < 3; ++v)
        for (unsigned int d = 0; d < 3; ++d)
          current[v][d] = scale * reference[v][d] + 0.02 * uniform(generator);

      ElementVector gradient;
      ElementMatrix hessian;
      membrane_energy_gradient_hessian(
        material, rest, current, infinity, gradient, &hessian);

      // Central differences, step h relative to the element size.
      const double  h = 1e-6 * std::sqrt(rest.area);
      ElementVector fd_gradient;
      ElementMatrix fd_hessian;
      for (unsigned int i = 0; i < 9; ++i)
        {
          TrianglePositions plus = current, minus = current;
          plus[i / 3][i % 3] += h;
          minus[i / 3][i % 3] -= h;
          fd_gradient[i] = (membrane_energy(material, rest, plus) -
                            membrane_energy(material, rest, minus)) /
                           (2. * h);
          ElementVector g_plus, g_minus;
          membrane_energy_gradient_hessian(
            material, rest, plus, infinity, g_plus, nullptr);
          membrane_energy_gradient_hessian(
            material, rest, minus, infinity, g_minus, nullptr);
          for (unsigned int j = 0; j < 9; ++j)
            fd_hessian[j][i] = (g_plus[j] - g_minus[j]) / (2. * h);
        }

      ElementVector difference;
      for (unsigned int i = 0; i < 9; ++i)
        difference[i] = gradient[i] - fd_gradient[i];
      const double gradient_error = l2_norm(difference) / l2_norm(gradient);
      double       hessian_norm = 0., hessian_difference = 0.;
      for (unsigned int i = 0; i < 9; ++i)
        for (unsigned int j = 0; j < 9; ++j)
          {
            hessian_norm += hessian[i][j] * hessian[i][j];
            hessian_difference += std::pow(hessian[i][j] - fd_hessian[i][j], 2);
          }
      const double hessian_error = std::sqrt(hessian_difference / hessian_norm);
      worst_gradient             = std::max(worst_gradient, gradient_error);
      worst_hessian              = std::max(worst_hessian, hessian_error);
      if (gradient_error > 1e-6 || hessian_error > 1e-6)
        {
          ++n_failures;
          std::cout << "trial " << trial << " (scale " << scale << "): gradient error "
                    << gradient_error << ", Hessian error " << hessian_error << '\n';
        }

      // Mixed-stress tangent from x_p = x - d: K(x) + G(S_lin - S(x)), G(S) the blocks
      // |T̄| Σ_ac w_va w_uc S^ac I (w_0 = (-1, -1), w_1 = (1, 0), w_2 = (0, 1)), S_lin the
      // stress of the metric linearised at x_p: m(x_p) + (m(x_p + t d) - m(x_p - t d)) /
      // 2t.
      {
        TrianglePositions from = current, plus = current, minus = current;
        const double      t = 1e-3;
        for (unsigned int v = 0; v < 3; ++v)
          for (unsigned int d = 0; d < 3; ++d)
            {
              const double step = 0.01 * uniform(generator);
              from[v][d] -= step;
              plus[v][d]  = from[v][d] + t * step;
              minus[v][d] = from[v][d] - t * step;
            }
        ElementMatrix mixed;
        membrane_energy_gradient_hessian(
          material, rest, current, infinity, gradient, &mixed, &from);
        const auto m_p = metric_of(from), m_plus = metric_of(plus),
                   m_minus = metric_of(minus);
        std::array<double, 3> m_lin;
        for (unsigned int k = 0; k < 3; ++k)
          m_lin[k] = m_p[k] + (m_plus[k] - m_minus[k]) / (2. * t);
        const auto S_lin = stress_at_metric(material, rest, m_lin);
        const auto S_x   = stress_at_metric(material, rest, metric_of(current));
        static constexpr double w[3][2]    = {{-1., -1.}, {1., 0.}, {0., 1.}};
        double                  difference = 0.;
        for (unsigned int i = 0; i < 9; ++i)
          for (unsigned int j = 0; j < 9; ++j)
            {
              double expected = hessian[i][j];
              if (i % 3 == j % 3)
                for (unsigned int a = 0; a < 2; ++a)
                  for (unsigned int c = 0; c < 2; ++c)
                    expected +=
                      rest.area * w[i / 3][a] * w[j / 3][c] * (S_lin[a][c] - S_x[a][c]);
              difference += std::pow(mixed[i][j] - expected, 2);
            }
        const double mixed_error = std::sqrt(difference / hessian_norm);
        worst_mixed              = std::max(worst_mixed, mixed_error);
        if (mixed_error > 1e-6)
          {
            ++n_failures;
            std::cout << "trial " << trial << ": mixed-stress tangent error "
                      << mixed_error << '\n';
          }
      }

      // Projected tangent (floor 0): positive semi-definite.
      ElementMatrix projected;
      membrane_energy_gradient_hessian(material, rest, current, 0., gradient, &projected);
      const auto [smallest, largest] = extreme_eigenvalues(projected);
      most_negative                  = std::min(most_negative, smallest / largest);
      if (smallest < -1e-10 * largest)
        {
          ++n_failures;
          std::cout << "trial " << trial << ": projected tangent has eigenvalue "
                    << smallest << " (largest " << largest << ")\n";
        }
    }

  std::cout << "worst relative gradient error " << worst_gradient
            << ", worst relative Hessian error " << worst_hessian
            << ", most negative projected eigenvalue / largest " << most_negative
            << ", worst relative mixed-stress tangent error " << worst_mixed << '\n';
  std::cout << (n_failures == 0 ? "PASSED" : "FAILED") << std::endl;
  return n_failures == 0 ? 0 : 1;
}
