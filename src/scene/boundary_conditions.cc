#include "scene/boundary_conditions.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/tria.h>

#include "io/input_error.h"

#include <boost/serialization/array.hpp>

#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>

namespace clothsim
{
  namespace
  {
    // Each pinned group as a vertex predicate, with the components it pins.
    struct GroupPin
    {
      std::array<bool, 3>   components;
      bool                  rotation    = false; // the rotation about its edges held
      int                   boundary_id = -1;    // line group
      int                   material_id = -1;    // surface group
      std::vector<Point<3>> points;              // point group
    };

    std::string
    list_names(const std::vector<std::string> &names)
    {
      std::string known;
      for (const std::string &n : names)
        known += (known.empty() ? "" : ", ") + n;
      return known.empty() ? "none" : known;
    }

  } // namespace


  double
  point_matching_tolerance(const Triangulation<2, 3> &triangulation,
                           const MPI_Comm             communicator)
  {
    // Lower and upper corners of the box, the lower negated so that one max finds both.
    std::array<double, 6> box;
    box.fill(-std::numeric_limits<double>::max());
    for (const auto &cell : triangulation.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < 3; ++d)
            {
              box[d]     = std::max(box[d], -cell->vertex(v)[d]);
              box[3 + d] = std::max(box[3 + d], cell->vertex(v)[d]);
            }
    std::array<double, 6> all;
    Utilities::MPI::max(ArrayView<const double>(box.data(), box.size()),
                        communicator,
                        ArrayView<double>(all.data(), all.size()));
    double diagonal_squared = 0.;
    for (unsigned int d = 0; d < 3; ++d)
      diagonal_squared += (all[3 + d] + all[d]) * (all[3 + d] + all[d]);
    return 1e-8 * std::sqrt(diagonal_squared);
  }


  void
  check_finite(const FunctionParser<3>                              &function,
               const std::vector<std::pair<unsigned int, Point<3>>> &samples,
               const MPI_Comm                                        communicator,
               const std::string                                    &parameter_file,
               const std::string                                    &entry,
               const std::string                                    &point_name)
  {
    // component (3: none), vertex x, y, z, value
    std::array<double, 5> first   = {{3., 0., 0., 0., 0.}};
    const auto            earlier = [](const std::array<double, 5> &a,
                            const std::array<double, 5> &b) {
      if (a[0] != b[0])
        return a[0] < b[0];
      return mesh::precedes(Point<3>(a[1], a[2], a[3]), Point<3>(b[1], b[2], b[3]));
    };
    for (const auto &[component, vertex] : samples)
      {
        const double                value  = function.value(vertex, component);
        const std::array<double, 5> sample = {
          {double(component), vertex[0], vertex[1], vertex[2], value}};
        if (!std::isfinite(value) && earlier(sample, first))
          first = sample;
      }
    for (const auto &sample : Utilities::MPI::all_gather(communicator, first))
      if (earlier(sample, first))
        first = sample;
    if (first[0] == 3.)
      return;

    const unsigned int component   = first[0];
    const auto         expressions = function.get_expressions();
    std::ostringstream message;
    message << "'" << expressions[component] << "' (component "
            << "xyz"[component] << ") is " << first[4] << " at the " << point_name << " ("
            << first[1] << ", " << first[2] << ", " << first[3]
            << ") at t = 0; expected a finite value at every " << point_name;
    throw InputError(parameter_file, entry, message.str());
  }


  BoundaryConditions::BoundaryConditions(const mesh::Discretization &discretization,
                                         const Parameters           &parameters,
                                         const std::string          &parameter_file,
                                         const mesh::MeshGroups     &groups)
    : discretization(discretization)
    , pinned_displacement(3)
    , initial_displacement(3)
    , initial_velocity(3)
  {
    std::vector<GroupPin>        group_pins;
    std::set<types::boundary_id> held_rotation_ids; // clamped, or pinned with 'r'
    for (const PinnedGroup &group : parameters.constraints.pinned_groups)
      {
        GroupPin pin;
        pin.components = group.components;
        pin.rotation   = group.rotation;
        if (const auto line = groups.line_groups.find(group.name);
            line != groups.line_groups.end())
          {
            pin.boundary_id = line->second;
            if (group.rotation)
              held_rotation_ids.insert(line->second);
          }
        else if (const auto surface = groups.surface_groups.find(group.name);
                 surface != groups.surface_groups.end())
          pin.material_id = surface->second;
        else if (const auto point = groups.point_groups.find(group.name);
                 point != groups.point_groups.end())
          pin.points = point->second;
        else
          throw InputError(parameter_file,
                           "Constraints/Pinned groups",
                           "the mesh has no group named '" + group.name +
                             "' (its groups: " + list_names(groups.all_names()) + ")");
        if (group.rotation && pin.boundary_id < 0)
          throw InputError(parameter_file,
                           "Constraints/Pinned groups",
                           "'" + group.name +
                             ": ...r' holds the rotation about a group's edges; '" +
                             group.name + "' is not a boundary line group");
        group_pins.push_back(pin);
        support_list.push_back({group.name, {}, {}, {}});
      }
    // Clamped groups: boundary lines whose vertices are fixed in every component and
    // whose rotation is held.
    for (const std::string &name : parameters.constraints.clamped_groups)
      {
        const auto line = groups.line_groups.find(name);
        if (line == groups.line_groups.end())
          {
            std::vector<std::string> line_names;
            for (const auto &[n, id] : groups.line_groups)
              line_names.push_back(n);
            throw InputError(parameter_file,
                             "Constraints/Clamped groups",
                             "the mesh has no boundary line group named '" + name +
                               "' (its line groups: " + list_names(line_names) + ")");
          }
        GroupPin pin;
        pin.components  = {{true, true, true}};
        pin.rotation    = true;
        pin.boundary_id = line->second;
        group_pins.push_back(pin);
        support_list.push_back({name, {}, {}, {}});
        held_rotation_ids.insert(line->second);
      }

    // Matching tolerance for point groups: far below any edge length.
    const DoFHandler<2, 3> &dof_handler = discretization.get_dof_handler();
    const double tolerance = point_matching_tolerance(dof_handler.get_triangulation(),
                                                      discretization.get_communicator());
    const auto  &vertex_component    = discretization.local_dof_vertex_component();
    const unsigned int dofs_per_cell = discretization.get_fe().n_dofs_per_cell();

    std::map<types::global_dof_index, PinnedDof> found;
    std::vector<types::global_dof_index>         dof_indices(dofs_per_cell);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(dof_indices);
          std::array<std::array<types::global_dof_index, 3>, 3> vertex_dofs;
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            if (vertex_component[i].second < 3)
              vertex_dofs[vertex_component[i].first][vertex_component[i].second] =
                dof_indices[i];
          // pinned[vertex][component]
          std::array<std::array<bool, 3>, 3> pinned_here{};
          for (unsigned int g = 0; g < group_pins.size(); ++g)
            {
              const GroupPin     &pin             = group_pins[g];
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
              Support &support = support_list[g];
              for (unsigned int v = 0; v < 3; ++v)
                if (vertex_in_group[v])
                  {
                    support.vertices[vertex_dofs[v][0]] = {vertex_dofs[v],
                                                           cell->vertex(v)};
                    for (unsigned int c = 0; c < 3; ++c)
                      if (pin.components[c])
                        support.pinned.insert(vertex_dofs[v][c]);
                  }
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const auto [vertex, component] = vertex_component[i];
                  if (pin.rotation && pin.boundary_id >= 0 && component == 3 &&
                      vertex >= 3 && cell->line(vertex - 3)->at_boundary() &&
                      cell->line(vertex - 3)->boundary_id() ==
                        types::boundary_id(pin.boundary_id))
                    support.held_angles.insert(dof_indices[i]);
                }
              for (unsigned int v = 0; v < 3; ++v)
                for (unsigned int c = 0; c < 3; ++c)
                  pinned_here[v][c] =
                    pinned_here[v][c] || (vertex_in_group[v] && pin.components[c]);
            }
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            {
              const auto [vertex, component] = vertex_component[i];
              if (component < 3 && pinned_here[vertex][component])
                found[dof_indices[i]] = {dof_indices[i], component, cell->vertex(vertex)};
              // The angle of a boundary line whose rotation is held (P2 line dof
              // vertex - 3).
              if (component == 3 && vertex >= 3 &&
                  cell->line(vertex - 3)->at_boundary() &&
                  held_rotation_ids.count(cell->line(vertex - 3)->boundary_id()) > 0)
                clamped_angle_dofs.insert(dof_indices[i]);
            }
        }

    std::vector<types::global_dof_index> lines; // the constrained dofs seen here
    for (const auto &[dof, pin] : found)
      {
        pinned.push_back(pin);
        pinned_dofs.insert(dof);
        lines.push_back(dof);
      }
    lines.insert(lines.end(), clamped_angle_dofs.begin(), clamped_angle_dofs.end());
    lines.insert(lines.end(),
                 discretization.unused_dofs().begin(),
                 discretization.unused_dofs().end());
    // Self-contact couples a vertex with any other of the sheet, also with vertices this
    // rank neither owns nor has as ghosts, and asks the constraints about their dofs
    // (SelfContact::add_couplings). Then every rank stores every rank's lines (the
    // unused angle dofs make one per vertex: as much as self-contact gathers of the
    // positions anyway); otherwise those of its locally relevant dofs.
    IndexSet stored = discretization.relevant_dofs();
    if (parameters.contact.self_contact &&
        Utilities::MPI::n_mpi_processes(discretization.get_communicator()) > 1)
      {
        std::vector<types::global_dof_index> owned_lines;
        for (const types::global_dof_index dof : lines)
          if (discretization.owned_dofs().is_element(dof))
            owned_lines.push_back(dof);
        lines.clear();
        for (const auto &rank_lines :
             Utilities::MPI::all_gather(discretization.get_communicator(), owned_lines))
          lines.insert(lines.end(), rank_lines.begin(), rank_lines.end());
        stored = complete_index_set(dof_handler.n_dofs());
      }
    constraint_set.reinit(stored);
    for (const types::global_dof_index dof : lines)
      constraint_set.add_line(dof);
    constraint_set.close();

    // Every named pinned group must pin something somewhere.
    if ((!parameters.constraints.pinned_groups.empty() ||
         !parameters.constraints.clamped_groups.empty()) &&
        Utilities::MPI::sum(static_cast<unsigned int>(pinned.size()),
                            discretization.get_communicator()) == 0)
      throw InputError(parameter_file,
                       "Constraints/Pinned groups",
                       "the named pinned and clamped groups contain no mesh vertex");

    parse_vector_function(pinned_displacement,
                          parameters.constraints.pinned_displacement,
                          /*time_dependent=*/true,
                          parameter_file,
                          "Constraints/Pinned displacement");
    parse_vector_function(initial_displacement,
                          parameters.time.initial_displacement,
                          /*time_dependent=*/false,
                          parameter_file,
                          "Time/Initial displacement");
    parse_vector_function(initial_velocity,
                          parameters.time.initial_velocity,
                          /*time_dependent=*/false,
                          parameter_file,
                          "Time/Initial velocity");

    // Each expression at t = 0 where it applies: the pinned displacement in the pinned
    // components, the initial state at every vertex.
    const MPI_Comm communicator = discretization.get_communicator();
    std::vector<std::pair<unsigned int, Point<3>>> samples;
    for (const PinnedDof &pin : pinned)
      samples.emplace_back(pin.component, pin.reference);
    pinned_displacement.set_time(0.);
    check_finite(pinned_displacement,
                 samples,
                 communicator,
                 parameter_file,
                 "Constraints/Pinned displacement");
    samples.clear();
    std::set<types::global_dof_index> seen;
    for (const auto &element : discretization.elements())
      for (unsigned int vertex = 0; vertex < 3; ++vertex)
        if (seen.insert(element.dofs[3 * vertex]).second)
          for (unsigned int c = 0; c < 3; ++c)
            samples.emplace_back(c, element.reference[vertex]);
    check_finite(initial_displacement,
                 samples,
                 communicator,
                 parameter_file,
                 "Time/Initial displacement");
    check_finite(
      initial_velocity, samples, communicator, parameter_file, "Time/Initial velocity");

    std::vector<bool> holds_rotation;
    for (const GroupPin &pin : group_pins)
      holds_rotation.push_back(pin.rotation);
    resolve_prescribed_rotations(parameters, parameter_file, holds_rotation);
  }


  void
  BoundaryConditions::resolve_prescribed_rotations(
    const Parameters        &parameters,
    const std::string       &parameter_file,
    const std::vector<bool> &holds_rotation)
  {
    const std::string entry     = "Constraints/Prescribed rotations";
    const auto       &requested = parameters.constraints.prescribed_rotations;
    if (!requested.empty() && !discretization.has_directors())
      throw InputError(parameter_file,
                       entry,
                       "a rotation turns the shell's directors, which only exist with "
                       "bending; set Material/Bending");
    std::map<types::global_dof_index, const mesh::Discretization::Edge *> edge_of;
    for (const mesh::Discretization::Edge &edge : discretization.edges())
      edge_of[edge.angle_dof] = &edge;
    for (unsigned int r = 0; r < requested.size(); ++r)
      {
        unsigned int g = 0;
        while (g < support_list.size() &&
               !(support_list[g].name == requested[r].name && holds_rotation[g]))
          ++g;
        if (g == support_list.size())
          throw InputError(parameter_file,
                           entry,
                           "'" + requested[r].name +
                             "' is no group whose rotation is held: add it to 'Clamped "
                             "groups', or give it 'r' in 'Pinned groups'");
        rotations.push_back(std::make_unique<FunctionParser<3>>(3));
        parse_vector_function(
          *rotations.back(), requested[r].expressions, true, parameter_file, entry);
        for (const types::global_dof_index dof : support_list[g].held_angles)
          if (discretization.owned_dofs().is_element(dof))
            {
              const mesh::Discretization::Edge &edge = *edge_of.at(dof);
              const Tensor<1, 3> e = edge.reference_points[1] - edge.reference_points[0];
              prescribed_angles.push_back(
                {dof,
                 e / e.norm(),
                 Point<3>(0.5 * (edge.reference_points[0] + edge.reference_points[1])),
                 r});
            }
      }

    // The rotation at a few times: finite, and about the edges (a component across an
    // edge would twist it). The largest offence over the ranks.
    const double end =
      is_static(parameters.time.integrator) ? 1. : parameters.time.end_time;
    double across = 0.;
    for (const double t : {0., 0.5 * end, end})
      {
        for (const auto &rotation : rotations)
          rotation->set_time(t);
        for (const PrescribedAngle &angle : prescribed_angles)
          {
            const Tensor<1, 3> theta = rotation_vector(angle);
            const double       off =
              (theta - (theta * angle.direction) * angle.direction).norm();
            across =
              std::max(across,
                       std::isfinite(theta.norm()) ? off / std::max(theta.norm(), 1.)
                                                   : HUGE_VAL);
          }
      }
    across = Utilities::MPI::max(across, discretization.get_communicator());
    if (across > 1e-9)
      throw InputError(parameter_file,
                       entry,
                       std::isfinite(across)
                         ? "a rotation has a component across its group's edges (up to " +
                             std::to_string(across) +
                             " rad), a twist a held edge cannot take: give it along the "
                             "edges"
                         : "a rotation is not finite at an edge of its group");
  }


  unsigned int
  BoundaryConditions::n_pinned_dofs() const
  {
    unsigned int n_owned = 0;
    for (const PinnedDof &pin : pinned)
      if (discretization.owned_dofs().is_element(pin.dof))
        ++n_owned;
    return Utilities::MPI::sum(n_owned, discretization.get_communicator());
  }


  void
  BoundaryConditions::initial_state(VectorType &u, VectorType &v) const
  {
    u                     = 0.;
    v                     = 0.;
    const IndexSet &owned = discretization.owned_dofs();
    for (const auto &element : discretization.elements())
      for (unsigned int vertex = 0; vertex < 3; ++vertex)
        for (unsigned int c = 0; c < 3; ++c)
          {
            const types::global_dof_index dof = element.dofs[3 * vertex + c];
            if (!owned.is_element(dof))
              continue;
            u[dof] = initial_displacement.value(element.reference[vertex], c);
            v[dof] = initial_velocity.value(element.reference[vertex], c);
          }
    u.compress(VectorOperation::insert);
    v.compress(VectorOperation::insert);
    apply_pinned_displacement(0., u);
  }


  Tensor<1, 3>
  BoundaryConditions::rotation_vector(const PrescribedAngle &angle) const
  {
    Tensor<1, 3> theta;
    for (unsigned int c = 0; c < 3; ++c)
      theta[c] = rotations[angle.rotation]->value(angle.midpoint, c);
    return theta;
  }


  void
  BoundaryConditions::apply_pinned_displacement(const double time, VectorType &u) const
  {
    pinned_displacement.set_time(time);
    for (const PinnedDof &pin : pinned)
      if (discretization.owned_dofs().is_element(pin.dof))
        u[pin.dof] = pinned_displacement.value(pin.reference, pin.component);
    for (const auto &rotation : rotations)
      rotation->set_time(time);
    for (const PrescribedAngle &angle : prescribed_angles)
      {
        u[angle.dof] = rotation_vector(angle) * angle.direction;
      }
    u.compress(VectorOperation::insert);
  }


  void
  parse_vector_function(FunctionParser<3> &function,
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
        for (unsigned int c = 0; c < function.n_components; ++c)
          function.value(Point<3>(), c);
        std::cerr.rdbuf(cerr_buffer);
      }
    catch (const std::exception &)
      {
        std::cerr.rdbuf(cerr_buffer);
        throw InputError(parameter_file,
                         entry,
                         "cannot parse '" + expressions + "' as " +
                           (function.n_components == 1 ? "an expression"
                                                       : "three expressions") +
                           " in x, y, z" + (time_dependent ? ", t" : ""));
      }
  }
} // namespace clothsim
