// The implicit integrators on the pre-stressed square membrane vibrating in its first
// mode (params/benchmarks/membrane-vibration.prm; f_11 = 2.67929 Hz, period T = 0.373234
// s):
// 1. Frequency: the implicit midpoint rule at T/80 over five periods gives f_11 within
//    1 % (zero crossings of the centre's deflection).
// 2. Numerical damping over those five periods, per integrator: the midpoint rule keeps
//    the amplitude (loss below 0.5 %), BDF2 damps less than backward Euler.
// 3. Temporal convergence: the largest error of the centre's deflection over one period
//    (0.4 s) with dt = 0.005, 0.0025, 0.00125 s against the midpoint rule at dt =
//    0.0003125 s; observed orders 1 (backward Euler) and 2 (BDF2, implicit midpoint,
//    average vector field) within ±0.15.
// 4. Energy: the midpoint rule at T/16 over 100 periods keeps the total energy within
//    0.5 % of the vibration's energy (the largest kinetic energy; the pre-stress energy
//    is a constant far larger); its average-vector-field variant conserves it to 1e-6
//    of that (the membrane is quartic, which two-point Gauss averages exactly: only the
//    Newton tolerance is left) and keeps f_11 within 1 % at T/80.
// 5. The single linearised step against full Newton (see below).
// 6. Adaptive steps with a tolerance per step (see below).
// 7. Accuracy target (error per unit step) over one period: the error at the end against
//    the fine reference is below the target, the run's estimate (its summed local
//    estimates) is below the target too and at least half the actual error, and a target
//    four times smaller gives a smaller error.

#include "test_support.h"

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  const std::string benchmark = source_path("params/benchmarks/membrane-vibration.prm");
  const std::string directory = scratch_directory("clothsim-time-integrators");
  const double      frequency = 2.6792856; // Hz
  const double      period    = 1. / frequency;

  // The centre's deflection history (time, uz) from probes.csv.
  std::vector<std::pair<double, double>>
  centre_history()
  {
    const Csv                              csv = read_csv(directory + "/probes.csv");
    std::vector<std::pair<double, double>> history;
    for (unsigned int r = 0; r < csv.rows.size(); ++r)
      history.emplace_back(csv.number(r, "time"), csv.number(r, "uz"));
    return history;
  }

  std::vector<std::pair<double, double>>
  run(const std::string &integrator, const double dt, const double end)
  {
    run_scene(benchmark,
              {"Time/Integrator=" + integrator,
               "Time/Time step=" + number(dt),
               "Time/End time=" + number(end)},
              directory,
              MPI_COMM_WORLD);
    return centre_history();
  }

  // Mean period from the downward zero crossings, and the largest |uz| in the first and
  // the last period.
  struct Oscillation
  {
    double frequency, first_amplitude, last_amplitude;
  };

  Oscillation
  analyse(const std::vector<std::pair<double, double>> &history)
  {
    std::vector<double> crossings;
    for (unsigned int i = 1; i < history.size(); ++i)
      {
        const auto [t0, w0] = history[i - 1];
        const auto [t1, w1] = history[i];
        if (w0 > 0. && w1 <= 0.)
          crossings.push_back(t0 + (t1 - t0) * w0 / (w0 - w1));
      }
    Oscillation result{0., 0., 0.};
    if (crossings.size() >= 2)
      result.frequency = (crossings.size() - 1) / (crossings.back() - crossings.front());
    const double end = history.back().first;
    for (const auto &[t, w] : history)
      {
        if (t <= period)
          result.first_amplitude = std::max(result.first_amplitude, std::abs(w));
        if (t >= end - period)
          result.last_amplitude = std::max(result.last_amplitude, std::abs(w));
      }
    return result;
  }

  bool
  check_frequency_and_damping(ConditionalOStream &pcout)
  {
    bool                passed = true;
    std::vector<double> losses;
    for (const std::string integrator :
         {"implicit midpoint", "bdf2", "backward euler", "average vector field"})
      {
        const Oscillation oscillation =
          analyse(run(integrator, period / 80., 5. * period));
        const double loss = 1. - oscillation.last_amplitude / oscillation.first_amplitude;
        pcout << "  " << integrator << " at T/80: frequency " << oscillation.frequency
              << " Hz (f_11 " << frequency << ", error "
              << 100. * (oscillation.frequency / frequency - 1.)
              << " %), amplitude lost over 4 periods " << 100. * loss << " %"
              << std::endl;
        losses.push_back(loss);
        if (integrator == "implicit midpoint" || integrator == "average vector field")
          {
            passed &= check_below(pcout,
                                  integrator + ": |f / f_11 - 1|",
                                  std::abs(oscillation.frequency / frequency - 1.),
                                  0.01);
            passed &=
              check_below(pcout, integrator + ": amplitude lost", std::abs(loss), 0.005);
          }
      }
    passed &= check_below(pcout,
                          "amplitude lost: bdf2 / backward euler",
                          losses[1] / losses[2],
                          1.);
    return passed;
  }

  // Largest |uz(t) - uz_ref(t)| over the steps of `history`, all of which are steps of
  // the reference (its step divides theirs).
  double
  largest_error(const std::vector<std::pair<double, double>> &history,
                const std::vector<std::pair<double, double>> &reference)
  {
    double       error = 0.;
    unsigned int r     = 0;
    for (const auto &[t, w] : history)
      {
        while (r + 1 < reference.size() && reference[r].first < t - 1e-9)
          ++r;
        error = std::max(error, std::abs(w - reference[r].second));
      }
    return error;
  }

  bool
  check_orders(ConditionalOStream &pcout)
  {
    const double end       = 0.4; // about one period
    const auto   reference = run("implicit midpoint", 0.0003125, end);
    bool         passed    = true;
    for (const auto &[integrator, order] :
         std::vector<std::pair<std::string, double>>{{"backward euler", 1.},
                                                     {"bdf2", 2.},
                                                     {"implicit midpoint", 2.},
                                                     {"average vector field", 2.}})
      {
        std::vector<double> errors;
        for (const double dt : {0.005, 0.0025, 0.00125})
          errors.push_back(largest_error(run(integrator, dt, end), reference));
        pcout << "  " << integrator << ": largest errors " << errors[0] << ", "
              << errors[1] << ", " << errors[2] << " m; orders "
              << observed_order(errors[0], errors[1]) << ", "
              << observed_order(errors[1], errors[2]) << std::endl;
        const double observed = observed_order(errors[1], errors[2]);
        passed &=
          check_above(pcout, integrator + ": observed order", observed, order - 0.15);
        passed &=
          check_below(pcout, integrator + ": observed order", observed, order + 0.15);
      }
    return passed;
  }

  bool
  check_energy(ConditionalOStream &pcout)
  {
    bool passed = true;
    for (const auto &[integrator, bound] :
         std::vector<std::pair<std::string, double>>{{"implicit midpoint", 0.005},
                                                     {"average vector field", 1e-6}})
      {
        run(integrator, period / 16., 100. * period);
        const EnergyDrift energy = energy_drift(directory + "/statistics.csv");
        pcout << "  " << integrator << " at T/16 over 100 periods (" << energy.steps
              << " steps): largest energy drift " << energy.drift
              << " J, vibration energy " << energy.largest_kinetic << " J" << std::endl;
        passed &= check_below(pcout,
                              integrator + ": energy drift / vibration energy",
                              energy.drift / energy.largest_kinetic,
                              bound);
      }
    return passed;
  }
  // 5. The single linearised step (Baraff & Witkin) on the default hanging sheet, 0.5 s
  // of
  //    backward Euler: its largest probe difference from the full Newton solution at the
  //    same step is larger at dt = 1/30 s than at dt = 1/240 s.
  bool
  check_single_step(ConditionalOStream &pcout)
  {
    const std::string   scene = source_path("params/hanging-sheet.prm");
    std::vector<double> differences;
    for (const double dt : {1. / 240., 1. / 30.})
      {
        std::array<SceneRun, 2> runs;
        for (unsigned int m = 0; m < 2; ++m)
          runs[m] = run_scene(scene,
                              {"Nonlinear solver/Method=" +
                                 std::string(m == 0 ? "newton" : "single step"),
                               "Time/Time step=" + number(dt),
                               "Time/End time=0.5"},
                              directory,
                              MPI_COMM_WORLD);
        const double difference =
          largest_probe_difference(runs[0],
                                   runs[1],
                                   {"top_middle", "center", "bottom_corner"});
        pcout << "  dt = " << dt << " s: single step against Newton, largest probe "
              << "difference " << difference << " m (Newton iterations per step: "
              << double(runs[0].summary.newton_iterations) / runs[0].summary.steps
              << " against 1)" << std::endl;
        differences.push_back(difference);
      }
    return check_above(pcout,
                       "single-step error at 1/30 s over that at 1/240 s",
                       differences[1] / differences[0],
                       2.);
  }
  // 6. Adaptive steps (midpoint rule and variable-step BDF2, one period of the
  //    benchmark, first step 0.05 s, far too large): the error at the end against the
  //    fine fixed-step reference shrinks with the tolerance τ and stays within 30 τ (the
  //    per-step control lets the errors of the 30-80 steps add up); the oversized first
  //    step is rejected (statistics.csv counts it) and the run still finishes.
  bool
  check_adaptive(ConditionalOStream &pcout)
  {
    const double end       = 0.4;
    const double reference = run("implicit midpoint", 0.0003125, end).back().second;
    bool         passed    = true;
    for (const std::string integrator : {"implicit midpoint", "bdf2"})
      {
        std::vector<double> errors;
        for (const double tolerance : {1e-6, 5e-7})
          {
            run_scene(benchmark,
                      {"Time/Integrator=" + integrator,
                       "Time/Adaptive time steps=true",
                       "Time/Error tolerance=" + number(tolerance),
                       "Time/Time step=0.05",
                       "Time/End time=" + number(end)},
                      directory,
                      MPI_COMM_WORLD);
            const double error = std::abs(centre_history().back().second - reference);
            const Csv    statistics = read_csv(directory + "/statistics.csv");
            double       rejected = 0., largest_estimate = 0.;
            for (unsigned int r = 0; r < statistics.rows.size(); ++r)
              {
                rejected += statistics.number(r, "rejected");
                largest_estimate =
                  std::max(largest_estimate, statistics.number(r, "error_estimate"));
              }
            pcout << "  " << integrator << ", tolerance " << tolerance
                  << " m: " << statistics.rows.size() - 1 << " steps, " << rejected
                  << " rejected, largest accepted estimate " << largest_estimate
                  << " m, error at t = " << end << " s: " << error << " m ("
                  << error / tolerance << " tolerances)" << std::endl;
            // The per-step time split adds up to no more than the run's wall time.
            double split = 0.;
            for (unsigned int r = 0; r < statistics.rows.size(); ++r)
              split += statistics.number(r, "assembly_seconds") +
                       statistics.number(r, "linear_solve_seconds");
            const double wall =
              statistics.number(statistics.rows.size() - 1, "wall_seconds");
            passed &= check_above(pcout, "assembly + linear solve seconds", split, 0.);
            passed &= check_below(pcout,
                                  "(assembly + linear solve) / wall seconds",
                                  split / wall,
                                  1.01);
            passed &= check_above(pcout, "rejected steps", rejected, 0.5);
            passed &= check_below(pcout,
                                  "largest accepted error estimate / tolerance",
                                  largest_estimate / tolerance,
                                  1. + 1e-9);
            passed &= check_below(pcout, "end error / tolerance", error / tolerance, 30.);
            errors.push_back(error);
          }
        passed &=
          check_below(pcout, "error ratio at tolerance / 2", errors[1] / errors[0], 1.);
      }
    return passed;
  }

  bool
  check_accuracy_target(ConditionalOStream &pcout)
  {
    const double end       = 0.4;
    const double reference = run("implicit midpoint", 0.0003125, end).back().second;
    bool         passed    = true;
    std::vector<double> errors;
    for (const double target : {4e-5, 1e-5})
      {
        const SceneRun result   = run_scene(benchmark,
                                          {"Time/Integrator=implicit midpoint",
                                             "Time/Accuracy target=" + number(target),
                                             "Time/Time step=0.01",
                                             "Time/End time=" + number(end)},
                                          directory,
                                          MPI_COMM_WORLD);
        const double   error    = std::abs(centre_history().back().second - reference);
        const double   estimate = result.summary.estimated_error;
        pcout << "  target " << target << " m: " << result.summary.steps << " steps, "
              << result.summary.rejected << " rejected, estimated error " << estimate
              << " m, error at t = " << end << " s: " << error << " m" << std::endl;
        passed &= check_below(pcout, "error / target", error / target, 1.);
        passed &= check_below(pcout, "estimate / target", estimate / target, 1. + 1e-9);
        passed &= check_above(pcout, "estimate / error", estimate / error, 0.5);
        errors.push_back(error);
      }
    passed &= check_below(pcout, "error ratio at target / 4", errors[1] / errors[0], 1.);
    return passed;
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &pcout = env.pcout;
  pcout << "1.-2. frequency and numerical damping over five periods" << std::endl;
  bool passed = check_frequency_and_damping(pcout);
  pcout << "3. temporal convergence" << std::endl;
  passed &= check_orders(pcout);
  pcout << "4. energy of the midpoint rule and its AVF variant" << std::endl;
  passed &= check_energy(pcout);
  pcout << "5. the single linearised step" << std::endl;
  passed &= check_single_step(pcout);
  pcout << "6. adaptive steps" << std::endl;
  passed &= check_adaptive(pcout);
  pcout << "7. accuracy target" << std::endl;
  passed &= check_accuracy_target(pcout);
  return finish(pcout, passed);
}
