#include "solvers/fill_reducing_order.h"

#include <dmumps_c.h>
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
} // namespace clothsim
