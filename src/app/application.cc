#include "app/application.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include "app/command_line.h"
#include "io/input_error.h"
#include "io/output_writer.h"
#include "io/parameters.h"
#include "scene/scene.h"
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

        // All input is read and checked before anything is written.
        const std::string      file = command_line.parameter_file.empty()
                                        ? default_parameter_file()
                                        : command_line.parameter_file;
        std::unique_ptr<Scene> scene =
          load_scene(file, command_line.overrides, communicator);
        const ParameterInput &input      = scene->input;
        const Parameters     &parameters = scene->parameters();
        const ClothModel     &model      = *scene->model;
        const std::string    &mesh_file  = scene->mesh_file;
        const auto           &probes     = scene->probes;

        const std::string directory = output_directory(command_line, input);
        if (is_root)
          {
            prepare_output_directory(directory);
            write_input_copies(directory, input, scene->prm);
          }
        MPI_Barrier(communicator);

        pcout << "clothsim: " << file << "\n"
              << "  mesh " << mesh_file << ": " << model.n_vertices() << " vertices, "
              << model.get_dof_handler().get_triangulation().n_global_active_cells()
              << " triangles, " << model.n_dofs() << " unknowns, "
              << Utilities::MPI::n_mpi_processes(communicator) << " MPI rank(s)\n"
              << "  pinned dofs: " << model.n_pinned_dofs()
              << ", mass: " << model.total_mass() << " kg\n";
        for (const ProbeLocation &probe : probes)
          pcout << "  probe " << probe.name << " at vertex " << probe.reference_point
                << "\n";
        pcout << "  output: " << directory << std::endl;

        TimerOutput  timer(communicator,
                          pcout,
                          TimerOutput::never,
                          TimerOutput::wall_times);
        OutputWriter output(directory, model, probes, parameters.output.write_vtk);
        TimeStepper  stepper(parameters, *scene->model, output, pcout, timer);
        Timer        wall_clock;
        RunSummary   summary;
        try
          {
            summary = stepper.run();
          }
        catch (const SimulationError &error)
          {
            pcout << std::endl;
            if (is_root)
              std::cerr << "clothsim: simulation failed: " << error.what() << std::endl;
            return 2;
          }
        const double seconds = wall_clock.wall_time();
        pcout << "done: " << summary.steps << " steps in " << seconds
              << " s; Newton iterations " << summary.newton_iterations << " ("
              << double(summary.newton_iterations) / std::max(1u, summary.steps)
              << " per step), linear iterations " << summary.linear_iterations << " ("
              << double(summary.linear_iterations) /
                   std::max(1u, summary.newton_iterations)
              << " per Newton step), step halvings " << summary.retries << std::endl;
        timer.print_summary();
        return 0;
      }
    catch (const InputError &error)
      {
        if (is_root)
          std::cerr << "clothsim: error: " << error.what() << std::endl;
        return 1;
      }
  }
} // namespace clothsim
