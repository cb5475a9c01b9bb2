#include "scene/cloth_model.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/tria.h>

#include "io/input_error.h"
#include "mesh/memory_estimate.h"
#include "physics/strain_limit.h"
#include "solvers/near_null_space.h"

#include <algorithm>

namespace clothsim
{
  namespace
  {
    // The mesh set-up of the parameters, once its refinement is known to fit in memory.
    mesh::MeshSetup
    mesh_setup(const MPI_Comm             communicator,
               const Parameters          &parameters,
               const std::string         &parameter_file,
               const Triangulation<2, 3> &serial_mesh)
    {
      mesh::MeshSetup setup;
      setup.global_refinements = parameters.scene.global_refinements;
      setup.surface            = parameters.scene.surface;
      setup.center             = parameters.scene.surface_center;
      setup.axis               = parameters.scene.surface_axis;
      setup.directors =
        parameters.material.bending && parameters.scene.model == Model::fem;

      const mesh::MemoryEstimate estimate =
        mesh::estimate_memory(communicator, serial_mesh.n_active_cells(), setup);
      if (!estimate.fits())
        throw InputError(parameter_file, "Mesh/Global refinements", estimate.shortage());
      return setup;
    }
  } // namespace


  ClothModel::ClothModel(const MPI_Comm             communicator,
                         const Parameters          &parameters,
                         const std::string         &parameter_file,
                         const Triangulation<2, 3> &serial_mesh,
                         const mesh::MeshGroups    &groups)
    : parameters(parameters)
    , prescribed_motion(parameters.prescribes_motion())
    , discretization(communicator,
                     serial_mesh,
                     mesh_setup(communicator, parameters, parameter_file, serial_mesh))
  {
    if (!parameters.constraints.clamped_groups.empty() && !parameters.material.bending &&
        parameters.scene.model == Model::fem)
      throw InputError(parameter_file,
                       "Constraints/Clamped groups",
                       "clamping holds the shell's rotation, which only exists with "
                       "bending; set Material/Bending, or pin the group instead");
    for (const PinnedGroup &group : parameters.constraints.pinned_groups)
      if (group.rotation &&
          (!parameters.material.bending || parameters.scene.model != Model::fem))
        throw InputError(parameter_file,
                         "Constraints/Pinned groups",
                         "'" + group.name +
                           ": ...r' holds the shell's rotation, which only exists in "
                           "the finite elements with bending; set Material/Bending, or "
                           "leave out 'r'");
    boundary_conditions = std::make_unique<BoundaryConditions>(discretization,
                                                               parameters,
                                                               parameter_file,
                                                               groups);
    model               = std::make_unique<physics::Model>(discretization,
                                             boundary_conditions->constraints());
    add_terms(parameter_file, groups);
    piece = discretization.surface_piece();
    if (contact != nullptr)
      {
        // The cloth must start off the obstacles (within the thickness is fine).
        VectorType u, v;
        initialize_owned(u);
        initialize_owned(v);
        initial_state(u, v);
        const std::string inside = contact->penetration(u, 0.);
        if (!inside.empty())
          throw InputError(parameter_file,
                           "Obstacle",
                           inside + ": start the cloth outside every obstacle");
      }
    if (springs)
      {
        VectorType masses;
        lumped_masses(masses);
        VectorType inverse(masses);
        for (const types::global_dof_index i : discretization.owned_dofs())
          inverse[i] =
            masses[i] > 0. && !boundary_conditions->is_pinned(i) ? 1. / masses[i] : 0.;
        inverse.compress(VectorOperation::insert);
        discretization.initialize_ghosted(inverse_masses);
        inverse_masses = inverse;
      }
  }


  bool
  ClothModel::update_couplings(const VectorType &u_n, const VectorType &u_new)
  {
    if (self_contact == nullptr)
      return false;
    VectorType from, to;
    initialize_ghosted(from);
    initialize_ghosted(to);
    import_ghosts(u_n, from);
    import_ghosts(u_new, to);
    return self_contact->update_couplings(from, to);
  }


  NearNullSpace
  ClothModel::near_null_space() const
  {
    std::vector<ReferenceTriangle> triangles;
    for (const auto &element : discretization.elements())
      triangles.push_back({element.reference,
                           element.dofs,
                           element.area,
                           discretization.has_directors()
                             ? element.angle_dofs
                             : std::array<types::global_dof_index, 3>{}});
    return make_near_null_space(triangles,
                                discretization.owned_dofs(),
                                discretization.relevant_dofs(),
                                discretization.has_directors(),
                                discretization.get_communicator());
  }


  void
  ClothModel::lumped_masses(VectorType &masses) const
  {
    discretization.initialize_owned(masses);
    const double rho = parameters.material.areal_density;
    for (const auto &element : discretization.elements())
      {
        const std::vector<types::global_dof_index> dofs(element.dofs.begin(),
                                                        element.dofs.end());
        const std::vector<double>                  values(9, rho * element.area / 3.);
        masses.add(dofs, values);
      }
    masses.compress(VectorOperation::add);
  }


  std::pair<types::global_dof_index, double>
  ClothModel::limit_strain(VectorType &u, VectorType &v, const double dt) const
  {
    Assert(springs != nullptr, ExcInternalError());
    const MassSpringParameters &limits = parameters.mass_spring;
    VectorType                  u_ghosted;
    discretization.initialize_ghosted(u_ghosted);
    const auto result = physics::limit_strain(*springs,
                                              {limits.strain_limit,
                                               limits.limit_compression,
                                               limits.strain_limit_iterations},
                                              inverse_masses,
                                              dt,
                                              u,
                                              v,
                                              u_ghosted,
                                              discretization);
    return {result.remaining, result.largest_strain};
  }


  void
  ClothModel::internal_forces(const VectorType &u, VectorType &forces) const
  {
    model->elastic_forces(u, forces);
  }


  std::vector<SupportReaction>
  ClothModel::support_reactions(const VectorType &u, const double time) const
  {
    const auto &supports = boundary_conditions->supports();
    if (supports.empty())
      return {};
    VectorType forces;
    initialize_owned(forces);
    StepTerms step;
    step.load_factor  = is_static(parameters.time.integrator) ? time : 1.;
    step.time         = time;
    const bool linear = parameters.time.integrator == Integrator::linear_static;
    if (!linear)
      model->static_forces(u, step, forces);
    else
      {
        // The linear problem's R = K0 u - f, with K0 u the derivative of the static
        // forces S along u at the reference state by central differences,
        // (S(εu) - S(-εu)) / 2ε (exact to O(ε²): ε u at most 1e-5 of the mesh's
        // size), and -f = S(0) (no stress there).
        const double largest = u.linfty_norm();
        const double epsilon = largest > 0. ? 1e-5 * reference_size() / largest : 1.;
        VectorType   owned, scaled, plus, minus;
        initialize_owned(owned);
        initialize_ghosted(scaled);
        initialize_owned(plus);
        initialize_owned(minus);
        for (const double sign : {1., -1., 0.})
          {
            for (const types::global_dof_index i : owned_dofs())
              owned[i] = sign * epsilon * u(i);
            owned.compress(VectorOperation::insert);
            import_ghosts(owned, scaled);
            model->static_forces(scaled,
                                 step,
                                 sign > 0.   ? plus
                                 : sign < 0. ? minus
                                             : forces);
          }
        plus -= minus;
        forces.add(0.5 / epsilon, plus);
      }

    const IndexSet              &owned = owned_dofs();
    const MPI_Comm               comm  = get_communicator();
    std::vector<SupportReaction> reactions;
    for (const BoundaryConditions::Support &support : supports)
      {
        // Linear theory: lever arms in the reference configuration.
        const auto position = [&u,
                               linear](const std::array<types::global_dof_index, 3> &dofs,
                                       const Point<3>                               &X) {
          Point<3> x = X;
          if (!linear)
            for (unsigned int d = 0; d < 3; ++d)
              x[d] += u(dofs[d]);
          return x;
        };
        // Centroid: each vertex counted by the rank owning its x dof.
        Point<3> sum;
        double   count = 0.;
        for (const auto &[x_dof, vertex] : support.vertices)
          if (owned.is_element(x_dof))
            {
              sum += position(vertex.first, vertex.second) - Point<3>();
              count += 1.;
            }
        for (unsigned int d = 0; d < 3; ++d)
          sum[d] = Utilities::MPI::sum(sum[d], comm);
        count                 = Utilities::MPI::sum(count, comm);
        const Point<3> centre = count > 0. ? Point<3>(sum / count) : Point<3>();

        Tensor<1, 3> force, moment;
        for (const auto &[x_dof, vertex] : support.vertices)
          if (owned.is_element(x_dof))
            {
              const auto  &dofs = vertex.first;
              Tensor<1, 3> R;
              for (unsigned int d = 0; d < 3; ++d)
                if (support.pinned.count(dofs[d]) > 0)
                  R[d] = forces(dofs[d]);
              force += R;
              moment += cross_product_3d(position(dofs, vertex.second) - centre, R);
            }
        for (const mesh::Discretization::Edge &edge : discretization.edges())
          if (support.held_angles.count(edge.angle_dof) > 0 &&
              owned.is_element(edge.angle_dof))
            {
              const Tensor<1, 3> t =
                position(edge.vertex_dofs[1], edge.reference_points[1]) -
                position(edge.vertex_dofs[0], edge.reference_points[0]);
              moment += forces(edge.angle_dof) / t.norm() * t;
            }
        for (unsigned int d = 0; d < 3; ++d)
          {
            force[d]  = Utilities::MPI::sum(force[d], comm);
            moment[d] = Utilities::MPI::sum(moment[d], comm);
          }
        reactions.push_back({support.name, centre, force, moment});
      }
    return reactions;
  }


  std::vector<std::string>
  ClothModel::term_names() const
  {
    std::vector<std::string> names;
    for (const physics::Term *term : model->terms())
      names.push_back(term->name());
    return names;
  }


  bool
  ClothModel::adapt_to_iterate()
  {
    // Both are asked: each keeps its closest distance at the iterate before.
    const bool obstacles = contact != nullptr && contact->adapt_stiffness();
    const bool self      = self_contact != nullptr && self_contact->adapt_stiffness();
    return obstacles || self;
  }


  std::string
  ClothModel::begin_step(const double      t_n,
                         const double      t_new,
                         const VectorType &u_n,
                         VectorType       &u_new,
                         const double      path_end)
  {
    if (adapts_stiffness())
      {
        VectorType start;
        initialize_ghosted(start);
        import_ghosts(u_n, start);
        if (contact != nullptr)
          contact->begin_attempt(start, t_n);
        if (self_contact != nullptr)
          self_contact->begin_attempt(start, t_n);
      }
    if (model->caps_steps())
      {
        // The terms' caps (bending tilts) on the straight path from u_n to the step's
        // end: a prediction that would carry a tilt across its barrier is pulled back
        // towards u_n.
        VectorType from, direction;
        initialize_ghosted(from);
        initialize_ghosted(direction);
        import_ghosts(u_n, from);
        VectorType owned_direction(u_new);
        owned_direction -= u_n;
        owned_direction *= path_end;
        import_ghosts(owned_direction, direction);
        const double alpha = model->largest_step(from, direction);
        if (alpha < 1.)
          {
            const AffineConstraints<double> &constraints =
              boundary_conditions->constraints();
            for (const types::global_dof_index i : u_new.locally_owned_elements())
              if (!constraints.is_constrained(i))
                u_new[i] = u_n[i] + alpha * (u_new[i] - u_n[i]);
            u_new.compress(VectorOperation::insert);
          }
      }
    if (self_contact != nullptr)
      {
        VectorType start;
        initialize_ghosted(start);
        import_ghosts(u_n, start);
        self_contact->lag_friction(start, t_new - t_n);
      }
    if (contact == nullptr)
      return "";
    return contact->begin_step(
      t_n, t_new, u_n, u_new, boundary_conditions->constraints());
  }


  std::vector<double>
  ClothModel::cell_field(const VectorType &u, const std::string &name) const
  {
    for (physics::CellField &field : model->cell_fields(u))
      if (field.name == name)
        return std::move(field.values);
    return {};
  }


  io::SurfacePiece
  ClothModel::output_piece() const
  {
    return {piece.points, piece.triangles};
  }


  io::FrameData
  ClothModel::output_fields(const VectorType &u, const VectorType &v) const
  {
    // Displacement (m) and velocity (m/s) per vertex; the director angles are re-based
    // to zero after every step and not written.
    io::FrameData data;
    for (const auto &[name, vector] :
         {std::make_pair("displacement", &u), std::make_pair("velocity", &v)})
      {
        io::Field field{name, 3, {}};
        field.values.reserve(3 * piece.point_dofs.size());
        for (const auto &dofs : piece.point_dofs)
          for (unsigned int d = 0; d < 3; ++d)
            field.values.push_back((*vector)(dofs[d]));
        data.point_fields.push_back(std::move(field));
      }
    for (physics::CellField &field : model->cell_fields(u))
      data.cell_fields.push_back({field.name, 1, std::move(field.values)});
    const double rank = Utilities::MPI::this_mpi_process(get_communicator());
    data.cell_fields.push_back(
      {"rank", 1, std::vector<double>(piece.triangles.size(), rank)});
    return data;
  }
} // namespace clothsim
