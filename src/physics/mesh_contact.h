#pragma once

// Contact of the cloth with triangle-mesh obstacles, by pairs of primitives (IPC, Li et
// al. 2020): every cloth vertex against the obstacle's triangles, every cloth edge
// against its edges, and every obstacle vertex against the cloth's triangles pays the
// pair barrier κ m(x) s(d) (physics/pair_barrier.h) while closer than d̂, with
// κ = m a_b / d̂ and m the mean lumped mass of the pair's cloth vertices. So a sharp
// obstacle edge or corner cannot pass between the cloth's vertices. Candidate pairs come
// from the obstacle's bounding-volume hierarchies, queried in its body frame (built
// once: the obstacles are rigid); the barrier's evaluations reuse a list of the pairs
// closer than 2 d̂ (for_each_near_pair). The line search is capped by continuous collision
// detection of every pair whose swept boxes meet (pair_step_bound). A part of
// ObstacleContact (physics/contact_term.h), which holds the obstacles and calls it.

#include "mesh/discretization.h"
#include "mesh/element_matrix_scatter.h"
#include "physics/cloth_surface.h"
#include "physics/obstacle.h"
#include "physics/pair_barrier.h"
#include "physics/pair_distance.h"
#include "physics/term.h"

#include <functional>
#include <string>
#include <vector>

namespace clothsim::physics
{
  struct ContactSettings;
  struct LaggedContact;

  class MeshContact
  {
  public:
    // `obstacles`: all of the scene's (the mesh ones are used); `lumped_masses`: owned.
    MeshContact(const std::vector<Obstacle> &obstacles,
                const ContactSettings       &settings,
                const mesh::Discretization  &discretization,
                const VectorType            &lumped_masses);

    bool
    empty() const
    {
      return mesh_obstacles.empty();
    }
    // The closest of the pairs the last add_to_step evaluated on this rank (m; +inf if
    // none: every pair within d̂ is among them).
    double
    closest_assembled() const
    {
      return assembled_closest;
    }
    // Every pair's κ times `scale` from now on (physics/barrier_stiffness.h).
    void
    set_stiffness_scale(const double scale)
    {
      kappa_scale = scale;
    }

    // The cloth as a surface: this rank's triangles and their vertices.
    const ClothSurface &
    cloth_surface() const
    {
      return cloth;
    }

    // This rank's barrier at u (`u_local`: a ghosted vector's values), the obstacles at
    // `poses` (all obstacles'), with its gradient and Hessian (projected to positive
    // semi-definite if `projected`) distributed through `constraints` if non-null.
    double
    add_to_step(const double                    *u_local,
                const std::vector<RigidPose>    &poses,
                const bool                       projected,
                const AffineConstraints<double> &constraints,
                VectorType                      *gradient,
                MatrixType                      *hessian) const;

    // The largest α <= 1 such that no pair comes closer than `fraction` of its distance
    // on the path u + s step, s in [0, α] (this rank's pairs; not reduced), with
    // obstacle `only` (all mesh obstacles by default).
    double
    largest_step(const double                 *u_local,
                 const double                 *step_local,
                 const std::vector<RigidPose> &poses,
                 const double                  fraction,
                 const unsigned int only = numbers::invalid_unsigned_int) const;

    // Over this rank's pairs within d̂ and its vertices' distances from the meshes: the
    // smallest distance (lowered, m); over the pairs within d̂, per obstacle the force
    // on the cloth (added, N) and the number of pairs (added).
    void
    report(const double                 *u_local,
           const std::vector<RigidPose> &poses,
           double                       &min_distance,
           std::vector<Tensor<1, 3>>    &forces,
           std::vector<unsigned int>    &contacts) const;

    // Over this rank's pairs within d̂, the obstacles at `poses`: per obstacle, the
    // barrier's force on each of a pair's cloth points times `displacement(o, x)` at the
    // point x (added to `work`, J), and the barrier's energy (added to `energy`, J).
    void
    pair_work(
      const double                                                      *u_local,
      const std::vector<RigidPose>                                      &poses,
      const std::function<Tensor<1, 3>(unsigned int, const Point<3> &)> &displacement,
      std::vector<double>                                               &work,
      std::vector<double>                                               &energy) const;

    // A pair at distance 0, a cloth edge through an obstacle's triangle or an obstacle's
    // edge through a cloth triangle at u, described; empty if none on this rank. Only the
    // mesh obstacles' if `meshes_only`.
    std::string
    touching(const double                 *u_local,
             const std::vector<RigidPose> &poses,
             const bool                    meshes_only = false) const;

    // For the analytic obstacle o's core features (a step's feasible start): the first
    // dof of every cloth vertex of a pair whose distance at `guess` (ghosted values) is
    // at most `fraction` of its distance at the step's start `start` carried along with
    // the obstacle from `start_poses` to `poses` (which keeps it). Such vertices must
    // ride along with the obstacle. This rank's pairs; a vertex may be listed repeatedly.
    std::vector<types::global_dof_index>
    pierced(const double                 *guess,
            const std::vector<double>    &start,
            const std::vector<RigidPose> &start_poses,
            const std::vector<RigidPose> &poses,
            const double                  fraction,
            const unsigned int            o) const;

    // Friction data (appended to `lagged`) of every pair within d̂, the obstacles at
    // `poses`: for each mesh obstacle with friction, at u (`u_local`; if null, at the
    // step's start `start` carried along with the obstacle from `start_poses`, which
    // keeps every distance), the slip measured from `start` carried along.
    void
    lag_friction(const double                 *u_local,
                 const std::vector<double>    &start,
                 const std::vector<RigidPose> &start_poses,
                 const std::vector<RigidPose> &poses,
                 std::vector<LaggedContact>   &lagged) const;

    // A step's feasible start for the mesh obstacles that move (ghosted values, the
    // step's start on entry): where an obstacle would hit the cloth left in place as it
    // moves from `start_poses` to `poses` (continuous collision detection on the relative
    // straight path in the obstacle's frame), the cloth rides along with it for the rest
    // of its motion (a rigid motion, which keeps every distance to it). Collective.
    void
    carry(const std::vector<RigidPose> &start_poses,
          const std::vector<RigidPose> &poses,
          const double                  fraction,
          std::vector<double>          &state) const;

  private:
    // One candidate pair: the four points' sources, cloth (index into `cloth.vertices`)
    // or obstacle vertex (index into its surface), in PairPoints order, and its cloth
    // primitive: the index of its vertex, edge or triangle in `cloth` (one, two or three
    // moving points).
    struct Pair
    {
      PairKind            kind;
      unsigned int        obstacle;
      std::array<bool, 4> moving;
      std::array<int, 4>  index;
      unsigned int        primitive;
      double              kappa;
      double              threshold; // the mollifier's (edge-edge), else 0
    };

    // What obstacle o's pair distances lose: its core's radius r for an analytic
    // obstacle (a pair of its core's features), 0 for a mesh.
    double
    offset(const unsigned int o) const;

    // Whether obstacle o's pairs take the projected exact Hessian (ContactSettings).
    bool
    projected_exact(const unsigned int o) const;

    // `state` with every cloth point carried along with an obstacle from `from` to `to`.
    std::vector<double>
    carried_along(const std::vector<double> &state,
                  const RigidPose           &from,
                  const RigidPose           &to) const;

    PairPoints
    pair_points(const Pair &pair, const double *u_local, const RigidPose &pose) const;

    // Calls `visit` for every pair whose cloth primitive's box (around its positions
    // at u, and at u + step if `step_local` is non-null, grown by `margin`) meets the
    // obstacle primitive's box; with obstacle `only` (all mesh obstacles by default).
    void
    for_each_pair(const double                            *u_local,
                  const double                            *step_local,
                  const std::vector<RigidPose>            &poses,
                  const double                             margin,
                  const std::function<void(const Pair &)> &visit,
                  const unsigned int only = numbers::invalid_unsigned_int) const;

    // Calls `visit(pair, x, d, b)` for every pair for_each_pair finds near u (margin
    // d̂), the obstacles at `poses`: its points x, its distance d (m, less the offset)
    // and, within d̂, its barrier b with the gradient (else null).
    void
    for_each_pair_barrier(
      const double                 *u_local,
      const std::vector<RigidPose> &poses,
      const std::function<
        void(const Pair &, const PairPoints &, const double, const PairBarrier *)> &visit)
      const;

    // Calls `visit` for every pair that may be closer than d̂ at u, the obstacles at
    // `poses`: from a list of the pairs closer than 2 d̂ at an earlier state with the
    // same poses, kept while no cloth vertex has moved by more than d̂ from it (a pair's
    // distance changes by at most the largest motion of its cloth points), else made
    // again here. The pairs come in for_each_pair's order.
    void
    for_each_near_pair(const double                            *u_local,
                       const std::vector<RigidPose>            &poses,
                       const std::function<void(const Pair &)> &visit) const;

    const std::vector<Obstacle> &obstacles;
    const MPI_Comm               communicator;
    const ContactSettings       &settings;
    double                       kappa_scale       = 1.; // set_stiffness_scale
    mutable double               assembled_closest = 0.; // closest_assembled
    // Indices into `obstacles` of those with a surface: the meshes, and the analytic
    // obstacles' core features (physics/obstacle.h).
    std::vector<unsigned int> mesh_obstacles;
    ClothSurface              cloth;
    // The pairs' Hessians added by position, per cloth primitive: its vertices',
    // edges' and triangles' (one, two and three moving points).
    mutable std::array<mesh::ElementMatrixScatter, 3> pair_scatters;
    // add_to_step's gradient summed per cloth vertex (zero between calls), the
    // vertices it touched and the list of them.
    mutable std::vector<Tensor<1, 3>> vertex_gradient;
    mutable std::vector<bool>         touched;
    mutable std::vector<unsigned int> touched_vertices;
    // for_each_near_pair's list, the cloth's positions and the poses it was made at.
    mutable std::vector<Pair>      near_pairs;
    mutable std::vector<Point<3>>  near_from;
    mutable std::vector<RigidPose> near_poses;
  };
} // namespace clothsim::physics
