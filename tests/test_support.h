#pragma once

// Running a scene in-process for tests (the pattern of uniaxial_stretch.cc): load_scene
// with overrides, TimeStepper::run into a scratch output directory, and the final state
// kept for inspection (displacement, probes, energies).

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include "io/output_writer.h"
#include "scene/scene.h"
#include "time/explicit_stepper.h"
#include "time/time_stepper.h"

#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace clothsim::test
{
  using namespace dealii;

  // Values of the given dofs of `u` (ghosted) on every rank.
  inline std::vector<double>
  gather_values(const ClothModel                           &model,
                const VectorType                           &u,
                const std::vector<types::global_dof_index> &dofs)
  {
    std::vector<double> values(dofs.size(), 0.);
    for (unsigned int i = 0; i < dofs.size(); ++i)
      if (model.owned_dofs().is_element(dofs[i]))
        values[i] = u(dofs[i]);
    MPI_Allreduce(MPI_IN_PLACE,
                  values.data(),
                  values.size(),
                  MPI_DOUBLE,
                  MPI_SUM,
                  model.get_communicator());
    return values;
  }

  // An output writer of probes.csv and statistics.csv (no VTK) for the model.
  inline OutputWriter
  make_output_writer(const std::string                &directory,
                     const ClothModel                 &model,
                     const std::vector<ProbeLocation> &probes)
  {
    return OutputWriter(directory,
                        model.get_communicator(),
                        model.output_piece(),
                        probes,
                        model.energy_columns(),
                        false);
  }

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
              gather_values(model(),
                            displacement,
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
      return model().energies(displacement, velocity, 0.).elastic;
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
    OutputWriter output = make_output_writer(output_directory, model, run.scene->probes);
    model.initialize_ghosted(run.velocity);
    if (is_explicit(run.scene->parameters().time.integrator))
      {
        ExplicitStepper stepper(run.scene->parameters(), model, output, pcout, timer);
        run.summary      = stepper.run();
        run.displacement = stepper.displacement();
        run.velocity     = stepper.velocity();
      }
    else
      {
        TimeStepper stepper(run.scene->parameters(), model, output, pcout, timer);
        run.summary      = stepper.run();
        run.displacement = stepper.displacement();
        run.velocity     = stepper.velocity();
      }
    return run;
  }

  // The x component of the internal forces summed over the (owned) vertices at
  // X = x_edge: the reaction the pins there take, N.
  inline double
  edge_reaction_x(const ClothModel &model, const VectorType &u, const double x_edge)
  {
    VectorType forces;
    model.initialize_owned(forces);
    model.internal_forces(u, forces);
    std::set<types::global_dof_index> edge;
    for (const auto &cell : model.get_dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned int v = 0; v < 3; ++v)
          if (std::abs(cell->vertex(v)[0] - x_edge) < 1e-12 &&
              model.owned_dofs().is_element(cell->vertex_dof_index(v, 0)))
            edge.insert(cell->vertex_dof_index(v, 0));
    double force = 0.;
    for (const auto dof : edge)
      force += forces[dof];
    return Utilities::MPI::sum(force, model.get_communicator());
  }

  // Bending energy per area of the triangles whose three reference vertices satisfy
  // `inside`, from each triangle's curvature change norm sqrt(tr M²): W_T = |T̄| D/2
  // tr(M²), exact for ν = 0.
  inline double
  interior_energy_density(const SceneRun                              &run,
                          const double                                 rigidity,
                          const std::function<bool(const Point<3> &)> &inside)
  {
    const ClothModel         &model = run.model();
    const std::vector<double> curvature =
      model.cell_field(run.displacement, "curvature_change");
    const auto &elements = model.get_discretization().elements();
    double      energy = 0., area = 0.;
    for (unsigned int e = 0; e < elements.size(); ++e)
      {
        bool all_inside = true;
        for (const Point<3> &X : elements[e].reference)
          all_inside = all_inside && inside(X);
        if (!all_inside)
          continue;
        const double M = curvature[e];
        energy += 0.5 * rigidity * elements[e].area * M * M;
        area += elements[e].area;
      }
    return Utilities::MPI::sum(energy, model.get_communicator()) /
           Utilities::MPI::sum(area, model.get_communicator());
  }

  // A parameter value that reads back as the same double ("Time/Time step=" +
  // number(dt)).
  inline std::string
  number(const double value)
  {
    std::ostringstream out;
    out << std::setprecision(17) << value;
    return out.str();
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
} // namespace clothsim::test
