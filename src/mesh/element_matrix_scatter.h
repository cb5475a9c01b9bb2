#pragma once

// Adding element matrices to a Trilinos matrix of fixed sparsity by position: for an
// element whose dofs are all rows of this rank and none constrained, the place of each
// of its n x n entries in the matrix's compressed rows is found once (a column search
// per entry) and later assemblies add straight into the value arrays. This replaces
// AffineConstraints::distribute_local_to_global for those elements, which sorts the
// element's rows and, per entry, looks the global row and column up (measured: two
// thirds of a shell tangent's assembly), and gives the same matrix up to the order of
// summation. Elements with a constrained dof or a row of another rank are left to the
// caller (add() returns false), who passes them to distribute_local_to_global.

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace clothsim::mesh
{
  using namespace dealii;

  class ElementMatrixScatter
  {
  public:
    // Starts an assembly into `matrix`, for `n_elements` elements of `n_dofs` dofs each.
    // The positions found for an earlier matrix are kept if it is the same one with the
    // same sparsity: the same object, the same number of entries, and no matrix made
    // since (sparsity_changed()). A matrix made again for a new sparsity may sit at the
    // old one's address with as many entries (self-contact's couplings shift as a layer
    // slides), so the address and count alone cannot tell.
    void
    start(TrilinosWrappers::SparseMatrix &matrix,
          unsigned int                    n_elements,
          unsigned int                    n_dofs);

    // Forgets the positions found: the elements' dofs changed (a term whose elements
    // are made anew, such as the contacts lagged for friction at each step).
    void
    forget();

    // A matrix was made (Discretization::initialize_matrix): every scatter finds its
    // positions again at its next start().
    static void
    sparsity_changed()
    {
      ++generation;
    }
    // Adds `cell_matrix` of element `element` (dofs `dofs`) to the matrix, if all its
    // dofs are rows of this rank and none is constrained; returns false otherwise (the
    // matrix is then unchanged). Which dofs are constrained is read once per element and
    // matrix: `constraints` must be the same set at every call between two start()s
    // that find positions again.
    bool
    add(unsigned int                                element,
        const std::vector<types::global_dof_index> &dofs,
        const FullMatrix<double>                   &cell_matrix,
        const AffineConstraints<double>            &constraints);

    // The same for an element matrix stored row by row, entry (i, j) at
    // values[i * row_stride + j] (row_stride >= the number of dofs).
    bool
    add(unsigned int                                element,
        const std::vector<types::global_dof_index> &dofs,
        const double                               *values,
        unsigned int                                row_stride,
        const AffineConstraints<double>            &constraints);

    // Adds `value` to the diagonal entry of each of `dofs` (rows of this rank, entries of
    // the matrix; constrained or not) in the matrix of the last start(). Their places
    // are found at the first call and kept while the dofs and the matrix stay (swinging
    // sheet, N = 81: the unit diagonal of its 6,561 unused angle dofs, 0.32 ms per
    // tangent when looked up each time by SumIntoMyValues, 1 % of the run).
    void
    add_to_diagonal(const std::vector<types::global_dof_index> &dofs, double value);

  private:
    // An element's slot: where its rows and positions are (0, 1, ...), or one of these.
    static constexpr int unknown = -1; // not looked at since the positions were reset
    static constexpr int other   = -2; // to be added by the caller
    static inline unsigned long generation     = 0;
    unsigned long               built_at       = 0;
    const void                 *matrix_id      = nullptr;
    const void                 *constraints_id = nullptr;
    int                         n_nonzeros     = -1;
    unsigned int                n_dofs         = 0;
    // Per element its slot; per slot (in the order elements were first added: a term
    // that adds few of its elements, such as contact pairs, stores only those) the
    // element's rows (local indices) and the position of each entry (row-major) within
    // its row.
    std::vector<int>           slot;
    std::vector<int>           local_rows;
    std::vector<std::uint16_t> positions;
    // The start of each local row's values in the matrix.
    std::vector<double *> row_values;
    // add_to_diagonal()'s dofs and, for each, its local row and place in the row.
    std::vector<types::global_dof_index> diagonal_dofs;
    std::vector<std::pair<int, int>>     diagonal_places;
  };
} // namespace clothsim::mesh
