// The explicit integrators (time/explicit_stepper.h) on the default hanging sheet:
// 1. Energy: undamped, fixed pins, 0.05 s from rest at three steps dt, dt/2, dt/4; the
//    largest drift of the total energy K + W + P from its initial value must shrink with
//    the observed order of the method: 2 for velocity Verlet, 1 for symplectic Euler
//    (its velocities are the leapfrog's half-step velocities, so the energy of the pair
//    it stores is off by O(dt) — bounded, without drift).
// 2. Stability limit: with the scene's Rayleigh damping (ζ ≈ 2.8 at ω_max, which cuts
//    the critical step fivefold), a run at 0.9 of the estimated critical step completes
//    and one at 1.5 of it is stopped with a SimulationError: a run beyond the limit is
//    reported, not left to explode. Both for the mass-spring and for the membrane (fem)
//    model. (Measured: the mass-spring run diverges at 1.2 already, within 90 steps;
//    the membrane's at 1.2 grows too slowly to show within 0.1 s.)

#include "test_support.h"

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  const std::string default_prm = source_path("params/hanging-sheet.prm");
  const std::string directory   = scratch_directory("clothsim-explicit-integrators");

  bool
  check_energy(ConditionalOStream &pcout, const MPI_Comm communicator)
  {
    bool passed = true;
    for (const std::string integrator : {"velocity verlet", "symplectic euler"})
      {
        std::vector<double> drifts;
        for (const double dt : {2e-4, 1e-4, 5e-5})
          {
            run_scene(default_prm,
                      {"Model=mass-spring",
                       "Time/Integrator=" + integrator,
                       "Time/Time step=" + std::to_string(dt),
                       "Time/End time=0.05",
                       "Damping/Mass proportional=0",
                       "Damping/Stiffness proportional=0"},
                      directory,
                      communicator);
            const EnergyDrift energy = energy_drift(directory + "/statistics.csv");
            pcout << "  " << integrator << ", dt = " << dt << " s: largest energy drift "
                  << energy.drift << " J (largest kinetic energy "
                  << energy.largest_kinetic << " J)" << std::endl;
            drifts.push_back(energy.drift);
          }
        const double order    = integrator == "velocity verlet" ? 2. : 1.;
        const double observed = observed_order(drifts[1], drifts[2]);
        passed &= check_above(pcout,
                              integrator + ": observed order of the energy drift",
                              observed,
                              order - 0.2);
        passed &= check_below(pcout,
                              integrator + ": observed order of the energy drift",
                              observed,
                              order + 0.5);
      }
    return passed;
  }

  bool
  check_stability_limit(ConditionalOStream &pcout, const MPI_Comm communicator)
  {
    bool passed = true;
    for (const std::string model : {"mass-spring", "fem"})
      {
        const std::vector<std::string> scene = {"Model=" + model,
                                                "Time/Integrator=velocity verlet",
                                                "Output/Write VTK=false"};
        auto       loaded = load_scene(default_prm, scene, communicator);
        VectorType u;
        loaded->model->initialize_ghosted(u);
        const CriticalStep critical =
          estimate_critical_step(*loaded->model, loaded->parameters(), u);
        pcout << "  " << model << ": critical step " << critical.estimate
              << " s (omega_max " << critical.omega_max << " 1/s, damping ratio "
              << critical.damping_ratio << "), Gershgorin bound "
              << critical.gershgorin_bound << " s" << std::endl;
        passed &= check_below(pcout,
                              model + ": Gershgorin bound / estimate",
                              critical.gershgorin_bound / critical.estimate,
                              1. + 1e-12);
        for (const double factor : {0.9, 1.5})
          {
            std::vector<std::string> overrides = scene;
            overrides.push_back("Time/Time step=" +
                                std::to_string(factor * critical.estimate));
            overrides.push_back("Time/End time=0.03");
            bool diverged = false;
            try
              {
                run_scene(default_prm, overrides, directory, communicator);
              }
            catch (const SimulationError &error)
              {
                diverged = true;
                pcout << "  stopped: " << error.what() << std::endl;
              }
            std::ostringstream what;
            what << model << " at " << factor << " x the critical step: "
                 << (diverged ? "diverged, stopped" : "completed");
            passed &= check(pcout, diverged == (factor > 1.), what.str());
          }
      }
    return passed;
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment env(argc, argv);
  env.pcout << "1. energy drift of the undamped hanging sheet (mass-spring)" << std::endl;
  bool passed = check_energy(env.pcout, env.communicator);
  env.pcout << "2. stability limit with the scene's damping" << std::endl;
  passed &= check_stability_limit(env.pcout, env.communicator);
  return finish(env.pcout, passed);
}
