// The work the obstacles' prescribed motion does on the cloth over a step, for the
// energy balance (statistics.csv's prescribed_work). The barrier's energy B(x; t)
// depends on the obstacles' poses; over a step its change splits into the part the
// cloth's motion makes, which the energy report sees, and the part the obstacles'
// motion makes, ∫ ∂B/∂t dt: the trapezoidal rule over Σ_i f_i·δ(x_i) at the step's two
// ends, f_i the barrier's force on the cloth at x_i, δ the obstacle's rigid displacement
// over the step there (a rigid motion's displacement differs between x_i and the
// obstacle's nearest point by a turn about the gap, perpendicular to f_i). An obstacle
// removed in the step takes its barrier energy with it. The barrier's stiffness is the
// last accepted step's, κ_old: a raise within the step counts at its end
// (AdaptiveBarrierTerm::raise_energy).

#include <deal.II/base/mpi.h>

#include "mesh/ghosted_values.h"
#include "physics/contact_potential.h"
#include "physics/contact_term.h"

#include <algorithm>
#include <functional>

namespace clothsim::physics
{
  double
  ObstacleContact::motion_work(const VectorType &u_n,
                               const VectorType &u_new,
                               const double      t_n,
                               const double      t_new) const
  {
    const std::vector<RigidPose> start = poses_at(t_n), end = poses_at(t_new);
    const unsigned int           n_obstacles = obstacles.size();
    const double d_hat = settings.thickness, scale = stiffness.committed_scale();
    const auto   n_local      = discretization.relevant_dofs().n_elements();
    const auto   displacement = [&](const unsigned int o, const Point<3> &x) {
      return Tensor<1, 3>(end[o].to_world(start[o].to_body(x)) - x);
    };
    // The vertices' barrier energies, or their forces' work, against the analytic
    // obstacles `wanted` at `poses`.
    std::vector<double> work(n_obstacles, 0.), leaving(n_obstacles, 0.);
    const auto          vertex_sums = [&](const double                            *local,
                                 const std::vector<RigidPose>            &poses,
                                 const std::function<bool(unsigned int)> &wanted,
                                 const bool                               energy,
                                 std::vector<double>                     &sums) {
      for (const Vertex &vertex : table)
        {
          const Point<3> x = position(vertex, local);
          for (unsigned int o = 0; o < n_obstacles; ++o)
            {
              if (is_mesh(o) || !wanted(o))
                continue;
              const SignedDistance d = obstacles[o].distance(poses[o], x, !energy);
              if (d.value >= d_hat || d.value <= 0.)
                continue;
              const double kappa = scale * vertex.kappa;
              sums[o] += energy ? kappa * contact::barrier(d.value, d_hat)
                                         : -kappa * contact::barrier_first(d.value, d_hat) *
                                    (d.gradient * displacement(o, x));
            }
        }
    };

    const auto moving = [&](const unsigned int o) {
      return start[o].present && end[o].present &&
             (start[o].translation != end[o].translation ||
              start[o].rotation != end[o].rotation);
    };
    const auto removed = [&](const unsigned int o) {
      return start[o].present && !end[o].present;
    };
    bool any_moving = false, any_removed = false;
    for (unsigned int o = 0; o < n_obstacles; ++o)
      {
        any_moving  = any_moving || moving(o);
        any_removed = any_removed || removed(o);
      }
    if (!any_moving && !any_removed) // the same on every rank
      return 0.;
    // The trapezoidal rule over the step's two ends, each state with its poses.
    const double *start_local = ghosted_values(u_n, n_local);
    const double *end_local   = ghosted_values(u_new, n_local);
    // The mesh pairs' barrier has the current κ: linear in it, their sums are rescaled.
    const double        to_committed = scale / stiffness.scale();
    std::vector<double> unused(n_obstacles, 0.), pair_sums(n_obstacles, 0.);
    for (const auto &[local, poses] :
         {std::make_pair(start_local, &start), std::make_pair(end_local, &end)})
      {
        vertex_sums(local, *poses, moving, false, work);
        if (!mesh_pairs.empty())
          mesh_pairs.pair_work(local, *poses, displacement, pair_sums, unused);
      }
    double total = 0.;
    for (unsigned int o = 0; o < n_obstacles; ++o)
      if (moving(o))
        total += 0.5 * (work[o] + to_committed * pair_sums[o]);

    if (any_removed)
      {
        vertex_sums(start_local, start, removed, true, leaving);
        if (!mesh_pairs.empty())
          {
            const auto none = [](const unsigned int, const Point<3> &) {
              return Tensor<1, 3>();
            };
            std::fill(pair_sums.begin(), pair_sums.end(), 0.);
            mesh_pairs.pair_work(start_local, start, none, unused, pair_sums);
          }
        for (unsigned int o = 0; o < n_obstacles; ++o)
          if (removed(o))
            total -= leaving[o] + to_committed * pair_sums[o];
      }
    return Utilities::MPI::sum(total, discretization.get_communicator());
  }
} // namespace clothsim::physics
