#include "solvers/subdomain_cholesky.h"

#include <deal.II/base/mpi.h>

#include "io/collective.h"
#include "solvers/dense_kernels.h"
#include "solvers/fill_reducing_order.h"
#include "solvers/flush_denormals.h"
#include "solvers/vertex_order.h"

#include <Epetra_Import.h>
#include <Epetra_IntVector.h>

#include <algorithm>
#include <numeric>

namespace clothsim
{
  namespace
  {
    // data = the sum of every rank's data, the same on every rank: summed on rank 0 and
    // broadcast (MPI_Allreduce may add in another order on each rank, and ranks whose
    // separator factors differ in their last bits would disagree on x_S).
    void
    sum_on_all_ranks(void              *data,
                     const int          count,
                     const MPI_Datatype type,
                     const MPI_Comm     communicator)
    {
      int rank = 0;
      MPI_Comm_rank(communicator, &rank);
      MPI_Reduce(
        rank == 0 ? MPI_IN_PLACE : data, data, count, type, MPI_SUM, 0, communicator);
      MPI_Bcast(data, count, type, 0, communicator);
    }
  } // namespace


  SubdomainCholesky::SubdomainCholesky(const MPI_Comm communicator,
                                       const bool     single_precision)
    : communicator(communicator)
    , cholesky(single_precision)
    , single(single_precision)
  {}


  bool
  SubdomainCholesky::analyse(
    const Epetra_CrsMatrix                                            &matrix,
    const std::vector<dealii::types::global_dof_index>                *mesh_dofs,
    const std::vector<std::array<dealii::types::global_dof_index, 2>> *mesh_vertices)
  {
    int rank = 0;
    MPI_Comm_rank(communicator, &rank);
    int    *offsets = nullptr, *columns = nullptr;
    double *values = nullptr;
    if (!io::on_all_ranks(matrix.StorageOptimized() &&
                            matrix.ExtractCrsDataPointers(offsets, columns, values) == 0,
                          communicator))
      {
        last_failure = "the matrix's storage is not optimised (FillComplete)";
        return false;
      }
    const Epetra_Map &row_map = matrix.RowMap(), &column_map = matrix.ColMap();
    const int         n_rows = matrix.NumMyRows();

    // Each column's owner; the separator: rows coupled to a row of a higher rank.
    Epetra_IntVector owner(row_map), column_owner(column_map);
    owner.PutValue(rank);
    const Epetra_Import to_columns(column_map, row_map);
    column_owner.Import(owner, to_columns, Insert);
    interior_rows.clear();
    separator_rows.clear();
    decoupled_rows.clear();
    decoupled_offsets.clear();
    for (int row = 0; row < n_rows; ++row)
      {
        const int begin = offsets[row], end = offsets[row + 1];
        if (end - begin == 1 && column_map.GID(columns[begin]) == row_map.GID(row))
          {
            decoupled_rows.push_back(row);
            decoupled_offsets.push_back(begin);
            continue;
          }
        bool coupled_up = false;
        for (int k = begin; k < end; ++k)
          coupled_up = coupled_up || column_owner[columns[k]] > rank;
        (coupled_up ? separator_rows : interior_rows).push_back(row);
      }
    decoupled_diagonal.resize(decoupled_rows.size());

    // The separator numbered across the ranks in their order.
    const int n_local_separator = static_cast<int>(separator_rows.size());
    int       first             = 0;
    MPI_Exscan(&n_local_separator, &first, 1, MPI_INT, MPI_SUM, communicator);
    if (rank == 0)
      first = 0; // MPI_Exscan leaves rank 0's result undefined
    MPI_Allreduce(&n_local_separator, &n_separator, 1, MPI_INT, MPI_SUM, communicator);
    Epetra_IntVector in_separator(row_map), column_in_separator(column_map);
    in_separator.PutValue(-1);
    separator_index.resize(n_local_separator);
    for (int i = 0; i < n_local_separator; ++i)
      in_separator[separator_rows[i]] = separator_index[i] = first + i;
    column_in_separator.Import(in_separator, to_columns, Insert);

    // The local system: the interior rows 0 .. n_interior - 1, then the whole
    // separator. Its upper triangle, each entry's place in the value array: interior
    // rows give their interior and separator entries; separator rows only their
    // entries within the separator (on the rank that owns the row, once).
    const int        n_interior = static_cast<int>(interior_rows.size());
    std::vector<int> local_index(n_rows, -1), column_interior(column_map.NumMyElements());
    for (int i = 0; i < n_interior; ++i)
      local_index[interior_rows[i]] = i;
    for (int c = 0; c < column_map.NumMyElements(); ++c)
      {
        const int row      = row_map.LID(column_map.GID(c));
        column_interior[c] = row < 0 ? -1 : local_index[row];
      }
    std::vector<int> rows, cols, value_index, interior_pattern[2];
    bool             symmetric = true;
    const auto       add       = [&](const int a, const int b, const int k) {
      rows.push_back(a);
      cols.push_back(b);
      value_index.push_back(k);
      if (b < n_interior)
        {
          interior_pattern[0].push_back(a);
          interior_pattern[1].push_back(b);
        }
    };
    for (int i = 0; i < n_interior; ++i)
      for (int k = offsets[interior_rows[i]]; k < offsets[interior_rows[i] + 1]; ++k)
        {
          const int c = columns[k];
          if (column_in_separator[c] >= 0)
            add(i, n_interior + column_in_separator[c], k);
          else if (column_interior[c] >= i)
            add(i, column_interior[c], k);
          else if (column_interior[c] < 0)
            symmetric = false; // another rank's interior row, or a decoupled row
        }
    for (int i = 0; i < n_local_separator; ++i)
      for (int k = offsets[separator_rows[i]]; k < offsets[separator_rows[i] + 1]; ++k)
        if (column_in_separator[columns[k]] >= separator_index[i])
          add(n_interior + separator_index[i],
              n_interior + column_in_separator[columns[k]],
              k);
    if (!io::on_all_ranks(symmetric, communicator))
      {
        last_failure = "the matrix's sparsity is not symmetric";
        return false;
      }

    // The interior in a fill-reducing order, the separator last.
    std::optional<std::vector<int>> interior_order;
    if (mesh_dofs != nullptr)
      {
        std::vector<dealii::types::global_dof_index> interior_dofs(n_interior);
        for (int i = 0; i < n_interior; ++i)
          interior_dofs[i] = row_map.GID64(interior_rows[i]);
        if (const auto vertices = rows_on_mesh(interior_dofs, *mesh_dofs, *mesh_vertices))
          interior_order = vertex_nested_dissection_order(n_interior,
                                                          interior_pattern[0],
                                                          interior_pattern[1],
                                                          vertices->first,
                                                          vertices->second,
                                                          {500, -1});
      }
    if (!interior_order)
      interior_order =
        nested_dissection_order(n_interior, interior_pattern[0], interior_pattern[1]);
    if (!io::on_all_ranks(interior_order.has_value(), communicator))
      {
        last_failure = "METIS' nested dissection of a rank's interior failed";
        return false;
      }
    std::vector<int> order(*interior_order);
    order.resize(n_interior + n_separator);
    std::iota(order.begin() + n_interior, order.end(), n_interior);
    cholesky.analyse(
      n_interior + n_separator, rows, cols, order, value_index, n_separator);
    const std::size_t n_entries = static_cast<std::size_t>(n_separator) * n_separator,
                      n_packed =
                        static_cast<std::size_t>(n_separator) * (n_separator + 1) / 2;
    separator.factor.assign(single ? 0 : n_entries, 0.);
    separator.packed.assign(single ? 0 : n_packed, 0.);
    separator_single.factor.assign(single ? n_entries : 0, 0.f);
    separator_single.packed.assign(single ? n_packed : 0, 0.f);
    separator_single.rhs.assign(single ? n_separator : 0, 0.f);
    schur.resize(n_entries);
    local.resize(n_interior + n_separator);
    return true;
  }


  bool
  SubdomainCholesky::factorize(const Epetra_CrsMatrix &matrix, const Epetra_Vector *rhs)
  {
    const FlushDenormals flush; // the separator's dense factorisation too
    double              *values = nullptr;
    int                 *offsets, *columns;
    matrix.ExtractCrsDataPointers(offsets, columns, values);
    bool definite = true;
    for (std::size_t i = 0; i < decoupled_rows.size(); ++i)
      {
        decoupled_diagonal[i] = values[decoupled_offsets[i]];
        definite              = definite && decoupled_diagonal[i] > 0.;
      }
    forwarded_rhs.clear();
    if (rhs != nullptr)
      {
        gather_local(*rhs);
        forwarded_rhs.assign(rhs->Values(), rhs->Values() + rhs->MyLength());
      }
    definite = io::on_all_ranks(
      definite && cholesky.factorize(values, rhs != nullptr ? local.data() : nullptr),
      communicator);
    if (definite && n_separator > 0)
      {
        std::fill(schur.begin(), schur.end(), 0.);
        cholesky.add_schur_complement(schur.data());
        definite = single ? factorize_separator(separator_single, MPI_FLOAT)
                          : factorize_separator(separator, MPI_DOUBLE);
      }
    if (!definite)
      {
        forwarded_rhs.clear();
        last_failure = "the Cholesky factorisation met a pivot that is not positive (the "
                       "matrix is not positive definite, or too ill-conditioned for the "
                       "factors' precision)";
      }
    return definite;
  }


  void
  SubdomainCholesky::gather_local(const Epetra_Vector &b)
  {
    const int n_interior = static_cast<int>(interior_rows.size());
    for (int i = 0; i < n_interior; ++i)
      local[i] = b[interior_rows[i]];
    // The separator's right-hand side enters on the rank that owns the row.
    std::fill(local.begin() + n_interior, local.end(), 0.);
    for (std::size_t i = 0; i < separator_rows.size(); ++i)
      local[n_interior + separator_index[i]] = b[separator_rows[i]];
  }


  void
  SubdomainCholesky::solve_separator(double *rhs)
  {
    sum_on_all_ranks(rhs, n_separator, MPI_DOUBLE, communicator);
    const auto solve_with = [&](auto &factor, auto *x) {
      dense::triangular_solve("N", n_separator, factor.data(), n_separator, x);
      dense::triangular_solve("T", n_separator, factor.data(), n_separator, x);
    };
    if (!single)
      return solve_with(separator.factor, rhs);
    std::vector<float> &x = separator_single.rhs;
    std::copy(rhs, rhs + n_separator, x.begin());
    solve_with(separator_single.factor, x.data());
    std::copy(x.begin(), x.end(), rhs);
  }


  void
  SubdomainCholesky::solve(const Epetra_Vector &b, Epetra_Vector &x)
  {
    const FlushDenormals flush;
    for (std::size_t i = 0; i < decoupled_rows.size(); ++i)
      x[decoupled_rows[i]] = b[decoupled_rows[i]] / decoupled_diagonal[i];
    // Whether factorize() substituted this b forward already (every rank decides
    // alike: both paths reduce the separator's right-hand side once).
    const bool forwarded = io::on_all_ranks(
      forwarded_rhs.size() == static_cast<std::size_t>(b.MyLength()) &&
        std::equal(forwarded_rhs.begin(), forwarded_rhs.end(), b.Values()),
      communicator);
    forwarded_rhs.clear();
    const auto separator_solve = [this](double *rhs) { solve_separator(rhs); };
    if (forwarded)
      cholesky.finish_solve(local.data(), separator_solve);
    else
      {
        gather_local(b);
        cholesky.solve(local.data(), separator_solve);
      }
    const int n_interior = static_cast<int>(interior_rows.size());
    for (int i = 0; i < n_interior; ++i)
      x[interior_rows[i]] = local[i];
    for (std::size_t i = 0; i < separator_rows.size(); ++i)
      x[separator_rows[i]] = local[n_interior + separator_index[i]];
  }


  template <typename Number>
  bool
  SubdomainCholesky::factorize_separator(Separator<Number> &in, const MPI_Datatype type)
  {
    // C = Σ_r (A_SS - A_{S I_r} A_{I_r I_r}⁻¹ A_{I_r S}): this rank's term (in `schur`),
    // its lower triangle packed for the sum, then factorised on every rank.
    const std::int64_t n = n_separator;
    std::size_t        p = 0;
    for (std::int64_t j = 0; j < n; ++j)
      for (std::int64_t i = j; i < n; ++i)
        in.packed[p++] = static_cast<Number>(schur[i + j * n]);
    sum_on_all_ranks(in.packed.data(),
                     static_cast<int>(in.packed.size()),
                     type,
                     communicator);
    p = 0;
    for (std::int64_t j = 0; j < n; ++j)
      for (std::int64_t i = j; i < n; ++i)
        in.factor[i + j * n] = in.packed[p++];
    // The same sum and the same kernel on every rank: the same factor.
    return dense::cholesky(n_separator, in.factor.data(), n_separator);
  }
} // namespace clothsim
