#pragma once

// A fill-reducing elimination order of a symmetric sparsity, computed on this rank alone
// by MUMPS' analysis (Amestoy et al., SIAM J. Matrix Anal. Appl. 23, 2001) with its
// ICNTL(7) `ordering` (0 AMD, 3 SCOTCH, 4 PORD, 5 METIS, which Debian's MUMPS replaces
// by PORD; MumpsFactorization::default_ordering).

#include <mpi.h>

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

  // Options of METIS' nested dissection that change the order's cost by 10 to 20 % on
  // the swinging sheet's pattern (README, "Several ranks: substructuring").
  struct NestedDissectionOptions
  {
    // How much larger than half of a part one side of a separator may be, in
    // thousandths (METIS_OPTION_UFACTOR); 0: METIS' default (200).
    int imbalance = 0;
    // The random seed of METIS' matchings and refinements (METIS_OPTION_SEED); -1:
    // METIS' default.
    int seed = -1;
  };

  // order[p] is the row eliminated p-th by METIS' nested dissection (METIS_NodeND:
  // Karypis & Kumar, SIAM J. Sci. Comput. 20, 1998) of the same pattern. Nothing if
  // METIS fails.
  std::optional<std::vector<int>>
  nested_dissection_order(int                            n,
                          const std::vector<int>        &rows,
                          const std::vector<int>        &columns,
                          const NestedDissectionOptions &options = {});

  // The same for a pattern distributed over the ranks (collective): `rows` and
  // `columns` (1-based) hold this rank's entries of one triangle. Rank 0 gathers them
  // and orders the rows with an entry off the diagonal alone; rows holding only their
  // diagonal go last (with them PORD takes 13 times longer: swing N = 321, 14.9 s
  // against 1.1 s without its 103,041 such rows). On rank 0 each row's 1-based
  // position (MUMPS' PERM_IN), on the others an empty vector; nothing if it failed.
  std::optional<std::vector<int>>
  order_on_rank_zero(int                     n,
                     const std::vector<int> &rows,
                     const std::vector<int> &columns,
                     int                     ordering,
                     MPI_Comm                communicator);
} // namespace clothsim
