#include "solvers/mumps_factorization.h"

#include <dmumps_c.h>

#include <algorithm>

namespace clothsim
{
  struct MumpsFactorization::Instance
  {
    DMUMPS_STRUC_C id{};
  };


  namespace
  {
    // Whether `value` holds on every rank (collective).
    bool
    on_all_ranks(const bool value, const MPI_Comm communicator)
    {
      int local = value ? 1 : 0, all = 0;
      MPI_Allreduce(&local, &all, 1, MPI_INT, MPI_MIN, communicator);
      return all == 1;
    }

    // MUMPS' arrays are 1-based in its documentation: ICNTL(k) is icntl[k - 1].
    constexpr int
    at(const int k)
    {
      return k - 1;
    }

    std::string
    mumps_error_text(const int code)
    {
      switch (code)
        {
          case -10:
            return "the matrix is numerically singular";
          case -13:
            return "MUMPS could not allocate memory";
          case -8:
          case -9:
          case -14:
          case -15:
          case -17:
          case -20:
            return "MUMPS' workspace was too small";
          default:
            return "see the MUMPS users' guide";
        }
    }
  } // namespace


  MumpsFactorization::MumpsFactorization(const MPI_Comm communicator,
                                         const Symmetry symmetry,
                                         const int      ordering)
    : communicator(communicator)
    , instance(std::make_unique<Instance>())
  {
    instance->id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(communicator));
    instance->id.par          = 1; // rank 0 works too
    instance->id.sym          = symmetry == Symmetry::positive_definite ? 1 : 2;
    instance->id.job          = -1;
    dmumps_c(&instance->id);
    instance->id.icntl[at(1)]  = -1; // no messages
    instance->id.icntl[at(2)]  = -1;
    instance->id.icntl[at(3)]  = -1;
    instance->id.icntl[at(4)]  = 0;
    instance->id.icntl[at(5)]  = 0; // assembled matrix,
    instance->id.icntl[at(18)] = 3; // distributed by rows as the caller's
    instance->id.icntl[at(7)]  = ordering;
    instance->id.icntl[at(28)] = 1; // sequential analysis: ICNTL(7) chooses the ordering
    instance->id.icntl[at(20)] =
      10;                           // right-hand side distributed (by the caller's rows),
    instance->id.icntl[at(21)] = 1; // solution distributed (as MUMPS' factors)
  }


  MumpsFactorization::~MumpsFactorization()
  {
    instance->id.job = -2;
    dmumps_c(&instance->id);
  }


  bool
  MumpsFactorization::call(const int job, const char *phase)
  {
    // Workspace estimates of the analysis can be short after pivoting (SYM = 2): grow
    // the relaxation ICNTL(14) (percent) and repeat, as the MUMPS guide advises.
    for (int attempt = 0;; ++attempt)
      {
        instance->id.job = job;
        dmumps_c(&instance->id);
        const int code = instance->id.infog[at(1)];
        if (code >= 0)
          return true;
        const bool workspace = code == -8 || code == -9 || code == -14 || code == -15 ||
                               code == -17 || code == -20;
        if (!workspace || attempt == 4)
          {
            last_failure = std::string("MUMPS ") + phase +
                           " failed: INFOG(1) = " + std::to_string(code) +
                           ", INFOG(2) = " + std::to_string(instance->id.infog[at(2)]) +
                           " (" + mumps_error_text(code) + ")";
            return false;
          }
        instance->id.icntl[at(14)] = 2 * std::max(instance->id.icntl[at(14)], 20);
      }
  }


  bool
  MumpsFactorization::factorize(const Epetra_CrsMatrix &matrix)
  {
    // The upper triangle of the owned rows, in row order: which entries of the row
    // views belong to it is found once (the sparsity does not change after the analysis).
    const bool first = !analysed;
    if (first)
      {
        rows.clear();
        columns.clear();
        upper.clear();
        for (int row = 0; row < matrix.NumMyRows(); ++row)
          {
            int     n_entries = 0;
            double *row_values;
            int    *row_columns;
            matrix.ExtractMyRowView(row, n_entries, row_values, row_columns);
            const int global_row = matrix.RowMap().GID(row);
            for (int j = 0; j < n_entries; ++j)
              {
                const int global_column = matrix.ColMap().GID(row_columns[j]);
                upper.push_back(global_column >= global_row);
                if (upper.back())
                  {
                    rows.push_back(global_row + 1);
                    columns.push_back(global_column + 1);
                  }
              }
          }
        values.resize(rows.size());
      }
    if (static_cast<std::size_t>(matrix.NumMyNonzeros()) != upper.size())
      {
        last_failure = "the matrix's sparsity changed after MUMPS analysed it";
        return false;
      }
    std::size_t entry = 0, value = 0;
    for (int row = 0; row < matrix.NumMyRows(); ++row)
      {
        int     n_entries = 0;
        double *row_values;
        int    *row_columns;
        matrix.ExtractMyRowView(row, n_entries, row_values, row_columns);
        for (int j = 0; j < n_entries; ++j, ++entry)
          if (upper[entry])
            values[value++] = row_values[j];
      }
    instance->id.a_loc = values.data();
    if (first)
      {
        instance->id.n       = matrix.NumGlobalRows();
        instance->id.nnz_loc = static_cast<MUMPS_INT8>(rows.size());
        instance->id.irn_loc = rows.data();
        instance->id.jcn_loc = columns.data();
        if (!call(1, "analysis"))
          return false;
        analysed = true;

        rhs_rows.resize(matrix.NumMyRows());
        for (int row = 0; row < matrix.NumMyRows(); ++row)
          rhs_rows[row] = matrix.RowMap().GID(row) + 1;
        rhs_values.resize(rhs_rows.size());
      }
    if (!call(2, "factorisation"))
      return false;
    // INFO(23): how many solution entries this rank receives.
    const int n_solution = std::max(instance->id.info[at(23)], 1);
    solution_rows.resize(n_solution);
    solution_values.resize(n_solution);
    return true;
  }


  bool
  MumpsFactorization::solve(const Epetra_Vector &b, Epetra_Vector &x)
  {
    std::copy(b.Values(), b.Values() + b.MyLength(), rhs_values.begin());
    instance->id.nrhs     = 1;
    instance->id.nloc_rhs = static_cast<MUMPS_INT>(rhs_rows.size());
    instance->id.lrhs_loc = std::max<MUMPS_INT>(instance->id.nloc_rhs, 1);
    instance->id.irhs_loc = rhs_rows.data();
    instance->id.rhs_loc  = rhs_values.data();
    instance->id.lsol_loc = static_cast<MUMPS_INT>(solution_values.size());
    instance->id.isol_loc = solution_rows.data();
    instance->id.sol_loc  = solution_values.data();
    if (!call(3, "solve"))
      return false;
    // This rank's solution entries: the first INFO(23) of ISOL_loc (1-based rows).
    const int n_local = instance->id.info[at(23)];
    bool      same    = from_solution != nullptr &&
                static_cast<int>(mapped_rows.size()) == n_local &&
                std::equal(mapped_rows.begin(), mapped_rows.end(), solution_rows.begin());
    if (!on_all_ranks(same, communicator))
      {
        mapped_rows.assign(solution_rows.begin(), solution_rows.begin() + n_local);
        std::vector<int> global(n_local);
        for (int i = 0; i < n_local; ++i)
          global[i] = mapped_rows[i] - 1;
        solution_map =
          std::make_unique<Epetra_Map>(-1, n_local, global.data(), 0, x.Map().Comm());
        from_solution = std::make_unique<Epetra_Import>(x.Map(), *solution_map);
      }
    const Epetra_Vector solution(View, *solution_map, solution_values.data());
    return x.Import(solution, *from_solution, Insert) == 0;
  }


  int
  MumpsFactorization::negative_pivots() const
  {
    return instance->id.infog[at(12)];
  }
} // namespace clothsim
