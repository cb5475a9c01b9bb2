#pragma once

// A fill-reducing elimination order of a symmetric sparsity, computed on this rank alone
// by MUMPS' analysis (Amestoy et al., SIAM J. Matrix Anal. Appl. 23, 2001) with its
// ICNTL(7) `ordering` (0 AMD, 3 SCOTCH, 4 PORD, 5 METIS, which Debian's MUMPS replaces
// by PORD; MumpsFactorization::default_ordering).

#include <optional>
#include <vector>

namespace clothsim
{
  // order[p] is the row eliminated p-th; `rows` and `columns` (0-based) hold each entry
  // of one triangle of the n x n pattern once. Nothing if the analysis fails.
  std::optional<std::vector<int>>
  fill_reducing_order(int                     n,
                      const std::vector<int> &rows,
                      const std::vector<int> &columns,
                      int                     ordering);
} // namespace clothsim
