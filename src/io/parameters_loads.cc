// Sections "Loads" and "Constraints": external forces, pinned and clamped groups.

#include "io/parameters.h"

#include <deal.II/base/parameter_handler.h>

#include <deal.II/base/utilities.h>

#include "io/input_error.h"
#include "io/parameters_detail.h"

#include <algorithm>

namespace clothsim
{
  using detail::vector_entry;


  namespace
  {
    // 'name: fx, fy, fz; name2: ...' (already matched by the entry's Patterns::Map).
    std::vector<GroupLoad>
    group_loads(const std::string &text)
    {
      std::vector<GroupLoad> loads;
      for (const std::string &item : Utilities::split_string_list(text, ';'))
        {
          const auto name_value = Utilities::split_string_list(item, ':');
          loads.push_back({name_value[0], vector_entry(name_value[1])});
        }
      return loads;
    }
  } // namespace


  void
  LoadParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Loads");
    prm.declare_entry("Gravity",
                      "0, 0, -9.81",
                      Patterns::List(Patterns::Double(-1e6, 1e6), 3, 3, ","),
                      "Gravitational acceleration g (x, y, z) in m/s².");
    const auto group_vectors =
      Patterns::Map(Patterns::Anything(),
                    Patterns::List(Patterns::Double(), 3, 3, ","),
                    0,
                    1000,
                    ";",
                    ":");
    prm.declare_entry(
      "Point forces",
      "",
      group_vectors,
      "Forces in N on every vertex of gmsh point groups: 'name: fx, fy, fz; "
      "name2: ...'. Dead loads; scaled by the load factor in static mode.");
    prm.declare_entry(
      "Line forces",
      "",
      group_vectors,
      "Forces in N per m of reference length along gmsh boundary line groups: "
      "'name: qx, qy, qz; ...', lumped onto the edges' vertices. Dead loads; "
      "scaled by the load factor in static mode.");
    prm.declare_entry(
      "Line moments",
      "",
      group_vectors,
      "Bending moments in N·m per m of reference length along gmsh boundary line "
      "groups: 'name: mx, my, mz; ...', a vector along the group's edges (a moment "
      "about the edge, e.g. 'tip: 0, M, 0' on an edge along y; a component across "
      "an edge, a twisting moment, is an input error). Each edge's share m ℓ acts "
      "on its director angle: it turns the shell about the edge, following the "
      "edge. Needs 'Material/Bending'. Scaled by the load factor in static mode. "
      "Their work m ψ, ψ the edges' rotation accumulated over the steps, is in "
      "statistics.csv's external_work.");
    prm.declare_entry(
      "Point moments",
      "",
      group_vectors,
      "Moments in N·m at every vertex of gmsh point groups: 'name: mx, my, mz; ...'. "
      "Each is a couple of dead forces on the vertex's triangles: F_j = ω × (X_j - "
      "X_p) on every other vertex j of a triangle at p and -Σ F_j on p, with ω such "
      "that Σ (X_j - X_p) × F_j = M: the moment M exactly in the reference "
      "configuration, no net force. Dead forces keep their direction, so the couple's "
      "moment turns with its triangles to first order only: for moments through large "
      "rotations use 'Line moments' (which follow the edges) or 'Constraints/"
      "Prescribed rotations'. A pinned neighbour absorbs its force. Scaled by the load "
      "factor in static mode.");
    prm.declare_entry(
      "Surface forces",
      "0; 0; 0",
      Patterns::List(Patterns::Anything(), 3, 3, ";"),
      "Forces in N per m² of reference area on the whole surface: 'fx; fy; fz', "
      "expressions in the reference coordinates x, y, z (m), e.g. a sinusoidal "
      "load '0; 0; -100*sin(pi*x)'. Dead loads, scaled by the load factor in static "
      "mode; each triangle carries the consistent load of f interpolated linearly "
      "between its vertices, ∫ f N_i dA = A (2 f_i + f_j + f_k) / 12.");
    prm.declare_entry(
      "Pressure",
      "0",
      Patterns::Double(),
      "Pressure in Pa on the whole surface, along the current normal (x1 - x0) x "
      "(x2 - x0) of each triangle (a follower load). Exact where the surface is "
      "closed or its boundary is held; on free edges it acts through the potential "
      "-p V (V: volume of the cones from the reference centroid to the triangles), "
      "see physics/pressure.h. Scaled by the load factor in static mode.");
    prm.leave_subsection();
  }

  void
  LoadParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Loads");
    const auto values =
      Utilities::string_to_double(Utilities::split_string_list(prm.get("Gravity"), ','));
    for (unsigned int d = 0; d < 3; ++d)
      gravity[d] = values[d];
    point_forces   = group_loads(prm.get("Point forces"));
    line_forces    = group_loads(prm.get("Line forces"));
    line_moments   = group_loads(prm.get("Line moments"));
    point_moments  = group_loads(prm.get("Point moments"));
    surface_forces = prm.get("Surface forces");
    pressure       = prm.get_double("Pressure");
    prm.leave_subsection();
  }


  void
  ConstraintParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Constraints");
    prm.declare_entry(
      "Pinned groups",
      "",
      Patterns::List(Patterns::Anything(), 0, 100, ";"),
      "gmsh physical groups (points, boundary lines or surfaces) whose vertices "
      "follow 'Pinned displacement', separated by ';'. Each is 'name' (x, y and z) "
      "or 'name: components' with components from x, y, z and r, e.g. 'pinned' or "
      "'left: x; corner: xy; cloth: z'. 'r' (boundary line groups, with "
      "'Material/Bending') holds the shell's rotation about the group's edges: the "
      "director along them turns only with the edge. A symmetry plane x = c is "
      "'name: xr' (no displacement across it, no rotation about it; the other "
      "components free); 'name: xyzr' is a clamped edge.");
    prm.declare_entry(
      "Pinned displacement",
      "0; 0; 0",
      Patterns::List(Patterns::Anything(), 3, 3, ";"),
      "Displacement of pinned vertices in m: three expressions 'ux; uy; uz' in "
      "the reference coordinates x, y, z (m) and time t (s), e.g. "
      "'0; 0; 0.1*sin(2*pi*t)'. In static mode t is the load factor 0..1.");
    prm.declare_entry(
      "Clamped groups",
      "",
      Patterns::List(Patterns::Anything(), 0, 100, ";"),
      "gmsh boundary line groups that are clamped, separated by ';': their "
      "vertices are fixed and the shell's director along them keeps its rest "
      "direction (rotation about the edge held). Needs 'Material/Bending'. A line "
      "group in 'Pinned groups' instead is simply supported (rotation free).");
    prm.declare_entry(
      "Prescribed rotations",
      "",
      Patterns::Anything(),
      "Rotations of groups whose rotation about their edges is held (clamped groups, "
      "and pinned groups with 'r'), in rad instead of zero: 'name: θx, θy, θz; name2: "
      "...', a rotation vector of expressions in the reference coordinates x, y, z "
      "(m) and the time t (s; in static mode the load factor 0..1), e.g. 'tip: 0, "
      "pi*t, 0' on an edge along y. Each edge turns its director by θ · t_e about "
      "its unit direction t_e (right-handed), following the edge as it moves; a "
      "component across an edge (a twist the edge cannot take) is an input error. "
      "Expressions contain no ',' or ';' (a ramp: 't < 0.5 ? 2*t : 1'). Needs "
      "'Material/Bending'.");
    prm.leave_subsection();
  }

  void
  ConstraintParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Constraints");
    pinned_groups.clear();
    for (const std::string &item :
         Utilities::split_string_list(prm.get("Pinned groups"), ';'))
      {
        const auto  parts = Utilities::split_string_list(item, ':');
        PinnedGroup group{parts[0], {{true, true, true}}};
        if (parts.size() > 2 || parts[0].empty() ||
            (parts.size() == 2 &&
             parts[1].find_first_not_of("xyzr") != std::string::npos) ||
            (parts.size() == 2 && parts[1].empty()))
          throw InputError("",
                           "Constraints/Pinned groups",
                           "'" + item +
                             "' is not 'name' or 'name: components' (components "
                             "from x, y, z, r)");
        if (parts.size() == 2)
          {
            for (unsigned int d = 0; d < 3; ++d)
              group.components[d] = parts[1].find("xyz"[d]) != std::string::npos;
            group.rotation = parts[1].find('r') != std::string::npos;
          }
        pinned_groups.push_back(group);
      }
    pinned_displacement = prm.get("Pinned displacement");
    clamped_groups      = Utilities::split_string_list(prm.get("Clamped groups"), ';');
    prescribed_rotations.clear();
    for (const std::string &item :
         Utilities::split_string_list(prm.get("Prescribed rotations"), ';'))
      {
        // 'name: θx, θy, θz', split at the first ':' (a ternary has more).
        const std::size_t colon = item.find(':');
        const auto        components =
          colon == std::string::npos
                   ? std::vector<std::string>()
                   : Utilities::split_string_list(item.substr(colon + 1), ',');
        if (colon == std::string::npos || colon == 0 || components.size() != 3 ||
            std::any_of(components.begin(), components.end(), [](const std::string &c) {
              return c.empty();
            }))
          throw InputError("",
                           "Constraints/Prescribed rotations",
                           "'" + item +
                             "' is not 'name: θx, θy, θz' (three expressions in x, y, "
                             "z, t)");
        prescribed_rotations.push_back(
          {Utilities::trim(item.substr(0, colon)),
           components[0] + "; " + components[1] + "; " + components[2]});
      }
    prm.leave_subsection();
  }
} // namespace clothsim
