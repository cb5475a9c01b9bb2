// Checks the output of the study drivers:
//   check_studies convergence DIR QUANTITY MIN_ORDER MAX_ORDER FINEST_BOUND
//     convergence.csv lists every level with the unknowns growing (space) or the step
//     halving (time); QUANTITY's observed order at the finest level lies in [MIN_ORDER,
//     MAX_ORDER] and its error there is below FINEST_BOUND (m); convergence.png is a
//     PNG, convergence.svg is there and gnuplot's script draws log axes and the reference
//     slopes of order 1 and 2.
//   check_studies sweep DIR RUNS
//     pareto.csv has RUNS settings, all completed, plus the reference (error 0); every
//     error is finite and positive; the on_front flags are exactly the runs that no
//     other run beats in both runtime and error; pareto.png is a PNG, pareto.svg is
//     there and the script labels the runtime axis.

#include "test_support.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

using namespace clothsim::test;

namespace
{
  bool
  is_png(const std::string &file)
  {
    std::ifstream in(file, std::ios::binary);
    char          signature[8] = {};
    in.read(signature, 8);
    return in && std::string(signature, 8) == "\x89PNG\r\n\x1a\n";
  }

  // The gnuplot script beside a plot (io/line_plot.h) has `part`.
  bool
  script_has(const std::string &file, const std::string &part)
  {
    std::ifstream     in(file);
    const std::string text((std::istreambuf_iterator<char>(in)),
                           std::istreambuf_iterator<char>());
    return text.find(part) != std::string::npos;
  }

  bool
  check_convergence_study(ConditionalOStream &out,
                          const std::string  &directory,
                          const std::string  &quantity,
                          const double        min_order,
                          const double        max_order,
                          const double        finest_bound)
  {
    const Csv csv    = read_csv(directory + "/convergence.csv");
    bool      passed = true;
    // The rows of the quantity, in level order.
    std::vector<unsigned int> rows;
    for (unsigned int r = 0; r < csv.rows.size(); ++r)
      if (csv.rows[r][csv.column("quantity")] == quantity)
        rows.push_back(r);
    passed &= check(out, rows.size() >= 2, quantity + ": at least two levels");
    if (rows.size() < 2)
      return false;
    for (unsigned int i = 1; i < rows.size(); ++i)
      {
        const std::string study = csv.rows[rows[i]][csv.column("study")];
        const double      ratio =
          study == "space"
                 ? csv.number(rows[i], "unknowns") / csv.number(rows[i - 1], "unknowns")
                 : csv.number(rows[i - 1], "size") / csv.number(rows[i], "size");
        passed &= check(out,
                        study == "space" ? ratio > 3. && ratio < 5. : ratio == 2.,
                        "level " + std::to_string(i) + ": " +
                          (study == "space" ? "unknowns grow about fourfold ("
                                            : "step halved (") +
                          std::to_string(ratio) + ")");
      }
    const unsigned int last  = rows.back();
    const double       order = csv.number(last, "observed_order");
    const double       error = csv.number(last, "error");
    out << "  " << quantity << " at the finest level: error " << error
        << " m, observed order " << order << " (reference "
        << csv.rows[last][csv.column("reference")] << ")" << std::endl;
    passed &= check(out,
                    order >= min_order && order <= max_order,
                    "observed order in [" + std::to_string(min_order) + ", " +
                      std::to_string(max_order) + "]");
    passed &= check(out, error < finest_bound, "finest error below the bound");
    passed &=
      check(out, is_png(directory + "/convergence.png"), "convergence.png is a PNG");
    passed &= check(out,
                    std::filesystem::exists(directory + "/convergence.svg"),
                    "convergence.svg written");
    passed &= check(out,
                    script_has(directory + "/convergence.gp", "title \"order 1\"") &&
                      script_has(directory + "/convergence.gp", "title \"order 2\"") &&
                      script_has(directory + "/convergence.gp", "set logscale x 10"),
                    "convergence.gp: log axes, reference slopes of order 1 and 2");
    return passed;
  }

  bool
  check_sweep(ConditionalOStream &out,
              const std::string  &directory,
              const unsigned int  expected_runs)
  {
    const Csv csv    = read_csv(directory + "/pareto.csv");
    bool      passed = true;
    passed &= check(out,
                    csv.rows.size() == expected_runs + 1,
                    std::to_string(expected_runs) + " runs and the reference");
    if (csv.rows.size() != expected_runs + 1)
      return false;
    const unsigned int reference = expected_runs;
    passed &= check(out,
                    csv.rows[reference][0].find("reference") != std::string::npos &&
                      csv.number(reference, "error") == 0.,
                    "the last row is the reference, error 0");
    for (unsigned int r = 0; r < expected_runs; ++r)
      {
        const double error   = csv.number(r, "error");
        const double runtime = csv.number(r, "runtime_seconds");
        passed &=
          check(out,
                csv.rows[r][csv.column("status")] == "completed" &&
                  std::isfinite(error) && error > 0. && runtime > 0.,
                "run " + std::to_string(r) + " completed, error " +
                  std::to_string(error) + " m, " + std::to_string(runtime) + " s");
        bool beaten = false;
        for (unsigned int o = 0; o < expected_runs; ++o)
          {
            const double other_error   = csv.number(o, "error");
            const double other_runtime = csv.number(o, "runtime_seconds");
            beaten =
              beaten || (o != r && other_error <= error && other_runtime <= runtime &&
                         (other_error < error || other_runtime < runtime));
          }
        const bool flagged = csv.rows[r][csv.column("on_front")] == "true";
        passed &= check(out,
                        flagged == !beaten,
                        "run " + std::to_string(r) + (beaten ? " is beaten" : " is not") +
                          " and flagged accordingly");
      }
    passed &= check(out, is_png(directory + "/pareto.png"), "pareto.png is a PNG");
    passed &= check(out,
                    script_has(directory + "/pareto.gp", "set xlabel \"runtime (s)\"") &&
                      std::filesystem::exists(directory + "/pareto.svg"),
                    "pareto.gp labels the runtime axis, pareto.svg written");
    return passed;
  }
} // namespace


int
main(int argc, char **argv)
{
  ConditionalOStream out(std::cout);
  const std::string  mode = argc > 1 ? argv[1] : "";
  bool               passed;
  if (mode == "convergence" && argc == 7)
    passed = check_convergence_study(
      out, argv[2], argv[3], std::stod(argv[4]), std::stod(argv[5]), std::stod(argv[6]));
  else if (mode == "sweep" && argc == 4)
    passed = check_sweep(out, argv[2], std::stoul(argv[3]));
  else
    {
      std::cerr << "usage: check_studies convergence DIR QUANTITY MIN MAX BOUND\n"
                   "       check_studies sweep DIR RUNS\n";
      return 2;
    }
  return finish(out, passed);
}
