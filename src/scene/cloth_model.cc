#include "scene/cloth_model.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include "io/input_error.h"
#include "scene/ghosted_values.h"

#include <deal.II/grid/manifold_lib.h>

#include <algorithm>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>

namespace clothsim
{
  ClothModel::ClothModel(const MPI_Comm             communicator,
                         const Parameters          &parameters,
                         const std::string         &parameter_file,
                         const Triangulation<2, 3> &serial_mesh,
                         const mesh::MeshGroups    &groups)
    : communicator(communicator)
    , parameters(parameters)
    , triangulation(communicator)
    , fe(parameters.material.bending && parameters.scene.model == Model::fem
           ? std::make_unique<FESystem<2, 3>>(FE_SimplexP<2, 3>(1),
                                              3,
                                              FE_SimplexP<2, 3>(2),
                                              1)
           : std::make_unique<FESystem<2, 3>>(FE_SimplexP<2, 3>(1), 3))
    , mapping(FE_SimplexP<2, 3>(1))
    , pinned_displacement(3)
    , initial_displacement_function(3)
    , initial_velocity_function(3)
  {
    material.stretch_stiffness     = parameters.material.stretch_stiffness;
    material.poisson_ratio         = parameters.material.poisson_ratio;
    bending_material.rigidity      = parameters.material.bending_rigidity;
    bending_material.poisson_ratio = parameters.material.poisson_ratio;
    bending_material.director_function =
      parameters.material.director_function == "sine" ? physics::DirectorFunction::sine
      : parameters.material.director_function == "tangent"
        ? physics::DirectorFunction::tangent
        : physics::DirectorFunction::angle;
    if (!parameters.constraints.clamped_groups.empty() && !parameters.material.bending &&
        !uses_springs())
      throw InputError(parameter_file,
                       "Constraints/Clamped groups",
                       "clamping holds the shell's rotation, which only exists with "
                       "bending; set Material/Bending, or pin the group instead");
    build_mesh(serial_mesh);
    setup_dofs();
    resolve_pinned(parameter_file, groups);
    resolve_loads(parameter_file, groups);
    if (uses_springs())
      {
        VectorType prototype;
        initialize_ghosted(prototype);
        springs = std::make_unique<SpringNetwork>(dof_handler, parameters, prototype);
        VectorType masses;
        lumped_masses(masses);
        for (const PinnedDof &pin : pinned)
          if (locally_owned_dofs.is_element(pin.dof))
            masses[pin.dof] = 0.;
        masses.compress(VectorOperation::insert);
        VectorType inverse(masses);
        for (const types::global_dof_index i : locally_owned_dofs)
          inverse[i] = masses[i] > 0. ? 1. / masses[i] : 0.;
        inverse.compress(VectorOperation::insert);
        initialize_ghosted(inverse_masses);
        inverse_masses = inverse;
      }
  }


  std::vector<std::string>
  ClothModel::component_names(const std::string &displacement_name) const
  {
    std::vector<std::string> names(3, displacement_name);
    if (has_bending())
      names.push_back(displacement_name + "_director_angle");
    return names;
  }


  void
  ClothModel::build_mesh(const Triangulation<2, 3> &serial_mesh)
  {
    // Every rank holds the same coarse mesh; refine it, partition it with METIS
    // (deterministic), and keep only this rank's part plus a ghost layer.
    Triangulation<2, 3> refined;
    refined.copy_triangulation(serial_mesh);
    // Curved rest surfaces: new vertices go onto the exact surface.
    std::unique_ptr<Manifold<2, 3>> surface;
    if (parameters.scene.surface == "cylinder")
      surface =
        std::make_unique<CylindricalManifold<2, 3>>(parameters.scene.surface_axis,
                                                    parameters.scene.surface_center);
    else if (parameters.scene.surface == "sphere")
      surface =
        std::make_unique<SphericalManifold<2, 3>>(parameters.scene.surface_center);
    if (surface != nullptr)
      {
        refined.set_all_manifold_ids(1);
        refined.set_manifold(1, *surface);
      }
    refined.refine_global(parameters.scene.global_refinements);
    refined.reset_all_manifolds();
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    if (n_ranks > 1)
      GridTools::partition_triangulation(n_ranks, refined);
    const auto description =
      TriangulationDescription::Utilities::create_description_from_triangulation(
        refined, communicator);
    // The distributed triangulation repeats the refinement from the coarse cells: it
    // needs the surface too.
    if (surface != nullptr)
      triangulation.set_manifold(1, *surface);
    triangulation.create_triangulation(description);
  }


  namespace
  {
    // Unit normal of a triangle with the given vertices.
    Tensor<1, 3>
    unit_normal(const Point<3> &x0, const Point<3> &x1, const Point<3> &x2)
    {
      const Tensor<1, 3> N = cross_product_3d(x1 - x0, x2 - x0);
      return N / N.norm();
    }

    // A rank-independent order of vertices: lexicographic in the reference coordinates.
    bool
    precedes(const Point<3> &a, const Point<3> &b)
    {
      for (unsigned int d = 0; d < 3; ++d)
        if (a[d] != b[d])
          return a[d] < b[d];
      return false;
    }
  } // namespace


  void
  ClothModel::setup_dofs()
  {
    dof_handler.reinit(triangulation);
    dof_handler.distribute_dofs(*fe);
    locally_owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);
    vertex_count = DoFTools::count_dofs_per_fe_component(dof_handler)[0];

    // local dof -> (vertex, component) for the displacements (the P1 base element's dof
    // k sits on vertex k); the angle component (4th) is handled in setup_edges().
    local_dof_vertex_component.resize(fe->n_dofs_per_cell());
    for (unsigned int i = 0; i < fe->n_dofs_per_cell(); ++i)
      {
        const auto component_index    = fe->system_to_component_index(i);
        local_dof_vertex_component[i] = {component_index.second, component_index.first};
      }

    VectorType prototype;
    initialize_ghosted(prototype);
    std::vector<types::global_dof_index> dof_indices(fe->n_dofs_per_cell());
    elements.clear();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dof_indices);
          Element element;
          for (unsigned int i = 0; i < fe->n_dofs_per_cell(); ++i)
            {
              const auto [vertex, component] = local_dof_vertex_component[i];
              if (component < 3)
                element.dofs[3 * vertex + component] = dof_indices[i];
            }
          for (unsigned int i = 0; i < 9; ++i)
            element.local_dofs[i] = local_index(prototype, element.dofs[i]);
          for (unsigned int v = 0; v < 3; ++v)
            element.reference[v] = cell->vertex(v);
          element.rest = physics::membrane_rest_data(element.reference);
          elements.push_back(element);
        }
    if (has_bending())
      setup_edges();
  }


  void
  ClothModel::setup_edges()
  {
    // The angle component's P2 dofs: k < 3 sits on vertex k (unused, constrained to
    // zero), k >= 3 on line k - 3 of the cell.
    std::map<types::global_dof_index, unsigned int> slot_of_dof;
    std::set<types::global_dof_index>               unused;
    std::vector<types::global_dof_index>            dof_indices(fe->n_dofs_per_cell());
    edges.clear();
    unsigned int e = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(dof_indices);
          for (unsigned int i = 0; i < fe->n_dofs_per_cell(); ++i)
            {
              const auto [component, index] = fe->system_to_component_index(i);
              if (component == 3 && index < 3)
                unused.insert(dof_indices[i]);
            }
          if (!cell->is_locally_owned())
            continue;

          Element           &element = elements[e++];
          const Tensor<1, 3> normal =
            unit_normal(cell->vertex(0), cell->vertex(1), cell->vertex(2));
          for (unsigned int i = 0; i < fe->n_dofs_per_cell(); ++i)
            {
              const auto [component, index] = fe->system_to_component_index(i);
              if (component != 3 || index < 3)
                continue;
              const unsigned int line = index - 3;
              // The triangle's edge opposite vertex v is this line.
              unsigned int v = 0;
              while (cell->vertex_index(v) == cell->line(line)->vertex_index(0) ||
                     cell->vertex_index(v) == cell->line(line)->vertex_index(1))
                ++v;
              const unsigned int next = (v + 1) % 3, after = (v + 2) % 3;
              const bool forward    = precedes(cell->vertex(next), cell->vertex(after));
              element.angle_dofs[v] = dof_indices[i];
              element.edge_signs[v] = forward ? 1. : -1.;

              auto [slot, inserted] = slot_of_dof.emplace(dof_indices[i], edges.size());
              element.edge_slots[v] = slot->second;
              if (!inserted)
                continue;
              // Rest director: the bisector of the two rest normals, or the normal on
              // the boundary (ψ̄ = 0 then gives the rest curvature B̄).
              Edge edge;
              edge.angle_dof = dof_indices[i];
              const std::array<unsigned int, 2> ends =
                forward ? std::array<unsigned int, 2>{{next, after}}
                        : std::array<unsigned int, 2>{{after, next}};
              for (unsigned int k = 0; k < 2; ++k)
                {
                  edge.reference_points[k] = cell->vertex(ends[k]);
                  for (unsigned int c = 0; c < 3; ++c)
                    edge.vertex_dofs[k][c] = element.dofs[3 * ends[k] + c];
                }
              edge.reference = normal;
              if (!cell->at_boundary(line))
                {
                  const auto         neighbor = cell->neighbor(line);
                  const Tensor<1, 3> bisector = normal + unit_normal(neighbor->vertex(0),
                                                                     neighbor->vertex(1),
                                                                     neighbor->vertex(2));
                  AssertThrow(bisector.norm() > 1e-8,
                              ExcMessage("two neighbouring triangles of the mesh are "
                                         "folded onto each other"));
                  edge.reference = bisector / bisector.norm();
                }
              edges.push_back(edge);
            }
        }
    unused_dofs.clear();
    for (const types::global_dof_index dof : unused)
      unused_dofs.push_back(dof);

    for (Element &element : elements)
      {
        physics::EdgeDirectors rest_directors;
        for (unsigned int i = 0; i < 3; ++i)
          {
            rest_directors.reference[i] = edges[element.edge_slots[i]].reference;
            rest_directors.sign[i]      = element.edge_signs[i];
          }
        element.bending_rest =
          physics::bending_rest_data(bending_material, element.reference, rest_directors);
      }
  }


  void
  ClothModel::resolve_pinned(const std::string      &parameter_file,
                             const mesh::MeshGroups &groups)
  {
    // Each pinned group as a vertex predicate, with the components it pins.
    struct GroupPin
    {
      std::array<bool, 3>   components;
      int                   boundary_id = -1; // line group
      int                   material_id = -1; // surface group
      std::vector<Point<3>> points;           // point group
    };
    std::vector<GroupPin> group_pins;
    for (const PinnedGroup &group : parameters.constraints.pinned_groups)
      {
        GroupPin pin;
        pin.components = group.components;
        if (const auto line = groups.line_groups.find(group.name);
            line != groups.line_groups.end())
          pin.boundary_id = line->second;
        else if (const auto surface = groups.surface_groups.find(group.name);
                 surface != groups.surface_groups.end())
          pin.material_id = surface->second;
        else if (const auto point = groups.point_groups.find(group.name);
                 point != groups.point_groups.end())
          pin.points = point->second;
        else
          {
            std::string known;
            for (const std::string &n : groups.all_names())
              known += (known.empty() ? "" : ", ") + n;
            throw InputError(parameter_file,
                             "Constraints/Pinned groups",
                             "the mesh has no group named '" + group.name +
                               "' (its groups: " + (known.empty() ? "none" : known) +
                               ")");
          }
        group_pins.push_back(pin);
      }
    // Clamped groups: boundary lines whose vertices are fixed in every component.
    std::set<types::boundary_id> clamped_ids;
    for (const std::string &name : parameters.constraints.clamped_groups)
      {
        const auto line = groups.line_groups.find(name);
        if (line == groups.line_groups.end())
          {
            std::string known;
            for (const auto &[n, id] : groups.line_groups)
              known += (known.empty() ? "" : ", ") + n;
            throw InputError(parameter_file,
                             "Constraints/Clamped groups",
                             "the mesh has no boundary line group named '" + name +
                               "' (its line groups: " + (known.empty() ? "none" : known) +
                               ")");
          }
        GroupPin pin;
        pin.components  = {{true, true, true}};
        pin.boundary_id = line->second;
        group_pins.push_back(pin);
        clamped_ids.insert(line->second);
      }

    // Matching tolerance for point groups: far below any edge length.
    const double tolerance =
      1e-8 * GridTools::diameter(dof_handler.get_triangulation().get_triangulation());

    std::map<types::global_dof_index, PinnedDof> found;
    std::set<types::global_dof_index>            clamped_angles;
    std::vector<types::global_dof_index>         dof_indices(fe->n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(dof_indices);
          // pinned[vertex][component]
          std::array<std::array<bool, 3>, 3> pinned_here{};
          for (const GroupPin &pin : group_pins)
            {
              std::array<bool, 3> vertex_in_group = {{false, false, false}};
              if (pin.material_id >= 0 &&
                  cell->material_id() == types::material_id(pin.material_id))
                vertex_in_group = {{true, true, true}};
              for (unsigned int v = 0; v < 3; ++v)
                for (const Point<3> &p : pin.points)
                  if (cell->vertex(v).distance(p) < tolerance)
                    vertex_in_group[v] = true;
              if (pin.boundary_id >= 0)
                for (const unsigned int f : cell->face_indices())
                  if (cell->face(f)->at_boundary() &&
                      cell->face(f)->boundary_id() == types::boundary_id(pin.boundary_id))
                    for (unsigned int fv = 0; fv < 2; ++fv)
                      for (unsigned int v = 0; v < 3; ++v)
                        if (cell->vertex_index(v) == cell->face(f)->vertex_index(fv))
                          vertex_in_group[v] = true;
              for (unsigned int v = 0; v < 3; ++v)
                for (unsigned int c = 0; c < 3; ++c)
                  pinned_here[v][c] =
                    pinned_here[v][c] || (vertex_in_group[v] && pin.components[c]);
            }
          for (unsigned int i = 0; i < fe->n_dofs_per_cell(); ++i)
            {
              const auto [vertex, component] = local_dof_vertex_component[i];
              if (component < 3 && pinned_here[vertex][component])
                found[dof_indices[i]] = {dof_indices[i], component, cell->vertex(vertex)};
              // The angle of a clamped boundary line (P2 line dof vertex - 3).
              if (component == 3 && vertex >= 3 &&
                  cell->line(vertex - 3)->at_boundary() &&
                  clamped_ids.count(cell->line(vertex - 3)->boundary_id()) > 0)
                clamped_angles.insert(dof_indices[i]);
            }
        }

    pinned.clear();
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    for (const auto &[dof, pin] : found)
      {
        pinned.push_back(pin);
        constraints.add_line(dof);
      }
    for (const types::global_dof_index dof : clamped_angles)
      constraints.add_line(dof);
    for (const types::global_dof_index dof : unused_dofs)
      constraints.add_line(dof);
    constraints.close();
    for (Edge &edge : edges)
      edge.clamped = clamped_angles.count(edge.angle_dof) > 0;

    // Every named pinned group must pin something somewhere.
    if ((!parameters.constraints.pinned_groups.empty() ||
         !parameters.constraints.clamped_groups.empty()) &&
        Utilities::MPI::sum(static_cast<unsigned int>(pinned.size()), communicator) == 0)
      throw InputError(parameter_file,
                       "Constraints/Pinned groups",
                       "the named pinned and clamped groups contain no mesh vertex");

    parse_vector_function(pinned_displacement,
                          parameters.constraints.pinned_displacement,
                          /*time_dependent=*/true,
                          parameter_file,
                          "Constraints/Pinned displacement");
    parse_vector_function(initial_displacement_function,
                          parameters.time.initial_displacement,
                          /*time_dependent=*/false,
                          parameter_file,
                          "Time/Initial displacement");
    parse_vector_function(initial_velocity_function,
                          parameters.time.initial_velocity,
                          /*time_dependent=*/false,
                          parameter_file,
                          "Time/Initial velocity");
  }


  void
  ClothModel::parse_vector_function(FunctionParser<3> &function,
                                    const std::string &expressions,
                                    const bool         time_dependent,
                                    const std::string &parameter_file,
                                    const std::string &entry)
  {
    // deal.II parses on the first evaluation (and prints the parser's complaint to
    // std::cerr): evaluate once here, quietly, so that a bad expression is a one-line
    // input error now rather than an abort mid-run.
    std::ostringstream parser_messages;
    std::streambuf    *cerr_buffer = std::cerr.rdbuf(parser_messages.rdbuf());
    try
      {
        function.initialize(time_dependent ? "x,y,z,t" : "x,y,z",
                            expressions,
                            {{"pi", numbers::PI}},
                            time_dependent);
        for (unsigned int c = 0; c < 3; ++c)
          function.value(Point<3>(), c);
        std::cerr.rdbuf(cerr_buffer);
      }
    catch (const std::exception &)
      {
        std::cerr.rdbuf(cerr_buffer);
        throw InputError(parameter_file,
                         entry,
                         "cannot parse '" + expressions +
                           "' as three expressions in x, y, z" +
                           (time_dependent ? ", t" : ""));
      }
  }


  void
  ClothModel::initial_state(VectorType &u, VectorType &v) const
  {
    u = 0.;
    v = 0.;
    for (const Element &element : elements)
      for (unsigned int vertex = 0; vertex < 3; ++vertex)
        for (unsigned int c = 0; c < 3; ++c)
          {
            const types::global_dof_index dof = element.dofs[3 * vertex + c];
            if (!locally_owned_dofs.is_element(dof))
              continue;
            u[dof] = initial_displacement_function.value(element.reference[vertex], c);
            v[dof] = initial_velocity_function.value(element.reference[vertex], c);
          }
    u.compress(VectorOperation::insert);
    v.compress(VectorOperation::insert);
    apply_pinned_displacement(0., u);
  }


  unsigned int
  ClothModel::n_pinned_dofs() const
  {
    unsigned int n_owned = 0;
    for (const PinnedDof &pin : pinned)
      if (locally_owned_dofs.is_element(pin.dof))
        ++n_owned;
    return Utilities::MPI::sum(n_owned, communicator);
  }


  void
  ClothModel::initialize_owned(VectorType &vector) const
  {
    vector.reinit(locally_owned_dofs, communicator);
  }


  void
  ClothModel::initialize_ghosted(VectorType &vector) const
  {
    vector.reinit(locally_owned_dofs, locally_relevant_dofs, communicator);
  }


  void
  ClothModel::initialize_matrix(MatrixType &matrix) const
  {
    TrilinosWrappers::SparsityPattern sparsity(locally_owned_dofs,
                                               locally_owned_dofs,
                                               locally_relevant_dofs,
                                               communicator);
    DoFTools::make_sparsity_pattern(dof_handler, sparsity, constraints, false);
    if (springs)
      springs->add_sparsity(sparsity, constraints);
    sparsity.compress();
    matrix.reinit(sparsity);
  }


  void
  ClothModel::apply_pinned_displacement(const double time, VectorType &u) const
  {
    pinned_displacement.set_time(time);
    for (const PinnedDof &pin : pinned)
      if (locally_owned_dofs.is_element(pin.dof))
        u[pin.dof] = pinned_displacement.value(pin.reference, pin.component);
    u.compress(VectorOperation::insert);
  }


  void
  ClothModel::gather(const VectorType      &ghosted,
                     const Element         &element,
                     std::array<double, 9> &values) const
  {
    const double *local = ghosted_values(ghosted, locally_relevant_dofs.n_elements());
    for (unsigned int i = 0; i < 9; ++i)
      values[i] = local[element.local_dofs[i]];
  }


  namespace
  {
    // Element mass matrix per component: lumped ρ|T|/3 δ_ab, or consistent ρ|T|/12 (1 +
    // δ_ab).
    inline double
    mass_entry(const bool         lumped,
               const double       vertex_mass,
               const unsigned int a,
               const unsigned int b)
    {
      if (lumped)
        return a == b ? vertex_mass : 0.;
      return vertex_mass * (a == b ? 0.5 : 0.25);
    }
  } // namespace


  physics::TrianglePositions
  ClothModel::current_positions(const Element         &element,
                                const VectorType      &u,
                                std::array<double, 9> &u_e) const
  {
    gather(u, element, u_e);
    physics::TrianglePositions x = element.reference;
    for (unsigned int v = 0; v < 3; ++v)
      for (unsigned int d = 0; d < 3; ++d)
        x[v][d] += u_e[3 * v + d];
    return x;
  }


  template <class CellFunction>
  void
  ClothModel::for_each_owned_cell(const VectorType &u, const CellFunction &function) const
  {
    std::array<double, 9> u_e;
    unsigned int          e = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const Element &element = elements[e++];
          function(cell->active_cell_index(),
                   element,
                   current_positions(element, u, u_e));
        }
  }


  void
  ClothModel::prepare_damping(const VectorType &u_n)
  {
    const double beta = parameters.damping.stiffness_proportional;
    if (beta == 0.)
      {
        damping_tangents.clear();
        return;
      }
    if (springs)
      {
        springs->prepare_damping(u_n);
        return;
      }
    damping_tangents.resize(elements.size());
    std::array<double, 9>  u_e;
    physics::ElementVector gradient;
    for (unsigned int e = 0; e < elements.size(); ++e)
      {
        const Element                   &element = elements[e];
        const physics::TrianglePositions x       = current_positions(element, u_n, u_e);
        physics::membrane_energy_gradient_hessian(material,
                                                  element.rest,
                                                  x,
                                                  /*stress_floor=*/0.,
                                                  gradient,
                                                  &damping_tangents[e]);
      }
  }


  physics::EdgeDirectors
  ClothModel::edge_directors(const Element       &element,
                             const VectorType    &u,
                             physics::EdgeAngles &psi) const
  {
    physics::EdgeDirectors directors;
    for (unsigned int i = 0; i < 3; ++i)
      {
        directors.reference[i] = edges[element.edge_slots[i]].reference;
        directors.sign[i]      = element.edge_signs[i];
        psi[i]                 = u(element.angle_dofs[i]);
      }
    return directors;
  }


  double
  ClothModel::assemble(const VectorType &u,
                       const StepTerms  &terms,
                       VectorType       *gradient,
                       MatrixType       *hessian) const
  {
    const bool   lumped  = parameters.material.lumped_mass;
    const double rho     = parameters.material.areal_density;
    const double alpha   = parameters.damping.mass_proportional;
    const double beta    = parameters.damping.stiffness_proportional;
    const bool   bending = has_bending();
    // Mass-like coefficient of the quadratic terms: w_i M + w_d α M.
    const double mass_weight = terms.inertia_weight + terms.damping_weight * alpha;
    // Projected tangent: compression in the geometric stiffness is kept down to what the
    // element's smallest mass eigenvalue m_min (ρ|T̄|/3 lumped, ρ|T̄|/12 consistent) pays
    // for, s_min = mass_weight m_min / (3|T̄|) (see membrane.h); the element Hessian stays
    // PSD. The bending part of a projected tangent is its Gauss–Newton part (bending.h).
    const double stress_floor = terms.projected_tangent
                                  ? mass_weight * rho / (lumped ? 9. : 36.)
                                  : std::numeric_limits<double>::infinity();
    const bool   use_inertia  = terms.inertia_weight > 0.;
    const bool   use_damping  = terms.damping_weight > 0. && (alpha > 0. || beta > 0.);
    Assert(!use_inertia || terms.predictor != nullptr, ExcInternalError());
    Assert(!use_damping || terms.previous != nullptr, ExcInternalError());
    Assert(beta == 0. || springs || damping_tangents.size() == elements.size(),
           ExcInternalError());

    if (gradient != nullptr)
      *gradient = 0.;
    if (hessian != nullptr)
      *hessian = 0.;

    const unsigned int                   n_local = bending ? 12 : 9;
    std::array<double, 9>                u_e, predictor_e, previous_e;
    physics::ElementVector               g_e;
    physics::ElementMatrix               H_e;
    physics::BendingVector               g_b;
    physics::BendingMatrix               H_b;
    physics::EdgeAngles                  psi;
    Vector<double>                       cell_vector(n_local);
    FullMatrix<double>                   cell_matrix(n_local, n_local);
    std::vector<types::global_dof_index> dof_vector(n_local);
    double                               value = 0.;

    for (unsigned int e = 0; e < elements.size(); ++e)
      {
        const Element                   &element = elements[e];
        const physics::TrianglePositions x       = current_positions(element, u, u_e);

        // Membrane energy W_e (the springs replace it in the mass-spring model).
        if (springs)
          {
            g_e.fill(0.);
            for (auto &row : H_e)
              row.fill(0.);
          }
        else if (gradient != nullptr || hessian != nullptr)
          value +=
            physics::membrane_energy_gradient_hessian(material,
                                                      element.rest,
                                                      x,
                                                      stress_floor,
                                                      g_e,
                                                      hessian != nullptr ? &H_e
                                                                         : nullptr);
        else
          {
            value += physics::membrane_energy(material, element.rest, x);
            g_e.fill(0.); // the load terms below still add to it
          }

        const double vertex_mass = rho * element.rest.area / 3.;
        // Gravity: -λ f_gᵀ u_e with f_g = m_v g on each vertex.
        for (unsigned int v = 0; v < 3; ++v)
          for (unsigned int d = 0; d < 3; ++d)
            {
              const double load =
                terms.load_factor * vertex_mass * parameters.loads.gravity[d];
              value -= load * u_e[3 * v + d];
              g_e[3 * v + d] -= load;
            }

        // Quadratic terms w_i/2 rᵀ M r + w_d α/2 sᵀ M s with r = u - û, s = u - u_n (a
        // term that is off has its centre at u, so r or s vanishes).
        if (use_inertia)
          gather(*terms.predictor, element, predictor_e);
        else
          predictor_e = u_e;
        if (use_damping)
          gather(*terms.previous, element, previous_e);
        else
          previous_e = u_e;
        const double damping_mass_weight = terms.damping_weight * alpha;
        for (unsigned int v = 0; v < 3; ++v)
          for (unsigned int w = 0; w < 3; ++w)
            {
              const double m_vw = mass_entry(lumped, vertex_mass, v, w);
              if (m_vw == 0.)
                continue;
              for (unsigned int d = 0; d < 3; ++d)
                {
                  const unsigned int i = 3 * v + d, j = 3 * w + d;
                  const double       r_i = u_e[i] - predictor_e[i],
                               r_j       = u_e[j] - predictor_e[j];
                  const double s_i = u_e[i] - previous_e[i], s_j = u_e[j] - previous_e[j];
                  value +=
                    0.5 * m_vw *
                    (terms.inertia_weight * r_i * r_j + damping_mass_weight * s_i * s_j);
                  g_e[i] +=
                    m_vw * (terms.inertia_weight * r_j + damping_mass_weight * s_j);
                  if (hessian != nullptr)
                    H_e[i][j] += mass_weight * m_vw;
                }
            }

        if (use_damping && beta > 0. && !springs)
          {
            const physics::ElementMatrix &K = damping_tangents[e];
            const double                  c = terms.damping_weight * beta;
            for (unsigned int i = 0; i < 9; ++i)
              {
                double Kdu = 0.;
                for (unsigned int j = 0; j < 9; ++j)
                  {
                    Kdu += K[i][j] * (u_e[j] - previous_e[j]);
                    if (hessian != nullptr)
                      H_e[i][j] += c * K[i][j];
                  }
                g_e[i] += c * Kdu;
                value += 0.5 * c * (u_e[i] - previous_e[i]) * Kdu;
              }
          }

        // Pressure: λ Φ_p (its indefinite Hessian only in the exact tangent).
        if (parameters.loads.pressure != 0.)
          {
            physics::ElementVector g_p;
            physics::ElementMatrix H_p;
            const bool with_hessian = hessian != nullptr && !terms.projected_tangent;
            value +=
              terms.load_factor *
              physics::pressure_potential_gradient_hessian(parameters.loads.pressure,
                                                           x,
                                                           pressure_apex,
                                                           g_p,
                                                           with_hessian ? &H_p : nullptr);
            for (unsigned int i = 0; i < 9; ++i)
              {
                g_e[i] += terms.load_factor * g_p[i];
                if (with_hessian)
                  for (unsigned int j = 0; j < 9; ++j)
                    H_e[i][j] += terms.load_factor * H_p[i][j];
              }
          }

        // Bending energy on positions and edge angles (12 local unknowns).
        if (bending)
          {
            const physics::EdgeDirectors directors = edge_directors(element, u, psi);
            if (gradient != nullptr || hessian != nullptr)
              value +=
                physics::bending_energy_gradient_hessian(bending_material,
                                                         element.bending_rest,
                                                         x,
                                                         directors,
                                                         psi,
                                                         terms.projected_tangent,
                                                         g_b,
                                                         hessian != nullptr ? &H_b
                                                                            : nullptr);
            else
              value += physics::bending_energy(
                bending_material, element.bending_rest, x, directors, psi);
          }

        std::copy(element.dofs.begin(), element.dofs.end(), dof_vector.begin());
        if (bending)
          std::copy(element.angle_dofs.begin(),
                    element.angle_dofs.end(),
                    dof_vector.begin() + 9);
        if (gradient != nullptr)
          {
            for (unsigned int i = 0; i < n_local; ++i)
              cell_vector[i] = (i < 9 ? g_e[i] : 0.) + (bending ? g_b[i] : 0.);
            constraints.distribute_local_to_global(cell_vector, dof_vector, *gradient);
          }
        if (hessian != nullptr)
          {
            for (unsigned int i = 0; i < n_local; ++i)
              for (unsigned int j = 0; j < n_local; ++j)
                cell_matrix(i, j) =
                  (i < 9 && j < 9 ? H_e[i][j] : 0.) + (bending ? H_b[i][j] : 0.);
            constraints.distribute_local_to_global(cell_matrix, dof_vector, *hessian);
          }
      }

    if (springs)
      value += springs->add_to_potential(u,
                                         terms.projected_tangent,
                                         use_damping ? terms.damping_weight * beta : 0.,
                                         terms.previous,
                                         constraints,
                                         gradient,
                                         hessian);

    // Point and line forces: -λ f_extᵀ u.
    value -= terms.load_factor * local_external_work(u);
    if (gradient != nullptr)
      {
        gradient->compress(VectorOperation::add);
        gradient->add(-terms.load_factor, external_forces);
      }
    if (hessian != nullptr)
      {
        // Unit diagonal on the unused (constrained) angle-component dofs.
        FullMatrix<double>                   unit(1, 1);
        std::vector<types::global_dof_index> single(1);
        unit(0, 0) = 1.;
        for (const types::global_dof_index dof : unused_dofs)
          if (locally_owned_dofs.is_element(dof))
            {
              single[0] = dof;
              constraints.distribute_local_to_global(unit, single, *hessian);
            }
        hessian->compress(VectorOperation::add);
      }
    return Utilities::MPI::sum(value, communicator);
  }


  void
  ClothModel::rebase_directors(const VectorType &u_ghosted, VectorType &u)
  {
    if (!has_bending())
      return;
    for (Edge &edge : edges)
      {
        if (edge.clamped)
          continue;
        std::array<Point<3>, 2> ends = edge.reference_points;
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int c = 0; c < 3; ++c)
            ends[k][c] += u_ghosted(edge.vertex_dofs[k][c]);
        edge.reference = physics::edge_director(ends[0],
                                                ends[1],
                                                edge.reference,
                                                u_ghosted(edge.angle_dof));
        if (locally_owned_dofs.is_element(edge.angle_dof))
          u[edge.angle_dof] = 0.;
      }
    u.compress(VectorOperation::insert);
  }


  double
  ClothModel::local_external_work(const VectorType &u) const
  {
    if (parameters.loads.point_forces.empty() && parameters.loads.line_forces.empty())
      return 0.;
    double work = 0.;
    for (const types::global_dof_index i : locally_owned_dofs)
      work += external_forces[i] * u[i];
    return work;
  }


  void
  ClothModel::resolve_loads(const std::string      &parameter_file,
                            const mesh::MeshGroups &groups)
  {
    initialize_owned(external_forces);
    external_forces = 0.;
    const double tolerance =
      1e-8 * GridTools::diameter(dof_handler.get_triangulation().get_triangulation());

    // Point forces: on every vertex of the point group (each vertex once).
    for (const GroupLoad &load : parameters.loads.point_forces)
      {
        const auto group = groups.point_groups.find(load.name);
        if (group == groups.point_groups.end())
          throw InputError(parameter_file,
                           "Loads/Point forces",
                           "the mesh has no point group named '" + load.name + "'");
        std::set<types::global_dof_index> loaded;
        for (const Element &element : elements)
          for (unsigned int v = 0; v < 3; ++v)
            if (locally_owned_dofs.is_element(element.dofs[3 * v]))
              for (const Point<3> &p : group->second)
                if (element.reference[v].distance(p) < tolerance &&
                    loaded.insert(element.dofs[3 * v]).second)
                  for (unsigned int c = 0; c < 3; ++c)
                    external_forces[element.dofs[3 * v + c]] += load.value[c];
        if (Utilities::MPI::sum(static_cast<unsigned int>(loaded.size()), communicator) ==
            0)
          throw InputError(parameter_file,
                           "Loads/Point forces",
                           "the point group '" + load.name + "' holds no mesh vertex");
      }
    external_forces.compress(VectorOperation::add);

    // Line forces: q ℓ/2 on each end of every boundary edge of the group.
    for (const GroupLoad &load : parameters.loads.line_forces)
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
                  external_forces.add(dofs, values);
                }
      }
    external_forces.compress(VectorOperation::add);
    constraints.set_zero(external_forces);

    // The pressure potential's apex: the area-weighted centroid of the reference surface.
    Tensor<1, 3> moment;
    double       area = 0.;
    for (const Element &element : elements)
      {
        for (unsigned int v = 0; v < 3; ++v)
          moment += (element.rest.area / 3.) * element.reference[v];
        area += element.rest.area;
      }
    for (unsigned int d = 0; d < 3; ++d)
      moment[d] = Utilities::MPI::sum(moment[d], communicator);
    pressure_apex = Point<3>(moment / Utilities::MPI::sum(area, communicator));
  }


  void
  ClothModel::internal_forces(const VectorType &u, VectorType &forces) const
  {
    forces = 0.;
    std::array<double, 9>  u_e;
    physics::ElementVector g_e;
    physics::BendingVector g_b;
    physics::EdgeAngles    psi;
    if (springs)
      {
        springs->add_to_potential(
          u, true, 0., nullptr, AffineConstraints<double>(), &forces, nullptr);
        forces.compress(VectorOperation::add);
        return;
      }
    for (const Element &element : elements)
      {
        const physics::TrianglePositions x = current_positions(element, u, u_e);
        physics::membrane_energy_gradient_hessian(
          material, element.rest, x, 0., g_e, nullptr);
        std::vector<types::global_dof_index> dofs(element.dofs.begin(),
                                                  element.dofs.end());
        std::vector<double>                  values(g_e.begin(), g_e.end());
        if (has_bending())
          {
            const physics::EdgeDirectors directors = edge_directors(element, u, psi);
            physics::bending_energy_gradient_hessian(bending_material,
                                                     element.bending_rest,
                                                     x,
                                                     directors,
                                                     psi,
                                                     true,
                                                     g_b,
                                                     nullptr);
            for (unsigned int i = 0; i < 12; ++i)
              {
                if (i < 9)
                  values[i] += g_b[i];
                else
                  {
                    dofs.push_back(element.angle_dofs[i - 9]);
                    values.push_back(g_b[i]);
                  }
              }
          }
        forces.add(dofs, values);
      }
    forces.compress(VectorOperation::add);
  }


  Energies
  ClothModel::energies(const VectorType &u, const VectorType &v) const
  {
    const bool            lumped = parameters.material.lumped_mass;
    const double          rho    = parameters.material.areal_density;
    std::array<double, 9> u_e, v_e;
    physics::EdgeAngles   psi;
    Energies              local;
    for (const Element &element : elements)
      {
        const physics::TrianglePositions x = current_positions(element, u, u_e);
        gather(v, element, v_e);
        if (!springs)
          local.elastic += physics::membrane_energy(material, element.rest, x);
        if (has_bending())
          {
            const physics::EdgeDirectors directors = edge_directors(element, u, psi);
            local.elastic += physics::bending_energy(
              bending_material, element.bending_rest, x, directors, psi);
          }
        if (parameters.loads.pressure != 0.)
          {
            // -p (V(x) - V(X)): zero in the reference configuration, like gravity's.
            physics::ElementVector g_p;
            local.potential +=
              physics::pressure_potential_gradient_hessian(
                parameters.loads.pressure, x, pressure_apex, g_p, nullptr) -
              physics::pressure_potential_gradient_hessian(parameters.loads.pressure,
                                                           element.reference,
                                                           pressure_apex,
                                                           g_p,
                                                           nullptr);
          }
        const double vertex_mass = rho * element.rest.area / 3.;
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int d = 0; d < 3; ++d)
            {
              local.potential -=
                vertex_mass * parameters.loads.gravity[d] * u_e[3 * a + d];
              for (unsigned int b = 0; b < 3; ++b)
                local.kinetic += 0.5 * mass_entry(lumped, vertex_mass, a, b) *
                                 v_e[3 * a + d] * v_e[3 * b + d];
            }
      }
    local.potential -= local_external_work(u);
    if (springs)
      local.elastic += springs->energy(u);
    Energies global;
    global.kinetic   = Utilities::MPI::sum(local.kinetic, communicator);
    global.elastic   = Utilities::MPI::sum(local.elastic, communicator);
    global.potential = Utilities::MPI::sum(local.potential, communicator);
    return global;
  }


  std::pair<double, double>
  ClothModel::area_ratio_range(const VectorType &u) const
  {
    std::array<double, 9> u_e;
    double                smallest = std::numeric_limits<double>::max(), largest = 0.;
    for (const Element &element : elements)
      {
        const physics::TrianglePositions x = current_positions(element, u, u_e);
        const double                     ratio =
          physics::membrane_strain_stress(material, element.rest, x).area_ratio;
        // NaN: smallest -1 and largest infinite, so that both checks catch it.
        smallest = std::min(smallest, std::isfinite(ratio) ? ratio : -1.);
        largest =
          std::max(largest,
                   std::isfinite(ratio) ? ratio
                                        : std::numeric_limits<double>::infinity());
      }
    return {Utilities::MPI::min(smallest, communicator),
            Utilities::MPI::max(largest, communicator)};
  }


  void
  ClothModel::lumped_masses(VectorType &masses) const
  {
    initialize_owned(masses);
    const double rho = parameters.material.areal_density;
    for (const Element &element : elements)
      {
        const std::vector<types::global_dof_index> dofs(element.dofs.begin(),
                                                        element.dofs.end());
        const std::vector<double> values(9, rho * element.rest.area / 3.);
        masses.add(dofs, values);
      }
    masses.compress(VectorOperation::add);
  }


  types::global_dof_index
  ClothModel::limit_strain(VectorType  &u,
                           VectorType  &v,
                           const double dt,
                           double      &largest_strain) const
  {
    const MassSpringParameters &limits = parameters.mass_spring;
    Assert(springs != nullptr, ExcInternalError());
    if (limits.strain_limit == 0.)
      return 0;
    VectorType u_ghosted, moves;
    initialize_ghosted(u_ghosted);
    initialize_owned(moves);
    // Gauss–Seidel sweeps colour by colour; the last sweep only counts.
    types::global_dof_index violations = 0;
    for (unsigned int sweep = 0; sweep <= limits.strain_limit_iterations; ++sweep)
      {
        const bool count_only = sweep == limits.strain_limit_iterations;
        violations            = 0;
        largest_strain        = 0.;
        for (unsigned int color = 0; color < springs->n_colors(); ++color)
          {
            u_ghosted = u;
            moves     = 0.;
            violations += Utilities::MPI::sum(
              static_cast<types::global_dof_index>(
                springs->add_strain_limit_moves(u_ghosted,
                                                inverse_masses,
                                                limits.strain_limit,
                                                limits.limit_compression,
                                                color,
                                                moves,
                                                largest_strain)),
              communicator);
            if (count_only)
              continue;
            moves.compress(VectorOperation::add);
            u.add(1., moves);
            v.add(1. / dt, moves);
          }
        if (violations == 0)
          break;
      }
    largest_strain = Utilities::MPI::max(largest_strain, communicator);
    return violations;
  }


  std::vector<std::array<double, 6>>
  ClothModel::vertex_displacements(const VectorType &u) const
  {
    std::vector<std::array<double, 6>> local;
    std::set<types::global_dof_index>  seen;
    for (const Element &element : elements)
      for (unsigned int v = 0; v < 3; ++v)
        if (locally_owned_dofs.is_element(element.dofs[3 * v]) &&
            seen.insert(element.dofs[3 * v]).second)
          {
            std::array<double, 6> row;
            for (unsigned int d = 0; d < 3; ++d)
              {
                row[d]     = element.reference[v][d];
                row[3 + d] = u(element.dofs[3 * v + d]);
              }
            local.push_back(row);
          }
    const auto gathered = Utilities::MPI::gather(communicator, local, 0);
    std::vector<std::array<double, 6>> all;
    for (const auto &part : gathered)
      all.insert(all.end(), part.begin(), part.end());
    std::sort(all.begin(), all.end(), [](const auto &a, const auto &b) {
      return std::lexicographical_compare(a.begin(),
                                          a.begin() + 3,
                                          b.begin(),
                                          b.begin() + 3);
    });
    return all;
  }


  void
  ClothModel::cell_edge_strain(const VectorType &u, Vector<double> &strain) const
  {
    strain.reinit(triangulation.n_active_cells());
    for_each_owned_cell(u,
                        [&](const unsigned int                cell,
                            const Element                    &element,
                            const physics::TrianglePositions &x) {
                          double largest = 0.;
                          for (unsigned int i = 0; i < 3; ++i)
                            {
                              const unsigned int a = (i + 1) % 3, b = (i + 2) % 3;
                              const double       edge_strain =
                                (x[b] - x[a]).norm() /
                                  (element.reference[b] - element.reference[a]).norm() -
                                1.;
                              if (std::abs(edge_strain) > std::abs(largest))
                                largest = edge_strain;
                            }
                          strain[cell] = largest;
                        });
  }


  void
  ClothModel::cell_strain_stress(const VectorType &u,
                                 Vector<double>   &strain,
                                 Vector<double>   &stress) const
  {
    strain.reinit(triangulation.n_active_cells());
    stress.reinit(triangulation.n_active_cells());
    for_each_owned_cell(u,
                        [&](const unsigned int                cell,
                            const Element                    &element,
                            const physics::TrianglePositions &x) {
                          const auto measures =
                            physics::membrane_strain_stress(material, element.rest, x);
                          strain[cell] = measures.green_strain_norm;
                          stress[cell] = measures.stress_norm;
                        });
  }


  void
  ClothModel::cell_curvature_change(const VectorType &u, Vector<double> &curvature) const
  {
    curvature.reinit(triangulation.n_active_cells());
    if (!has_bending())
      return;
    physics::EdgeAngles psi;
    for_each_owned_cell(u,
                        [&](const unsigned int                cell,
                            const Element                    &element,
                            const physics::TrianglePositions &x) {
                          const physics::EdgeDirectors directors =
                            edge_directors(element, u, psi);
                          curvature[cell] = physics::curvature_change_norm(
                            bending_material, element.bending_rest, x, directors, psi);
                        });
  }


  std::vector<ProbeLocation>
  ClothModel::locate_probes(const std::vector<Probe> &probes) const
  {
    std::vector<ProbeLocation> located;
    const unsigned int         rank = Utilities::MPI::this_mpi_process(communicator);
    for (const Probe &probe : probes)
      {
        // Nearest locally owned vertex (its x dof owned here), then the global minimum.
        double        best = std::numeric_limits<double>::max();
        ProbeLocation candidate{probe.name, Point<3>(), {{0, 0, 0}}};
        for (const Element &element : elements)
          for (unsigned int v = 0; v < 3; ++v)
            if (locally_owned_dofs.is_element(element.dofs[3 * v]))
              {
                const double distance =
                  element.reference[v].distance(probe.reference_point);
                if (distance < best)
                  {
                    best                      = distance;
                    candidate.reference_point = element.reference[v];
                    for (unsigned int d = 0; d < 3; ++d)
                      candidate.dofs[d] = element.dofs[3 * v + d];
                  }
              }
        // Ties between ranks go to the lowest rank.
        const auto all =
          Utilities::MPI::all_gather(communicator, std::make_pair(best, rank));
        const auto winner = std::min_element(all.begin(), all.end())->second;
        located.push_back(Utilities::MPI::broadcast(communicator, candidate, winner));
      }
    return located;
  }


  std::vector<double>
  ClothModel::gather_values(const VectorType                           &u,
                            const std::vector<types::global_dof_index> &dofs) const
  {
    std::vector<double> values(dofs.size(), 0.);
    for (unsigned int i = 0; i < dofs.size(); ++i)
      if (locally_owned_dofs.is_element(dofs[i]))
        values[i] = u(dofs[i]);
    std::vector<double> sums(dofs.size(), 0.);
    MPI_Allreduce(
      values.data(), sums.data(), values.size(), MPI_DOUBLE, MPI_SUM, communicator);
    return sums;
  }


  NearNullSpace
  ClothModel::near_null_space() const
  {
    // Translations, plus the rotation about the sheet's mean normal n through its
    // centroid: the membrane's in-plane elasticity has that rotation in its kernel.
    // (Rotations about in-plane axes are not: they bend, and a tensioned membrane resists
    // them like a Laplacian; with all six rigid modes ML's CG diverged on the default
    // scene.)
    Tensor<1, 3> moment, normal_sum;
    double       area = 0.;
    for (const Element &element : elements)
      {
        const auto &X = element.reference;
        for (unsigned int v = 0; v < 3; ++v)
          moment += (element.rest.area / 3.) * X[v];
        normal_sum += 0.5 * cross_product_3d(X[1] - X[0], X[2] - X[0]);
        area += element.rest.area;
      }
    for (unsigned int d = 0; d < 3; ++d)
      {
        moment[d]     = Utilities::MPI::sum(moment[d], communicator);
        normal_sum[d] = Utilities::MPI::sum(normal_sum[d], communicator);
      }
    area                        = Utilities::MPI::sum(area, communicator);
    const Tensor<1, 3> centroid = moment / area;
    // A sheet that is far from planar has no single in-plane rotation.
    const bool         nearly_planar = normal_sum.norm() > 0.9 * area;
    const Tensor<1, 3> normal        = normal_sum / normal_sum.norm();

    const unsigned int               n_owned = locally_owned_dofs.n_elements();
    std::vector<std::vector<double>> modes(nearly_planar ? 4 : 3,
                                           std::vector<double>(n_owned, 0.));
    for (const Element &element : elements)
      for (unsigned int v = 0; v < 3; ++v)
        {
          const Tensor<1, 3> rotation =
            cross_product_3d(normal, element.reference[v] - centroid);
          for (unsigned int c = 0; c < 3; ++c)
            if (locally_owned_dofs.is_element(element.dofs[3 * v + c]))
              {
                const unsigned int i =
                  locally_owned_dofs.index_within_set(element.dofs[3 * v + c]);
                modes[c][i] = 1.;
                if (nearly_planar)
                  modes[3][i] = rotation[c];
              }
        }
    NearNullSpace space{modes, 3u, IndexSet(), IndexSet(), IndexSet()};
    if (has_bending())
      {
        // Displacements and angles interleave: AMG gets the displacement block alone.
        space.displacement_dofs = IndexSet(dof_handler.n_dofs());
        for (const Element &element : elements)
          for (const types::global_dof_index dof : element.dofs)
            if (locally_owned_dofs.is_element(dof))
              space.displacement_dofs.add_index(dof);
        space.displacement_dofs.compress();
        space.owned_dofs    = locally_owned_dofs;
        space.relevant_dofs = locally_relevant_dofs;
      }
    return space;
  }


  double
  ClothModel::total_mass() const
  {
    return parameters.material.areal_density * reference_area();
  }


  double
  ClothModel::reference_area() const
  {
    double area = 0.;
    for (const Element &element : elements)
      area += element.rest.area;
    return Utilities::MPI::sum(area, communicator);
  }
} // namespace clothsim
