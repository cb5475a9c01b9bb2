// Arc-length continuation ('Time/Integrator = arc length') through the snap-through of
// a shallow sinusoidal arch (params/benchmarks/shallow-arch.prm): span L = 1, rise
// e = 0.01, hinged ends, D = 10 N·m, E h = 9e5 N/m, nu = 0, load q0 lambda sin(pi x/L)
// with q0 = 20 N/m². Shallow-arch theory's closed form for the mid-height a = alpha r,
// r = sqrt(D/(E h)), epsilon = e/r = 3:
//   q0 lambda = (D pi^4 r / L^4) [ (epsilon - alpha) + alpha (epsilon^2 - alpha^2)/4 ],
// limit points at alpha = ±sqrt((epsilon^2 - 4)/3) (Timoshenko & Gere 1961, §7.8).
// Checked:
// - every point of the path (probe 'mid', per step) against the closed form: |lambda -
//   lambda(alpha)| within 0.25 % of the limit load (measured 0.143 %; it tends to 0.15 %
//   under refinement, 0.121, 0.143, 0.151 % on 32, 64, 128 cells: the shell is not
//   shallow-arch theory, whose neglected terms are of order (pi e/L)² = 1e-3);
// - both limit loads, from a parabola through the three path points around each, within
//   0.25 % of the upper one of the closed form's (measured 0.16 and 0.10 %);
// - the path goes through: the arch ends inverted, at lambda = 1 exactly, its mid-span
//   deflection within 0.25 % of the closed form's (measured 0.17 %);
// - a snap-back: the axial displacement at the quarter point, u(L/4) = pi (e² - a²)/(8 L)
//   by the same theory (the axial force is uniform), rises to a = 0 and falls back, so
//   between a = 0 and the valley the load and that displacement fall together; the path
//   must follow the closed form to 1e-3 of its largest value (measured 3.2e-4) and
//   contain such steps;
// - fixed arc lengths ('Adaptive load steps = false') follow the same curve.

#include "csv.h"
#include "test_support.h"

#include <cmath>

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  const double D = 10., Eh = 9e5, L = 1., e = 0.01, q0 = 20.;
  const double r       = std::sqrt(D / Eh);
  const double epsilon = e / r;
  const double scale   = D * std::pow(M_PI, 4) * r / std::pow(L, 4) / q0;

  // The closed form's load factor at mid-height alpha r.
  double
  load_factor(const double alpha)
  {
    return scale * ((epsilon - alpha) + alpha * (epsilon * epsilon - alpha * alpha) / 4.);
  }

  struct PathPoint
  {
    double lambda, alpha;
    double quarter_ux; // m, the axial displacement at x = L/4
  };

  // The path from probes.csv (probes 'mid' and 'quarter', in this order per step).
  std::vector<PathPoint>
  read_path(const std::string &directory)
  {
    const Csv              probes = read_csv(directory + "/probes.csv");
    std::vector<PathPoint> path;
    for (unsigned int row = 0; row < probes.rows.size(); ++row)
      if (probes.rows[row][probes.column("probe")] == "mid")
        path.push_back(
          {probes.number(row, "time"), (e + probes.number(row, "uz")) / r, 0.});
      else
        path.back().quarter_ux = probes.number(row, "ux");
    return path;
  }

  // The extreme value of the parabola lambda(alpha) through path points k-1, k, k+1.
  double
  parabola_extremum(const std::vector<PathPoint> &path, const unsigned int k)
  {
    const double x0 = path[k - 1].alpha, x1 = path[k].alpha, x2 = path[k + 1].alpha;
    const double y0 = path[k - 1].lambda, y1 = path[k].lambda, y2 = path[k + 1].lambda;
    // Newton's divided differences: y = y0 + d1 (x - x0) + d2 (x - x0)(x - x1).
    const double d1     = (y1 - y0) / (x1 - x0);
    const double d2     = ((y2 - y1) / (x2 - x1) - d1) / (x2 - x0);
    const double vertex = 0.5 * (x0 + x1) - d1 / (2. * d2);
    return y0 + d1 * (vertex - x0) + d2 * (vertex - x0) * (vertex - x1);
  }
} // namespace

int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &pcout = env.pcout;

  const double alpha_limit = std::sqrt((epsilon * epsilon - 4.) / 3.);
  const double peak = load_factor(alpha_limit), valley = load_factor(-alpha_limit);
  // The closed form's inverted state at lambda = 1 (bisection on alpha < -alpha_limit,
  // where lambda(alpha) falls monotonically).
  double low = -2. * epsilon, high = -alpha_limit;
  for (int i = 0; i < 200; ++i)
    (load_factor(0.5 * (low + high)) > 1. ? low : high) = 0.5 * (low + high);
  const double alpha_end = 0.5 * (low + high);
  pcout << "closed form: limit loads " << peak << " and " << valley
        << " (load factors), at lambda = 1 alpha = " << alpha_end << std::endl;

  bool passed = true;
  for (const bool adaptive : {true, false})
    {
      const std::string name      = adaptive ? "adaptive" : "fixed";
      const std::string directory = scratch_directory("clothsim-arc-length-" + name);
      const SceneRun    run = run_scene(source_path("params/benchmarks/shallow-arch.prm"),
                                     {"Time/Adaptive load steps=" +
                                         std::string(adaptive ? "true" : "false")},
                                     directory,
                                     env.communicator);
      const std::vector<PathPoint> path  = read_path(directory);
      double                       worst = 0., worst_axial = 0.;
      unsigned int                 top = 0, bottom = 0, snapping_back = 0;
      for (unsigned int k = 0; k < path.size(); ++k)
        {
          worst = std::max(worst, std::abs(path[k].lambda - load_factor(path[k].alpha)));
          // u(L/4) = π (e² - a²) / (8 L), a = α r.
          const double a = path[k].alpha * r;
          worst_axial =
            std::max(worst_axial,
                     std::abs(path[k].quarter_ux - M_PI * (e * e - a * a) / (8. * L)));
          if (k > 0 && path[k].lambda < path[k - 1].lambda &&
              path[k].quarter_ux < path[k - 1].quarter_ux)
            ++snapping_back;
          // The first local maximum of the load, and the first minimum after it.
          if (k == 0 || k + 1 == path.size())
            continue;
          const bool at_most =
            path[k].lambda >= path[k - 1].lambda && path[k].lambda >= path[k + 1].lambda;
          const bool at_least =
            path[k].lambda <= path[k - 1].lambda && path[k].lambda <= path[k + 1].lambda;
          if (top == 0 && at_most)
            top = k;
          else if (top > 0 && bottom == 0 && at_least)
            bottom = k;
        }
      pcout << name << " arc lengths: " << path.size() - 1 << " steps, "
            << run.summary.newton_iterations << " corrector iterations, "
            << run.summary.retries << " halvings; largest |lambda - lambda(alpha)| "
            << worst << std::endl;
      passed &= check_below(pcout,
                            name + ": path off the closed form / limit load",
                            worst / peak,
                            2.5e-3);
      passed &=
        check_below(pcout,
                    name + ": quarter point's u_x off the closed form / its largest",
                    worst_axial / (M_PI * e * e / (8. * L)),
                    1e-3);
      passed &=
        check(pcout,
              snapping_back > 0,
              name + ": the path snaps back in u_x(L/4) (" +
                std::to_string(snapping_back) + " steps with load and u_x falling)");
      const bool interior =
        top > 0 && top + 1 < path.size() && bottom > top && bottom + 1 < path.size();
      passed &=
        check(pcout, interior, name + ": the path has a peak and a valley inside it");
      if (interior)
        {
          passed &= check_near(pcout,
                               name + ": upper limit load",
                               parabola_extremum(path, top),
                               peak,
                               2.5e-3 * peak);
          passed &= check_near(pcout,
                               name + ": lower limit load",
                               parabola_extremum(path, bottom),
                               valley,
                               2.5e-3 * peak);
        }
      passed &=
        check_near(pcout, name + ": last load factor", path.back().lambda, 1., 1e-14);
      const double deflection = alpha_end * r - e;
      passed &= check_near(pcout,
                           name + ": mid-span deflection at lambda = 1",
                           path.back().alpha * r - e,
                           deflection,
                           2.5e-3 * std::abs(deflection));
    }
  return finish(pcout, passed);
}
