#pragma once

// The bending element's formulas (physics/bending.h) computed independently, from
// scratch, for tests/bending_derivatives.cc: edge vectors, normal, shape quality, tilts,
// edge curvatures, curvature change and energy.

#include <deal.II/base/tensor.h>

#include "physics/bending.h"

#include <array>
#include <cmath>

namespace clothsim::test
{
  using namespace clothsim::physics;

  // e_i = x_{i+2} - x_{i+1}, the edge opposite vertex i.
  inline Tensor<1, 3>
  edge(const TrianglePositions &x, const unsigned int i)
  {
    return x[(i + 2) % 3] - x[(i + 1) % 3];
  }

  inline Tensor<1, 3>
  unit_normal(const TrianglePositions &x)
  {
    const Tensor<1, 3> N = cross_product_3d(x[1] - x[0], x[2] - x[0]);
    return N / N.norm();
  }

  // Shape quality 4√3 |T| / Σ ℓ_i² (1 for an equilateral triangle, 0 when degenerate).
  inline double
  quality(const TrianglePositions &x)
  {
    double sum = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      sum += edge(x, i).norm_square();
    return 2. * std::sqrt(3.) * cross_product_3d(x[1] - x[0], x[2] - x[0]).norm() / sum;
  }

  // The header's tilt, computed independently:
  //   μ_i = e_i × n / ℓ_i,  δ_i = atan2(r_i·μ_i, r_i·n) + s_i ψ_i.
  inline std::array<double, 3>
  expected_tilts(const TrianglePositions &x,
                 const EdgeDirectors     &directors,
                 const EdgeAngles        &psi)
  {
    const Tensor<1, 3>    n = unit_normal(x);
    std::array<double, 3> tilts;
    for (unsigned int i = 0; i < 3; ++i)
      {
        const Tensor<1, 3>  e  = edge(x, i);
        const Tensor<1, 3>  mu = cross_product_3d(e, n) / e.norm();
        const Tensor<1, 3> &r  = directors.reference[i];
        tilts[i]               = std::atan2(r * mu, r * n) + directors.sign[i] * psi[i];
      }
    return tilts;
  }

  // II_i = 2 h_i f(δ_i), h_i = |N| / ℓ_i, from the header's formulas.
  inline std::array<double, 3>
  expected_edge_curvatures(const DirectorFunction   function,
                           const TrianglePositions &x,
                           const EdgeDirectors     &directors,
                           const EdgeAngles        &psi)
  {
    const std::array<double, 3> tilts = expected_tilts(x, directors, psi);
    const double                area2 = cross_product_3d(x[1] - x[0], x[2] - x[0]).norm();
    std::array<double, 3>       curvatures;
    for (unsigned int i = 0; i < 3; ++i)
      {
        const double f =
          (function == DirectorFunction::angle     ? tilts[i]
           : function == DirectorFunction::sine    ? std::sin(tilts[i])
           : function == DirectorFunction::tangent ? std::tan(tilts[i])
                                                   : 2. * std::tan(0.5 * tilts[i]));
        curvatures[i] = 2. * area2 / edge(x, i).norm() * f;
      }
    return curvatures;
  }

  // The curvature change M = Ā⁻¹ (b - B̄), b = [[II_0 + II_1, II_0], [II_0, II_0 + II_2]]
  // in the basis a_1 = x1 - x0, a_2 = x2 - x0, computed from scratch.
  inline Tensor<2, 2>
  expected_curvature_change(const BendingMaterial   &material,
                            const TrianglePositions &reference,
                            const EdgeDirectors     &rest_directors,
                            const TrianglePositions &x,
                            const EdgeDirectors     &directors,
                            const EdgeAngles        &psi)
  {
    const std::array<double, 3> II =
      expected_edge_curvatures(material.director_function, x, directors, psi);
    const std::array<double, 3> II_rest = expected_edge_curvatures(
      material.director_function, reference, rest_directors, {{0., 0., 0.}});
    const Tensor<1, 3> a1 = reference[1] - reference[0], a2 = reference[2] - reference[0];
    Tensor<2, 2>       metric, change;
    metric[0][0] = a1 * a1;
    metric[0][1] = metric[1][0]   = a1 * a2;
    metric[1][1]                  = a2 * a2;
    const std::array<double, 3> d = {
      {II[0] - II_rest[0], II[1] - II_rest[1], II[2] - II_rest[2]}};
    change[0][0] = d[0] + d[1];
    change[0][1] = change[1][0] = d[0];
    change[1][1]                = d[0] + d[2];
    return invert(metric) * change;
  }

  // W = |T̄| D/2 [ν (tr M)² + (1-ν) tr(M²)]; orthotropic (weft rigidity >= 0), in the
  // frame e_1 = the warp projected onto the reference plane, e_2 = n x e_1, with the
  // Cartesian curvature change K_ij = (b - B̄)_ab (a^a · e_i)(a^b · e_j), b - B̄ = Ā M:
  // W = |T̄| [½ D_1 K_11² + ν √(D_1 D_2) K_11 K_22 + ½ D_2 K_22² + (1-ν) √(D_1 D_2)
  // K_12²].
  inline double
  expected_energy(const BendingMaterial   &material,
                  const TrianglePositions &reference,
                  const EdgeDirectors     &rest_directors,
                  const TrianglePositions &x,
                  const EdgeDirectors     &directors,
                  const EdgeAngles        &psi)
  {
    const Tensor<2, 2> M =
      expected_curvature_change(material, reference, rest_directors, x, directors, psi);
    const double area =
      0.5 *
      cross_product_3d(reference[1] - reference[0], reference[2] - reference[0]).norm();
    const double nu = material.poisson_ratio;
    if (material.weft_rigidity < 0.)
      return area * material.rigidity / 2. *
             (nu * trace(M) * trace(M) + (1. - nu) * trace(M * M));

    const Tensor<1, 3> a[2] = {reference[1] - reference[0], reference[2] - reference[0]};
    Tensor<2, 2>       metric;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        metric[i][j] = a[i] * a[j];
    const Tensor<2, 2> change  = metric * M;
    const Tensor<2, 2> inverse = invert(metric);
    const Tensor<1, 3> dual[2] = {inverse[0][0] * a[0] + inverse[0][1] * a[1],
                                  inverse[1][0] * a[0] + inverse[1][1] * a[1]};
    Tensor<1, 3>       n       = cross_product_3d(a[0], a[1]);
    n /= n.norm();
    Tensor<1, 3> e1 = material.warp_direction - (material.warp_direction * n) * n;
    e1 /= e1.norm();
    const Tensor<1, 3> e[2] = {e1, cross_product_3d(n, e1)};
    Tensor<2, 2>       K;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        for (unsigned int p = 0; p < 2; ++p)
          for (unsigned int q = 0; q < 2; ++q)
            K[i][j] += change[p][q] * (dual[p] * e[i]) * (dual[q] * e[j]);
    const double D1 = material.rigidity, D2 = material.weft_rigidity;
    const double mean = std::sqrt(D1 * D2);
    return area * (0.5 * D1 * K[0][0] * K[0][0] + nu * mean * K[0][0] * K[1][1] +
                   0.5 * D2 * K[1][1] * K[1][1] + (1. - nu) * mean * K[0][1] * K[0][1]);
  }
} // namespace clothsim::test
