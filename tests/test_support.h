#pragma once

// What the test programs that run scenes share, beyond test_checks.h (set-up, checks,
// small numerics): running a scene in-process, run_scene (load_scene with overrides, a
// stepper into a scratch output directory, the final state kept in a SceneRun),
// run_clothsim (the executable's entry point), and what the tests read from a run or its
// files. Reading CSV files is in csv.h (also used by the helpers that do not link
// deal.II).

#include "app/application.h"
#include "io/output_writer.h"
#include "scene/scene.h"
#include "test_checks.h"
#include "time/arc_length_stepper.h"
#include "time/explicit_stepper.h"
#include "time/time_stepper.h"

namespace clothsim::test
{
  // ---------------------------------------------------------------------------------
  // Running scenes

  // A parameter value that reads back as the same double ("Time/Time step=" +
  // number(dt)).
  inline std::string
  number(const double value)
  {
    std::ostringstream out;
    out << std::setprecision(17) << value;
    return out.str();
  }

  // Runs the clothsim executable's entry point in-process with `arguments` (those after
  // the program name); returns its exit code.
  inline int
  run_clothsim(const std::vector<std::string> &arguments)
  {
    std::vector<const char *> argv = {"clothsim"};
    for (const std::string &argument : arguments)
      argv.push_back(argument.c_str());
    return run_application(argv.size(), argv.data());
  }

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
          return probe_displacements({probe},
                                     displacement,
                                     model().get_discretization().get_communicator())[0];
      throw std::runtime_error("no probe named " + name);
    }

    // The surface point the probe was located at, m.
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
    else if (run.scene->parameters().time.integrator == Integrator::arc_length)
      {
        ArcLengthStepper stepper(run.scene->parameters(), model, output, pcout, timer);
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

  // `a` followed by `b` (override lists).
  inline std::vector<std::string>
  join(std::vector<std::string> a, const std::vector<std::string> &b)
  {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  }

  // Largest distance between the displacements of the named probes in two runs, m.
  inline double
  largest_probe_difference(const SceneRun                 &a,
                           const SceneRun                 &b,
                           const std::vector<std::string> &probes)
  {
    double difference = 0.;
    for (const std::string &probe : probes)
      difference =
        std::max(difference,
                 (a.probe_displacement(probe) - b.probe_displacement(probe)).norm());
    return difference;
  }

  // The energy history of a run's statistics.csv: the largest |H_n - H_0| of the total
  // energy, the largest kinetic energy, and the number of steps.
  struct EnergyDrift
  {
    double       drift;
    double       largest_kinetic;
    unsigned int steps;
  };

  inline EnergyDrift
  energy_drift(const std::string &statistics_file)
  {
    const Csv    csv     = read_csv(statistics_file);
    const double initial = csv.number(0, "total_energy");
    EnergyDrift  result{0., 0., static_cast<unsigned int>(csv.rows.size() - 1)};
    for (unsigned int r = 0; r < csv.rows.size(); ++r)
      {
        result.drift =
          std::max(result.drift, std::abs(csv.number(r, "total_energy") - initial));
        result.largest_kinetic =
          std::max(result.largest_kinetic, csv.number(r, "kinetic_energy"));
      }
    return result;
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
    for (const auto &element : model.get_discretization().elements())
      for (unsigned int v = 0; v < 3; ++v)
        if (std::abs(element.reference[v][0] - x_edge) < 1e-12 &&
            model.owned_dofs().is_element(element.dofs[3 * v]))
          edge.insert(element.dofs[3 * v]);
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

  // ---------------------------------------------------------------------------------
  // Energy convergence studies of the bending tests (bending_isometric.cc,
  // bending_curved_rest.cc): a table row per refinement level, the energy against the
  // exact one and, for the interior, the energy density.

  // Prints the head of the table: the title with the exact energy, and the columns.
  inline void
  print_energy_table_head(ConditionalOStream &out,
                          const std::string  &title,
                          const double        exact_energy)
  {
    out << "\n"
        << title << " (exact energy " << std::setprecision(10) << exact_energy
        << " J)\nlevel  vertices  energy (J)      ratio         |ratio - 1|  order\n";
  }

  // Prints a row: level, vertices, the run's elastic energy, its ratio to
  // `exact_energy`, |ratio - 1| and the observed order; appends |ratio - 1| to `errors`.
  // Returns the energy.
  inline double
  print_energy_level(ConditionalOStream  &out,
                     const unsigned int   level,
                     const SceneRun      &run,
                     const double         exact_energy,
                     std::vector<double> &errors)
  {
    const double energy = run.elastic_energy();
    const double ratio  = energy / exact_energy;
    errors.push_back(std::abs(ratio - 1.));
    out << std::setw(5) << level << std::setw(10) << run.model().n_vertices()
        << std::setw(16) << std::setprecision(10) << energy << std::setw(14)
        << std::setprecision(8) << ratio << std::setw(13) << std::setprecision(3)
        << errors.back();
    if (level > 0)
      out << std::setw(7) << std::setprecision(3)
          << observed_order(errors[level - 1], errors[level]);
    return energy;
  }

  // Continues the row with the energy density of the triangles `inside` (named by
  // `where`) against `exact_density`, and appends |ratio - 1| to `errors`.
  inline void
  print_interior_density_level(ConditionalOStream                          &out,
                               const std::string                           &where,
                               const unsigned int                           level,
                               const SceneRun                              &run,
                               const double                                 rigidity,
                               const double                                 exact_density,
                               const std::function<bool(const Point<3> &)> &inside,
                               std::vector<double>                         &errors)
  {
    const double density_ratio =
      interior_energy_density(run, rigidity, inside) / exact_density;
    errors.push_back(std::abs(density_ratio - 1.));
    out << "\n       " << where << ": energy density ratio " << std::setprecision(8)
        << density_ratio << ", |ratio - 1| " << std::setprecision(3) << errors.back();
    if (level > 0)
      out << ", order " << observed_order(errors[level - 1], errors[level]);
  }

  // The interior energy density converges at O(h²): observed order at the last pair at
  // least 1.5, |ratio - 1| at the finest level below 1e-4.
  inline bool
  check_interior_density(ConditionalOStream        &out,
                         const std::string         &name,
                         const std::vector<double> &errors)
  {
    const unsigned int n     = errors.size();
    bool               holds = check_above(out,
                             name + ": interior density, observed order at the last pair",
                             observed_order(errors[n - 2], errors[n - 1]),
                             1.5);
    holds &= check_below(out,
                         name + ": interior density, |ratio - 1| at the finest level",
                         errors.back(),
                         1e-4);
    return holds;
  }
} // namespace clothsim::test
