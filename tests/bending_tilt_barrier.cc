// The director functions with a barrier (physics/bending.h): f = tan δ (at |δ| = π/2) and
// f = 2 tan(δ/2) (at |δ| = π), and the line-search cap tilt_step_bound that keeps every
// tilt on its branch of f.
//  1. Closed form: an edge angle alone turning at dψ/dα = 10 rad. The followed tilt
//     reaches 9/10 of the way to the barrier at α* = 0.9 b / 10, and halving from one
//     gives the largest 2^-k <= α*: 0.25 for 2 tan(δ/2) (b = π), 0.125 for tan δ.
//  2. A face hinged about one edge, its third vertex moved straight across the edge's
//     line so that the face turns by nearly π against the edge's director (a crease
//     turning inside out): at the bound no tilt passes 9/10 of the way to π (2,000
//     samples), and the bound is within a factor 4 of where the first tilt does.
//  3. Random bent triangles moved by random large updates (positions by up to the
//     triangle's size, angles by up to 6 rad): at the returned α, the tilts followed
//     continuously along 2,000 samples of [0, α] never pass 9/10 of the way to the
//     barrier (the bound samples only 4 points), and α is within a factor 4 of the
//     sampled largest admissible step.
//  4. Functions without barrier ('angle', 'sine') never cap a step.

#include "physics/bending.h"
#include "test_checks.h"

#include <cmath>
#include <random>

using namespace clothsim::physics;
using namespace clothsim::test;

namespace
{
  using Displacements = std::array<Tensor<1, 3>, 3>;

  // The tilts along x + a dx, ψ + a dψ for a in [0, alpha] (n samples), followed
  // continuously from a = 0: the largest |δ_i| - limit_i on the way, and the first a at
  // which a tilt passes its limit (infinity if none).
  struct Followed
  {
    double worst_excess;
    double first_violation;
  };

  Followed
  follow(const double             barrier,
         const TrianglePositions &x,
         const Displacements     &dx,
         const EdgeDirectors     &directors,
         const EdgeAngles        &psi,
         const EdgeAngles        &dpsi,
         const double             alpha,
         const unsigned int       n)
  {
    const std::array<double, 3> start    = director_tilts(x, directors, psi);
    std::array<double, 3>       followed = start, previous = start;
    Followed                    result{-1e300, std::numeric_limits<double>::infinity()};
    for (unsigned int k = 1; k <= n; ++k)
      {
        const double      a = alpha * k / n;
        TrianglePositions x_a;
        EdgeAngles        psi_a;
        for (unsigned int i = 0; i < 3; ++i)
          {
            x_a[i]   = x[i] + a * dx[i];
            psi_a[i] = psi[i] + a * dpsi[i];
          }
        const std::array<double, 3> tilts = director_tilts(x_a, directors, psi_a);
        for (unsigned int i = 0; i < 3; ++i)
          {
            followed[i] =
              previous[i] + std::remainder(tilts[i] - previous[i], 2. * numbers::PI);
            previous[i] = followed[i];
            if (std::abs(start[i]) >= barrier)
              continue;
            const double limit =
              std::abs(start[i]) + 0.9 * (barrier - std::abs(start[i]));
            const double excess = std::abs(followed[i]) - limit;
            result.worst_excess = std::max(result.worst_excess, excess);
            if (excess > 0. && a < result.first_violation)
              result.first_violation = a;
          }
      }
    return result;
  }

  EdgeDirectors
  normal_directors()
  {
    EdgeDirectors directors;
    for (unsigned int i = 0; i < 3; ++i)
      {
        directors.reference[i] = Tensor<1, 3>({0., 0., 1.});
        directors.sign[i]      = (i == 1 ? -1. : 1.);
      }
    return directors;
  }
} // namespace


int
main()
{
  ConditionalOStream      out(std::cout, true);
  const TrianglePositions flat = {
    {Point<3>(0., 0., 0.), Point<3>(1., 0., 0.), Point<3>(0.3, 0.9, 0.)}};
  const EdgeDirectors directors = normal_directors();
  const EdgeAngles    zero      = {{0., 0., 0.}};
  const Displacements still     = {};

  out << "1. an edge angle turning at 10 rad per unit step" << std::endl;
  {
    const EdgeAngles dpsi = {{10., 0., 0.}};
    check_equal(out,
                "half tangent: alpha",
                tilt_step_bound(
                  DirectorFunction::half_tangent, flat, still, directors, zero, dpsi, 1.),
                0.25);
    check_equal(
      out,
      "tangent: alpha",
      tilt_step_bound(DirectorFunction::tangent, flat, still, directors, zero, dpsi, 1.),
      0.125);
    check_equal(
      out,
      "half tangent from alpha = 0.2: alpha",
      tilt_step_bound(
        DirectorFunction::half_tangent, flat, still, directors, zero, dpsi, 0.2),
      0.2);
  }

  out << "2. a crease turning inside out (vertex 2 moved through the plane x-z)"
      << std::endl;
  {
    // Edge 2 (from x0 to x1, the x axis) keeps the director (0, 0, 1); the face turns
    // about it by nearly π (its normal from (0, 0, 1) to ∝ (0, -0.1, -0.9)) as x2 moves
    // from (0.3, 0.9, 0) to (0.3, -0.9, 0.1).
    const Displacements dx = {
      {Tensor<1, 3>(), Tensor<1, 3>(), Tensor<1, 3>({0., -1.8, 0.1})}};
    const double alpha = tilt_step_bound(
      DirectorFunction::half_tangent, flat, dx, directors, zero, zero, 1.);
    const Followed at_bound =
      follow(numbers::PI, flat, dx, directors, zero, zero, alpha, 2000);
    const Followed whole =
      follow(numbers::PI, flat, dx, directors, zero, zero, 1., 20000);
    check_below(out,
                "tilts at the bound: largest excess over 0.9 pi, rad",
                at_bound.worst_excess,
                0.);
    check_below(out,
                "the whole update passes 0.9 pi at alpha",
                whole.first_violation,
                1.);
    check_at_most(out, "alpha", alpha, whole.first_violation);
    check_above(out, "alpha", alpha, 0.25 * whole.first_violation);
  }

  out << "3. random triangles and updates" << std::endl;
  {
    std::mt19937                           generator(11);
    std::uniform_real_distribution<double> uniform(-1., 1.);
    WorstCase    excess{"largest tilt excess over the limit at the bound, rad", 0.};
    WorstCase    conservative{"largest admissible step over the bound", 4.};
    unsigned int n_capped = 0;
    for (const DirectorFunction function :
         {DirectorFunction::tangent, DirectorFunction::half_tangent})
      for (unsigned int trial = 0; trial < 300; ++trial)
        {
          TrianglePositions x = flat;
          EdgeDirectors     d = directors;
          EdgeAngles        psi, dpsi;
          Displacements     dx;
          for (unsigned int i = 0; i < 3; ++i)
            {
              for (unsigned int c = 0; c < 3; ++c)
                {
                  x[i][c] += 0.2 * uniform(generator);
                  dx[i][c] = uniform(generator);
                }
              Tensor<1, 3> r({0.3 * uniform(generator), 0.3 * uniform(generator), 1.});
              d.reference[i] = r / r.norm();
              psi[i]         = 0.5 * uniform(generator);
              dpsi[i]        = 6. * uniform(generator);
            }
          const double      barrier = barrier_tilt(function);
          const double      alpha   = tilt_step_bound(function, x, dx, d, psi, dpsi, 1.);
          const std::string where   = "trial " + std::to_string(trial) + "\n";
          excess.record(
            out,
            std::max(0., follow(barrier, x, dx, d, psi, dpsi, alpha, 2000).worst_excess),
            where);
          const double admissible =
            std::min(1., follow(barrier, x, dx, d, psi, dpsi, 1., 20000).first_violation);
          conservative.record(out, admissible / alpha, where);
          n_capped += alpha < 1. ? 1 : 0;
        }
    excess.report(out);
    conservative.report(out);
    check_above(out, "updates capped (of 600)", n_capped, 100);
  }

  out << "4. no barrier, no cap" << std::endl;
  {
    const EdgeAngles dpsi = {{10., 0., 0.}};
    check_equal(
      out,
      "angle: alpha",
      tilt_step_bound(DirectorFunction::angle, flat, still, directors, zero, dpsi, 1.),
      1.);
    check_equal(
      out,
      "sine: alpha",
      tilt_step_bound(DirectorFunction::sine, flat, still, directors, zero, dpsi, 1.),
      1.);
  }
  return finish_tally(out);
}
