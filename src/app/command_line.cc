#include "app/command_line.h"

#include "io/input_error.h"

namespace clothsim
{
  CommandLine
  parse_command_line(const int argc, const char *const *argv)
  {
    CommandLine command_line;
    for (int i = 1; i < argc; ++i)
      {
        const std::string argument = argv[i];
        const auto        value    = [&]() -> std::string {
          if (i + 1 >= argc)
            throw InputError("", argument, "expects a value");
          return argv[++i];
        };
        if (argument == "--help" || argument == "-h")
          command_line.action = CommandLine::Action::help;
        else if (argument == "--print-parameters")
          command_line.action = CommandLine::Action::print_parameters;
        else if (argument == "--compare")
          command_line.action = CommandLine::Action::compare;
        else if (argument == "--set")
          command_line.overrides.push_back(value());
        else if (argument == "--fem-set")
          command_line.fem_overrides.push_back(value());
        else if (argument == "--mass-spring-set")
          command_line.mass_spring_overrides.push_back(value());
        else if (argument == "--output-dir")
          command_line.output_directory = value();
        else if (!argument.empty() && argument[0] == '-')
          throw InputError("", argument, "unknown option (see clothsim --help)");
        else if (command_line.parameter_file.empty())
          command_line.parameter_file = argument;
        else
          throw InputError("", argument, "only one parameter file may be given");
      }
    return command_line;
  }


  std::string
  usage()
  {
    return "clothsim: finite-element cloth and thin-shell simulator\n"
           "\n"
           "usage:\n"
           "  clothsim [PARAMS.prm] [--set \"Section/Name=value\"]... [--output-dir "
           "DIR]\n"
           "      run the scene in PARAMS.prm (or .json); without one, "
           "params/default.prm.\n"
           "      --set overrides one entry (repeatable), e.g. --set \"Time/End "
           "time=0.5\".\n"
           "      Output goes to DIR, default output/<Scene name or file stem>/.\n"
           "  clothsim --compare [PARAMS.prm] [--set ...]... [--fem-set ...]...\n"
           "           [--mass-spring-set ...]... [--output-dir DIR]\n"
           "      run the scene with Model = fem and with Model = mass-spring (into\n"
           "      DIR/fem and DIR/mass-spring; DIR default output/<name>-comparison/),\n"
           "      --fem-set / --mass-spring-set override one run only, e.g.\n"
           "      --mass-spring-set \"Time/Integrator=velocity verlet\". Writes\n"
           "      DIR/comparison.csv (probe and whole-mesh position differences over\n"
           "      time), DIR/runtimes.csv and DIR/comparison.png (probe histories).\n"
           "  clothsim --print-parameters\n"
           "      print every parameter with its default, allowed values and unit.\n"
           "  clothsim --help\n"
           "      this text.\n"
           "\n"
           "Under MPI: mpirun -np N clothsim PARAMS.prm (same results for any N).\n";
  }
} // namespace clothsim
