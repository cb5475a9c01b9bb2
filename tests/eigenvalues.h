#pragma once

// Extreme eigenvalues of a small symmetric matrix, for the tests' positive
// semi-definiteness checks (LAPACK through deal.II).

#include <deal.II/lac/lapack_full_matrix.h>

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

namespace clothsim::test
{
  // (smallest, largest) eigenvalue of the symmetric matrix `entries`.
  template <std::size_t n>
  std::pair<double, double>
  extreme_eigenvalues(const std::array<std::array<double, n>, n> &entries)
  {
    dealii::LAPACKFullMatrix<double> matrix(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        matrix(i, j) = entries[i][j];
    matrix.compute_eigenvalues();
    double smallest = std::numeric_limits<double>::infinity(), largest = 0.;
    for (unsigned int i = 0; i < n; ++i)
      {
        smallest = std::min(smallest, matrix.eigenvalue(i).real());
        largest  = std::max(largest, matrix.eigenvalue(i).real());
      }
    return {smallest, largest};
  }
} // namespace clothsim::test
