#pragma once

// What the tests at the extremes share (stability_extremes.cc, swing_extremes.cc): a
// scene run that may stop (run_guarded: it finishes, or stops with a SimulationError
// whose message is printed; anything else is a failure), the checks every such run gets
// (that outcome; every field of statistics.csv and probes.csv a finite number, also in a
// run that stopped) and the figures read back from its files (steps, the energy's growth
// and scale, the probes' largest displacement).

#include "test_support.h"

#include <chrono>
#include <cstdlib>

namespace clothsim::test
{
  // A mesh generated from copies of the project's `geo_files` (meshes/; the first is the
  // mesh's .geo, the others what it includes) in `directory`, emptied first: a fresh .msh
  // every run, none in the source tree. Returns the .msh path to give as 'Mesh file'.
  inline std::string
  scratch_mesh(const std::filesystem::path    &directory,
               const std::vector<std::string> &geo_files)
  {
    std::filesystem::remove_all(directory);
    std::filesystem::create_directories(directory);
    for (const std::string &file : geo_files)
      std::filesystem::copy_file(source_path("meshes/" + file), directory / file);
    return (directory / geo_files.front()).replace_extension(".msh").string();
  }

  // Checks that every field of `file` (but the columns named in `text_columns`) is a
  // finite number and every row has the header's number of fields. Returns the number of
  // bad fields; prints the first. The distances from the obstacles may be +inf: none is
  // left in the scene ('Obstacle k/Removed at').
  inline unsigned int
  count_bad_fields(ConditionalOStream             &pcout,
                   const std::string              &file,
                   const std::vector<std::string> &text_columns)
  {
    if (!std::filesystem::exists(file))
      {
        pcout << "  FAIL  " << file << " was not written" << std::endl;
        return 1;
      }
    const Csv    csv = read_csv(file);
    unsigned int bad = 0;
    for (unsigned int r = 0; r < csv.rows.size(); ++r)
      {
        const auto &row = csv.rows[r];
        if (row.size() != csv.header.size())
          {
            if (bad++ == 0)
              pcout << "  FAIL  " << file << ": row " << r + 1 << " has " << row.size()
                    << " fields, the header " << csv.header.size() << std::endl;
            continue;
          }
        for (unsigned int c = 0; c < row.size(); ++c)
          {
            if (std::find(text_columns.begin(), text_columns.end(), csv.header[c]) !=
                text_columns.end())
              continue;
            const char  *begin     = row[c].c_str();
            char        *end       = nullptr;
            const double value     = std::strtod(begin, &end);
            const bool   unbounded = csv.header[c] == "contact_min_distance" ||
                                   csv.header[c] == "contact_surface_distance";
            if (row[c].empty() || *end != '\0' ||
                !(std::isfinite(value) || (unbounded && value > 0.)))
              if (bad++ == 0)
                pcout << "  FAIL  " << file << ": row " << r + 1 << ", " << csv.header[c]
                      << " = '" << row[c] << "' is not a finite number" << std::endl;
          }
      }
    return bad;
  }

  // A run at an extreme setting: how it ended and what its files say.
  struct GuardedRun
  {
    bool        finished = false;
    bool        stopped  = false; // SimulationError
    std::string message;          // its message, or another exception's
    RunSummary  summary;          // the solver's counts, if it finished
    double      final_max_u  = std::numeric_limits<double>::quiet_NaN(); // if finished
    double      seconds      = 0.;
    bool        files_read   = false; // both CSV files written and every field finite
    int         steps        = -1;    // the last step written
    double      time_reached = 0.;
    double      probe_max_u  = 0.;   // largest |u| at the probes over the rows written
    double      growth       = 0.;   // max_n>0 E_n - E_0, J (0 without steps)
    double      step_growth  = 0.;   // max_n E_n+1 - E_n, J (0 without steps)
    double      deviation    = 0.;   // max_n |E_n - E_0|, J
    double      scale        = 0.;   // S = max_n (K + W + |P|), J
    bool        passed       = true; // every check on this run held
  };

  // Steps, time, energy growth and the probes' largest displacement from the files a run
  // wrote (also when it stopped).
  inline void
  read_run_files(const std::filesystem::path &directory, GuardedRun &run)
  {
    const Csv statistics = read_csv(directory / "statistics.csv");
    if (statistics.rows.empty())
      return;
    const unsigned int last = statistics.rows.size() - 1;
    run.steps               = std::lround(statistics.number(last, "step"));
    run.time_reached        = statistics.number(last, "time");
    const double initial    = statistics.number(0, "total_energy");
    double       previous   = initial;
    run.growth              = last > 0 ? -std::numeric_limits<double>::max() : 0.;
    run.step_growth         = run.growth;
    for (unsigned int r = 0; r < statistics.rows.size(); ++r)
      {
        const double total = statistics.number(r, "total_energy");
        run.deviation      = std::max(run.deviation, std::abs(total - initial));
        if (r > 0)
          {
            run.growth      = std::max(run.growth, total - initial);
            run.step_growth = std::max(run.step_growth, total - previous);
          }
        previous  = total;
        run.scale = std::max(run.scale,
                             statistics.number(r, "kinetic_energy") +
                               statistics.number(r, "elastic_energy") +
                               std::abs(statistics.number(r, "potential_energy")));
      }
    const Csv probes = read_csv(directory / "probes.csv");
    for (unsigned int r = 0; r < probes.rows.size(); ++r)
      {
        const double ux = probes.number(r, "ux"), uy = probes.number(r, "uy"),
                     uz = probes.number(r, "uz");
        run.probe_max_u =
          std::max(run.probe_max_u, std::sqrt(ux * ux + uy * uy + uz * uz));
      }
    run.files_read = true;
  }

  // Runs `parameter_file` with `overrides` into `directory` (emptied first) and checks
  // a. that it finished, or stopped with a SimulationError with a message (printed); any
  //    other exception fails;
  // b. that statistics.csv and probes.csv hold finite numbers only (but the probe names).
  // Then reads the run's figures from its files (if they passed b).
  inline GuardedRun
  run_guarded(ConditionalOStream             &pcout,
              const std::string              &parameter_file,
              const std::vector<std::string> &overrides,
              const std::filesystem::path    &directory,
              const MPI_Comm                  communicator)
  {
    std::filesystem::remove_all(directory);
    GuardedRun run;
    const auto start = std::chrono::steady_clock::now();
    try
      {
        const SceneRun scene_run =
          run_scene(parameter_file, overrides, directory.string(), communicator);
        run.finished    = true;
        run.summary     = scene_run.summary;
        run.final_max_u = scene_run.displacement.linfty_norm();
      }
    catch (const SimulationError &error)
      {
        run.stopped = true;
        run.message = error.what();
      }
    catch (const std::exception &error)
      {
        run.message =
          std::string("exception other than SimulationError: ") + error.what();
      }
    catch (...)
      {
        run.message = "unknown exception";
      }
    run.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!run.message.empty())
      pcout << "  " << (run.stopped ? "stopped: " : "") << run.message << std::endl;

    run.passed &=
      check(pcout,
            run.finished || (run.stopped && !run.message.empty()),
            std::string("outcome: ") + (run.finished  ? "finished"
                                        : run.stopped ? "stopped with a SimulationError"
                                                      : "crashed out of the run"));
    const unsigned int bad =
      count_bad_fields(pcout, (directory / "statistics.csv").string(), {}) +
      count_bad_fields(pcout, (directory / "probes.csv").string(), {"probe"});
    run.passed &= check_below(pcout, "non-finite or malformed fields written", bad, 0.5);
    if (bad == 0)
      read_run_files(directory, run);
    return run;
  }

  // No energy gained: the total energy grows neither from its initial value (max_n E_n -
  // E_0) by `from_initial` (J) or more nor from step to step (max_n E_n+1 - E_n) by
  // `per_step` or more.
  inline bool
  check_no_energy_gain(ConditionalOStream &pcout,
                       const GuardedRun   &run,
                       const double        from_initial,
                       const double        per_step)
  {
    bool holds =
      check_below(pcout, "energy growth max E_n - E_0, J", run.growth, from_initial);
    holds &= check_below(pcout,
                         "energy growth per step max E_n+1 - E_n, J",
                         run.step_growth,
                         per_step);
    return holds;
  }

  // "finished", "stopped" or "CRASHED".
  inline std::string
  outcome_name(const GuardedRun &run)
  {
    return run.finished ? "finished" : run.stopped ? "stopped" : "CRASHED";
  }

  // A number in scientific notation with `digits` decimals.
  inline std::string
  scientific(const double value, const int digits = 2)
  {
    std::ostringstream out;
    out << std::scientific << std::setprecision(digits) << value;
    return out.str();
  }
} // namespace clothsim::test
