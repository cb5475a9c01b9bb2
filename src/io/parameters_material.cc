// Sections "Material", "Mass spring" and "Damping": the cloth's constitutive constants.

#include "io/parameters.h"

#include <deal.II/base/numbers.h>

#include "io/input_error.h"

namespace clothsim
{
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
      Patterns::Selection("angle|sine|tangent|half tangent"),
      "f in the edge curvature 2 h f(tilt), tilt in rad: 'angle' (f = id), 'sine', "
      "'tangent' (f = tan(tilt): a barrier at pi/2, against folding a triangle flat "
      "onto its neighbour), or 'half tangent' (f = 2 tan(tilt/2): a barrier at pi, "
      "against a crease turning inside out). All agree for small tilts. With a "
      "barrier, Newton's line search is capped so that no tilt crosses it.");
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
} // namespace clothsim
