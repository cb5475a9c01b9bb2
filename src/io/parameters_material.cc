// Sections "Material", "Mass spring" and "Damping": the cloth's constitutive constants.

#include "io/parameters.h"

#include <deal.II/base/parameter_handler.h>

#include <deal.II/base/numbers.h>

#include "io/fabric_presets.h"
#include "io/input_error.h"

namespace clothsim
{
  void
  MaterialParameters::declare_parameters(ParameterHandler &prm, const std::string &preset)
  {
    // An entry's default: the preset's value if it names the entry.
    const FabricPreset *fabric        = find_fabric_preset(preset);
    const auto          default_value = [&](const std::string &entry,
                                   const std::string &value) -> std::string {
      if (fabric != nullptr)
        for (const auto &[name, preset_value] : fabric->values)
          if (name == entry)
            return preset_value;
      return value;
    };
    prm.enter_subsection("Material");
    prm.declare_entry(
      "Preset",
      preset,
      Patterns::Selection(fabric_preset_names()),
      "A fabric by name: its measured values become the defaults of the Material "
      "entries it sets (each can still be set to override it; parameters.prm of a run "
      "shows the values used)." +
        fabric_preset_documentation());
    prm.declare_entry(
      "Stiffness given as",
      default_value("Stiffness given as", "E*h"),
      Patterns::Selection("E*h|E and thickness"),
      "How the membrane (stretch) stiffness is given: 'E*h' uses 'Stretch "
      "stiffness' directly (fabrics); 'E and thickness' uses Young's modulus "
      "times thickness (engineering shells; isotropic only).");
    prm.declare_entry("Stretch stiffness",
                      default_value("Stretch stiffness", "100"),
                      Patterns::Double(1e-12, 1e15),
                      "Membrane stiffness E*h in N/m (used when 'Stiffness given as = "
                      "E*h'); orthotropic: along the warp, E_1 h.");
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
                      default_value("Poisson ratio", "0.3"),
                      Patterns::Double(0., 0.499),
                      "Poisson's ratio ν (dimensionless), 0 <= ν < 0.5; orthotropic: "
                      "ν_12, the weft's contraction per stretch along the warp (also "
                      "the bending's, physics/sheet_stiffness.h).");
    prm.declare_entry("Areal density",
                      default_value("Areal density", "0.1"),
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
      default_value("Bending", "none"),
      Patterns::Selection("none|E and thickness|rigidity"),
      "Bending stiffness (midedge-director shell, physics/bending.h): 'none' "
      "(a membrane; no bending term is assembled), 'E and thickness' (plate "
      "rigidity D = E h^3 / (12 (1 - nu^2)) from 'Young's modulus', 'Thickness' "
      "and 'Poisson ratio'; isotropic only), or 'rigidity' ('Bending rigidity' given "
      "directly, as measured for fabrics).");
    prm.declare_entry("Bending rigidity",
                      default_value("Bending rigidity", "1e-5"),
                      Patterns::Double(0., 1e15),
                      "Bending rigidity D in N·m (= J), used when 'Bending = rigidity'; "
                      "orthotropic: along the warp, D_1. Fabrics: roughly 1e-6 to 1e-3.");
    prm.declare_entry(
      "Director function",
      "angle",
      Patterns::Selection("angle|sine|tangent|half tangent"),
      "f in the edge curvature 2 h f(tilt), tilt in rad: 'angle' (f = id), 'sine', "
      "'tangent' (f = tan(tilt): a barrier at pi/2, against folding a triangle flat "
      "onto its neighbour), or 'half tangent' (f = 2 tan(tilt/2): a barrier at pi, "
      "against a crease turning inside out). All agree for small tilts. With a "
      "barrier, Newton's line search is capped so that no tilt crosses it.");
    prm.declare_entry(
      "Anisotropy",
      default_value("Anisotropy", "isotropic"),
      Patterns::Selection("isotropic|orthotropic"),
      "'isotropic': the same stiffness in every direction. 'orthotropic' (woven "
      "cloth: warp and weft stiff, bias soft; physics/sheet_stiffness.h): 'Stretch "
      "stiffness' and 'Bending rigidity' hold along the warp, the weft has its own, "
      "and 'Shear stiffness' sets the bias; needs 'Stiffness given as = E*h' and "
      "'Bending = none' or 'rigidity'.");
    prm.declare_entry("Warp direction",
                      "1, 0, 0",
                      Patterns::List(Patterns::Double(-1e6, 1e6), 3, 3, ","),
                      "Orthotropic: the warp (x, y, z; any length) in the reference "
                      "configuration, projected onto each triangle's plane; it must not "
                      "be normal to any triangle. The weft is perpendicular to it in the "
                      "surface.");
    prm.declare_entry("Weft stretch stiffness",
                      default_value("Weft stretch stiffness", "100"),
                      Patterns::Double(1e-12, 1e15),
                      "Orthotropic: membrane stiffness E_2 h along the weft, N/m.");
    prm.declare_entry("Shear stiffness",
                      default_value("Shear stiffness", "38.46"),
                      Patterns::Double(1e-12, 1e15),
                      "Orthotropic: in-plane shear stiffness G_12 h, N/m (isotropic "
                      "value: E h / (2 (1 + nu)); woven cloth: far below it).");
    prm.declare_entry("Weft bending rigidity",
                      default_value("Weft bending rigidity", "1e-5"),
                      Patterns::Double(0., 1e15),
                      "Orthotropic with 'Bending = rigidity': bending rigidity D_2 along "
                      "the weft, N·m (twist: Huber's (1 - nu) sqrt(D_1 D_2) / 2).");
    prm.leave_subsection();
  }

  void
  MaterialParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material");
    preset                  = prm.get("Preset");
    const bool given_as_e_h = prm.get("Stiffness given as") == "E*h";
    if (given_as_e_h)
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

    orthotropic                    = prm.get("Anisotropy") == "orthotropic";
    weft_stretch_stiffness         = prm.get_double("Weft stretch stiffness");
    shear_stiffness                = prm.get_double("Shear stiffness");
    weft_bending_rigidity          = prm.get_double("Weft bending rigidity");
    const std::vector<double> warp = Utilities::string_to_double(
      Utilities::split_string_list(prm.get("Warp direction")));
    for (unsigned int d = 0; d < 3; ++d)
      warp_direction[d] = warp[d];
    prm.leave_subsection();

    if (orthotropic)
      {
        if (!given_as_e_h)
          throw InputError("",
                           "Material/Stiffness given as",
                           "an orthotropic sheet takes its stiffnesses in N/m: set "
                           "'E*h' and give 'Stretch stiffness' (warp) and 'Weft stretch "
                           "stiffness'");
        if (bending_given_as == "E and thickness")
          throw InputError("",
                           "Material/Bending",
                           "an orthotropic sheet takes its bending rigidities in N·m: "
                           "set 'rigidity' and give 'Bending rigidity' (warp) and "
                           "'Weft bending rigidity'");
        if (warp_direction.norm() == 0.)
          throw InputError("", "Material/Warp direction", "must not be zero");
        const double nu = poisson_ratio;
        if (nu * nu * weft_stretch_stiffness >= stretch_stiffness)
          throw InputError("",
                           "Material/Poisson ratio",
                           "nu_12^2 must stay below 'Stretch stiffness' / 'Weft stretch "
                           "stiffness' (k_warp/k_weft = " +
                             std::to_string(stretch_stiffness / weft_stretch_stiffness) +
                             "), or the membrane energy is not positive");
      }
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
