// Mass-spring kernel: gradient and exact Hessian against central finite differences on
// random stretched and compressed springs, the projected Hessian's positive
// semi-definiteness, rigid-motion invariance, zero force at rest; Provot's strain limit
// (strain exactly τ, compliant springs untouched, pinned ends fixed, mass-weighted centre
// conserved); and the derived constants: an equilateral lattice with the structural
// springs reproduces the continuum membrane energy at ν = 1/3 and its uniaxial-strain
// stiffness E h / (1 - ν²) at any ν, the hinge coefficient reproduces the plate under
// cylindrical bending (spherical and saddle: the predicted ratios), and the bend spring
// matches the hinge at its reference angle.

#include <deal.II/lac/lapack_full_matrix.h>

#include "physics/mass_spring.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <vector>

using namespace clothsim::physics;
using namespace clothsim::test;

namespace
{
  Tensor<1, 3>
  random_unit(std::mt19937 &generator)
  {
    std::normal_distribution<double> normal;
    Tensor<1, 3>                     u;
    for (unsigned int d = 0; d < 3; ++d)
      u[d] = normal(generator);
    return u / u.norm();
  }

  // Rotation by angle about a unit axis (Rodrigues).
  Tensor<2, 3>
  rotation(const Tensor<1, 3> &axis, const double angle)
  {
    Tensor<2, 3> R;
    const double c = std::cos(angle), s = std::sin(angle);
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        R[i][j] = (i == j ? c : 0.) + (1. - c) * axis[i] * axis[j];
    R[0][1] -= s * axis[2];
    R[0][2] += s * axis[1];
    R[1][0] += s * axis[2];
    R[1][2] -= s * axis[0];
    R[2][0] -= s * axis[1];
    R[2][1] += s * axis[0];
    return R;
  }

  // Equilateral triangular lattice, n x n nodes, spacing a, rotated by alpha in the
  // plane.
  struct Lattice
  {
    std::vector<Point<2>>                                          nodes;
    std::vector<std::array<unsigned, 3>>                           triangles;
    std::map<std::pair<unsigned, unsigned>, std::vector<unsigned>> edge_triangles;
  };

  Lattice
  equilateral_lattice(const unsigned int n, const double a, const double alpha)
  {
    Lattice      lattice;
    const double c = std::cos(alpha), s = std::sin(alpha);
    for (unsigned int j = 0; j < n; ++j)
      for (unsigned int i = 0; i < n; ++i)
        {
          const double x = (i + (j % 2 ? 0.5 : 0.) - 0.5 * n) * a;
          const double y = (j - 0.5 * n) * a * std::sqrt(3.) / 2.;
          lattice.nodes.emplace_back(c * x - s * y, s * x + c * y);
        }
    auto id = [n](unsigned i, unsigned j) { return j * n + i; };
    for (unsigned int j = 0; j + 1 < n; ++j)
      for (unsigned int i = 0; i + 1 < n; ++i)
        if (j % 2 == 0)
          {
            lattice.triangles.push_back({{id(i, j), id(i + 1, j), id(i, j + 1)}});
            lattice.triangles.push_back({{id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)}});
          }
        else
          {
            lattice.triangles.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
            lattice.triangles.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
          }
    for (unsigned int t = 0; t < lattice.triangles.size(); ++t)
      for (unsigned int k = 0; k < 3; ++k)
        {
          unsigned p = lattice.triangles[t][k], q = lattice.triangles[t][(k + 1) % 3];
          lattice.edge_triangles[{std::min(p, q), std::max(p, q)}].push_back(t);
        }
    return lattice;
  }

  double
  triangle_area(const Lattice &lattice, const unsigned t)
  {
    const auto &T = lattice.triangles[t];
    const auto  a = lattice.nodes[T[1]] - lattice.nodes[T[0]];
    const auto  b = lattice.nodes[T[2]] - lattice.nodes[T[0]];
    return 0.5 * std::abs(a[0] * b[1] - a[1] * b[0]);
  }

  // Total spring energy of the lattice under the homogeneous in-plane strain ε (x =
  // (I+ε)X), quadratic part only: (W(ε) + W(-ε)) / 2.
  double
  lattice_strain_energy(const Lattice &lattice,
                        const double   stretch_stiffness,
                        const double   nu,
                        const double   strain[2][2])
  {
    double energy = 0.;
    for (const auto &[edge, tris] : lattice.edge_triangles)
      {
        const Point<2> &X0 = lattice.nodes[edge.first], &X1 = lattice.nodes[edge.second];
        const double    L = (X1 - X0).norm();
        const double    k =
          structural_spring_stiffness(stretch_stiffness,
                                      nu,
                                      L,
                                      triangle_area(lattice, tris[0]),
                                      tris.size() > 1 ? triangle_area(lattice, tris[1])
                                                      : 0.);
        for (const double sign : {1., -1.})
          {
            SpringPositions x;
            for (unsigned int v = 0; v < 2; ++v)
              {
                const Point<2> &X = v == 0 ? X0 : X1;
                for (unsigned int i = 0; i < 2; ++i)
                  x[v][i] = X[i] + sign * (strain[i][0] * X[0] + strain[i][1] * X[1]);
                x[v][2] = 0.;
              }
            energy += 0.5 * spring_energy({k, L}, x);
          }
      }
    return energy;
  }

  double
  continuum_density(const double k_m, const double nu, const double e[2][2])
  {
    const double lambda = nu / (1. - nu * nu), mu = 1. / (2. * (1. + nu));
    const double tr = e[0][0] + e[1][1];
    const double ee = e[0][0] * e[0][0] + e[1][1] * e[1][1] + 2. * e[0][1] * e[0][1];
    return k_m * (0.5 * lambda * tr * tr + mu * ee);
  }

  Tensor<1, 3>
  unit_normal(const std::vector<Point<3>> &x, const std::array<unsigned, 3> &T)
  {
    const Tensor<1, 3> n = cross_product_3d(x[T[1]] - x[T[0]], x[T[2]] - x[T[0]]);
    return n / n.norm();
  }

  // Hinge energy density Σ c_e θ_e² / area of the lattice lifted to the height field
  // w = ½ Xᵀ b X. Interior edges only; the density is (1 / (2|T|)) Σ_directions of the
  // mean edge energy per direction (every direction has 1/(2|T|) edges per unit area).
  double
  hinge_density(const Lattice &lattice,
                const double   alpha,
                const double   D,
                const double   b[2][2])
  {
    std::vector<Point<3>> x;
    for (const auto &X : lattice.nodes)
      x.emplace_back(X[0],
                     X[1],
                     0.5 * (b[0][0] * X[0] * X[0] + 2. * b[0][1] * X[0] * X[1] +
                            b[1][1] * X[1] * X[1]));
    std::map<long, std::pair<double, unsigned>> per_direction;
    double                                      area = 0.;
    for (const auto &[edge, tris] : lattice.edge_triangles)
      {
        if (tris.size() < 2)
          continue;
        const Tensor<1, 3> n1    = unit_normal(x, lattice.triangles[tris[0]]);
        const Tensor<1, 3> n2    = unit_normal(x, lattice.triangles[tris[1]]);
        const double       theta = std::atan2(cross_product_3d(n1, n2).norm(), n1 * n2);
        const Tensor<1, 2> d     = lattice.nodes[edge.second] - lattice.nodes[edge.first];
        const double       A1    = triangle_area(lattice, tris[0]),
                     A2          = triangle_area(lattice, tris[1]);
        const double c           = hinge_bending_coefficient(D, d.norm(), A1, A2);
        const long   direction =
          std::lround(std::fmod(std::atan2(d[1], d[0]) - alpha + 2. * M_PI, M_PI) /
                      (M_PI / 3.)) %
          3;
        per_direction[direction].first += c * theta * theta;
        per_direction[direction].second += 1;
        area = A1;
      }
    double density = 0.;
    for (const auto &[direction, sum] : per_direction)
      density += sum.first / sum.second / (2. * area);
    return per_direction.size() == 3 ? density : std::nan("");
  }
} // namespace

int
main()
{
  ConditionalOStream                     out(std::cout);
  bool                                   passed = true;
  std::mt19937                           generator(42);
  std::uniform_real_distribution<double> uniform(-1., 1.);

  // 1. Derivatives, PSD projection, invariance, rest state.
  double worst_gradient = 0., worst_hessian = 0., most_negative = 0., worst_rigid = 0.,
         worst_rest_force = 0.;
  for (unsigned int trial = 0; trial < 200; ++trial)
    {
      const Spring spring{10. + 1000. * std::abs(uniform(generator)),
                          0.01 + 0.1 * std::abs(uniform(generator))};
      // Stretch ratio in [0.5, 0.95] or [1.05, 1.5]: compressed half the time.
      const double ratio =
        1. + (trial % 2 ? 1. : -1.) * (0.05 + 0.45 * std::abs(uniform(generator)));
      SpringPositions x;
      for (unsigned int d = 0; d < 3; ++d)
        x[0][d] = 0.1 * uniform(generator);
      x[1] = x[0] + ratio * spring.rest_length * random_unit(generator);

      SpringVector gradient;
      SpringMatrix hessian;
      spring_energy_gradient_hessian(spring, x, false, gradient, &hessian);

      const double h = 1e-6 * spring.rest_length;
      SpringVector fd_gradient;
      SpringMatrix fd_hessian;
      for (unsigned int i = 0; i < 6; ++i)
        {
          SpringPositions plus = x, minus = x;
          plus[i / 3][i % 3] += h;
          minus[i / 3][i % 3] -= h;
          fd_gradient[i] =
            (spring_energy(spring, plus) - spring_energy(spring, minus)) / (2. * h);
          SpringVector g_plus, g_minus;
          spring_energy_gradient_hessian(spring, plus, false, g_plus, nullptr);
          spring_energy_gradient_hessian(spring, minus, false, g_minus, nullptr);
          for (unsigned int j = 0; j < 6; ++j)
            fd_hessian[j][i] = (g_plus[j] - g_minus[j]) / (2. * h);
        }
      SpringVector difference;
      for (unsigned int i = 0; i < 6; ++i)
        difference[i] = gradient[i] - fd_gradient[i];
      double hessian_norm = 0., hessian_difference = 0.;
      for (unsigned int i = 0; i < 6; ++i)
        for (unsigned int j = 0; j < 6; ++j)
          {
            hessian_norm += hessian[i][j] * hessian[i][j];
            hessian_difference += std::pow(hessian[i][j] - fd_hessian[i][j], 2);
          }
      worst_gradient = std::max(worst_gradient, l2_norm(difference) / l2_norm(gradient));
      worst_hessian =
        std::max(worst_hessian, std::sqrt(hessian_difference / hessian_norm));

      // Projected Hessian: positive semi-definite.
      SpringMatrix projected;
      spring_energy_gradient_hessian(spring, x, true, gradient, &projected);
      const auto [smallest, largest] = extreme_eigenvalues(projected);
      most_negative                  = std::min(most_negative, smallest / largest);

      // Rigid motion.
      const Tensor<2, 3> R = rotation(random_unit(generator), M_PI * uniform(generator));
      Tensor<1, 3>       shift;
      for (unsigned int d = 0; d < 3; ++d)
        shift[d] = uniform(generator);
      SpringPositions moved;
      for (unsigned int v = 0; v < 2; ++v)
        moved[v] = Point<3>(R * x[v] + shift);
      const double W = spring_energy(spring, x);
      worst_rigid = std::max(worst_rigid, std::abs(spring_energy(spring, moved) - W) / W);

      // Rest length: no force (relative to k L).
      SpringPositions rest = {{x[0], x[0] + spring.rest_length * random_unit(generator)}};
      spring_energy_gradient_hessian(spring, rest, false, gradient, nullptr);
      worst_rest_force =
        std::max(worst_rest_force,
                 l2_norm(gradient) / (spring.stiffness * spring.rest_length));
    }
  out << "spring kernel, 200 random springs:\n";
  passed &= check_below(out, "worst relative gradient error", worst_gradient, 1e-6);
  passed &= check_below(out, "worst relative Hessian error", worst_hessian, 1e-6);
  passed &= check_at_least(out,
                           "most negative projected eigenvalue / largest",
                           most_negative,
                           -1e-12);
  passed &= check_below(out,
                        "worst relative energy change under rigid motion",
                        worst_rigid,
                        1e-12);
  passed &=
    check_below(out, "worst force at rest length / (k L)", worst_rest_force, 1e-12);

  // 2. Strain limit.
  double worst_limited = 0., worst_compliant = 0., worst_pinned = 0., worst_centre = 0.;
  const double tau = 0.1;
  for (unsigned int trial = 0; trial < 200; ++trial)
    {
      const double    L = 0.01 + 0.1 * std::abs(uniform(generator));
      SpringPositions x;
      for (unsigned int d = 0; d < 3; ++d)
        x[0][d] = uniform(generator);
      const double w0          = trial % 4 == 0 ? 0. : 1. + std::abs(uniform(generator));
      const double w1          = trial % 4 == 1 ? 0. : 1. + std::abs(uniform(generator));
      const bool   compression = trial % 3 == 0;

      // Over-stretched (or over-compressed when limiting compression).
      const double ratio     = (compression && trial % 2)
                                 ? 1. - tau - 0.5 * std::abs(uniform(generator))
                                 : 1. + tau + std::abs(uniform(generator));
      x[1]                   = x[0] + ratio * L * random_unit(generator);
      SpringPositions y      = limit_strain(x, L, tau, w0, w1, compression);
      const double    strain = std::abs((y[1] - y[0]).norm() - L) / L;
      worst_limited          = std::max(worst_limited, std::abs(strain - tau));
      if (w0 == 0.)
        worst_pinned = std::max(worst_pinned, (y[0] - x[0]).norm());
      if (w1 == 0.)
        worst_pinned = std::max(worst_pinned, (y[1] - x[1]).norm());
      if (w0 > 0. && w1 > 0.)
        {
          const Tensor<1, 3> before = x[0] / w0 + x[1] / w1,
                             after  = y[0] / w0 + y[1] / w1;
          worst_centre              = std::max(worst_centre,
                                  (after - before).norm() /
                                    (before.norm() + (x[1] - x[0]).norm() / w0));
        }

      // Compliant: strain within (-τ, τ), or compressed without the compression limit.
      SpringPositions z = {
        {x[0],
         x[0] + (1. + 0.99 * tau * uniform(generator)) * L * random_unit(generator)}};
      SpringPositions c = limit_strain(z, L, tau, w0, w1, compression);
      worst_compliant =
        std::max({worst_compliant, (c[0] - z[0]).norm(), (c[1] - z[1]).norm()});
      z[1] = z[0] + 0.5 * L * random_unit(generator);
      c    = limit_strain(z, L, tau, w0, w1, false);
      worst_compliant =
        std::max({worst_compliant, (c[0] - z[0]).norm(), (c[1] - z[1]).norm()});
    }
  out << "strain limit, 200 random springs (tau = " << tau << "):\n";
  passed &= check_below(out, "worst |strain - tau| after limiting", worst_limited, 1e-12);
  passed &= check_equal(out, "worst move of a compliant spring", worst_compliant, 0.);
  passed &= check_equal(out, "worst move of a pinned end", worst_pinned, 0.);
  passed &= check_below(out,
                        "worst relative change of the mass-weighted centre",
                        worst_centre,
                        1e-12);

  // 3. Structural springs on an equilateral lattice (rotated, boundary included).
  out << "structural springs on an equilateral lattice:\n";
  const double  k_m     = 120.;
  const Lattice lattice = equilateral_lattice(12, 0.01, 0.37);
  double        area    = 0.;
  for (unsigned int t = 0; t < lattice.triangles.size(); ++t)
    area += triangle_area(lattice, t);
  const double eps          = 1e-4;
  double       worst_energy = 0.;
  for (unsigned int trial = 0; trial < 20; ++trial)
    {
      double e[2][2];
      e[0][0] = eps * uniform(generator);
      e[1][1] = eps * uniform(generator);
      e[0][1] = e[1][0] = eps * uniform(generator);
      if (trial < 3) // xx, yy, xy alone
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            e[i][j] = (trial == 0 && i + j == 0) || (trial == 1 && i + j == 2) ||
                          (trial == 2 && i + j == 1)
                        ? eps
                        : 0.;
      const double lattice_energy = lattice_strain_energy(lattice, k_m, 1. / 3., e);
      const double expected       = area * continuum_density(k_m, 1. / 3., e);
      worst_energy = std::max(worst_energy, std::abs(lattice_energy / expected - 1.));
    }
  passed &= check_below(
    out,
    "nu = 1/3: worst relative error of lattice energy vs continuum (20 strains)",
    worst_energy,
    1e-6);
  const double uniaxial[2][2] = {{eps, 0.}, {0., 0.}};
  const double shear[2][2]    = {{0., eps}, {eps, 0.}};
  for (const double nu : {0., 0.2, 1. / 3., 0.45})
    {
      const double C11 =
        2. * lattice_strain_energy(lattice, k_m, nu, uniaxial) / (area * eps * eps);
      const double C11_expected = k_m / (1. - nu * nu);
      passed &= check_below(out,
                            "nu = " + std::to_string(nu) +
                              ": |uniaxial-strain stiffness / (E h / (1 - nu^2)) - 1|",
                            std::abs(C11 / C11_expected - 1.),
                            1e-6);
      // Shear modulus: W/area = 2 μ ε_xy² -> ratio to the continuum's, predicted
      // 2/(3(1-ν)).
      const double G =
        lattice_strain_energy(lattice, k_m, nu, shear) / (area * 2. * eps * eps);
      const double G_ratio = G / (k_m / (2. * (1. + nu)));
      passed &= check_below(out,
                            "nu = " + std::to_string(nu) +
                              ": shear modulus ratio lattice/continuum " +
                              std::to_string(G_ratio) +
                              ", vs predicted 2/(3(1-nu)), |rel. diff.|",
                            std::abs(G_ratio / (2. / (3. * (1. - nu))) - 1.),
                            1e-6);
    }

  // 4. Hinge coefficient: cylindrical bending of an equilateral lattice in several
  // directions against the plate's D/2 κ²; spherical and saddle reported.
  out << "hinge coefficient on an equilateral lattice (height field, kappa L = 1e-4):\n";
  const double D = 2e-3, kappa = 1e-2;
  double       worst_cylinder = 0.;
  for (const double alpha : {0., 0.3, 0.9, M_PI / 2.})
    {
      const Lattice patch   = equilateral_lattice(30, 0.01, alpha);
      const double  b[2][2] = {{kappa, 0.}, {0., 0.}};
      worst_cylinder =
        std::max(worst_cylinder,
                 std::abs(hinge_density(patch, alpha, D, b) / (0.5 * D * kappa * kappa) -
                          1.));
    }
  passed &= check_below(out,
                        "worst relative error, cylindrical bending in 4 directions",
                        worst_cylinder,
                        1e-4);
  {
    const Lattice patch        = equilateral_lattice(30, 0.01, 0.3);
    const double  sphere[2][2] = {{kappa, 0.}, {0., kappa}};
    const double  saddle[2][2] = {{kappa, 0.}, {0., -kappa}};
    const double  sphere_ratio =
      hinge_density(patch, 0.3, D, sphere) / (0.5 * D * kappa * kappa * (2. + 2. / 3.));
    const double saddle_ratio =
      hinge_density(patch, 0.3, D, saddle) / (0.5 * D * kappa * kappa * (2. - 2. / 3.));
    // Predicted 2/(3(1+ν)) = 1/2 and 4/(3(1-ν)) = 2 at ν = 1/3 (effective ν = -1/3).
    passed &=
      check_below(out,
                  "spherical bending, hinge/plate(nu=1/3) " +
                    std::to_string(sphere_ratio) + " vs predicted 1/2, |rel. diff.|",
                  std::abs(sphere_ratio / 0.5 - 1.),
                  1e-4);
    passed &=
      check_below(out,
                  "saddle bending, hinge/plate(nu=1/3) " + std::to_string(saddle_ratio) +
                    " vs predicted 2, |rel. diff.|",
                  std::abs(saddle_ratio / 2. - 1.),
                  1e-4);
  }

  // 5. Bend spring: two equilateral triangles folded by θ about their shared edge.
  out << "bend spring across one hinge:\n";
  double worst_bend = 0.;
  for (const double theta_r : {0.05, 0.3, 1.})
    {
      const double L_e = 0.01, A = std::sqrt(3.) / 4. * L_e * L_e, h = 2. * A / L_e;
      const double L_b = 2. * h;
      const double k_b = bend_spring_stiffness(D, L_e, A, A, L_b, theta_r);
      const double c   = hinge_bending_coefficient(D, L_e, A, A);
      for (const double factor : {1., 0.5})
        {
          const double theta = factor * theta_r;
          // Edge along z through the origin; apexes at distance h, fold angle θ between
          // the two half-planes' continuations (flat: θ = 0, apexes opposite).
          SpringPositions x     = {{Point<3>(h, 0., 0.),
                                    Point<3>(-h * std::cos(theta), h * std::sin(theta), 0.)}};
          const double    ratio = spring_energy({k_b, L_b}, x) / (c * theta * theta);
          if (factor == 1.)
            worst_bend = std::max(worst_bend, std::abs(ratio - 1.));
          else
            out << "  info: theta_r = " << theta_r
                << ": spring/hinge energy at theta_r/2 = " << ratio
                << " (quartic spring: ~0.25)\n";
        }
    }
  // ℓ - L_b ~ θ² L_b / 8 loses digits to cancellation: 1e-10, not 1e-12.
  passed &= check_below(out,
                        "worst relative error of bend spring vs hinge at theta_r",
                        worst_bend,
                        1e-10);

  return finish(out, passed);
}
