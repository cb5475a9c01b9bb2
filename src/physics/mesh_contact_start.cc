// MeshContact's part of a step's start (physics/mesh_contact.h): the cloth carried along
// with a moving mesh obstacle where the obstacle would hit it, and the vertices of the
// pairs of an analytic obstacle's core features that a guess brings too close.

#include <deal.II/base/mpi.h>

#include "physics/mesh_contact.h"

#include <cmath>

namespace clothsim::physics
{
  std::vector<double>
  MeshContact::carried_along(const std::vector<double> &state,
                             const RigidPose           &from,
                             const RigidPose           &to) const
  {
    std::vector<double> result(state);
    for (unsigned int p = 0; p < cloth.vertices.size(); ++p)
      {
        const Point<3> x = to.to_world(from.to_body(cloth.position(p, state.data())));
        for (unsigned int c = 0; c < 3; ++c)
          result[cloth.vertices[p].local[c]] = x[c] - cloth.vertices[p].reference[c];
      }
    return result;
  }


  void
  MeshContact::carry(const std::vector<RigidPose> &start_poses,
                     const std::vector<RigidPose> &poses,
                     const double                  fraction,
                     std::vector<double>          &state) const
  {
    for (const unsigned int o : mesh_obstacles)
      {
        if (obstacles[o].shape().core != ObstacleCore::mesh)
          continue;
        // An obstacle that has left carries nothing.
        const RigidPose &from = start_poses[o], &to = poses[o];
        if (!to.present ||
            (from.rotation == to.rotation && from.translation == to.translation))
          continue;
        // The cloth carried along, then back to where it is: in the obstacle's frame
        // the straight path of the cloth left in place.
        const std::vector<double> carried = carried_along(state, from, to);
        std::vector<double>       back(state.size());
        for (unsigned int i = 0; i < state.size(); ++i)
          back[i] = state[i] - carried[i];
        const double alpha = Utilities::MPI::min(
          largest_step(carried.data(), back.data(), poses, fraction, o), communicator);
        for (unsigned int i = 0; i < state.size(); ++i)
          state[i] = carried[i] + alpha * back[i];
      }
  }


  std::vector<types::global_dof_index>
  MeshContact::pierced(const double                 *guess,
                       const std::vector<double>    &start,
                       const std::vector<RigidPose> &start_poses,
                       const std::vector<RigidPose> &poses,
                       const double                  fraction,
                       const unsigned int            o) const
  {
    // The start carried along keeps every distance to the obstacle.
    const std::vector<double> carried = carried_along(start, start_poses[o], poses[o]);
    const double              r       = offset(o);
    std::vector<types::global_dof_index> result;
    for_each_pair(
      guess,
      nullptr,
      poses,
      settings.thickness,
      [&](const Pair &pair) {
        const double d =
          std::sqrt(
            pair_squared_distance(pair.kind, pair_points(pair, guess, poses[o]))) -
          r;
        const double d0 =
          std::sqrt(pair_squared_distance(pair.kind,
                                          pair_points(pair, carried.data(), poses[o]))) -
          r;
        if (d0 <= 0. || d > fraction * d0)
          return;
        for (unsigned int i = 0; i < 4; ++i)
          if (pair.moving[i])
            result.push_back(cloth.vertices[pair.index[i]].dofs[0]);
      },
      o);
    return result;
  }
} // namespace clothsim::physics
