#include "solvers/fill_reducing_order.h"

#include <dmumps_c.h>
#include <metis.h>
#include <mpi.h>

namespace clothsim
{
  std::optional<std::vector<int>>
  fill_reducing_order(const int               n,
                      const std::vector<int> &rows,
                      const std::vector<int> &columns,
                      const int               ordering)
  {
    if (n == 0)
      return std::vector<int>();
    DMUMPS_STRUC_C id{};
    id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(MPI_COMM_SELF));
    id.par          = 1;
    id.sym          = 1;
    id.job          = -1;
    dmumps_c(&id);
    // ICNTL(k) of MUMPS' users' guide is icntl[k - 1].
    const auto icntl = [&id](const int k) -> MUMPS_INT & { return id.icntl[k - 1]; };
    for (const int k : {1, 2, 3})
      icntl(k) = -1; // no messages
    icntl(4)  = 0;
    icntl(5)  = 0; // an assembled matrix,
    icntl(18) = 0; // on the host
    icntl(7)  = ordering;
    std::vector<int> irn(rows.size()), jcn(columns.size());
    for (std::size_t k = 0; k < rows.size(); ++k)
      {
        irn[k] = rows[k] + 1;
        jcn[k] = columns[k] + 1;
      }
    id.n   = n;
    id.nnz = static_cast<MUMPS_INT8>(irn.size());
    id.irn = irn.data();
    id.jcn = jcn.data();
    id.job = 1;
    dmumps_c(&id);
    std::optional<std::vector<int>> order;
    if (id.infog[0] >= 0) // INFOG(1): no error
      {
        order.emplace(n);
        for (int i = 0; i < n; ++i) // SYM_PERM(i): row i's position in the order
          (*order)[id.sym_perm[i] - 1] = i;
      }
    id.job = -2;
    dmumps_c(&id);
    return order;
  }


  std::optional<std::vector<int>>
  nested_dissection_order(const int                      n,
                          const std::vector<int>        &rows,
                          const std::vector<int>        &columns,
                          const NestedDissectionOptions &choices)
  {
    // The graph: each row's neighbours, both ways, without the diagonal.
    std::vector<idx_t> start(n + 2, 0);
    for (std::size_t k = 0; k < rows.size(); ++k)
      if (rows[k] != columns[k])
        {
          ++start[rows[k] + 2];
          ++start[columns[k] + 2];
        }
    for (int i = 0; i < n; ++i)
      start[i + 2] += start[i + 1];
    std::vector<idx_t> neighbours(start[n + 1]);
    for (std::size_t k = 0; k < rows.size(); ++k)
      if (rows[k] != columns[k])
        {
          neighbours[start[rows[k] + 1]++]    = columns[k];
          neighbours[start[columns[k] + 1]++] = rows[k];
        }
    start.pop_back();
    idx_t              n_vertices = n;
    std::vector<idx_t> permutation(n), inverse(n);
    idx_t              options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_NUMBERING] = 0;
    if (choices.imbalance > 0)
      options[METIS_OPTION_UFACTOR] = choices.imbalance;
    options[METIS_OPTION_SEED] = choices.seed;
    if (n > 0 && METIS_NodeND(&n_vertices,
                              start.data(),
                              neighbours.data(),
                              nullptr,
                              options,
                              permutation.data(),
                              inverse.data()) != METIS_OK)
      return std::nullopt;
    // METIS' perm[p] is the row eliminated p-th (iperm[i] the position of row i).
    return std::vector<int>(permutation.begin(), permutation.end());
  }


  std::optional<std::vector<int>>
  order_on_rank_zero(const int               n,
                     const std::vector<int> &rows,
                     const std::vector<int> &columns,
                     const int               ordering,
                     const MPI_Comm          communicator)
  {
    int rank = 0, n_ranks = 1;
    MPI_Comm_rank(communicator, &rank);
    MPI_Comm_size(communicator, &n_ranks);
    const int        count = static_cast<int>(rows.size());
    std::vector<int> counts(n_ranks), offsets(n_ranks + 1, 0);
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, communicator);
    for (int r = 0; r < n_ranks; ++r)
      offsets[r + 1] = offsets[r] + counts[r];
    std::vector<int> all_rows, all_columns;
    for (auto [local, all] :
         {std::pair(&rows, &all_rows), std::pair(&columns, &all_columns)})
      {
        all->resize(rank == 0 ? offsets.back() : 0);
        MPI_Gatherv(local->data(),
                    count,
                    MPI_INT,
                    all->data(),
                    counts.data(),
                    offsets.data(),
                    MPI_INT,
                    0,
                    communicator);
      }
    std::vector<int> positions;
    int              ordered = 1;
    if (rank == 0)
      {
        // Rows with an entry off the diagonal, numbered 0, 1, ... among themselves.
        std::vector<int> reduced(n, -1);
        for (std::size_t k = 0; k < all_rows.size(); ++k)
          if (all_rows[k] != all_columns[k])
            reduced[all_rows[k] - 1] = reduced[all_columns[k] - 1] = 0;
        int n_reduced = 0;
        for (int &index : reduced)
          if (index == 0)
            index = n_reduced++;
        std::vector<int> reduced_rows, reduced_columns;
        for (std::size_t k = 0; k < all_rows.size(); ++k)
          if (reduced[all_rows[k] - 1] >= 0)
            {
              reduced_rows.push_back(reduced[all_rows[k] - 1]);
              reduced_columns.push_back(reduced[all_columns[k] - 1]);
            }
        const auto order =
          fill_reducing_order(n_reduced, reduced_rows, reduced_columns, ordering);
        ordered = order.has_value() ? 1 : 0;
        if (order)
          {
            std::vector<int> position(n_reduced);
            for (int p = 0; p < n_reduced; ++p)
              position[(*order)[p]] = p;
            positions.resize(n);
            int last = n_reduced;
            for (int i = 0; i < n; ++i)
              positions[i] = (reduced[i] >= 0 ? position[reduced[i]] : last++) + 1;
          }
      }
    MPI_Bcast(&ordered, 1, MPI_INT, 0, communicator);
    if (ordered == 0)
      return std::nullopt;
    return positions;
  }
} // namespace clothsim
