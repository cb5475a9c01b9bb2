// mesh::describe_largest_entry (ClothModel::describe_largest_entry), which a failed
// Newton solve appends to its message: on the swinging sheet at N = 21 (displacements and
// one director angle per edge), a vector with one large entry is named by what that entry
// moves and where, the same text on every rank (also run on 2 ranks).

#include <deal.II/base/mpi.h>

#include "scene/scene.h"
#include "test_checks.h"


using namespace clothsim;
using namespace clothsim::test;

namespace
{
  // Whether every rank got the same text.
  bool
  same_on_every_rank(const std::string &text, const MPI_Comm communicator)
  {
    const std::string first = Utilities::MPI::broadcast(communicator, text, 0);
    return Utilities::MPI::min(first == text ? 1 : 0, communicator) == 1;
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment                  env(argc, argv);
  const MPI_Comm               communicator = env.communicator;
  const std::unique_ptr<Scene> scene =
    load_scene(source_path("params/benchmarks/swing.prm"),
               {"Mesh/Mesh file=" + source_path("meshes/swing-21.msh")},
               communicator);
  const ClothModel           &model = *scene->model;
  const mesh::Discretization &mesh  = model.get_discretization();
  VectorType                  v;
  mesh.initialize_owned(v);

  check(env.pcout, model.describe_largest_entry(v).empty(), "a zero vector: no text");

  // An edge's angle: the edge along y = 0 from x = 0.5 to 0.55,
  // found in the rank-independent edge table by its end points.
  const Point<3>          a(0.5, 0., 0.), b(0.55, 0., 0.);
  types::global_dof_index angle = numbers::invalid_dof_index;
  for (const auto &edge : mesh.edges())
    if (edge.reference_points[0].distance(a) < 1e-9 &&
        edge.reference_points[1].distance(b) < 1e-9)
      angle = edge.angle_dof;
  angle = Utilities::MPI::min(angle, communicator);
  check(env.pcout, angle != numbers::invalid_dof_index, "the edge from a to b exists");
  if (mesh.owned_dofs().is_element(angle))
    v[angle] = -0.75;
  v.compress(VectorOperation::insert);
  const std::string angle_text = model.describe_largest_entry(v);
  env.pcout << "  angle: " << angle_text << std::endl;
  check(env.pcout,
        angle_text ==
          "the director angle of the edge from (0.5, 0, 0) to (0.55, 0, 0) m, "
          "-0.75 rad",
        "names the director angle of the edge from a to b, -0.75 rad");
  check(env.pcout,
        same_on_every_rank(angle_text, communicator),
        "the same on every rank");

  // A larger displacement: the z component of the vertex at the free corner (1, 1, 0).
  const Point<3>          corner(1., 1., 0.);
  types::global_dof_index z = numbers::invalid_dof_index;
  for (const auto &element : mesh.elements())
    for (unsigned int k = 0; k < 3; ++k)
      if (element.reference[k].distance(corner) < 1e-12)
        z = element.dofs[3 * k + 2];
  z = Utilities::MPI::min(z, communicator);
  check(env.pcout, z != numbers::invalid_dof_index, "the free corner exists");
  if (mesh.owned_dofs().is_element(z))
    v[z] = 2.5;
  v.compress(VectorOperation::insert);
  const std::string z_text = model.describe_largest_entry(v);
  env.pcout << "  displacement: " << z_text << std::endl;
  check(env.pcout,
        z_text == "the z displacement of the vertex at (1, 1, 0) m, 2.5 m",
        "names the z displacement of the vertex at the free corner, 2.5 m");
  check(env.pcout, same_on_every_rank(z_text, communicator), "the same on every rank");
  return finish_tally(env.pcout);
}
