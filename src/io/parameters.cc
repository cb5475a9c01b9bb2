// All sections together, and reading a parameter file (.prm or .json) with --set
// overrides into them: deal.II's parse errors turned into one-line InputErrors, and the
// checks across sections that patterns cannot express. The sections are declared and
// parsed in io/parameters_<section>.cc.

#include "io/parameters.h"

#include <deal.II/base/parameter_handler.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include "io/input_error.h"
#include "io/input_file.h"
#include "io/parameter_errors.h"
#include "io/parameters_detail.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

namespace clothsim
{
  namespace detail
  {
    Tensor<1, 3>
    vector_entry(const std::string &text)
    {
      const auto values =
        Utilities::string_to_double(Utilities::split_string_list(text, ','));
      Tensor<1, 3> vector;
      for (unsigned int d = 0; d < 3; ++d)
        vector[d] = values[d];
      return vector;
    }
  } // namespace detail


  namespace
  {
    // deal.II's parser follows 'INCLUDE file' (or 'include file') lines, with the path as
    // given, and recurses without a limit: a file that includes itself overflows the
    // stack. The include graph is walked here first: a cycle, or nesting deeper than
    // this, is an input error.
    constexpr unsigned int max_include_depth = 8;

    void
    check_includes(const std::string &file, std::vector<std::string> &chain)
    {
      std::error_code   error;
      const std::string identity =
        std::filesystem::weakly_canonical(file, error).string();
      for (const std::string &outer : chain)
        if (outer == identity)
          throw InputError(chain.front(),
                           "",
                           "INCLUDE cycle: " + file + " includes itself");
      if (chain.size() > max_include_depth)
        throw InputError(chain.front(),
                         "",
                         "INCLUDE nested deeper than " +
                           std::to_string(max_include_depth) + " files (at " + file +
                           ")");
      chain.push_back(identity);
      std::ifstream in(file);
      std::string   line;
      while (std::getline(in, line))
        {
          line = Utilities::trim(line.substr(0, line.find('#')));
          if (line.rfind("INCLUDE ", 0) == 0 || line.rfind("include ", 0) == 0)
            {
              const std::string included = Utilities::trim(line.substr(8));
              if (input_file_type(included, "INCLUDE " + included) ==
                  std::filesystem::file_type::regular)
                check_includes(included, chain);
            }
        }
      chain.pop_back();
    }
  } // namespace


  void
  Parameters::declare_parameters(ParameterHandler &prm, const std::string &preset)
  {
    SceneParameters::declare_parameters(prm);
    MaterialParameters::declare_parameters(prm, preset);
    MassSpringParameters::declare_parameters(prm);
    DampingParameters::declare_parameters(prm);
    LoadParameters::declare_parameters(prm);
    AirParameters::declare_parameters(prm);
    ConstraintParameters::declare_parameters(prm);
    TimeParameters::declare_parameters(prm);
    NonlinearSolverParameters::declare_parameters(prm);
    LinearSolverParameters::declare_parameters(prm);
    OutputParameters::declare_parameters(prm);
    ContactParameters::declare_parameters(prm);
  }

  void
  Parameters::parse_parameters(ParameterHandler &prm)
  {
    scene.parse_parameters(prm);
    material.parse_parameters(prm);
    mass_spring.parse_parameters(prm);
    damping.parse_parameters(prm);
    loads.parse_parameters(prm);
    air.parse_parameters(prm);
    constraints.parse_parameters(prm);
    time.parse_parameters(prm);
    nonlinear_solver.parse_parameters(prm);
    linear_solver.parse_parameters(prm);
    output.parse_parameters(prm);
    contact.parse_parameters(prm);
    // 'automatic' resolved here, where the integrator is known: a dynamic step's mass
    // term makes the projected tangent positive definite without losing quadratic
    // convergence in tension; a static step has none.
    if (nonlinear_solver.tangent == "automatic")
      nonlinear_solver.tangent = is_static(time.integrator) ? "adaptive" : "projected";
    if (time.integrator == Integrator::linear_static)
      {
        // One linearised step from the reference state with the exact tangent, taken
        // whatever the residual (no tolerance could stop it before it moved).
        time.load_steps                            = 1;
        time.adaptive_load_steps                   = false;
        time.max_step_halvings                     = 0; // half the load is no answer
        nonlinear_solver.method                    = NewtonMethod::single_step;
        nonlinear_solver.tangent                   = "exact";
        nonlinear_solver.mixed_stress_tangent      = false;
        nonlinear_solver.absolute_tolerance        = 0.;
        nonlinear_solver.relative_tolerance        = 0.;
        nonlinear_solver.displacement_tolerance    = 0.;
        nonlinear_solver.truncation_error_fraction = 0.;
      }
  }


  bool
  mentions_time(const std::string &expression)
  {
    static const std::regex token("(^|[^A-Za-z0-9_])t([^A-Za-z0-9_(]|$)");
    return std::regex_search(expression, token);
  }


  bool
  Parameters::prescribes_motion() const
  {
    if (!constraints.pinned_groups.empty() &&
        mentions_time(constraints.pinned_displacement))
      return true;
    for (const PrescribedRotation &rotation : constraints.prescribed_rotations)
      if (mentions_time(rotation.expressions))
        return true;
    for (const ObstacleParameters &obstacle : contact.obstacles)
      if (mentions_time(obstacle.translation) || mentions_time(obstacle.rotation_angle) ||
          std::isfinite(obstacle.removal_time))
        return true;
    return false;
  }


  namespace
  {
    // Reads the file (.prm or .json) into `prm`, then the --set assignments. Errors in
    // the common format of io/parameter_errors.h.
    void
    parse_file_and_overrides(ParameterHandler               &prm,
                             const std::string              &file,
                             const std::vector<std::string> &overrides)
    {
      const io::DeclaredParameters declared(prm);
      const bool json = std::filesystem::path(file).extension() == ".json";
      if (json)
        io::check_json_names(file, declared);
      try
        {
          prm.parse_input(file, "", /*skip_undefined=*/false, /*assert_mandatory=*/false);
        }
      catch (const std::exception &e)
        {
          if (json)
            io::throw_json_error(file, io::one_line(e));
          io::throw_prm_error(file, io::one_line(e), declared);
        }
      // --set "Section/Sub/Name=value"
      for (const std::string &assignment : overrides)
        io::apply_assignment(prm, assignment, declared);
    }
  } // namespace


  ParameterInput
  read_parameters(ParameterHandler               &prm,
                  const std::string              &file,
                  const std::vector<std::string> &overrides)
  {
    Parameters::declare_parameters(prm);

    ParameterInput input;
    input.file      = file;
    input.overrides = overrides;
    input.directory = std::filesystem::path(file).parent_path().string();

    const std::filesystem::file_type type = input_file_type(file);
    if (type == std::filesystem::file_type::not_found)
      throw InputError(file, "", "parameter file not found");
    if (type != std::filesystem::file_type::regular)
      throw InputError(file, "", "not a regular file; expected a parameter file");
    {
      std::ifstream probe(file);
      if (!probe)
        throw InputError(file, "", "parameter file cannot be read");
    }
    if (std::filesystem::path(file).extension() != ".json")
      {
        std::vector<std::string> chain;
        check_includes(file, chain);
      }
    parse_file_and_overrides(prm, file, overrides);
    // A fabric preset supplies defaults: declare again with them, and read the input
    // again, so that what the file and --set give overrides the preset.
    prm.enter_subsection("Material");
    const std::string preset = prm.get("Preset");
    prm.leave_subsection();
    if (preset != "none")
      {
        prm.clear();
        Parameters::declare_parameters(prm, preset);
        parse_file_and_overrides(prm, file, overrides);
      }

    try
      {
        input.parameters.parse_parameters(prm);
      }
    catch (const InputError &e)
      {
        throw InputError(file, e.entry, e.message, e.line);
      }
    catch (const std::exception &e)
      {
        throw InputError(file, "", io::one_line(e));
      }

    // Checks that patterns cannot express.
    const Parameters &parameters  = input.parameters;
    const bool        mass_spring = parameters.scene.model == Model::mass_spring;
    if (is_explicit(parameters.time.integrator))
      {
        if (parameters.material.bending && !mass_spring)
          throw InputError(file,
                           "Time/Integrator",
                           "explicit integrators need a mass on every unknown; the "
                           "shell's director angles have none: use 'backward "
                           "euler', or 'Model = mass-spring'");
        if (!parameters.material.lumped_mass)
          throw InputError(file,
                           "Time/Integrator",
                           "explicit integrators need 'Material/Mass = lumped'");
      }
    const Integrator integrator = parameters.time.integrator;
    if ((!parameters.contact.obstacles.empty() || parameters.contact.self_contact) &&
        integrator != Integrator::backward_euler && integrator != Integrator::bdf2 &&
        integrator != Integrator::static_load_steps)
      throw InputError(
        file,
        "Time/Integrator",
        std::string(parameters.contact.obstacles.empty() ? "self-contact"
                                                         : "contact with obstacles") +
          " needs 'backward euler', 'bdf2' or 'static' (the barrier holds "
          "the state solved for, which the midpoint rules and the explicit "
          "integrators do not end on, and a linear solve does not keep)");
    if (parameters.contact.adaptive_stiffness &&
        (parameters.nonlinear_solver.line_search == "full step" ||
         parameters.nonlinear_solver.method == NewtonMethod::single_step))
      throw InputError(file,
                       "Contact/Adaptive barrier stiffness",
                       "raises the stiffness at the iterates the energy line search "
                       "accepts: it needs 'Nonlinear solver/Line search = energy' and a "
                       "method other than 'single step'");
    if (mass_spring && parameters.material.orthotropic &&
        parameters.mass_spring.derived_constants)
      throw InputError(file,
                       "Material/Anisotropy",
                       "the mass-spring model derives its spring constants for an "
                       "isotropic sheet only; use 'isotropic', or 'Mass spring/Spring "
                       "constants = given'");
    if (mass_spring && !parameters.material.lumped_mass)
      throw InputError(file,
                       "Material/Mass",
                       "the mass-spring model has lumped masses only; set 'lumped'");
    if (parameters.time.accuracy_target > 0. && (is_static(parameters.time.integrator) ||
                                                 is_explicit(parameters.time.integrator)))
      throw InputError(file,
                       "Time/Accuracy target",
                       "an accuracy target needs an implicit dynamic integrator "
                       "(backward euler, bdf2, implicit midpoint, average vector field)");
    if (parameters.time.accuracy_target > 0. &&
        parameters.nonlinear_solver.method == NewtonMethod::single_step)
      throw InputError(file,
                       "Time/Accuracy target",
                       "an accuracy target needs a Newton method that solves each step "
                       "('single step' leaves it unsolved)");
    if (parameters.time.adaptive_time_steps && (is_static(parameters.time.integrator) ||
                                                is_explicit(parameters.time.integrator)))
      throw InputError(file,
                       "Time/Adaptive time steps",
                       "adaptive time steps are for the implicit dynamic integrators "
                       "(backward euler, bdf2, implicit midpoint, average vector field)");
    if (parameters.time.adaptive_time_steps && parameters.time.accuracy_target == 0. &&
        parameters.time.error_tolerance == 0. &&
        parameters.time.relative_error_tolerance == 0.)
      throw InputError(file,
                       "Time/Error tolerance",
                       "adaptive time steps need a positive absolute or relative "
                       "tolerance");
    if (parameters.nonlinear_solver.method == NewtonMethod::single_step &&
        parameters.time.integrator == Integrator::static_load_steps)
      throw InputError(file,
                       "Nonlinear solver/Method",
                       "static mode needs a converging method (a single linearised "
                       "step does not find the equilibrium)");
    if (parameters.linear_solver.factor_precision == "single" &&
        (parameters.linear_solver.method != "direct" ||
         parameters.linear_solver.direct_solver != "mumps"))
      throw InputError(file,
                       "Linear solver/Factor precision",
                       "single-precision factors are MUMPS': set 'Linear solver/Method "
                       "= direct' and 'Direct solver = mumps', or 'Factor precision = "
                       "double'");
    if (parameters.nonlinear_solver.method == NewtonMethod::inexact &&
        parameters.linear_solver.method == "direct")
      throw InputError(file,
                       "Nonlinear solver/Method",
                       "'inexact newton' sets the tolerance of an iterative linear "
                       "solver; 'Linear solver/Method' is 'direct'");
    if (parameters.nonlinear_solver.method == NewtonMethod::inexact &&
        parameters.nonlinear_solver.forcing_term_maximum <
          parameters.linear_solver.relative_tolerance)
      throw InputError(file,
                       "Nonlinear solver/Forcing term maximum",
                       "is below 'Linear solver/Relative tolerance', the tightest "
                       "forcing term");
    if (parameters.mass_spring.strain_limit > 0. &&
        (!mass_spring || is_static(parameters.time.integrator)))
      throw InputError(file,
                       "Mass spring/Strain limit",
                       "the strain limit corrects dynamic steps of the mass-spring "
                       "model only; set it to 0");
    if (parameters.air.density > 0. &&
        (is_static(integrator) || is_explicit(integrator) ||
         integrator == Integrator::average_vector_field))
      throw InputError(
        file,
        "Air/Density",
        "air drag acts on the velocity of an implicit step, its "
        "geometry lagged at the step's start (the explicit steps have "
        "no such state, static steps no velocity, and the average "
        "vector field takes the drag at velocities from 0 to twice the "
        "step's: 4/3 of it in still air): use 'backward euler', 'bdf2' or 'implicit "
        "midpoint', or set the density to 0");
    if (integrator == Integrator::arc_length && parameters.linear_solver.method == "cg")
      throw InputError(file,
                       "Linear solver/Method",
                       "'arc length' follows the path past limit points, where the "
                       "tangent is indefinite and CG breaks down: use 'direct' or "
                       "'gmres'");
    if (integrator == Integrator::arc_length &&
        parameters.output.checkpoint_interval > 0.)
      throw InputError(file,
                       "Output/Checkpoint interval",
                       "'arc length' runs write no checkpoints; set it to 0");
    for (const Probe &probe : input.parameters.output.probes)
      if (probe.name.empty() || probe.name.find(',') != std::string::npos)
        throw InputError(file,
                         "Output/Probes",
                         "probe names must be non-empty, without commas");
    return input;
  }
} // namespace clothsim
