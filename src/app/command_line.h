#pragma once

// The clothsim command line (see README.md and ../shared/DESIGN.md):
//   clothsim [PARAMS.prm|.json] [--set "Section/Name=value"]... [--output-dir DIR]
//   clothsim --compare [PARAMS.prm] [--set ...]... [--fem-set ...]... [--mass-spring-set
//   ...]...
//            [--output-dir DIR]
//   clothsim --convergence [PARAMS.prm] [--space K] [--time K] [--set ...]...
//            [--output-dir DIR]
//   clothsim --sweep [PARAMS.prm] [--axis "A=1|A=2"]... [--reference-set ...]...
//            [--set ...]... [--output-dir DIR]
//   clothsim --restart DIR [--set "Time/End time=..."]...
//   clothsim --print-parameters
//   clothsim --help

#include <string>
#include <vector>

namespace clothsim
{
  struct CommandLine
  {
    enum class Action
    {
      run,
      print_parameters,
      help,
      version,     // clothsim's version and git revision, the libraries' versions
      compare,     // the scene with both models side by side
      convergence, // mesh refinement and/or step halving study
      sweep,       // speed-accuracy sweep over a grid of settings
      restart      // continue a run from its output directory's checkpoint
    };
    Action                   action             = Action::run;
    bool                     parameters_as_json = false; // --print-parameters json
    std::string              parameter_file;             // empty: params/default.prm
    std::vector<std::string> overrides;                  // --set: every run
    std::vector<std::string> fem_overrides;         // --fem-set: the fem run of --compare
    std::vector<std::string> mass_spring_overrides; // --mass-spring-set
    std::string              output_directory;      // empty: output/<scene name>
    std::string              restart_directory;     // --restart DIR
    unsigned int             space_levels = 0;      // --space K: refinements +0..K
    unsigned int             time_levels  = 0;      // --time K: dt, dt/2, ..., dt/2^K
    // --axis "Section/Name=v1 | Section/Name=v2": one axis of the sweep's grid, its
    // alternatives separated by '|', each one or more assignments joined by '&'.
    std::vector<std::string> sweep_axes;
    std::vector<std::string>
      reference_overrides; // --reference-set: the sweep's reference
  };

  // Throws InputError("<command line>", argument, message) on unknown or incomplete
  // options.
  CommandLine
  parse_command_line(const int argc, const char *const *argv);

  std::string
  usage();
} // namespace clothsim
