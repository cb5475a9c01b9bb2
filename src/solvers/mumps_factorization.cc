#include "solvers/mumps_factorization.h"

#include "io/collective.h"
#include "solvers/fill_reducing_order.h"
#include "solvers/flush_denormals.h"
#include "solvers/subdomain_cholesky.h"
#include "solvers/supernodal_cholesky.h"
#include "solvers/vertex_order.h"

#include <dmumps_c.h>
#include <smumps_c.h>

#include <Epetra_IntVector.h>

#include <algorithm>
#include <cstring>
#include <sstream>

namespace clothsim
{
  namespace
  {
    void
    run_mumps(DMUMPS_STRUC_C &id)
    {
      dmumps_c(&id);
    }

    void
    run_mumps(SMUMPS_STRUC_C &id)
    {
      smumps_c(&id);
    }
  } // namespace


  // MUMPS' double (DMUMPS) or single (SMUMPS) precision instance: their C structures
  // have the same fields, of double or float values.
  struct MumpsFactorization::Instance
  {
    DMUMPS_STRUC_C     d{};
    SMUMPS_STRUC_C     s{};
    bool               single = false;
    std::vector<float> values, rhs, solution; // single precision's copies

    // f(id) on the instance in use.
    template <typename Function>
    decltype(auto)
    visit(Function &&f)
    {
      return single ? f(s) : f(d);
    }
  };


  namespace
  {
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


  MumpsFactorization::MumpsFactorization(const MPI_Comm  communicator,
                                         const Symmetry  symmetry,
                                         const int       ordering,
                                         const Precision precision)
    : communicator(communicator)
    , instance(std::make_unique<Instance>())
    , requested_ordering(ordering)
  {
    instance->single = precision == Precision::single_refined;
    instance->visit([&](auto &id) {
      id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(communicator));
      id.par          = 1; // rank 0 works too
      id.sym          = symmetry == Symmetry::positive_definite ? 1 : 2;
      id.job          = -1;
      run_mumps(id);
      id.icntl[at(1)]  = -1; // no messages
      id.icntl[at(2)]  = -1;
      id.icntl[at(3)]  = -1;
      id.icntl[at(4)]  = 0;
      id.icntl[at(5)]  = 0; // assembled matrix,
      id.icntl[at(18)] = 3; // distributed by rows as the caller's
      id.icntl[at(7)]  = ordering;
      id.icntl[at(28)] = 1;  // sequential analysis: ICNTL(7) chooses the ordering
      id.icntl[at(20)] = 10; // right-hand side distributed (by the caller's rows),
      id.icntl[at(21)] = 1;  // solution distributed (as MUMPS' factors)
    });
  }


  MumpsFactorization::~MumpsFactorization()
  {
    instance->visit([](auto &id) {
      id.job = -2;
      run_mumps(id);
    });
  }


  bool
  MumpsFactorization::call(const int job, const char *phase)
  {
    // Workspace estimates of the analysis can be short after pivoting (SYM = 2): grow
    // the relaxation ICNTL(14) (percent) and repeat, as the MUMPS guide advises.
    return instance->visit([&](auto &id) {
      for (int attempt = 0;; ++attempt)
        {
          id.job = job;
          {
            const FlushDenormals flush; // as our own Cholesky (flush_denormals.h)
            run_mumps(id);
          }
          const int code = id.infog[at(1)];
          if (code >= 0)
            return true;
          const bool workspace = code == -8 || code == -9 || code == -14 || code == -15 ||
                                 code == -17 || code == -20;
          if (!workspace || attempt == 4)
            {
              last_failure = std::string("MUMPS ") + phase +
                             " failed: INFOG(1) = " + std::to_string(code) +
                             ", INFOG(2) = " + std::to_string(id.infog[at(2)]) + " (" +
                             mumps_error_text(code) + ")";
              return false;
            }
          id.icntl[at(14)] = 2 * std::max(id.icntl[at(14)], 20);
        }
    });
  }


  bool
  MumpsFactorization::set_up_rows(const Epetra_CrsMatrix &matrix)
  {
    cholesky.reset(); // a new sparsity: set up again after MUMPS' analysis
    kept_rows.clear();
    decoupled_rows.clear();
    int n_ranks = 1;
    MPI_Comm_size(communicator, &n_ranks);
    const bool       single_rank = n_ranks == 1;
    Epetra_IntVector new_index(matrix.RowMap());
    for (int row = 0; row < matrix.NumMyRows(); ++row)
      {
        int     n_entries = 0;
        double *row_values;
        int    *row_columns;
        matrix.ExtractMyRowView(row, n_entries, row_values, row_columns);
        const bool decoupled =
          single_rank && n_entries == 1 &&
          matrix.ColMap().GID(row_columns[0]) == matrix.RowMap().GID(row);
        (decoupled ? decoupled_rows : kept_rows).push_back(row);
      }
    const int n_local = static_cast<int>(kept_rows.size());
    int       offset  = 0;
    MPI_Exscan(&n_local, &offset, 1, MPI_INT, MPI_SUM, communicator);
    int rank = 0;
    MPI_Comm_rank(communicator, &rank);
    if (rank == 0)
      offset = 0; // MPI_Exscan leaves rank 0's result undefined
    MPI_Allreduce(&n_local, &n_kept, 1, MPI_INT, MPI_SUM, communicator);
    new_index.PutValue(-1);
    std::vector<int> kept_indices(n_local);
    for (int i = 0; i < n_local; ++i)
      {
        kept_indices[i]         = offset + i;
        new_index[kept_rows[i]] = offset + i;
      }
    kept_map = std::make_unique<Epetra_Map>(
      -1, n_local, kept_indices.data(), 0, matrix.RowMap().Comm());
    Epetra_IntVector new_column_index(matrix.ColMap());
    new_column_index.Import(new_index,
                            Epetra_Import(matrix.ColMap(), matrix.RowMap()),
                            Insert);

    // The upper triangle in the new numbering: of each symmetric pair of entries, the
    // one with new column >= new row.
    rows.clear();
    columns.clear();
    upper.clear();
    bool symmetric = true;
    for (int row = 0; row < matrix.NumMyRows(); ++row)
      {
        int     n_entries = 0;
        double *row_values;
        int    *row_columns;
        matrix.ExtractMyRowView(row, n_entries, row_values, row_columns);
        for (int j = 0; j < n_entries; ++j)
          {
            const int column = new_column_index[row_columns[j]];
            upper.push_back(new_index[row] >= 0 && column >= new_index[row]);
            if (new_index[row] >= 0 && column < 0)
              symmetric = false; // a kept row with an entry in a decoupled column
            if (upper.back())
              {
                rows.push_back(new_index[row] + 1);
                columns.push_back(column + 1);
              }
          }
      }
    values.resize(rows.size());
    decoupled_diagonal.resize(decoupled_rows.size());
    rhs_rows.resize(n_local);
    for (int i = 0; i < n_local; ++i)
      rhs_rows[i] = kept_indices[i] + 1;
    rhs_values.resize(n_local);
    if (!io::on_all_ranks(symmetric, communicator))
      {
        last_failure = "the matrix's sparsity is not symmetric (MUMPS needs it)";
        return false;
      }
    return true;
  }


  bool
  MumpsFactorization::factorize(const Epetra_CrsMatrix &matrix, const Epetra_Vector *rhs)
  {
    forwarded_rhs.clear();
    // Which entries of the row views go to MUMPS is found once (the sparsity does not
    // change after the analysis).
    const bool first = !analysed;
    if (first && !set_up_subdomains(matrix))
      return false;
    if (subdomains)
      {
        analysed = true;
        if (subdomains->factorize(matrix, rhs))
          return true;
        last_failure = subdomains->failure();
        return false;
      }
    if (first && !set_up_rows(matrix))
      return false;
    if (static_cast<std::size_t>(matrix.NumMyNonzeros()) != upper.size())
      {
        last_failure = "the matrix's sparsity changed after MUMPS analysed it";
        return false;
      }
    std::size_t entry = 0, value = 0, decoupled = 0;
    int         n_negative = 0, n_zero = 0;
    // The Cholesky reads the matrix's own value array (its entries' positions there
    // fixed by the analysis): only the decoupled diagonals are copied.
    double *crs_values = nullptr;
    int    *crs_offsets, *crs_columns;
    if (cholesky &&
        matrix.ExtractCrsDataPointers(crs_offsets, crs_columns, crs_values) != 0)
      {
        last_failure = "the matrix's storage changed after the analysis";
        return false;
      }
    if (crs_values != nullptr)
      for (const int row : decoupled_rows)
        {
          const double diagonal           = crs_values[crs_offsets[row]];
          decoupled_diagonal[decoupled++] = diagonal;
          n_negative += diagonal < 0.;
          n_zero += diagonal == 0.;
        }
    for (int row = 0; crs_values == nullptr && row < matrix.NumMyRows(); ++row)
      {
        int     n_entries = 0;
        double *row_values;
        int    *row_columns;
        matrix.ExtractMyRowView(row, n_entries, row_values, row_columns);
        if (decoupled < decoupled_rows.size() && decoupled_rows[decoupled] == row)
          {
            const double diagonal           = row_values[0];
            decoupled_diagonal[decoupled++] = diagonal;
            n_negative += diagonal < 0.;
            n_zero += diagonal == 0.;
            ++entry;
            continue;
          }
        for (int j = 0; j < n_entries; ++j, ++entry)
          if (upper[entry])
            values[value++] = row_values[j];
      }
    int counts[2] = {n_negative, n_zero}, totals[2] = {0, 0};
    MPI_Allreduce(counts, totals, 2, MPI_INT, MPI_SUM, communicator);
    n_negative_decoupled = totals[0];
    if (totals[1] > 0)
      {
        last_failure =
          "MUMPS factorisation failed: a row holds only a zero diagonal (the "
          "matrix is singular)";
        return false;
      }
    const bool definite = instance->visit([](auto &id) { return id.sym == 1; });
    if (definite && n_negative_decoupled > 0)
      {
        last_failure = "MUMPS factorisation failed: a row holds only a negative diagonal "
                       "(the matrix is not positive definite)";
        return false;
      }
    if (n_kept == 0)
      {
        analysed = true;
        return true;
      }
    if (instance->single && !cholesky)
      {
        instance->values.assign(values.begin(), values.end());
        instance->s.a_loc = instance->values.data();
      }
    else
      instance->d.a_loc = values.data();
    if (first)
      {
        instance->visit([&](auto &id) {
          id.n            = n_kept;
          id.nnz_loc      = static_cast<MUMPS_INT8>(rows.size());
          id.irn_loc      = rows.data();
          id.jcn_loc      = columns.data();
          id.icntl[at(7)] = requested_ordering;
        });
        int n_ranks = 1;
        MPI_Comm_size(communicator, &n_ranks);
        if (n_ranks > 1 && !order_on_host())
          return false;
        if (!call(1, "analysis"))
          return false;
        analysed = true;
        set_up_cholesky(matrix);
        if (cholesky)
          return factorize(matrix, rhs); // from the matrix's value array
      }
    if (cholesky)
      {
        if (rhs != nullptr)
          {
            forwarded_rhs.resize(kept_rows.size());
            for (std::size_t i = 0; i < kept_rows.size(); ++i)
              forwarded_rhs[i] = (*rhs)[kept_rows[i]];
          }
        if (cholesky->factorize(crs_values,
                                rhs != nullptr ? forwarded_rhs.data() : nullptr))
          return true;
        forwarded_rhs.clear();
        last_failure =
          std::string("the Cholesky factorisation met a pivot that is not "
                      "positive (the matrix is not positive definite, or too "
                      "ill-conditioned for ") +
          (instance->single ? "single" : "double") + " precision)";
        return false;
      }
    if (!call(2, "factorisation"))
      return false;
    // INFO(23): how many solution entries this rank receives.
    const int n_solution =
      std::max(instance->visit([](auto &id) { return id.info[at(23)]; }), 1);
    solution_rows.resize(n_solution);
    solution_values.resize(n_solution);
    return true;
  }


  bool
  MumpsFactorization::solve(const Epetra_Vector    &b,
                            Epetra_Vector          &x,
                            const Epetra_CrsMatrix *matrix,
                            const double            relative_tolerance)
  {
    last_refinements = 0;
    if (!solve_once(b, x))
      return false;
    if (!instance->single || matrix == nullptr)
      return true;
    // Iterative refinement with the residual in double precision (Higham, "Accuracy and
    // Stability of Numerical Algorithms", 2nd ed., ch. 12): x += A⁻¹ (b - A x) with the
    // single-precision factors, until ‖b - A x‖ ≤ tolerance ‖b‖. Each step gains about
    // as many digits as the first solve had (swinging sheet, N = 41: relative residuals
    // of 7e-8 to 8e-6 after it, median 7e-7).
    // Work vectors kept between solves (at N = 321 each is 5.8 MB of fresh pages).
    if (!residual_work || !residual_work->Map().SameAs(b.Map()))
      residual_work = std::make_unique<Epetra_Vector>(b.Map(), false);
    if (!correction_work || !correction_work->Map().SameAs(x.Map()))
      correction_work = std::make_unique<Epetra_Vector>(x.Map(), false);
    Epetra_Vector &residual = *residual_work, &correction = *correction_work;
    double         b_norm = 0.;
    b.Norm2(&b_norm);
    for (;; ++last_refinements)
      {
        matrix->Multiply(false, x, residual);
        residual.Update(1., b, -1.);
        double r_norm = 0.;
        residual.Norm2(&r_norm);
        if (r_norm <= relative_tolerance * b_norm)
          return true;
        if (last_refinements == max_refinements)
          {
            std::ostringstream message;
            message
              << "the single-precision factors' solve reached a relative residual of "
              << r_norm / b_norm << " after " << max_refinements
              << " refinement steps, not the " << relative_tolerance
              << " asked ('Linear solver/Relative tolerance'): the matrix is too "
                 "ill-conditioned for them, or the tolerance below double "
                 "precision's round-off; set 'Linear solver/Factor precision = "
                 "double' or a larger tolerance";
            last_failure = message.str();
            return false;
          }
        if (!solve_once(residual, correction))
          return false;
        x.Update(1., correction, 1.);
      }
  }


  bool
  MumpsFactorization::solve_once(const Epetra_Vector &b, Epetra_Vector &x)
  {
    if (subdomains)
      {
        subdomains->solve(b, x);
        return true;
      }
    for (std::size_t i = 0; i < decoupled_rows.size(); ++i)
      x[decoupled_rows[i]] = b[decoupled_rows[i]] / decoupled_diagonal[i];
    if (n_kept == 0)
      return true;
    for (std::size_t i = 0; i < kept_rows.size(); ++i)
      rhs_values[i] = b[kept_rows[i]];
    if (cholesky)
      {
        // The right-hand side whose forward substitution the factorisation did.
        if (!forwarded_rhs.empty() && forwarded_rhs.size() == rhs_values.size() &&
            std::memcmp(forwarded_rhs.data(),
                        rhs_values.data(),
                        rhs_values.size() * sizeof(double)) == 0)
          cholesky->finish_solve(rhs_values.data());
        else
          cholesky->solve(rhs_values.data());
        forwarded_rhs.clear();
        for (std::size_t i = 0; i < kept_rows.size(); ++i)
          x[kept_rows[i]] = rhs_values[i];
        return true;
      }
    if (instance->single)
      {
        instance->rhs.assign(rhs_values.begin(), rhs_values.end());
        instance->solution.resize(solution_values.size());
        instance->s.rhs_loc = instance->rhs.data();
        instance->s.sol_loc = instance->solution.data();
      }
    else
      {
        instance->d.rhs_loc = rhs_values.data();
        instance->d.sol_loc = solution_values.data();
      }
    instance->visit([&](auto &id) {
      id.nrhs     = 1;
      id.nloc_rhs = static_cast<MUMPS_INT>(rhs_rows.size());
      id.lrhs_loc = std::max<MUMPS_INT>(id.nloc_rhs, 1);
      id.irhs_loc = rhs_rows.data();
      id.lsol_loc = static_cast<MUMPS_INT>(solution_values.size());
      id.isol_loc = solution_rows.data();
    });
    if (!call(3, "solve"))
      return false;
    if (instance->single)
      std::copy(instance->solution.begin(),
                instance->solution.end(),
                solution_values.begin());
    // This rank's solution entries: the first INFO(23) of ISOL_loc (1-based new rows).
    const int n_local = instance->visit([](auto &id) { return id.info[at(23)]; });
    bool      same    = from_solution != nullptr &&
                static_cast<int>(mapped_rows.size()) == n_local &&
                std::equal(mapped_rows.begin(), mapped_rows.end(), solution_rows.begin());
    if (!io::on_all_ranks(same, communicator))
      {
        mapped_rows.assign(solution_rows.begin(), solution_rows.begin() + n_local);
        std::vector<int> global(n_local);
        for (int i = 0; i < n_local; ++i)
          global[i] = mapped_rows[i] - 1;
        solution_map =
          std::make_unique<Epetra_Map>(-1, n_local, global.data(), 0, x.Map().Comm());
        from_solution = std::make_unique<Epetra_Import>(*kept_map, *solution_map);
      }
    const Epetra_Vector solution(View, *solution_map, solution_values.data());
    Epetra_Vector       kept_solution(*kept_map);
    if (kept_solution.Import(solution, *from_solution, Insert) != 0)
      return false;
    for (std::size_t i = 0; i < kept_rows.size(); ++i)
      x[kept_rows[i]] = kept_solution[i];
    return true;
  }


  bool
  MumpsFactorization::order_on_host()
  {
    const auto order =
      order_on_rank_zero(n_kept, rows, columns, requested_ordering, communicator);
    if (!order)
      {
        last_failure = "MUMPS' analysis failed to order the matrix on rank 0";
        return false;
      }
    host_order = *order;
    instance->visit([&](auto &id) {
      id.icntl[at(7)] = 1; // the order given in PERM_IN (read on the host)
      id.perm_in      = host_order.data();
    });
    return true;
  }


  bool
  MumpsFactorization::set_up_subdomains(const Epetra_CrsMatrix &matrix)
  {
    subdomains.reset();
    int n_ranks = 1;
    MPI_Comm_size(communicator, &n_ranks);
    const bool definite = instance->visit([](auto &id) { return id.sym == 1; });
    if (n_ranks == 1 || !definite)
      return true;
    subdomains = std::make_unique<SubdomainCholesky>(communicator, instance->single);
    if (subdomains->analyse(matrix, mesh_dofs, mesh_vertices))
      return true;
    last_failure = subdomains->failure();
    return false;
  }


  int
  MumpsFactorization::negative_pivots() const
  {
    return n_negative_decoupled +
           (n_kept == 0 || cholesky ? 0 : instance->visit([](auto &id) {
             return id.infog[at(12)];
           }));
  }


  void
  MumpsFactorization::set_up_cholesky(const Epetra_CrsMatrix &matrix)
  {
    int n_ranks = 1;
    MPI_Comm_size(communicator, &n_ranks);
    const bool definite = instance->visit([](auto &id) { return id.sym == 1; });
    if (n_ranks != 1 || !definite || !matrix.StorageOptimized())
      return;
    // SYM_PERM(i): the position of row i in MUMPS' elimination order.
    std::vector<int> order(n_kept), pattern_rows(rows.size()),
      pattern_columns(rows.size());
    for (int i = 0; i < n_kept; ++i)
      order[instance->visit([i](auto &id) { return id.sym_perm[i]; }) - 1] = i;
    for (std::size_t k = 0; k < rows.size(); ++k)
      {
        pattern_rows[k]    = rows[k] - 1;
        pattern_columns[k] = columns[k] - 1;
      }
    // Each entry's place in the matrix's value array (StorageOptimized: rows in turn).
    std::vector<int> value_index;
    value_index.reserve(rows.size());
    for (std::size_t entry = 0; entry < upper.size(); ++entry)
      if (upper[entry])
        value_index.push_back(static_cast<int>(entry));
    cholesky = std::make_unique<SupernodalCholesky>(instance->single);
    cholesky->analyse(n_kept, pattern_rows, pattern_columns, order, value_index);
    if (mesh_dofs != nullptr)
      prefer_vertex_order(cholesky,
                          instance->single,
                          n_kept,
                          pattern_rows,
                          pattern_columns,
                          value_index,
                          matrix.RowMap(),
                          kept_rows,
                          *mesh_dofs,
                          *mesh_vertices);
  }
} // namespace clothsim
