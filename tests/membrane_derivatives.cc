// Membrane element: gradient and exact Hessian against central finite differences on
// random triangles and random deformations (stretched, compressed, sheared, rotated), and
// the projected tangent's positive semi-definiteness. Asserts relative errors < 1e-6.

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

int
main()
{
  std::mt19937                           generator(42);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  const double infinity       = std::numeric_limits<double>::infinity();
  unsigned int n_failures     = 0;
  double       worst_gradient = 0., worst_hessian = 0., most_negative = 0.;

  for (unsigned int trial = 0; trial < 200; ++trial)
    {
      const MembraneMaterial material{50. + 100. * std::abs(uniform(generator)),
                                      0.45 * std::abs(uniform(generator))};
      TrianglePositions      reference;
      for (auto &p : reference)
        for (unsigned int d = 0; d < 3; ++d)
          p[d] = 0.1 * uniform(generator);
      const MembraneRestData rest = membrane_rest_data(reference);
      if (rest.area < 1e-4)
        continue;

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
            << ", most negative projected eigenvalue / largest " << most_negative << '\n';
  std::cout << (n_failures == 0 ? "PASSED" : "FAILED") << std::endl;
  return n_failures == 0 ? 0 : 1;
}
