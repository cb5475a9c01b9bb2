#include "scene/group_loads.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>

#include "io/input_error.h"

#include <set>

namespace clothsim
{
  VectorType
  resolve_group_loads(const mesh::Discretization      &discretization,
                      const LoadParameters            &loads,
                      const AffineConstraints<double> &constraints,
                      const std::string               &parameter_file,
                      const mesh::MeshGroups          &groups)
  {
    VectorType forces;
    discretization.initialize_owned(forces);
    forces                               = 0.;
    const MPI_Comm          communicator = discretization.get_communicator();
    const DoFHandler<2, 3> &dof_handler  = discretization.get_dof_handler();
    const IndexSet         &owned        = discretization.owned_dofs();
    const double            tolerance =
      1e-8 * GridTools::diameter(dof_handler.get_triangulation().get_triangulation());

    // Point forces: on every vertex of the point group (each vertex once).
    for (const GroupLoad &load : loads.point_forces)
      {
        const auto group = groups.point_groups.find(load.name);
        if (group == groups.point_groups.end())
          throw InputError(parameter_file,
                           "Loads/Point forces",
                           "the mesh has no point group named '" + load.name + "'");
        std::set<types::global_dof_index> loaded;
        for (const auto &element : discretization.elements())
          for (unsigned int v = 0; v < 3; ++v)
            if (owned.is_element(element.dofs[3 * v]))
              for (const Point<3> &p : group->second)
                if (element.reference[v].distance(p) < tolerance &&
                    loaded.insert(element.dofs[3 * v]).second)
                  for (unsigned int c = 0; c < 3; ++c)
                    forces[element.dofs[3 * v + c]] += load.value[c];
        if (Utilities::MPI::sum(static_cast<unsigned int>(loaded.size()), communicator) ==
            0)
          throw InputError(parameter_file,
                           "Loads/Point forces",
                           "the point group '" + load.name + "' holds no mesh vertex");
      }
    forces.compress(VectorOperation::add);

    // Line forces: q ℓ/2 on each end of every boundary edge of the group.
    for (const GroupLoad &load : loads.line_forces)
      {
        const auto group = groups.line_groups.find(load.name);
        if (group == groups.line_groups.end())
          throw InputError(parameter_file,
                           "Loads/Line forces",
                           "the mesh has no boundary line group named '" + load.name +
                             "'");
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  cell->face(f)->boundary_id() == types::boundary_id(group->second))
                {
                  const double length =
                    cell->face(f)->vertex(0).distance(cell->face(f)->vertex(1));
                  std::vector<types::global_dof_index> dofs;
                  std::vector<double>                  values;
                  for (unsigned int fv = 0; fv < 2; ++fv)
                    for (unsigned int c = 0; c < 3; ++c)
                      {
                        dofs.push_back(cell->face(f)->vertex_dof_index(fv, c));
                        values.push_back(0.5 * length * load.value[c]);
                      }
                  forces.add(dofs, values);
                }
      }
    forces.compress(VectorOperation::add);
    constraints.set_zero(forces);
    return forces;
  }
} // namespace clothsim
