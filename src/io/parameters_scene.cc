// Section-less entries and "Mesh": the scene's name, the cloth model, the mesh and its
// exact rest surface.

#include "io/parameters.h"

#include <deal.II/base/parameter_handler.h>

#include <filesystem>

#include "io/input_error.h"
#include "io/parameters_detail.h"

namespace clothsim
{
  using detail::vector_entry;


  void
  SceneParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry(
      "Scene name",
      "",
      Patterns::Anything(),
      "Name of the run; output goes to output/<Scene name>/ unless --output-dir "
      "is given. Empty: the parameter file's name without extension. One "
      "directory name: no '/', not '.' or '..'.");
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
      "gmsh triangle mesh (.msh), relative to this parameter file's directory "
      "(required). "
      "If it is missing but a .geo of the same name exists, gmsh generates it. "
      "Lengths in the mesh are in m.");
    prm.declare_entry("Global refinements",
                      "0",
                      Patterns::Integer(0, 8),
                      "Number of uniform (red) refinements of the mesh as read; each one "
                      "quarters the triangles' area. Refused before refining when the "
                      "run's estimated memory (mesh/memory_estimate.cc) exceeds what "
                      "the node has available.");
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
    name = prm.get("Scene name");
    // The name is a directory below the output root: it must not leave it (--output-dir
    // is the way to write elsewhere).
    if (name.find('/') != std::string::npos || name == "." || name == "..")
      throw InputError("",
                       "Scene name",
                       "'" + name +
                         "' is not a plain directory name (no '/', not '.' or '..'); "
                         "use --output-dir to write elsewhere");
    model = prm.get("Model") == "mass-spring" ? Model::mass_spring : Model::fem;
    prm.enter_subsection("Mesh");
    mesh_file = prm.get("Mesh file");
    if (mesh_file.empty())
      throw InputError("",
                       "Mesh/Mesh file",
                       "is empty; expected a gmsh mesh file (.msh)");
    // The cloth's mesh is read as a .msh (generated from the .geo of the same name when
    // missing); a .geo named here would be read unmeshed, as "no triangles".
    if (std::filesystem::path(mesh_file).extension() == ".geo")
      throw InputError("",
                       "Mesh/Mesh file",
                       "'" + mesh_file +
                         "' is a gmsh script; name the .msh of the same name instead "
                         "(gmsh generates it from the .geo when it is missing)");
    global_refinements = prm.get_integer("Global refinements");
    surface            = prm.get("Surface");
    surface_center     = Point<3>(vector_entry(prm.get("Surface center")));
    surface_axis       = vector_entry(prm.get("Surface axis"));
    if (surface == "cylinder" && surface_axis.norm() == 0.)
      throw InputError("", "Mesh/Surface axis", "the cylinder axis must not be zero");
    prm.leave_subsection();
  }
} // namespace clothsim
