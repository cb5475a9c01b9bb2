// The shells' block preconditioner (solvers/block_preconditioner.h) against its formula,
// evaluated densely:
//   y_ψ = D⁻¹ r_ψ,  z_u = S̃⁻¹ (r_u − B y_ψ),  z_ψ = D⁻¹ (r_ψ − Bᵀ z_u),
//   S̃ = A − B D⁻¹ Bᵀ,
// with ML's hierarchy reduced to one level (S̃ solved directly by KLU), so that P⁻¹ r is
// exact to round-off. The tangent is a symmetric, diagonally dominant matrix with the
// shells' structure: 8 vertices (3 displacements each) and 12 director angles, each angle
// coupled to 4 vertices and to its neighbouring angles. A second tangent with the same
// sparsity and new entries goes through the same preconditioner (which then adds into the
// Schur complement's profile instead of building it) and through a new one: both match
// the formula. On one rank and on two (each owning half the vertices and half the angles:
// the Schur complement then receives rows from the other rank).

#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include "app/mpi_session.h"
#include "solvers/block_preconditioner.h"

#include <cmath>
#include <iostream>
#include <random>

using namespace dealii;
using namespace clothsim;

namespace
{
  constexpr unsigned int n_vertices = 8, n_angles = 12;
  constexpr unsigned int n_u = 3 * n_vertices, n = n_u + n_angles;

  // The structural pattern: displacements of vertices up to two apart (cyclically); angle
  // a with the displacements of vertices a .. a + 3 and with angles a ± 1.
  bool
  coupled(const unsigned int i, const unsigned int j)
  {
    const auto vertex_distance = [](const unsigned int v, const unsigned int w) {
      const unsigned int d = v > w ? v - w : w - v;
      return std::min(d, n_vertices - d);
    };
    if (i < n_u && j < n_u)
      return vertex_distance(i / 3, j / 3) <= 2;
    if (i >= n_u && j >= n_u)
      {
        const unsigned int a = i - n_u, b = j - n_u;
        const unsigned int d = a > b ? a - b : b - a;
        return std::min(d, n_angles - d) <= 1;
      }
    const unsigned int angle = (i >= n_u ? i : j) - n_u, dof = i >= n_u ? j : i;
    return (dof / 3 + n_vertices - angle % n_vertices) % n_vertices < 4;
  }

  // Symmetric entries in [-1, 1] on the pattern, each diagonal 1 more than its row's
  // off-diagonal magnitudes: symmetric positive definite.
  FullMatrix<double>
  random_tangent(const unsigned int seed)
  {
    std::mt19937                           generator(seed);
    std::uniform_real_distribution<double> entry(-1., 1.);
    FullMatrix<double>                     A(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < i; ++j)
        if (coupled(i, j))
          A(i, j) = A(j, i) = entry(generator);
    for (unsigned int i = 0; i < n; ++i)
      {
        double sum = 1.;
        for (unsigned int j = 0; j < n; ++j)
          if (j != i)
            sum += std::abs(A(i, j));
        A(i, i) = sum;
      }
    return A;
  }

  // P⁻¹ r by the formula, densely.
  Vector<double>
  formula(const FullMatrix<double> &A, const Vector<double> &r)
  {
    Vector<double> y(n_angles), t(n_u), z(n);
    for (unsigned int a = 0; a < n_angles; ++a)
      y[a] = r[n_u + a] / A(n_u + a, n_u + a);
    FullMatrix<double> S(n_u, n_u);
    for (unsigned int i = 0; i < n_u; ++i)
      {
        t[i] = r[i];
        for (unsigned int a = 0; a < n_angles; ++a)
          t[i] -= A(i, n_u + a) * y[a];
        for (unsigned int j = 0; j < n_u; ++j)
          {
            S(i, j) = A(i, j);
            for (unsigned int a = 0; a < n_angles; ++a)
              S(i, j) -= A(i, n_u + a) * A(n_u + a, j) / A(n_u + a, n_u + a);
          }
      }
    S.gauss_jordan();
    for (unsigned int i = 0; i < n_u; ++i)
      for (unsigned int j = 0; j < n_u; ++j)
        z[i] += S(i, j) * t[j];
    for (unsigned int a = 0; a < n_angles; ++a)
      {
        double s = r[n_u + a];
        for (unsigned int i = 0; i < n_u; ++i)
          s -= A(n_u + a, i) * z[i];
        z[n_u + a] = s / A(n_u + a, n_u + a);
      }
    return z;
  }
} // namespace


int
main(int argc, char **argv)
{
  MpiSession     mpi(argc, argv);
  const MPI_Comm comm   = MPI_COMM_WORLD;
  const unsigned rank   = Utilities::MPI::this_mpi_process(comm);
  const unsigned ranks  = Utilities::MPI::n_mpi_processes(comm);
  unsigned int   failed = 0;

  // Rank p owns vertices and angles in the p-th of `ranks` equal parts.
  IndexSet   owned(n), displacements(n);
  const auto part = [&](const unsigned int count) {
    return std::make_pair(count * rank / ranks, count * (rank + 1) / ranks);
  };
  owned.add_range(3 * part(n_vertices).first, 3 * part(n_vertices).second);
  displacements.add_range(3 * part(n_vertices).first, 3 * part(n_vertices).second);
  owned.add_range(n_u + part(n_angles).first, n_u + part(n_angles).second);
  owned.compress();
  displacements.compress();
  const IndexSet relevant = complete_index_set(n);

  DynamicSparsityPattern pattern(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      if (coupled(i, j) || i == j)
        pattern.add(i, j);
  const auto make_matrix = [&](const FullMatrix<double> &A) {
    TrilinosWrappers::SparseMatrix matrix;
    matrix.reinit(owned, owned, pattern, comm);
    for (const types::global_dof_index i : owned)
      for (unsigned int j = 0; j < n; ++j)
        if (coupled(i, j) || i == j)
          matrix.set(i, j, A(i, j));
    matrix.compress(VectorOperation::insert);
    return matrix;
  };

  // One level: S̃ (24 rows) is below ML's coarse size and is solved by KLU.
  TrilinosWrappers::PreconditionAMG::AdditionalData data;
  data.coarse_type = "Amesos-KLU";
  Teuchos::ParameterList              ml_parameters;
  std::unique_ptr<Epetra_MultiVector> constant_modes;
  const FullMatrix<double>            A1 = random_tangent(1), A2 = random_tangent(2);
  TrilinosWrappers::SparseMatrix matrix1 = make_matrix(A1), matrix2 = make_matrix(A2);
  data.set_parameters(ml_parameters, constant_modes, matrix1.trilinos_matrix());
  ml_parameters.set("PDE equations", 3);
  ml_parameters.set("coarse: max size", 1000);

  Vector<double> r(n);
  for (unsigned int i = 0; i < n; ++i)
    r[i] = std::sin(1. + 3. * i);
  TrilinosWrappers::MPI::Vector src(owned, comm), dst(owned, comm);
  for (const types::global_dof_index i : owned)
    src[i] = r[i];
  src.compress(VectorOperation::insert);

  const auto check = [&](BlockPreconditioner      &preconditioner,
                         const FullMatrix<double> &A,
                         const std::string        &what) {
    preconditioner.vmult(dst, src);
    const Vector<double> expected = formula(A, r);
    double               error = 0., size = 0.;
    for (const types::global_dof_index i : owned)
      {
        error = std::max(error, std::abs(dst[i] - expected[i]));
        size  = std::max(size, std::abs(expected[i]));
      }
    error         = Utilities::MPI::max(error, comm);
    size          = Utilities::MPI::max(size, comm);
    const bool ok = error <= 1e-12 * size;
    if (rank == 0)
      std::cout << (ok ? "ok      " : "FAILED  ") << what
                << ": |P⁻¹r − formula| = " << error << " (|P⁻¹r| = " << size
                << ", at most 1e-12 of it)" << std::endl;
    failed += ok ? 0 : 1;
  };

  BlockPreconditioner reused(owned, relevant, displacements, comm);
  reused.initialize(matrix1, ml_parameters);
  check(reused, A1, "first tangent (the Schur complement's profile built)");
  reused.initialize(matrix2, ml_parameters);
  check(reused, A2, "second tangent, same preconditioner (added into the profile)");
  BlockPreconditioner fresh(owned, relevant, displacements, comm);
  fresh.initialize(matrix2, ml_parameters);
  check(fresh, A2, "second tangent, a new preconditioner");

  if (rank == 0)
    std::cout << (failed == 0 ? "PASSED" : "FAILED") << " (" << ranks << " rank(s))"
              << std::endl;
  return failed == 0 ? 0 : 1;
}
