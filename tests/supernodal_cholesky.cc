// The multifrontal supernodal Cholesky (solvers/supernodal_cholesky.h) on SPD matrices
// with a known solution: b = A x* for a chosen x*, so the error of the solve is measured
// against x*, not against another solver.
// - A "shell-like" matrix: a triangulated nx x ny grid, 3 unknowns per vertex, coupled
//   along the edges by random symmetric 3x3 blocks, diagonally dominant (SPD), its
//   condition number about 1e3. Single-precision factors solve it to about
//   cond * 6e-8; three steps of iterative refinement in double to round-off;
//   double-precision factors to round-off at once. The solution does not depend on the
//   elimination order (natural, reversed, random).
// - Refactorisation with new values on the same analysis (2 A: x / 2); a second
//   analysis of the same object, on a larger matrix.
// - A matrix that is not positive definite: factorize() fails, and the object then
//   factorises the SPD one again.
// - Structure: a dense matrix is one supernode of n(n + 1)/2 + ... entries and n³/3
//   operations; a diagonal one n supernodes, solved to a few roundings in single.
// - The written-out panels (in blocks) and substitutions (solvers/panel_cholesky.h)
// against
//   LAPACK's and BLAS' (potrf, trsm, trsv, gemv): the same solution to round-off in both
//   precisions, on fronts of both kinds in one
//   factorisation; a negative pivot in a written-out panel fails.
// - FlushDenormals (the factorisations' guard) flushes a denormal product and restores
//   the flags.
// - An elimination order that is not a permutation is refused.
// - A Schur block (the last rows of the order left unfactorised): for the middle row of
//   a tridiagonal Toeplitz matrix (a, b) its Schur complement is a - 2 b² / p_k, p_k the
//   last pivot of the k x k chain on either side (p_1 = a, p_{j+1} = a - b² / p_j); on
//   the grid, the complement does not depend on the interior's order, and the solve
//   through it (its dense Cholesky factor applied by the caller) gives x* to round-off,
//   bit for bit the same with the forward substitution done while factorising.

#include "solvers/supernodal_cholesky.h"

#include "solvers/flush_denormals.h"

#include "test_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  // A sparse symmetric matrix: its upper triangle, each entry once.
  struct Upper
  {
    int                 n = 0;
    std::vector<int>    rows, columns;
    std::vector<double> values;

    std::vector<double>
    multiply(const std::vector<double> &x) const
    {
      std::vector<double> y(n, 0.);
      for (std::size_t k = 0; k < rows.size(); ++k)
        {
          y[rows[k]] += values[k] * x[columns[k]];
          if (rows[k] != columns[k])
            y[columns[k]] += values[k] * x[rows[k]];
        }
      return y;
    }
  };

  Upper
  grid_matrix(const int nx, const int ny, std::mt19937 &random)
  {
    Upper                                  a;
    const int                              n_vertices = nx * ny;
    std::uniform_real_distribution<double> weight(1., 100.), coupling(-0.1, 0.1);
    a.n = 3 * n_vertices;
    std::vector<double> diagonal(a.n, 1.);
    const auto          vertex = [&](int i, int j) { return i + nx * j; };
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        {
          std::vector<int> neighbours;
          if (i + 1 < nx)
            neighbours.push_back(vertex(i + 1, j));
          if (j + 1 < ny)
            neighbours.push_back(vertex(i, j + 1));
          if (i + 1 < nx && j + 1 < ny)
            neighbours.push_back(vertex(i + 1, j + 1));
          const int v = vertex(i, j);
          for (int w : neighbours)
            {
              const double e = weight(random);
              for (int p = 0; p < 3; ++p)
                for (int q = 0; q < 3; ++q)
                  {
                    // -e I + e R, R random with entries in [-0.1, 0.1]
                    const double value = e * ((p == q ? -1. : 0.) + coupling(random));
                    a.rows.push_back(3 * v + p);
                    a.columns.push_back(3 * w + q);
                    a.values.push_back(value);
                    diagonal[3 * v + p] += std::abs(value);
                    diagonal[3 * w + q] += std::abs(value);
                  }
            }
        }
    for (int i = 0; i < a.n; ++i)
      {
        a.rows.push_back(i);
        a.columns.push_back(i);
        a.values.push_back(diagonal[i]);
      }
    return a;
  }

  // x = S⁻¹ x for the lower triangle of an n x n SPD S (column-major), by a dense
  // Cholesky factorisation written out here.
  void
  dense_solve(const int n, std::vector<double> s, double *x)
  {
    const auto at = [&](int i, int j) -> double & { return s[i + j * n]; };
    for (int j = 0; j < n; ++j)
      {
        for (int k = 0; k < j; ++k)
          for (int i = j; i < n; ++i)
            at(i, j) -= at(i, k) * at(j, k);
        const double pivot = std::sqrt(at(j, j));
        for (int i = j; i < n; ++i)
          at(i, j) /= pivot;
      }
    for (int j = 0; j < n; ++j)
      {
        x[j] /= at(j, j);
        for (int i = j + 1; i < n; ++i)
          x[i] -= at(i, j) * x[j];
      }
    for (int j = n - 1; j >= 0; --j)
      {
        for (int i = j + 1; i < n; ++i)
          x[j] -= at(i, j) * x[i];
        x[j] /= at(j, j);
      }
  }

  double
  relative_error(const std::vector<double> &x, const std::vector<double> &exact)
  {
    double difference = 0., norm = 0.;
    for (std::size_t i = 0; i < x.size(); ++i)
      {
        difference += (x[i] - exact[i]) * (x[i] - exact[i]);
        norm += exact[i] * exact[i];
      }
    return std::sqrt(difference / norm);
  }

  // x = A⁻¹ b with the factors, then `refinements` steps x += A⁻¹ (b - A x) in double.
  std::vector<double>
  solve(SupernodalCholesky        &cholesky,
        const Upper               &a,
        const std::vector<double> &b,
        const int                  refinements = 0)
  {
    std::vector<double> x = b;
    cholesky.solve(x.data());
    for (int step = 0; step < refinements; ++step)
      {
        std::vector<double> residual = a.multiply(x);
        for (int i = 0; i < a.n; ++i)
          residual[i] = b[i] - residual[i];
        cholesky.solve(residual.data());
        for (int i = 0; i < a.n; ++i)
          x[i] += residual[i];
      }
    return x;
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment         environment(argc, argv);
  ConditionalOStream &out = environment.pcout;
  std::mt19937        random(20261125);

  const Upper                            a = grid_matrix(30, 20, random);
  std::uniform_real_distribution<double> entry(-1., 1.);
  std::vector<double>                    exact(a.n);
  for (double &x : exact)
    x = entry(random);
  const std::vector<double> b = a.multiply(exact);

  std::vector<int> natural(a.n), reversed(a.n), shuffled(a.n);
  for (int i = 0; i < a.n; ++i)
    natural[i] = reversed[a.n - 1 - i] = shuffled[i] = i;
  std::shuffle(shuffled.begin(), shuffled.end(), random);
  const std::pair<const char *, const std::vector<int> *> orders[] = {
    {"natural", &natural}, {"reversed", &reversed}, {"random", &shuffled}};
  for (const auto &[name, order] : orders)
    {
      SupernodalCholesky cholesky;
      cholesky.analyse(a.n, a.rows, a.columns, *order);
      const std::string what = std::string("grid, 1,800 unknowns, ") + name + " order";
      check(out,
            cholesky.factorize(a.values.data()),
            what + ": factorises (" + std::to_string(cholesky.n_supernodes()) +
              " supernodes)");
      check_below(out,
                  what + ": relative error, single precision",
                  relative_error(solve(cholesky, a, b), exact),
                  1e-4);
      check_below(out,
                  what + ": relative error after 3 refinement steps",
                  relative_error(solve(cholesky, a, b, 3), exact),
                  1e-12);

      // Double-precision factors: round-off in double without refinement.
      SupernodalCholesky in_double(/*single_precision=*/false);
      in_double.analyse(a.n, a.rows, a.columns, *order);
      check(out, in_double.factorize(a.values.data()), what + ", double: factorises");
      check_below(out,
                  what + ", double: relative error",
                  relative_error(solve(in_double, a, b), exact),
                  1e-13);
    }

  {
    SupernodalCholesky cholesky;
    cholesky.analyse(a.n, a.rows, a.columns, shuffled);
    Upper doubled = a;
    for (double &value : doubled.values)
      value *= 2.;
    check(out, cholesky.factorize(doubled.values.data()), "2 A factorises");
    std::vector<double> half = exact;
    for (double &x : half)
      x /= 2.;
    check_below(out,
                "2 A x = b: relative error against x* / 2 (3 refinement steps)",
                relative_error(solve(cholesky, doubled, b, 3), half),
                1e-12);

    Upper indefinite = a;
    for (std::size_t k = 0; k < indefinite.values.size(); ++k)
      if (indefinite.rows[k] == indefinite.columns[k] && indefinite.rows[k] == a.n / 2)
        indefinite.values[k] = -1.;
    check(out,
          !cholesky.factorize(indefinite.values.data()),
          "a negative diagonal entry: factorize() fails");
    check(out,
          cholesky.factorize(a.values.data()) &&
            relative_error(solve(cholesky, a, b, 3), exact) < 1e-12,
          "then A factorises and solves again");
    SupernodalCholesky in_double(/*single_precision=*/false);
    in_double.analyse(a.n, a.rows, a.columns, shuffled);
    check(out,
          !in_double.factorize(indefinite.values.data()) &&
            in_double.factorize(a.values.data()) &&
            relative_error(solve(in_double, a, b), exact) < 1e-13,
          "double: a negative diagonal entry fails, then A factorises and solves");
  }

  {
    // A second analysis on the same object (its numeric arrays are sized by the first
    // factorisation after each analysis): a small grid factorised, then the large one.
    std::mt19937        other(7);
    const Upper         small = grid_matrix(6, 5, other);
    std::vector<int>    small_order(small.n);
    std::vector<double> small_exact(small.n, 1.);
    for (int i = 0; i < small.n; ++i)
      small_order[i] = i;
    SupernodalCholesky cholesky;
    cholesky.analyse(small.n, small.rows, small.columns, small_order);
    check(out,
          cholesky.factorize(small.values.data()) &&
            relative_error(solve(cholesky, small, small.multiply(small_exact), 3),
                           small_exact) < 1e-12,
          "re-analysis: the 6 x 5 grid factorises and solves");
    cholesky.analyse(a.n, a.rows, a.columns, shuffled);
    check(out,
          cholesky.factorize(a.values.data()) &&
            relative_error(solve(cholesky, a, b, 3), exact) < 1e-12,
          "re-analysis: then the 30 x 20 grid on the same object");
  }

  {
    // Dense SPD: J + n I (J all ones), solution by Sherman-Morrison not needed: b = A x*.
    const int n = 40;
    Upper     dense;
    dense.n = n;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i <= j; ++i)
        {
          dense.rows.push_back(i);
          dense.columns.push_back(j);
          dense.values.push_back(i == j ? n + 1. : 1.);
        }
    SupernodalCholesky cholesky;
    cholesky.analyse(n,
                     dense.rows,
                     dense.columns,
                     std::vector<int>(natural.begin(), natural.begin() + n));
    check_equal(out, "dense 40 x 40: supernodes", cholesky.n_supernodes(), 1);
    check_equal(out,
                "dense 40 x 40: operations",
                cholesky.operations(),
                40. * 40. * 40. / 3.);
    check(out, cholesky.factorize(dense.values.data()), "dense 40 x 40 factorises");
    std::vector<double> x_dense(n);
    for (int i = 0; i < n; ++i)
      x_dense[i] = i - 20.;
    check_below(out,
                "dense 40 x 40: relative error, single precision",
                relative_error(solve(cholesky, dense, dense.multiply(x_dense)), x_dense),
                1e-6);

    Upper diagonal;
    diagonal.n = 100;
    for (int i = 0; i < 100; ++i)
      {
        diagonal.rows.push_back(i);
        diagonal.columns.push_back(i);
        diagonal.values.push_back(0.25 * (i + 1));
      }
    SupernodalCholesky separate;
    separate.analyse(100,
                     diagonal.rows,
                     diagonal.columns,
                     std::vector<int>(natural.begin(), natural.begin() + 100));
    check_equal(out, "diagonal 100 x 100: supernodes", separate.n_supernodes(), 100);
    check(out, separate.factorize(diagonal.values.data()), "diagonal factorises");
    std::vector<double>       ones(100, 1.);
    const std::vector<double> x_diagonal =
      solve(separate, diagonal, diagonal.multiply(ones));
    check_below(out, "diagonal: relative error", relative_error(x_diagonal, ones), 3e-7);
  }

  {
    // The middle row of a tridiagonal Toeplitz matrix as the Schur block.
    const int    k = 10, n = 2 * k + 1;
    const double diagonal = 4., off = -1.;
    Upper        t;
    t.n = n;
    for (int i = 0; i < n; ++i)
      for (int j = i; j <= std::min(i + 1, n - 1); ++j)
        {
          t.rows.push_back(i);
          t.columns.push_back(j);
          t.values.push_back(i == j ? diagonal : off);
        }
    std::vector<int> order;
    for (int i = 0; i < n; ++i)
      if (i != k)
        order.push_back(i);
    order.push_back(k);
    SupernodalCholesky cholesky(/*single_precision=*/false);
    cholesky.analyse(n, t.rows, t.columns, order, {}, 1);
    double pivot = diagonal;
    for (int j = 1; j < k; ++j)
      pivot = diagonal - off * off / pivot;
    double schur = 0.;
    check(out,
          cholesky.factorize(t.values.data()),
          "tridiagonal, Schur block: factorises");
    cholesky.add_schur_complement(&schur);
    check_below(out,
                "tridiagonal: Schur complement of the middle row against a - 2 b² / p_k",
                std::abs(schur - (diagonal - 2. * off * off / pivot)) / schur,
                1e-15);

    // The grid with the last 60 rows of the random order as the Schur block.
    const int           m = 60;
    std::vector<double> schurs[2];
    const auto          interior = [&](const bool reverse) {
      std::vector<int> order = shuffled;
      if (reverse)
        std::reverse(order.begin(), order.end() - m);
      return order;
    };
    for (const bool reverse : {false, true})
      {
        SupernodalCholesky in_double(/*single_precision=*/false);
        in_double.analyse(a.n, a.rows, a.columns, interior(reverse), {}, m);
        check(out,
              in_double.factorize(a.values.data()),
              std::string("grid, Schur block of 60 rows, ") +
                (reverse ? "interior reversed" : "random order") + ": factorises");
        schurs[reverse].assign(m * m, 0.);
        in_double.add_schur_complement(schurs[reverse].data());
        std::vector<double> x = b;
        in_double.solve(x.data(),
                        [&](double *rhs) { dense_solve(m, schurs[reverse], rhs); });
        check_below(out,
                    std::string("grid, Schur block, ") +
                      (reverse ? "interior reversed" : "random order") +
                      ": relative error of the solve through it",
                    relative_error(x, exact),
                    1e-13);
        // The forward substitution through the interior done with the factorisation,
        // then finish_solve() through the Schur block: solve()'s bits.
        std::vector<double> fused(a.n, 0.);
        const auto          schur_solve = [&](double *rhs) {
          dense_solve(m, schurs[reverse], rhs);
        };
        const bool factorised = in_double.factorize(a.values.data(), b.data());
        in_double.finish_solve(fused.data(), schur_solve);
        check(out,
              factorised && fused == x,
              std::string("grid, Schur block, ") +
                (reverse ? "interior reversed" : "random order") +
                ": factorize(A, b) and finish_solve() give solve()'s bits");
      }
    double difference = 0., norm = 0.;
    for (int j = 0; j < m; ++j)
      for (int i = j; i < m; ++i)
        {
          difference =
            std::max(difference, std::abs(schurs[0][i + j * m] - schurs[1][i + j * m]));
          norm = std::max(norm, std::abs(schurs[0][i + j * m]));
        }
    check_below(out,
                "grid: the Schur complement does not depend on the interior's order",
                difference / norm,
                1e-13);
  }

  {
    // The written-out panels (dense::panel_cholesky, in blocks of 64 columns with syrk
    // and gemm between them) and substitutions (dense::panel_forward_solve and
    // panel_backward_solve) against LAPACK's potrf and BLAS' trsm, trsv and gemv: the
    // same solution up to round-off, in either precision, on the grid (in each order one
    // supernode has 105 to 1,413 columns, so several blocks, and the others fewer than
    // 64; single precision measured 4.9 to 6.5e-7 apart).
    // Two kinds of factorisation of the grid in one order: both factorise, their
    // solutions agree to round-off, and the first's is accurate (labels: those three).
    const auto compare_kinds = [&](SupernodalCholesky               &first,
                                   SupernodalCholesky               &second,
                                   const std::vector<int>           &order,
                                   const bool                        single,
                                   const std::string                &what,
                                   const std::array<std::string, 3> &labels) {
      first.analyse(a.n, a.rows, a.columns, order);
      second.analyse(a.n, a.rows, a.columns, order);
      check(out,
            first.factorize(a.values.data()) && second.factorize(a.values.data()),
            what + labels[0]);
      const std::vector<double> x_first  = solve(first, a, b),
                                x_second = solve(second, a, b);
      check_below(out,
                  what + labels[1],
                  relative_error(x_first, x_second),
                  single ? 2e-6 : 1e-13);
      check_below(out,
                  what + labels[2],
                  relative_error(x_first, exact),
                  single ? 1e-4 : 1e-13);
    };
    SupernodalCholesky probe;
    out << (probe.writes_out_panels() ? "this CPU runs the written-out panels (AVX2, FMA)"
                                      : "this CPU has no AVX2 or FMA: BLAS panels only")
        << std::endl;
    for (const bool single : {true, false})
      for (const auto &[name, order] : orders)
        {
          SupernodalCholesky written_out(single), blas(single, /*blas_panels=*/true);
          const std::string  what = std::string("grid, ") + name + " order, " +
                                   (single ? "single" : "double") + ": ";
          compare_kinds(written_out,
                        blas,
                        *order,
                        single,
                        what,
                        {{"both kinds of panels factorise",
                          "written-out panels' solution against BLAS panels'",
                          "written-out panels' relative error"}});
          // The forward substitution done with the factorisation, then finish_solve():
          // the same operations in the same order as solve(), so the same bits.
          for (SupernodalCholesky *kind : {&written_out, &blas})
            {
              std::vector<double> plain = b, fused(a.n, 0.);
              kind->factorize(a.values.data());
              kind->solve(plain.data());
              const bool factorised = kind->factorize(a.values.data(), b.data());
              kind->finish_solve(fused.data());
              check(out,
                    factorised && fused == plain,
                    what + (kind == &blas ? "BLAS" : "written-out") +
                      " panels: factorize(A, b) and finish_solve() give solve()'s "
                      "bits");
            }
        }
    // The fronts' updates for their parents by gemm on the whole square (the default
    // with OpenBLAS' AVX-512 kernels) against syrk on the lower triangle: the same
    // solution up to round-off.
    out << "this BLAS runs "
        << (probe.updates_square() ? "square updates (AVX-512 kernels)" : "syrk updates")
        << " by default" << std::endl;
    for (const bool single : {true, false})
      for (const auto &[name, order] : orders)
        {
          SupernodalCholesky square(single), lower(single);
          square.set_square_updates(true);
          lower.set_square_updates(false);
          compare_kinds(square,
                        lower,
                        *order,
                        single,
                        std::string("grid, ") + name + " order, " +
                          (single ? "single" : "double") + ": ",
                        {{"square and lower-triangle updates factorise",
                          "square updates' solution against syrk's",
                          "square updates' relative error"}});
        }
    {
      // finish_solve() only right after a factorize() with a right-hand side.
      SupernodalCholesky  cholesky;
      std::vector<double> x(a.n), other = b;
      cholesky.analyse(a.n, a.rows, a.columns, shuffled);
      const auto refused = [&] {
        try
          {
            cholesky.finish_solve(x.data());
          }
        catch (const std::logic_error &)
          {
            return true;
          }
        return false;
      };
      cholesky.factorize(a.values.data());
      const bool without_rhs = refused();
      cholesky.factorize(a.values.data(), b.data());
      cholesky.finish_solve(x.data());
      const bool twice = refused();
      cholesky.factorize(a.values.data(), b.data());
      cholesky.solve(other.data());
      const bool after_solve = refused();
      check(out,
            without_rhs && twice && after_solve,
            "finish_solve() is refused without a right-hand side, a second time, and "
            "after a solve() of another one");
    }
    Upper indefinite = a;
    for (std::size_t k = 0; k < indefinite.values.size(); ++k)
      if (indefinite.rows[k] == indefinite.columns[k] && indefinite.rows[k] == 0)
        indefinite.values[k] = -1.;
    SupernodalCholesky cholesky;
    cholesky.analyse(a.n, a.rows, a.columns, natural);
    check(out,
          !cholesky.factorize(indefinite.values.data()) &&
            cholesky.factorize(a.values.data()) &&
            relative_error(solve(cholesky, a, b, 3), exact) < 1e-12,
          "a negative first pivot (a written-out panel, natural order) fails, then A "
          "factorises and solves");
  }

  {
    // Denormals flushed inside FlushDenormals (a product of 1e-40, below float's
    // normal range, is zero) and not after it (the flags restored).
    volatile float small = 1e-30f, smaller = 1e-10f;
    const float    before = small * smaller;
    float          inside = 0.f;
    {
      const FlushDenormals flush;
      inside = small * smaller;
    }
    const float after = small * smaller;
    check(out,
          before > 0.f && inside == 0.f && after == before,
          "1e-30f * 1e-10f: a denormal before, zero inside FlushDenormals, the same "
          "denormal after");
  }

  {
    SupernodalCholesky cholesky;
    std::vector<int>   repeated = natural;
    repeated[1]                 = 0;
    bool refused                = false;
    try
      {
        cholesky.analyse(a.n, a.rows, a.columns, repeated);
      }
    catch (const std::invalid_argument &)
      {
        refused = true;
      }
    check(out, refused, "an elimination order that repeats a row is refused");
  }
  return finish_tally(out);
}
