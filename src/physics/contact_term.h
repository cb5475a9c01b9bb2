#pragma once

// Contact of the cloth's vertices with rigid obstacles as a term of the step's potential:
// each vertex of mass m within the thickness d̂ of an obstacle pays the barrier
// κ s(d), κ = m a_b / d̂ (physics/contact_potential.h). The barrier is infinite at
// d = 0, and Newton's line search is capped (largest_step) so that no iterate comes
// closer to an obstacle than a tenth of its current distance along the straight path:
// no iterate ever crosses an obstacle. Obstacles move rigidly; within a step they sit at
// their pose at the step's time (StepTerms::time), and begin_step() makes Newton's
// initial guess feasible there by carrying the vertices' step-start positions along the
// obstacle's motion (see begin_step). The term also lags the friction data (normal force
// and tangent plane of every contact) for physics/friction_term.h.

#include "mesh/discretization.h"
#include "mesh/element_matrix_scatter.h"
#include "physics/adaptive_barrier_term.h"
#include "physics/mesh_contact.h"
#include "physics/obstacle.h"
#include "physics/term.h"

#include <limits>
#include <string>
#include <vector>

namespace clothsim::physics
{
  struct ContactSettings
  {
    double thickness;            // d̂, m
    double barrier_acceleration; // a_b, m/s²
    double slip_velocity;        // ε_v, m/s: friction is static below it
    double ccd_fraction = 0.1;   // the line search keeps d >= this share of d(x)
    // Per obstacle, the tangent of the pairs of its core (edge contact): the exact
    // Hessian projected if true, else Gauss-Newton's (physics/pair_barrier.h; none
    // given: Gauss-Newton's for all).
    std::vector<bool> core_pairs_projected_exact = {};
    // IPC's adaptive stiffness (physics/barrier_stiffness.h); off by default.
    StiffnessSettings stiffness = {};
  };

  // A cloth vertex in a lagged contact: its dofs, their indices in the values that
  // LaggedContacts::point_values() gives (for obstacles: local indices in ghosted
  // vectors), its reference position, its weight w in the contact's closest point, and
  // its step-start position carried along with the obstacle to the step's end (where it
  // would be without slipping). Then whether this rank adds to the point's rows (it owns
  // the vertex; obstacle contacts are lagged where each point's rows may be added), and
  // its dofs' local indices in ghosted vectors, for a RankVector (-1 if not held here).
  struct FrictionPoint
  {
    std::array<types::global_dof_index, 3> dofs;
    std::array<int, 3>                     local;
    Point<3>                               reference;
    double                                 weight;
    Point<3>                               carried;
    bool                                   owned;
    std::array<int, 3>                     relevant;
  };

  // One contact as lagged at the start of a step (IPC): its slip over the step is
  // u_T = Tᵀ Σ_i w_i (x_i - c_i) over its cloth points, with the tangent plane's basis T
  // and μ λ (N) taken at the step's start.
  struct LaggedContact
  {
    unsigned int                 obstacle; // none for self-contact
    unsigned int                 vertex;   // in vertices() for a vertex contact
    unsigned int                 n_points;
    std::array<FrictionPoint, 4> points;
    Tensor<1, 3>                 tangent[2];
    double                       mu_lambda;
    // Only each point's own 3 x 3 block in the tangent (self-contact's vertex blocks).
    bool diagonal_only = false;
    // Whether its value counts on this rank (a contact lagged on several ranks counts on
    // one).
    bool counted = true;
  };

  // A contact term that lags friction data for physics/friction_term.h.
  class LaggedContacts
  {
  public:
    virtual ~LaggedContacts() = default;
    // The contacts lagged at the last step's start.
    virtual const std::vector<LaggedContact> &
    lagged_contacts() const = 0;
    // The slip below which friction is static: ε_v times the step's length (m).
    virtual double
    static_slip() const = 0;
    // The values at u (ghosted) that FrictionPoint::local indexes (collective: every
    // rank calls it).
    virtual const double *
    point_values(const VectorType &u) const
    {
      return u.trilinos_vector()[0];
    }
    // How many times the contacts were lagged anew: what a user derived from the list
    // (physics/friction_term.h: the matrix positions of each contact) is stale once it
    // changes.
    unsigned long
    lag_count() const
    {
      return n_lags;
    }

  protected:
    unsigned long n_lags = 0;
  };

  // Two unit vectors spanning the plane perpendicular to the unit n.
  void
  tangent_basis(const Tensor<1, 3> &n, Tensor<1, 3> (&t)[2]);

  class ObstacleContact : public AdaptiveBarrierTerm, public LaggedContacts
  {
  public:
    // `lumped_masses`: owned vector of each dof's vertex mass (kg).
    ObstacleContact(std::vector<Obstacle>       obstacles,
                    const ContactSettings      &settings,
                    const mesh::Discretization &discretization,
                    const VectorType           &lumped_masses);

    std::string
    report_column() const override
    {
      return "contact_energy";
    }

    double
    add_to_step(const VectorType                &u,
                const StepTerms                 &step,
                const AffineConstraints<double> &constraints,
                VectorType                      *gradient,
                MatrixType                      *hessian,
                RankVector                      *dissipative_gradient) const override;

    // The barrier's energy at u, the obstacles at the time of the last step assembled.
    double
    energy(const VectorType &u,
           const VectorType &v,
           RankVector       *damping_force) const override;

    // Before a step from t_n to t_new: moves `u_new` (owned, Newton's initial guess)
    // where it is infeasible: each vertex goes from its step-start position carried
    // along the obstacle's rigid motion (feasible: it keeps its distance) toward the
    // guess, capped as the line search is. Lags the friction data from u_n (owned).
    // Constrained (pinned) vertices keep their prescribed guess. Collective. Returns
    // why no feasible start exists (a vertex on or inside an obstacle: a pinned one
    // driven into it, or an obstacle moved onto it), empty if one was found.
    std::string
    begin_step(const double                     t_n,
               const double                     t_new,
               const VectorType                &u_n,
               VectorType                      &u_new,
               const AffineConstraints<double> &constraints);

    // Friction solved further (IPC's lagged iterations): takes the normal forces and
    // tangent planes again at u (ghosted, a solution of the step), the slip still
    // measured from the step's start. Returns the largest change of a contact's μ λ over
    // the largest μ λ (1 if contacts appear where there were none). Collective.
    double
    relag_friction(const VectorType &u);

    // The first vertex (on any rank) that is on or inside an obstacle at `time`, given u
    // (owned), described for a message; empty if none. Collective.
    std::string
    penetration(const VectorType &u, const double time) const;

    // The largest step α <= 1 along `direction` from u (both ghosted) that keeps every
    // vertex at a tenth of its distance from every obstacle or farther, the obstacles
    // at `time`. Collective.
    double
    largest_step(const VectorType &u,
                 const VectorType &direction,
                 const double      time) const;

    // The smallest distance from an obstacle of what contact keeps off them (the
    // cloth's vertices, and the pairs of edge contact and of mesh obstacles) and of the
    // cloth's whole surface (its triangles measured against the analytic obstacles'
    // signed distance too: negative where the cloth passes into an obstacle between its
    // vertices) at u (ghosted) at `time` (m; +inf with no obstacle near), and per
    // obstacle the force the barrier exerts on the cloth (N). Collective.
    struct Report
    {
      double                    min_distance;
      double                    min_surface_distance;
      std::vector<Tensor<1, 3>> forces;
      std::vector<unsigned int> contacts; // vertices within d̂, per obstacle
    };
    Report
    report(const VectorType &u, const double time) const;

    // The work the obstacles' prescribed motion from t_n to t_new does on the cloth, J
    // (collective): each barrier force on the cloth times the obstacle's rigid
    // displacement P_new(P_n⁻¹(x)) - x at the force's point x, by the trapezoidal rule
    // over the step's start u_n (the obstacles at t_n) and end u_new (at t_new; both
    // ghosted); less, for an obstacle that leaves the scene within the step, its
    // barrier energy at the step's start, which its removal takes away.
    double
    motion_work(const VectorType &u_n,
                const VectorType &u_new,
                const double      t_n,
                const double      t_new) const;
    const std::vector<Obstacle> &
    get_obstacles() const
    {
      return obstacles;
    }
    const std::vector<LaggedContact> &
    lagged_contacts() const override
    {
      return lagged;
    }
    double
    static_slip() const override
    {
      return settings.slip_velocity * last_dt;
    }
    const ContactSettings &
    get_settings() const
    {
      return settings;
    }
    // The time of the last step assembled (s): where the obstacles are for energy().
    double
    time_of_state() const
    {
      return state_time;
    }
    // The step's length of the last begin_step (s), for the friction's slip scale.
    double
    step_length() const
    {
      return last_dt;
    }

    // One owned vertex: its displacement dofs, their local indices in ghosted vectors,
    // its reference position and κ = m a_b / d̂ (N/m).
    struct Vertex
    {
      std::array<types::global_dof_index, 3> dofs;
      std::array<int, 3>                     local;
      Point<3>                               reference;
      double                                 kappa;
    };
    const std::vector<Vertex> &
    vertices() const
    {
      return table;
    }
    // The vertex's current position from a ghosted vector.
    Point<3>
    position(const Vertex &vertex, const double *u_local) const;

  private:
    double
    barrier_energy(const VectorType &u, const double time) const override;
    // For the adaptive barrier stiffness: report(u_n, t_n).min_distance (every vertex's
    // and every pair's within d̂); the scale is also mesh_pairs'.
    double
    closest_at_start(const VectorType &u_n, const double t_n) const override;
    void
    scale_changed() override
    {
      mesh_pairs.set_stiffness_scale(stiffness.scale());
    }
    bool
    is_mesh(const unsigned int o) const
    {
      return obstacles[o].shape().core == ObstacleCore::mesh;
    }
    // report() but for the surface distance, on this rank (not reduced), `local` a
    // ghosted vector's values.
    Report
    local_report(const double *local, const std::vector<RigidPose> &poses) const;
    // A vertex contact's friction data but for its tangent plane and μ λ.
    LaggedContact
    vertex_contact(const unsigned int k,
                   const unsigned int o,
                   const Point<3>    &carried) const;
    // begin_step for the mesh obstacles, after the analytic ones have moved u_new: the
    // path from the step's start, carried along with moving mesh obstacles (pinned dofs
    // at their guess), to u_new, capped; lags the mesh pairs' friction. This rank's
    // failure message, or empty. Collective.
    std::string
    begin_mesh_step(const VectorType                &u_n,
                    VectorType                      &u_new,
                    const AffineConstraints<double> &constraints);
    // The largest α <= 1 such that no owned vertex comes closer to an analytic obstacle
    // than a tenth of its distance on the path u + s step, s in [0, α] (ghosted values;
    // this rank's vertices, not reduced).
    double
    vertex_step_bound(const double                 *u_local,
                      const double                 *step_local,
                      const std::vector<RigidPose> &poses) const;
    // begin_step for the analytic obstacles' core features (after the vertices and the
    // mesh obstacles): every cloth vertex of a pair that `u_new` (owned) brings within a
    // tenth of its step-start distance rides along with that obstacle instead (its
    // step-start position carried along), until no pair does. Pinned vertices keep
    // their guess. The failure message, or empty. Collective.
    std::string
    ride_along(const double                     t_new,
               const VectorType                &u_n,
               VectorType                      &u_new,
               const AffineConstraints<double> &constraints);
    // Every obstacle's pose at `time`.
    std::vector<RigidPose>
    poses_at(const double time) const;
    // Lowers `min_distance` to the smallest distance of a point of this rank's cloth
    // triangles from an analytic obstacle, at u (`u_local`, ghosted values), the
    // obstacles at `poses` (to 1e-3 d̂, from above).
    void
    lower_to_surface_distance(const double                 *u_local,
                              const std::vector<RigidPose> &poses,
                              double                       &min_distance) const;
    // `local` (this rank's message or empty) from the lowest rank that has one.
    std::string
    first_message(const std::string &local) const;

    const std::vector<Obstacle> obstacles;
    const ContactSettings       settings;
    const mesh::Discretization &discretization;
    std::vector<Vertex>         table;
    std::vector<LaggedContact>  lagged;
    // Per vertex and obstacle (vertex-major), the step-start position carried along with
    // the obstacle to the step's end, and the obstacles' poses there.
    std::vector<Point<3>>  carried_points;
    std::vector<RigidPose> start_poses, end_poses;
    // Triangle-mesh obstacles (by primitive pairs) and the step's start (ghosted).
    MeshContact mesh_pairs;
    // The vertices' barrier Hessians added by position (vertex k is element k).
    mutable mesh::ElementMatrixScatter vertex_scatter;
    VectorType                         step_start;
    double                             last_dt    = 0.;
    mutable double                     state_time = 0.; // of the last step assembled
  };
} // namespace clothsim::physics
