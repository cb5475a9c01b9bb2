// The direct MUMPS LDLᵀ (solvers/mumps_factorization.h) on tridiagonal Toeplitz matrices
// T = a I + b (shift up + shift down), whose eigenvalues are known in closed form,
//   λ_j = a + 2 b cos(j π / (n + 1)),  j = 1 .. n,
// on one rank or distributed over several: the solution of T x = T x* to round-off, the
// inertia (negative pivots = negative eigenvalues), a refactorisation with new values on
// the same sparsity, the definite factorisation (SYM = 1) telling an indefinite matrix by
// failing or by negative pivots, and a clear failure on a singular matrix.
// Single-precision factors: their plain solve is accurate to single precision only (so
// they are single), refinement in double brings it to the tolerance asked, and a matrix
// too ill-conditioned for them fails with a message instead of a wrong answer.
// On one rank the single-precision definite factorisation is SupernodalCholesky's (MUMPS
// orders): the same checks hold for it.
// Rows holding only their diagonal are solved outside MUMPS: the solution and the inertia
// are the same, and the definite factorisation refuses a negative one.
// On several ranks the definite factorisation is SubdomainCholesky's (each rank's rows
// by its own Cholesky, the interface by a dense Schur complement): the same checks, and
// a 2D five-point matrix whose interface between the ranks is a whole grid line, solved
// to round-off in double and refined to 1e-12 in single precision, bit for bit the same
// with the forward substitution done while factorising.

#include <deal.II/base/mpi.h>

#include "app/mpi_session.h"
#include "solvers/blas_kernels.h"
#include "solvers/mumps_factorization.h"

#include <Epetra_MpiComm.h>

#include <cmath>
#include <iostream>
#include <sstream>

using namespace dealii;
using namespace clothsim;

namespace
{
  unsigned int failures = 0;

  void
  check(const bool ok, const std::string &what, const int rank)
  {
    if (rank == 0)
      std::cout << (ok ? "ok      " : "FAILED  ") << what << std::endl;
    if (!ok)
      ++failures;
  }

  std::string
  sci(const double value)
  {
    std::ostringstream text;
    text << value;
    return text.str();
  }

  // T = a I + b (shift up + shift down) on `map`; `zero_row` (if >= 0) left empty but for
  // a structural zero on the diagonal (a singular matrix with the same sparsity).
  Epetra_CrsMatrix
  toeplitz(const Epetra_Map &map, const double a, const double b, const int zero_row = -1)
  {
    Epetra_CrsMatrix matrix(Copy, map, 3);
    const int        n = map.NumGlobalElements();
    for (int local = 0; local < map.NumMyElements(); ++local)
      {
        const int i = map.GID(local);
        for (int j = std::max(i - 1, 0); j <= std::min(i + 1, n - 1); ++j)
          {
            double value = (i == j ? a : b);
            if (i == zero_row || j == zero_row)
              value = 0.;
            matrix.InsertGlobalValues(i, 1, &value, &j);
          }
      }
    matrix.FillComplete();
    return matrix;
  }

  // Every third row (i % 3 == 2) decoupled, only a diagonal: 4, or -2 where i % 6 == 5
  // if `negative`; the other rows a tridiagonal T = a I + b (shift up + shift down) in
  // their order (their own chain, skipping the decoupled rows). MUMPS gets only the chain
  // (solvers/mumps_factorization.h); with `all_decoupled` the matrix is only the
  // diagonal.
  Epetra_CrsMatrix
  interleaved(const Epetra_Map &map,
              const double      a,
              const double      b,
              const bool        negative,
              const bool        all_decoupled = false)
  {
    Epetra_CrsMatrix matrix(Copy, map, 3);
    const int        n         = map.NumGlobalElements();
    const auto       decoupled = [&](const int i) { return all_decoupled || i % 3 == 2; };
    for (int local = 0; local < map.NumMyElements(); ++local)
      {
        const int i = map.GID(local);
        if (decoupled(i))
          {
            const double value = negative && i % 6 == 5 ? -2. : 4.;
            matrix.InsertGlobalValues(i, 1, &value, &i);
            continue;
          }
        matrix.InsertGlobalValues(i, 1, &a, &i);
        const int previous = decoupled(i - 1) ? i - 2 : i - 1;
        const int next     = decoupled(i + 1) ? i + 2 : i + 1;
        if (previous >= 0)
          matrix.InsertGlobalValues(i, 1, &b, &previous);
        if (next < n)
          matrix.InsertGlobalValues(i, 1, &b, &next);
      }
    matrix.FillComplete();
    return matrix;
  }

  // (4 + shift) I minus the five-point grid's adjacency on an nx x ny grid, row i + nx j
  // for vertex (i, j): SPD for shift > 0, its eigenvalues shift + 4 - 2 cos(i π / (nx +
  // 1)) - 2 cos(j π / (ny + 1)).
  Epetra_CrsMatrix
  five_point(const Epetra_Map &map, const int nx, const double shift)
  {
    Epetra_CrsMatrix matrix(Copy, map, 5);
    const int        n = map.NumGlobalElements();
    for (int local = 0; local < map.NumMyElements(); ++local)
      {
        const int    row      = map.GID(local);
        const double diagonal = 4. + shift, off = -1.;
        matrix.InsertGlobalValues(row, 1, &diagonal, &row);
        for (const int column : {row - nx, row + nx})
          if (column >= 0 && column < n)
            matrix.InsertGlobalValues(row, 1, &off, &column);
        for (const int column : {row - 1, row + 1})
          if (column / nx == row / nx && column >= 0)
            matrix.InsertGlobalValues(row, 1, &off, &column);
      }
    matrix.FillComplete();
    return matrix;
  }

  int
  negative_eigenvalues(const int n, const double a, const double b)
  {
    int count = 0;
    for (int j = 1; j <= n; ++j)
      if (a + 2. * b * std::cos(j * M_PI / (n + 1)) < 0.)
        ++count;
    return count;
  }

  // Relative error of the solution of T x = T x* for x*_i = sin(i + 1); refined against
  // T to `tolerance` if given (single-precision factors).
  double
  solution_error(MumpsFactorization     &mumps,
                 const Epetra_CrsMatrix &matrix,
                 const double            tolerance = -1.)
  {
    const Epetra_Map &map = matrix.RowMap();
    Epetra_Vector     exact(map), rhs(map), x(map);
    for (int local = 0; local < map.NumMyElements(); ++local)
      exact[local] = std::sin(map.GID(local) + 1.);
    matrix.Multiply(false, exact, rhs);
    if (!mumps.solve(rhs, x, tolerance > 0. ? &matrix : nullptr, tolerance))
      return 1e300;
    x.Update(-1., exact, 1.);
    double error = 0., norm = 0.;
    x.Norm2(&error);
    exact.Norm2(&norm);
    return error / norm;
  }

  // Whether factorize(matrix, &b) then solve(b) (the forward substitution done while
  // factorising) gives, bit for bit, what factorize(matrix) then solve(b) gives, b = T x*
  // as above; refined against T to `tolerance` if given.
  bool
  forwarded_solve_same_bits(MumpsFactorization     &mumps,
                            const Epetra_CrsMatrix &matrix,
                            const double            tolerance = -1.)
  {
    const Epetra_Map &map = matrix.RowMap();
    Epetra_Vector     exact(map), rhs(map), plain(map), fused(map);
    for (int local = 0; local < map.NumMyElements(); ++local)
      exact[local] = std::sin(map.GID(local) + 1.);
    matrix.Multiply(false, exact, rhs);
    const Epetra_CrsMatrix *refine = tolerance > 0. ? &matrix : nullptr;
    const bool              ok =
      mumps.factorize(matrix) && mumps.solve(rhs, plain, refine, tolerance) &&
      mumps.factorize(matrix, &rhs) && mumps.solve(rhs, fused, refine, tolerance);
    bool same = ok;
    for (int local = 0; local < map.NumMyElements(); ++local)
      same = same && plain[local] == fused[local];
    int all = same ? 1 : 0, everywhere = 0;
    MPI_Allreduce(&all, &everywhere, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return everywhere == 1;
  }
} // namespace


int
main(int argc, char **argv)
{
  clothsim::MpiSession mpi(argc, argv);
  clothsim::select_blas_kernels(); // as the clothsim executable does
  const int      rank = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  Epetra_MpiComm comm(MPI_COMM_WORLD);
  const int      n = 1000;
  Epetra_Map     map(n, 0, comm);

  {
    // Indefinite: a = 0.3, b = 1 has eigenvalues on both sides of zero.
    const Epetra_CrsMatrix matrix = toeplitz(map, 0.3, 1.);
    MumpsFactorization mumps(MPI_COMM_WORLD, MumpsFactorization::Symmetry::indefinite);
    check(mumps.factorize(matrix), "indefinite T factorises", rank);
    const double error = solution_error(mumps, matrix);
    check(error < 1e-10, "indefinite T: relative error " + sci(error), rank);
    const int expected = negative_eigenvalues(n, 0.3, 1.);
    check(mumps.negative_pivots() == expected,
          "inertia: " + std::to_string(mumps.negative_pivots()) +
            " negative pivots, negative eigenvalues " + std::to_string(expected),
          rank);

    // New values, same sparsity: the analysis is kept.
    const Epetra_CrsMatrix shifted = toeplitz(map, 2.5, -1.);
    check(mumps.factorize(shifted), "refactorisation with new values", rank);
    const double shifted_error = solution_error(mumps, shifted);
    check(shifted_error < 1e-10,
          "refactorised T: relative error " + sci(shifted_error),
          rank);
    check(mumps.negative_pivots() == 0, "positive definite T: no negative pivot", rank);
  }
  {
    const Epetra_CrsMatrix matrix = toeplitz(map, 2.5, -1.);
    MumpsFactorization     mumps(MPI_COMM_WORLD,
                             MumpsFactorization::Symmetry::positive_definite);
    check(mumps.factorize(matrix), "SPD T factorises (SYM = 1)", rank);
    const double error = solution_error(mumps, matrix);
    check(error < 1e-10, "SPD T: relative error " + sci(error), rank);
  }
  {
    // The definite factorisation of an indefinite T tells (LinearSolver then switches to
    // the pivoting one): it fails, or it counts negative pivots.
    const Epetra_CrsMatrix matrix = toeplitz(map, 0.3, 1.);
    MumpsFactorization     mumps(MPI_COMM_WORLD,
                             MumpsFactorization::Symmetry::positive_definite);
    const bool             factorized = mumps.factorize(matrix);
    check(!factorized || mumps.negative_pivots() > 0,
          "SYM = 1 on indefinite T tells: " +
            (factorized ? std::to_string(mumps.negative_pivots()) + " negative pivots"
                        : mumps.failure()),
          rank);
  }
  {
    const Epetra_CrsMatrix matrix = toeplitz(map, 0.3, 1., n / 2);
    MumpsFactorization mumps(MPI_COMM_WORLD, MumpsFactorization::Symmetry::indefinite);
    const bool         factorized = mumps.factorize(matrix);
    check(!factorized && mumps.failure().find("singular") != std::string::npos,
          "singular T fails: " + mumps.failure(),
          rank);
  }
  {
    // Single precision (ε = 6e-8): T with condition number 9 solves to about 1e-7 without
    // refinement; refined against T to 1e-12, to round-off in double.
    using Precision               = MumpsFactorization::Precision;
    const Epetra_CrsMatrix matrix = toeplitz(map, 2.5, -1.);
    MumpsFactorization     mumps(MPI_COMM_WORLD,
                             MumpsFactorization::Symmetry::positive_definite,
                             5,
                             Precision::single_refined);
    check(mumps.factorize(matrix), "single-precision SPD T factorises", rank);
    const double plain = solution_error(mumps, matrix);
    check(plain > 1e-12 && plain < 1e-5,
          "single precision, not refined: relative error " + sci(plain) +
            " (single, not double)",
          rank);
    const double refined = solution_error(mumps, matrix, 1e-12);
    check(refined < 1e-11 && mumps.refinements() >= 1 && mumps.refinements() <= 3,
          "single precision refined to 1e-12: relative error " + sci(refined) + " in " +
            std::to_string(mumps.refinements()) + " refinement steps",
          rank);

    // The definite single-precision factorisation of an indefinite T tells too (on one
    // rank it is SupernodalCholesky's, which fails at the first pivot that is not
    // positive); so does the next SPD one on the same factorisation object.
    const Epetra_CrsMatrix indefinite = toeplitz(map, 0.3, 1.);
    {
      MumpsFactorization definite(MPI_COMM_WORLD,
                                  MumpsFactorization::Symmetry::positive_definite,
                                  5,
                                  Precision::single_refined);
      const bool         factorized = definite.factorize(indefinite);
      check(!factorized || definite.negative_pivots() > 0,
            "single precision, SYM = 1 on indefinite T tells: " +
              (factorized
                 ? std::to_string(definite.negative_pivots()) + " negative pivots"
                 : definite.failure()),
            rank);
      check(definite.factorize(matrix) && solution_error(definite, matrix, 1e-12) < 1e-11,
            "single precision, SYM = 1: then SPD T factorises and solves",
            rank);
    }
    MumpsFactorization pivoting(MPI_COMM_WORLD,
                                MumpsFactorization::Symmetry::indefinite,
                                5,
                                Precision::single_refined);
    check(pivoting.factorize(indefinite),
          "single-precision indefinite T factorises",
          rank);
    const double indefinite_error = solution_error(pivoting, indefinite, 1e-12);
    check(indefinite_error < 1e-10 &&
            pivoting.negative_pivots() == negative_eigenvalues(n, 0.3, 1.),
          "single precision, indefinite, refined: relative error " +
            sci(indefinite_error) + ", " + std::to_string(pivoting.negative_pivots()) +
            " negative pivots",
          rank);

    // A tolerance below double round-off (1e-20): the refinement stalls, and after its
    // 10 steps the solve fails and says what to do instead of returning as solved.
    const double unreachable = solution_error(mumps, matrix, 1e-20);
    check(unreachable > 1e299 &&
            mumps.failure().find("Factor precision") != std::string::npos &&
            mumps.refinements() == 10,
          "single precision refined to 1e-20 fails after " +
            std::to_string(mumps.refinements()) + " steps: " + mumps.failure(),
          rank);
  }
  {
    // Decoupled rows are solved outside MUMPS: the solution, and the inertia counting
    // their negative diagonals (the chain's 667 rows and 166 of the 333 decoupled).
    const int              chain = n - n / 3, negative_diagonals = (n + 1) / 6;
    const Epetra_CrsMatrix matrix = interleaved(map, 0.3, 1., true);
    MumpsFactorization mumps(MPI_COMM_WORLD, MumpsFactorization::Symmetry::indefinite);
    check(mumps.factorize(matrix), "interleaved decoupled rows: factorises", rank);
    const double error = solution_error(mumps, matrix);
    check(error < 1e-10,
          "interleaved decoupled rows: relative error " + sci(error),
          rank);
    const int expected = negative_eigenvalues(chain, 0.3, 1.) + negative_diagonals;
    check(mumps.negative_pivots() == expected,
          "interleaved decoupled rows: " + std::to_string(mumps.negative_pivots()) +
            " negative pivots, negative eigenvalues " + std::to_string(expected),
          rank);

    // The definite factorisation tells a negative decoupled diagonal: it fails (one
    // rank: refused before MUMPS) or counts negative pivots (several: MUMPS sees it).
    const Epetra_CrsMatrix spd_chain = interleaved(map, 2.5, -1., true);
    MumpsFactorization     definite(MPI_COMM_WORLD,
                                MumpsFactorization::Symmetry::positive_definite);
    const bool             factorized = definite.factorize(spd_chain);
    const bool one_rank = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1;
    check(one_rank ? !factorized && definite.failure().find("not positive definite") !=
                                      std::string::npos
                   : !factorized || definite.negative_pivots() > 0,
          "SYM = 1, a negative decoupled diagonal tells: " +
            (factorized ? std::to_string(definite.negative_pivots()) + " negative pivots"
                        : definite.failure()),
          rank);

    // Positive definite, single precision, refined against the matrix.
    const Epetra_CrsMatrix spd = interleaved(map, 2.5, -1., false);
    MumpsFactorization     single(MPI_COMM_WORLD,
                              MumpsFactorization::Symmetry::positive_definite,
                              5,
                              MumpsFactorization::Precision::single_refined);
    check(single.factorize(spd), "interleaved SPD, single precision: factorises", rank);
    const double single_error = solution_error(single, spd, 1e-12);
    check(single_error < 1e-11 && single.negative_pivots() == 0,
          "interleaved SPD, single precision refined: relative error " +
            sci(single_error),
          rank);

    // Only a diagonal: MUMPS is not called at all.
    const Epetra_CrsMatrix diagonal = interleaved(map, 0., 0., true, true);
    MumpsFactorization     none(MPI_COMM_WORLD, MumpsFactorization::Symmetry::indefinite);
    check(none.factorize(diagonal), "diagonal matrix: factorises", rank);
    const double diagonal_error = solution_error(none, diagonal);
    check(diagonal_error < 1e-15 && none.negative_pivots() == n / 6,
          "diagonal matrix: relative error " + sci(diagonal_error) + ", " +
            std::to_string(none.negative_pivots()) + " negative pivots",
          rank);
  }
  {
    // A 2D grid: on several ranks (rows distributed by grid lines) the interface is a
    // grid line of 30 rows for each pair of neighbouring ranks.
    const int              nx = 30, ny = 40;
    Epetra_Map             grid_map(nx * ny, 0, comm);
    const Epetra_CrsMatrix matrix = five_point(grid_map, nx, 0.01);
    MumpsFactorization     mumps(MPI_COMM_WORLD,
                             MumpsFactorization::Symmetry::positive_definite);
    check(mumps.factorize(matrix), "five-point grid 30 x 40: factorises", rank);
    const double error = solution_error(mumps, matrix);
    check(error < 1e-12, "five-point grid: relative error " + sci(error), rank);
    check(forwarded_solve_same_bits(mumps, matrix),
          "five-point grid: the forward substitution done while factorising gives the "
          "same bits",
          rank);
    MumpsFactorization single(MPI_COMM_WORLD,
                              MumpsFactorization::Symmetry::positive_definite,
                              5,
                              MumpsFactorization::Precision::single_refined);
    check(single.factorize(matrix) && single.factorize(five_point(grid_map, nx, 1.)),
          "five-point grid, single precision: factorises twice (new values)",
          rank);
    const double refined = solution_error(single, five_point(grid_map, nx, 1.), 1e-12);
    check(refined < 1e-11,
          "five-point grid, single precision refined: relative error " + sci(refined),
          rank);
    check(forwarded_solve_same_bits(single, five_point(grid_map, nx, 1.), 1e-12),
          "five-point grid, single precision refined: the forward substitution done "
          "while factorising gives the same bits",
          rank);
    MumpsFactorization negative(MPI_COMM_WORLD,
                                MumpsFactorization::Symmetry::positive_definite);
    const bool         factorized = negative.factorize(five_point(grid_map, nx, -0.05));
    check(!factorized || negative.negative_pivots() > 0,
          "five-point grid shifted below zero, SYM = 1 tells: " +
            (factorized ? std::to_string(negative.negative_pivots()) + " negative pivots"
                        : negative.failure()),
          rank);
  }
  return failures == 0 ? 0 : 1;
}
