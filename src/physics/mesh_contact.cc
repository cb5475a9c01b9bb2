#include "physics/mesh_contact.h"

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include "mesh/ghosted_values.h"
#include "physics/contact_potential.h"
#include "physics/contact_term.h"
#include "physics/pair_barrier.h"

#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace clothsim::physics
{
  MeshContact::MeshContact(const std::vector<Obstacle> &obstacles,
                           const ContactSettings       &settings,
                           const mesh::Discretization  &discretization,
                           const VectorType            &lumped_masses)
    : obstacles(obstacles)
    , communicator(discretization.get_communicator())
    , settings(settings)
    , cloth(discretization, lumped_masses)
  {
    for (unsigned int o = 0; o < obstacles.size(); ++o)
      if (obstacles[o].shape().surface != nullptr)
        mesh_obstacles.push_back(o);
  }


  double
  MeshContact::offset(const unsigned int o) const
  {
    const ObstacleShape &shape = obstacles[o].shape();
    return shape.core == ObstacleCore::mesh ? 0. : shape.radius;
  }


  bool
  MeshContact::projected_exact(const unsigned int o) const
  {
    return o < settings.core_pairs_projected_exact.size() &&
           settings.core_pairs_projected_exact[o];
  }


  PairPoints
  MeshContact::pair_points(const Pair      &pair,
                           const double    *u_local,
                           const RigidPose &pose) const
  {
    const ObstacleSurface &surface = *obstacles[pair.obstacle].shape().surface;
    PairPoints             x;
    for (unsigned int i = 0; i < 4; ++i)
      x[i] = pair.moving[i] ? cloth.position(pair.index[i], u_local)
                            : pose.to_world(surface.vertices[pair.index[i]]);
    return x;
  }


  void
  MeshContact::for_each_pair(const double                            *u_local,
                             const double                            *step_local,
                             const std::vector<RigidPose>            &poses,
                             const double                             margin,
                             const std::function<void(const Pair &)> &visit,
                             const unsigned int                       only) const
  {
    const double a_per_d = settings.barrier_acceleration / settings.thickness;
    // Each cloth vertex's box (around it at u and at u + step) in the obstacle's body
    // frame, once per obstacle; a primitive's box joins its vertices' boxes, and a
    // primitive whose box misses the surface's is not looked up.
    std::vector<Box> vertex_boxes(cloth.vertices.size());
    Box              box, bounds;
    const auto       box_of = [&](const std::initializer_list<unsigned int> primitive,
                            const double                              grow) {
      box = vertex_boxes[*primitive.begin()];
      for (const unsigned int p : primitive)
        box = box.merged(vertex_boxes[p]);
      for (unsigned int c = 0; c < 3; ++c)
        {
          box.lower[c] -= grow;
          box.upper[c] += grow;
        }
      return box.overlaps(bounds);
    };

    std::vector<unsigned int> found;
    for (const unsigned int o : mesh_obstacles)
      {
        if ((only != numbers::invalid_unsigned_int && o != only) || !poses[o].present)
          continue;
        const ObstacleSurface &surface = *obstacles[o].shape().surface;
        const RigidPose       &pose    = poses[o];
        const double           reach   = margin + offset(o);
        bounds                         = surface.bounds;
        for (unsigned int p = 0; p < cloth.vertices.size(); ++p)
          {
            const Point<3>          x = cloth.position(p, u_local);
            std::array<Point<3>, 2> ends{{pose.to_body(x), pose.to_body(x)}};
            if (step_local != nullptr)
              ends[1] = pose.to_body(x + cloth.part(p, step_local));
            vertex_boxes[p] = Box::around(ends);
          }
        Pair pair;
        pair.obstacle = o;

        // Cloth vertices against the obstacle's triangles.
        pair.kind      = PairKind::point_triangle;
        pair.moving    = {{true, false, false, false}};
        pair.threshold = 0.;
        for (unsigned int p = 0; p < cloth.vertices.size(); ++p)
          {
            if (!cloth.vertices[p].owned)
              continue;
            found.clear();
            if (box_of({p}, reach))
              surface.triangle_tree.find(box, found);
            pair.kappa     = cloth.vertices[p].mass * a_per_d;
            pair.primitive = p;
            for (const unsigned int t : found)
              {
                const auto &triangle = surface.triangles[t];
                pair.index           = {{static_cast<int>(p),
                                         static_cast<int>(triangle[0]),
                                         static_cast<int>(triangle[1]),
                                         static_cast<int>(triangle[2])}};
                visit(pair);
              }
          }

        // Cloth edges against the obstacle's edges.
        pair.kind   = PairKind::edge_edge;
        pair.moving = {{true, true, false, false}};
        for (unsigned int e = 0; e < cloth.edges.size(); ++e)
          {
            const auto [a, b] = cloth.edges[e];
            found.clear();
            if (box_of({a, b}, reach))
              surface.edge_tree.find(box, found);
            pair.kappa =
              0.5 * (cloth.vertices[a].mass + cloth.vertices[b].mass) * a_per_d;
            pair.primitive = e;
            for (const unsigned int k : found)
              {
                const auto &edge = surface.edges[k];
                pair.index       = {{static_cast<int>(a),
                                     static_cast<int>(b),
                                     static_cast<int>(edge[0]),
                                     static_cast<int>(edge[1])}};
                pair.threshold   = mollifier_threshold(cloth.edge_length[e],
                                                     surface.vertices[edge[0]].distance(
                                                       surface.vertices[edge[1]]));
                visit(pair);
              }
          }

        // The obstacle's vertices against the cloth's triangles.
        pair.kind      = PairKind::point_triangle;
        pair.moving    = {{false, true, true, true}};
        pair.threshold = 0.;
        for (unsigned int t = 0; t < cloth.triangles.size(); ++t)
          {
            const auto &triangle = cloth.triangles[t];
            found.clear();
            if (box_of({triangle[0], triangle[1], triangle[2]}, reach))
              surface.vertex_tree.find(box, found);
            pair.kappa =
              (cloth.vertices[triangle[0]].mass + cloth.vertices[triangle[1]].mass +
               cloth.vertices[triangle[2]].mass) /
              3. * a_per_d;
            pair.primitive = t;
            for (const unsigned int v : found)
              {
                pair.index = {{static_cast<int>(v),
                               static_cast<int>(triangle[0]),
                               static_cast<int>(triangle[1]),
                               static_cast<int>(triangle[2])}};
                visit(pair);
              }
          }
      }
  }


  void
  MeshContact::for_each_near_pair(const double                            *u_local,
                                  const std::vector<RigidPose>            &poses,
                                  const std::function<void(const Pair &)> &visit) const
  {
    const double d_hat  = settings.thickness;
    const double margin = 2. * d_hat;
    bool         same   = !near_from.empty() && near_poses.size() == poses.size();
    for (unsigned int o = 0; same && o < poses.size(); ++o)
      same = near_poses[o].rotation == poses[o].rotation &&
             near_poses[o].translation == poses[o].translation &&
             near_poses[o].present == poses[o].present;
    double moved = 0.;
    for (unsigned int p = 0; same && p < near_from.size(); ++p)
      moved = std::max(moved, cloth.position(p, u_local).distance_square(near_from[p]));
    if (!same || moved > (margin - d_hat) * (margin - d_hat))
      {
        near_pairs.clear();
        for_each_pair(u_local, nullptr, poses, margin, [&](const Pair &pair) {
          const double d =
            std::sqrt(
              pair_squared_distance(pair.kind,
                                    pair_points(pair, u_local, poses[pair.obstacle]))) -
            offset(pair.obstacle);
          if (d < margin)
            near_pairs.push_back(pair);
        });
        near_from.resize(cloth.vertices.size());
        for (unsigned int p = 0; p < near_from.size(); ++p)
          near_from[p] = cloth.position(p, u_local);
        near_poses = poses;
      }
    for (const Pair &pair : near_pairs)
      visit(pair);
  }


  double
  MeshContact::add_to_step(const double                    *u_local,
                           const std::vector<RigidPose>    &poses,
                           const bool                       projected,
                           const AffineConstraints<double> &constraints,
                           VectorType                      *gradient,
                           MatrixType                      *hessian) const
  {
    const double       d_hat = settings.thickness;
    const unsigned int order = hessian != nullptr ? 2 : gradient != nullptr ? 1 : 0;
    double             value = 0.;
    FullMatrix<double> H;
    std::vector<types::global_dof_index> dofs;
    assembled_closest = std::numeric_limits<double>::infinity();
    vertex_gradient.resize(cloth.vertices.size());
    touched.resize(cloth.vertices.size(), false);
    if (hessian != nullptr)
      for (unsigned int k = 0; k < 3; ++k)
        pair_scatters[k].start(*hessian,
                               k == 0   ? cloth.vertices.size()
                               : k == 1 ? cloth.edges.size()
                                        : cloth.triangles.size(),
                               3 * (k + 1));
    for_each_near_pair(u_local, poses, [&](const Pair &pair) {
      const PairPoints  x    = pair_points(pair, u_local, poses[pair.obstacle]);
      const double      r    = offset(pair.obstacle);
      const PairHessian form = !projected ? PairHessian::exact
                               : projected_exact(pair.obstacle)
                                 ? PairHessian::projected
                                 : PairHessian::gauss_newton;
      const PairBarrier b    = pair_barrier(pair.kind,
                                         x,
                                         pair.moving,
                                         kappa_scale * pair.kappa,
                                         d_hat,
                                         pair.threshold,
                                         order,
                                         form,
                                         false,
                                         r);
      value += b.value;
      assembled_closest = std::min(assembled_closest, b.distance);
      if (b.n == 0 || !std::isfinite(b.value))
        return;
      dofs.clear();
      for (unsigned int i = 0, k = 0; i < 4; ++i)
        if (pair.moving[i])
          {
            const unsigned int p = pair.index[i];
            for (unsigned int c = 0; c < 3; ++c)
              dofs.push_back(cloth.vertices[p].dofs[c]);
            if (gradient == nullptr)
              continue;
            if (!touched[p])
              {
                touched[p] = true;
                touched_vertices.push_back(p);
              }
            for (unsigned int c = 0; c < 3; ++c)
              vertex_gradient[p][c] += b.gradient[k++];
          }
      if (hessian != nullptr &&
          !pair_scatters[b.n / 3 - 1].add(
            pair.primitive, dofs, b.hessian.data(), b.n, constraints))
        {
          H.reinit(b.n, b.n);
          for (unsigned int i = 0; i < b.n; ++i)
            for (unsigned int j = 0; j < b.n; ++j)
              H(i, j) = b.hessian[i * b.n + j];
          constraints.distribute_local_to_global(H, dofs, *hessian);
        }
    });
    // Each vertex's sum over its pairs (about six per vertex on a sheet lying on a
    // sphere) distributed once.
    Vector<double> g(3);
    dofs.resize(3);
    for (const unsigned int p : touched_vertices)
      {
        for (unsigned int c = 0; c < 3; ++c)
          {
            dofs[c] = cloth.vertices[p].dofs[c];
            g[c]    = vertex_gradient[p][c];
          }
        constraints.distribute_local_to_global(g, dofs, *gradient);
        vertex_gradient[p] = Tensor<1, 3>();
        touched[p]         = false;
      }
    touched_vertices.clear();
    return value;
  }


  double
  MeshContact::largest_step(const double                 *u_local,
                            const double                 *step_local,
                            const std::vector<RigidPose> &poses,
                            const double                  fraction,
                            const unsigned int            only) const
  {
    double alpha = 1.;
    // Pairs whose swept boxes stay apart cannot meet on the path.
    for_each_pair(
      u_local,
      step_local,
      poses,
      0.,
      [&](const Pair &pair) {
        const PairPoints x = pair_points(pair, u_local, poses[pair.obstacle]);
        PairPoints       dx;
        for (unsigned int i = 0; i < 4; ++i)
          if (pair.moving[i])
            for (unsigned int c = 0; c < 3; ++c)
              dx[i][c] = step_local[cloth.vertices[pair.index[i]].local[c]];
        alpha =
          std::min(alpha,
                   pair_step_bound(pair.kind, x, dx, fraction, offset(pair.obstacle)));
      },
      only);
    return alpha;
  }


  void
  MeshContact::for_each_pair_barrier(
    const double                 *u_local,
    const std::vector<RigidPose> &poses,
    const std::function<
      void(const Pair &, const PairPoints &, const double, const PairBarrier *)> &visit)
    const
  {
    const double d_hat = settings.thickness;
    for_each_pair(u_local, nullptr, poses, d_hat, [&](const Pair &pair) {
      const PairPoints x = pair_points(pair, u_local, poses[pair.obstacle]);
      const double     r = offset(pair.obstacle);
      const double     d = std::sqrt(pair_squared_distance(pair.kind, x)) - r;
      if (d >= d_hat)
        {
          visit(pair, x, d, nullptr);
          return;
        }
      const PairBarrier b = pair_barrier(pair.kind,
                                         x,
                                         pair.moving,
                                         kappa_scale * pair.kappa,
                                         d_hat,
                                         pair.threshold,
                                         1,
                                         PairHessian::exact,
                                         false,
                                         r);
      visit(pair, x, d, &b);
    });
  }


  void
  MeshContact::report(const double                 *u_local,
                      const std::vector<RigidPose> &poses,
                      double                       &min_distance,
                      std::vector<Tensor<1, 3>>    &forces,
                      std::vector<unsigned int>    &contacts) const
  {
    for_each_pair_barrier(
      u_local,
      poses,
      [&](const Pair &pair, const PairPoints &, const double d, const PairBarrier *b) {
        min_distance = std::min(min_distance, d);
        if (b == nullptr)
          return;
        ++contacts[pair.obstacle];
        for (unsigned int i = 0; i < b->n; ++i)
          forces[pair.obstacle][i % 3] -= b->gradient[i];
      });
    // Beyond d̂: the distance from the nearest owned cloth vertex to each mesh (the
    // analytic obstacles' vertex distances are ObstacleContact's).
    for (const unsigned int o : mesh_obstacles)
      {
        if (obstacles[o].shape().core != ObstacleCore::mesh || !poses[o].present)
          continue;
        const ObstacleSurface &surface = *obstacles[o].shape().surface;
        for (unsigned int p = 0; p < cloth.vertices.size(); ++p)
          if (cloth.vertices[p].owned)
            {
              const Point<3> y     = poses[o].to_body(cloth.position(p, u_local));
              const auto     lower = [&y](const Box &box) { return box.distance(y); };
              const auto     exact = [&](const unsigned int t) {
                const auto &v = surface.vertices;
                const auto &k = surface.triangles[t];
                return std::sqrt(
                  pair_squared_distance(PairKind::point_triangle,
                                        PairPoints{{y, v[k[0]], v[k[1]], v[k[2]]}}));
              };
              min_distance = surface.triangle_tree.nearest(lower, exact, min_distance);
            }
      }
  }


  void
  MeshContact::pair_work(
    const double                                                      *u_local,
    const std::vector<RigidPose>                                      &poses,
    const std::function<Tensor<1, 3>(unsigned int, const Point<3> &)> &displacement,
    std::vector<double>                                               &work,
    std::vector<double>                                               &energy) const
  {
    for_each_pair_barrier(
      u_local,
      poses,
      [&](const Pair &pair, const PairPoints &x, const double, const PairBarrier *b) {
        if (b == nullptr)
          return;
        energy[pair.obstacle] += b->value;
        // The gradient has 3 entries per moving point, in order; the force is -∇.
        unsigned int entry = 0;
        for (unsigned int k = 0; k < 4; ++k)
          if (pair.moving[k])
            {
              const Tensor<1, 3> delta = displacement(pair.obstacle, x[k]);
              for (unsigned int c = 0; c < 3; ++c)
                work[pair.obstacle] -= b->gradient[entry + c] * delta[c];
              entry += 3;
            }
      });
  }


  std::string
  MeshContact::touching(const double                 *u_local,
                        const std::vector<RigidPose> &poses,
                        const bool                    meshes_only) const
  {
    std::string found;
    for_each_pair(u_local, nullptr, poses, settings.thickness, [&](const Pair &pair) {
      const PairPoints x = pair_points(pair, u_local, poses[pair.obstacle]);
      if (meshes_only && obstacles[pair.obstacle].shape().core != ObstacleCore::mesh)
        return;
      if (!found.empty() ||
          std::sqrt(pair_squared_distance(pair.kind, x)) > offset(pair.obstacle))
        return;
      const Point<3>     at = x[pair.moving[0] ? 0 : 1];
      std::ostringstream text;
      text << "the cloth "
           << (pair.kind == PairKind::edge_edge ? "edge" : "vertex or triangle")
           << " at (" << at[0] << ", " << at[1] << ", " << at[2] << ") touches obstacle '"
           << obstacles[pair.obstacle].name() << "'";
      found = text.str();
    });
    // Crossings (a cloth that starts through an obstacle has no pair at distance 0).
    const auto describe = [](const Point<3> &x) {
      std::ostringstream text;
      text << "(" << x[0] << ", " << x[1] << ", " << x[2] << ")";
      return text.str();
    };
    std::vector<unsigned int> hits;
    for (const unsigned int o : mesh_obstacles)
      {
        if (!found.empty())
          break;
        if (!poses[o].present)
          continue;
        const ObstacleSurface &surface = *obstacles[o].shape().surface;
        const auto            &v       = surface.vertices;
        const std::string      name    = "obstacle '" + obstacles[o].name() + "'";
        for (const auto &[a, b] : cloth.edges)
          {
            const std::array<Point<3>, 2> y = {
              {poses[o].to_body(cloth.position(a, u_local)),
               poses[o].to_body(cloth.position(b, u_local))}};
            hits.clear();
            surface.triangle_tree.find(Box::around(y), hits);
            for (const unsigned int k : hits)
              {
                const auto &t = surface.triangles[k];
                if (found.empty() &&
                    segment_crosses_triangle(y[0], y[1], v[t[0]], v[t[1]], v[t[2]]))
                  found = "the cloth edge at " + describe(cloth.position(a, u_local)) +
                          " passes through " + name;
              }
          }
        for (const auto &triangle : cloth.triangles)
          {
            std::array<Point<3>, 3> y;
            for (unsigned int i = 0; i < 3; ++i)
              y[i] = poses[o].to_body(cloth.position(triangle[i], u_local));
            hits.clear();
            surface.edge_tree.find(Box::around(y), hits);
            for (const unsigned int k : hits)
              {
                const auto &e = surface.edges[k];
                if (found.empty() &&
                    segment_crosses_triangle(v[e[0]], v[e[1]], y[0], y[1], y[2]))
                  found = "an edge of " + name +
                          " passes through the cloth triangle at " +
                          describe(cloth.position(triangle[0], u_local));
              }
          }
      }
    return found;
  }


  void
  MeshContact::lag_friction(const double                 *u_local,
                            const std::vector<double>    &start,
                            const std::vector<RigidPose> &start_poses,
                            const std::vector<RigidPose> &poses,
                            std::vector<LaggedContact>   &lagged) const
  {
    const double d_hat = settings.thickness;
    for (const unsigned int o : mesh_obstacles)
      {
        const double mu = obstacles[o].friction();
        if (mu <= 0.)
          continue;
        // Where the cloth would be without slipping: its start carried along.
        const std::vector<double> carried =
          carried_along(start, start_poses[o], poses[o]);
        const double *at = u_local != nullptr ? u_local : carried.data();
        for_each_pair(
          at,
          nullptr,
          poses,
          d_hat,
          [&](const Pair &pair) {
            const PairPoints   x    = pair_points(pair, at, poses[o]);
            const DistanceType type = distance_type(pair.kind, x);
            const double       d    = std::sqrt(squared_distance(type, x)) - offset(o);
            if (d >= d_hat || d <= 0.)
              return;
            const std::array<double, 4> w = closest_point_weights(type, x);
            Tensor<1, 3>                r;
            for (unsigned int i = 0; i < 4; ++i)
              r += w[i] * x[i];
            // λ = -∂b/∂d (the mollifier scales it for edge-edge pairs).
            double lambda =
              kappa_scale * pair.kappa * std::abs(contact::barrier_first(d, d_hat));
            if (pair.threshold > 0.)
              lambda *=
                mollifier(cross_product_3d(x[1] - x[0], x[3] - x[2]).norm_square(),
                          pair.threshold);
            LaggedContact contact;
            contact.obstacle  = o;
            contact.vertex    = numbers::invalid_unsigned_int;
            contact.mu_lambda = mu * lambda;
            tangent_basis(r / r.norm(), contact.tangent);
            contact.n_points = 0;
            for (unsigned int i = 0; i < 4; ++i)
              if (pair.moving[i] && w[i] != 0.)
                {
                  FrictionPoint              &point  = contact.points[contact.n_points++];
                  const ClothSurface::Vertex &vertex = cloth.vertices[pair.index[i]];
                  point.dofs                         = vertex.dofs;
                  point.local                        = vertex.local;
                  point.reference                    = vertex.reference;
                  point.weight                       = w[i];
                  point.carried  = cloth.position(pair.index[i], carried.data());
                  point.owned    = true;
                  point.relevant = vertex.local;
                }
            if (contact.n_points > 0)
              lagged.push_back(contact);
          },
          o);
      }
  }
} // namespace clothsim::physics
