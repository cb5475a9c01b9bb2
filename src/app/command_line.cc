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
          // An option in its place means the value was forgotten.
          if (i + 1 >= argc || std::string(argv[i + 1]).rfind("--", 0) == 0)
            throw InputError("", argument, "expects a value");
          return argv[++i];
        };
        if (argument == "--help" || argument == "-h")
          command_line.action = CommandLine::Action::help;
        else if (argument == "--version")
          command_line.action = CommandLine::Action::version;
        else if (argument == "--print-parameters")
          {
            command_line.action = CommandLine::Action::print_parameters;
            if (i + 1 < argc && (std::string(argv[i + 1]) == "json" ||
                                 std::string(argv[i + 1]) == "text"))
              command_line.parameters_as_json = std::string(argv[++i]) == "json";
          }
        else if (argument == "--compare")
          command_line.action = CommandLine::Action::compare;
        else if (argument == "--convergence")
          command_line.action = CommandLine::Action::convergence;
        else if (argument == "--sweep")
          command_line.action = CommandLine::Action::sweep;
        else if (argument == "--space" || argument == "--time")
          {
            const std::string text   = value();
            std::size_t       used   = 0;
            int               levels = -1;
            try
              {
                levels = std::stoi(text, &used);
              }
            catch (const std::exception &)
              {}
            if (used != text.size() || levels < 0 || levels > 8)
              throw InputError("", argument, "expects a whole number 0..8, got " + text);
            (argument == "--space" ? command_line.space_levels
                                   : command_line.time_levels) = levels;
          }
        else if (argument == "--axis")
          command_line.sweep_axes.push_back(value());
        else if (argument == "--reference-set")
          command_line.reference_overrides.push_back(value());
        else if (argument == "--set")
          command_line.overrides.push_back(value());
        else if (argument == "--fem-set")
          command_line.fem_overrides.push_back(value());
        else if (argument == "--mass-spring-set")
          command_line.mass_spring_overrides.push_back(value());
        else if (argument == "--restart")
          {
            command_line.action            = CommandLine::Action::restart;
            command_line.restart_directory = value();
          }
        else if (argument == "--output-dir")
          command_line.output_directory = value();
        else if (!argument.empty() && argument[0] == '-')
          throw InputError("", argument, "unknown option (see clothsim --help)");
        else if (command_line.parameter_file.empty())
          command_line.parameter_file = argument;
        else
          throw InputError("", argument, "only one parameter file may be given");
      }
    if (command_line.action == CommandLine::Action::restart &&
        !(command_line.parameter_file.empty() && command_line.output_directory.empty()))
      throw InputError("",
                       "--restart",
                       "takes its parameters and output directory from DIR: no parameter "
                       "file, no --output-dir");
    const bool convergence = command_line.action == CommandLine::Action::convergence;
    if (convergence && command_line.space_levels + command_line.time_levels == 0)
      throw InputError("",
                       "--convergence",
                       "needs --space K and/or --time K (K >= 1 refinements or step "
                       "halvings)");
    if (!convergence && command_line.space_levels + command_line.time_levels > 0)
      throw InputError("", "--space/--time", "only with --convergence");
    if (command_line.action != CommandLine::Action::sweep &&
        !(command_line.sweep_axes.empty() && command_line.reference_overrides.empty()))
      throw InputError("", "--axis/--reference-set", "only with --sweep");
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
           "      time), DIR/runtimes.csv and DIR/comparison.png and .svg\n"
           "      (probe histories, drawn by gnuplot).\n"
           "  clothsim --convergence [PARAMS.prm] [--space K] [--time K] [--set ...]...\n"
           "           [--output-dir DIR]\n"
           "      convergence study: the scene at 'Mesh/Global refinements' +0..K\n"
           "      (--space) and/or at 'Time/Time step' / 1, 2, ..., 2^K (--time), each\n"
           "      run in DIR/space-N or DIR/time-N (DIR default\n"
           "      output/<name>-convergence/). Errors at the end of the run: probes\n"
           "      against their 'Output/Probe references' where given, and probes and\n"
           "      the whole mesh (on the coarsest run's vertices) against the\n"
           "      Richardson extrapolation of the three finest runs (the finest run\n"
           "      with fewer). Prints the table with observed orders; writes\n"
           "      DIR/convergence.csv and DIR/convergence.png, .svg (log-log).\n"
           "  clothsim --sweep [PARAMS.prm] [--axis \"A=x | A=y & B=z\"]...\n"
           "           [--reference-set ...]... [--set ...]... [--output-dir DIR]\n"
           "      speed-accuracy sweep: runs every combination of the axes (each\n"
           "      alternative one or more assignments joined by '&'; without --axis\n"
           "      a default grid of model, integrator, step and Newton method, plus\n"
           "      the midpoint rule with a 1 mm accuracy target) and a converged\n"
           "      reference (default: implicit midpoint, newton, fem, an eighth of the\n"
           "      grid's smallest step, its finest mesh; --reference-set changes it).\n"
           "      Error: the largest vertex position difference from the reference\n"
           "      at the end (m). Writes DIR/pareto.csv and DIR/pareto.png, .svg "
           "(runtime\n"
           "      against error, Pareto front marked) and prints the fastest setting\n"
           "      for each error level.\n"
           "  clothsim --restart DIR [--set \"Time/End time=T\"]...\n"
           "      continue the run whose output directory is DIR from its last\n"
           "      checkpoint (DIR/checkpoint.bin), on as many MPI ranks; --set may\n"
           "      change 'Time/End time' and 'Output/Output interval', 'Checkpoint\n"
           "      interval', 'Progress' only.\n"
           "  clothsim --print-parameters [json]\n"
           "      print every parameter with its default, allowed values and unit\n"
           "      (with json: one JSON object, sections holding entries, each entry\n"
           "      {\"default\", \"allowed\", \"documentation\"}).\n"
           "  clothsim --version\n"
           "      clothsim's version and git revision, and the versions of deal.II,\n"
           "      Trilinos, MUMPS, gmsh and MPI it was built with (every run's log and\n"
           "      parameters.prm start with them).\n"
           "  clothsim --help\n"
           "      this text.\n"
           "\n"
           "Under MPI: mpirun -np N clothsim PARAMS.prm (same results for any N).\n";
  }
} // namespace clothsim
