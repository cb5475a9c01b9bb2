#include "physics/self_contact.h"

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include "mesh/ghosted_values.h"
#include "physics/pair_barrier.h"

#include <cmath>
#include <limits>

namespace clothsim::physics
{
  SelfContact::SelfContact(const ContactSettings      &settings,
                           const mesh::Discretization &discretization,
                           const VectorType           &lumped_masses)
    : GlobalTerm("self contact", TermKind::constraint)
    , settings(settings)
    , n_relevant_dofs(discretization.relevant_dofs().n_elements())
    , cloth(discretization, lumped_masses)
  {
    AssertThrow(Utilities::MPI::n_mpi_processes(discretization.get_communicator()) == 1,
                ExcMessage("self-contact runs on one MPI rank only"));
    for (const auto &triangle : cloth.triangles)
      for (unsigned int v = 0; v < 3; ++v)
        neighbours.insert(key(triangle[v], triangle[(v + 1) % 3]));
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
  SelfContact::for_each_pair(const double                            *u_local,
                             const double                            *step_local,
                             const double                             margin,
                             const std::function<void(const Pair &)> &visit) const
  {
    const double a_per_d = settings.barrier_acceleration / settings.thickness;
    // The box around vertices at u (and u + step), grown by `grow`.
    std::vector<Point<3>> corners;
    const auto            box_of = [&](const auto &primitive, const double grow) {
      corners.clear();
      for (const unsigned int p : primitive)
        {
          const Point<3> x = cloth.position(p, u_local);
          corners.push_back(x);
          if (step_local != nullptr)
            corners.push_back(x + cloth.part(p, step_local));
        }
      return Box::around(corners, grow);
    };
    const auto mass = [&](const unsigned int p) { return cloth.vertices[p].mass; };

    // The hierarchies are built once per step (update_couplings) and refitted here.
    const auto fit = [this](AabbTree &tree, const std::vector<Box> &boxes) {
      if (rebuild_trees || tree.size() != boxes.size())
        tree = AabbTree(boxes);
      else
        tree.refit(boxes);
    };
    boxes.clear();
    for (const auto &triangle : cloth.triangles)
      boxes.push_back(box_of(triangle, 0.));
    fit(triangle_tree, boxes);
    boxes.clear();
    for (const auto &edge : cloth.edges)
      boxes.push_back(box_of(edge, 0.));
    fit(edge_tree, boxes);
    rebuild_trees = false;
    std::vector<unsigned int> found;
    Pair                      pair;

    // Vertices against triangles.
    pair.kind      = PairKind::point_triangle;
    pair.threshold = 0.;
    for (unsigned int p = 0; p < cloth.vertices.size(); ++p)
      {
        found.clear();
        triangle_tree.find(box_of(std::array<unsigned int, 1>{{p}}, margin), found);
        for (const unsigned int t : found)
          {
            const auto &triangle = cloth.triangles[t];
            if (triangle[0] == p || triangle[1] == p || triangle[2] == p)
              continue;
            pair.index = {{p, triangle[0], triangle[1], triangle[2]}};
            pair.kappa =
              0.25 *
              (mass(p) + mass(triangle[0]) + mass(triangle[1]) + mass(triangle[2])) *
              a_per_d;
            visit(pair);
          }
      }

    // Edges against edges, each pair once.
    pair.kind = PairKind::edge_edge;
    for (unsigned int e = 0; e < cloth.edges.size(); ++e)
      {
        const auto [a, b] = cloth.edges[e];
        found.clear();
        edge_tree.find(box_of(cloth.edges[e], margin), found);
        for (const unsigned int k : found)
          {
            const auto [c, d] = cloth.edges[k];
            if (k <= e || c == a || c == b || d == a || d == b)
              continue;
            pair.index = {{a, b, c, d}};
            pair.kappa = 0.25 * (mass(a) + mass(b) + mass(c) + mass(d)) * a_per_d;
            pair.threshold =
              mollifier_threshold(cloth.edge_length[e], cloth.edge_length[k]);
            visit(pair);
          }
      }
  }


  void
  SelfContact::add_couplings(TrilinosWrappers::SparsityPattern &sparsity,
                             const AffineConstraints<double> & /*constraints*/) const
  {
    // Every component of one vertex with every component of the other (constrained
    // dofs included: their rows and columns stay, eliminated when assembled).
    std::vector<types::global_dof_index> rows(6);
    for (const std::uint64_t coupling : extra_couplings)
      {
        const unsigned int a = coupling >> 32, b = coupling & 0xffffffffu;
        for (unsigned int c = 0; c < 3; ++c)
          {
            rows[c]     = cloth.vertices[a].dofs[c];
            rows[3 + c] = cloth.vertices[b].dofs[c];
          }
        for (const types::global_dof_index row : rows)
          sparsity.add_entries(row, rows.begin(), rows.end());
      }
  }


  double
  SelfContact::add_to_step(const VectorType                &u,
                           const StepTerms                 &step,
                           const AffineConstraints<double> &constraints,
                           VectorType                      *gradient,
                           MatrixType                      *hessian,
                           RankVector * /*dissipative_gradient*/) const
  {
    const double      *u_local = ghosted_values(u, n_relevant_dofs);
    const double       d_hat   = settings.thickness;
    const unsigned int order   = hessian != nullptr ? 2 : gradient != nullptr ? 1 : 0;
    double             value   = 0.;
    Vector<double>     g(12), g_vertex(3);
    FullMatrix<double> H(12, 12), H_vertex(3, 3);
    std::vector<types::global_dof_index> dofs(12), vertex_dofs(3);
    const std::array<bool, 4>            moving = {{true, true, true, true}};
    for_each_pair(u_local, nullptr, d_hat, [&](const Pair &pair) {
      const PairPoints  x = pair_points(pair, u_local);
      const PairBarrier b = pair_barrier(pair.kind,
                                         x,
                                         moving,
                                         pair.kappa,
                                         d_hat,
                                         pair.threshold,
                                         order,
                                         step.projected_tangent,
                                         /*gauss_newton_mollified=*/true);
      value += b.value;
      if (b.n == 0 || !std::isfinite(b.value))
        return;
      for (unsigned int i = 0; i < 4; ++i)
        for (unsigned int c = 0; c < 3; ++c)
          dofs[3 * i + c] = cloth.vertices[pair.index[i]].dofs[c];
      if (gradient != nullptr)
        {
          for (unsigned int i = 0; i < 12; ++i)
            g[i] = b.gradient[i];
          constraints.distribute_local_to_global(g, dofs, *gradient);
        }
      if (hessian == nullptr)
        return;
      bool all_coupled = true;
      for (unsigned int i = 0; i < 4; ++i)
        for (unsigned int j = i + 1; j < 4; ++j)
          all_coupled = all_coupled && coupled(pair.index[i], pair.index[j]);
      if (all_coupled)
        {
          for (unsigned int i = 0; i < 12; ++i)
            for (unsigned int j = 0; j < 12; ++j)
              H(i, j) = b.hessian[i * 12 + j];
          constraints.distribute_local_to_global(H, dofs, *hessian);
          return;
        }
      // The block diagonal of a positive semi-definite matrix is positive
      // semi-definite too.
      ++dropped;
      for (unsigned int i = 0; i < 4; ++i)
        {
          for (unsigned int r = 0; r < 3; ++r)
            {
              vertex_dofs[r] = dofs[3 * i + r];
              for (unsigned int c = 0; c < 3; ++c)
                H_vertex(r, c) = b.hessian[(3 * i + r) * 12 + 3 * i + c];
            }
          constraints.distribute_local_to_global(H_vertex, vertex_dofs, *hessian);
        }
    });
    return value;
  }


  double
  SelfContact::energy(const VectorType &u,
                      const VectorType & /*v*/,
                      RankVector * /*damping_force*/) const
  {
    const double             *u_local = ghosted_values(u, n_relevant_dofs);
    double                    value   = 0.;
    const std::array<bool, 4> moving  = {{true, true, true, true}};
    for_each_pair(u_local, nullptr, settings.thickness, [&](const Pair &pair) {
      value += pair_barrier(pair.kind,
                            pair_points(pair, u_local),
                            moving,
                            pair.kappa,
                            settings.thickness,
                            pair.threshold,
                            0,
                            true)
                 .value;
    });
    return value;
  }


  double
  SelfContact::step_cap(const VectorType &u, const VectorType &direction) const
  {
    const double *u_local    = ghosted_values(u, n_relevant_dofs);
    const double *step_local = ghosted_values(direction, n_relevant_dofs);
    double        alpha      = 1.;
    // Pairs whose swept boxes stay apart cannot meet on the path.
    for_each_pair(u_local, step_local, 0., [&](const Pair &pair) {
      PairPoints dx;
      for (unsigned int i = 0; i < 4; ++i)
        dx[i] = Point<3>(cloth.part(pair.index[i], step_local));
      alpha = std::min(alpha,
                       pair_step_bound(pair.kind,
                                       pair_points(pair, u_local),
                                       dx,
                                       settings.ccd_fraction));
    });
    return alpha;
  }


  bool
  SelfContact::update_couplings(const VectorType &u_n, const VectorType &u_new)
  {
    const double *u_local = ghosted_values(u_n, n_relevant_dofs);
    // The path to twice the guess: Newton's corrections may go as far again.
    std::vector<double> step(n_relevant_dofs);
    const double       *new_local = ghosted_values(u_new, n_relevant_dofs);
    for (unsigned int i = 0; i < n_relevant_dofs; ++i)
      step[i] = 2. * (new_local[i] - u_local[i]);
    const double d_hat = settings.thickness;
    rebuild_trees      = true;

    std::unordered_set<std::uint64_t> needed;
    for_each_pair(u_local, step.data(), 2. * d_hat, [&](const Pair &pair) {
      PairPoints dx;
      for (unsigned int i = 0; i < 4; ++i)
        dx[i] = Point<3>(cloth.part(pair.index[i], step.data()));
      const double d0 =
        std::sqrt(pair_squared_distance(pair.kind, pair_points(pair, u_local)));
      if (d0 >= 2. * d_hat + pair_motion_bound(pair.kind, dx))
        return;
      for (unsigned int i = 0; i < 4; ++i)
        for (unsigned int j = i + 1; j < 4; ++j)
          if (neighbours.count(key(pair.index[i], pair.index[j])) == 0)
            needed.insert(key(pair.index[i], pair.index[j]));
    });
    bool grown = false;
    for (const std::uint64_t coupling : needed)
      grown = grown || extra_couplings.count(coupling) == 0;
    if (grown)
      extra_couplings = std::move(needed);
    return grown;
  }


  SelfContact::Report
  SelfContact::report(const VectorType &u, const double range) const
  {
    const double *u_local = ghosted_values(u, n_relevant_dofs);
    Report        result{std::numeric_limits<double>::infinity(), 0};
    for_each_pair(u_local, nullptr, range, [&](const Pair &pair) {
      const double d =
        std::sqrt(pair_squared_distance(pair.kind, pair_points(pair, u_local)));
      if (d < range)
        result.min_distance = std::min(result.min_distance, d);
      if (d < settings.thickness)
        ++result.pairs;
    });
    return result;
  }
} // namespace clothsim::physics
