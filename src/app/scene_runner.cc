#include "app/scene_runner.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

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


  RunOutcome
  run_loaded_scene(Scene                             &scene,
                   const std::string                 &file,
                   const std::string                 &directory,
                   ConditionalOStream                &pcout,
                   const OutputWriter::FrameObserver &observer)
  {
    const MPI_Comm    communicator = scene.model->get_communicator();
    const bool        is_root      = Utilities::MPI::this_mpi_process(communicator) == 0;
    const Parameters &parameters   = scene.parameters();
    const ClothModel &model        = *scene.model;
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
          << ", mass: " << model.total_mass() << " kg\n"
          << "  terms:";
    for (const std::string &name : model.term_names())
      pcout << " " << name;
    pcout << "\n";
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
      pcout << "  probe " << probe.name << " at vertex " << probe.reference_point << "\n";
    pcout << "  output: " << directory << std::endl;

    TimerOutput  timer(communicator, pcout, TimerOutput::never, TimerOutput::wall_times);
    OutputWriter output(directory,
                        communicator,
                        model.output_piece(),
                        scene.probes,
                        model.energy_columns(),
                        parameters.output.write_vtk);
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
    // The assembly's cost per term: a term the scene does not need is not there.
    const physics::Model &physics = model.get_physics();
    pcout << "assembly time per term (element terms estimated from every 64th triangle):";
    for (unsigned int k = 0; k < physics.terms().size(); ++k)
      pcout << (k == 0 ? " " : ", ") << physics.terms()[k]->name() << " "
            << physics.term_seconds()[k] << " s";
    pcout << std::endl;
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

} // namespace clothsim
