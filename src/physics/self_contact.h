#pragma once

// Contact of the cloth with itself (IPC, Li et al. 2020), as a term of the step's
// potential: every pair of a vertex and a triangle, and of two edges, that share no
// vertex pays the pair barrier κ m(x) s(d) (physics/pair_barrier.h, all four points
// moving) while closer than the contact thickness d̂, with κ = m̄ a_b / d̂ and m̄ the mean
// lumped mass of the pair's four vertices. Candidates come from bounding-volume
// hierarchies of the cloth's vertices, triangles and edges (physics/aabb_tree.h),
// refitted to the positions an evaluation is given and descended two at once (vertices
// against triangles, edges against edges), through a list of the pairs near an earlier
// state: only the pairs of vertices that have moved far from it are looked up again
// (physics/self_contact_pairs.cc). Newton's line search is capped by
// continuous collision detection of every pair whose swept boxes meet
// (pair_step_bound): no iterate passes through the cloth.
//
// With `creases_only` the pairs are those of the two triangles at each interior edge
// only (a hinge: each one's opposite vertex against the other triangle, and each one's
// two other edges against the other's), listed once from the mesh: a crease cannot
// close through itself, where `Director function = angle` jumps (README, "Shell
// bending"), and no hierarchy is needed. While a hinge is open by 90 degrees or more,
// none of its pairs is closer than a bound from its two triangles' shape
// (hinge_distance_bound), which decides which hinges an evaluation visits.
//
// A pair's Hessian couples vertices that share no triangle. By default only its
// vertices' 3 x 3 diagonal blocks enter the tangent (the block diagonal of a positive
// semi-definite matrix is one too), and the tangent's sparsity stays the mesh's. With
// `couple_pairs` the whole pair enters: the sparsity follows the pairs, as before each
// step update_couplings() takes every pair that may come within d̂ during the step (with
// a margin for Newton's corrections) and asks for a new sparsity if one of them is new;
// a pair whose coupling is not in the sparsity yet keeps its diagonal blocks only until
// the next step's update (dropped_blocks() counts them).
//
// Under MPI every rank holds the whole surface (physics/whole_surface.h: all vertices'
// positions gathered at each evaluation) and evaluates the pairs that touch a vertex it
// owns, adding to its owned vertices' rows only; a pair's energy counts on the rank that
// owns its lowest-numbered vertex. A vertex's sums thus see the same pairs in the same
// order on any number of ranks. Friction between layers is lagged the same way: each rank
// lags the contacts that touch its vertices and adds to their rows.

#include "mesh/discretization.h"
#include "physics/aabb_tree.h"
#include "physics/cloth_surface.h"
#include "physics/contact_term.h"
#include "physics/pair_distance.h"
#include "physics/term.h"
#include "physics/whole_surface.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace clothsim::physics
{
  class SelfContact : public AdaptiveBarrierTerm, public LaggedContacts
  {
  public:
    // `lumped_masses`: owned, each dof's vertex mass (kg). `couple_pairs`: the whole
    // pair Hessians in the tangent (see above).
    SelfContact(const ContactSettings      &settings,
                const mesh::Discretization &discretization,
                const VectorType           &lumped_masses,
                const bool                  couple_pairs = false,
                const double                friction     = 0.,
                const bool                  creases_only = false);

    std::string
    report_column() const override
    {
      return "self_contact_energy";
    }

    // The dof couplings of the vertex pairs taken by the last update_couplings().
    void
    add_couplings(TrilinosWrappers::SparsityPattern &sparsity,
                  const AffineConstraints<double>   &constraints) const override;

    double
    add_to_step(const VectorType                &u,
                const StepTerms                 &step,
                const AffineConstraints<double> &constraints,
                VectorType                      *gradient,
                MatrixType                      *hessian,
                RankVector                      *dissipative_gradient) const override;

    double
    energy(const VectorType &u,
           const VectorType &v,
           RankVector       *damping_force) const override;

    bool
    caps_steps() const override
    {
      return true;
    }

    // The largest α <= 1 along `direction` from u (both ghosted) that keeps every pair
    // at a tenth of its distance or farther on the straight path.
    double
    step_cap(const VectorType &u, const VectorType &direction) const override;

    // Before a step from u_n to Newton's initial guess u_new (both ghosted): the vertex
    // pairs of every pair that may come within d̂ during the step (closer than
    // 2 (d̂ + L) at u_n, L the pair's motion bound on the path to u_new: twice that path,
    // for Newton's corrections) are coupled. Returns whether a coupling is new (then the
    // tangent's sparsity must be made again, with add_couplings()).
    bool
    update_couplings(const VectorType &u_n, const VectorType &u_new);

    // Before a step of length dt from u_n (ghosted): with friction μ > 0, every pair
    // within d̂ at u_n is lagged for physics/friction_term.h (IPC): its normal force
    // λ = -κ m(x) s'(d), the plane perpendicular to the line between its closest points,
    // and its four vertices with their closest-point weights, so that the slip is that of
    // one closest point against the other.
    void
    lag_friction(const VectorType &u_n, const double dt);
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
    // The gathered positions (the lagged points index them, all ranks' vertices).
    const double *
    point_values(const VectorType &u) const override
    {
      return gathered(u, friction_positions);
    }
    bool
    has_friction() const
    {
      return friction > 0.;
    }

    // At u (ghosted): the smallest distance between primitives that share no vertex
    // (m; +inf if none is closer than `range`), and the pairs within d̂.
    struct Report
    {
      double       min_distance;
      unsigned int pairs;
    };
    // `within_pieces`: over the pairs within one connected piece of the mesh only
    // (stacked sheets may start in contact; one piece must not touch itself at rest).
    Report
    report(const VectorType &u,
           const double      range,
           const bool        within_pieces = false) const;

    // Wall time so far (s, this rank) in: gathering positions from all ranks; the broad
    // phase (the near-pair list's checks and rebuilds); the barrier's pairs in
    // add_to_step and energy; the CCD step cap; the statistics' report (each less the
    // gathering and broad phase it called).
    struct Phases
    {
      double gather = 0., broad = 0., barrier = 0., ccd = 0., report = 0.;
    };
    std::vector<std::pair<std::string, double>>
    phase_seconds() const override;

    // With `couple_pairs`: pairs whose Hessian kept only its diagonal vertex blocks
    // (coupling not yet in the sparsity), since the start.
    unsigned long
    dropped_blocks() const
    {
      return dropped;
    }

  private:
    // The barrier's energy at u (the cloth's own: no time).
    double
    barrier_energy(const VectorType &u, const double /*time*/) const override
    {
      return energy(u, u, nullptr);
    }
    // For the adaptive barrier stiffness: the closest pair at u_n within the stiffening
    // distance (report()).
    double
    closest_at_start(const VectorType &u_n, const double t_n) const override;

    struct Pair
    {
      PairKind                    kind;
      std::array<unsigned int, 4> index; // into cloth.vertices, in PairPoints order
      double                      kappa;
      double                      threshold; // the mollifier's (edge-edge), else 0
      bool   listed   = false; // from the near-pair list (then `coupled` is known)
      bool   coupled  = true;  // all its vertices coupled in the sparsity
      double distance = 0.;    // listed: at the state the list was made at (m)
    };

    PairPoints
    pair_points(const Pair &pair, const double *u_local) const;
    // The pair of vertex p and triangle t, and of edges e and k (e < k: the order in
    // which pairs are visited), with their κ and mollifier threshold.
    Pair
    point_triangle_pair(const unsigned int p, const unsigned int t) const;
    Pair
    edge_edge_pair(const unsigned int e, const unsigned int k) const;

    // Fills `hinges` and `crease_pairs` from the mesh (each interior edge of two
    // triangles).
    void
    list_creases();

    // for_each_pair with `creases_only`: the hinges' pairs, each hinge visited if its
    // bound is below `margin` (with a step: below margin + 2 M / (1 - CCD fraction),
    // M the largest motion of its vertices along the step less their mean motion).
    void
    for_each_crease_pair(const double                            *u_local,
                         const double                            *step_local,
                         const double                            &margin,
                         const std::function<void(const Pair &)> &visit) const;

    // Visits the pair of vertex p and triangle t unless t has p or no vertex of the
    // pair is owned here.
    void
    visit_point_triangle(const unsigned int                       p,
                         const unsigned int                       t,
                         const std::function<void(const Pair &)> &visit) const
    {
      const auto &triangle = cloth.triangles[t];
      if (triangle[0] == p || triangle[1] == p || triangle[2] == p)
        return;
      const Pair pair = point_triangle_pair(p, t);
      if (touches_owned(pair))
        visit(pair);
    }

    // Whether the boxes around the pair's two primitives are `gap` or more apart (then
    // so are the primitives: a cheap test before the distance's).
    static bool
    boxes_apart(const PairKind kind, const PairPoints &x, const double gap);

    // The hierarchies refitted to the primitives' boxes around their positions at u,
    // and at u + step if `step_local` is non-null (built again at a step's start).
    void
    fit_trees(const double *u_local, const double *step_local) const;

    // Calls `visit` for every pair whose primitives' boxes (around their positions at
    // u, and at u + step if `step_local` is non-null) come within `margin`. `margin` is
    // read at each primitive's query: `visit` may lower it (report's nearest pair).
    void
    for_each_pair(const double                            *u_local,
                  const double                            *step_local,
                  const double                            &margin,
                  const std::function<void(const Pair &)> &visit) const;

    // The same for the pairs with a vertex marked in `moved` only.
    void
    for_each_pair_of_moved(const double                            *u_local,
                           const double                            *step_local,
                           const double                             margin,
                           const std::function<void(const Pair &)> &visit) const;

    // Marks in `moved` the vertices whose motion from near_from (and, with a step,
    // along it) may bring a pair off the list into play (see the definition); returns
    // how many.
    unsigned int
    mark_moved(const double *u_local, const double *step_local, const double reach) const;

    // Without a step: calls `visit` for every pair that may be closer than `reach` at u
    // (and returns false, visiting none, if `reach` exceeds 2 d̂). With a step: for every
    // pair that the step cap must test (its swept boxes may meet, or its distance fall
    // below the CCD fraction of itself on the path). From a list of the pairs closer
    // than 2 d̂ at an earlier state where few vertices have moved far from it, the
    // pairs of those that have looked up anew; else from the hierarchies.
    bool
    for_each_near_pair(const double                            *u_local,
                       const double                            *step_local,
                       const double                             reach,
                       const std::function<void(const Pair &)> &visit) const;

    static std::uint64_t
    key(unsigned int a, unsigned int b)
    {
      if (a > b)
        std::swap(a, b);
      return (static_cast<std::uint64_t>(a) << 32) | b;
    }
    // Whether this rank evaluates the pair (one of its vertices is owned here), and
    // whether it counts its energy (its first vertex is).
    bool
    touches_owned(const Pair &pair) const
    {
      return cloth.vertices[pair.index[0]].owned || cloth.vertices[pair.index[1]].owned ||
             cloth.vertices[pair.index[2]].owned || cloth.vertices[pair.index[3]].owned;
    }
    bool
    counted(const Pair &pair) const
    {
      return cloth.vertices[*std::min_element(pair.index.begin(), pair.index.end())]
        .owned;
    }
    // Whether all of the pair's vertices are coupled in the tangent's sparsity.
    bool
    pair_coupled(const Pair &pair) const
    {
      bool all = true;
      for (unsigned int i = 0; i < 4; ++i)
        for (unsigned int j = i + 1; j < 4; ++j)
          all = all && coupled(pair.index[i], pair.index[j]);
      return all;
    }
    // Whether vertices a and b are coupled in the tangent's sparsity.
    bool
    coupled(const unsigned int a, const unsigned int b) const
    {
      return a == b || neighbours.count(key(a, b)) > 0 ||
             extra_couplings.count(key(a, b)) > 0;
    }

    const ContactSettings settings;
    const bool            couple_pairs;
    const double          friction; // μ between layers
    const bool            creases_only;
    // With `creases_only`: per hinge its vertices (a, b, p, q: the shared edge, then the
    // opposite vertices) and its four pairs (crease_pairs[4 h] to [4 h + 3]).
    std::vector<std::array<unsigned int, 4>> hinges;
    std::vector<Pair>                        crease_pairs;
    mutable std::vector<Point<3>>            crease_positions; // of an evaluation
    std::vector<LaggedContact>               lagged;
    double                                   last_dt = 0.;
    WholeSurface                             whole;
    const ClothSurface                      &cloth; // whole.surface()
    // The gathered displacements (3 per vertex) of an evaluation's vectors.
    mutable std::vector<double> positions, motions, friction_positions;
    mutable Phases              phases;
    // whole.gather(u, buffer), timed; returns the buffer's values.
    const double *
    gathered(const VectorType &u, std::vector<double> &buffer) const;
    std::unordered_set<std::uint64_t> neighbours;      // vertices of a common triangle
    std::vector<unsigned int>         piece;           // per vertex: its connected piece
    std::unordered_set<std::uint64_t> extra_couplings; // of the pairs, see above
    mutable unsigned long             dropped = 0;
    // Bounding-volume hierarchies of the triangles, the edges and the vertices, and
    // their boxes.
    mutable AabbTree         triangle_tree, edge_tree, vertex_tree;
    mutable std::vector<Box> boxes, vertex_boxes;
    mutable bool             rebuild_trees = true;
    // for_each_near_pair's list, the positions it was made at and whether it is made;
    // the vertices that have moved far from them (mark_moved), per vertex and listed,
    // and every vertex's motion since (m);
    // the pairs of those vertices for one call, and a buffer for the hierarchies'
    // queries.
    mutable std::vector<Pair>         near_pairs;
    mutable std::vector<Point<3>>     near_from;
    mutable bool                      near_listed = false;
    mutable std::vector<char>         moved;
    mutable std::vector<unsigned int> moved_vertices;
    mutable std::vector<double>       motion_since; // per vertex, less the common part
    mutable std::vector<Pair>         near_visits;
    mutable std::vector<unsigned int> found_buffer;
    // add_to_step's sums per vertex and per coupled pair of vertices (key(a, b), a < b:
    // the block of a's rows and b's columns).
    mutable std::vector<Tensor<1, 3>>                       vertex_gradient;
    mutable std::vector<Tensor<2, 3>>                       vertex_blocks;
    mutable std::unordered_map<std::uint64_t, Tensor<2, 3>> pair_blocks;
  };
} // namespace clothsim::physics
