#pragma once

// Running a scene in-process for tests (the pattern of uniaxial_stretch.cc): load_scene
// with overrides, TimeStepper::run into a scratch output directory, and the final state
// kept for inspection (displacement, probes, energies).

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include "io/output_writer.h"
#include "scene/scene.h"
#include "time/time_stepper.h"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace clothsim::test
{
  using namespace dealii;

  // A finished run: the scene (model, probes) and its final state.
  struct SceneRun
  {
    std::unique_ptr<Scene> scene;
    RunSummary             summary;
    VectorType             displacement; // ghosted, angles re-based to zero
    VectorType             velocity;     // ghosted (zero in static mode)

    ClothModel &
    model() const
    {
      return *scene->model;
    }

    // Displacement (x, y, z) of the probe with the given name, m.
    Tensor<1, 3>
    probe_displacement(const std::string &name) const
    {
      for (const ProbeLocation &probe : scene->probes)
        if (probe.name == name)
          {
            const std::vector<double> values =
              model().gather_values(displacement,
                                    {probe.dofs[0], probe.dofs[1], probe.dofs[2]});
            return Tensor<1, 3>({values[0], values[1], values[2]});
          }
      throw std::runtime_error("no probe named " + name);
    }

    // Reference position of the vertex the probe snapped to, m.
    Point<3>
    probe_point(const std::string &name) const
    {
      for (const ProbeLocation &probe : scene->probes)
        if (probe.name == name)
          return probe.reference_point;
      throw std::runtime_error("no probe named " + name);
    }

    // Elastic (membrane plus bending) energy of the final state, J.
    double
    elastic_energy() const
    {
      return model().energies(displacement, velocity).elastic;
    }
  };

  // Loads `parameter_file` with `overrides` ("Section/Name=value") and runs it to the
  // end, writing probes.csv and statistics.csv into `output_directory`. A failing run
  // throws SimulationError.
  inline SceneRun
  run_scene(const std::string              &parameter_file,
            const std::vector<std::string> &overrides,
            const std::string              &output_directory,
            const MPI_Comm                  communicator)
  {
    std::filesystem::create_directories(output_directory);
    ConditionalOStream pcout(std::cout,
                             Utilities::MPI::this_mpi_process(communicator) == 0);
    SceneRun           run;
    run.scene          = load_scene(parameter_file, overrides, communicator);
    ClothModel  &model = *run.scene->model;
    TimerOutput  timer(communicator, pcout, TimerOutput::never, TimerOutput::wall_times);
    OutputWriter output(output_directory, model, run.scene->probes, false);
    TimeStepper  stepper(run.scene->parameters(), model, output, pcout, timer);
    run.summary      = stepper.run();
    run.displacement = stepper.displacement();
    model.initialize_ghosted(run.velocity);
    run.velocity = 0.;
    return run;
  }

  // Observed order of convergence between two successive levels (mesh size halved).
  inline double
  observed_order(const double coarse_error, const double fine_error)
  {
    return std::log2(coarse_error / fine_error);
  }

  // One check, value < bound: prints the measured value against its bound and returns
  // whether it holds.
  inline bool
  check_below(ConditionalOStream &out,
              const std::string  &what,
              const double        value,
              const double        bound)
  {
    const bool holds = value < bound;
    out << (holds ? "  ok    " : "  FAIL  ") << what << ": " << std::setprecision(6)
        << value << " < " << bound << std::endl;
    return holds;
  }

  // One check, value > bound.
  inline bool
  check_above(ConditionalOStream &out,
              const std::string  &what,
              const double        value,
              const double        bound)
  {
    const bool holds = value > bound;
    out << (holds ? "  ok    " : "  FAIL  ") << what << ": " << std::setprecision(6)
        << value << " > " << bound << std::endl;
    return holds;
  }
} // namespace clothsim::test
