// ObstacleContact's step start for the pairs (physics/contact_term.h): the mesh
// obstacles' (their motion carries the cloth along) and the analytic obstacles' core
// features' (edge contact: vertices of pierced pairs ride along).

#include <deal.II/base/mpi.h>

#include "mesh/ghosted_values.h"
#include "physics/contact_term.h"

#include <algorithm>

namespace clothsim::physics
{
  std::string
  ObstacleContact::begin_mesh_step(const VectorType                &u_n,
                                   VectorType                      &u_new,
                                   const AffineConstraints<double> &constraints)
  {
    const unsigned int n = discretization.relevant_dofs().n_elements();
    discretization.import_ghosts(u_n, step_start);
    VectorType guess;
    discretization.initialize_ghosted(guess);
    discretization.import_ghosts(u_new, guess);
    const double             *start  = ghosted_values(step_start, n);
    const double             *target = ghosted_values(guess, n);
    const std::vector<double> at_start(start, start + n);
    mesh_pairs.lag_friction(nullptr, at_start, start_poses, end_poses, lagged);
    if (std::none_of(obstacles.begin(), obstacles.end(), [](const Obstacle &obstacle) {
          return obstacle.shape().core == ObstacleCore::mesh;
        }))
      return "";

    std::vector<double> from(at_start), direction(n);
    mesh_pairs.carry(start_poses, end_poses, settings.ccd_fraction, from);
    const auto &map = step_start.trilinos_partitioner();
    for (unsigned int i = 0; i < n; ++i)
      {
        if (constraints.is_constrained(map.GID(i)))
          from[i] = target[i];
        direction[i] = target[i] - from[i];
      }
    const std::string failure =
      mesh_pairs.touching(from.data(), end_poses, /*meshes_only=*/true);
    const MPI_Comm communicator = discretization.get_communicator();
    if (Utilities::MPI::max(failure.empty() ? 0 : 1, communicator) > 0)
      return failure.empty() ? failure : "no start for the step keeps " + failure;
    double alpha = 1.;
    for (unsigned int o = 0; o < obstacles.size(); ++o)
      if (is_mesh(o))
        alpha =
          std::min(alpha,
                   mesh_pairs.largest_step(
                     from.data(), direction.data(), end_poses, settings.ccd_fraction, o));
    alpha = Utilities::MPI::min(alpha, communicator);
    for (const types::global_dof_index i : discretization.owned_dofs())
      if (!constraints.is_constrained(i))
        {
          const int k = map.LID(static_cast<TrilinosWrappers::types::int_type>(i));
          u_new[i]    = from[k] + alpha * direction[k];
        }
    u_new.compress(VectorOperation::insert);
    return "";
  }


  std::string
  ObstacleContact::ride_along(const double                     t_new,
                              const VectorType                &u_n,
                              VectorType                      &u_new,
                              const AffineConstraints<double> &constraints)
  {
    const unsigned int n = discretization.relevant_dofs().n_elements();
    VectorType         start, guess, marks;
    discretization.initialize_ghosted(start);
    discretization.initialize_ghosted(guess);
    discretization.initialize_owned(marks);
    discretization.import_ghosts(u_n, start);
    const double             *start_values = ghosted_values(start, n);
    const std::vector<double> at_start(start_values, start_values + n);
    const MPI_Comm            communicator = discretization.get_communicator();
    // Halvings of each vertex's way from its step-start position carried along with
    // obstacle o (feasible: it keeps its distance) to its guess.
    std::vector<unsigned int> halvings(table.size() * obstacles.size(), 0);
    constexpr unsigned int    carried_along = 30; // then it rides along exactly
    for (;;)
      {
        guess                = u_new;
        const double *values = ghosted_values(guess, n);
        unsigned int  moved = 0, left = 0;
        for (unsigned int o = 0; o < obstacles.size() && moved == 0; ++o)
          {
            if (is_mesh(o) || obstacles[o].shape().surface == nullptr)
              continue;
            marks                                           = 0.;
            const std::vector<types::global_dof_index> dofs = mesh_pairs.pierced(
              values, at_start, start_poses, end_poses, settings.ccd_fraction, o);
            for (const types::global_dof_index dof : dofs)
              marks[dof] += 1.;
            marks.compress(VectorOperation::add);
            for (unsigned int k = 0; k < table.size(); ++k)
              {
                const Vertex &vertex = table[k];
                unsigned int &halved = halvings[k * obstacles.size() + o];
                if (marks[vertex.dofs[0]] == 0.)
                  continue;
                if (halved == carried_along || constraints.is_constrained(vertex.dofs[0]))
                  {
                    ++left;
                    continue;
                  }
                ++halved;
                ++moved;
                const Point<3> &carried = carried_points[k * obstacles.size() + o];
                for (unsigned int c = 0; c < 3; ++c)
                  {
                    const double at = vertex.reference[c] + u_new[vertex.dofs[c]];
                    const double to =
                      halved == carried_along ? carried[c] : 0.5 * (carried[c] + at);
                    u_new[vertex.dofs[c]] = to - vertex.reference[c];
                  }
              }
            u_new.compress(VectorOperation::insert);
            moved = Utilities::MPI::sum(moved, communicator);
            left  = Utilities::MPI::sum(left, communicator);
          }
        if (moved == 0)
          return left == 0 ? ""
                           : "no start for the step to t = " + std::to_string(t_new) +
                               " s keeps the cloth's triangles off the obstacles (" +
                               std::to_string(left) +
                               " vertices ride along with an obstacle already, or are "
                               "pinned)";
      }
  }
} // namespace clothsim::physics
