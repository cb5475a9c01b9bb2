#include "app/scene_runner.h"

#include "app/restart.h"
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_handler.h>

#include "io/collective.h"
#include "io/input_error.h"
#include "io/output_file.h"
#include "io/provenance.h"
#include "scene/obstacles.h"
#include "time/arc_length_stepper.h"
#include "time/explicit_stepper.h"
#include "time/time_stepper.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <regex>
#include <sstream>

namespace clothsim
{
  namespace
  {
    namespace fs = std::filesystem;

    // A parameter file as ParameterHandler prints it (PRM), without the "Obstacle k"
    // sections that are unused ('Shape = none', their default): eight such sections with
    // their documentation would triple the file.
    std::string
    without_unused_obstacles(const std::string &text)
    {
      std::istringstream       in(text);
      std::string              result, line;
      std::vector<std::string> block;
      while (std::getline(in, line))
        {
          if (block.empty() && line.rfind("subsection Obstacle ", 0) != 0)
            {
              result += line + '\n';
              continue;
            }
          block.push_back(line);
          if (line != "end")
            continue;
          const bool unused =
            std::any_of(block.begin(), block.end(), [](const std::string &entry) {
              return std::regex_match(entry, std::regex("\\s*set Shape\\s*= none\\s*"));
            });
          if (!unused)
            for (const std::string &kept : block)
              result += kept + '\n';
          else if (!result.empty() && result.back() == '\n' && result.size() > 1 &&
                   result[result.size() - 2] == '\n')
            result.pop_back(); // the blank line before the dropped section
          block.clear();
        }
      return result;
    }

    // Creates the directory (an InputError if that is impossible, after removing any
    // parent it created) and removes the frames and checkpoint of an earlier run in it
    // (and any left under a temporary name).
    void
    prepare_output_directory(const std::string &directory)
    {
      std::error_code error;
      // The directories on the way that do not exist yet, deepest first: removed again
      // if the directory cannot be made.
      std::vector<fs::path> missing;
      fs::path              prefix;
      for (const fs::path &part : fs::absolute(directory, error))
        {
          prefix /= part;
          std::error_code       status_error;
          const fs::file_status status = fs::symlink_status(prefix, status_error);
          if (status.type() == fs::file_type::not_found)
            missing.insert(missing.begin(), prefix);
          else if (status_error)
            break;
        }
      error.clear();
      fs::create_directories(directory, error);
      if (!error && !fs::is_directory(directory, error))
        error = std::make_error_code(std::errc::not_a_directory);
      if (error)
        {
          std::error_code ignored;
          for (const fs::path &path : missing)
            fs::remove(path, ignored); // only directories made here, and empty
          throw InputError(directory,
                           "",
                           "cannot create the output directory: " + error.message());
        }
      for (fs::directory_iterator entry(directory, error), end; !error && entry != end;
           entry.increment(error))
        {
          // Only the names a run writes: a directory given with --output-dir may hold
          // other files. An earlier run's checkpoint goes too: it is not this run's.
          static const std::regex frame_file(
            "(solution(-[0-9]{5}([.][0-9]{4})?[.](vtu|pvtu)|[.]pvd)|checkpoint[.]bin)"
            "([.]partial)?");
          if (std::regex_match(entry->path().filename().string(), frame_file))
            fs::remove(entry->path(), error);
        }
      if (error)
        throw io::OutputError(directory,
                              "cannot remove the frames of an earlier run: " +
                                error.message());
    }

    // parameters.prm: the run's provenance as comments, then every parameter's value,
    // written whole.
    void
    write_parameter_copy(const std::string              &directory,
                         const ParameterHandler         &prm,
                         const std::vector<std::string> &provenance)
    {
      io::write_file_atomically(directory + "/parameters.prm", [&](std::ostream &out) {
        for (const std::string &line : provenance)
          out << "# " << line << "\n";
        out << "\n";
        std::ostringstream text;
        prm.print_parameters(text, ParameterHandler::PRM);
        out << without_unused_obstacles(text.str());
      });
    }

    // original.prm (the input as given, with the command line's overrides) and
    // parameters.prm (every parameter's value, after the run's provenance as comments),
    // each written whole.
    void
    write_input_copies(const std::string              &directory,
                       const ParameterInput           &input,
                       const ParameterHandler         &prm,
                       const std::vector<std::string> &provenance)
    {
      std::ifstream      in(input.file, std::ios::binary);
      std::ostringstream original;
      original << in.rdbuf();
      if (!in)
        throw InputError(input.file, "", "cannot be read again for original.prm");
      io::write_file_atomically(directory + "/original.prm", [&](std::ostream &out) {
        out << original.str();
        if (!input.overrides.empty() && fs::path(input.file).extension() != ".json")
          {
            out << "\n# Command-line overrides:\n";
            for (const std::string &assignment : input.overrides)
              out << "#   --set \"" << assignment << "\"\n";
          }
      });
      write_parameter_copy(directory, prm, provenance);
    }

    // After a dynamic run, completed or failed: if the energy balance (total +
    // dissipated - the energy given from outside the step's equations: the work of
    // prescribed motion, the strain limit's and the barrier stiffness raises' energy)
    // rose by more than the energy the run had to move with (its initial kinetic and
    // elastic energy, the largest potential energy and the largest energy given from
    // outside), the integrator made that energy.
    void
    print_instability_note(const Parameters   &parameters,
                           const OutputWriter &output,
                           ConditionalOStream &pcout)
    {
      const double gained = output.energy_balance_change();
      if (!(gained > output.energy_scale()))
        return;
      pcout << "  warning: the energy balance rose by " << gained
            << " J, more than the energy the run moved with (initial, potential and "
               "given from outside: "
            << output.energy_scale() << " J): the time integration was unstable";
      if (parameters.time.integrator == Integrator::implicit_midpoint)
        pcout << "; the implicit midpoint rule is not energy-stable on stiff nonlinear "
                 "motion such as folding cloth (README, \"Time integration\"): 'average "
                 "vector field' keeps the energy, 'bdf2' damps it";
      pcout << std::endl;
    }

    // The time loop with its timer, then the run's figures. An output error or an
    // interruption is handed back in `stopped`, for the caller to throw once the timer is
    // gone (its destructor warns when an exception is in flight).
    RunOutcome
    run_steps(Scene                             &scene,
              const std::string                 &directory,
              ConditionalOStream                &pcout,
              const OutputWriter::FrameObserver &observer,
              const RunOptions                  &options,
              std::exception_ptr                &stopped)
    {
      const MPI_Comm    communicator = scene.model->get_communicator();
      const bool        is_root    = Utilities::MPI::this_mpi_process(communicator) == 0;
      const Parameters &parameters = scene.parameters();
      const ClothModel &model      = *scene.model;
      TimerOutput timer(communicator, pcout, TimerOutput::never, TimerOutput::wall_times);
      Timer       wall_clock;
      RunOutcome  outcome;
      std::optional<OutputWriter> output;
      try
        {
          output.emplace(directory,
                         communicator,
                         model.output_piece(),
                         scene.probes,
                         model.energy_columns(),
                         parameters.output.write_vtk,
                         options.resume_run);
          output->set_frame_observer(observer);
          if (is_explicit(parameters.time.integrator))
            outcome.summary =
              ExplicitStepper(parameters, *scene.model, *output, pcout, timer).run();
          else if (parameters.time.integrator == Integrator::arc_length)
            {
              // The load factor falls along a path: ParaView gets the frames by step.
              output->number_frames_by_step();
              outcome.summary =
                ArcLengthStepper(parameters, *scene.model, *output, pcout, timer).run();
            }
          else
            {
              TimeStepper stepper(parameters, *scene.model, *output, pcout, timer);
              if (options.checkpoints && supports_checkpoints(parameters))
                stepper.enable_checkpoints(directory,
                                           parameters.output.checkpoint_interval,
                                           checkpoint_record(scene));
              if (options.resume_run != nullptr)
                stepper.restore(*options.resume_run, *options.resume_rank);
              outcome.summary = stepper.run();
            }
          outcome.completed = true;
        }
      catch (const SimulationError &error)
        {
          outcome.failure = error.what();
          pcout << std::endl;
          if (is_root)
            std::cerr << "clothsim: simulation failed: " << error.what() << std::endl;
          // What was computed up to the failure: every file written so far is whole.
          if (output && is_root)
            output->print_summary(std::cout);
          if (output && !is_static(parameters.time.integrator))
            print_instability_note(parameters, *output, pcout);
        }
      catch (...)
        {
          stopped = std::current_exception();
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
      if (is_root)
        output->print_summary(std::cout);
      if (!is_static(parameters.time.integrator))
        print_instability_note(parameters, *output, pcout);
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
      pcout
        << "assembly time per term (element terms estimated from every 64th triangle):";
      for (unsigned int k = 0; k < physics.terms().size(); ++k)
        {
          const physics::Term *term = physics.terms()[k];
          pcout << (k == 0 ? " " : ", ") << term->name() << " ";
          if (physics.assembled_by(k) != term)
            pcout << "(in the " << physics.assembled_by(k)->name() << " loop)";
          else
            pcout << physics.term_seconds()[k] << " s";
        }
      pcout << std::endl;
      // Terms that time their own phases (this rank's wall time).
      for (const physics::Term *term : physics.terms())
        {
          const auto phases = term->phase_seconds();
          if (phases.empty())
            continue;
          pcout << term->name() << " phases:";
          for (unsigned int i = 0; i < phases.size(); ++i)
            pcout << (i == 0 ? " " : ", ") << phases[i].first << " " << phases[i].second
                  << " s";
          pcout << std::endl;
        }
      return outcome;
    }

  } // namespace


  RunOutcome
  run_loaded_scene(Scene                             &scene,
                   const std::string                 &file,
                   const std::string                 &directory,
                   ConditionalOStream                &pcout,
                   const OutputWriter::FrameObserver &observer,
                   const RunOptions                  &options)
  {
    const MPI_Comm    communicator = scene.model->get_communicator();
    const bool        is_root      = Utilities::MPI::this_mpi_process(communicator) == 0;
    const Parameters &parameters   = scene.parameters();
    const ClothModel &model        = *scene.model;
    const std::vector<std::string> provenance = io::provenance_lines(communicator);
    if (options.checkpoints && parameters.output.checkpoint_interval > 0. &&
        !supports_checkpoints(parameters))
      throw InputError(file,
                       "Output/Checkpoint interval",
                       "checkpoints need an implicit integrator and no 'Contact/Self "
                       "contact = true' nor 'full pairs' (0 for this run)");
    io::run_collectively(communicator, [&]() {
      if (!is_root)
        return;
      if (options.resume_run != nullptr)
        write_parameter_copy(directory, *scene.prm, provenance);
      else
        {
          prepare_output_directory(directory);
          write_input_copies(directory, scene.input, *scene.prm, provenance);
        }
    });

    for (const std::string &line : provenance)
      pcout << line << "\n";
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
    if (const physics::ObstacleContact *contact = model.obstacle_contact())
      for (unsigned int o = 0; o < contact->get_obstacles().size(); ++o)
        if (contact->get_settings().core_pairs_projected_exact[o])
          pcout << "  edge contact of obstacle '" << contact->get_obstacles()[o].name()
                << "': the projected exact tangent (its core moves by up to "
                << largest_core_step(contact->get_obstacles()[o],
                                     longest_time_step(parameters.time),
                                     parameters.time.end_time)
                << " m in a time step of " << longest_time_step(parameters.time)
                << " s; 'Contact/Edge contact tangent')\n";
    if (model.uses_springs())
      {
        const auto counts = model.get_springs().global_counts();
        const auto range  = model.get_springs().stiffness_range();
        pcout << "  mass-spring model: " << counts[0] << " structural springs (k "
              << range[0].first << " to " << range[0].second << " N/m), " << counts[1]
              << " cross springs (k " << range[1].first << " to " << range[1].second
              << " N/m)\n";
        if (is_static(parameters.time.integrator))
          pcout
            << "  note: springs have no linear bending stiffness at a flat state (a "
               "bend spring's energy grows like the fold angle^4): a static solve of a "
               "flat sheet under transverse load is singular there; use 'backward "
               "euler' with damping\n";
        if (!parameters.constraints.clamped_groups.empty())
          pcout << "  note: springs carry no rotation; the clamped groups hold their "
                   "vertices' positions only\n";
      }
    if (!is_explicit(parameters.time.integrator))
      {
        const NonlinearSolverParameters &newton = parameters.nonlinear_solver;
        pcout << "  newton: " << newton.tangent << " tangent";
        if (newton.truncation_error_fraction > 0. &&
            !is_static(parameters.time.integrator))
          pcout << ", stops below " << newton.truncation_error_fraction
                << " of the step's local truncation estimate ("
                << newton.truncation_error_norm << " norm)";
        pcout << ", at most " << newton.max_iterations << " iterations\n";
      }
    if (parameters.time.accuracy_target > 0.)
      pcout << "  accuracy target " << parameters.time.accuracy_target
            << " m: adaptive steps, each step's local error at most the target x dt / "
            << parameters.time.end_time << " s, Newton to a tenth of that\n";
    for (const ProbeLocation &probe : scene.probes)
      pcout << "  probe " << probe.name << " at " << probe.reference_point << " ("
            << probe.distance << " m from the point given)\n";
    pcout << "  output: " << directory << std::endl;
    if (options.resume_run != nullptr)
      {
        const std::vector<double> &loop = options.resume_run->get("loop");
        pcout << "  restart from the checkpoint at step " << loop.at(1)
              << ", t = " << loop.at(0) << std::endl;
      }

    std::exception_ptr stopped;
    const RunOutcome   outcome =
      run_steps(scene, directory, pcout, observer, options, stopped);
    if (stopped)
      std::rethrow_exception(stopped);
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
        case Integrator::linear_static:
          return "linear static";
        case Integrator::arc_length:
          return "arc length";
        case Integrator::symplectic_euler:
          return "symplectic euler";
        case Integrator::velocity_verlet:
          return "velocity verlet";
        case Integrator::bdf2:
          return "bdf2";
        case Integrator::implicit_midpoint:
          return "implicit midpoint";
        case Integrator::average_vector_field:
          return "average vector field";
      }
    return "";
  }

} // namespace clothsim
