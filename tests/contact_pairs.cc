// The pair kernels of contact (cloth-mesh, edge contact and self-contact), one by one:
// 1. Pair distances (physics/pair_distance.h): on 2,000 random point-triangle and
//    edge-edge pairs the distance is at most that of any of 40,000 sampled point pairs
//    of the two primitives and within 1e-4 of the closest one sampled; the closest
//    points' weights give it (|Σ w_i x_i| = d to 1e-12); 2,000 random segments cross
//    their triangle exactly when solving for the intersection point says so.
// 2. The pair barrier (physics/pair_barrier.h): gradient and Hessian against central
//    differences (relative 1e-5) for every kind and set of moving points, edge-edge
//    pairs with and without the mollifier at work, of the pair's distance and of its
//    distance less an offset r (an analytic obstacle's inflated core, edge contact).
//    The gradient alone and Gauss-Newton's (closed form, from the closest points'
//    weights) equal the exact path's gradient to 1e-10, and Gauss-Newton's curvature
//    along a random direction is κ s''(d) (∇d·v)², ∇d·v by differences (1e-5).
// 3. The positive semi-definite projection: a 12 x 12 matrix of known eigenvalues
//    (half negative) becomes the matrix with those set to zero, to 1e-12. And what the
//    tangents keep of a triangle turning about the point of it closest to a core point
//    (a sphere's centre, distance less r = 0.25 m): along the turn the exact Hessian's
//    second derivative is κ |s'(d)| (d + r) (the plane comes (d + r)(1 - cos θ) closer),
//    to 1e-7 relative; the projected exact Hessian keeps at least that and has no
//    negative eigenvalue (below 1e-12 of its largest); Gauss-Newton's has none of it.
// 4. The line search's cap (pair_step_bound) on 2,000 random paths, many crossing:
//    the distance stays at or above the fraction of its start along the whole capped
//    path (sampled at 1,000 points); the same for the distance less an offset.
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include "contact_checks.h"
#include "physics/contact_potential.h"
#include "physics/pair_barrier.h"
#include "physics/pair_distance.h"

#include <random>

using namespace clothsim;
using namespace clothsim::test;
using physics::PairKind;
using physics::PairPoints;

namespace
{
  // Points within `spread` of the origin, the second primitive's moved by 0.3 spread.
  PairPoints
  random_pair(std::mt19937 &random, const double spread, const PairKind kind)
  {
    std::uniform_real_distribution<double> u(-1., 1.);
    const unsigned int first = kind == PairKind::point_triangle ? 1 : 2;
    PairPoints         x;
    for (unsigned int i = 0; i < 4; ++i)
      for (unsigned int c = 0; c < 3; ++c)
        x[i][c] = spread * (u(random) + (i < first ? 0. : 0.3));
    return x;
  }

  unsigned int
  n_moving(const std::array<bool, 4> &moving)
  {
    return std::count(moving.begin(), moving.end(), true);
  }

  // The smallest distance between points of the two primitives, by sampling their
  // parameters on a grid and zooming in on the best sample four times (to about 1e-9 of
  // their size).
  double
  sampled_distance(const PairKind kind, const PairPoints &x)
  {
    const auto distance = [&](const double s, const double t) {
      if (kind == PairKind::point_triangle)
        return x[0].distance(Point<3>(x[1] + s * (x[2] - x[1]) + t * (x[3] - x[1])));
      return Point<3>(x[0] + s * (x[1] - x[0]))
        .distance(Point<3>(x[2] + t * (x[3] - x[2])));
    };
    const unsigned int n    = 100;
    double             best = std::numeric_limits<double>::infinity(), s0 = 0.5, t0 = 0.5;
    double             width = 1.;
    for (unsigned int zoom = 0; zoom < 5; ++zoom)
      {
        const double sc = s0, tc = t0;
        for (unsigned int i = 0; i <= n; ++i)
          for (unsigned int j = 0; j <= n; ++j)
            {
              const double s = std::clamp(sc + width * (double(i) / n - 0.5), 0., 1.);
              const double t = std::clamp(tc + width * (double(j) / n - 0.5), 0., 1.);
              if (kind == PairKind::point_triangle && s + t > 1.)
                continue;
              const double d = distance(s, t);
              if (d < best)
                {
                  best = d;
                  s0   = s;
                  t0   = t;
                }
            }
        width = zoom == 0 ? 0.04 : width / 20.;
      }
    return best;
  }

  bool
  check_distances(ConditionalOStream &pcout)
  {
    std::mt19937 random(3);
    double       excess = 0., shortfall = 0., weight_error = 0.;
    for (const PairKind kind : {PairKind::point_triangle, PairKind::edge_edge})
      for (unsigned int sample = 0; sample < 1000; ++sample)
        {
          PairPoints x = random_pair(random, 1., kind);
          if (sample % 10 == 0) // nearly parallel edges, or a point over an edge
            x[3] = x[2] + (x[1] - x[0]) * 0.7 + Tensor<1, 3>({1e-9, 0., 0.});
          const physics::DistanceType type = physics::distance_type(kind, x);
          const double                d = std::sqrt(physics::squared_distance(type, x));
          const double                sampled = sampled_distance(kind, x);
          excess                              = std::max(excess, d - sampled);
          shortfall                           = std::max(shortfall, sampled - d);
          const auto   w                      = physics::closest_point_weights(type, x);
          Tensor<1, 3> r;
          for (unsigned int i = 0; i < 4; ++i)
            r += w[i] * x[i];
          weight_error = std::max(weight_error, std::abs(r.norm() - d));
        }
    bool passed =
      check_below(pcout, "distance above the closest sampled pair, m", excess, 1e-12);
    passed &=
      check_below(pcout, "distance below the closest sampled pair, m", shortfall, 1e-4);
    passed &= check_below(pcout,
                          "| |Σ w_i x_i| - d | of the closest points, m",
                          weight_error,
                          1e-12);

    // Segments through triangles, against solving a + s (b - a) = t0 + u e0 + v e1.
    unsigned int wrong = 0, crossing = 0;
    for (unsigned int sample = 0; sample < 2000; ++sample)
      {
        // A segment through a point of the triangle's plane, inside or outside it, its
        // ends on either side or on one.
        const PairPoints x  = random_pair(random, 1., PairKind::edge_edge);
        const Point<3>   t0 = x[0], t1 = x[1], t2 = x[2];
        std::uniform_real_distribution<double> in(-0.3, 1.), along(-0.5, 1.);
        const double                           u = in(random), v = in(random) * (1. - u);
        const Point<3>                         p(t0 + u * (t1 - t0) + v * (t2 - t0));
        const Tensor<1, 3>                     d = x[3] - x[0];
        const Point<3>     a(p + along(random) * d), b(p - along(random) * d);
        FullMatrix<double> M(3, 3), inverse(3, 3);
        for (unsigned int c = 0; c < 3; ++c)
          {
            M(c, 0) = b[c] - a[c];
            M(c, 1) = t0[c] - t1[c];
            M(c, 2) = t0[c] - t2[c];
          }
        inverse.invert(M);
        Vector<double> rhs(3), stu(3);
        for (unsigned int c = 0; c < 3; ++c)
          rhs[c] = t0[c] - a[c];
        inverse.vmult(stu, rhs);
        const bool expected = stu[0] >= 0. && stu[0] <= 1. && stu[1] >= 0. &&
                              stu[2] >= 0. && stu[1] + stu[2] <= 1.;
        crossing += expected ? 1 : 0;
        wrong += expected != physics::segment_crosses_triangle(a, b, t0, t1, t2) ? 1 : 0;
      }
    pcout << "  " << crossing << " of 2000 random segments cross their triangle"
          << std::endl;
    passed &= check_equal(pcout, "segment-triangle crossings misjudged", wrong, 0u);
    passed &= check_above(pcout, "segments crossing", crossing, 100);
    return passed;
  }

  bool
  check_barrier(ConditionalOStream &pcout)
  {
    std::mt19937                             random(5);
    std::uniform_real_distribution<double>   u(-1., 1.);
    const double                             d_hat = 0.01, kappa = 300.;
    const std::array<std::array<bool, 4>, 4> masks  = {{{{true, false, false, false}},
                                                        {{false, true, true, true}},
                                                        {{true, true, false, false}},
                                                        {{true, true, true, true}}}};
    bool                                     passed = true;
    // offset r: an analytic obstacle's core feature inflated by r (edge contact).
    for (unsigned int m = 0; m < masks.size(); ++m)
      for (const bool mollified : {false, true})
        for (const double offset : {0., 0.03})
          {
            if (mollified && m != 2)
              continue;
            const PairKind kind  = m < 2 ? PairKind::point_triangle : PairKind::edge_edge;
            double         g_err = 0., h_err = 0., closed_err = 0., gauss_err = 0.;
            unsigned int   tried = 0;
            std::mt19937   local(m + 10 * mollified);
            while (tried < 50)
              {
                PairPoints x = random_pair(local, 0.05, kind);
                if (mollified) // nearly parallel edges
                  x[3] = x[2] + (x[1] - x[0]) + Tensor<1, 3>({2e-3, -1e-3, 1e-3});
                const double d = std::sqrt(physics::pair_squared_distance(kind, x));
                if (d - offset > 0.9 * d_hat || d - offset < 0.1 * d_hat)
                  {
                    // Move the second primitive to a distance within the barrier.
                    const auto w =
                      physics::closest_point_weights(physics::distance_type(kind, x), x);
                    Tensor<1, 3> r;
                    for (unsigned int i = 0; i < 4; ++i)
                      r += w[i] * x[i];
                    const double target =
                      offset + d_hat * (0.2 + 0.6 * (0.5 + 0.5 * u(random)));
                    const unsigned int first = kind == PairKind::point_triangle ? 1 : 2;
                    for (unsigned int i = first; i < 4; ++i)
                      x[i] += r * (1. - target / r.norm());
                  }
                const double dd =
                  std::sqrt(physics::pair_squared_distance(kind, x)) - offset;
                if (dd >= d_hat || dd <= 0.)
                  continue;
                const double threshold =
                  mollified ? physics::mollifier_threshold(x[0].distance(x[1]),
                                                           x[2].distance(x[3]))
                            : 0.;
                const auto barrier_at = [&](const PairPoints &y) {
                  return physics::pair_barrier(kind,
                                               y,
                                               masks[m],
                                               kappa,
                                               d_hat,
                                               threshold,
                                               2,
                                               physics::PairHessian::exact,
                                               false,
                                               offset);
                };
                const physics::PairBarrier b = barrier_at(x);
                // The gradient alone (closed form unless mollified) and Gauss-Newton's
                // Hessian: the same gradient, and along a random v the curvature
                // κ s''(d) (∇d·v)², ∇d·v by central differences of the distance.
                const auto other_form = [&](const unsigned int order) {
                  return physics::pair_barrier(kind,
                                               x,
                                               masks[m],
                                               kappa,
                                               d_hat,
                                               threshold,
                                               order,
                                               physics::PairHessian::gauss_newton,
                                               false,
                                               offset);
                };
                const physics::PairBarrier first = other_form(1), gauss = other_form(2);
                double                     scale = 0.;
                for (unsigned int j = 0; j < b.n; ++j)
                  scale = std::max(scale, std::abs(b.gradient[j]));
                for (unsigned int j = 0; j < b.n; ++j)
                  closed_err =
                    std::max({closed_err,
                              std::abs(first.gradient[j] - b.gradient[j]) / scale,
                              std::abs(gauss.gradient[j] - b.gradient[j]) / scale});
                if (!mollified)
                  {
                    std::array<double, 12> v{};
                    PairPoints             plus = x, minus = x;
                    const double           step = 1e-7;
                    for (unsigned int i = 0, k = 0; i < 4; ++i)
                      if (masks[m][i])
                        for (unsigned int c = 0; c < 3; ++c, ++k)
                          {
                            v[k] = u(local);
                            plus[i][c] += step * v[k];
                            minus[i][c] -= step * v[k];
                          }
                    const double slope =
                      (std::sqrt(physics::pair_squared_distance(kind, plus)) -
                       std::sqrt(physics::pair_squared_distance(kind, minus))) /
                      (2. * step);
                    const double expected =
                      kappa * physics::contact::barrier_second(dd, d_hat) * slope * slope;
                    double curvature = 0., v_squared = 0.;
                    for (unsigned int i = 0; i < gauss.n; ++i)
                      {
                        v_squared += v[i] * v[i];
                        for (unsigned int j = 0; j < gauss.n; ++j)
                          curvature += v[i] * gauss.hessian[i * gauss.n + j] * v[j];
                      }
                    // Relative to κ s''(d) |v|² (|∇d| is at most √2).
                    gauss_err =
                      std::max(gauss_err,
                               std::abs(curvature - expected) /
                                 (kappa * physics::contact::barrier_second(dd, d_hat) *
                                  v_squared));
                  }
                const double h = 1e-8;
                unsigned int k = 0;
                for (unsigned int i = 0; i < 4; ++i)
                  if (masks[m][i])
                    for (unsigned int c = 0; c < 3; ++c, ++k)
                      {
                        PairPoints plus = x, minus = x;
                        plus[i][c] += h;
                        minus[i][c] -= h;
                        const auto bp      = barrier_at(plus);
                        const auto bm      = barrier_at(minus);
                        double     g_scale = 0., h_scale = 0.;
                        for (unsigned int j = 0; j < b.n; ++j)
                          {
                            g_scale = std::max(g_scale, std::abs(b.gradient[j]));
                            h_scale = std::max(h_scale, std::abs(b.hessian[j * b.n + k]));
                          }
                        g_err = std::max(g_err,
                                         std::abs((bp.value - bm.value) / (2. * h) -
                                                  b.gradient[k]) /
                                           g_scale);
                        for (unsigned int j = 0; j < b.n; ++j)
                          h_err = std::max(h_err,
                                           std::abs((bp.gradient[j] - bm.gradient[j]) /
                                                      (2. * h) -
                                                    b.hessian[j * b.n + k]) /
                                             h_scale);
                      }
                ++tried;
              }
            const std::string what =
              std::string(kind == PairKind::point_triangle ? "point-triangle"
                                                           : "edge-edge") +
              ", " + std::to_string(n_moving(masks[m])) + " moving" +
              (mollified ? ", mollified" : "") +
              (offset > 0. ? ", distance less r = " + std::to_string(offset) + " m"
                           : "") +
              ": ";
            passed &=
              check_below(pcout, what + "gradient against differences", g_err, 1e-5);
            passed &=
              check_below(pcout, what + "Hessian against differences", h_err, 1e-5);
            passed &= check_below(pcout,
                                  what + "gradient alone and Gauss-Newton's against it",
                                  closed_err,
                                  1e-10);
            if (!mollified)
              passed &= check_below(pcout,
                                    what + "Gauss-Newton's curvature against differences",
                                    gauss_err,
                                    1e-5);
          }
    return passed;
  }

  bool
  check_projection(ConditionalOStream &pcout)
  {
    // A = Q diag(λ) Qᵀ with Q from Gram-Schmidt of random columns.
    const unsigned int                     n = 12;
    std::mt19937                           random(9);
    std::uniform_real_distribution<double> u(-1., 1.);
    std::array<Tensor<1, 12>, 12>          Q;
    for (unsigned int k = 0; k < n; ++k)
      {
        for (unsigned int i = 0; i < n; ++i)
          Q[k][i] = u(random);
        for (unsigned int j = 0; j < k; ++j)
          Q[k] -= (Q[k] * Q[j]) * Q[j];
        Q[k] /= Q[k].norm();
      }
    std::array<double, 144> A{}, expected{};
    for (unsigned int k = 0; k < n; ++k)
      {
        const double lambda = (k % 2 == 0 ? -1. : 1.) * (1. + k);
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            {
              A[i * n + j] += lambda * Q[k][i] * Q[k][j];
              expected[i * n + j] += std::max(lambda, 0.) * Q[k][i] * Q[k][j];
            }
      }
    physics::project_to_positive_semidefinite(A.data(), n);
    double error = 0.;
    for (unsigned int i = 0; i < n * n; ++i)
      error = std::max(error, std::abs(A[i] - expected[i]));
    return check_below(pcout,
                       "projection of a 12 x 12 matrix, largest error",
                       error,
                       1e-12);
  }

  // δᵀ H δ over the nine coordinates of a pair's moving triangle.
  double
  quadratic_form(const physics::PairBarrier &b, const std::array<double, 9> &delta)
  {
    double sum = 0.;
    for (unsigned int i = 0; i < 9; ++i)
      for (unsigned int j = 0; j < 9; ++j)
        sum += delta[i] * b.hessian[i * 9 + j] * delta[j];
    return sum;
  }

  bool
  check_turn_stiffness(ConditionalOStream &pcout)
  {
    // A core point r + d above a triangle in z = 0 whose closest point is the origin,
    // inside it; the triangle turns about the x axis: δx_i = (0, 0, y_i).
    const double r = 0.25, d = 1e-3, d_hat = 5e-3, kappa = 1.;
    PairPoints   x;
    x[0] = Point<3>(0., 0., r + d);
    x[1] = Point<3>(-0.02, -0.01, 0.);
    x[2] = Point<3>(0.02, -0.01, 0.);
    x[3] = Point<3>(0., 0.02, 0.);
    std::array<double, 9> delta{};
    for (unsigned int i = 0; i < 3; ++i)
      delta[3 * i + 2] = x[i + 1][1];
    const auto barrier = [&](const physics::PairHessian form) {
      return physics::pair_barrier(PairKind::point_triangle,
                                   x,
                                   {{false, true, true, true}},
                                   kappa,
                                   d_hat,
                                   0.,
                                   2,
                                   form,
                                   false,
                                   r);
    };
    // δ is the motion per unit angle θ, along which the plane's unit normal turns at
    // |dn̂/dθ| = 1 and the distance's first derivative is zero.
    const double expected = -kappa * physics::contact::barrier_first(d, d_hat) * (r + d);
    const physics::PairBarrier exact     = barrier(physics::PairHessian::exact);
    const physics::PairBarrier projected = barrier(physics::PairHessian::projected);
    const physics::PairBarrier gauss     = barrier(physics::PairHessian::gauss_newton);
    bool                       passed    = check_near(pcout,
                             "a triangle turning over a core point: exact Hessian along "
                                                      "the turn / (κ |s'(d)| (d + r))",
                             quadratic_form(exact, delta) / expected,
                             1.,
                             1e-7);
    passed &=
      check_at_least(pcout,
                     "projected exact Hessian along the turn / (κ |s'(d)| (d + r))",
                     quadratic_form(projected, delta) / expected,
                     1. - 1e-9);
    passed &= check_below(pcout,
                          "Gauss-Newton's along the turn / (κ |s'(d)| (d + r))",
                          std::abs(quadratic_form(gauss, delta)) / expected,
                          1e-9);
    // The projection's smallest eigenvalue: the matrix minus the projection of its
    // negation must vanish (A = A+ - A-, so projecting -A gives A-, zero for A >= 0).
    std::array<double, 144> negated{};
    double                  largest = 0.;
    for (unsigned int i = 0; i < 81; ++i)
      {
        negated[i] = -projected.hessian[i];
        largest    = std::max(largest, std::abs(projected.hessian[i]));
      }
    physics::project_to_positive_semidefinite(negated.data(), 9);
    double negative_part = 0.;
    for (unsigned int i = 0; i < 81; ++i)
      negative_part = std::max(negative_part, std::abs(negated[i]));
    passed &= check_below(pcout,
                          "projected exact Hessian: negative part / its largest entry",
                          negative_part / largest,
                          1e-12);
    return passed;
  }

  bool
  check_step_bounds(ConditionalOStream &pcout)
  {
    std::mt19937                           random(13);
    std::uniform_real_distribution<double> u(-1., 1.);
    const double                           fraction = 0.1;
    bool                                   passed   = true;
    for (const PairKind kind : {PairKind::point_triangle, PairKind::edge_edge})
      for (const double offset : {0., 0.01})
        {
          double       worst  = std::numeric_limits<double>::infinity();
          unsigned int capped = 0;
          for (unsigned int sample = 0; sample < 1000; ++sample)
            {
              const PairPoints x = random_pair(random, 0.1, kind);
              const double     d0 =
                std::sqrt(physics::pair_squared_distance(kind, x)) - offset;
              if (d0 <= 0.)
                continue;
              // The first primitive toward the second's centre and beyond.
              PairPoints         dx;
              const Tensor<1, 3> toward =
                (kind == PairKind::point_triangle ? (x[1] + x[2] + x[3]) / 3. - x[0]
                                                  : (x[2] + x[3] - x[0] - x[1]) / 2.) *
                (1. + 2. * (0.5 + 0.5 * u(random)));
              for (unsigned int i = 0; i < 4; ++i)
                for (unsigned int c = 0; c < 3; ++c)
                  dx[i][c] =
                    0.05 * u(random) +
                    ((i < (kind == PairKind::point_triangle ? 1u : 2u)) ? toward[c] : 0.);
              const double alpha =
                physics::pair_step_bound(kind, x, dx, fraction, offset);
              capped += alpha < 1. ? 1 : 0;
              for (unsigned int k = 0; k <= 1000; ++k)
                {
                  PairPoints y;
                  for (unsigned int i = 0; i < 4; ++i)
                    y[i] = x[i] + (alpha * k / 1000.) * dx[i];
                  worst = std::min(
                    worst,
                    (std::sqrt(physics::pair_squared_distance(kind, y)) - offset) / d0);
                }
            }
          const std::string name =
            std::string(kind == PairKind::point_triangle ? "point-triangle"
                                                         : "edge-edge") +
            (offset > 0. ? " less r = " + std::to_string(offset) + " m" : "");
          pcout << "  " << name << ": " << capped << " of 1000 paths capped" << std::endl;
          passed &= check_at_least(pcout,
                                   name + ": smallest d / d0 on the capped paths",
                                   worst,
                                   fraction * (1. - 1e-12));
          passed &= check_above(pcout, name + ": paths capped", capped, 200);
        }
    return passed;
  }
} // namespace

int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &pcout  = env.pcout;
  bool                passed = true;
  pcout << "Pair distances" << std::endl;
  passed &= check_distances(pcout);
  pcout << "Pair barrier" << std::endl;
  passed &= check_barrier(pcout);
  passed &= check_projection(pcout);
  passed &= check_turn_stiffness(pcout);
  pcout << "Continuous collision detection" << std::endl;
  passed &= check_step_bounds(pcout);
  return finish(pcout, passed);
}
