// Bending element (midedge-director shell, physics/bending.h) on random triangles, for
// every director function f, for flat and curved rest states, isotropic and (half the
// trials) orthotropic materials with a random warp:
//   1. the gradient (9 positions, 3 angles ψ) against central differences of the energy,
//      and the exact Hessian against central differences of the gradient (errors
//      max|g - g_fd| / max|g| with positions measured in units of the triangle's size,
//      so that position and angle entries weigh alike); energy and curvature change
//      against the header's formulas evaluated here from scratch;
//   2. the Gauss–Newton Hessian symmetric and positive semi-definite, the exact one
//      symmetric;
//   3. invariance under rigid motions (positions and reference vectors moved together),
//      and zero energy and gradient in the rest state;
//   4. the chart: director_tilts follows the header's formula, and re-basing
//      (r_i := edge director, ψ_i := 0) changes neither the tilts nor the energy
// (5., the isometric cylinder limit, is tests/bending_cylinder.cc).
// Every check asserts a bound and prints the worst value it measured.

#include <deal.II/lac/lapack_full_matrix.h>

#include "bending_formulas.h"
#include "physics/bending.h"
#include "test_checks.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>

using namespace clothsim::physics;
using namespace clothsim::test;

namespace
{
  const char *
  function_name(const DirectorFunction function)
  {
    switch (function)
      {
        case DirectorFunction::angle:
          return "angle";
        case DirectorFunction::sine:
          return "sine";
        case DirectorFunction::tangent:
          return "tangent";
        case DirectorFunction::half_tangent:
          return "half tangent";
      }
    return "?";
  }

  // Rotation of v by `angle` about the unit axis k (Rodrigues):
  //   v cos θ + (k × v) sin θ + k (k·v)(1 - cos θ).
  Tensor<1, 3>
  rotate_about(const Tensor<1, 3> &v, const Tensor<1, 3> &k, const double angle)
  {
    return v * std::cos(angle) + cross_product_3d(k, v) * std::sin(angle) +
           k * (k * v) * (1. - std::cos(angle));
  }

  // Uniformly distributed rotation from a random unit quaternion (w, x, y, z).
  Tensor<2, 3>
  random_rotation(std::mt19937 &generator)
  {
    std::normal_distribution<double> normal;
    double                           q[4], norm = 0.;
    for (double &c : q)
      {
        c = normal(generator);
        norm += c * c;
      }
    norm           = std::sqrt(norm);
    const double w = q[0] / norm, x = q[1] / norm, y = q[2] / norm, z = q[3] / norm;
    Tensor<2, 3> Q;
    Q[0][0] = 1. - 2. * (y * y + z * z);
    Q[0][1] = 2. * (x * y - z * w);
    Q[0][2] = 2. * (x * z + y * w);
    Q[1][0] = 2. * (x * y + z * w);
    Q[1][1] = 1. - 2. * (x * x + z * z);
    Q[1][2] = 2. * (y * z - x * w);
    Q[2][0] = 2. * (x * z - y * w);
    Q[2][1] = 2. * (y * z + x * w);
    Q[2][2] = 1. - 2. * (x * x + y * y);
    return Q;
  }

  // One element state: material, rest state and current state.
  struct Case
  {
    BendingMaterial   material;
    double            size; // L, m: the reference vertices lie in [-L, L]³
    TrianglePositions reference;
    EdgeDirectors     rest_directors;
    BendingRestData   rest;
    TrianglePositions x;
    EdgeDirectors     directors;
    EdgeAngles        psi;
  };

  std::string
  describe(const Case &c, const std::string &label)
  {
    std::ostringstream out;
    out << std::setprecision(17) << "  case: " << label << "\n  D " << c.material.rigidity
        << ", nu " << c.material.poisson_ratio << ", f "
        << function_name(c.material.director_function) << ", L " << c.size << '\n';
    for (unsigned int v = 0; v < 3; ++v)
      out << "  X" << v << " (" << c.reference[v] << ")  x" << v << " (" << c.x[v]
          << ")\n";
    for (unsigned int i = 0; i < 3; ++i)
      out << "  edge " << i << ": s " << c.directors.sign[i] << ", rest r ("
          << c.rest_directors.reference[i] << "), r (" << c.directors.reference[i]
          << "), psi " << c.psi[i] << '\n';
    return out.str();
  }

  // A random rest state (vertices in [-L, L]³, L in [0.01, 1]; flat: rest directors on
  // the normal; curved: the normal rotated about each edge by up to 0.3 rad) and a random
  // current state: vertices moved by 10-30 % of L, a rigid motion, reference vectors
  // moved with it and perturbed by ~0.1 rad, ψ in [-0.3, 0.3]. Tilts |δ| <= 1.2 rad keep
  // the tangent function away from its poles.
  Case
  random_case(std::mt19937 &generator, const DirectorFunction function, const bool curved)
  {
    std::uniform_real_distribution<double> uniform(-1., 1.);
    std::bernoulli_distribution            coin;
    Case                                   c;
    for (;;)
      {
        c.material = {0.1 + 9.9 * (0.5 + 0.5 * uniform(generator)),
                      0.45 * (0.5 + 0.5 * uniform(generator)),
                      function};
        if (coin(generator))
          {
            // Orthotropic: a weft up to 10 times softer, a random warp.
            c.material.weft_rigidity =
              c.material.rigidity * (0.1 + 0.45 * (1. + uniform(generator)));
            for (unsigned int d = 0; d < 3; ++d)
              c.material.warp_direction[d] = uniform(generator);
          }
        c.size = std::pow(10., -1. + uniform(generator));
        for (auto &p : c.reference)
          for (unsigned int d = 0; d < 3; ++d)
            p[d] = c.size * uniform(generator);
        if (quality(c.reference) < 0.3)
          continue;

        const Tensor<1, 3> normal = unit_normal(c.reference);
        for (unsigned int i = 0; i < 3; ++i)
          {
            const Tensor<1, 3> e = edge(c.reference, i);
            c.rest_directors.reference[i] =
              curved ? rotate_about(normal, e / e.norm(), 0.3 * uniform(generator))
                     : normal;
            c.rest_directors.sign[i] = coin(generator) ? 1. : -1.;
          }
        c.rest = bending_rest_data(c.material, c.reference, c.rest_directors);

        const Tensor<2, 3> Q         = random_rotation(generator);
        const double       amplitude = c.size * (0.2 + 0.1 * uniform(generator));
        Tensor<1, 3>       translation;
        for (unsigned int d = 0; d < 3; ++d)
          translation[d] = c.size * uniform(generator);
        for (unsigned int v = 0; v < 3; ++v)
          {
            Tensor<1, 3> moved = c.reference[v];
            for (unsigned int d = 0; d < 3; ++d)
              moved[d] += amplitude * uniform(generator);
            c.x[v] = Point<3>(Q * moved + translation);
          }
        if (quality(c.x) < 0.1)
          continue;

        c.directors.sign = c.rest_directors.sign;
        for (unsigned int i = 0; i < 3; ++i)
          {
            Tensor<1, 3> r = Q * c.rest_directors.reference[i];
            for (unsigned int d = 0; d < 3; ++d)
              r[d] += 0.1 * uniform(generator);
            c.directors.reference[i] = r / r.norm();
            c.psi[i]                 = 0.3 * uniform(generator);
          }
        const std::array<double, 3> tilts = expected_tilts(c.x, c.directors, c.psi);
        if (std::all_of(tilts.begin(), tilts.end(), [](const double t) {
              return std::abs(t) <= 1.2;
            }))
          return c;
      }
  }

  double
  max_abs(const BendingVector &v)
  {
    double result = 0.;
    for (const double a : v)
      result = std::max(result, std::abs(a));
    return result;
  }

  // Unknowns in common units: positions divided by L, so that the scaled gradient
  // (L ∂W/∂x, ∂W/∂ψ) and Hessian (scale_k scale_l ∂²W/∂u_k∂u_l) are all in J.
  BendingVector
  unknown_scale(const double size)
  {
    BendingVector scale;
    for (unsigned int k = 0; k < 12; ++k)
      scale[k] = (k < 9 ? size : 1.);
    return scale;
  }

  void
  perturb(const unsigned int k, const double step, TrianglePositions &x, EdgeAngles &psi)
  {
    if (k < 9)
      x[k / 3][k % 3] += step;
    else
      psi[k - 9] += step;
  }

  double
  energy(const Case &c, const TrianglePositions &x, const EdgeAngles &psi)
  {
    return bending_energy(c.material, c.rest, x, c.directors, psi);
  }

  BendingVector
  gradient(const Case &c, const TrianglePositions &x, const EdgeAngles &psi)
  {
    BendingVector g;
    bending_energy_gradient_hessian(
      c.material, c.rest, x, c.directors, psi, false, g, nullptr);
    return g;
  }

  // max |A - B| / max |A| of the scaled matrices (scale_k scale_l A_kl).
  double
  relative_difference(const BendingMatrix &A,
                      const BendingMatrix &B,
                      const BendingVector &scale)
  {
    double difference = 0., norm = 0.;
    for (unsigned int k = 0; k < 12; ++k)
      for (unsigned int l = 0; l < 12; ++l)
        {
          const double s = scale[k] * scale[l];
          difference     = std::max(difference, s * std::abs(A[k][l] - B[k][l]));
          norm           = std::max(norm, s * std::abs(A[k][l]));
        }
    return difference / norm;
  }

  BendingMatrix
  transpose(const BendingMatrix &A)
  {
    BendingMatrix T;
    for (unsigned int k = 0; k < 12; ++k)
      for (unsigned int l = 0; l < 12; ++l)
        T[k][l] = A[l][k];
    return T;
  }
} // namespace

int
main()
{
  ConditionalOStream                     out(std::cout);
  std::mt19937                           generator(42);
  std::uniform_real_distribution<double> uniform(-1., 1.);

  WorstCase gradient_check{"1. gradient vs central differences, max|g - g_fd| / max|g|",
                           1e-6};
  WorstCase hessian_check{
    "1. exact Hessian vs central differences, max|H - H_fd| / max|H|", 1e-6};
  WorstCase returned_energy_check{
    "1. energy and gradient of bending_energy_gradient_hessian vs bending_energy and "
    "the exact call, relative",
    1e-12};
  WorstCase formula_check{"1. energy and curvature change norm vs the header's formulas, "
                          "relative",
                          1e-10};
  WorstCase exact_symmetry_check{"2. exact Hessian, max|H - Hᵀ| / max|H|", 1e-12};
  WorstCase gn_symmetry_check{"2. Gauss–Newton Hessian, max|H - Hᵀ| / max|H|", 1e-12};
  WorstCase gn_psd_check{"2. Gauss–Newton Hessian, -λ_min / λ_max", 1e-12};
  WorstCase rigid_energy_check{"3. rigid motion, |W' - W| / |W|", 1e-10};
  WorstCase rigid_gradient_check{"3. rigid motion, max|g' - Q g| / max|g|", 1e-9};
  WorstCase rest_energy_check{"3. rest state (and rigidly moved), |W| / D", 1e-12};
  WorstCase rest_gradient_check{"3. rest state, max(L |∂W/∂x|, |∂W/∂ψ|) / D", 1e-9};
  WorstCase rest_hessian_check{"3. rest state, exact vs Gauss–Newton Hessian, relative",
                               1e-9};
  WorstCase tilt_formula_check{"4. director_tilts vs atan2(r·μ, r·n) + s ψ, rad", 1e-12};
  WorstCase director_check{"4. edge_director unit and normal to the edge, max(||d| - 1|, "
                           "|d·t|)",
                           1e-12};
  WorstCase rebased_tilt_check{"4. re-based chart, |δ' - δ|, rad", 1e-12};
  WorstCase rebased_energy_check{"4. re-based chart, |W' - W| / |W|", 1e-10};

  for (const DirectorFunction function : {DirectorFunction::angle,
                                          DirectorFunction::sine,
                                          DirectorFunction::tangent,
                                          DirectorFunction::half_tangent})
    for (const bool curved : {false, true})
      for (unsigned int trial = 0; trial < 200; ++trial)
        {
          const Case          c     = random_case(generator, function, curved);
          const std::string   where = describe(c,
                                             std::string(function_name(function)) +
                                               (curved ? ", curved" : ", flat") +
                                               " rest, trial " + std::to_string(trial));
          const BendingVector scale = unknown_scale(c.size);

          // 1. Central differences, steps h = 1e-6 L (positions) and 1e-6 rad (angles):
          //      g_k ≈ [W(u + h e_k) - W(u - h e_k)] / 2h,
          //      H_lk ≈ [g_l(u + h e_k) - g_l(u - h e_k)] / 2h.
          BendingVector g, g_fd;
          BendingMatrix H, H_fd;
          const double  W = bending_energy_gradient_hessian(
            c.material, c.rest, c.x, c.directors, c.psi, false, g, &H);
          for (unsigned int k = 0; k < 12; ++k)
            {
              const double      h      = 1e-6 * scale[k];
              TrianglePositions x_plus = c.x, x_minus = c.x;
              EdgeAngles        psi_plus = c.psi, psi_minus = c.psi;
              perturb(k, h, x_plus, psi_plus);
              perturb(k, -h, x_minus, psi_minus);
              g_fd[k] =
                (energy(c, x_plus, psi_plus) - energy(c, x_minus, psi_minus)) / (2. * h);
              const BendingVector g_plus  = gradient(c, x_plus, psi_plus);
              const BendingVector g_minus = gradient(c, x_minus, psi_minus);
              for (unsigned int l = 0; l < 12; ++l)
                H_fd[l][k] = (g_plus[l] - g_minus[l]) / (2. * h);
            }
          BendingVector g_scaled, g_difference;
          for (unsigned int k = 0; k < 12; ++k)
            {
              g_scaled[k]     = scale[k] * g[k];
              g_difference[k] = scale[k] * (g[k] - g_fd[k]);
            }
          gradient_check.record(out, max_abs(g_difference) / max_abs(g_scaled), where);
          hessian_check.record(out, relative_difference(H, H_fd, scale), where);

          // Same energy from both entry points; the gradient does not depend on
          // `gauss_newton`.
          BendingVector g_gn;
          BendingMatrix H_gn;
          const double  W_gn = bending_energy_gradient_hessian(
            c.material, c.rest, c.x, c.directors, c.psi, true, g_gn, &H_gn);
          BendingVector gn_difference;
          for (unsigned int k = 0; k < 12; ++k)
            gn_difference[k] = scale[k] * (g_gn[k] - g[k]);
          returned_energy_check.record(
            out,
            std::max({std::abs(W - energy(c, c.x, c.psi)) / std::abs(W),
                      std::abs(W_gn - W) / std::abs(W),
                      max_abs(gn_difference) / max_abs(g_scaled)}),
            where);

          // The energy and the curvature change norm sqrt(tr(M²)) against the header's
          // formulas evaluated independently.
          {
            const double W_expected = expected_energy(
              c.material, c.reference, c.rest_directors, c.x, c.directors, c.psi);
            const Tensor<2, 2> M = expected_curvature_change(
              c.material, c.reference, c.rest_directors, c.x, c.directors, c.psi);
            const double norm_expected = std::sqrt(trace(M * M));
            formula_check.record(
              out,
              std::max(std::abs(W - W_expected) / W_expected,
                       std::abs(curvature_change_norm(
                                  c.material, c.rest, c.x, c.directors, c.psi) -
                                norm_expected) /
                         norm_expected),
              where);
          }

          // 2. Symmetry; eigenvalues of the scaled Gauss–Newton Hessian (congruent to
          //    the unscaled one, so it has the same inertia).
          exact_symmetry_check.record(out,
                                      relative_difference(H, transpose(H), scale),
                                      where);
          gn_symmetry_check.record(out,
                                   relative_difference(H_gn, transpose(H_gn), scale),
                                   where);
          BendingMatrix scaled;
          for (unsigned int k = 0; k < 12; ++k)
            for (unsigned int l = 0; l < 12; ++l)
              scaled[k][l] = scale[k] * scale[l] * H_gn[k][l];
          const auto [smallest, largest] = extreme_eigenvalues(scaled);
          gn_psd_check.record(out, -smallest / largest, where);

          // 3. x' = Q x + t, r' = Q r, ψ' = ψ: W' = W, ∂W/∂x'_v = Q ∂W/∂x_v,
          //    ∂W/∂ψ' = ∂W/∂ψ.
          {
            const Tensor<2, 3> Q = random_rotation(generator);
            Tensor<1, 3>       translation;
            for (unsigned int d = 0; d < 3; ++d)
              translation[d] = c.size * uniform(generator);
            Case moved = c;
            for (unsigned int v = 0; v < 3; ++v)
              moved.x[v] = Point<3>(Q * c.x[v] + translation);
            for (unsigned int i = 0; i < 3; ++i)
              moved.directors.reference[i] = Q * c.directors.reference[i];
            BendingVector g_moved;
            const double  W_moved = bending_energy_gradient_hessian(moved.material,
                                                                   moved.rest,
                                                                   moved.x,
                                                                   moved.directors,
                                                                   moved.psi,
                                                                   false,
                                                                   g_moved,
                                                                   nullptr);
            BendingVector difference;
            for (unsigned int v = 0; v < 3; ++v)
              {
                Tensor<1, 3> g_v;
                for (unsigned int d = 0; d < 3; ++d)
                  g_v[d] = g[3 * v + d];
                const Tensor<1, 3> rotated = Q * g_v;
                for (unsigned int d = 0; d < 3; ++d)
                  difference[3 * v + d] = c.size * (g_moved[3 * v + d] - rotated[d]);
              }
            for (unsigned int i = 0; i < 3; ++i)
              difference[9 + i] = g_moved[9 + i] - g[9 + i];
            rigid_energy_check.record(out, std::abs(W_moved - W) / std::abs(W), where);
            rigid_gradient_check.record(out,
                                        max_abs(difference) / max_abs(g_scaled),
                                        where);
          }

          // 3. Rest state: x = X, r = r̄, ψ = 0, as given and after a rigid motion
          //    (x = Q X + t, r = Q r̄), gives W = 0, ∇W = 0, and there the exact Hessian
          //    is its Gauss–Newton part (C (II - ĪI) = 0).
          for (const bool move : {false, true})
            {
              const Tensor<2, 3> Q =
                move ? random_rotation(generator) : unit_symmetric_tensor<3>();
              Tensor<1, 3> translation;
              for (unsigned int d = 0; d < 3 && move; ++d)
                translation[d] = c.size * uniform(generator);
              Case at_rest = c;
              for (unsigned int v = 0; v < 3; ++v)
                at_rest.x[v] = Point<3>(Q * c.reference[v] + translation);
              for (unsigned int i = 0; i < 3; ++i)
                at_rest.directors.reference[i] = Q * c.rest_directors.reference[i];
              at_rest.psi = {{0., 0., 0.}};
              BendingVector g_rest, g_rest_gn;
              BendingMatrix H_rest, H_rest_gn;
              const double  W_rest = bending_energy_gradient_hessian(at_rest.material,
                                                                    at_rest.rest,
                                                                    at_rest.x,
                                                                    at_rest.directors,
                                                                    at_rest.psi,
                                                                    false,
                                                                    g_rest,
                                                                    &H_rest);
              bending_energy_gradient_hessian(at_rest.material,
                                              at_rest.rest,
                                              at_rest.x,
                                              at_rest.directors,
                                              at_rest.psi,
                                              true,
                                              g_rest_gn,
                                              &H_rest_gn);
              for (unsigned int k = 0; k < 12; ++k)
                g_rest[k] *= scale[k];
              rest_energy_check.record(out,
                                       std::abs(W_rest) / c.material.rigidity,
                                       where);
              rest_gradient_check.record(out,
                                         max_abs(g_rest) / c.material.rigidity,
                                         where);
              rest_hessian_check.record(out,
                                        relative_difference(H_rest, H_rest_gn, scale),
                                        where);
            }

          // 4. The header's tilt formula; re-basing on d_i = edge_director(first,
          //    second, r_i, ψ_i) (first = x_{i+1}, second = x_{i+2} if s_i = +1, else
          //    reversed), r_i := d_i, ψ_i := 0 keeps δ and W.
          {
            const std::array<double, 3> tilts = director_tilts(c.x, c.directors, c.psi);
            const std::array<double, 3> expected =
              expected_tilts(c.x, c.directors, c.psi);
            Case rebased = c;
            for (unsigned int i = 0; i < 3; ++i)
              {
                const Point<3>    &a     = c.x[(i + 1) % 3];
                const Point<3>    &b     = c.x[(i + 2) % 3];
                const bool         along = (c.directors.sign[i] > 0.);
                const Tensor<1, 3> d     = edge_director(along ? a : b,
                                                     along ? b : a,
                                                     c.directors.reference[i],
                                                     c.psi[i]);
                const Tensor<1, 3> t = edge(c.x, i) / edge(c.x, i).norm();
                tilt_formula_check.record(out, std::abs(tilts[i] - expected[i]), where);
                director_check.record(out,
                                      std::max(std::abs(d.norm() - 1.), std::abs(d * t)),
                                      where);
                rebased.directors.reference[i] = d;
                rebased.psi[i]                 = 0.;
              }
            const std::array<double, 3> rebased_tilts =
              director_tilts(rebased.x, rebased.directors, rebased.psi);
            for (unsigned int i = 0; i < 3; ++i)
              rebased_tilt_check.record(out,
                                        std::abs(rebased_tilts[i] - tilts[i]),
                                        where);
            rebased_energy_check.record(
              out,
              std::abs(energy(rebased, rebased.x, rebased.psi) - W) / std::abs(W),
              where);
          }
        }

  bool passed = true;
  for (const WorstCase *check : {&gradient_check,
                                 &hessian_check,
                                 &returned_energy_check,
                                 &formula_check,
                                 &exact_symmetry_check,
                                 &gn_symmetry_check,
                                 &gn_psd_check,
                                 &rigid_energy_check,
                                 &rigid_gradient_check,
                                 &rest_energy_check,
                                 &rest_gradient_check,
                                 &rest_hessian_check,
                                 &tilt_formula_check,
                                 &director_check,
                                 &rebased_tilt_check,
                                 &rebased_energy_check})
    passed &= check->report(out);
  return finish(out, passed);
}
