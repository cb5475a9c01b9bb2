#include "app/application.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include "app/command_line.h"
#include "app/model_comparison.h"
#include "io/input_error.h"
#include "io/output_writer.h"
#include "io/parameters.h"
#include "scene/scene.h"
#include "time/explicit_stepper.h"
#include "time/time_stepper.h"

#include <filesystem>
#include <fstream>
#include <iostream>

namespace clothsim
{
  namespace
  {
    namespace fs = std::filesystem;

    std::string
    default_parameter_file()
    {
      // Next to the executable's source tree first, then the working directory.
      const fs::path in_source = fs::path(CLOTHSIM_SOURCE_DIR) / "params" / "default.prm";
      if (fs::exists(in_source))
        return in_source.string();
      return "params/default.prm";
    }

    std::string
    output_directory(const CommandLine &command_line, const ParameterInput &input)
    {
      if (!command_line.output_directory.empty())
        return command_line.output_directory;
      const std::string name = input.parameters.scene.name.empty()
                                 ? fs::path(input.file).stem().string()
                                 : input.parameters.scene.name;
      return (fs::path("output") / name).string();
    }

    // Creates the directory and removes frames of an earlier run in it.
    void
    prepare_output_directory(const std::string &directory)
    {
      fs::create_directories(directory);
      for (const auto &entry : fs::directory_iterator(directory))
        {
          const std::string name = entry.path().filename().string();
          if (name.rfind("solution", 0) == 0)
            fs::remove(entry.path());
        }
    }

    void
    write_input_copies(const std::string      &directory,
                       const ParameterInput   &input,
                       const ParameterHandler &prm)
    {
      fs::copy_file(input.file,
                    directory + "/original.prm",
                    fs::copy_options::overwrite_existing);
      if (!input.overrides.empty() && fs::path(input.file).extension() != ".json")
        {
          std::ofstream out(directory + "/original.prm", std::ios::app);
          out << "\n# Command-line overrides:\n";
          for (const std::string &assignment : input.overrides)
            out << "#   --set \"" << assignment << "\"\n";
        }
      std::ofstream out(directory + "/parameters.prm");
      prm.print_parameters(out, ParameterHandler::PRM);
    }

    // What one run did.
    struct RunOutcome
    {
      RunSummary  summary;
      double      wall_seconds = 0.;
      bool        completed    = false;
      std::string failure;
    };

    // Runs a loaded scene into `directory` (created; earlier frames removed): the
    // header, the time loop, the summary. A SimulationError ends the run with everything
    // written so far kept; it is reported and returned, not thrown.
    RunOutcome
    run_scene(Scene                             &scene,
              const std::string                 &file,
              const std::string                 &directory,
              ConditionalOStream                &pcout,
              const OutputWriter::FrameObserver &observer = {})
    {
      const MPI_Comm    communicator = scene.model->get_communicator();
      const bool        is_root    = Utilities::MPI::this_mpi_process(communicator) == 0;
      const Parameters &parameters = scene.parameters();
      const ClothModel &model      = *scene.model;
      if (is_root)
        {
          prepare_output_directory(directory);
          write_input_copies(directory, scene.input, scene.prm);
        }
      MPI_Barrier(communicator);

      pcout << "clothsim: " << file << "\n"
            << "  mesh " << scene.mesh_file << ": " << model.n_vertices() << " vertices, "
            << model.get_dof_handler().get_triangulation().n_global_active_cells()
            << " triangles, " << model.n_dofs() << " unknowns, "
            << Utilities::MPI::n_mpi_processes(communicator) << " MPI rank(s)\n"
            << "  pinned dofs: " << model.n_pinned_dofs()
            << ", mass: " << model.total_mass() << " kg\n";
      if (model.uses_springs())
        {
          const auto counts = model.get_springs().global_counts();
          const auto range  = model.get_springs().stiffness_range();
          pcout << "  mass-spring model: " << counts[0] << " structural springs (k "
                << range[0].first << " to " << range[0].second << " N/m), " << counts[1]
                << " cross springs (k " << range[1].first << " to " << range[1].second
                << " N/m)\n";
          if (parameters.time.integrator == Integrator::static_load_steps)
            pcout
              << "  note: springs have no linear bending stiffness at a flat state (a "
                 "bend spring's energy grows like the fold angle^4): a static solve of a "
                 "flat sheet under transverse load is singular there; use 'backward "
                 "euler' with damping\n";
          if (!parameters.constraints.clamped_groups.empty())
            pcout << "  note: springs carry no rotation; the clamped groups hold their "
                     "vertices' positions only\n";
        }
      if (parameters.time.accuracy_target > 0.)
        pcout << "  accuracy target " << parameters.time.accuracy_target
              << " m: adaptive steps, each step's local error at most the target x dt / "
              << parameters.time.end_time << " s, Newton to a tenth of that\n";
      for (const ProbeLocation &probe : scene.probes)
        pcout << "  probe " << probe.name << " at vertex " << probe.reference_point
              << "\n";
      pcout << "  output: " << directory << std::endl;

      TimerOutput timer(communicator, pcout, TimerOutput::never, TimerOutput::wall_times);
      OutputWriter output(directory, model, scene.probes, parameters.output.write_vtk);
      output.set_frame_observer(observer);
      Timer      wall_clock;
      RunOutcome outcome;
      try
        {
          if (is_explicit(parameters.time.integrator))
            outcome.summary =
              ExplicitStepper(parameters, *scene.model, output, pcout, timer).run();
          else
            outcome.summary =
              TimeStepper(parameters, *scene.model, output, pcout, timer).run();
          outcome.completed = true;
        }
      catch (const SimulationError &error)
        {
          outcome.failure = error.what();
          pcout << std::endl;
          if (is_root)
            std::cerr << "clothsim: simulation failed: " << error.what() << std::endl;
        }
      outcome.wall_seconds = wall_clock.wall_time();
      if (!outcome.completed)
        return outcome;
      const RunSummary &summary = outcome.summary;
      pcout << "done: " << summary.steps << " steps in " << outcome.wall_seconds
            << " s; Newton iterations " << summary.newton_iterations << " ("
            << double(summary.newton_iterations) / std::max(1u, summary.steps)
            << " per step), linear iterations " << summary.linear_iterations << " ("
            << double(summary.linear_iterations) / std::max(1u, summary.newton_iterations)
            << " per Newton step), tangents " << summary.tangents << ", step halvings "
            << summary.retries << std::endl;
      if (parameters.time.adaptive_time_steps)
        {
          pcout << "estimated error at the end: " << summary.estimated_error
                << " m (the accepted steps' local error estimates, summed";
          if (parameters.time.accuracy_target > 0.)
            pcout << "; accuracy target " << parameters.time.accuracy_target << " m";
          pcout << "); " << summary.rejected << " steps rejected" << std::endl;
        }
      timer.print_summary();
      return outcome;
    }

    std::string
    integrator_name(const Integrator integrator)
    {
      switch (integrator)
        {
          case Integrator::backward_euler:
            return "backward euler";
          case Integrator::static_load_steps:
            return "static";
          case Integrator::symplectic_euler:
            return "symplectic euler";
          case Integrator::velocity_verlet:
            return "velocity verlet";
          case Integrator::bdf2:
            return "bdf2";
          case Integrator::implicit_midpoint:
            return "implicit midpoint";
        }
      return "";
    }

    // clothsim --compare: the scene with Model = fem and with Model = mass-spring, each
    // into its own subdirectory, then the comparison files. Returns the exit code.
    int
    run_comparison(const CommandLine  &command_line,
                   const std::string  &file,
                   const MPI_Comm      communicator,
                   ConditionalOStream &pcout)
    {
      const bool is_root = Utilities::MPI::this_mpi_process(communicator) == 0;
      // All input of both runs is read and checked before anything is written.
      std::array<std::unique_ptr<Scene>, 2> scenes;
      const std::array<std::string, 2>      models = {{"fem", "mass-spring"}};
      for (unsigned int m = 0; m < 2; ++m)
        {
          std::vector<std::string> overrides = command_line.overrides;
          overrides.push_back("Model=" + models[m]);
          const auto &own =
            m == 0 ? command_line.fem_overrides : command_line.mass_spring_overrides;
          overrides.insert(overrides.end(), own.begin(), own.end());
          scenes[m] = load_scene(file, overrides, communicator);
        }
      std::string directory = command_line.output_directory;
      if (directory.empty())
        directory = output_directory(command_line, scenes[0]->input) + "-comparison";

      std::array<ComparedRun, 2> runs;
      for (unsigned int m = 0; m < 2; ++m)
        {
          const Parameters &parameters = scenes[m]->parameters();
          ComparedRun      &run        = runs[m];
          run.model                    = models[m];
          run.integrator               = integrator_name(parameters.time.integrator);
          run.time_step                = parameters.time.time_step;
          const ClothModel &model      = *scenes[m]->model;
          const auto observer = [&run, &model](const double time, const VectorType &u) {
            auto vertices = model.vertex_displacements(u);
            run.trajectory.times.push_back(time);
            run.trajectory.frames.push_back(std::move(vertices));
          };
          pcout << "=== " << models[m] << " ===" << std::endl;
          const RunOutcome outcome =
            run_scene(*scenes[m], file, directory + "/" + models[m], pcout, observer);
          run.summary      = outcome.summary;
          run.wall_seconds = outcome.wall_seconds;
          run.completed    = outcome.completed;
        }

      if (is_root)
        {
          const ComparisonFigures figures =
            write_comparison(directory, runs[0], runs[1], [&]() {
              std::vector<std::pair<std::string, Point<3>>> points;
              for (const ProbeLocation &probe : scenes[0]->probes)
                points.emplace_back(probe.name, probe.reference_point);
              return points;
            }());
          std::cout << "comparison (" << directory << "): " << figures.frames
                    << " output times; sheet size " << figures.sheet_size
                    << " m; at the end |x_fem - x_ms| RMS " << figures.final_rms << " m ("
                    << 100. * figures.final_rms / figures.sheet_size << " %), max "
                    << figures.final_max << " m ("
                    << 100. * figures.final_max / figures.sheet_size
                    << " %); largest over time: RMS " << figures.largest_rms << " m, max "
                    << figures.largest_max << " m\n"
                    << "  runtime: fem (" << runs[0].integrator << ") "
                    << runs[0].wall_seconds << " s, mass-spring (" << runs[1].integrator
                    << ") " << runs[1].wall_seconds << " s" << std::endl;
        }
      return runs[0].completed && runs[1].completed ? 0 : 2;
    }
  } // namespace


  int
  run_application(const int argc, const char *const *argv)
  {
    const MPI_Comm     communicator = MPI_COMM_WORLD;
    const bool         is_root      = Utilities::MPI::this_mpi_process(communicator) == 0;
    ConditionalOStream pcout(std::cout, is_root);

    try
      {
        const CommandLine command_line = parse_command_line(argc, argv);
        if (command_line.action == CommandLine::Action::help)
          {
            pcout << usage();
            return 0;
          }
        if (command_line.action == CommandLine::Action::print_parameters)
          {
            if (is_root)
              print_parameter_reference(std::cout);
            return 0;
          }

        const std::string file = command_line.parameter_file.empty()
                                   ? default_parameter_file()
                                   : command_line.parameter_file;
        if (command_line.action == CommandLine::Action::compare)
          return run_comparison(command_line, file, communicator, pcout);

        // All input is read and checked before anything is written.
        std::unique_ptr<Scene> scene =
          load_scene(file, command_line.overrides, communicator);
        const RunOutcome outcome =
          run_scene(*scene, file, output_directory(command_line, scene->input), pcout);
        return outcome.completed ? 0 : 2;
      }
    catch (const InputError &error)
      {
        if (is_root)
          std::cerr << "clothsim: error: " << error.what() << std::endl;
        return 1;
      }
  }
} // namespace clothsim
