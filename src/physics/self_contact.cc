#include "physics/self_contact.h"

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include "mesh/ghosted_values.h"
#include "physics/contact_potential.h"
#include "physics/pair_barrier.h"
#include "physics/wall_clock.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace clothsim::physics
{
  namespace
  {
    using Clock = WallClock;

    // Adds the wall time of its scope to one of SelfContact's phases, less what the scope
    // spent gathering and in the broad phase (those count in their own).
    class PhaseScope
    {
    public:
      PhaseScope(SelfContact::Phases &phases, double &phase)
        : phases(phases)
        , phase(phase)
        , nested(phases.gather + phases.broad)
        , start(Clock::now())
      {}
      ~PhaseScope()
      {
        phase += seconds_since(start) - (phases.gather + phases.broad - nested);
      }

    private:
      SelfContact::Phases &phases;
      double              &phase;
      const double         nested;
      Clock::time_point    start;
    };
  } // namespace


  SelfContact::SelfContact(const ContactSettings      &settings,
                           const mesh::Discretization &discretization,
                           const VectorType           &lumped_masses,
                           const bool                  couple_pairs,
                           const double                friction,
                           const bool                  creases_only)
    : AdaptiveBarrierTerm("self contact",
                          settings.stiffness,
                          discretization.get_communicator())
    , settings(settings)
    , couple_pairs(couple_pairs)
    , friction(friction)
    , creases_only(creases_only)
    , whole(discretization, lumped_masses)
    , cloth(whole.surface())
  {
    for (const auto &triangle : cloth.triangles)
      for (unsigned int v = 0; v < 3; ++v)
        neighbours.insert(key(triangle[v], triangle[(v + 1) % 3]));
    // Connected pieces by union-find over the triangles' vertices.
    piece.resize(cloth.vertices.size());
    std::iota(piece.begin(), piece.end(), 0u);
    const auto root = [this](unsigned int v) {
      while (piece[v] != v)
        v = piece[v] = piece[piece[v]];
      return v;
    };
    for (const auto &triangle : cloth.triangles)
      for (unsigned int v = 1; v < 3; ++v)
        piece[root(triangle[v])] = root(triangle[0]);
    for (unsigned int v = 0; v < piece.size(); ++v)
      piece[v] = root(v);
    if (creases_only)
      list_creases();
  }


  void
  SelfContact::add_couplings(TrilinosWrappers::SparsityPattern &sparsity,
                             const AffineConstraints<double>   &constraints) const
  {
    // The pairs couple vertices of every rank, also those this rank neither owns nor has
    // as ghosts, and their assembly (here and in the friction between layers) asks the
    // constraints about those vertices' dofs: the constraints must store every rank's
    // lines (BoundaryConditions does with self-contact). Asked about a dof it does not
    // store, AffineConstraints says "not constrained" in a Release build, so a pinned
    // vertex of another rank would be taken for a free one. Checked on every rank
    // together, so that all of them stop.
    const IndexSet &stored  = constraints.get_local_lines();
    unsigned int    missing = 0;
    if (stored.size() > 0)
      for (const auto &vertex : cloth.vertices)
        for (const types::global_dof_index dof : vertex.dofs)
          missing += stored.is_element(dof) ? 0 : 1;
    AssertThrow(Utilities::MPI::max(missing, whole.get_communicator()) == 0,
                ExcMessage("self-contact: the constraints do not store the lines of "
                           "every vertex of the cloth"));
    // Every component of one vertex with every component of the other (constrained
    // dofs included: their rows and columns stay, eliminated when assembled).
    // Rows of owned vertices only.
    std::vector<types::global_dof_index> columns(6);
    for (const std::uint64_t coupling : extra_couplings)
      {
        const unsigned int a = coupling >> 32, b = coupling & 0xffffffffu;
        for (unsigned int c = 0; c < 3; ++c)
          {
            columns[c]     = cloth.vertices[a].dofs[c];
            columns[3 + c] = cloth.vertices[b].dofs[c];
          }
        for (unsigned int r = 0; r < 6; ++r)
          if (cloth.vertices[r < 3 ? a : b].owned)
            sparsity.add_entries(columns[r], columns.begin(), columns.end());
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
    const PhaseScope   scope(phases, phases.barrier);
    const double      *u_local = gathered(u, positions);
    const double       d_hat   = settings.thickness;
    const unsigned int order   = hessian != nullptr ? 2 : gradient != nullptr ? 1 : 0;
    const std::array<bool, 4> moving = {{true, true, true, true}};
    // The pairs' parts summed per vertex and per pair of vertices first (stacked layers
    // give each vertex many pairs), then distributed once each.
    std::vector<Tensor<1, 3>> &forces   = vertex_gradient;
    std::vector<Tensor<2, 3>> &diagonal = vertex_blocks;
    forces.assign(cloth.vertices.size(), Tensor<1, 3>());
    diagonal.assign(cloth.vertices.size(), Tensor<2, 3>());
    std::unordered_map<std::uint64_t, Tensor<2, 3>> &off_diagonal = pair_blocks;
    off_diagonal.clear();
    std::vector<unsigned int> touched;
    double                    value = 0.;
    assembled_closest               = std::numeric_limits<double>::infinity();
    for_each_near_pair(u_local, nullptr, d_hat, [&](const Pair &pair) {
      const PairPoints x = pair_points(pair, u_local);
      if (boxes_apart(pair.kind, x, d_hat))
        return;
      const PairBarrier b =
        pair_barrier(pair.kind,
                     x,
                     moving,
                     stiffness.scale() * pair.kappa,
                     d_hat,
                     pair.threshold,
                     order,
                     step.projected_tangent ? PairHessian::gauss_newton
                                            : PairHessian::exact,
                     /*gauss_newton_mollified=*/true);
      assembled_closest = std::min(assembled_closest, b.distance);
      if (counted(pair))
        value += b.value;
      if (b.n == 0 || !std::isfinite(b.value))
        return;
      for (unsigned int i = 0; i < 4; ++i)
        {
          const unsigned int a = pair.index[i];
          if (!cloth.vertices[a].owned)
            continue; // its owner adds it
          if (forces[a] == Tensor<1, 3>() && diagonal[a] == Tensor<2, 3>())
            touched.push_back(a);
          for (unsigned int r = 0; r < 3; ++r)
            {
              forces[a][r] += b.gradient[3 * i + r];
              if (hessian != nullptr)
                for (unsigned int c = 0; c < 3; ++c)
                  diagonal[a][r][c] += b.hessian[(3 * i + r) * 12 + 3 * i + c];
            }
        }
      if (hessian == nullptr)
        return;
      // Off the diagonal only where the sparsity has the coupling (else the block
      // diagonal alone: that of a positive semi-definite matrix is one too).
      if (!(pair.listed ? pair.coupled : pair_coupled(pair)))
        {
          dropped += couple_pairs ? 1 : 0;
          return;
        }
      for (unsigned int i = 0; i < 4; ++i)
        for (unsigned int j = 0; j < 4; ++j)
          if (pair.index[i] < pair.index[j] && (cloth.vertices[pair.index[i]].owned ||
                                                cloth.vertices[pair.index[j]].owned))
            {
              Tensor<2, 3> &block = off_diagonal[key(pair.index[i], pair.index[j])];
              for (unsigned int r = 0; r < 3; ++r)
                for (unsigned int c = 0; c < 3; ++c)
                  block[r][c] += b.hessian[(3 * i + r) * 12 + 3 * j + c];
            }
    });

    // A vertex's gradient could sum to zero exactly; touched once is listed once.
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    Vector<double>                       g(3);
    FullMatrix<double>                   H(3, 3), H_t(3, 3);
    std::vector<types::global_dof_index> dofs(3), other_dofs(3);
    for (const unsigned int a : touched)
      {
        for (unsigned int r = 0; r < 3; ++r)
          {
            dofs[r] = cloth.vertices[a].dofs[r];
            g[r]    = forces[a][r];
            for (unsigned int c = 0; c < 3; ++c)
              H(r, c) = diagonal[a][r][c];
          }
        if (gradient != nullptr)
          constraints.distribute_local_to_global(g, dofs, *gradient);
        if (hessian != nullptr)
          constraints.distribute_local_to_global(H, dofs, *hessian);
      }
    // Each block (a, b) and its transpose, in the rows of their owners.
    for (const auto &[coupling, block] : off_diagonal)
      {
        const unsigned int a = coupling >> 32, b = coupling & 0xffffffffu;
        for (unsigned int r = 0; r < 3; ++r)
          {
            dofs[r]       = cloth.vertices[a].dofs[r];
            other_dofs[r] = cloth.vertices[b].dofs[r];
            for (unsigned int c = 0; c < 3; ++c)
              {
                H(r, c)   = block[r][c];
                H_t(c, r) = block[r][c];
              }
          }
        if (cloth.vertices[a].owned)
          constraints.distribute_local_to_global(H, dofs, other_dofs, *hessian);
        if (cloth.vertices[b].owned)
          constraints.distribute_local_to_global(H_t, other_dofs, dofs, *hessian);
      }
    return value;
  }


  double
  SelfContact::energy(const VectorType &u,
                      const VectorType & /*v*/,
                      RankVector * /*damping_force*/) const
  {
    const PhaseScope          scope(phases, phases.barrier);
    const double             *u_local = gathered(u, positions);
    double                    value   = 0.;
    const std::array<bool, 4> moving  = {{true, true, true, true}};
    for_each_near_pair(u_local, nullptr, settings.thickness, [&](const Pair &pair) {
      const PairPoints x = pair_points(pair, u_local);
      if (!counted(pair) || boxes_apart(pair.kind, x, settings.thickness))
        return;
      value += pair_barrier(pair.kind,
                            x,
                            moving,
                            stiffness.scale() * pair.kappa,
                            settings.thickness,
                            pair.threshold,
                            0,
                            PairHessian::gauss_newton)
                 .value;
    });
    return value;
  }


  double
  SelfContact::step_cap(const VectorType &u, const VectorType &direction) const
  {
    const PhaseScope scope(phases, phases.ccd);
    const double    *u_local    = gathered(u, positions);
    const double    *step_local = gathered(direction, motions);
    double           alpha      = 1.;
    double           reach      = 0.; // see below
    const auto       cap        = [&](const Pair &pair) {
      const PairPoints x = pair_points(pair, u_local);
      if (boxes_apart(pair.kind, x, reach))
        return; // its distance is `reach` or more
      PairPoints dx;
      for (unsigned int i = 0; i < 4; ++i)
        dx[i] = Point<3>(cloth.part(pair.index[i], step_local));
      alpha = std::min(alpha, pair_step_bound(pair.kind, x, dx, settings.ccd_fraction));
    };
    // A pair's distance D changes by at most 2 s on the path (s: the largest motion of
    // a vertex less the motions' common part), so it cannot come below a tenth of D if
    // 0.9 D > 2 s: only the pairs closer than 2 s / 0.9 need the test. They are among
    // the near pairs (for_each_near_pair) or those whose swept boxes meet (pairs apart
    // cannot meet on the path).
    const double largest =
      largest_relative_motion(cloth.vertices.size(), [&](const unsigned int p) {
        return Tensor<1, 3>(cloth.part(p, step_local));
      });
    reach = 2. * largest / (1. - settings.ccd_fraction);
    for_each_near_pair(u_local, step_local, reach, cap);
    return alpha;
  }


  bool
  SelfContact::update_couplings(const VectorType &u_n, const VectorType &u_new)
  {
    rebuild_trees = true; // a new step: hierarchies fitted to where the cloth is now
    if (!couple_pairs)
      return false;
    const PhaseScope scope(phases, phases.broad);
    const double    *u_local = gathered(u_n, positions);
    gathered(u_new, motions);
    // The path to twice the guess: Newton's corrections may go as far again.
    std::vector<double> step(positions.size());
    for (unsigned int i = 0; i < step.size(); ++i)
      step[i] = 2. * (motions[i] - positions[i]);
    const double d_hat = settings.thickness;
    near_from.clear(); // the couplings of the near pairs may change
    near_listed = false;

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
    // A new sparsity is made by all ranks or none.
    return Utilities::MPI::max(grown ? 1u : 0u, whole.get_communicator()) == 1u;
  }


  void
  SelfContact::lag_friction(const VectorType &u_n, const double dt)
  {
    lagged.clear();
    ++n_lags;
    last_dt = dt;
    if (friction == 0.)
      return;
    const double *u_local = gathered(u_n, positions);
    const double  d_hat   = settings.thickness;
    for_each_pair(u_local, nullptr, d_hat, [&](const Pair &pair) {
      const PairPoints   x    = pair_points(pair, u_local);
      const DistanceType type = distance_type(pair.kind, x);
      const double       d    = std::sqrt(squared_distance(type, x));
      if (d >= d_hat || d <= 0.)
        return;
      const double m =
        pair.threshold > 0.
          ? mollifier(cross_product_3d(x[1] - x[0], x[3] - x[2]).norm_square(),
                      pair.threshold)
          : 1.;
      const double lambda =
        -stiffness.scale() * pair.kappa * m * contact::barrier_first(d, d_hat);
      if (lambda <= 0.)
        return;
      const std::array<double, 4> w = closest_point_weights(type, x);
      Tensor<1, 3>                r;
      for (unsigned int i = 0; i < 4; ++i)
        r += w[i] * x[i];
      LaggedContact contact;
      contact.obstacle = numbers::invalid_unsigned_int;
      contact.vertex   = numbers::invalid_unsigned_int;
      contact.n_points = 0;
      for (unsigned int i = 0; i < 4; ++i)
        if (w[i] != 0.)
          {
            const ClothSurface::Vertex &vertex = cloth.vertices[pair.index[i]];
            FrictionPoint              &point  = contact.points[contact.n_points++];
            point.dofs                         = vertex.dofs;
            point.local     = vertex.local; // into the gathered positions
            point.owned     = vertex.owned;
            point.relevant  = whole.ghosted_local(pair.index[i]);
            point.reference = vertex.reference;
            point.weight    = w[i];
            point.carried   = x[i]; // no slip: the points stay where they start
          }
      tangent_basis(r / r.norm(), contact.tangent);
      contact.mu_lambda     = friction * lambda;
      contact.diagonal_only = !(couple_pairs && pair_coupled(pair));
      contact.counted       = counted(pair);
      lagged.push_back(contact);
    });
  }


  SelfContact::Report
  SelfContact::report(const VectorType &u,
                      const double      range,
                      const bool        within_pieces) const
  {
    const PhaseScope scope(phases, phases.report);
    const double    *u_local = gathered(u, positions);
    Report           result{std::numeric_limits<double>::infinity(), 0};
    // The search reach falls to the nearest distance found so far (a closer pair lies
    // within it), never below d̂ (every pair within d̂ is counted): with a range of 10
    // d̂ the report took 13 % of the twisted tube's run.
    double reach = range;
    for_each_pair(u_local, nullptr, reach, [&](const Pair &pair) {
      if (within_pieces && piece[pair.index[0]] != piece[pair.index[3]])
        return;
      const double d =
        std::sqrt(pair_squared_distance(pair.kind, pair_points(pair, u_local)));
      if (d < range)
        result.min_distance = std::min(result.min_distance, d);
      if (d < settings.thickness && counted(pair))
        ++result.pairs;
      reach = std::max(settings.thickness, std::min(reach, d));
    });
    const MPI_Comm communicator = whole.get_communicator();
    result.min_distance         = Utilities::MPI::min(result.min_distance, communicator);
    result.pairs                = Utilities::MPI::sum(result.pairs, communicator);
    return result;
  }


  double
  SelfContact::closest_at_start(const VectorType &u_n, const double) const
  {
    return report(u_n, settings.stiffness.distance).min_distance;
  }


  const double *
  SelfContact::gathered(const VectorType &u, std::vector<double> &buffer) const
  {
    const Clock::time_point start = Clock::now();
    whole.gather(u, buffer);
    phases.gather += seconds_since(start);
    return buffer.data();
  }


  std::vector<std::pair<std::string, double>>
  SelfContact::phase_seconds() const
  {
    return {{"broad phase", phases.broad},
            {"barrier", phases.barrier},
            {"CCD", phases.ccd},
            {"gather", phases.gather},
            {"report", phases.report}};
  }
} // namespace clothsim::physics
