// Pressure load (physics/pressure.h): the potential -p V with V the volume of the cones
// from an apex c to the triangles.
// 1. Gradient and Hessian against central finite differences on random triangles
// (relative
//    error < 1e-7), Hessian symmetric.
// 2. On a closed surface (a regular octahedron, outward normals) the force on every
// vertex is
//    the follower load p Σ_T N_T / 6 (N_T = (x1 - x0) × (x2 - x0)) whatever the apex, the
//    forces sum to zero, and the potential is -p times the enclosed volume (√2/3 a³ for
//    edge a), all to 1e-12 relative.

#include "physics/pressure.h"

#include <cmath>
#include <iostream>
#include <random>

using namespace clothsim::physics;

int
main()
{
  std::mt19937                           generator(7);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  double worst_gradient = 0., worst_hessian = 0., worst_symmetry = 0.;

  for (unsigned int trial = 0; trial < 200; ++trial)
    {
      const double      pressure = 1e3 * uniform(generator);
      TrianglePositions x;
      Point<3>          apex;
      for (unsigned int d = 0; d < 3; ++d)
        {
          apex[d] = uniform(generator);
          for (auto &p : x)
            p[d] = uniform(generator);
        }
      ElementVector g, g_plus, g_minus;
      ElementMatrix H;
      pressure_potential_gradient_hessian(pressure, x, apex, g, &H);
      const double step    = 1e-6;
      double       g_scale = 0., H_scale = 0., g_error = 0., H_error = 0.;
      for (unsigned int i = 0; i < 9; ++i)
        {
          TrianglePositions plus = x, minus = x;
          plus[i / 3][i % 3] += step;
          minus[i / 3][i % 3] -= step;
          const double fd =
            (pressure_potential_gradient_hessian(pressure, plus, apex, g_plus, nullptr) -
             pressure_potential_gradient_hessian(
               pressure, minus, apex, g_minus, nullptr)) /
            (2. * step);
          g_scale = std::max(g_scale, std::abs(g[i]));
          g_error = std::max(g_error, std::abs(fd - g[i]));
          for (unsigned int j = 0; j < 9; ++j)
            {
              const double fd_H = (g_plus[j] - g_minus[j]) / (2. * step);
              H_scale           = std::max(H_scale, std::abs(H[j][i]));
              H_error           = std::max(H_error, std::abs(fd_H - H[j][i]));
              worst_symmetry    = std::max(worst_symmetry, std::abs(H[i][j] - H[j][i]));
            }
        }
      worst_gradient = std::max(worst_gradient, g_error / g_scale);
      worst_hessian  = std::max(worst_hessian, H_error / H_scale);
    }

  // Regular octahedron with edge a = √2 (vertices ±e_i), triangles ordered outward.
  const std::array<Point<3>, 6>            vertex = {{Point<3>(1, 0, 0),
                                                      Point<3>(-1, 0, 0),
                                                      Point<3>(0, 1, 0),
                                                      Point<3>(0, -1, 0),
                                                      Point<3>(0, 0, 1),
                                                      Point<3>(0, 0, -1)}};
  std::vector<std::array<unsigned int, 3>> triangles;
  for (const unsigned int a : {0u, 1u})
    for (const unsigned int b : {2u, 3u})
      for (const unsigned int c : {4u, 5u})
        {
          // Outward iff (x_b - x_a) × (x_c - x_a) points away from the origin.
          const Tensor<1, 3> N =
            cross_product_3d(vertex[b] - vertex[a], vertex[c] - vertex[a]);
          if (N * vertex[a] > 0.)
            triangles.push_back({{a, b, c}});
          else
            triangles.push_back({{a, c, b}});
        }
  const double pressure       = 250.;
  const double exact_volume   = std::sqrt(2.) / 3. * std::pow(std::sqrt(2.), 3);
  double       worst_follower = 0., worst_sum = 0., worst_volume = 0.;
  for (const Point<3> apex : {Point<3>(0, 0, 0), Point<3>(3, -2, 5)})
    {
      std::array<Tensor<1, 3>, 6> force, follower;
      double                      potential = 0.;
      for (const auto &t : triangles)
        {
          const TrianglePositions x = {{vertex[t[0]], vertex[t[1]], vertex[t[2]]}};
          ElementVector           g;
          potential += pressure_potential_gradient_hessian(pressure, x, apex, g, nullptr);
          const Tensor<1, 3> N = cross_product_3d(x[1] - x[0], x[2] - x[0]);
          for (unsigned int v = 0; v < 3; ++v)
            for (unsigned int d = 0; d < 3; ++d)
              {
                force[t[v]][d] -= g[3 * v + d];
                follower[t[v]][d] += pressure * N[d] / 6.;
              }
        }
      Tensor<1, 3> sum;
      for (unsigned int v = 0; v < 6; ++v)
        {
          worst_follower = std::max(worst_follower,
                                    (force[v] - follower[v]).norm() / follower[v].norm());
          sum += force[v];
        }
      worst_sum    = std::max(worst_sum, sum.norm() / (pressure * exact_volume));
      worst_volume = std::max(worst_volume,
                              std::abs(potential + pressure * exact_volume) /
                                (pressure * exact_volume));
    }

  std::cout << "1. gradient vs finite differences, worst relative error "
            << worst_gradient << " (bound 1e-7)\n   Hessian vs finite differences "
            << worst_hessian << " (bound 1e-7), asymmetry " << worst_symmetry
            << "\n2. octahedron: force vs p sum(N)/6, worst relative deviation "
            << worst_follower << "\n   |sum of forces| / (p V) " << worst_sum
            << "\n   |potential + p V| / (p V) " << worst_volume << " (bounds 1e-12)"
            << std::endl;
  const bool passed = worst_gradient < 1e-7 && worst_hessian < 1e-7 &&
                      worst_symmetry < 1e-12 && worst_follower < 1e-12 &&
                      worst_sum < 1e-12 && worst_volume < 1e-12;
  std::cout << (passed ? "PASSED" : "FAILED") << std::endl;
  return passed ? 0 : 1;
}
