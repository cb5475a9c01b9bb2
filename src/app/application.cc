#include "app/application.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include "app/command_line.h"
#include "app/convergence_study.h"
#include "app/model_comparison.h"
#include "app/restart.h"
#include "app/scene_runner.h"
#include "app/speed_accuracy_sweep.h"
#include "io/collective.h"
#include "io/input_error.h"
#include "io/output_file.h"
#include "io/output_writer.h"
#include "io/parameters.h"
#include "io/provenance.h"
#include "scene/scene.h"
#include "solvers/blas_kernels.h"
#include "time/explicit_stepper.h"
#include "time/interruption.h"
#include "time/time_stepper.h"

#include <csignal>
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
          const ClothModel                 &model    = *scenes[m]->model;
          const std::vector<ProbeLocation> &probes   = scenes[m]->probes;
          const auto                        observer = [&run,
                                 &model,
                                 &probes,
                                 communicator](const double time, const VectorType &u) {
            auto vertices = model.get_discretization().vertex_displacements(u);
            run.trajectory.times.push_back(time);
            run.trajectory.frames.push_back(std::move(vertices));
            run.trajectory.probes.push_back(probe_displacements(probes, u, communicator));
          };
          pcout << "=== " << models[m] << " ===" << std::endl;
          const RunOutcome outcome = run_loaded_scene(
            *scenes[m], file, directory + "/" + models[m], pcout, observer);
          run.summary      = outcome.summary;
          run.wall_seconds = outcome.wall_seconds;
          run.completed    = outcome.completed;
        }

      io::run_collectively(communicator, [&]() {
        if (is_root)
          {
            const ComparisonFigures figures =
              write_comparison(directory, runs[0], runs[1], [&]() {
                std::vector<std::string> names;
                for (const ProbeLocation &probe : scenes[0]->probes)
                  names.push_back(probe.name);
                return names;
              }());
            std::cout << "comparison (" << directory << "): " << figures.frames
                      << " output times; sheet size " << figures.sheet_size
                      << " m; at the end |x_fem - x_ms| RMS " << figures.final_rms
                      << " m (" << 100. * figures.final_rms / figures.sheet_size
                      << " %), max " << figures.final_max << " m ("
                      << 100. * figures.final_max / figures.sheet_size
                      << " %); largest over time: RMS " << figures.largest_rms
                      << " m, max " << figures.largest_max << " m\n"
                      << "  runtime: fem (" << runs[0].integrator << ") "
                      << runs[0].wall_seconds << " s, mass-spring (" << runs[1].integrator
                      << ") " << runs[1].wall_seconds << " s" << std::endl;
          }
      });
      return runs[0].completed && runs[1].completed ? 0 : 2;
    }

    // An error that may have happened on this rank only: one line on stderr (from every
    // rank that has it), then exit code 2; with several ranks MPI_Abort, so that no
    // rank waits forever for this one.
    int
    stop_on_defect(const MPI_Comm communicator, std::string message)
    {
      for (char &c : message)
        if (c == '\n')
          c = ' ';
      std::cerr << "clothsim: " << message << std::endl;
      if (Utilities::MPI::n_mpi_processes(communicator) > 1)
        MPI_Abort(communicator, 2);
      return 2;
    }
  } // namespace


  int
  run_application(const int argc, const char *const *argv)
  {
    const MPI_Comm     communicator = MPI_COMM_WORLD;
    const bool         is_root      = Utilities::MPI::this_mpi_process(communicator) == 0;
    ConditionalOStream pcout(std::cout, is_root);

    io::record_invocation(argc, argv);
    io::record_blas(blas_description(select_blas_kernels()));
    install_interruption_handlers(is_root);
    // A file-size limit (ulimit -f) then fails the write with EFBIG, reported like a full
    // disk, instead of killing the process with SIGXFSZ.
    std::signal(SIGXFSZ, SIG_IGN);
    try
      {
        const CommandLine command_line = parse_command_line(argc, argv);
        if (command_line.action == CommandLine::Action::help)
          {
            pcout << usage();
            return 0;
          }
        if (command_line.action == CommandLine::Action::version)
          {
            pcout << io::version_line() << "\n" << io::libraries_line() << std::endl;
            return 0;
          }
        if (command_line.action == CommandLine::Action::print_parameters)
          {
            if (is_root)
              print_parameter_reference(std::cout, command_line.parameters_as_json);
            return 0;
          }

        if (command_line.action == CommandLine::Action::restart)
          return run_restart(command_line.restart_directory,
                             command_line.overrides,
                             communicator,
                             pcout);

        const std::string file = command_line.parameter_file.empty()
                                   ? default_parameter_file()
                                   : command_line.parameter_file;
        if (command_line.action == CommandLine::Action::compare)
          return run_comparison(command_line, file, communicator, pcout);
        if (command_line.action == CommandLine::Action::convergence ||
            command_line.action == CommandLine::Action::sweep)
          {
            const bool convergence =
              command_line.action == CommandLine::Action::convergence;
            std::string directory = command_line.output_directory;
            if (directory.empty())
              {
                ParameterHandler prm;
                directory =
                  output_directory(command_line,
                                   read_parameters(prm, file, command_line.overrides)) +
                  (convergence ? "-convergence" : "-sweep");
              }
            if (convergence)
              return run_convergence_study(
                command_line, file, directory, communicator, pcout);
            return run_speed_accuracy_sweep(
              command_line, file, directory, communicator, pcout);
          }

        // All input is read and checked before anything is written.
        std::unique_ptr<Scene> scene =
          load_scene(file, command_line.overrides, communicator);
        RunOptions options;
        options.checkpoints = true;
        const RunOutcome outcome =
          run_loaded_scene(*scene,
                           file,
                           output_directory(command_line, scene->input),
                           pcout,
                           OutputWriter::FrameObserver(),
                           options);
        return outcome.completed ? 0 : 2;
      }
    // Exit codes (README): 1 bad input, 2 the run failed (simulation, output, memory),
    // 128 + signal for an interrupted run. These errors reach every rank together
    // (io/collective.h, the steppers' collective decisions); anything else is a defect
    // that may have happened on one rank only, and MPI_Abort is then the only way not to
    // leave the other ranks waiting.
    catch (const InputError &error)
      {
        if (is_root)
          std::cerr << "clothsim: error: " << error.what() << std::endl;
        return 1;
      }
    catch (const io::OutputError &error)
      {
        if (is_root)
          std::cerr << "clothsim: output failed: " << error.what()
                    << "; the run stops here, every file written before is complete"
                    << std::endl;
        return 2;
      }
    catch (const Interrupted &interruption)
      {
        if (is_root)
          std::cerr << "clothsim: " << interruption.what() << std::endl;
        return interruption.exit_code();
      }
    catch (const std::bad_alloc &)
      {
        return stop_on_defect(communicator,
                              "out of memory (reduce 'Mesh/Global refinements' or run on "
                              "more MPI ranks)");
      }
    catch (const std::exception &error)
      {
        return stop_on_defect(communicator,
                              std::string("internal error: ") + error.what());
      }
  }
} // namespace clothsim
