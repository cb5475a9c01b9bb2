// Benchmark (not a ctest test: it asserts nothing and prints timings): one factorisation
// and one solve by the supernodal Cholesky (solvers/supernodal_cholesky.h) with its
// written-out panels and substitutions (solvers/panel_cholesky.h) against the same with
// LAPACK's potrf, BLAS' trsm and (in the solve) BLAS' trsv and gemv, in
// single (default) or double precision, on the pattern of the swinging sheet's tangent:
// tests/sheet_pattern.h (the cost does not depend on the values), in a fill-reducing
// order. The two are timed in alternating passes and each one's
// fastest pass is reported with their ratio, measured in this one run.
//
//   build/tests/factor_benchmark [N, default 81] [passes, default 40] [single | double]
//                                [order, default metis]
//
// order: `metis` (METIS' nested dissection of the unknowns' graph), `metis:U:S` (with
// UFACTOR U and seed S, either may be empty), `vertex:U:S` (METIS on the graph of the N²
// vertices: vertex_nested_dissection_order), or `pord`
// (MUMPS' PORD, as clothsim orders on one rank). The order's operations, and the time
// taken to order and analyse, are printed first; with 0 passes nothing else.

#include <deal.II/base/mpi.h>

#include "solvers/blas_kernels.h"
#include "solvers/fill_reducing_order.h"
#include "solvers/supernodal_cholesky.h"
#include "solvers/vertex_order.h"

#include "sheet_pattern.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <optional>
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

  const test::SheetPattern   sheet = test::sheet_pattern(N, 2026);
  const int                  n     = sheet.n;
  const std::vector<int>    &rows = sheet.rows, &columns = sheet.columns;
  const std::vector<double> &values = sheet.values;

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
    order = vertex_nested_dissection_order(
      n, rows, columns, sheet.vertices, sheet.n_vertices, metis_options);
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
