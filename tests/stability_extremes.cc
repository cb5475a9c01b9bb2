// Stability at the extremes (issue 6): short runs of the default hanging sheet
// (params/hanging-sheet.prm: 1 m² cotton, 2,798 vertices, two pinned top corners,
// gravity, backward Euler at dt = 1/60 s, Rayleigh damping α = 0.1 1/s, β = 0.001 s),
// each with one setting pushed to an extreme, 0.25 s unless said otherwise:
// 1. Stiffness: Young's modulus 1e-2, 1, 1e2, 1e4, 1e6 times the default 0.821 MPa
//    (backward Euler); the implicit midpoint rule at 1e-2 and 1e6.
// 2. Damping: none (backward Euler; midpoint rule), very high (α = 100 1/s, β = 1 s). The
//    default damping is the baseline run of 1 (E x 1).
// 3. Time steps: 1e-5 s (2e-3 s, 200 steps), 1e-3 s (0.05 s), 0.1 s (0.5 s, 5 steps; also
//    at E x 1e-2 and E x 1e6). 1/60 s is the baseline.
// 4. Poisson's ratio 0 and 0.49.
// 5. Nearly inextensible: E x 1e4 on the mass-spring model, and the membrane at E x 1e4
//    with ν = 0.49.
// 6. Poorly shaped triangles: meshes/sliver-sheet.geo (100 x 5 cells, right triangles of
//    legs 0.01 and 0.2 m, aspect ratio 20; the mesh is generated from a copy of the .geo
//    in the scratch directory), at the default and at E x 1e-2 (large stretches of the
//    slivers). Checked first: the largest aspect ratio (longest edge over shortest
//    altitude) is above 15.
// 7. Explicit integration beyond its critical step: the mass-spring model with velocity
//    Verlet at 1.5 x the estimated critical step (0.03 s), and at a fixed 1e-3 s (16 x;
//    also symplectic Euler, and the membrane with velocity Verlet).
// Every case must:
// a. finish, or stop with a SimulationError with a message (printed); any other
//    exception is a failure. The cases of 7 must stop (the divergence is detected);
// b. write no NaN or Inf: every field of statistics.csv and probes.csv (but the probe
//    names) parses as a finite number, also in a run that stopped;
// c. if it finished: the largest displacement component at the end below 1 m + g T²/2
//    (free fall over the run plus the sheet's size: a loose bound against garbage);
// d. implicit integrators (no external work: the pins are fixed, gravity's potential is
//    in total_energy): the total energy does not grow, neither from its initial value
//    (max_n E_n - E_0) nor from step to step (max_n E_n+1 - E_n), within
//    1e-6 S + 1e-15 J, where S = max_n (K + W + |P|) is the run's energy scale. The
//    energies span eight orders of magnitude across the stiffnesses (S = 3.5e-8 J at
//    E x 1e6, 0.79 J at E x 1e-2), so the tolerance is relative: an absolute 1e-6 J
//    would exceed the whole energy of the stiff sheets. The Newton tolerances (residual
//    1e-9 N absolute, 1e-8 relative, displacement 1e-6 m) leave energy errors of the
//    order of residual x update, below 1e-12 J; measured: no step gains more than
//    1e-10 S (E x 1e6: 2.4e-18 J at S = 3.5e-8 J), most lose energy. Backward Euler
//    dissipates (exactly so for a convex energy; the membrane in compression is not
//    convex, but no growth was measured). The midpoint rule without damping conserves
//    quadratic energies only: for the membrane its energy error is O(dt²) and oscillates
//    without drift (measured on the hanging sheet over 0.25 s: largest E - E_0 = 5.4e-5,
//    1.4e-5, 3.6e-6 J at dt = 1/60, 1/120, 1/240 s, the same with Newton tolerances of
//    1e-12; 7e-4 S at 1/60 s); for that case the bound is |E - E_0| < 5e-3 S. With the
//    default damping the midpoint runs dissipate and get the strict check.
// e. the cases of 7: no kinetic or elastic energy above 1e9 J written before the stop.
// A run's outcome, steps, largest probe displacement and energy growth are printed in a
// table at the end. The runs and the checks a, b and d are in extreme_runs.h (shared with
// swing_extremes.cc).

#include <deal.II/dofs/dof_handler.h>

#include "extreme_runs.h"

#include <algorithm>

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  namespace fs = std::filesystem;

  const std::string default_prm = source_path("params/hanging-sheet.prm");
  const fs::path    root        = scratch_directory("clothsim-stability");
  const double      young       = 0.821e6; // Pa, the default
  const double      gravity     = 9.81;    // m/s²

  enum class EnergyCheck
  {
    none,        // explicit: no energy claim
    dissipative, // E_n - E_0 and E_n+1 - E_n below 1e-6 S
    bounded      // undamped midpoint rule: |E_n - E_0| below 5e-3 S
  };

  struct Case
  {
    std::string              name;     // table label and output directory
    std::string              settings; // what is extreme
    std::vector<std::string> overrides;
    double                   end_time;
    bool                     must_stop = false;
    EnergyCheck              energy    = EnergyCheck::dissipative;
  };

  std::string
  young_times(const double factor)
  {
    return "Material/Young's modulus=" + number(factor * young);
  }

  const std::vector<std::string> no_damping = {"Damping/Mass proportional=0",
                                               "Damping/Stiffness proportional=0"};

  GuardedRun
  run_case(ConditionalOStream &pcout, const Case &c)
  {
    pcout << c.name << " (" << c.settings << ")" << std::endl;
    const fs::path directory = root / c.name;
    // a. finished or stopped cleanly; b. nothing non-finite written.
    GuardedRun outcome =
      run_guarded(pcout,
                  default_prm,
                  join({"Time/End time=" + number(c.end_time), "Output/Progress=off"},
                       c.overrides),
                  directory,
                  MPI_COMM_WORLD);
    bool &passed = outcome.passed;
    // a. the explicit cases beyond the limit stopped.
    if (c.must_stop)
      passed &=
        check(pcout, outcome.stopped, "the divergence is detected (SimulationError)");
    if (!outcome.files_read)
      return outcome;

    // e. a diverging explicit run is stopped before it writes absurd energies (the
    //    sheet's physical energies are below 0.1 J; a blow-up grows about 1e4-fold per
    //    step, and an area check every 10 steps once let 3e278 J through).
    if (c.must_stop)
      {
        const Csv statistics = read_csv((directory / "statistics.csv").string());
        double    largest    = 0.;
        for (unsigned int r = 0; r < statistics.rows.size(); ++r)
          largest = std::max({largest,
                              std::abs(statistics.number(r, "kinetic_energy")),
                              std::abs(statistics.number(r, "elastic_energy"))});
        passed &=
          check_below(pcout, "largest energy written before the stop, J", largest, 1e9);
      }

    // c. a plausible final state.
    if (outcome.finished)
      passed &= check_below(pcout,
                            "largest displacement component at the end, m",
                            outcome.final_max_u,
                            1. + 0.5 * gravity * c.end_time * c.end_time);

    // d. energy.
    if (c.energy == EnergyCheck::dissipative)
      {
        const double tolerance = 1e-6 * outcome.scale + 1e-15;
        passed &= check_no_energy_gain(pcout, outcome, tolerance, tolerance);
      }
    else if (c.energy == EnergyCheck::bounded)
      passed &= check_below(pcout,
                            "energy error max |E_n - E_0|, J",
                            outcome.deviation,
                            5e-3 * outcome.scale + 1e-15);
    return outcome;
  }

  // Largest aspect ratio (longest edge over shortest altitude, L_max² / 2A) over the
  // triangles of a scene's mesh.
  double
  largest_aspect_ratio(const std::vector<std::string> &overrides)
  {
    const auto loaded  = load_scene(default_prm, overrides, MPI_COMM_WORLD);
    double     largest = 0.;
    for (const auto &cell : loaded->model->get_dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          double longest = 0.;
          for (unsigned int v = 0; v < 3; ++v)
            longest =
              std::max(longest, cell->vertex(v).distance(cell->vertex((v + 1) % 3)));
          largest = std::max(largest, longest * longest / (2. * cell->measure()));
        }
    return Utilities::MPI::max(largest, MPI_COMM_WORLD);
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &pcout  = env.pcout;
  bool                passed = true;

  // 6. The sliver mesh, generated from a copy of the .geo in the scratch directory (a
  //    fresh .msh every run, none in the source tree).
  const std::string sliver_mesh =
    "Mesh/Mesh file=" + scratch_mesh(root / "sliver-mesh", {"sliver-sheet.geo"});
  pcout << "mesh quality" << std::endl;
  pcout << "  sheet.msh: largest aspect ratio " << largest_aspect_ratio({}) << std::endl;
  passed &= check_above(pcout,
                        "sliver-sheet.msh: largest aspect ratio",
                        largest_aspect_ratio({sliver_mesh}),
                        15.);

  // 7. The mass-spring model's critical step under velocity Verlet (as in
  //    explicit_integrators.cc).
  const std::vector<std::string> verlet_springs = {"Model=mass-spring",
                                                   "Time/Integrator=velocity verlet"};
  double                         critical_step  = 0.;
  {
    const auto loaded = load_scene(default_prm, verlet_springs, env.communicator);
    VectorType u;
    loaded->model->initialize_ghosted(u);
    critical_step =
      estimate_critical_step(*loaded->model, loaded->parameters(), u).estimate;
    pcout << "  mass-spring, velocity Verlet: estimated critical step " << critical_step
          << " s" << std::endl;
  }

  const std::string midpoint = "Time/Integrator=implicit midpoint";
  const double      base_end = 0.25;
  std::vector<Case> cases    = {
       // 1. Stiffness.
    {"E x 1e-2", "E = 8.21e3 Pa, backward Euler", {young_times(1e-2)}, base_end},
    {"baseline", "defaults: E = 0.821 MPa, dt = 1/60 s", {}, base_end},
    {"E x 1e2", "E = 8.21e7 Pa", {young_times(1e2)}, base_end},
    {"E x 1e4", "E = 8.21e9 Pa", {young_times(1e4)}, base_end},
    {"E x 1e6", "E = 8.21e11 Pa", {young_times(1e6)}, base_end},
    {"midpoint E x 1e-2", "implicit midpoint", {midpoint, young_times(1e-2)}, base_end},
    {"midpoint E x 1e6", "implicit midpoint", {midpoint, young_times(1e6)}, base_end},
    // 2. Damping.
    {"no damping", "alpha = beta = 0, backward Euler", no_damping, base_end},
    {"midpoint no damping",
        "alpha = beta = 0, implicit midpoint",
        join({midpoint}, no_damping),
        base_end,
        false,
        EnergyCheck::bounded},
    {"high damping",
        "alpha = 100 1/s, beta = 1 s",
        {"Damping/Mass proportional=100", "Damping/Stiffness proportional=1"},
        base_end},
    // 3. Time steps.
    {"dt 1e-5", "dt = 1e-5 s, 200 steps", {"Time/Time step=1e-5"}, 2e-3},
    {"dt 1e-3", "dt = 1e-3 s, 50 steps", {"Time/Time step=1e-3"}, 0.05},
    {"dt 0.1", "dt = 0.1 s, 5 steps", {"Time/Time step=0.1"}, 0.5},
    {"dt 0.1 E x 1e-2", "dt = 0.1 s", {"Time/Time step=0.1", young_times(1e-2)}, 0.5},
    {"dt 0.1 E x 1e6", "dt = 0.1 s", {"Time/Time step=0.1", young_times(1e6)}, 0.5},
    // 4. Poisson's ratio.
    {"nu 0", "Poisson ratio 0", {"Material/Poisson ratio=0"}, base_end},
    {"nu 0.49", "Poisson ratio 0.49", {"Material/Poisson ratio=0.49"}, base_end},
    // 5. Nearly inextensible.
    {"springs E x 1e4",
        "mass-spring, E = 8.21e9 Pa",
        {"Model=mass-spring", young_times(1e4)},
        base_end},
    {"nu 0.49 E x 1e4",
        "membrane, E = 8.21e9 Pa, nu = 0.49",
        {"Material/Poisson ratio=0.49", young_times(1e4)},
        base_end},
    // 6. Slivers.
    {"slivers", "sliver-sheet.msh (aspect 20)", {sliver_mesh}, base_end},
    {"slivers E x 1e-2",
        "sliver-sheet.msh, E = 8.21e3 Pa",
        {sliver_mesh, young_times(1e-2)},
        base_end},
    // 7. Explicit beyond the critical step.
    {"verlet 1.5 dt_crit",
        "mass-spring, velocity Verlet, dt = " + scientific(1.5 * critical_step) + " s",
        join(verlet_springs, {"Time/Time step=" + number(1.5 * critical_step)}),
        0.03,
        true,
        EnergyCheck::none},
    {"verlet 1e-3",
        "mass-spring, velocity Verlet, dt = 1e-3 s",
        join(verlet_springs, {"Time/Time step=1e-3"}),
        0.05,
        true,
        EnergyCheck::none},
    {"symplectic 1e-3",
        "mass-spring, symplectic Euler, dt = 1e-3 s",
        {"Model=mass-spring", "Time/Integrator=symplectic euler", "Time/Time step=1e-3"},
        0.05,
        true,
        EnergyCheck::none},
    {"membrane verlet 1e-3",
        "fem, velocity Verlet, dt = 1e-3 s",
        {"Time/Integrator=velocity verlet", "Time/Time step=1e-3"},
        0.05,
        true,
        EnergyCheck::none}};

  std::vector<GuardedRun> outcomes;
  for (const Case &c : cases)
    {
      outcomes.push_back(run_case(pcout, c));
      passed &= outcomes.back().passed;
    }

  // The table.
  pcout << std::endl
        << std::left << std::setw(22) << "case" << std::setw(46) << "settings"
        << std::setw(10) << "outcome" << std::right << std::setw(6) << "steps"
        << std::setw(9) << "t, s" << std::setw(11) << "max|u|, m" << std::setw(11)
        << "dE_step, J" << std::setw(10) << "S, J" << std::setw(11) << "dE_step/S"
        << std::setw(7) << "s"
        << "  check" << std::endl;
  for (unsigned int i = 0; i < cases.size(); ++i)
    {
      const Case       &c = cases[i];
      const GuardedRun &o = outcomes[i];
      pcout << std::left << std::setw(22) << c.name << std::setw(46) << c.settings
            << std::setw(10) << outcome_name(o) << std::right << std::setw(6) << o.steps
            << std::setw(9) << std::setprecision(4) << o.time_reached << std::setw(11)
            << scientific(o.probe_max_u) << std::setw(11)
            << (c.energy == EnergyCheck::none ? "-" : scientific(o.step_growth))
            << std::setw(10) << scientific(o.scale) << std::setw(11)
            << (c.energy == EnergyCheck::none || o.scale == 0.
                  ? "-"
                  : scientific(o.step_growth / o.scale))
            << std::setw(7) << std::fixed << std::setprecision(1) << o.seconds
            << std::defaultfloat << "  " << (o.passed ? "ok" : "FAIL") << std::endl;
      if (!o.finished)
        pcout << "    " << o.message << std::endl;
    }
  pcout << "(steps, t: the last step written; max|u|: largest displacement at the "
           "probes over the rows written (the explicit runs stop before their first "
           "output time, 1/30 s, so only t = 0 is there); dE_step: "
           "largest energy gain of a step, negative if every step lost energy; S: the "
           "run's energy scale max (K + W + |P|))"
        << std::endl;

  return finish(pcout, passed);
}
