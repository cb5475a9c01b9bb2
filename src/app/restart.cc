#include "app/restart.h"

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include "app/scene_runner.h"
#include "io/input_error.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>

namespace clothsim
{
  namespace
  {
    namespace fs = std::filesystem;

    // The entries a restart may change: the end time and output-only ones. Everything
    // else decides the run's answer up to the checkpoint and after it.
    const std::vector<std::string> changeable = {"Time/End time",
                                                 "Output/Output interval",
                                                 "Output/Checkpoint interval",
                                                 "Output/Progress"};

    std::string
    changeable_list()
    {
      std::string list;
      for (const std::string &entry : changeable)
        list += (list.empty() ? "'" : ", '") + entry + "'";
      return list;
    }

    // Every entry of a ParameterHandler printed as ShortPRM: "Section/Sub/Name" -> value.
    std::map<std::string, std::string>
    entries(const std::string &short_prm)
    {
      std::map<std::string, std::string> result;
      std::vector<std::string>           sections;
      std::istringstream                 in(short_prm);
      std::string                        line;
      while (std::getline(in, line))
        {
          line = Utilities::trim(line);
          if (line.rfind("subsection ", 0) == 0)
            sections.push_back(Utilities::trim(line.substr(11)));
          else if (line == "end" && !sections.empty())
            sections.pop_back();
          else if (line.rfind("set ", 0) == 0)
            {
              const std::size_t equals = line.find('=');
              std::string       path;
              for (const std::string &section : sections)
                path += section + '/';
              path += Utilities::trim(line.substr(4, equals - 4));
              result[path] = equals == std::string::npos
                               ? ""
                               : Utilities::trim(line.substr(equals + 1));
            }
        }
      return result;
    }

    std::string
    short_prm(const ParameterHandler &prm)
    {
      std::ostringstream text;
      prm.print_parameters(text, ParameterHandler::ShortPRM);
      return text.str();
    }

    // "Section / Name = value" as --set gives it: the entry's path, normalised.
    std::string
    override_entry(const std::string &assignment)
    {
      std::string path;
      for (const std::string &part :
           Utilities::split_string_list(assignment.substr(0, assignment.find('=')), '/'))
        path += (path.empty() ? "" : "/") + part;
      return path;
    }

    // Whether the entry names a mesh file (relative to the parameter file's directory).
    bool
    is_mesh_file(const std::string &entry)
    {
      static const std::regex mesh_entry("(Mesh|Obstacle [0-9]+)/Mesh file");
      return std::regex_match(entry, mesh_entry);
    }

    // Sets an entry "Section/Sub/Name" of `prm`.
    void
    set_entry(ParameterHandler &prm, const std::string &entry, const std::string &value)
    {
      const std::vector<std::string> path = Utilities::split_string_list(entry, '/');
      for (unsigned int i = 0; i + 1 < path.size(); ++i)
        prm.enter_subsection(path[i]);
      prm.set(path.back(), value);
      for (unsigned int i = 0; i + 1 < path.size(); ++i)
        prm.leave_subsection();
    }
  } // namespace


  bool
  supports_checkpoints(const Parameters &parameters)
  {
    return !is_explicit(parameters.time.integrator) &&
           parameters.time.integrator != Integrator::arc_length &&
           // Self-contact's near-pair list and full pairs' couplings change over the
           // run and are not stored; the creases' pairs are the mesh's, in its order.
           (!parameters.contact.self_contact ||
            (parameters.contact.self_contact_creases &&
             !parameters.contact.self_contact_full_pairs));
  }


  io::CheckpointData
  checkpoint_record(const Scene &scene)
  {
    io::CheckpointData record;
    record.set_text("run parameters", short_prm(*scene.prm));
    record.set_text("run input directory",
                    fs::absolute(scene.input.directory.empty() ? "."
                                                               : scene.input.directory)
                      .lexically_normal()
                      .string());
    return record;
  }


  int
  run_restart(const std::string              &directory,
              const std::vector<std::string> &overrides,
              const MPI_Comm                  communicator,
              ConditionalOStream             &pcout)
  {
    for (const std::string &assignment : overrides)
      {
        const std::string entry = override_entry(assignment);
        if (std::find(changeable.begin(), changeable.end(), entry) == changeable.end())
          throw InputError("--set",
                           entry,
                           "a restart continues the run as it was: only " +
                             changeable_list() + " may change");
      }
    const std::string parameter_file = directory + "/parameters.prm";
    if (!fs::is_regular_file(parameter_file))
      throw InputError(parameter_file,
                       "",
                       "not found: --restart expects the output directory of a run");
    const auto [run, rank] = io::read_checkpoint(directory, communicator);

    // The run's parameters, its mesh files found from its parameter file's directory.
    const std::map<std::string, std::string> saved =
      entries(run.get_text("run parameters"));
    const fs::path           base = run.get_text("run input directory");
    std::vector<std::string> all_overrides;
    for (const auto &[entry, value] : saved)
      if (is_mesh_file(entry) && !value.empty() && fs::path(value).is_relative())
        all_overrides.push_back(entry + "=" + (base / value).lexically_normal().string());
    const std::size_t n_mesh_overrides = all_overrides.size();
    all_overrides.insert(all_overrides.end(), overrides.begin(), overrides.end());
    std::unique_ptr<Scene> scene =
      load_scene(parameter_file, all_overrides, communicator);
    // Relative paths stay relative to the run's parameter file (later checkpoints);
    // parameters.prm keeps the mesh files as that file gave them.
    scene->input.directory = base.string();
    for (std::size_t k = 0; k < n_mesh_overrides; ++k)
      {
        const std::string entry = override_entry(all_overrides[k]);
        set_entry(*scene->prm, entry, saved.at(entry));
      }

    // Nothing but the changeable entries may differ from the checkpoint's run.
    const std::map<std::string, std::string> now = entries(short_prm(*scene->prm));
    for (const auto &[entry, value] : now)
      {
        const auto        found = saved.find(entry);
        const std::string was   = found == saved.end() ? "" : found->second;
        const bool        allowed =
          std::find(changeable.begin(), changeable.end(), entry) != changeable.end();
        if (value == was || allowed)
          continue;
        throw InputError(parameter_file,
                         entry,
                         "differs from the checkpoint's run ('" + was + "', now '" +
                           value + "'): a restart continues the run as it was; only " +
                           changeable_list() + " may change");
      }

    const Parameters          &parameters = scene->parameters();
    const std::vector<double> &loop       = run.get("loop", 6);
    const bool                 dynamic    = !is_static(parameters.time.integrator);
    const double               end        = dynamic ? parameters.time.end_time : 1.;
    const double               step =
      dynamic ? parameters.time.time_step : 1. / parameters.time.load_steps;
    if (loop[0] >= end - 1e-9 * step)
      {
        std::ostringstream message;
        message << "the checkpoint is at t = " << loop[0]
                << (dynamic ? " s, not before the end time: give a later one, e.g. "
                              "--set \"Time/End time=" +
                                std::to_string(2. * loop[0]) + "\""
                            : ": the static run has finished");
        throw InputError(overrides.empty() ? parameter_file : "--set",
                         dynamic ? "Time/End time" : "",
                         message.str());
      }
    // The mesh and partition must be the checkpoint's (InputError before anything is
    // written; the stepper takes the state again).
    scene->model->restore_state(rank);

    RunOptions options;
    options.checkpoints      = true;
    options.resume_run       = &run;
    options.resume_rank      = &rank;
    const RunOutcome outcome = run_loaded_scene(
      *scene, parameter_file, directory, pcout, OutputWriter::FrameObserver(), options);
    return outcome.completed ? 0 : 2;
  }
} // namespace clothsim
