// The average-vector-field step ('Time/Integrator = average vector field';
// time/step_problem.h) on the swinging sheet of params/benchmarks/swing.prm (1 m², E h =
// 1,200 N/m, 0.1 kg/m², pinned at two corners, released flat under gravity, undamped, dt
// = 1/60 s) on its N = 21 mesh (generated in the scratch directory). Nothing works on the
// sheet from outside, so its total energy E = K + W + P is constant; S = max_n (K + W +
// |P|) is the run's energy scale (about 1 J).
// 1. Membrane only (swing-membrane.prm), Newton solved tightly (residual 1e-11 N, steps
//    1e-10 m), 0.6 s (the sheet folds from about 0.15 s on): |E_n - E_0| stays below
//    1e-6 S with no step halvings. The St. Venant-Kirchhoff membrane is quartic and
//    gravity linear, which the two-point Gauss average integrates exactly; what is left
//    is the Newton tolerance (measured 1.7e-7 S). The implicit midpoint rule on the same
//    run must gain more than 0.1 S, or the test would not tell the two apart (measured:
//    its energy grows to 140 times the scale by 0.6 s; the midpoint rule is not
//    energy-stable for stiff nonlinear elasticity, Simo & Tarnow, ZAMP 43, 1992).
// 2. With the scene's cotton bending and Newton stopping (3 % of the truncation error),
//    the whole 2 s: it finishes, writes no NaN, and |E_n - E_0| stays below 1.5e-2 S
//    (measured 6.0e-3 S: the bending energy is not polynomial, and with 'Director
//    function = angle' it jumps where a director turns past the back of its face; a
//    blow-up gains orders of magnitude more). It halves steps (3 times, measured);
//    statistics.csv's `retries`, summed, counts those halvings.

#include "extreme_runs.h"

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  namespace fs = std::filesystem;

  const fs::path root = scratch_directory("clothsim-energy-conserving-step");

  bool
  check_membrane(ConditionalOStream &pcout, const std::string &mesh)
  {
    const std::vector<std::string> settings = {
      "Mesh/Mesh file=" + mesh,
      "Time/End time=0.6",
      "Nonlinear solver/Truncation error fraction=0",
      "Nonlinear solver/Displacement tolerance=1e-10",
      "Nonlinear solver/Absolute tolerance=1e-11",
      "Output/Progress=off"};
    bool passed = true;
    for (const std::string integrator : {"average vector field", "implicit midpoint"})
      {
        const GuardedRun run =
          run_guarded(pcout,
                      source_path("params/benchmarks/swing-membrane.prm"),
                      join(settings, {"Time/Integrator=" + integrator}),
                      root / ("membrane " + integrator),
                      MPI_COMM_WORLD);
        if (!run.files_read)
          return false;
        pcout << "  " << integrator << ": " << run.steps << " steps, "
              << run.summary.retries << " step halvings, S = " << run.scale
              << " J, largest |E_n - E_0| = " << run.deviation / run.scale << " S"
              << std::endl;
        if (integrator == "average vector field")
          {
            passed &= run.passed;
            passed &=
              check_above(pcout, "finished (1) or stopped (0)", run.finished, 0.5);
            passed &= check_below(pcout, "step halvings", run.summary.retries, 0.5);
            passed &= check_below(pcout,
                                  "average vector field: |E_n - E_0| / S",
                                  run.deviation / run.scale,
                                  1e-6);
          }
        else if (run.finished)
          passed &= check_above(pcout,
                                "implicit midpoint: largest E_n - E_0, J",
                                run.growth,
                                0.1 * 0.985); // S of the exact motion
      }
    return passed;
  }

  bool
  check_bending(ConditionalOStream &pcout, const std::string &mesh)
  {
    const GuardedRun run    = run_guarded(pcout,
                                       source_path("params/benchmarks/swing.prm"),
                                       {"Mesh/Mesh file=" + mesh,
                                           "Time/Integrator=average vector field",
                                           "Output/Progress=off"},
                                       root / "bending",
                                       MPI_COMM_WORLD);
    bool             passed = run.passed;
    passed &= check_above(pcout, "finished (1) or stopped (0)", run.finished, 0.5);
    if (!run.files_read)
      return false;
    pcout << "  " << run.steps << " steps, " << run.summary.retries << " step halvings, "
          << double(run.summary.newton_iterations) / run.steps
          << " Newton iterations per step, S = " << run.scale << " J" << std::endl;
    passed &=
      check_below(pcout, "largest |E_n - E_0| / S", run.deviation / run.scale, 1.5e-2);
    const Csv statistics = read_csv((root / "bending" / "statistics.csv").string());
    double    retries    = 0.;
    for (unsigned int r = 0; r < statistics.rows.size(); ++r)
      retries += statistics.number(r, "retries");
    passed &= check_below(pcout,
                          "|retries summed over statistics.csv - the run's halvings|",
                          std::abs(retries - run.summary.retries),
                          0.5);
    return passed;
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &pcout = env.pcout;
  const std::string   mesh =
    scratch_mesh(root / "mesh", {"swing-21.geo", "swing-grid.geo.inc"});
  pcout << "1. membrane only, tight Newton, 0.6 s" << std::endl;
  bool passed = check_membrane(pcout, mesh);
  pcout << "2. cotton bending as shipped, 2 s" << std::endl;
  passed &= check_bending(pcout, mesh);
  return finish(pcout, passed);
}
