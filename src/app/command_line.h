#pragma once

// The clothsim command line (see README.md and ../shared/DESIGN.md):
//   clothsim [PARAMS.prm|.json] [--set "Section/Name=value"]... [--output-dir DIR]
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
      help
    };
    Action                   action = Action::run;
    std::string              parameter_file; // empty: params/default.prm
    std::vector<std::string> overrides;
    std::string              output_directory; // empty: output/<scene name>
  };

  // Throws InputError("<command line>", argument, message) on unknown or incomplete
  // options.
  CommandLine
  parse_command_line(const int argc, const char *const *argv);

  std::string
  usage();
} // namespace clothsim
