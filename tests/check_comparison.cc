// Checks the output of `clothsim --compare` on the hanging sheet:
//   check_comparison DIR EXPECTED_RATIO TOLERANCE MESH_BOUND
// - both runs completed (runtimes.csv), comparison.png is a PNG, comparison.csv has
//   probe and whole-mesh rows at every output time;
// - the sag (vertical displacement of each probe at the last time) of the mass-spring
//   run over the fem run's is EXPECTED_RATIO within TOLERANCE: the small-strain theory
//   of physics/mass_spring.h makes the springs' uniaxial stiffness 8/(9(1-ν²)) of the
//   continuum's, so the expected ratio is 9(1-ν²)/8 (1 at ν = 1/3);
// - the whole-mesh largest position difference at the last time, relative to the sheet
//   size, is below MESH_BOUND.

#include "test_support.h"

#include <cmath>
#include <fstream>
#include <map>

using namespace clothsim::test;

namespace
{
  // Vertical displacement of each probe in the last rows of probes.csv.
  std::map<std::string, double>
  final_sag(const std::string &file)
  {
    const Csv                     csv = read_csv(file);
    std::map<std::string, double> sag;
    const double                  last_time = csv.number(csv.rows.size() - 1, "time");
    for (unsigned int r = 0; r < csv.rows.size(); ++r)
      if (csv.number(r, "time") == last_time)
        sag[csv.rows[r][csv.column("probe")]] = csv.number(r, "uz");
    return sag;
  }
} // namespace


int
main(int argc, char **argv)
{
  if (argc != 5)
    {
      std::cerr << "usage: check_comparison DIR EXPECTED_RATIO TOLERANCE MESH_BOUND\n";
      return 2;
    }
  const std::string  directory  = argv[1];
  const double       expected   = std::stod(argv[2]);
  const double       tolerance  = std::stod(argv[3]);
  const double       mesh_bound = std::stod(argv[4]);
  ConditionalOStream out(std::cout);
  bool               passed = true;

  const Csv runtimes = read_csv(directory + "/runtimes.csv");
  passed &= check(out, runtimes.rows.size() == 2, "runtimes.csv has one row per model");
  for (const auto &row : runtimes.rows)
    passed &= check(out,
                    row.at(runtimes.column("completed")) == "true",
                    row.at(0) + " run completed in " +
                      row.at(runtimes.column("wall_seconds")) + " s");

  std::ifstream png(directory + "/comparison.png", std::ios::binary);
  char          signature[8] = {};
  png.read(signature, 8);
  passed &=
    check(out, png && std::string(signature + 1, 3) == "PNG", "comparison.png is a PNG");

  const Csv    comparison = read_csv(directory + "/comparison.csv");
  const double last_time  = comparison.number(comparison.rows.size() - 1, "time");
  double       mesh_max   = -1.;
  for (unsigned int r = 0; r < comparison.rows.size(); ++r)
    if (comparison.number(r, "time") == last_time &&
        comparison.rows[r][comparison.column("quantity")] == "mesh_max")
      mesh_max = comparison.number(r, "relative_difference");
  passed &= check(out,
                  mesh_max >= 0. && mesh_max < mesh_bound,
                  "largest position difference at t = " + std::to_string(last_time) +
                    " s: " + std::to_string(100. * mesh_max) + " % of the sheet size < " +
                    std::to_string(100. * mesh_bound) + " %");

  const auto fem = final_sag(directory + "/fem/probes.csv");
  const auto ms  = final_sag(directory + "/mass-spring/probes.csv");
  for (const auto &[probe, sag] : fem)
    {
      const double ratio = ms.at(probe) / sag;
      passed &=
        check(out,
              std::abs(ratio - expected) < tolerance,
              "probe " + probe + ": sag fem " + std::to_string(sag) + " m, mass-spring " +
                std::to_string(ms.at(probe)) + " m, ratio " + std::to_string(ratio) +
                " = " + std::to_string(expected) + " +- " + std::to_string(tolerance));
    }
  return finish(out, passed);
}
