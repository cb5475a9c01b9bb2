#pragma once

// The boundary conditions and initial state of a scene: pinned groups (points, lines or
// surfaces of the mesh; any of x, y, z) with their prescribed displacement (an expression
// of x, y, z, t; on line groups also 'r', the director angle about the edge), clamped
// boundary lines (every component pinned and the edge's director angle held), prescribed
// rotations of the groups whose director angles are held (a rotation vector θ(x, t): each
// edge's angle is θ · t_e, t_e its unit direction; clamped edges keep their rest
// directors as references, so the angle is the whole rotation), and the
// initial displacement and velocity (expressions of x, y, z). Each group is also a
// support whose reaction the output reports (supports()).
// Pinned and clamped dofs, and the unused angle dofs of the discretization, become
// homogeneous constraints: Newton's updates there are zero, and the prescribed values
// are set before each step.

#include <deal.II/base/function_parser.h>
#include <deal.II/lac/affine_constraints.h>

#include "io/parameters.h"
#include "mesh/discretization.h"
#include "mesh/gmsh_reader.h"

#include <array>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace clothsim
{
  class BoundaryConditions
  {
  public:
    // Resolves the groups of `parameters` on the mesh and parses the expressions. Throws
    // InputError (naming `parameter_file`) for unknown or empty groups and bad
    // expressions.
    BoundaryConditions(const mesh::Discretization &discretization,
                       const Parameters           &parameters,
                       const std::string          &parameter_file,
                       const mesh::MeshGroups     &groups);

    const AffineConstraints<double> &
    constraints() const
    {
      return constraint_set;
    }
    // Angle dofs whose rotation is held (locally relevant): the edges of clamped groups
    // and of pinned line groups with component 'r'.
    const std::set<types::global_dof_index> &
    clamped_angles() const
    {
      return clamped_angle_dofs;
    }
    // Pinned displacement dofs over all ranks.
    unsigned int
    n_pinned_dofs() const;
    // Whether `dof` (locally relevant) is a pinned displacement dof.
    bool
    is_pinned(const types::global_dof_index dof) const
    {
      return pinned_dofs.count(dof) > 0;
    }

    // The state at t = 0 (owned vectors): the initial displacement and velocity at every
    // vertex (angles zero), pinned dofs at their prescribed position.
    void
    initial_state(VectorType &u, VectorType &v) const;

    // Sets the pinned entries of `u` (owned) to the prescribed displacement at time t,
    // and the angles of edges with a prescribed rotation to it.
    void
    apply_pinned_displacement(const double time, VectorType &u) const;

    // A pinned or clamped group as a support, for its reaction (locally relevant dofs):
    // the displacement dofs it pins, its vertices, and the angle dofs of
    // the edges whose rotation it holds. In the order of 'Pinned groups', then 'Clamped
    // groups'; a vertex in two groups belongs to both.
    struct Support
    {
      std::string                       name;
      std::set<types::global_dof_index> pinned;
      // Its vertices by x dof: their (x, y, z) dofs and reference positions.
      std::map<types::global_dof_index,
               std::pair<std::array<types::global_dof_index, 3>, Point<3>>>
                                        vertices;
      std::set<types::global_dof_index> held_angles;
    };
    const std::vector<Support> &
    supports() const
    {
      return support_list;
    }

  private:
    // A pinned dof (locally relevant): dof, component, reference position of its vertex.
    struct PinnedDof
    {
      types::global_dof_index dof;
      unsigned int            component;
      Point<3>                reference;
    };

    // A held angle with a prescribed rotation (owned): its dof, its edge's unit direction
    // t_e (as the angle turns about it) and reference midpoint, the rotation's index.
    struct PrescribedAngle
    {
      types::global_dof_index dof;
      Tensor<1, 3>            direction;
      Point<3>                midpoint;
      unsigned int            rotation;
    };

    // Resolves 'Prescribed rotations' on the supports (`holds_rotation`: per support,
    // whether its rotation is held) and checks them at a few times (`times`).
    void
    resolve_prescribed_rotations(const Parameters        &parameters,
                                 const std::string       &parameter_file,
                                 const std::vector<bool> &holds_rotation);

    // θ at the angle's edge midpoint, at the time its function was last set to.
    Tensor<1, 3>
    rotation_vector(const PrescribedAngle &angle) const;

    const mesh::Discretization  &discretization;
    AffineConstraints<double>    constraint_set;
    std::vector<PrescribedAngle> prescribed_angles;
    // θ(x, y, z, t) per 'Prescribed rotations' entry (evaluated at set times: pointers).
    std::vector<std::unique_ptr<FunctionParser<3>>> rotations;
    std::vector<PinnedDof>                          pinned;
    std::set<types::global_dof_index>               pinned_dofs;
    std::set<types::global_dof_index>               clamped_angle_dofs;
    std::vector<Support>                            support_list;
    mutable FunctionParser<3>                       pinned_displacement;
    FunctionParser<3>                               initial_displacement;
    FunctionParser<3>                               initial_velocity;
  };

  // Parses 'fx; fy; fz' (or one expression, as `function` has components; in x, y, z
  // and, if `time_dependent`, t) into `function` and
  // evaluates it once; InputError naming `parameter_file` and `entry` if it fails.
  void
  parse_vector_function(FunctionParser<3> &function,
                        const std::string &expressions,
                        const bool         time_dependent,
                        const std::string &parameter_file,
                        const std::string &entry);

  // The distance below which a vertex matches a point of a group: 1e-8 times the
  // diagonal of the mesh's bounding box (all ranks' cells; the same on every rank), far
  // below any edge. O(cells): GridTools::diameter compares pairs of boundary vertices,
  // 1.6 s at 103,041 vertices. Collective.
  double
  point_matching_tolerance(const Triangulation<2, 3> &triangulation,
                           const MPI_Comm             communicator);

  // An expression that is inf or NaN at t = 0 would only surface as a failed first
  // step: evaluates `function` (at its time as set) at each (component, point) of
  // `samples` and throws an InputError naming `entry`, the component and a point where
  // it is not finite (the first by component, then position: the same for any number
  // of ranks); `point_name` says what the points are ("vertex"). Collective.
  void
  check_finite(const FunctionParser<3>                              &function,
               const std::vector<std::pair<unsigned int, Point<3>>> &samples,
               const MPI_Comm                                        communicator,
               const std::string                                    &parameter_file,
               const std::string                                    &entry,
               const std::string &point_name = "vertex");
} // namespace clothsim
