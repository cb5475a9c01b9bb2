#include "io/parameters.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>

#include "io/input_error.h"

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace clothsim
{
  namespace
  {
    // A deal.II exception's "Additional information" as one line.
    std::string
    one_line(const std::exception &exception)
    {
      std::string       text   = exception.what();
      const std::string marker = "Additional information:";
      const auto        pos    = text.find(marker);
      if (pos != std::string::npos)
        text = text.substr(pos + marker.size());
      const auto stacktrace = text.find("Stacktrace:");
      if (stacktrace != std::string::npos)
        text = text.substr(0, stacktrace);
      text = std::regex_replace(text, std::regex("[\\s-]*\\n[\\s-]*"), " ");
      text = std::regex_replace(text, std::regex("\\s+"), " ");
      text = std::regex_replace(text, std::regex("^ | $"), "");
      return text;
    }

    // deal.II's parse errors ("Line <N> of file <F>: ...") as (entry, one-line text),
    // with the entry given as Section/Name where the message names one.
    std::pair<std::string, std::string>
    describe_parse_error(const std::string &message, const std::string &section)
    {
      const std::string prefix = section.empty() ? "" : section + "/";
      std::smatch       match;
      if (std::regex_search(message,
                            match,
                            std::regex(
                              "Line <([0-9]+)> of file <[^>]*>: The entry value (.*) "
                              "for the entry named (.*) does not match the given "
                              "pattern:? (.*)$")))
        return {prefix + std::string(match[3]),
                "value " + std::string(match[2]) + " does not match " +
                  std::string(match[4]) + " (line " + std::string(match[1]) + ")"};
      if (std::regex_search(message,
                            match,
                            std::regex(
                              "Line <([0-9]+)> of file <[^>]*>: No entry with name "
                              "<([^>]*)> was declared")))
        return {prefix + std::string(match[2]),
                "no such entry (line " + std::string(match[1]) +
                  "; clothsim --print-parameters lists them all)"};
      if (std::regex_search(message,
                            match,
                            std::regex("Line <([0-9]+)> of file <[^>]*>: (.*)$")))
        return {"line " + std::string(match[1]), std::string(match[2])};
      return {"", message};
    }

    const char *const solver_methods = "cg|gmres|direct";

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

    // 'name: fx, fy, fz; name2: ...' (already matched by the entry's Patterns::Map).
    std::vector<GroupLoad>
    group_loads(const std::string &text)
    {
      std::vector<GroupLoad> loads;
      for (const std::string &item : Utilities::split_string_list(text, ';'))
        {
          const auto name_value = Utilities::split_string_list(item, ':');
          loads.push_back({name_value[0], vector_entry(name_value[1])});
        }
      return loads;
    }

    // The subsection path (a/b) enclosing the line named in deal.II's "Line <N> of file"
    // message.
    std::string
    current_section(const std::string &file, const std::string &message)
    {
      std::smatch match;
      if (!std::regex_search(message, match, std::regex("Line <([0-9]+)>")))
        return "";
      const unsigned int       line_number = std::stoi(match[1]);
      std::ifstream            in(file);
      std::vector<std::string> sections;
      std::string              line;
      for (unsigned int n = 1; n < line_number && std::getline(in, line); ++n)
        {
          std::smatch words;
          if (std::regex_search(line,
                                words,
                                std::regex("^\\s*subsection\\s+(.*?)\\s*(#.*)?$")))
            sections.push_back(words[1]);
          else if (std::regex_search(line, std::regex("^\\s*end\\s*(#.*)?$")) &&
                   !sections.empty())
            sections.pop_back();
        }
      std::string path;
      for (const std::string &section : sections)
        path += (path.empty() ? "" : "/") + section;
      return path;
    }

    // 'name: a, b, c; name2: ...' (Output/Probes, Output/Probe references): the pattern
    // and the parsed entries.
    Patterns::Map
    named_triples_pattern()
    {
      return Patterns::Map(Patterns::Anything(),
                           Patterns::List(Patterns::Double(), 3, 3, ","),
                           0,
                           1000,
                           ";",
                           ":");
    }

    std::vector<std::pair<std::string, Tensor<1, 3>>>
    parse_named_triples(const std::string &text)
    {
      std::vector<std::pair<std::string, Tensor<1, 3>>> entries;
      for (const std::string &item : Utilities::split_string_list(text, ';'))
        {
          const auto name_value = Utilities::split_string_list(item, ':');
          const auto v =
            Utilities::string_to_double(Utilities::split_string_list(name_value[1], ','));
          entries.emplace_back(name_value[0], Tensor<1, 3>({v[0], v[1], v[2]}));
        }
      return entries;
    }
  } // namespace


  void
  SceneParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry(
      "Scene name",
      "",
      Patterns::Anything(),
      "Name of the run; output goes to output/<Scene name>/ unless --output-dir "
      "is given. Empty: the parameter file's name without extension.");
    prm.declare_entry("Model",
                      "fem",
                      Patterns::Selection("fem|mass-spring"),
                      "How the cloth's elasticity is discretised: 'fem' (membrane finite "
                      "elements, plus the shell's bending if Material/Bending is set) or "
                      "'mass-spring' (Provot's springs on the same mesh, constants from "
                      "Material or given in 'Mass spring'; see physics/mass_spring.h).");
    prm.enter_subsection("Mesh");
    prm.declare_entry(
      "Mesh file",
      "../meshes/sheet.msh",
      Patterns::FileName(),
      "gmsh triangle mesh (.msh), relative to this parameter file's directory. "
      "If it is missing but a .geo of the same name exists, gmsh generates it. "
      "Lengths in the mesh are in m.");
    prm.declare_entry("Global refinements",
                      "0",
                      Patterns::Integer(0, 8),
                      "Number of uniform (red) refinements of the mesh as read; each one "
                      "quarters the triangles' area.");
    prm.declare_entry(
      "Surface",
      "flat",
      Patterns::Selection("flat|cylinder|sphere"),
      "The exact rest surface of a curved mesh: refinement places new vertices "
      "on it, so a refined cylinder stays a cylinder. 'flat': new vertices at edge "
      "midpoints (right for flat sheets).");
    prm.declare_entry("Surface center",
                      "0, 0, 0",
                      Patterns::List(Patterns::Double(), 3, 3, ","),
                      "A point on the cylinder's axis, or the sphere's centre (m).");
    prm.declare_entry("Surface axis",
                      "0, 0, 1",
                      Patterns::List(Patterns::Double(), 3, 3, ","),
                      "Direction of the cylinder's axis.");
    prm.leave_subsection();
  }

  void
  SceneParameters::parse_parameters(ParameterHandler &prm)
  {
    name  = prm.get("Scene name");
    model = prm.get("Model") == "mass-spring" ? Model::mass_spring : Model::fem;
    prm.enter_subsection("Mesh");
    mesh_file          = prm.get("Mesh file");
    global_refinements = prm.get_integer("Global refinements");
    surface            = prm.get("Surface");
    surface_center     = Point<3>(vector_entry(prm.get("Surface center")));
    surface_axis       = vector_entry(prm.get("Surface axis"));
    if (surface == "cylinder" && surface_axis.norm() == 0.)
      throw InputError("", "Mesh/Surface axis", "the cylinder axis must not be zero");
    prm.leave_subsection();
  }


  void
  MaterialParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material");
    prm.declare_entry(
      "Stiffness given as",
      "E*h",
      Patterns::Selection("E*h|E and thickness"),
      "How the membrane (stretch) stiffness is given: 'E*h' uses 'Stretch "
      "stiffness' directly (fabrics); 'E and thickness' uses Young's modulus "
      "times thickness (engineering shells).");
    prm.declare_entry(
      "Stretch stiffness",
      "100",
      Patterns::Double(1e-12, 1e15),
      "Membrane stiffness E*h in N/m (used when 'Stiffness given as = E*h').");
    prm.declare_entry("Young's modulus",
                      "1e6",
                      Patterns::Double(1e-12, 1e15),
                      "Young's modulus E in Pa (used when 'Stiffness given as = E and "
                      "thickness').");
    prm.declare_entry("Thickness",
                      "1e-3",
                      Patterns::Double(1e-12, 1e3),
                      "Shell thickness h in m (used when 'Stiffness given as = E and "
                      "thickness').");
    prm.declare_entry("Poisson ratio",
                      "0.3",
                      Patterns::Double(0., 0.499),
                      "Poisson's ratio ν (dimensionless), 0 <= ν < 0.5.");
    prm.declare_entry("Areal density",
                      "0.1",
                      Patterns::Double(1e-12, 1e6),
                      "Mass per unit reference area ρ_A in kg/m².");
    prm.declare_entry(
      "Mass",
      "lumped",
      Patterns::Selection("lumped|consistent"),
      "Mass matrix: 'lumped' (a third of each triangle's mass on each vertex) "
      "or 'consistent' (the P1 Galerkin mass matrix).");
    prm.declare_entry(
      "Bending",
      "none",
      Patterns::Selection("none|E and thickness|rigidity"),
      "Bending stiffness (midedge-director shell, physics/bending.h): 'none' "
      "(a membrane; no bending term is assembled), 'E and thickness' (plate "
      "rigidity D = E h^3 / (12 (1 - nu^2)) from 'Young's modulus', 'Thickness' "
      "and 'Poisson ratio'), or 'rigidity' ('Bending rigidity' given directly, "
      "as measured for fabrics).");
    prm.declare_entry("Bending rigidity",
                      "1e-5",
                      Patterns::Double(0., 1e15),
                      "Bending rigidity D in N·m (= J), used when 'Bending = rigidity'. "
                      "Fabrics: roughly 1e-6 to 1e-3.");
    prm.declare_entry(
      "Director function",
      "angle",
      Patterns::Selection("angle|sine|tangent"),
      "f in the edge curvature 2 h f(tilt): 'angle' (f = id), 'sine', or "
      "'tangent' (a barrier against folding a triangle flat onto its neighbour). "
      "All three agree for small tilts.");
    prm.leave_subsection();
  }

  void
  MaterialParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material");
    if (prm.get("Stiffness given as") == "E*h")
      stretch_stiffness = prm.get_double("Stretch stiffness");
    else
      stretch_stiffness = prm.get_double("Young's modulus") * prm.get_double("Thickness");
    poisson_ratio                      = prm.get_double("Poisson ratio");
    areal_density                      = prm.get_double("Areal density");
    lumped_mass                        = prm.get("Mass") == "lumped";
    const std::string bending_given_as = prm.get("Bending");
    bending                            = bending_given_as != "none";
    if (bending_given_as == "rigidity")
      bending_rigidity = prm.get_double("Bending rigidity");
    else
      {
        const double h   = prm.get_double("Thickness");
        bending_rigidity = prm.get_double("Young's modulus") * h * h * h /
                           (12. * (1. - poisson_ratio * poisson_ratio));
      }
    director_function = prm.get("Director function");
    prm.leave_subsection();
  }


  void
  MassSpringParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mass spring");
    prm.declare_entry(
      "Spring constants",
      "derived",
      Patterns::Selection("derived|given"),
      "'derived': from Material, so that both models describe the same cloth: "
      "structural springs k_e = 8/(9(1-nu^2)) E h sum|T|/L^2 over the edge's "
      "triangles, bend springs from the bending rigidity D (none without "
      "Material/Bending), no separate shear springs (the triangles' edges resist "
      "shear). 'given': the three stiffnesses below, the same on every spring, as "
      "in classic Provot scenes. Formulas and their limits: physics/mass_spring.h.");
    prm.declare_entry("Structural stiffness",
                      "100",
                      Patterns::Double(0., 1e15),
                      "'given': stiffness in N/m of the spring on every mesh edge.");
    prm.declare_entry(
      "Shear stiffness",
      "0",
      Patterns::Double(0., 1e15),
      "'given': stiffness in N/m of the spring across every interior edge "
      "(between the two vertices opposite it), added to 'Bend stiffness'.");
    prm.declare_entry(
      "Bend stiffness",
      "0",
      Patterns::Double(0., 1e15),
      "'given': stiffness in N/m of the spring across every interior edge.");
    prm.declare_entry(
      "Bend reference angle",
      "10",
      Patterns::Double(1e-3, 90.),
      "'derived': fold angle (degrees) at which a bend spring's energy equals the "
      "continuum's hinge energy D L^2/(2(A1+A2)) theta^2; softer below, stiffer "
      "above (a spring's bending energy grows like theta^4).");
    prm.declare_entry(
      "Strain limit",
      "0",
      Patterns::Double(0., 10.),
      "Provot's deformation limit: after every step, structural springs "
      "stretched by more than this strain (l - L)/L are shortened back to it, "
      "moving both ends by their inverse masses, and the velocities follow. "
      "0: off; 0.1 is Provot's 10 %. Dynamic runs only.");
    prm.declare_entry("Strain limit compression",
                      "false",
                      Patterns::Bool(),
                      "Also lengthen springs compressed by more than 'Strain limit'.");
    prm.declare_entry(
      "Strain limit iterations",
      "10",
      Patterns::Integer(1, 1000),
      "Correction sweeps per step at most (each sweep corrects all springs at "
      "once and averages the moves of shared vertices); a warning tells when "
      "springs remain beyond the limit.");
    prm.leave_subsection();
  }

  void
  MassSpringParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mass spring");
    derived_constants       = prm.get("Spring constants") == "derived";
    structural_stiffness    = prm.get_double("Structural stiffness");
    shear_stiffness         = prm.get_double("Shear stiffness");
    bend_stiffness          = prm.get_double("Bend stiffness");
    bend_reference_angle    = prm.get_double("Bend reference angle") * numbers::PI / 180.;
    strain_limit            = prm.get_double("Strain limit");
    limit_compression       = prm.get_bool("Strain limit compression");
    strain_limit_iterations = prm.get_integer("Strain limit iterations");
    if (!derived_constants && structural_stiffness == 0.)
      throw InputError("",
                       "Mass spring/Structural stiffness",
                       "must be positive: without structural springs the mesh's "
                       "vertices are not held together");
    prm.leave_subsection();
  }


  void
  DampingParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Damping");
    prm.declare_entry(
      "Mass proportional",
      "0",
      Patterns::Double(0., 1e6),
      "Rayleigh coefficient α in 1/s: damping force -α M v (air-like drag on "
      "every motion, rigid included).");
    prm.declare_entry(
      "Stiffness proportional",
      "0",
      Patterns::Double(0., 1e3),
      "Rayleigh coefficient β in s: damping force -β K v, K the (positive "
      "semi-definite) membrane tangent at the start of the step; damps "
      "straining only.");
    prm.leave_subsection();
  }

  void
  DampingParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Damping");
    mass_proportional      = prm.get_double("Mass proportional");
    stiffness_proportional = prm.get_double("Stiffness proportional");
    prm.leave_subsection();
  }


  void
  LoadParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Loads");
    prm.declare_entry("Gravity",
                      "0, 0, -9.81",
                      Patterns::List(Patterns::Double(-1e6, 1e6), 3, 3, ","),
                      "Gravitational acceleration g (x, y, z) in m/s².");
    const auto group_vectors =
      Patterns::Map(Patterns::Anything(),
                    Patterns::List(Patterns::Double(), 3, 3, ","),
                    0,
                    1000,
                    ";",
                    ":");
    prm.declare_entry(
      "Point forces",
      "",
      group_vectors,
      "Forces in N on every vertex of gmsh point groups: 'name: fx, fy, fz; "
      "name2: ...'. Dead loads; scaled by the load factor in static mode.");
    prm.declare_entry(
      "Line forces",
      "",
      group_vectors,
      "Forces in N per m of reference length along gmsh boundary line groups: "
      "'name: qx, qy, qz; ...', lumped onto the edges' vertices. Dead loads; "
      "scaled by the load factor in static mode.");
    prm.declare_entry(
      "Pressure",
      "0",
      Patterns::Double(),
      "Pressure in Pa on the whole surface, along the current normal (x1 - x0) x "
      "(x2 - x0) of each triangle (a follower load). Exact where the surface is "
      "closed or its boundary is held; on free edges it acts through the potential "
      "-p V (V: volume of the cones from the reference centroid to the triangles), "
      "see physics/pressure.h. Scaled by the load factor in static mode.");
    prm.leave_subsection();
  }

  void
  LoadParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Loads");
    const auto values =
      Utilities::string_to_double(Utilities::split_string_list(prm.get("Gravity"), ','));
    for (unsigned int d = 0; d < 3; ++d)
      gravity[d] = values[d];
    point_forces = group_loads(prm.get("Point forces"));
    line_forces  = group_loads(prm.get("Line forces"));
    pressure     = prm.get_double("Pressure");
    prm.leave_subsection();
  }


  void
  ConstraintParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Constraints");
    prm.declare_entry(
      "Pinned groups",
      "",
      Patterns::List(Patterns::Anything(), 0, 100, ";"),
      "gmsh physical groups (points, boundary lines or surfaces) whose vertices "
      "follow 'Pinned displacement', separated by ';'. Each is 'name' (all "
      "components) or 'name: components' with components from x, y, z, e.g. "
      "'pinned' or 'left: x; corner: xy; cloth: z'.");
    prm.declare_entry(
      "Pinned displacement",
      "0; 0; 0",
      Patterns::List(Patterns::Anything(), 3, 3, ";"),
      "Displacement of pinned vertices in m: three expressions 'ux; uy; uz' in "
      "the reference coordinates x, y, z (m) and time t (s), e.g. "
      "'0; 0; 0.1*sin(2*pi*t)'. In static mode t is the load factor 0..1.");
    prm.declare_entry(
      "Clamped groups",
      "",
      Patterns::List(Patterns::Anything(), 0, 100, ";"),
      "gmsh boundary line groups that are clamped, separated by ';': their "
      "vertices are fixed and the shell's director along them keeps its rest "
      "direction (rotation about the edge held). Needs 'Material/Bending'. A line "
      "group in 'Pinned groups' instead is simply supported (rotation free).");
    prm.leave_subsection();
  }

  void
  ConstraintParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Constraints");
    pinned_groups.clear();
    for (const std::string &item :
         Utilities::split_string_list(prm.get("Pinned groups"), ';'))
      {
        const auto  parts = Utilities::split_string_list(item, ':');
        PinnedGroup group{parts[0], {{true, true, true}}};
        if (parts.size() > 2 || parts[0].empty() ||
            (parts.size() == 2 &&
             parts[1].find_first_not_of("xyz") != std::string::npos) ||
            (parts.size() == 2 && parts[1].empty()))
          throw InputError("",
                           "Constraints/Pinned groups",
                           "'" + item +
                             "' is not 'name' or 'name: components' (components "
                             "from x, y, z)");
        if (parts.size() == 2)
          for (unsigned int d = 0; d < 3; ++d)
            group.components[d] = parts[1].find("xyz"[d]) != std::string::npos;
        pinned_groups.push_back(group);
      }
    pinned_displacement = prm.get("Pinned displacement");
    clamped_groups      = Utilities::split_string_list(prm.get("Clamped groups"), ';');
    prm.leave_subsection();
  }


  void
  TimeParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time");
    prm.declare_entry(
      "Integrator",
      "backward euler",
      Patterns::Selection(
        "backward euler|bdf2|implicit midpoint|static|symplectic euler|velocity verlet"),
      "'backward euler': implicit dynamics, each step the minimiser of the "
      "incremental potential (first order, damps high frequencies). 'bdf2': "
      "second-order backward differentiation with variable steps (the first "
      "step backward Euler), the same minimisation with other weights. 'implicit "
      "midpoint': second order and symplectic (no numerical damping; energy "
      "oscillates but does not drift): a backward-Euler minimisation over half "
      "the step to the midpoint, then extrapolation. 'static': equilibrium under "
      "loads ramped in "
      "'Load steps' equal increments (time = load factor 0..1). 'symplectic "
      "euler' (v first, then x; first order) and 'velocity verlet' (second "
      "order): explicit, one force evaluation per step, stable only below the "
      "critical step 2/omega_max, which the run estimates and prints (a warning "
      "if 'Time step' exceeds it); they need a lumped mass on every unknown "
      "(Model = mass-spring, or fem without bending).");
    prm.declare_entry("End time", "2", Patterns::Double(0., 1e9), "Simulated time in s.");
    prm.declare_entry("Time step",
                      "0.0166666666666667",
                      Patterns::Double(1e-12, 1e6),
                      "Time step dt in s (backward euler).");
    prm.declare_entry(
      "Maximum step halvings",
      "8",
      Patterns::Integer(0, 30),
      "A step whose Newton solve fails is retried with half the step, at most "
      "this many times in a row; then the run stops with an error.");
    prm.declare_entry("Load steps",
                      "10",
                      Patterns::Integer(1, 100000),
                      "Number of equal load increments in static mode (the first "
                      "increment's size 1/N when 'Adaptive load steps' is on).");
    prm.declare_entry(
      "Adaptive time steps",
      "false",
      Patterns::Bool(),
      "Implicit dynamics: choose each step from a local error estimate (the "
      "difference to an explicit predictor of the method's order, scaled by the "
      "methods' error constants; see time/time_stepper.h). A step whose estimate "
      "exceeds 'Error tolerance' + 'Relative error tolerance' x max|u| is "
      "rejected and retried smaller (counted in statistics.csv); accepted steps "
      "grow by at most 2x. 'Time step' is the first step. Newton then also "
      "stops once a full step moves no coordinate by more than a tenth of 'Error "
      "tolerance' (solving further is below the truncation error).");
    prm.declare_entry("Error tolerance",
                      "1e-4",
                      Patterns::Double(0., 1e3),
                      "Absolute local error tolerance per step in m (adaptive steps).");
    prm.declare_entry("Relative error tolerance",
                      "0",
                      Patterns::Double(0., 1.),
                      "Local error tolerance relative to the largest displacement "
                      "(adaptive steps).");
    prm.declare_entry("Maximum time step",
                      "0.1",
                      Patterns::Double(1e-12, 1e6),
                      "Largest step in s that adaptive stepping may take.");
    prm.declare_entry(
      "Accuracy target",
      "0",
      Patterns::Double(0., 1e3),
      "0: off. Otherwise the error in m the run may accumulate by the end: it "
      "turns on 'Adaptive time steps' with the tolerance of each step set to "
      "target x dt / 'End time' (error per unit step), so that the accepted "
      "local error estimates add up to at most the target; 'Error tolerance' and "
      "'Relative error tolerance' are then not used, and Newton stops at a tenth "
      "of each step's tolerance. The run reports that sum, its estimated error, "
      "at the end. Implicit dynamic integrators with a converging Newton method.");
    prm.declare_entry("Initial displacement",
                      "0; 0; 0",
                      Patterns::List(Patterns::Anything(), 3, 3, ";"),
                      "Displacement at t = 0 in m: three expressions 'ux; uy; uz' in the "
                      "reference coordinates x, y, z (m), e.g. a mode shape "
                      "'0; 0; 0.01*sin(pi*x)*sin(pi*y)'. Pinned vertices follow 'Pinned "
                      "displacement' instead. Dynamic integrators only.");
    prm.declare_entry("Initial velocity",
                      "0; 0; 0",
                      Patterns::List(Patterns::Anything(), 3, 3, ";"),
                      "Velocity at t = 0 in m/s: 'vx; vy; vz' in x, y, z (m). Dynamic "
                      "integrators only.");
    prm.declare_entry(
      "Adaptive load steps",
      "false",
      Patterns::Bool(),
      "Static mode: after an increment that Newton solves in at most 6 iterations "
      "the next one is 1.5 times larger (never more than 1/'Load steps' times 4); "
      "a failed increment is halved as always.");
    prm.leave_subsection();
  }

  void
  TimeParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time");
    const std::string name   = prm.get("Integrator");
    integrator               = name == "static" ? Integrator::static_load_steps
                               : name == "bdf2" ? Integrator::bdf2
                               : name == "implicit midpoint" ? Integrator::implicit_midpoint
                               : name == "symplectic euler" ? Integrator::symplectic_euler
                               : name == "velocity verlet"  ? Integrator::velocity_verlet
                                                            : Integrator::backward_euler;
    end_time                 = prm.get_double("End time");
    time_step                = prm.get_double("Time step");
    max_step_halvings        = prm.get_integer("Maximum step halvings");
    load_steps               = prm.get_integer("Load steps");
    adaptive_load_steps      = prm.get_bool("Adaptive load steps");
    adaptive_time_steps      = prm.get_bool("Adaptive time steps");
    error_tolerance          = prm.get_double("Error tolerance");
    relative_error_tolerance = prm.get_double("Relative error tolerance");
    maximum_time_step        = prm.get_double("Maximum time step");
    accuracy_target          = prm.get_double("Accuracy target");
    if (accuracy_target > 0.)
      adaptive_time_steps = true;
    initial_displacement = prm.get("Initial displacement");
    initial_velocity     = prm.get("Initial velocity");
    prm.leave_subsection();
  }


  void
  NonlinearSolverParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    prm.declare_entry(
      "Method",
      "newton",
      Patterns::Selection("newton|single step|inexact newton|modified newton"),
      "'newton': Newton iterations with line search until the tolerances below "
      "hold, each linear solve to 'Linear solver/Relative tolerance'. "
      "'single step': one linearised Newton step per time step, taken in "
      "full and accepted without a convergence test (Baraff & Witkin 1998): "
      "cheap, but the step's equations are not solved (measure the error against "
      "'newton'). Static mode needs a method that converges. "
      "'inexact newton': as 'newton', but each linear solve stops at the "
      "Eisenstat-Walker forcing term eta_k = 0.9 (|F_k|/|F_k-1|)^1.5 (their "
      "choice 2, safeguarded; between the linear solver's tolerance and "
      "'Forcing term maximum'): loose far from the solution, tight near it; needs "
      "an iterative linear solver. 'modified newton': a tangent and its "
      "preconditioner (or factorisation) serve up to 'Jacobian reuse' Newton "
      "iterations, across time steps while the step size stays the same; a new "
      "one is computed when an iteration reduces the residual by less than half, "
      "when the line search cuts a step, or after a failed step. Converges "
      "linearly: the step tolerances then bound the error only roughly.");
    prm.declare_entry(
      "Jacobian reuse",
      "10",
      Patterns::Integer(1, 10000),
      "'modified newton': the most Newton iterations one tangent serves.");
    prm.declare_entry(
      "Forcing term maximum",
      "0.1",
      Patterns::Double(1e-16, 0.9),
      "'inexact newton': the loosest relative tolerance of a linear solve (the "
      "first iteration of every step uses it).");
    prm.declare_entry("Maximum iterations",
                      "25",
                      Patterns::Integer(1, 1000),
                      "Newton iterations per step before the step counts as failed.");
    prm.declare_entry("Absolute tolerance",
                      "1e-9",
                      Patterns::Double(0., 1e10),
                      "Converged when the residual's 2-norm (N) is below this, ...");
    prm.declare_entry(
      "Relative tolerance",
      "1e-8",
      Patterns::Double(0., 1.),
      "... or below this times the residual at the step's first iterate.");
    prm.declare_entry(
      "Line search",
      "energy",
      Patterns::Selection("energy|full step"),
      "'energy': backtracking until the step's incremental potential decreases "
      "enough (Armijo); below its round-off, until the residual decreases. "
      "'full step': no line search.");
    prm.declare_entry(
      "Displacement tolerance",
      "1e-6",
      Patterns::Double(0., 1e3),
      "... or when a full Newton step (not cut by the line search) moves no "
      "vertex coordinate by more than this (m). 0 disables this criterion.");
    prm.declare_entry(
      "Print iterations",
      "false",
      Patterns::Bool(),
      "Print NOX's residual norm, step length and update norm for every Newton "
      "iteration (for diagnosing convergence).");
    prm.declare_entry(
      "Tangent",
      "adaptive",
      Patterns::Selection("adaptive|projected|exact"),
      "Compression makes the membrane Hessian indefinite. 'projected': the "
      "geometric stiffness keeps only as much compressive stress as the step's "
      "mass term pays for, so the tangent is positive definite and CG is valid "
      "(Newton converges linearly where the sheet is strongly compressed). "
      "'exact': the true Hessian (quadratic convergence; CG may break down, "
      "use 'gmres' or 'direct'). 'adaptive': the exact Hessian, replaced by the "
      "projected one for a Newton iteration whose linear solve fails or does "
      "not give a descent direction.");
    prm.leave_subsection();
  }

  void
  NonlinearSolverParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    const std::string method_name = prm.get("Method");
    method                 = method_name == "single step"      ? NewtonMethod::single_step
                             : method_name == "inexact newton" ? NewtonMethod::inexact
                             : method_name == "modified newton" ? NewtonMethod::modified
                                                                : NewtonMethod::full;
    jacobian_reuse         = prm.get_integer("Jacobian reuse");
    forcing_term_maximum   = prm.get_double("Forcing term maximum");
    max_iterations         = prm.get_integer("Maximum iterations");
    absolute_tolerance     = prm.get_double("Absolute tolerance");
    relative_tolerance     = prm.get_double("Relative tolerance");
    line_search            = prm.get("Line search");
    displacement_tolerance = prm.get_double("Displacement tolerance");
    print_iterations       = prm.get_bool("Print iterations");
    tangent                = prm.get("Tangent");
    prm.leave_subsection();
  }


  void
  LinearSolverParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    prm.declare_entry(
      "Method",
      "cg",
      Patterns::Selection(solver_methods),
      "Krylov method for each Newton step: 'cg' (needs the projected tangent), "
      "'gmres', or 'direct' (a sparse LU factorisation, see 'Direct solver').");
    prm.declare_entry(
      "Direct solver",
      "mumps",
      Patterns::Selection("mumps|klu"),
      "Sparse direct solver behind 'Method = direct' (through Amesos): 'mumps' "
      "(multifrontal, nested-dissection ordering, distributed; fast on large "
      "meshes) or 'klu' (serial, no fill-reducing ordering for 2D meshes; small "
      "systems).");
    prm.declare_entry(
      "Preconditioner",
      "amg",
      Patterns::Selection("amg|jacobi"),
      "'amg': ML smoothed-aggregation algebraic multigrid with one constant "
      "mode per displacement component; 'jacobi': point Jacobi.");
    prm.declare_entry(
      "Relative tolerance",
      "1e-6",
      Patterns::Double(1e-16, 1.),
      "Krylov stopping criterion, relative to the Newton residual's 2-norm.");
    prm.declare_entry("Maximum iterations",
                      "2000",
                      Patterns::Integer(1, 1000000),
                      "Krylov iterations before the linear solve counts as failed.");
    prm.declare_entry("AMG smoother sweeps",
                      "2",
                      Patterns::Integer(1, 20),
                      "Chebyshev smoother sweeps per multigrid level.");
    prm.declare_entry("AMG aggregation threshold",
                      "1e-4",
                      Patterns::Double(0., 1.),
                      "ML aggregation threshold (strength of connection).");
    prm.declare_entry(
      "AMG smoother range",
      "20",
      Patterns::Double(1.1, 1000.),
      "The Chebyshev smoother damps eigenvalues in [λ_max / range, λ_max] of "
      "each level (ML's 'smoother: Chebyshev alpha'). 20 keeps the CG iteration "
      "count flat under refinement on the default scene; ML's usual 10 gives "
      "fewer iterations on coarse meshes and about 30 % more per refinement.");
    prm.declare_entry(
      "AMG coarse size",
      "2000",
      Patterns::Integer(10, 100000),
      "Largest multigrid level solved directly (Amesos KLU), in unknowns.");
    prm.declare_entry(
      "AMG reuse aggregates",
      "true",
      Patterns::Bool(),
      "Keep the multigrid aggregates and only recompute the hierarchy's operators "
      "for a new tangent (same sparsity), as long as CG needs at most 30 % more "
      "iterations than right after the aggregates were built; false rebuilds "
      "everything for every tangent.");
    prm.leave_subsection();
  }

  void
  LinearSolverParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    method                    = prm.get("Method");
    direct_solver             = prm.get("Direct solver");
    preconditioner            = prm.get("Preconditioner");
    relative_tolerance        = prm.get_double("Relative tolerance");
    max_iterations            = prm.get_integer("Maximum iterations");
    amg_smoother_sweeps       = prm.get_integer("AMG smoother sweeps");
    amg_aggregation_threshold = prm.get_double("AMG aggregation threshold");
    amg_reuse_aggregates      = prm.get_bool("AMG reuse aggregates");
    amg_coarse_size           = prm.get_integer("AMG coarse size");
    amg_chebyshev_range       = prm.get_double("AMG smoother range");
    prm.leave_subsection();
  }


  void
  OutputParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry(
      "Output interval",
      "0.0333333333333333",
      Patterns::Double(0., 1e9),
      "Simulated time in s between VTK frames and probe rows (0: every step). "
      "The first and last states are always written.");
    prm.declare_entry("Write VTK",
                      "true",
                      Patterns::Bool(),
                      "Write solution.pvd and its frames.");
    prm.declare_entry(
      "Probes",
      "",
      named_triples_pattern(),
      "Named reference points 'name: X, Y, Z; name2: X, Y, Z' (m). Each snaps to "
      "the nearest mesh vertex; probes.csv records its reference position and "
      "displacement.");
    prm.declare_entry(
      "Probe references",
      "",
      named_triples_pattern(),
      "Closed-form displacements 'probe: ux, uy, uz; ...' (m) of named probes at "
      "the end of the run (static mode: at full load), e.g. an elastica's tip. "
      "Convergence studies (clothsim --convergence) measure the probes' errors "
      "against them; runs ignore them.");
    prm.declare_entry(
      "Progress",
      "auto",
      Patterns::Selection("auto|on|off"),
      "One updating progress line with ETA: 'auto' shows it on a terminal only.");
    prm.leave_subsection();
  }

  void
  OutputParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    interval  = prm.get_double("Output interval");
    write_vtk = prm.get_bool("Write VTK");
    probes.clear();
    for (const auto &[name, X] : parse_named_triples(prm.get("Probes")))
      probes.push_back({name, Point<3>(X), false, {}});
    for (const auto &[name, u] : parse_named_triples(prm.get("Probe references")))
      {
        const auto probe =
          std::find_if(probes.begin(), probes.end(), [&](const Probe &candidate) {
            return candidate.name == name;
          });
        if (probe == probes.end())
          throw InputError("",
                           "Output/Probe references",
                           "no probe named '" + name + "' in 'Output/Probes'");
        probe->has_reference          = true;
        probe->reference_displacement = u;
      }
    progress = prm.get("Progress");
    prm.leave_subsection();
  }


  void
  Parameters::declare_parameters(ParameterHandler &prm)
  {
    SceneParameters::declare_parameters(prm);
    MaterialParameters::declare_parameters(prm);
    MassSpringParameters::declare_parameters(prm);
    DampingParameters::declare_parameters(prm);
    LoadParameters::declare_parameters(prm);
    ConstraintParameters::declare_parameters(prm);
    TimeParameters::declare_parameters(prm);
    NonlinearSolverParameters::declare_parameters(prm);
    LinearSolverParameters::declare_parameters(prm);
    OutputParameters::declare_parameters(prm);
  }

  void
  Parameters::parse_parameters(ParameterHandler &prm)
  {
    scene.parse_parameters(prm);
    material.parse_parameters(prm);
    mass_spring.parse_parameters(prm);
    damping.parse_parameters(prm);
    loads.parse_parameters(prm);
    constraints.parse_parameters(prm);
    time.parse_parameters(prm);
    nonlinear_solver.parse_parameters(prm);
    linear_solver.parse_parameters(prm);
    output.parse_parameters(prm);
  }


  namespace
  {
    // ParameterHandler stores names with every character outside [A-Za-z0-9] as "_" and
    // two hex digits.
    std::string
    demangle(const std::string &name)
    {
      std::string plain;
      for (unsigned int i = 0; i < name.size(); ++i)
        if (name[i] == '_' && i + 2 < name.size())
          {
            plain += static_cast<char>(std::stoi(name.substr(i + 1, 2), nullptr, 16));
            i += 2;
          }
        else
          plain += name[i];
      return plain;
    }

    // Walks ParameterHandler's JSON tree: entries carry "default_value",
    // "pattern_description" and "documentation"; anything else is a subsection.
    void
    print_entries(std::ostream                      &out,
                  const boost::property_tree::ptree &tree,
                  const std::string                 &path)
    {
      for (const auto &[name, child] : tree)
        {
          const std::string demangled = demangle(name);
          if (child.get_optional<std::string>("default_value"))
            out << path << demangled << " = " << child.get<std::string>("default_value")
                << "\n    allowed: " << child.get<std::string>("pattern_description")
                << "\n    " << child.get<std::string>("documentation") << "\n\n";
          else
            print_entries(out, child, path + demangled + "/");
        }
    }
  } // namespace


  void
  print_parameter_reference(std::ostream &out)
  {
    ParameterHandler prm;
    Parameters::declare_parameters(prm);
    std::stringstream json;
    prm.print_parameters(json, ParameterHandler::JSON);
    boost::property_tree::ptree tree;
    boost::property_tree::read_json(json, tree);
    out << "clothsim parameters: Section/Name = default, allowed values, meaning and "
           "unit.\n"
           "Set them in a .prm file ('subsection Section', 'set Name = value', 'end') or "
           "with\n"
           "--set \"Section/Name=value\".\n\n";
    print_entries(out, tree, "");
  }


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

    if (!std::filesystem::is_regular_file(file))
      throw InputError(file, "", "parameter file not found");
    {
      std::ifstream probe(file);
      if (!probe)
        throw InputError(file, "", "parameter file cannot be read");
    }
    try
      {
        prm.parse_input(file, "", /*skip_undefined=*/false, /*assert_mandatory=*/false);
      }
    catch (const std::exception &e)
      {
        const std::string message = one_line(e);
        const auto [entry, text] =
          describe_parse_error(message, current_section(file, message));
        throw InputError(file, entry, text);
      }

    // --set "Section/Sub/Name=value"
    for (const std::string &assignment : overrides)
      {
        const auto equals = assignment.find('=');
        if (equals == std::string::npos)
          throw InputError("--set", assignment, "expected \"Section/Name=value\"");
        const auto path = Utilities::split_string_list(assignment.substr(0, equals), '/');
        const std::string value = Utilities::trim(assignment.substr(equals + 1));
        try
          {
            for (unsigned int i = 0; i + 1 < path.size(); ++i)
              prm.enter_subsection(path[i]);
            prm.set(path.back(), value);
            for (unsigned int i = 0; i + 1 < path.size(); ++i)
              prm.leave_subsection();
          }
        catch (const std::exception &e)
          {
            throw InputError(
              "--set",
              assignment.substr(0, equals),
              "no such entry, or the value does not match its pattern (see "
              "clothsim --print-parameters): " +
                one_line(e));
          }
      }

    try
      {
        input.parameters.parse_parameters(prm);
      }
    catch (const InputError &e)
      {
        throw InputError(file, e.entry, e.message);
      }
    catch (const std::exception &e)
      {
        const std::string message = one_line(e);
        const auto [entry, text]  = describe_parse_error(message, "");
        throw InputError(file, entry, text);
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
    if (mass_spring && !parameters.material.lumped_mass)
      throw InputError(file,
                       "Material/Mass",
                       "the mass-spring model has lumped masses only; set 'lumped'");
    if (parameters.time.accuracy_target > 0. &&
        (parameters.time.integrator == Integrator::static_load_steps ||
         is_explicit(parameters.time.integrator)))
      throw InputError(file,
                       "Time/Accuracy target",
                       "an accuracy target needs an implicit dynamic integrator "
                       "(backward euler, bdf2, implicit midpoint)");
    if (parameters.time.accuracy_target > 0. &&
        parameters.nonlinear_solver.method == NewtonMethod::single_step)
      throw InputError(file,
                       "Time/Accuracy target",
                       "an accuracy target needs a Newton method that solves each step "
                       "('single step' leaves it unsolved)");
    if (parameters.time.adaptive_time_steps &&
        (parameters.time.integrator == Integrator::static_load_steps ||
         is_explicit(parameters.time.integrator)))
      throw InputError(file,
                       "Time/Adaptive time steps",
                       "adaptive time steps are for the implicit dynamic integrators "
                       "(backward euler, bdf2, implicit midpoint)");
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
        (!mass_spring || parameters.time.integrator == Integrator::static_load_steps))
      throw InputError(file,
                       "Mass spring/Strain limit",
                       "the strain limit corrects dynamic steps of the mass-spring "
                       "model only; set it to 0");
    for (const Probe &probe : input.parameters.output.probes)
      if (probe.name.empty() || probe.name.find(',') != std::string::npos)
        throw InputError(file,
                         "Output/Probes",
                         "probe names must be non-empty, without commas");
    return input;
  }
} // namespace clothsim
