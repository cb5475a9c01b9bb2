// Benchmark (not a ctest test: it asserts nothing and prints timings): one factorisation
// and one solve by the supernodal Cholesky (solvers/supernodal_cholesky.h) with its
// written-out panels and substitutions (solvers/panel_cholesky.h) against the same with
// LAPACK's potrf, BLAS' trsm and (in the solve) BLAS' trsv and gemv, in
// single (default) or double precision, on the pattern of the swinging sheet's tangent:
// an N x N-vertex square with alternating diagonals, each triangle coupling its three
// vertices' three displacements and its three edges' unknowns (a 12 x 12 element matrix),
// in a fill-reducing order. The values are a diagonally dominant symmetric matrix (the
// cost does not depend on them). The two are timed in alternating passes and each one's
// fastest pass is reported with their ratio, measured in this one run.
//
//   build/tests/factor_benchmark [N, default 81] [passes, default 40] [single | double]
//                                [order, default metis]
//
// order: `metis` (METIS' nested dissection of the unknowns' graph), `metis:U:S` (with
// UFACTOR U and seed S, either may be empty), `vertex:U:S` (METIS on the graph of the N²
// vertices, each edge's unknown right after the first of its two vertices), or `pord`
// (MUMPS' PORD, as clothsim orders on one rank). The order's operations, and the time
// taken to order and analyse, are printed first; with 0 passes nothing else.

#include <deal.II/base/mpi.h>

#include "solvers/blas_kernels.h"
#include "solvers/fill_reducing_order.h"
#include "solvers/supernodal_cholesky.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

using namespace clothsim;

int
main(int argc, char **argv)
{
  const int         N          = argc > 1 ? std::atoi(argv[1]) : 81;
  const int         passes     = argc > 2 ? std::atoi(argv[2]) : 40;
  const std::string precision  = argc > 3 ? argv[3] : "single";
  const std::string order_name = argc > 4 ? argv[4] : "metis";
  // The order's kind and its METIS options from "kind:U:S".
  const std::string       kind = order_name.substr(0, order_name.find(':'));
  NestedDissectionOptions metis_options;
  {
    std::string rest =
      order_name.size() > kind.size() ? order_name.substr(kind.size() + 1) : "";
    const std::string::size_type colon = rest.find(':');
    const std::string            u     = rest.substr(0, colon),
                      seed  = colon == std::string::npos ? "" : rest.substr(colon + 1);
    metis_options.imbalance = u.empty() ? 0 : std::atoi(u.c_str());
    metis_options.seed      = seed.empty() ? -1 : std::atoi(seed.c_str());
  }
  if (N < 3 || passes < 0 || (precision != "single" && precision != "double") ||
      (kind != "metis" && kind != "vertex" && kind != "pord"))
    {
      std::cerr << "usage: factor_benchmark [N >= 3] [passes >= 0] [single | double] "
                   "[metis[:U:S] | vertex[:U:S] | pord]\n";
      return 2;
    }
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1); // PORD runs in MUMPS
  select_blas_kernels();

  // Unknowns: 3 per vertex, then 1 per edge (numbered as met).
  const auto                         vertex = [N](int i, int j) { return i + N * j; };
  std::map<std::pair<int, int>, int> edges;
  const int                          n_vertex_unknowns = 3 * N * N;
  const auto                         edge              = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    const auto it =
      edges.emplace(key, n_vertex_unknowns + static_cast<int>(edges.size()));
    return it.first->second;
  };
  std::vector<std::array<int, 12>> elements;
  for (int j = 0; j + 1 < N; ++j)
    for (int i = 0; i + 1 < N; ++i)
      {
        const int v00 = vertex(i, j), v10 = vertex(i + 1, j), v01 = vertex(i, j + 1),
                  v11 = vertex(i + 1, j + 1);
        // Alternating diagonals, as meshes/swing-N.geo.
        const bool               diagonal_up = (i + j) % 2 == 0;
        const std::array<int, 3> first       = {{v00, v10, diagonal_up ? v11 : v01}},
                                 second      = {{diagonal_up ? v00 : v10, v11, v01}};
        for (const auto &t : {first, second})
          {
            std::array<int, 12> dofs;
            for (int a = 0; a < 3; ++a)
              for (int d = 0; d < 3; ++d)
                dofs[3 * a + d] = 3 * t[a] + d;
            for (int a = 0; a < 3; ++a)
              dofs[9 + a] = edge(t[(a + 1) % 3], t[(a + 2) % 3]);
            elements.push_back(dofs);
          }
      }
  const int n = n_vertex_unknowns + static_cast<int>(edges.size());

  // The upper triangle: off-diagonal entries in [-1, 0), each diagonal entry 1 + 1e-4
  // times the absolute sum of its row (diagonally dominant, so SPD). The excess is about
  // the swinging sheet's mass term against its stiffness: with more (1 + the sum, say),
  // the factor's entries decay with the distance in the mesh to below single
  // precision's normal range at N = 321 (unflushed, those denormals made a factorisation
  // 14 times slower; solvers/flush_denormals.h now flushes them).
  std::map<std::pair<int, int>, double>  upper;
  std::mt19937                           random(2026);
  std::uniform_real_distribution<double> entry(-1., 0.);
  for (const auto &dofs : elements)
    for (int a = 0; a < 12; ++a)
      for (int b = a + 1; b < 12; ++b)
        upper[std::minmax(dofs[a], dofs[b])] += entry(random);
  std::vector<double> diagonal(n, 0.);
  for (const auto &[key, value] : upper)
    {
      diagonal[key.first] -= value;
      diagonal[key.second] -= value;
    }
  for (double &d : diagonal)
    d *= 1. + 1e-4;
  std::vector<int>    rows, columns;
  std::vector<double> values;
  for (int i = 0; i < n; ++i)
    upper[{i, i}] = diagonal[i];
  for (const auto &[key, value] : upper)
    {
      rows.push_back(key.first);
      columns.push_back(key.second);
      values.push_back(value);
    }

  const auto seconds_since = [](const std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
      .count();
  };
  auto                            start = std::chrono::steady_clock::now();
  std::optional<std::vector<int>> order;
  if (kind == "pord")
    order = fill_reducing_order(n, rows, columns, 4);
  else if (kind == "metis")
    order = nested_dissection_order(n, rows, columns, metis_options);
  else
    {
      // The vertices' graph (its upper triangle, each edge once), ordered; then each
      // vertex's displacements, each followed by the edges whose earlier vertex it is.
      std::vector<int> vertex_rows, vertex_columns;
      for (const auto &[key, dof] : edges)
        {
          vertex_rows.push_back(key.first);
          vertex_columns.push_back(key.second);
        }
      const auto vertex_order =
        nested_dissection_order(N * N, vertex_rows, vertex_columns, metis_options);
      if (vertex_order)
        {
          std::vector<int> position(N * N);
          for (int p = 0; p < N * N; ++p)
            position[(*vertex_order)[p]] = p;
          std::vector<std::vector<int>> edges_after(N * N);
          for (const auto &[key, dof] : edges)
            edges_after[position[key.first] < position[key.second] ? key.first
                                                                   : key.second]
              .push_back(dof);
          order.emplace();
          for (const int v : *vertex_order)
            {
              for (int d = 0; d < 3; ++d)
                order->push_back(3 * v + d);
              order->insert(order->end(), edges_after[v].begin(), edges_after[v].end());
            }
        }
    }
  const double ordering_seconds = seconds_since(start);
  if (!order)
    {
      std::cerr << "factor_benchmark: ordering failed\n";
      return 1;
    }
  const bool         single = precision == "single";
  SupernodalCholesky written_out(single), blas(single, /*blas_panels=*/true);
  start = std::chrono::steady_clock::now();
  written_out.analyse(n, rows, columns, *order);
  const double analysis_seconds = seconds_since(start);
  std::cout << "N = " << N << ": " << n << " unknowns, order " << order_name << " ("
            << ordering_seconds << " s, analysis " << analysis_seconds << " s), "
            << written_out.n_supernodes() << " supernodes, " << written_out.operations()
            << " operations, " << written_out.factor_entries()
            << " entries in the factor\n";
  if (passes == 0)
    return 0;
  blas.analyse(n, rows, columns, *order);
  if (!written_out.writes_out_panels())
    {
      std::cout
        << "this CPU has no AVX2 or FMA: the written-out panels do not run here\n";
      return 0;
    }

  // Each pass: a factorisation, then a solve with its factors, for each kind in turn;
  // and for the written-out panels both at once (factorize with the right-hand side,
  // then finish_solve), which must give the same bits.
  double              best_factor[2] = {1e30, 1e30}, best_solve[2] = {1e30, 1e30};
  double              best_fused = 1e30;
  std::vector<double> x[2];
  for (int pass = 0; pass < passes; ++pass)
    for (int which = 0; which < 2; ++which)
      {
        SupernodalCholesky &cholesky = which == 0 ? written_out : blas;
        start                        = std::chrono::steady_clock::now();
        if (!cholesky.factorize(values.data()))
          {
            std::cerr << "factor_benchmark: factorisation failed\n";
            return 1;
          }
        best_factor[which] = std::min(best_factor[which], seconds_since(start));
        x[which].assign(n, 1.);
        start = std::chrono::steady_clock::now();
        cholesky.solve(x[which].data());
        best_solve[which] = std::min(best_solve[which], seconds_since(start));
        if (which == 1)
          continue;
        // The same with the forward substitution done while factorising.
        const std::vector<double> ones(n, 1.);
        std::vector<double>       fused(n);
        start = std::chrono::steady_clock::now();
        cholesky.factorize(values.data(), ones.data());
        cholesky.finish_solve(fused.data());
        best_fused = std::min(best_fused, seconds_since(start));
        if (fused != x[0])
          {
            std::cerr << "factor_benchmark: finish_solve differs from solve\n";
            return 1;
          }
      }
  double difference = 0., size = 0.;
  for (int i = 0; i < n; ++i)
    {
      difference = std::max(difference, std::abs(x[0][i] - x[1][i]));
      size       = std::max(size, std::abs(x[1][i]));
    }
  std::cout << precision << "-precision, fastest of " << passes << " passes:\n"
            << "  factorisation: written-out panels " << best_factor[0] * 1e3
            << " ms, BLAS panels " << best_factor[1] * 1e3 << " ms, ratio "
            << best_factor[0] / best_factor[1] << "\n"
            << "  solve:         written-out panels " << best_solve[0] * 1e3
            << " ms, BLAS panels " << best_solve[1] * 1e3 << " ms, ratio "
            << best_solve[0] / best_solve[1] << " (solutions " << difference / size
            << " apart, relative)\n"
            << "  written-out, factorisation and solve: apart "
            << (best_factor[0] + best_solve[0]) * 1e3
            << " ms, the forward substitution within the factorisation "
            << best_fused * 1e3 << " ms, ratio "
            << best_fused / (best_factor[0] + best_solve[0]) << "\n";
  return 0;
}
