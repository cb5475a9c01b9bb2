#include "solvers/block_preconditioner.h"

#include <deal.II/base/mpi.h>

#include <Epetra_Map.h>

namespace clothsim
{
  BlockPreconditioner::BlockPreconditioner(const IndexSet &owned_dofs,
                                           const IndexSet &relevant_dofs,
                                           const IndexSet &displacement_dofs,
                                           const MPI_Comm  communicator)
    : communicator(communicator)
    , owned(owned_dofs)
  {
    // The displacement block's numbering: this rank's displacements, in dof order, form
    // one contiguous range after those of the lower ranks.
    const unsigned long long n_local = displacement_dofs.n_elements();
    unsigned long long       offset  = 0;
    MPI_Exscan(&n_local, &offset, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, communicator);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      offset = 0;
    const unsigned long long n_total = Utilities::MPI::sum(n_local, communicator);
    block_owned                      = IndexSet(n_total);
    block_owned.add_range(offset, offset + n_local);
    block_owned.compress();

    TrilinosWrappers::MPI::Vector block_index_owned(owned, communicator);
    for (const types::global_dof_index dof : owned)
      {
        if (displacement_dofs.is_element(dof))
          {
            block_index_owned[dof] = offset + displacement_local.size();
            displacement_local.push_back(owned.index_within_set(dof));
          }
        else
          {
            block_index_owned[dof] = -1.;
            other_local.push_back(owned.index_within_set(dof));
          }
      }
    block_index_owned.compress(VectorOperation::insert);
    block_index_ghosted.reinit(owned, relevant_dofs, communicator);
    block_index_ghosted = block_index_owned;
    block_src.reinit(block_owned, communicator);
    block_dst.reinit(block_owned, communicator);
  }


  void
  BlockPreconditioner::initialize(const TrilinosWrappers::SparseMatrix &matrix,
                                  const Teuchos::ParameterList         &ml_parameters)
  {
    tangent                   = &matrix;
    const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
    if (full_in.size() != matrix.m())
      {
        full_in.reinit(owned, communicator);
        full_out.reinit(owned, communicator);
      }
    if (column_block.size() != static_cast<std::size_t>(A.NumMyCols()))
      {
        column_block.resize(A.NumMyCols());
        for (int c = 0; c < A.NumMyCols(); ++c)
          column_block[c] = static_cast<int>(block_index_ghosted(A.ColMap().GID(c)));
      }

    // A: the displacement rows restricted to displacement columns; the hinge stencil of
    // the Schur correction makes rows longer. The first tangent builds S̃'s profile; later
    // ones (the same sparsity: a new one makes a new BlockPreconditioner) only replace
    // its values: on one rank in place, row by row (about 0.07 s per tangent on the swing
    // at N = 161), on several by Epetra's sums (0.22 s there), against 0.44 s to build
    // it. The old hierarchy first: it refers to the old matrix (ML's IFPACK smoothers
    // read it when destroyed).
    amg.reset();
    const bool refill = block_matrix != nullptr;
    if (refill && Utilities::MPI::n_mpi_processes(communicator) == 1)
      refill_in_place(A);
    else
      fill_by_sums(A, refill);
    amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    amg->initialize(*block_matrix, ml_parameters);
  }


  void
  BlockPreconditioner::set_inverse_diagonal(const unsigned int angle,
                                            const double       diagonal)
  {
    AssertThrow(diagonal > 0.,
                ExcMessage("the tangent has a non-positive diagonal entry on a director "
                           "angle"));
    other_inverse_diagonal[angle] = 1. / diagonal;
  }


  void
  BlockPreconditioner::fill_by_sums(const Epetra_CrsMatrix &A, const bool refill)
  {
    if (refill)
      block_matrix->PutScalar(0.);
    else
      block_matrix = std::make_unique<Epetra_FECrsMatrix>(
        Copy, block_owned.make_trilinos_map(communicator, /*overlapping=*/false), 64);
    const int first_row = block_owned.n_elements() > 0 ? *block_owned.begin() : 0;

    // The row of the tangent with local index `row`, split into displacement columns
    // (block numbering) and the diagonal entry.
    std::vector<int>    columns;
    std::vector<double> entries;
    const auto          split_row = [&](const int row, double &diagonal) {
      int     n;
      double *values;
      int    *indices;
      A.ExtractMyRowView(row, n, values, indices);
      const int row_gid = A.RowMap().GID(row);
      columns.clear();
      entries.clear();
      diagonal = 0.;
      for (int e = 0; e < n; ++e)
        {
          if (A.ColMap().GID(indices[e]) == row_gid)
            diagonal = values[e];
          if (column_block[indices[e]] >= 0)
            {
              columns.push_back(column_block[indices[e]]);
              entries.push_back(values[e]);
            }
        }
    };

    const auto add = [&](const int     n_rows,
                         const int    *row_indices,
                         const int     n_columns,
                         const int    *column_indices,
                         const double *values) {
      const int status =
        refill ? block_matrix->SumIntoGlobalValues(n_rows,
                                                   row_indices,
                                                   n_columns,
                                                   column_indices,
                                                   values,
                                                   Epetra_FECrsMatrix::ROW_MAJOR)
               : block_matrix->InsertGlobalValues(n_rows,
                                                  row_indices,
                                                  n_columns,
                                                  column_indices,
                                                  values,
                                                  Epetra_FECrsMatrix::ROW_MAJOR);
      AssertThrow(status >= 0 && !(refill && status > 0),
                  ExcMessage("the Schur complement's profile does not hold an entry "
                             "of the tangent (Epetra status " +
                             std::to_string(status) + ")"));
    };
    double unused_diagonal;
    for (unsigned int k = 0; k < displacement_local.size(); ++k)
      {
        split_row(displacement_local[k], unused_diagonal);
        const int row = first_row + k;
        add(1, &row, columns.size(), columns.data(), entries.data());
      }

    // D and -B D⁻¹ Bᵀ: each angle row's displacement entries b give -b bᵀ / D_ψψ.
    other_inverse_diagonal.resize(other_local.size());
    std::vector<double> outer;
    for (unsigned int k = 0; k < other_local.size(); ++k)
      {
        double diagonal;
        split_row(other_local[k], diagonal);
        set_inverse_diagonal(k, diagonal);
        if (columns.empty())
          continue;
        outer.resize(columns.size() * columns.size());
        for (unsigned int a = 0; a < columns.size(); ++a)
          for (unsigned int b = 0; b < columns.size(); ++b)
            outer[a * columns.size() + b] = -entries[a] * entries[b] / diagonal;
        add(columns.size(), columns.data(), columns.size(), columns.data(), outer.data());
      }
    // Later tangents reuse the profile and the exporter of other ranks' rows.
    block_matrix->GlobalAssemble(/*callFillComplete=*/!refill,
                                 Add,
                                 /*save_off_and_reuse_map_exporter=*/true);
  }


  void
  BlockPreconditioner::refill_in_place(const Epetra_CrsMatrix &A)
  {
    if (column_row.empty())
      {
        // One rank: every column is a row of this rank.
        column_row.resize(A.NumMyCols());
        for (int c = 0; c < A.NumMyCols(); ++c)
          column_row[c] = A.RowMap().LID(A.ColMap().GID(c));
        angle_of_row.assign(A.NumMyRows(), -1);
        for (unsigned int k = 0; k < other_local.size(); ++k)
          angle_of_row[other_local[k]] = k;
        block_column.assign(A.NumMyCols(), -1);
        for (int c = 0; c < A.NumMyCols(); ++c)
          if (column_block[c] >= 0)
            block_column[c] = block_matrix->LCID(column_block[c]);
        scatter.assign(block_matrix->NumMyCols(), -1);
      }

    for (unsigned int k = 0; k < other_local.size(); ++k)
      {
        int     n;
        double *values;
        int    *indices;
        A.ExtractMyRowView(other_local[k], n, values, indices);
        double diagonal = 0.;
        for (int e = 0; e < n; ++e)
          if (column_row[indices[e]] == other_local[k])
            diagonal = values[e];
        set_inverse_diagonal(k, diagonal);
      }

    // S̃'s row of displacement i: A's own entries, then −(A_iψ / D_ψψ) A_ψ for each angle
    // ψ of the row, through a scatter of S̃'s columns (no search per entry). A is
    // symmetric, so this is the outer products' sum by rows.
    bool missing = false;
    for (unsigned int k = 0; k < displacement_local.size(); ++k)
      {
        int     n_s, n, m;
        double *s_values, *values, *angle_values;
        int    *s_indices, *indices, *angle_indices;
        block_matrix->ExtractMyRowView(k, n_s, s_values, s_indices);
        for (int e = 0; e < n_s; ++e)
          {
            scatter[s_indices[e]] = e;
            s_values[e]           = 0.;
          }
        const auto add = [&](const int column, const double value) {
          const int position =
            block_column[column] >= 0 ? scatter[block_column[column]] : -1;
          if (position < 0)
            missing = true;
          else
            s_values[position] += value;
        };
        A.ExtractMyRowView(displacement_local[k], n, values, indices);
        for (int e = 0; e < n; ++e)
          {
            if (column_block[indices[e]] >= 0)
              {
                add(indices[e], values[e]);
                continue;
              }
            const int row   = column_row[indices[e]];
            const int angle = row >= 0 ? angle_of_row[row] : -1;
            if (angle < 0)
              continue;
            const double weight = values[e] * other_inverse_diagonal[angle];
            A.ExtractMyRowView(row, m, angle_values, angle_indices);
            for (int f = 0; f < m; ++f)
              if (column_block[angle_indices[f]] >= 0)
                add(angle_indices[f], -weight * angle_values[f]);
          }
        for (int e = 0; e < n_s; ++e)
          scatter[s_indices[e]] = -1;
      }
    AssertThrow(!missing,
                ExcMessage("the Schur complement's profile does not hold an entry of "
                           "the tangent"));
  }


  void
  BlockPreconditioner::vmult(TrilinosWrappers::MPI::Vector       &dst,
                             const TrilinosWrappers::MPI::Vector &src) const
  {
    const Epetra_Vector &s   = *src.trilinos_vector()(0);
    Epetra_Vector       &d   = *dst.trilinos_vector()(0);
    Epetra_Vector       &in  = *full_in.trilinos_vector()(0);
    Epetra_Vector       &out = *full_out.trilinos_vector()(0);
    Epetra_Vector       &bs  = *block_src.trilinos_vector()(0);
    Epetra_Vector       &bd  = *block_dst.trilinos_vector()(0);

    // y_ψ = D⁻¹ r_ψ, then r_u - B y_ψ.
    in.PutScalar(0.);
    for (unsigned int k = 0; k < other_local.size(); ++k)
      in[other_local[k]] = other_inverse_diagonal[k] * s[other_local[k]];
    tangent->vmult(full_out, full_in);
    for (unsigned int k = 0; k < displacement_local.size(); ++k)
      bs[k] = s[displacement_local[k]] - out[displacement_local[k]];

    // z_u = S̃⁻¹ (...)
    amg->vmult(block_dst, block_src);

    // z_ψ = D⁻¹ (r_ψ - Bᵀ z_u).
    in.PutScalar(0.);
    for (unsigned int k = 0; k < displacement_local.size(); ++k)
      in[displacement_local[k]] = bd[k];
    tangent->vmult(full_out, full_in);
    for (unsigned int k = 0; k < displacement_local.size(); ++k)
      d[displacement_local[k]] = bd[k];
    for (unsigned int k = 0; k < other_local.size(); ++k)
      d[other_local[k]] =
        other_inverse_diagonal[k] * (s[other_local[k]] - out[other_local[k]]);
  }
} // namespace clothsim
