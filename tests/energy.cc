// Energy behaviour of the time integration, on scenes run in-process through the
// executable's entry point:
// 1. Free fall (tests/scenes/free_fall.prm: unpinned, undamped): the sheet keeps its
// shape (elastic
//    energy zero to round-off) and every vertex follows backward Euler's discrete free
//    fall u_n = -g t_n (t_n + dt) / 2 to round-off (relative 1e-10). Its distance from
//    the exact -g t²/2 is g t dt / 2: first order in dt, as backward Euler must be.
// 2. The damped hanging sheet: the total energy (kinetic + elastic + gravity) never
// increases from
//    one step to the next (backward Euler dissipates; the pins do no work).

#include "test_support.h"

#include <cmath>

using namespace clothsim;
using namespace clothsim::test;

int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &pcout  = env.pcout;
  const std::string   output = scratch_directory("clothsim-energy");
  bool                passed = true;

  // 1. Free fall.
  if (run_clothsim({source_path("tests/scenes/free_fall.prm"),
                    "--output-dir",
                    output + "/free_fall"}) != 0)
    return 1;
  {
    const auto   probes = read_csv(output + "/free_fall/probes.csv");
    const auto   stats  = read_csv(output + "/free_fall/statistics.csv");
    const double g = 9.81, dt = 0.01;
    double       worst_discrete = 0., worst_offset = 0., worst_lateral = 0.;
    for (unsigned int r = 0; r < probes.rows.size(); ++r)
      {
        const double t          = probes.number(r, "time");
        const double uz         = probes.number(r, "uz");
        const double discrete   = -0.5 * g * t * (t + dt);
        const double continuous = -0.5 * g * t * t;
        if (t > 0.)
          {
            worst_discrete =
              std::max(worst_discrete, std::abs(uz - discrete) / std::abs(discrete));
            // uz - (-g t²/2) = -g t dt / 2 exactly for backward Euler.
            worst_offset = std::max(worst_offset,
                                    std::abs((uz - continuous) - (-0.5 * g * t * dt)) /
                                      (0.5 * g * t * dt));
          }
        worst_lateral = std::max({worst_lateral,
                                  std::abs(probes.number(r, "ux")),
                                  std::abs(probes.number(r, "uy"))});
      }
    double worst_elastic = 0.;
    for (unsigned int r = 0; r < stats.rows.size(); ++r)
      worst_elastic =
        std::max(worst_elastic, std::abs(stats.number(r, "elastic_energy")));
    const double final_time = probes.number(probes.rows.size() - 1, "time");
    pcout << "free fall: " << probes.rows.size() << " probe rows up to t = " << final_time
          << " s\n  worst relative deviation from the discrete free fall "
          << worst_discrete
          << "\n  worst relative deviation of (u - (-g t²/2)) from -g t dt/2 "
          << worst_offset << "\n  largest lateral displacement " << worst_lateral
          << " m, largest elastic energy " << worst_elastic << " J" << std::endl;
    passed = passed && final_time > 0.499 && worst_discrete < 1e-10 &&
             worst_offset < 1e-8 && worst_lateral < 1e-12 && worst_elastic < 1e-20;
  }

  // 2. Damped hanging sheet, first 0.5 s: total energy non-increasing.
  if (run_clothsim({source_path("params/hanging-sheet.prm"),
                    "--set",
                    "Time/End time=0.5",
                    "--set",
                    "Output/Write VTK=false",
                    "--output-dir",
                    output + "/damped"}) != 0)
    return 1;
  {
    const auto stats        = read_csv(output + "/damped/statistics.csv");
    double     largest_rise = -1e300;
    double     energy_scale = 0.;
    for (unsigned int r = 0; r < stats.rows.size(); ++r)
      energy_scale =
        std::max(energy_scale, std::abs(stats.number(r, "potential_energy")));
    for (unsigned int r = 1; r < stats.rows.size(); ++r)
      largest_rise =
        std::max(largest_rise,
                 stats.number(r, "total_energy") - stats.number(r - 1, "total_energy"));
    const double drop = stats.number(0, "total_energy") -
                        stats.number(stats.rows.size() - 1, "total_energy");
    pcout << "damped hanging sheet: " << stats.rows.size() - 1
          << " steps, largest step-to-step rise of the total energy " << largest_rise
          << " J (energy scale " << energy_scale << " J), total dissipated " << drop
          << " J" << std::endl;
    // Round-off allowance: 1e-9 of the energy scale.
    passed = passed && largest_rise <= 1e-9 * energy_scale && drop > 0.;
  }

  return finish(pcout, passed);
}
