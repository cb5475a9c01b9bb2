#include "scene/group_loads.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>

#include "io/input_error.h"
#include "scene/boundary_conditions.h"

#include <map>
#include <set>
#include <vector>

namespace clothsim
{
  namespace
  {
    // Whether 'fx; fy; fz' are all the literal zero (no surface forces).
    bool
    is_zero(const std::string &expressions)
    {
      for (const std::string &e : Utilities::split_string_list(expressions, ';'))
        if (e != "0")
          return false;
      return true;
    }


    // A (2 f_i + f_j + f_k) / 12 on vertex i of every locally owned triangle.
    void
    add_surface_forces(const mesh::Discretization &discretization,
                       const std::string          &expressions,
                       const std::string          &parameter_file,
                       VectorType                 &forces)
    {
      FunctionParser<3> density(3);
      parse_vector_function(
        density, expressions, false, parameter_file, "Loads/Surface forces");
      std::vector<std::pair<unsigned int, Point<3>>> samples;
      for (const auto &element : discretization.elements())
        for (unsigned int v = 0; v < 3; ++v)
          for (unsigned int c = 0; c < 3; ++c)
            samples.emplace_back(c, element.reference[v]);
      check_finite(density,
                   samples,
                   discretization.get_communicator(),
                   parameter_file,
                   "Loads/Surface forces");
      std::vector<types::global_dof_index> dofs(9);
      std::vector<double>                  values(9);
      for (const auto &element : discretization.elements())
        {
          Tensor<1, 3> f[3], sum;
          for (unsigned int v = 0; v < 3; ++v)
            {
              for (unsigned int c = 0; c < 3; ++c)
                f[v][c] = density.value(element.reference[v], c);
              sum += f[v];
            }
          for (unsigned int v = 0; v < 3; ++v)
            for (unsigned int c = 0; c < 3; ++c)
              {
                dofs[3 * v + c]   = element.dofs[3 * v + c];
                values[3 * v + c] = element.area * (f[v][c] + sum[c]) / 12.;
              }
          forces.add(dofs, values);
        }
    }


    // The couple of 'Loads/Point moments' at every vertex of the point group: F_j =
    // ω × r_j on the other vertices j of each triangle at p (r_j = X_j - X_p, counted per
    // triangle), -F_j on p, with A ω = M for A = Σ (|r_j|² I - r_j r_jᵀ), so that
    // Σ r_j × F_j = A ω = M. A sums over the ranks' triangles.
    void
    add_point_moment(const mesh::Discretization  &discretization,
                     const GroupLoad             &load,
                     const std::vector<Point<3>> &points,
                     const double                 tolerance,
                     const std::string           &parameter_file,
                     VectorType                  &forces)
    {
      const auto &elements = discretization.elements();
      for (const Point<3> &p : points)
        {
          Tensor<2, 3> A;
          unsigned int triangles = 0;
          for (const auto &element : elements)
            for (unsigned int v = 0; v < 3; ++v)
              if (element.reference[v].distance(p) < tolerance)
                {
                  ++triangles;
                  for (const unsigned int w : {(v + 1) % 3, (v + 2) % 3})
                    {
                      const Tensor<1, 3> r = element.reference[w] - element.reference[v];
                      A -= outer_product(r, r);
                      for (unsigned int d = 0; d < 3; ++d)
                        A[d][d] += r * r;
                    }
                }
          const MPI_Comm communicator = discretization.get_communicator();
          triangles                   = Utilities::MPI::sum(triangles, communicator);
          A                           = Utilities::MPI::sum(A, communicator);
          if (triangles == 0)
            throw InputError(parameter_file,
                             "Loads/Point moments",
                             "the point group '" + load.name +
                               "' has a point that is no mesh vertex");
          const Tensor<1, 3> omega = invert(A) * load.value;
          for (const auto &element : elements)
            for (unsigned int v = 0; v < 3; ++v)
              if (element.reference[v].distance(p) < tolerance)
                for (const unsigned int w : {(v + 1) % 3, (v + 2) % 3})
                  {
                    const Tensor<1, 3> F =
                      cross_product_3d(omega,
                                       element.reference[w] - element.reference[v]);
                    std::vector<types::global_dof_index> dofs;
                    std::vector<double>                  values;
                    for (unsigned int c = 0; c < 3; ++c)
                      {
                        dofs.push_back(element.dofs[3 * w + c]);
                        values.push_back(F[c]);
                        dofs.push_back(element.dofs[3 * v + c]);
                        values.push_back(-F[c]);
                      }
                    forces.add(dofs, values);
                  }
        }
    }
  } // namespace


  bool
  has_group_loads(const LoadParameters &loads)
  {
    return !loads.point_forces.empty() || !loads.line_forces.empty() ||
           !loads.line_moments.empty() || !loads.point_moments.empty() ||
           !is_zero(loads.surface_forces);
  }


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
      point_matching_tolerance(dof_handler.get_triangulation(), communicator);

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
    if (!is_zero(loads.surface_forces))
      add_surface_forces(discretization, loads.surface_forces, parameter_file, forces);
    for (const GroupLoad &load : loads.point_moments)
      {
        const auto group = groups.point_groups.find(load.name);
        if (group == groups.point_groups.end())
          throw InputError(parameter_file,
                           "Loads/Point moments",
                           "the mesh has no point group named '" + load.name + "'");
        add_point_moment(
          discretization, load, group->second, tolerance, parameter_file, forces);
      }
    forces.compress(VectorOperation::add);

    // Line moments: (m · t_e) ℓ_e on the director angle of every boundary edge of the
    // group, t_e the edge's unit direction as its angle is oriented (the angle turns
    // the director about t_e; mesh::Discretization::Edge).
    if (!loads.line_moments.empty() && !discretization.has_directors())
      throw InputError(parameter_file,
                       "Loads/Line moments",
                       "a moment turns the shell's directors, which only exist with "
                       "bending; set Material/Bending");
    std::map<types::global_dof_index, const mesh::Discretization::Edge *> edge_of;
    for (const mesh::Discretization::Edge &edge : discretization.edges())
      edge_of[edge.angle_dof] = &edge;
    const auto &vertex_component = discretization.local_dof_vertex_component();
    std::vector<types::global_dof_index> dof_indices(
      discretization.get_fe().n_dofs_per_cell());
    for (const GroupLoad &load : loads.line_moments)
      {
        const auto group = groups.line_groups.find(load.name);
        if (group == groups.line_groups.end())
          throw InputError(parameter_file,
                           "Loads/Line moments",
                           "the mesh has no boundary line group named '" + load.name +
                             "'");
        double across = 0.; // largest component across an edge, N·m/m
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(dof_indices);
              for (unsigned int i = 0; i < dof_indices.size(); ++i)
                {
                  const auto [vertex, component] = vertex_component[i];
                  if (component != 3 || vertex < 3 ||
                      !cell->line(vertex - 3)->at_boundary() ||
                      cell->line(vertex - 3)->boundary_id() !=
                        types::boundary_id(group->second))
                    continue;
                  const mesh::Discretization::Edge &edge = *edge_of.at(dof_indices[i]);
                  const Tensor<1, 3>                e =
                    edge.reference_points[1] - edge.reference_points[0];
                  const Tensor<1, 3> t = e / e.norm();
                  across = std::max(across, (load.value - (load.value * t) * t).norm());
                  forces.add(std::vector<types::global_dof_index>{dof_indices[i]},
                             std::vector<double>{(load.value * t) * e.norm()});
                }
            }
        if (Utilities::MPI::max(across, communicator) > 1e-9 * load.value.norm())
          throw InputError(parameter_file,
                           "Loads/Line moments",
                           "the moment on '" + load.name +
                             "' has a component across the group's edges (a twisting "
                             "moment, up to " +
                             std::to_string(Utilities::MPI::max(across, communicator)) +
                             " N·m/m), which the shell does not take: give it along the "
                             "edges");
      }
    forces.compress(VectorOperation::add);
    constraints.set_zero(forces);
    return forces;
  }
} // namespace clothsim
