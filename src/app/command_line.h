#pragma once

// The clothsim command line (see README.md and ../shared/DESIGN.md):
//   clothsim [PARAMS.prm|.json] [--set "Section/Name=value"]... [--output-dir DIR]
//   clothsim --compare [PARAMS.prm] [--set ...]... [--fem-set ...]... [--mass-spring-set
//   ...]...
//            [--output-dir DIR]
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
      compare // the scene with both models side by side
    };
    Action                   action = Action::run;
    std::string              parameter_file;        // empty: params/default.prm
    std::vector<std::string> overrides;             // --set: every run
    std::vector<std::string> fem_overrides;         // --fem-set: the fem run of --compare
    std::vector<std::string> mass_spring_overrides; // --mass-spring-set
    std::string              output_directory;      // empty: output/<scene name>
  };

  // Throws InputError("<command line>", argument, message) on unknown or incomplete
  // options.
  CommandLine
  parse_command_line(const int argc, const char *const *argv);

  std::string
  usage();
} // namespace clothsim
