// Support reactions (reactions.csv: per output state and pinned or clamped group, the
// force its pins exert on the cloth and the moment about the group's centroid, the held
// rotations' moments included), checked by equilibrium, which they must satisfy to the
// solver's tolerance:
//  1. the cantilever strip under end shear (params/benchmarks/cantilever-end-shear.prm,
//     P = 4 N up at x = L = 10 m, clamped at x = 0), linear static: the root carries
//     F = (0, 0, -P) and M = (0, P L, 0) = (0, 40, 0) N·m about its centre (0, 0.5, 0),
//     all of it through the clamped director angles (the root's vertex forces have no
//     lever about the root's axis); 1e-7 relative (measured 4e-9: the linear reaction
//     K0 u - f takes K0 u by central differences);
//  2. the same, nonlinear, at full load: F = (0, 0, -P) to 1e-6 relative (measured
//  2e-12),
//     and M_y = P (L + u_x,tip), the load's lever arm shortened by the tip's pull-in, to
//     1e-4 (measured 6.4e-6: the tip edge's vertices pull in by slightly different
//     amounts on the unstructured mesh, the probe measures its middle);
//  3. the same strip, linear static, under a point moment (0, M, 0) = (0, 40, 0) N·m at
//  the
//     tip's mid vertex (Loads/Point moments) instead of the shear: the root carries no
//     force and the moment (0, -M, 0), to 1e-7; the strip bends as the beam,
//     u_z = -M x²/(2 EI), at mid-span to 1e-4 (measured 6e-6) and at the tip, where the
//     couple acts, to 2e-3 (measured 7e-4);
//  4. the clamped square plate under its weight, full and quarter model
//     (params/benchmarks/clamped-plate*.prm): the edges carry the weight, 1.5 kg/m² x
//     9.81 m/s² x 1 m² = 14.715 N, the quarter's clamped edges a quarter of it; 1e-9
//     relative.

#include "csv.h"
#include "test_support.h"

#include <cmath>

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  // The last row of `group` in DIR/reactions.csv: X, Y, Z, Fx, Fy, Fz, Mx, My, Mz.
  std::array<double, 9>
  last_reaction(const std::string &directory, const std::string &group)
  {
    const Csv             csv = read_csv(directory + "/reactions.csv");
    std::array<double, 9> values{};
    bool                  found = false;
    for (unsigned int r = 0; r < csv.rows.size(); ++r)
      if (csv.rows[r].at(csv.column("group")) == group)
        {
          unsigned int k = 0;
          for (const char *name : {"X", "Y", "Z", "Fx", "Fy", "Fz", "Mx", "My", "Mz"})
            values[k++] = csv.number(r, name);
          found = true;
        }
    if (!found)
      throw std::runtime_error("no reaction of group " + group + " in " + directory);
    return values;
  }
} // namespace

int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &pcout  = env.pcout;
  bool                passed = true;

  const auto run = [&](const std::string              &file,
                       const std::vector<std::string> &overrides,
                       const std::string              &name) {
    const std::string directory = scratch_directory("clothsim-reactions-" + name);
    SceneRun          result    = run_scene(source_path("params/benchmarks/" + file),
                                overrides,
                                directory,
                                env.communicator);
    return std::make_pair(std::move(result), directory);
  };
  const auto report = [&](const std::string &what, const std::array<double, 9> &r) {
    pcout << what << ": centre (" << r[0] << ", " << r[1] << ", " << r[2] << "), F ("
          << r[3] << ", " << r[4] << ", " << r[5] << ") N, M (" << r[6] << ", " << r[7]
          << ", " << r[8] << ") N·m" << std::endl;
  };
  const auto distance = [](const std::array<double, 9> &r,
                           const unsigned int           first,
                           const Tensor<1, 3>          &expected) {
    return std::hypot(r[first] - expected[0],
                      r[first + 1] - expected[1],
                      r[first + 2] - expected[2]) /
           expected.norm();
  };
  const double P = 4., L = 10.;

  {
    const auto [linear, directory] =
      run("cantilever-end-shear.prm", {"Time/Integrator=linear static"}, "linear");
    const auto r = last_reaction(directory, "clamped");
    report("cantilever, linear: root", r);
    passed &= check_below(pcout,
                          "linear: root centre, |c - (0, 0.5, 0)| [m]",
                          std::hypot(r[0], r[1] - 0.5, r[2]),
                          1e-10);
    passed &= check_below(pcout,
                          "linear: |F - (0, 0, -P)| / P",
                          distance(r, 3, Tensor<1, 3>({0., 0., -P})),
                          1e-7);
    passed &= check_below(pcout,
                          "linear: |M - (0, P L, 0)| / (P L)",
                          distance(r, 6, Tensor<1, 3>({0., P * L, 0.})),
                          1e-7);
  }
  {
    const auto [nonlinear, directory] = run("cantilever-end-shear.prm", {}, "nonlinear");
    const auto   r                    = last_reaction(directory, "clamped");
    const double pull_in              = nonlinear.probe_displacement("tip")[0];
    report("cantilever, nonlinear: root", r);
    pcout << "tip u_x " << pull_in << " m" << std::endl;
    passed &= check_below(pcout,
                          "nonlinear: |F - (0, 0, -P)| / P",
                          distance(r, 3, Tensor<1, 3>({0., 0., -P})),
                          1e-6);
    passed &= check_below(pcout,
                          "nonlinear: |M - (0, P (L + u_x,tip), 0)| / (P (L + u_x,tip))",
                          distance(r, 6, Tensor<1, 3>({0., P * (L + pull_in), 0.})),
                          1e-4);
  }
  {
    // A point moment M = (0, 40, 0) N·m at the tip's mid vertex instead of the shear: a
    // couple of forces on its triangles, no net force.
    const double M = 40.;
    const auto [couple, directory] =
      run("cantilever-end-shear.prm",
          {"Time/Integrator=linear static",
           "Loads/Line forces=",
           "Loads/Point moments=tip: 0, 40, 0",
           "Output/Probes=tip: 10, 0.5, 0; mid: 5, 0.5, 0"},
          "point-moment");
    const auto r = last_reaction(directory, "clamped");
    report("cantilever, point moment: root", r);
    passed &= check_below(pcout,
                          "point moment: |F| / (M / L)",
                          std::hypot(r[3], r[4], r[5]) / (M / L),
                          1e-7);
    passed &= check_below(pcout,
                          "point moment: |M_root - (0, -M, 0)| / M",
                          distance(r, 6, Tensor<1, 3>({0., -M, 0.})),
                          1e-7);
    // Away from the point, the beam's u_z = -M x² / (2 EI) (EI = 100).
    const double EI = 100.;
    passed &=
      check_below(pcout,
                  "point moment: mid-span |u_z / (-M (L/2)² / (2 EI)) - 1|",
                  std::abs(couple.probe_displacement("mid")[2] / (-M * L * L / 8. / EI) -
                           1.),
                  1e-4);
    passed &=
      check_below(pcout,
                  "point moment: tip |u_z / (-M L² / (2 EI)) - 1|",
                  std::abs(couple.probe_displacement("tip")[2] / (-M * L * L / 2. / EI) -
                           1.),
                  2e-3);
  }
  const double weight = 1.5 * 9.81;
  {
    const auto [full, directory] = run("clamped-plate.prm", {}, "plate");
    const auto r                 = last_reaction(directory, "edges");
    report("clamped plate: edges", r);
    passed &= check_below(pcout,
                          "plate: |F - (0, 0, W)| / W",
                          distance(r, 3, Tensor<1, 3>({0., 0., weight})),
                          1e-9);
  }
  {
    const auto [quarter, directory] = run("clamped-plate-quarter.prm", {}, "quarter");
    const auto r                    = last_reaction(directory, "outer");
    report("quarter plate: outer edges", r);
    report("quarter plate: symmetry line x = 0.5", last_reaction(directory, "sym_x"));
    passed &= check_below(pcout,
                          "quarter: |F_z - W/4| / (W/4)",
                          std::abs(r[5] - weight / 4.) / (weight / 4.),
                          1e-9);
  }
  return finish(pcout, passed);
}
