#include "mesh/element_matrix_scatter.h"

#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <limits>
#include <string>

namespace clothsim::mesh
{
  void
  ElementMatrixScatter::start(TrilinosWrappers::SparseMatrix &matrix,
                              const unsigned int              n_elements,
                              const unsigned int              n_dofs)
  {
    // The matrix is ours to fill: deal.II hands out its Epetra matrix read-only only.
    auto &crs     = const_cast<Epetra_CrsMatrix &>(matrix.trilinos_matrix());
    bool  rebuilt = false;
    if (&crs != matrix_id || crs.NumMyNonzeros() != n_nonzeros ||
        n_dofs != this->n_dofs || slot.size() != n_elements || built_at != generation)
      {
        rebuilt      = true;
        built_at     = generation;
        matrix_id    = &crs;
        n_nonzeros   = crs.NumMyNonzeros();
        this->n_dofs = n_dofs;
        slot.assign(n_elements, unknown);
        local_rows.clear();
        positions.clear();
        diagonal_dofs.clear();
      }
    // Each row's values, looked up again unless the matrix keeps them in one array
    // (StorageOptimized) that has not moved: a loop over all rows at every start would
    // cost a large sheet's term with few elements (contact) more than its elements.
    const int  n_rows = crs.NumMyRows();
    const auto view   = [&crs](const int row) {
      int     n_entries = 0;
      double *values    = nullptr;
      int    *columns   = nullptr;
      crs.ExtractMyRowView(row, n_entries, values, columns);
      return values;
    };
    if (!rebuilt && crs.StorageOptimized() && n_rows > 0 &&
        row_values.size() == std::size_t(n_rows) && row_values.front() == view(0) &&
        row_values.back() == view(n_rows - 1))
      return;
    row_values.resize(n_rows);
    for (int row = 0; row < n_rows; ++row)
      row_values[row] = view(row);
  }


  void
  ElementMatrixScatter::forget()
  {
    slot.assign(slot.size(), unknown);
    local_rows.clear();
    positions.clear();
  }


  void
  ElementMatrixScatter::add_to_diagonal(const std::vector<types::global_dof_index> &dofs,
                                        const double                                value)
  {
    Assert(matrix_id != nullptr, ExcMessage("add_to_diagonal() before start()"));
    if (dofs != diagonal_dofs)
      {
        const auto &crs = *static_cast<const Epetra_CrsMatrix *>(matrix_id);
        diagonal_places.clear();
        for (const types::global_dof_index dof : dofs)
          {
            const int  row       = crs.RowMap().LID(static_cast<int>(dof));
            const int  column    = crs.ColMap().LID(static_cast<int>(dof));
            int        n_entries = 0;
            double    *values    = nullptr;
            int       *columns   = nullptr;
            const int *found     = nullptr;
            if (row >= 0 && column >= 0 &&
                crs.ExtractMyRowView(row, n_entries, values, columns) == 0)
              found = std::find(columns, columns + n_entries, column);
            AssertThrow(found != nullptr && found != columns + n_entries,
                        ExcMessage("the diagonal entry of dof " + std::to_string(dof) +
                                   " is not in this rank's rows of the matrix"));
            diagonal_places.emplace_back(row, static_cast<int>(found - columns));
          }
        diagonal_dofs = dofs;
      }
    for (const auto &[row, place] : diagonal_places)
      row_values[row][place] += value;
  }


  bool
  ElementMatrixScatter::add(const unsigned int                          element,
                            const std::vector<types::global_dof_index> &dofs,
                            const FullMatrix<double>                   &cell_matrix,
                            const AffineConstraints<double>            &constraints)
  {
    AssertDimension(cell_matrix.m(), dofs.size());
    AssertDimension(cell_matrix.n(), dofs.size());
    return add(element, dofs, &cell_matrix(0, 0), cell_matrix.n(), constraints);
  }


  bool
  ElementMatrixScatter::add(const unsigned int                          element,
                            const std::vector<types::global_dof_index> &dofs,
                            const double                               *values,
                            const unsigned int                          row_stride,
                            const AffineConstraints<double>            &constraints)
  {
    AssertDimension(dofs.size(), n_dofs);
    Assert(row_stride >= n_dofs, ExcInternalError());
    if (constraints_id != &constraints)
      {
        // Another constraint set: which elements touch a constrained dof may differ.
        constraints_id = &constraints;
        forget();
      }
    if (slot[element] == unknown)
      {
        // Find the entries once: local row, and the column's place in that row.
        const auto &crs   = *static_cast<const Epetra_CrsMatrix *>(matrix_id);
        const auto  first = static_cast<std::ptrdiff_t>(local_rows.size());
        local_rows.resize(local_rows.size() + n_dofs);
        positions.resize(positions.size() + std::size_t(n_dofs) * n_dofs);
        bool direct = true;
        for (const types::global_dof_index dof : dofs)
          direct = direct && !constraints.is_constrained(dof);
        for (unsigned int i = 0; i < n_dofs && direct; ++i)
          {
            const int row           = crs.RowMap().LID(static_cast<int>(dofs[i]));
            int       n_entries     = 0;
            double   *values_of_row = nullptr;
            int      *columns       = nullptr;
            direct                  = row >= 0 &&
                     crs.ExtractMyRowView(row, n_entries, values_of_row, columns) == 0;
            local_rows[first + i] = row;
            for (unsigned int j = 0; j < n_dofs && direct; ++j)
              {
                const int        column = crs.ColMap().LID(static_cast<int>(dofs[j]));
                const int *const found =
                  column < 0 ? columns + n_entries
                             : std::find(columns, columns + n_entries, column);
                direct = found != columns + n_entries &&
                         found - columns <= std::numeric_limits<std::uint16_t>::max();
                positions[first * n_dofs + i * n_dofs + j] =
                  static_cast<std::uint16_t>(found - columns);
              }
          }
        if (direct)
          slot[element] = static_cast<int>(first / n_dofs);
        else
          {
            slot[element] = other;
            local_rows.resize(first);
            positions.resize(first * n_dofs);
          }
      }
    if (slot[element] == other)
      return false;
    const int *const           rows = &local_rows[std::size_t(slot[element]) * n_dofs];
    const std::uint16_t *const position =
      &positions[std::size_t(slot[element]) * n_dofs * n_dofs];
    for (unsigned int i = 0; i < n_dofs; ++i)
      {
        double *const        row_of_matrix = row_values[rows[i]];
        const double *const  row_of_cell   = values + std::size_t(i) * row_stride;
        const std::uint16_t *place         = position + i * n_dofs;
        for (unsigned int j = 0; j < n_dofs; ++j)
          row_of_matrix[place[j]] += row_of_cell[j];
      }
    return true;
  }
} // namespace clothsim::mesh
