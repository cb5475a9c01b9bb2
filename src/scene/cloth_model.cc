#include "scene/cloth_model.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/tria.h>

#include "io/input_error.h"
#include "mesh/memory_estimate.h"
#include "mesh/projected_area.h"
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


  std::vector<std::string>
  ClothModel::energy_columns() const
  {
    // Kinetic energy has its own column already; the dissipative terms share one.
    std::vector<std::string> columns;
    for (const physics::Term *term : model->terms())
      if (term->kind() != physics::TermKind::kinetic &&
          std::find(columns.begin(), columns.end(), term->report_column()) ==
            columns.end())
        columns.push_back(term->report_column());
    // Contact: the smallest distance from an obstacle of what contact keeps off them
    // and of the whole surface (m), then per obstacle the force on the cloth (N) and the
    // vertices and pairs within the thickness.
    if (contact != nullptr)
      {
        columns.push_back("contact_min_distance");
        columns.push_back("contact_surface_distance");
        for (const physics::Obstacle &obstacle : contact->get_obstacles())
          {
            std::string name = obstacle.name();
            std::replace(name.begin(), name.end(), ' ', '_');
            for (const char *part : {"_force_x", "_force_y", "_force_z", "_contacts"})
              columns.push_back(name + part);
          }
        if (adapts_stiffness())
          columns.push_back("contact_barrier_stiffness");
      }
    // Self-contact: the smallest distance between primitives that share no vertex (m;
    // at most ten times the thickness: none closer), and the pairs within the thickness.
    // With 'Adaptive barrier stiffness', each contact's a_b as raised (m/s²).
    if (self_contact != nullptr)
      for (const char *column : {"self_contact_min_distance", "self_contact_pairs"})
        columns.push_back(column);
    if (self_contact != nullptr && adapts_stiffness())
      columns.push_back("self_contact_barrier_stiffness");
    if (parameters.output.drape_disc_radius > 0.)
      for (const char *column : {"projected_area", "drape_coefficient"})
        columns.push_back(column);
    if (parameters.output.check_intersections)
      columns.push_back("intersecting_pairs");
    return columns;
  }


  EnergyReport
  ClothModel::energies(const VectorType &u,
                       const VectorType &v,
                       const double      dissipated) const
  {
    return add_step_report(u, report(model->energies(u, v), dissipated));
  }


  EnergyReport
  ClothModel::energies(const VectorType    &u,
                       const VectorType    &v,
                       const double         dissipated,
                       physics::RankVector &damping_force) const
  {
    return add_step_report(u, report(model->energies(u, v, &damping_force), dissipated));
  }


  EnergyReport
  ClothModel::add_step_report(const VectorType &u, EnergyReport energies) const
  {
    // The contact, drape and intersection columns are the last ones (energy_columns()).
    const double       drape_radius = parameters.output.drape_disc_radius;
    const bool         intersecting = parameters.output.check_intersections;
    const unsigned int adaptive     = adapts_stiffness() ? 1 : 0;
    const double       a_b          = parameters.contact.barrier_acceleration;
    std::size_t        column = energies.columns.size() - (drape_radius > 0. ? 2 : 0) -
                         (intersecting ? 1 : 0) -
                         (self_contact != nullptr ? 2 + adaptive : 0);
    if (contact != nullptr)
      {
        const physics::ObstacleContact::Report contacts =
          contact->report(u, contact->time_of_state());
        column -= 2 + 4 * contacts.forces.size() + adaptive;
        energies.columns[column++] = contacts.min_distance;
        energies.columns[column++] = contacts.min_surface_distance;
        for (unsigned int o = 0; o < contacts.forces.size(); ++o)
          {
            for (unsigned int c = 0; c < 3; ++c)
              energies.columns[column++] = contacts.forces[o][c];
            energies.columns[column++] = contacts.contacts[o];
          }
        if (adaptive)
          energies.columns[column++] = a_b * contact->barrier_stiffness().scale();
      }
    if (self_contact != nullptr)
      {
        const double                       range = 10. * parameters.contact.thickness;
        const physics::SelfContact::Report pairs = self_contact->report(u, range);
        energies.columns[column++]               = std::min(pairs.min_distance, range);
        energies.columns[column++]               = pairs.pairs;
        if (adaptive)
          energies.columns[column++] = a_b * self_contact->barrier_stiffness().scale();
      }
    if (drape_radius == 0. && !intersecting)
      return energies;
    // Both measure the whole mesh on rank 0 (0 elsewhere, summed over ranks).
    const MPI_Comm                           communicator = get_communicator();
    const std::vector<physics::MeshTriangle> triangles    = triangles_on_root(u);
    if (drape_radius > 0.)
      {
        double area = 0.;
        if (Utilities::MPI::this_mpi_process(communicator) == 0)
          {
            std::vector<std::array<Point<2>, 3>> shadows;
            for (const physics::MeshTriangle &triangle : triangles)
              {
                std::array<Point<2>, 3> shadow;
                for (unsigned int v = 0; v < 3; ++v)
                  shadow[v] = Point<2>(triangle.corners[v][0], triangle.corners[v][1]);
                shadows.push_back(shadow);
              }
            area = mesh::projected_area(shadows);
          }
        area                       = Utilities::MPI::sum(area, communicator);
        const double disc          = numbers::PI * drape_radius * drape_radius;
        energies.columns[column++] = area;
        energies.columns[column++] =
          (area - disc) / (discretization.reference_area() - disc);
      }
    if (intersecting)
      {
        const double pairs =
          Utilities::MPI::this_mpi_process(communicator) == 0
            ? static_cast<double>(physics::intersecting_pairs(triangles).size())
            : 0.;
        energies.columns[column++] = Utilities::MPI::sum(pairs, communicator);
      }
    return energies;
  }


  std::vector<physics::MeshTriangle>
  ClothModel::triangles_on_root(const VectorType &u) const
  {
    // Per triangle: 9 coordinates, then its vertices' ids (their x dofs, exact in a
    // double below 2^53).
    std::vector<double>   values;
    std::array<double, 9> u_e;
    for (const auto &element : discretization.elements())
      {
        for (const Point<3> &x : discretization.current_positions(element, u, u_e))
          values.insert(values.end(), {x[0], x[1], x[2]});
        for (unsigned int v = 0; v < 3; ++v)
          values.push_back(static_cast<double>(element.dofs[3 * v]));
      }
    const auto all = Utilities::MPI::gather(get_communicator(), values, 0);
    std::vector<physics::MeshTriangle> triangles;
    for (const std::vector<double> &part : all)
      for (std::size_t k = 0; k + 12 <= part.size(); k += 12)
        {
          physics::MeshTriangle triangle;
          for (unsigned int v = 0; v < 3; ++v)
            {
              triangle.corners[v] =
                Point<3>(part[k + 3 * v], part[k + 3 * v + 1], part[k + 3 * v + 2]);
              triangle.vertices[v] =
                static_cast<types::global_dof_index>(part[k + 9 + v]);
            }
          triangles.push_back(triangle);
        }
    return triangles;
  }


  EnergyReport
  ClothModel::report(const physics::Energies &energies, const double dissipated) const
  {
    const std::vector<std::string> columns = energy_columns();
    EnergyReport                   report{energies.kinetic,
                        energies.elastic,
                        energies.potential,
                        std::vector<double>(columns.size(), 0.)};
    const auto                    &terms = model->terms();
    for (unsigned int k = 0; k < terms.size(); ++k)
      {
        const auto column =
          std::find(columns.begin(), columns.end(), terms[k]->report_column());
        if (column == columns.end())
          continue;
        report.columns[column - columns.begin()] =
          terms[k]->kind() == physics::TermKind::dissipative
            ? dissipated
            : terms[k]->reported_value(energies.terms[k]);
      }
    return report;
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
