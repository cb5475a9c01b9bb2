#include "physics/spring_network.h"

#include "mesh/ghosted_values.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/full_matrix.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>

namespace clothsim
{
  namespace
  {
    using VertexDofs = std::array<std::array<types::global_dof_index, 3>, 3>;

    // Dofs of a cell's vertices, [vertex][component] (FE_SimplexP(1)^3: the base
    // element's dof k sits on vertex k).
    template <class CellIterator>
    VertexDofs
    vertex_dofs(const CellIterator &cell)
    {
      const auto                          &fe = cell->get_fe();
      std::vector<types::global_dof_index> indices(fe.n_dofs_per_cell());
      cell->get_dof_indices(indices);
      VertexDofs dofs;
      for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
        {
          const auto [component, vertex] = fe.system_to_component_index(i);
          dofs[vertex][component]        = indices[i];
        }
      return dofs;
    }

    template <class CellIterator>
    double
    reference_area(const CellIterator &cell)
    {
      return 0.5 * cross_product_3d(cell->vertex(1) - cell->vertex(0),
                                    cell->vertex(2) - cell->vertex(0))
                     .norm();
    }

    // The local number of the cell's vertex that is not on the edge (a, b).
    template <class CellIterator>
    unsigned int
    opposite_vertex(const CellIterator &cell, const unsigned int a, const unsigned int b)
    {
      for (unsigned int v = 0; v < 3; ++v)
        if (cell->vertex_index(v) != a && cell->vertex_index(v) != b)
          return v;
      Assert(false, ExcInternalError());
      return numbers::invalid_unsigned_int;
    }

    // The local number of the cell's vertex with global index `index`.
    template <class CellIterator>
    unsigned int
    local_vertex(const CellIterator &cell, const unsigned int index)
    {
      for (unsigned int v = 0; v < 3; ++v)
        if (cell->vertex_index(v) == index)
          return v;
      Assert(false, ExcInternalError());
      return numbers::invalid_unsigned_int;
    }
  } // namespace


  SpringNetwork::SpringNetwork(const DoFHandler<2, 3> &dof_handler,
                               const SpringConstants  &constants,
                               const VectorType       &ghosted_prototype)
    : communicator(dof_handler.get_communicator())
    , n_relevant_dofs(ghosted_prototype.trilinos_vector().MyLength())
  {
    const SpringConstants &springs  = constants;
    const SpringConstants &material = constants;
    const bool             derived  = springs.derived;

    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const VertexDofs dofs = vertex_dofs(cell);
          const double     area = reference_area(cell);
          for (const unsigned int f : cell->face_indices())
            {
              const unsigned int a = cell->face(f)->vertex_index(0);
              const unsigned int b = cell->face(f)->vertex_index(1);
              const unsigned int i = local_vertex(cell, a), j = local_vertex(cell, b);
              const double       edge_length = (cell->vertex(j) - cell->vertex(i)).norm();

              if (cell->at_boundary(f))
                {
                  const double k =
                    derived
                      ? physics::structural_spring_stiffness(material.stretch_stiffness,
                                                             material.poisson_ratio,
                                                             edge_length,
                                                             area,
                                                             0.)
                      : springs.structural_stiffness;
                  entries.push_back(make_entry(Kind::structural,
                                               k,
                                               dofs[i],
                                               dofs[j],
                                               cell->vertex(i),
                                               cell->vertex(j),
                                               ghosted_prototype));
                  continue;
                }
              const auto neighbor = cell->neighbor(f);
              if (neighbor->id() < cell->id())
                continue; // the neighbour's owner makes these springs
              const double neighbor_area = reference_area(neighbor);
              const double k_structural =
                derived ? physics::structural_spring_stiffness(material.stretch_stiffness,
                                                               material.poisson_ratio,
                                                               edge_length,
                                                               area,
                                                               neighbor_area)
                        : springs.structural_stiffness;
              entries.push_back(make_entry(Kind::structural,
                                           k_structural,
                                           dofs[i],
                                           dofs[j],
                                           cell->vertex(i),
                                           cell->vertex(j),
                                           ghosted_prototype));

              // The cross spring between the two opposite vertices.
              const unsigned int p      = opposite_vertex(cell, a, b);
              const unsigned int q      = opposite_vertex(neighbor, a, b);
              const double cross_length = (neighbor->vertex(q) - cell->vertex(p)).norm();
              double       k_cross      = 0.;
              if (!derived)
                k_cross = springs.cross_stiffness;
              else if (material.bending)
                k_cross = physics::bend_spring_stiffness(material.bending_rigidity,
                                                         edge_length,
                                                         area,
                                                         neighbor_area,
                                                         cross_length,
                                                         springs.bend_reference_angle);
              if (k_cross > 0.)
                entries.push_back(make_entry(Kind::cross,
                                             k_cross,
                                             dofs[p],
                                             vertex_dofs(neighbor)[q],
                                             cell->vertex(p),
                                             neighbor->vertex(q),
                                             ghosted_prototype));
            }
        }
    color_structural_springs();
  }


  SpringNetwork::Entry
  SpringNetwork::make_entry(const Kind                                    kind,
                            const double                                  stiffness,
                            const std::array<types::global_dof_index, 3> &dofs_0,
                            const std::array<types::global_dof_index, 3> &dofs_1,
                            const Point<3>                               &x_0,
                            const Point<3>                               &x_1,
                            const VectorType &ghosted_prototype) const
  {
    Entry entry;
    entry.kind   = kind;
    entry.spring = {stiffness, (x_1 - x_0).norm()};
    for (unsigned int d = 0; d < 3; ++d)
      {
        entry.dofs[d]     = dofs_0[d];
        entry.dofs[3 + d] = dofs_1[d];
      }
    for (unsigned int i = 0; i < 6; ++i)
      entry.local_dofs[i] = local_index(ghosted_prototype, entry.dofs[i]);
    entry.reference = {{x_0, x_1}};
    return entry;
  }


  std::array<types::global_dof_index, 2>
  SpringNetwork::global_counts() const
  {
    std::array<types::global_dof_index, 2> counts = {{0, 0}};
    for (const Entry &entry : entries)
      ++counts[static_cast<unsigned int>(entry.kind)];
    for (auto &count : counts)
      count = Utilities::MPI::sum(count, communicator);
    return counts;
  }


  std::array<std::pair<double, double>, 2>
  SpringNetwork::stiffness_range() const
  {
    std::array<std::pair<double, double>, 2> range;
    for (auto &r : range)
      r = {std::numeric_limits<double>::max(), 0.};
    for (const Entry &entry : entries)
      {
        auto &r  = range[static_cast<unsigned int>(entry.kind)];
        r.first  = std::min(r.first, entry.spring.stiffness);
        r.second = std::max(r.second, entry.spring.stiffness);
      }
    for (auto &r : range)
      {
        r.first  = Utilities::MPI::min(r.first, communicator);
        r.second = Utilities::MPI::max(r.second, communicator);
        if (r.second == 0.)
          r.first = 0.;
      }
    return range;
  }


  void
  SpringNetwork::add_sparsity(TrilinosWrappers::SparsityPattern &sparsity,
                              const AffineConstraints<double>   &constraints) const
  {
    std::vector<types::global_dof_index> dofs(6);
    for (const Entry &entry : entries)
      if (entry.kind == Kind::cross)
        {
          std::copy(entry.dofs.begin(), entry.dofs.end(), dofs.begin());
          constraints.add_entries_local_to_global(dofs, sparsity, false);
        }
  }


  physics::SpringPositions
  SpringNetwork::current_positions(const Entry &entry, const VectorType &u) const
  {
    const double            *local = ghosted_values(u, n_relevant_dofs);
    physics::SpringPositions x     = entry.reference;
    for (unsigned int k = 0; k < 2; ++k)
      for (unsigned int d = 0; d < 3; ++d)
        x[k][d] += local[entry.local_dofs[3 * k + d]];
    return x;
  }


  double
  SpringNetwork::energy(const VectorType &u) const
  {
    double value = 0.;
    for (const Entry &entry : entries)
      value += physics::spring_energy(entry.spring, current_positions(entry, u));
    return value;
  }


  double
  SpringNetwork::add_damping_force(const VectorType    &v,
                                   const double         damping_coefficient,
                                   std::vector<double> &damping_force,
                                   const VectorType    *u) const
  {
    Assert(damping_blocks.size() == entries.size(), ExcInternalError());
    AssertDimension(damping_force.size(), n_relevant_dofs);
    const double *v_local = ghosted_values(v, n_relevant_dofs);
    double        value   = 0.;
    for (unsigned int s = 0; s < entries.size(); ++s)
      {
        const Entry &entry = entries[s];
        if (u != nullptr)
          value += physics::spring_energy(entry.spring, current_positions(entry, *u));
        // c K_n v = c (-B r, B r) with r = v_1 - v_0.
        Tensor<1, 3> r;
        for (unsigned int d = 0; d < 3; ++d)
          r[d] = v_local[entry.local_dofs[3 + d]] - v_local[entry.local_dofs[d]];
        const Tensor<1, 3> force = damping_coefficient * (damping_blocks[s] * r);
        for (unsigned int d = 0; d < 3; ++d)
          {
            damping_force[entry.local_dofs[d]] -= force[d];
            damping_force[entry.local_dofs[3 + d]] += force[d];
          }
      }
    return value;
  }


  double
  SpringNetwork::add_to_step(const VectorType                &u,
                             const StepParts                 &parts,
                             const AffineConstraints<double> &constraints,
                             VectorType                      *gradient,
                             MatrixType                      *hessian,
                             std::vector<double>             *damping_gradient) const
  {
    const double c       = parts.damping_coefficient;
    const bool   damping = c > 0.;
    Assert(!damping ||
             (parts.previous != nullptr && damping_blocks.size() == entries.size()),
           ExcInternalError());
    Assert(damping_gradient == nullptr || damping_gradient->size() == n_relevant_dofs,
           ExcInternalError());
    if (!damping && gradient == nullptr && hessian == nullptr)
      return parts.elastic ? energy(u) : 0.;

    const double *u_local = ghosted_values(u, n_relevant_dofs);
    const double *previous_local =
      damping ? ghosted_values(*parts.previous, n_relevant_dofs) : nullptr;
    std::vector<types::global_dof_index> dofs(6);
    FullMatrix<double>                   cell_matrix(6, 6);
    physics::SpringVector                g;
    physics::SpringMatrix                H;
    double                               value = 0.;
    if (gradient != nullptr)
      gradient_sums.start(u);
    if (hessian != nullptr)
      hessian_scatter.start(*hessian, entries.size(), 6);
    for (unsigned int s = 0; s < entries.size(); ++s)
      {
        const Entry &entry = entries[s];
        if (parts.elastic)
          value +=
            physics::spring_energy_gradient_hessian(entry.spring,
                                                    current_positions(entry, u),
                                                    parts.projected,
                                                    g,
                                                    hessian != nullptr ? &H : nullptr);
        else
          {
            g.fill(0.);
            if (hessian != nullptr)
              for (auto &row : H)
                row.fill(0.);
          }

        if (damping)
          {
            // c/2 sᵀ K_n s with K_n = [[B, -B], [-B, B]]: with r = s_1 - s_0 (the
            // relative step of the two ends) its value is c/2 rᵀ B r, its gradient
            // c (-B r, B r), its Hessian c K_n.
            const Tensor<2, 3> &B = damping_blocks[s];
            Tensor<1, 3>        r;
            for (unsigned int d = 0; d < 3; ++d)
              r[d] = (u_local[entry.local_dofs[3 + d]] -
                      previous_local[entry.local_dofs[3 + d]]) -
                     (u_local[entry.local_dofs[d]] - previous_local[entry.local_dofs[d]]);
            const Tensor<1, 3> force = c * (B * r);
            value += 0.5 * (force * r);
            for (unsigned int d = 0; d < 3; ++d)
              {
                g[d] -= force[d];
                g[3 + d] += force[d];
              }
            if (damping_gradient != nullptr)
              for (unsigned int d = 0; d < 3; ++d)
                {
                  (*damping_gradient)[entry.local_dofs[d]] -= force[d];
                  (*damping_gradient)[entry.local_dofs[3 + d]] += force[d];
                }
            if (hessian != nullptr)
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  {
                    const double cB = c * B[i][j];
                    H[i][j] += cB;
                    H[3 + i][3 + j] += cB;
                    H[i][3 + j] -= cB;
                    H[3 + i][j] -= cB;
                  }
          }

        if (gradient != nullptr)
          for (unsigned int i = 0; i < 6; ++i)
            gradient_sums.add(entry.local_dofs[i], g[i]);
        if (hessian != nullptr)
          {
            std::copy(entry.dofs.begin(), entry.dofs.end(), dofs.begin());
            for (unsigned int i = 0; i < 6; ++i)
              for (unsigned int j = 0; j < 6; ++j)
                cell_matrix(i, j) = H[i][j];
            if (!hessian_scatter.add(s, dofs, cell_matrix, constraints))
              constraints.distribute_local_to_global(cell_matrix, dofs, *hessian);
          }
      }
    if (gradient != nullptr)
      gradient_sums.add_to(*gradient, constraints);
    return value;
  }


  void
  SpringNetwork::prepare_damping(const VectorType &u_n)
  {
    damping_blocks.resize(entries.size());
    physics::SpringVector gradient;
    physics::SpringMatrix hessian;
    for (unsigned int s = 0; s < entries.size(); ++s)
      {
        physics::spring_energy_gradient_hessian(entries[s].spring,
                                                current_positions(entries[s], u_n),
                                                /*project=*/true,
                                                gradient,
                                                &hessian);
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            damping_blocks[s][i][j] = hessian[i][j];
      }
  }


  void
  SpringNetwork::color_structural_springs()
  {
    // Key of a spring: its end points' reference coordinates, the smaller end first.
    using Key         = std::array<double, 6>;
    const auto key_of = [](const Entry &entry) {
      std::array<Point<3>, 2> ends = entry.reference;
      if (std::lexicographical_compare(
            &ends[1][0], &ends[1][0] + 3, &ends[0][0], &ends[0][0] + 3))
        std::swap(ends[0], ends[1]);
      return Key{
        {ends[0][0], ends[0][1], ends[0][2], ends[1][0], ends[1][1], ends[1][2]}};
    };
    std::vector<Key> local;
    for (const Entry &entry : entries)
      if (entry.kind == Kind::structural)
        local.push_back(key_of(entry));

    // Greedy colouring on rank 0 in key order; every rank gets the sorted (key, colour)
    // table.
    const auto                gathered = Utilities::MPI::gather(communicator, local, 0);
    std::vector<Key>          keys;
    std::vector<unsigned int> key_colors;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        for (const auto &part : gathered)
          keys.insert(keys.end(), part.begin(), part.end());
        std::sort(keys.begin(), keys.end());
        std::map<std::array<double, 3>, std::uint64_t> used; // per vertex, colour bits
        for (const Key &key : keys)
          {
            std::uint64_t &a = used[{{key[0], key[1], key[2]}}];
            std::uint64_t &b = used[{{key[3], key[4], key[5]}}];
            unsigned int   c = 0;
            while (c < 63 && (((a | b) >> c) & 1u))
              ++c;
            a |= std::uint64_t(1) << c;
            b |= std::uint64_t(1) << c;
            key_colors.push_back(c);
          }
      }
    keys        = Utilities::MPI::broadcast(communicator, keys, 0);
    key_colors  = Utilities::MPI::broadcast(communicator, key_colors, 0);
    color_count = key_colors.empty()
                    ? 0
                    : *std::max_element(key_colors.begin(), key_colors.end()) + 1;
    colors.assign(entries.size(), 0);
    for (unsigned int s = 0; s < entries.size(); ++s)
      if (entries[s].kind == Kind::structural)
        {
          const auto found =
            std::lower_bound(keys.begin(), keys.end(), key_of(entries[s]));
          Assert(found != keys.end() && *found == key_of(entries[s]), ExcInternalError());
          colors[s] = key_colors[found - keys.begin()];
        }
  }


  unsigned int
  SpringNetwork::add_strain_limit_moves(const VectorType  &u,
                                        const VectorType  &inverse_mass,
                                        const double       limit,
                                        const bool         limit_compression,
                                        const unsigned int color,
                                        VectorType        &moves,
                                        double            &largest_strain) const
  {
    unsigned int violations = 0;
    // Springs within 0.1 % of the limit count as satisfied (the sweeps converge
    // linearly).
    const double  tolerance = 1e-3 * limit;
    const double *w_local   = ghosted_values(inverse_mass, n_relevant_dofs);
    std::vector<types::global_dof_index> dofs;
    std::vector<double>                  values;
    for (unsigned int s = 0; s < entries.size(); ++s)
      {
        const Entry &entry = entries[s];
        if (entry.kind != Kind::structural || colors[s] != color)
          continue;
        const physics::SpringPositions x = current_positions(entry, u);
        const double strain = (x[1] - x[0]).norm() / entry.spring.rest_length - 1.;
        if (strain <= limit + tolerance &&
            (!limit_compression || strain >= -limit - tolerance))
          continue;
        // An end pinned in any component does not move.
        std::array<double, 2> w;
        for (unsigned int k = 0; k < 2; ++k)
          w[k] = std::min({w_local[entry.local_dofs[3 * k]],
                           w_local[entry.local_dofs[3 * k + 1]],
                           w_local[entry.local_dofs[3 * k + 2]]});
        if (w[0] == 0. && w[1] == 0.)
          continue;
        largest_strain = std::max(largest_strain, std::abs(strain));
        const physics::SpringPositions corrected = physics::limit_strain(
          x, entry.spring.rest_length, limit, w[0], w[1], limit_compression);
        ++violations;
        dofs.clear();
        values.clear();
        for (unsigned int k = 0; k < 2; ++k)
          if (w[k] > 0.)
            for (unsigned int d = 0; d < 3; ++d)
              {
                dofs.push_back(entry.dofs[3 * k + d]);
                values.push_back(corrected[k][d] - x[k][d]);
              }
        moves.add(dofs, values);
      }
    return violations;
  }
} // namespace clothsim
