// SelfContact's broad phase: the candidate pairs from the bounding-volume hierarchies,
// and the list of near pairs that the barrier's evaluations and the step cap reuse
// (physics/self_contact.h).

#include "physics/self_contact.h"

#include "physics/pair_barrier.h"
#include "physics/wall_clock.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace clothsim::physics
{
  bool
  SelfContact::boxes_apart(const PairKind kind, const PairPoints &x, const double gap)
  {
    // The boxes of the two primitives (the point and the triangle, or the two edges).
    const unsigned int first = kind == PairKind::point_triangle ? 1 : 2;
    double             sum   = 0.;
    for (unsigned int d = 0; d < 3; ++d)
      {
        double lower_a = x[0][d], upper_a = x[0][d];
        for (unsigned int i = 1; i < first; ++i)
          {
            lower_a = std::min(lower_a, x[i][d]);
            upper_a = std::max(upper_a, x[i][d]);
          }
        double lower_b = x[first][d], upper_b = x[first][d];
        for (unsigned int i = first + 1; i < 4; ++i)
          {
            lower_b = std::min(lower_b, x[i][d]);
            upper_b = std::max(upper_b, x[i][d]);
          }
        const double apart = std::max({lower_b - upper_a, lower_a - upper_b, 0.});
        sum += apart * apart;
      }
    return sum >= gap * gap;
  }


  PairPoints
  SelfContact::pair_points(const Pair &pair, const double *u_local) const
  {
    PairPoints x;
    for (unsigned int i = 0; i < 4; ++i)
      x[i] = cloth.position(pair.index[i], u_local);
    return x;
  }


  void
  SelfContact::fit_trees(const double *u_local, const double *step_local) const
  {
    // Each vertex's box (around it at u, and u + step); a primitive's joins its
    // vertices'.
    vertex_boxes.resize(cloth.vertices.size());
    for (unsigned int p = 0; p < cloth.vertices.size(); ++p)
      {
        const Point<3> x = cloth.position(p, u_local);
        vertex_boxes[p] =
          step_local == nullptr
            ? Box{x, x}
            : Box::around(std::array<Point<3>, 2>{{x, x + cloth.part(p, step_local)}});
      }
    const auto box_of = [this](const auto &primitive) {
      Box box = vertex_boxes[primitive[0]];
      for (const unsigned int p : primitive)
        box = box.merged(vertex_boxes[p]);
      return box;
    };
    // The hierarchies are built once per step (update_couplings) and refitted here.
    const auto fit = [this](AabbTree &tree, const std::vector<Box> &boxes) {
      if (rebuild_trees || tree.size() != boxes.size())
        tree = AabbTree(boxes);
      else
        tree.refit(boxes);
    };
    boxes.clear();
    for (const auto &triangle : cloth.triangles)
      boxes.push_back(box_of(triangle));
    fit(triangle_tree, boxes);
    boxes.clear();
    for (const auto &edge : cloth.edges)
      boxes.push_back(box_of(edge));
    fit(edge_tree, boxes);
    fit(vertex_tree, vertex_boxes);
    rebuild_trees = false;
  }


  SelfContact::Pair
  SelfContact::point_triangle_pair(const unsigned int p, const unsigned int t) const
  {
    const auto  &triangle = cloth.triangles[t];
    const auto   mass     = [&](const unsigned int v) { return cloth.vertices[v].mass; };
    const double a_per_d  = settings.barrier_acceleration / settings.thickness;
    Pair         pair;
    pair.kind  = PairKind::point_triangle;
    pair.index = {{p, triangle[0], triangle[1], triangle[2]}};
    pair.kappa = 0.25 *
                 (mass(p) + mass(triangle[0]) + mass(triangle[1]) + mass(triangle[2])) *
                 a_per_d;
    pair.threshold = 0.;
    return pair;
  }


  SelfContact::Pair
  SelfContact::edge_edge_pair(const unsigned int e, const unsigned int k) const
  {
    const auto [a, b]    = cloth.edges[e];
    const auto [c, d]    = cloth.edges[k];
    const auto   mass    = [&](const unsigned int v) { return cloth.vertices[v].mass; };
    const double a_per_d = settings.barrier_acceleration / settings.thickness;
    Pair         pair;
    pair.kind      = PairKind::edge_edge;
    pair.index     = {{a, b, c, d}};
    pair.kappa     = 0.25 * (mass(a) + mass(b) + mass(c) + mass(d)) * a_per_d;
    pair.threshold = mollifier_threshold(cloth.edge_length[e], cloth.edge_length[k]);
    return pair;
  }


  void
  SelfContact::for_each_pair(const double                            *u_local,
                             const double                            *step_local,
                             const double                            &margin,
                             const std::function<void(const Pair &)> &visit) const
  {
    if (creases_only)
      return for_each_crease_pair(u_local, step_local, margin, visit);
    fit_trees(u_local, step_local);
    // Vertices against triangles, both hierarchies descended at once.
    vertex_tree.for_each_overlap(triangle_tree,
                                 margin,
                                 [&](const unsigned int p, const unsigned int t) {
                                   visit_point_triangle(p, t, visit);
                                 });
    // Edges against edges, each pair once (e < k).
    edge_tree.for_each_overlap(margin, [&](const unsigned int e, const unsigned int k) {
      const auto [a, b] = cloth.edges[e];
      const auto [c, d] = cloth.edges[k];
      if (c == a || c == b || d == a || d == b)
        return;
      const Pair pair = edge_edge_pair(e, k);
      if (touches_owned(pair))
        visit(pair);
    });
  }


  void
  SelfContact::for_each_pair_of_moved(
    const double                            *u_local,
    const double                            *step_local,
    const double                             margin,
    const std::function<void(const Pair &)> &visit) const
  {
    fit_trees(u_local, step_local);
    const auto grown = [margin](Box box) {
      for (unsigned int d = 0; d < 3; ++d)
        {
          box.lower[d] -= margin;
          box.upper[d] += margin;
        }
      return box;
    };
    const auto is_moved = [this](const auto &primitive) {
      for (const unsigned int p : primitive)
        if (moved[p])
          return true;
      return false;
    };
    std::vector<unsigned int> &found = found_buffer;
    // A moved vertex against every triangle; a triangle with a moved vertex against
    // every vertex that has not moved (those that have are the first loop's).
    for (const unsigned int p : moved_vertices)
      {
        found.clear();
        triangle_tree.find(grown(vertex_tree.box(p)), found);
        for (const unsigned int t : found)
          visit_point_triangle(p, t, visit);
      }
    for (unsigned int t = 0; t < cloth.triangles.size(); ++t)
      {
        const auto &triangle = cloth.triangles[t];
        if (!is_moved(triangle))
          continue;
        found.clear();
        vertex_tree.find(grown(triangle_tree.box(t)), found);
        for (const unsigned int p : found)
          {
            if (moved[p] || triangle[0] == p || triangle[1] == p || triangle[2] == p)
              continue;
            const Pair pair = point_triangle_pair(p, t);
            if (touches_owned(pair))
              visit(pair);
          }
      }
    // An edge with a moved vertex against every edge (a pair of two such edges once).
    for (unsigned int e = 0; e < cloth.edges.size(); ++e)
      {
        const auto [a, b] = cloth.edges[e];
        if (!moved[a] && !moved[b])
          continue;
        found.clear();
        edge_tree.find(grown(edge_tree.box(e)), found);
        for (const unsigned int k : found)
          {
            const auto [c, d] = cloth.edges[k];
            if (c == a || c == b || d == a || d == b ||
                (k < e && is_moved(cloth.edges[k])))
              continue;
            const Pair pair = edge_edge_pair(std::min(e, k), std::max(e, k));
            if (touches_owned(pair))
              visit(pair);
          }
      }
  }


  unsigned int
  SelfContact::mark_moved(const double *u_local,
                          const double *step_local,
                          const double  reach) const
  {
    // A pair off the list was 2 d̂ = m or farther apart at near_from. Its distance has
    // shrunk since by at most a_i + a_j, a the largest motion of a vertex of each
    // primitive less the motions' common part c (which moves no distance). Without a
    // step: if every a < (m - reach)/2, the pair is still farther than `reach`. With a
    // step (the cap): if also every b < (1 - f) m/4, b a vertex's motion along the step
    // less its common part, the pair's distance D > m/2 changes by at most b_i + b_j <
    // (1 - f) D on the path, so it cannot come below f D (f: the CCD fraction).
    const unsigned int n      = cloth.vertices.size();
    const double       margin = 2. * settings.thickness;
    const double slack     = step_local == nullptr ? (margin - reach) / 2. : margin / 4.;
    const double step_room = (1. - settings.ccd_fraction) * margin / 4.;
    const auto   since     = [&](const unsigned int p) {
      return cloth.position(p, u_local) - near_from[p];
    };
    const auto along = [&](const unsigned int p) {
      return Tensor<1, 3>(cloth.part(p, step_local));
    };
    const auto far =
      [&](const unsigned int p, const Tensor<1, 3> &c, const Tensor<1, 3> &s) {
        return (since(p) - c).norm_square() >= slack * slack ||
               (step_local != nullptr &&
                (along(p) - s).norm_square() >= step_room * step_room);
      };
    // Taken out either the motions' common part (the centre of their box: a sheet
    // moving as a whole) or nothing (a part of it moving alone), whichever marks fewer.
    Tensor<1, 3>       c, s;
    const Tensor<1, 3> centre = common_motion(n, since);
    const Tensor<1, 3> step_centre =
      step_local != nullptr ? common_motion(n, along) : Tensor<1, 3>();
    unsigned int without = 0, with = 0;
    for (unsigned int p = 0; p < n; ++p)
      {
        without += far(p, c, s) ? 1 : 0;
        with += far(p, centre, step_centre) ? 1 : 0;
      }
    if (with < without)
      {
        c = centre;
        s = step_centre;
      }
    moved.assign(n, 0);
    moved_vertices.clear();
    motion_since.resize(n);
    for (unsigned int p = 0; p < n; ++p)
      {
        motion_since[p] = (since(p) - c).norm();
        if (far(p, c, s))
          {
            moved[p] = 1;
            moved_vertices.push_back(p);
          }
      }
    return moved_vertices.size();
  }


  bool
  SelfContact::for_each_near_pair(const double                            *u_local,
                                  const double                            *step_local,
                                  const double                             reach,
                                  const std::function<void(const Pair &)> &visit) const
  {
    // The list holds the pairs closer than m = 2 d̂ at near_from. A call visits the
    // listed pairs of vertices that have not moved far from there (mark_moved), and the
    // pairs of those that have, found in the hierarchies refitted to u: the pairs whose
    // boxes come within `reach` (without a step), or whose swept boxes meet (with one).
    // Where more than a quarter of the vertices have moved, every pair whose swept boxes
    // meet is taken (with a step), or (without) those whose boxes come within `reach`
    // and u becomes near_from: a list is made at the next call if few vertices have
    // moved far from there (a cloth wrapping an obstacle, or turning, moves far in every
    // Newton iteration, and a list made at each call would not be reused).
    if (creases_only)
      {
        for_each_crease_pair(u_local,
                             step_local,
                             step_local != nullptr ? 0. : reach,
                             visit);
        return true;
      }
    const double margin = 2. * settings.thickness;
    if (step_local == nullptr && reach > margin)
      return false;
    const WallClock::time_point start = WallClock::now();
    const unsigned int          n     = cloth.vertices.size();
    const unsigned int          n_moved =
      near_from.empty() ? n : mark_moved(u_local, step_local, reach);
    const auto set_near_from = [&] {
      near_from.resize(n);
      for (unsigned int p = 0; p < n; ++p)
        near_from[p] = cloth.position(p, u_local);
    };
    if (step_local != nullptr && (n_moved > n / 4 || !near_listed))
      {
        phases.broad += seconds_since(start);
        for_each_pair(u_local, step_local, 0., visit);
        return true;
      }
    if (n_moved > n / 4)
      {
        near_listed = false;
        near_visits.clear();
        for_each_pair(u_local, nullptr, reach, [&](const Pair &pair) {
          if (!boxes_apart(pair.kind, pair_points(pair, u_local), reach))
            near_visits.push_back(pair);
        });
        set_near_from();
        phases.broad += seconds_since(start);
        for (const Pair &pair : near_visits)
          visit(pair);
        return true;
      }
    if (!near_listed)
      {
        near_pairs.clear();
        for_each_pair(u_local, nullptr, margin, [&](const Pair &pair) {
          const PairPoints x = pair_points(pair, u_local);
          if (boxes_apart(pair.kind, x, margin))
            return;
          const double squared = pair_squared_distance(pair.kind, x);
          if (squared < margin * margin)
            {
              near_pairs.push_back(pair);
              near_pairs.back().listed   = true;
              near_pairs.back().coupled  = pair_coupled(pair);
              near_pairs.back().distance = std::sqrt(squared);
            }
        });
        set_near_from();
        near_listed = true;
        moved.assign(n, 0);
        moved_vertices.clear();
        motion_since.assign(n, 0.);
      }
    // A listed pair of vertices that have not moved far: whether it may be within
    // `reach` now (its distance at near_from less its primitives' motions since).
    const auto may_reach = [&](const Pair &pair) {
      if (moved[pair.index[0]] || moved[pair.index[1]] || moved[pair.index[2]] ||
          moved[pair.index[3]])
        return false;
      const unsigned int first = pair.kind == PairKind::point_triangle ? 1 : 2;
      double             a = 0., b = 0.;
      for (unsigned int i = 0; i < 4; ++i)
        (i < first ? a : b) = std::max(i < first ? a : b, motion_since[pair.index[i]]);
      return pair.distance - (a + b) < reach;
    };
    near_visits.clear();
    if (!moved_vertices.empty())
      for_each_pair_of_moved(u_local,
                             step_local,
                             step_local == nullptr ? reach : 0.,
                             [&](const Pair &pair) { near_visits.push_back(pair); });
    phases.broad += seconds_since(start);
    for (const Pair &pair : near_pairs)
      if (may_reach(pair))
        visit(pair);
    for (const Pair &pair : near_visits)
      visit(pair);
    return true;
  }

  void
  SelfContact::list_creases()
  {
    std::unordered_map<std::uint64_t, unsigned int> edge_of;
    for (unsigned int e = 0; e < cloth.edges.size(); ++e)
      edge_of[key(cloth.edges[e][0], cloth.edges[e][1])] = e;
    // Per edge, the triangles on it and their vertices opposite it.
    std::unordered_map<std::uint64_t, std::vector<std::array<unsigned int, 2>>> sides;
    for (unsigned int t = 0; t < cloth.triangles.size(); ++t)
      for (unsigned int v = 0; v < 3; ++v)
        sides[key(cloth.triangles[t][v], cloth.triangles[t][(v + 1) % 3])].push_back(
          {{t, cloth.triangles[t][(v + 2) % 3]}});
    const auto edge_pair = [&](const unsigned int a,
                               const unsigned int b,
                               const unsigned int c,
                               const unsigned int d) {
      const unsigned int e = edge_of.at(key(a, b)), k = edge_of.at(key(c, d));
      return edge_edge_pair(std::min(e, k), std::max(e, k));
    };
    for (const auto &[a, b] : cloth.edges) // in the edges' order, the same on all ranks
      {
        const auto &on = sides.at(key(a, b));
        if (on.size() != 2)
          continue; // a free edge (or a non-manifold one: left to full self-contact)
        const unsigned int p = on[0][1], q = on[1][1];
        hinges.push_back({{a, b, p, q}});
        crease_pairs.push_back(point_triangle_pair(p, on[1][0]));
        crease_pairs.push_back(point_triangle_pair(q, on[0][0]));
        crease_pairs.push_back(edge_pair(p, a, b, q));
        crease_pairs.push_back(edge_pair(p, b, a, q));
      }
  }


  void
  SelfContact::for_each_crease_pair(const double                            *u_local,
                                    const double                            *step_local,
                                    const double                            &margin,
                                    const std::function<void(const Pair &)> &visit) const
  {
    std::vector<Point<3>> &x = crease_positions;
    x.resize(cloth.vertices.size());
    for (unsigned int p = 0; p < x.size(); ++p)
      x[p] = cloth.position(p, u_local);
    for (unsigned int h = 0; h < hinges.size(); ++h)
      {
        const std::array<unsigned int, 4> &v     = hinges[h];
        double                             reach = margin;
        if (step_local != nullptr)
          {
            // A pair's distance changes by at most twice its points' largest motion
            // less any common one (here their mean) on the path.
            std::array<Tensor<1, 3>, 4> dx;
            Tensor<1, 3>                mean;
            for (unsigned int i = 0; i < 4; ++i)
              mean += (dx[i] = cloth.part(v[i], step_local)) / 4.;
            double largest = 0.;
            for (const Tensor<1, 3> &motion : dx)
              largest = std::max(largest, (motion - mean).norm());
            reach += 2. * largest / (1. - settings.ccd_fraction);
          }
        if (hinge_distance_bound(x[v[0]], x[v[1]], x[v[2]], x[v[3]]) >= reach)
          continue;
        for (unsigned int k = 4 * h; k < 4 * h + 4; ++k)
          if (touches_owned(crease_pairs[k]))
            visit(crease_pairs[k]);
      }
  }
} // namespace clothsim::physics
