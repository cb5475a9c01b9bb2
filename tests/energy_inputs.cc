// The energy given to the cloth from outside its equations, in the energy balance:
// the work of prescribed motion (statistics.csv's prescribed_work; time/stepper_core.h,
// physics/contact_work.cc) and the energy of the strain limit's corrections
// (strain_limit_energy). Balance: total + dissipated - both, from the first row to the
// last.
// 1. Pins driven along a circle (tests/scenes/moving_pins.prm, damped): with the
//    average vector field, which keeps the energy, the balance is below 0.5 % of the
//    work at dt = 5 ms and falls at second order (at least 8 times from dt to dt/4);
//    with BDF2 it is negative (its damping of the motion) and falls at least 4 times.
// 2. The cantilever rolled into a circle by a prescribed end rotation (static, 20 load
//    steps): the work is the strip's bending energy E I θ²/(2L) = 2π² E I/L within
//    0.1 %, the balance within 1e-6 of it (the trapezoidal rule over the reactions, M
//    linear in θ).
// 3. A sheet resting on a plane that rises with z = t²/2 (m, s), frictionless: the
// plane's
//    work lifts it by 0.125 m and gives it 0.5 m/s by t = 0.5 s, m g h + m v²/2 =
//    0.135125 J within 1 % (the barrier's gap changes), the balance within 1e-3 of it.
// 4. A frictionless plane driven at 2 m/s into a free flat sheet (no gravity): the
//    barrier's bounce is elastic, so the sheet leaves at 4 m/s and the plane's work is
//    m (2V)²/2 = 0.8 J; resolved (dt = 62.5 us) within 0.5 %, the balance within 0.5 %
//    of it and at least 5 times smaller than at dt = 250 us (BDF2's damping of the
//    impact).
// 5. A scene that prescribes no motion has no prescribed_work column.
// 6. The hanging sheet as springs with a strain limit of 2 % (backward Euler, 0.5 s):
//    the limit cannot hold the strain at the point pins (springs there stay stretched
//    beyond 10 %), and its corrections add over 0.1 J, which the step's damping takes
//    out again; with them in the balance, the balance falls (below -0.1 J), as backward
//    Euler's must.
// 7. A ball driven at 15 m/s into the sheet, the adaptive barrier stiffness on: the
//    energy of the stiffness raises (stiffness_raise_energy) grows in exactly the steps
//    whose stiffness rose where its barrier has energy at the step's end, and by no more
//    than that energy.

#include "csv.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>

using namespace clothsim::test;

namespace
{
  struct Balance
  {
    double work    = 0.; // J, prescribed_work at the end
    double balance = 0.; // J
  };

  // Runs clothsim with `arguments` and reads the balance from statistics.csv.
  Balance
  run_balance(const std::string &name, std::vector<std::string> arguments)
  {
    const std::string output = scratch_directory("clothsim-energy-inputs-" + name);
    arguments.insert(arguments.end(),
                     {"--set", "Output/Progress=off", "--output-dir", output});
    if (run_clothsim(arguments) != 0)
      throw std::runtime_error(name + ": the run failed");
    const Csv          statistics = read_csv(output + "/statistics.csv");
    const unsigned int last       = statistics.rows.size() - 1;
    double             balance    = 0.;
    for (const unsigned int row : {0u, last})
      {
        double sum = statistics.number(row, "total_energy") -
                     statistics.number(row, "prescribed_work");
        for (const std::string &column : statistics.header)
          if (column.size() > 11 && column.substr(column.size() - 11) == "_dissipated")
            sum += statistics.number(row, column);
        balance += row == 0 ? -sum : sum;
      }
    return {statistics.number(last, "prescribed_work"), balance};
  }

  std::vector<std::string>
  with(const std::string &file, const std::vector<std::string> &settings)
  {
    std::vector<std::string> arguments = {source_path(file)};
    for (const std::string &setting : settings)
      arguments.insert(arguments.end(), {"--set", setting});
    return arguments;
  }
} // namespace

int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &out = env.pcout;

  // 1. Moving pins.
  for (const std::string integrator : {"average vector field", "bdf2"})
    {
      const auto run_at = [&integrator](const double dt) {
        return run_balance(integrator.substr(0, 4) + "-" + number(dt),
                           with("tests/scenes/moving_pins.prm",
                                {"Time/Integrator=" + integrator,
                                 "Time/Time step=" + number(dt)}));
      };
      const Balance coarse = run_at(0.005), fine = run_at(0.00125);
      out << integrator << ": work " << coarse.work << " and " << fine.work
          << " J, balance " << coarse.balance << " and " << fine.balance << " J"
          << std::endl;
      if (integrator == "bdf2")
        {
          check_below(out, "bdf2, dt = 5 ms: balance, J", coarse.balance, 0.);
          check_below(out, "bdf2, dt = 1.25 ms: balance, J", fine.balance, 0.);
          check_above(out,
                      "bdf2: the balance's fall from dt = 5 ms to 1.25 ms",
                      coarse.balance / fine.balance,
                      4.);
        }
      else
        {
          check_below(out,
                      "average vector field, dt = 5 ms: |balance| / work",
                      std::abs(coarse.balance) / coarse.work,
                      5e-3);
          check_above(
            out,
            "average vector field: the balance's fall from dt = 5 ms to 1.25 ms",
            std::abs(coarse.balance / fine.balance),
            8.);
        }
    }

  // 2. The end rotation: E I = 100, L = 10, θ = 2π.
  const Balance rotation =
    run_balance("end-rotation",
                with("params/benchmarks/cantilever-end-rotation.prm", {}));
  const double bending = 2. * M_PI * M_PI * 100. / 10.;
  check_near(out, "end rotation: work, J", rotation.work, bending, 1e-3 * bending);
  check_below(out,
              "end rotation: |balance| / work",
              std::abs(rotation.balance) / rotation.work,
              1e-6);

  // 3. The rising plane.
  const Balance lift   = run_balance("rising-plane",
                                   with("params/contact/sheet-on-sphere.prm",
                                        {"Mesh/Mesh file=../../meshes/swing-21.msh",
                                           "Obstacle 1/Shape=plane",
                                           "Obstacle 1/Center=0, 0, -0.004",
                                           "Obstacle 1/Axis=0, 0, 1",
                                           "Obstacle 1/Friction=0",
                                           "Obstacle 1/Translation=0; 0; 0.5*t*t",
                                           "Contact/Self contact=false",
                                           "Time/End time=0.5",
                                           "Time/Time step=0.0025",
                                           "Output/Write VTK=false"}));
  const double  lifted = 0.1 * 9.81 * 0.125 + 0.5 * 0.1 * 0.5 * 0.5;
  check_near(out, "rising plane: work, J", lift.work, lifted, 0.01 * lifted);
  check_below(out,
              "rising plane: |balance| / work",
              std::abs(lift.balance) / lift.work,
              1e-3);

  // 4. The plane struck into the free sheet.
  const auto strike = [](const double dt) {
    return run_balance("strike-" + number(dt),
                       with("params/contact/sheet-on-sphere.prm",
                            {"Mesh/Mesh file=../../meshes/swing-21.msh",
                             "Obstacle 1/Shape=plane",
                             "Obstacle 1/Center=0, 0, -0.02",
                             "Obstacle 1/Axis=0, 0, 1",
                             "Obstacle 1/Friction=0",
                             "Obstacle 1/Translation=0; 0; 2*t",
                             "Contact/Self contact=false",
                             "Contact/Adaptive barrier stiffness=false",
                             "Loads/Gravity=0, 0, 0",
                             "Time/End time=0.04",
                             "Time/Time step=" + number(dt),
                             "Nonlinear solver/Truncation error fraction=0",
                             "Output/Write VTK=false"}));
  };
  const Balance struck = strike(2.5e-4), resolved = strike(6.25e-5);
  const double  bounce = 0.5 * 0.1 * 4. * 4.;
  check_near(out, "strike, dt = 62.5 us: work, J", resolved.work, bounce, 5e-3 * bounce);
  check_below(out,
              "strike, dt = 62.5 us: |balance| / work",
              std::abs(resolved.balance) / resolved.work,
              5e-3);
  check_above(out,
              "strike: the balance's fall from dt = 250 us to 62.5 us",
              struck.balance / resolved.balance,
              5.);

  // 5. No motion, no column.
  const std::string        still = scratch_directory("clothsim-energy-inputs-still");
  std::vector<std::string> arguments =
    with("tests/scenes/moving_pins.prm",
         {"Constraints/Pinned displacement=0; 0; 0", "Time/End time=0.04"});
  arguments.insert(arguments.end(),
                   {"--set", "Output/Progress=off", "--output-dir", still});
  bool column = true;
  if (run_clothsim(arguments) == 0)
    {
      column = false;
      for (const std::string &name : read_csv(still + "/statistics.csv").header)
        column = column || name == "prescribed_work";
    }
  check(out, !column, "pins held still: no prescribed_work column");

  // 6. The strain limit.
  const std::string limited = scratch_directory("clothsim-energy-inputs-limit");
  arguments                 = with("params/hanging-sheet-mass-spring.prm",
                   {"Mass spring/Strain limit=0.02", "Time/End time=0.5"});
  arguments.insert(arguments.end(),
                   {"--set", "Output/Progress=off", "--output-dir", limited});
  if (check(out, run_clothsim(arguments) == 0, "strain limit: the run completes"))
    {
      const Csv          statistics = read_csv(limited + "/statistics.csv");
      const unsigned int last       = statistics.rows.size() - 1;
      const double       added      = statistics.number(last, "strain_limit_energy");
      const double       balance    = statistics.number(last, "total_energy") -
                             statistics.number(0, "total_energy") +
                             statistics.number(last, "damping_dissipated") - added;
      check_above(out, "strain limit: the energy its corrections added, J", added, 0.1);
      check_below(out, "strain limit: balance, J", balance, -0.1);
    }

  // 7. Raises of the barrier stiffness.
  const std::string raised = scratch_directory("clothsim-energy-inputs-raises");
  arguments                = with("params/contact/sheet-on-sphere.prm",
                   {"Mesh/Mesh file=../../meshes/swing-21.msh",
                                   "Obstacle 1/Radius=0.1",
                                   "Obstacle 1/Center=0.5, 0.5, -0.15",
                                   "Obstacle 1/Translation=0; 0; 15*t",
                                   "Contact/Adaptive barrier stiffness=true",
                                   "Time/End time=0.1",
                                   "Output/Write VTK=false"});
  arguments.insert(arguments.end(),
                   {"--set", "Output/Progress=off", "--output-dir", raised});
  if (check(out, run_clothsim(arguments) == 0, "stiffness raises: the run completes"))
    {
      const Csv    statistics  = read_csv(raised + "/statistics.csv");
      unsigned int rows_raised = 0, mismatches = 0;
      double       largest_excess = 0.; // J
      for (unsigned int row = 1; row < statistics.rows.size(); ++row)
        {
          // A raise adds energy where its barrier has energy at the step's end.
          bool rose = false;
          for (const std::string term : {"contact", "self_contact"})
            rose = rose || (statistics.number(row, term + "_barrier_stiffness") >
                              statistics.number(row - 1, term + "_barrier_stiffness") &&
                            statistics.number(row, term + "_energy") > 0.);
          const double added = statistics.number(row, "stiffness_raise_energy") -
                               statistics.number(row - 1, "stiffness_raise_energy");
          rows_raised += rose ? 1 : 0;
          mismatches += rose != (added > 0.) ? 1 : 0;
          // (1 - old/new) of the end state's barrier energy: never more than that energy.
          // (Taken at the step's start it was 0.092 J against 0.073 J in one step.)
          largest_excess = std::max(largest_excess,
                                    added - statistics.number(row, "contact_energy") -
                                      statistics.number(row, "self_contact_energy"));
        }
      check_above(
        out,
        "stiffness raises: steps that raised a stiffness with energy in its barrier",
        rows_raised,
        0.5);
      check_below(out,
                  "stiffness raises: steps whose raise energy grew without a raise, or "
                  "did not grow with one",
                  mismatches,
                  0.5);
      check_below(out,
                  "stiffness raises: largest raise energy of a step over the barrier "
                  "energy at its end, J",
                  largest_excess,
                  1e-12);
    }
  return finish_tally(out);
}
