#pragma once

// What every test program uses (test_support.h adds running scenes):
// - set-up: Environment (MPI, the communicator, an output stream on rank 0), the paths of
//   the source tree and of scratch directories, finish() and finish_tally() for the
//   closing line and the exit code;
// - checks: one line per check, "  ok    " or "  FAIL  " followed by what was measured
//   and, for a value against a bound, the value and the bound (check, check_below,
//   check_above, check_at_most, check_at_least, check_equal, check_near,
//   check_decreasing, check_convergence; WorstCase for the worst of many samples). Every
//   check is counted in tally();
// - small numerics: extreme eigenvalues of a small symmetric matrix, the Euclidean norm
//   of an element vector, observed orders of convergence.
// Reading CSV files is in csv.h (also used by the helpers that do not link deal.II).

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include "app/mpi_session.h"
#include "csv.h"
#include "solvers/blas_kernels.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace clothsim::test
{
  using namespace dealii;

  // ---------------------------------------------------------------------------------
  // Set-up

  // A file of the source tree, e.g. source_path("params/hanging-sheet.prm").
  inline std::string
  source_path(const std::string &relative)
  {
    return std::string(CLOTHSIM_SOURCE_DIR) + "/" + relative;
  }

  // A directory named `name` in the system's temporary directory (not created).
  inline std::string
  scratch_directory(const std::string &name)
  {
    return (std::filesystem::temp_directory_path() / name).string();
  }

  // A test program's set-up: MPI (one thread per process), MPI_COMM_WORLD, an output
  // stream that prints on rank 0, and the BLAS' kernels chosen as the clothsim executable
  // chooses them (solvers/blas_kernels.h), so that scenes run in the test program
  // compute what they compute there.
  struct Environment
  {
    Environment(int &argc, char **&argv)
      : mpi(argc, argv)
      , communicator(MPI_COMM_WORLD)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    {
      clothsim::select_blas_kernels();
    }

    clothsim::MpiSession mpi;
    const MPI_Comm       communicator;
    ConditionalOStream   pcout;
  };

  // Prints the verdict, PASSED or FAILED, and returns the program's exit code.
  inline int
  finish(ConditionalOStream &out, const bool passed)
  {
    out << (passed ? "PASSED" : "FAILED") << std::endl;
    return passed ? 0 : 1;
  }

  // ---------------------------------------------------------------------------------
  // Checks

  // The checks a program ran and how many of them failed (on this rank).
  struct Tally
  {
    unsigned int n_checks   = 0;
    unsigned int n_failures = 0;
  };

  inline Tally &
  tally()
  {
    static Tally counts;
    return counts;
  }

  // One check: prints "  ok    what" or "  FAIL  what", counts it and returns `holds`.
  // A check that holds is printed where `out` is active (rank 0); one that fails on
  // every rank, marked with the rank where `out` is not active.
  inline bool
  check(ConditionalOStream &out, const bool holds, const std::string &what)
  {
    ++tally().n_checks;
    if (!holds)
      ++tally().n_failures;
    if (out.is_active())
      out << (holds ? "  ok    " : "  FAIL  ") << what << std::endl;
    else if (!holds)
      out.get_stream() << "  FAIL  [rank "
                       << (Utilities::MPI::job_supports_mpi()
                             ? Utilities::MPI::this_mpi_process(MPI_COMM_WORLD)
                             : 0)
                       << "] " << what << std::endl;
    return holds;
  }

  // Prints "N of M checks passed" from the tally and returns the exit code (0 if no
  // check failed).
  inline int
  finish_tally(ConditionalOStream &out)
  {
    out << tally().n_checks - tally().n_failures << " of " << tally().n_checks
        << " checks passed" << std::endl;
    return tally().n_failures == 0 ? 0 : 1;
  }

  namespace internal
  {
    // A value against a bound: "what: value relation bound", 6 significant digits (also
    // left set on `out`).
    inline bool
    check_bound(ConditionalOStream &out,
                const bool          holds,
                const std::string  &what,
                const double        value,
                const char         *relation,
                const double        bound)
    {
      out << std::setprecision(6);
      std::ostringstream line;
      line << std::setprecision(6) << what << ": " << value << ' ' << relation << ' '
           << bound;
      return check(out, holds, line.str());
    }
  } // namespace internal

  // value < bound.
  inline bool
  check_below(ConditionalOStream &out,
              const std::string  &what,
              const double        value,
              const double        bound)
  {
    return internal::check_bound(out, value < bound, what, value, "<", bound);
  }

  // value > bound.
  inline bool
  check_above(ConditionalOStream &out,
              const std::string  &what,
              const double        value,
              const double        bound)
  {
    return internal::check_bound(out, value > bound, what, value, ">", bound);
  }

  // value <= bound.
  inline bool
  check_at_most(ConditionalOStream &out,
                const std::string  &what,
                const double        value,
                const double        bound)
  {
    return internal::check_bound(out, value <= bound, what, value, "<=", bound);
  }

  // value >= bound.
  inline bool
  check_at_least(ConditionalOStream &out,
                 const std::string  &what,
                 const double        value,
                 const double        bound)
  {
    return internal::check_bound(out, value >= bound, what, value, ">=", bound);
  }

  // value == expected: "what = value (expected expected)", numbers to 17 digits.
  template <typename T>
  bool
  check_equal(ConditionalOStream &out,
              const std::string  &what,
              const T            &value,
              const T            &expected)
  {
    std::ostringstream line;
    line << std::setprecision(17) << what << " = " << value << " (expected " << expected
         << ")";
    return check(out, value == expected, line.str());
  }

  // |value - expected| <= tolerance: "what = value (expected expected +- tolerance)",
  // 16 digits.
  inline bool
  check_near(ConditionalOStream &out,
             const std::string  &what,
             const double        value,
             const double        expected,
             const double        tolerance)
  {
    std::ostringstream line;
    line << std::setprecision(16) << what << " = " << value << " (expected " << expected
         << " +- " << tolerance << ")";
    return check(out, std::abs(value - expected) <= tolerance, line.str());
  }

  // Observed order of convergence between two successive levels (mesh size halved).
  inline double
  observed_order(const double coarse_error, const double fine_error)
  {
    return std::log2(coarse_error / fine_error);
  }

  // Errors of successive refinement levels: each smaller than the one before.
  inline bool
  check_decreasing(ConditionalOStream        &out,
                   const std::string         &name,
                   const std::vector<double> &errors)
  {
    bool holds = true;
    for (unsigned int level = 1; level < errors.size(); ++level)
      holds &= check_below(out,
                           name + ": error ratio e_" + std::to_string(level) + " / e_" +
                             std::to_string(level - 1),
                           errors[level] / errors[level - 1],
                           1.);
    return holds;
  }

  // A convergence study: errors decreasing, observed order at the last pair at least
  // `order`, and the finest error (described by `finest`) below `bound`.
  inline bool
  check_convergence(ConditionalOStream        &out,
                    const std::string         &name,
                    const std::vector<double> &errors,
                    const double               order,
                    const std::string         &finest,
                    const double               bound)
  {
    const unsigned int n     = errors.size();
    bool               holds = check_decreasing(out, name, errors);
    holds &= check_above(out,
                         name + ": observed order at the last pair",
                         observed_order(errors[n - 2], errors[n - 1]),
                         order);
    holds &= check_below(out,
                         name + ": " + finest + " at the finest level",
                         errors.back(),
                         bound);
    return holds;
  }

  // The worst of many sampled values against a bound (value <= bound; NaN fails): the
  // first five failures are printed as they happen, with where they happened, and
  // report() prints the worst value as one check.
  struct WorstCase
  {
    std::string  name;
    double       bound;
    double       worst      = 0.;
    unsigned int n_failures = 0;

    void
    record(ConditionalOStream &out, const double value, const std::string &where)
    {
      if (std::isnan(value) || value > worst)
        worst = value;
      if (!(value <= bound))
        {
          if (n_failures < 5)
            out << "FAILED " << name << ": " << value << " > " << bound << '\n' << where;
          ++n_failures;
        }
    }

    bool
    report(ConditionalOStream &out) const
    {
      std::ostringstream line;
      line.precision(out.get_stream().precision());
      line << name << ": worst " << worst << " (bound " << bound << ")";
      if (n_failures > 0)
        line << ", FAILED " << n_failures << " times";
      return check(out, n_failures == 0, line.str());
    }
  };

  // ---------------------------------------------------------------------------------
  // Small numerics

  // Euclidean norm of an element vector.
  template <std::size_t n>
  double
  l2_norm(const std::array<double, n> &v)
  {
    double sum = 0.;
    for (const double x : v)
      sum += x * x;
    return std::sqrt(sum);
  }

  // (smallest, largest) eigenvalue of the symmetric matrix `entries` (LAPACK).
  template <std::size_t n>
  std::pair<double, double>
  extreme_eigenvalues(const std::array<std::array<double, n>, n> &entries)
  {
    LAPACKFullMatrix<double> matrix(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        matrix(i, j) = entries[i][j];
    matrix.compute_eigenvalues();
    double smallest = std::numeric_limits<double>::infinity(), largest = 0.;
    for (unsigned int i = 0; i < n; ++i)
      {
        smallest = std::min(smallest, matrix.eigenvalue(i).real());
        largest  = std::max(largest, matrix.eigenvalue(i).real());
      }
    return {smallest, largest};
  }
} // namespace clothsim::test
