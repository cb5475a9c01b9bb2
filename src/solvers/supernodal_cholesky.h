#pragma once

// Sparse Cholesky factorisation A = P L Lᵀ Pᵀ in single or double precision, multifrontal
// and supernodal (Duff & Reid, ACM TOMS 9, 1983; Liu, SIAM Review 34, 1992), for a
// sequence of symmetric positive definite matrices that share one sparsity: a Newton
// run's tangents. Everything that depends only on the sparsity is computed once by
// analyse(): the elimination tree, the supernodes (relaxed amalgamation as in CHOLMOD:
// Chen, Davis, Hager & Rajamanickam, ACM TOMS 35, 2008), where each matrix entry lands in
// its front, and where each child's update lands in its parent's front. factorize() then
// runs only dense kernels (BLAS, LAPACK and solvers/panel_cholesky) and precomputed
// scatters: no searching, sorting or allocation, which is what a general-purpose solver
// spends most of its time on for the small fronts of a 2D mesh.

#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

namespace clothsim
{
  class SupernodalCholesky
  {
  public:
    // The factors' precision (the matrix is given in double either way). Each front's
    // panel is factorised by dense::panel_cholesky in blocks of
    // `written_out_block_columns` columns (BLAS' syrk and gemm between the blocks), and
    // its substitutions in solve() done by dense::panel_forward_solve and
    // panel_backward_solve, where this CPU runs them, unless `blas_panels` (LAPACK's
    // potrf, BLAS' trsm, trsv and gemv, as on CPUs without AVX2; tests compare the two).
    explicit SupernodalCholesky(bool single_precision = true, bool blas_panels = false);

    static constexpr int written_out_block_columns = 64;

    // A front's update for its parent, C -= A Aᵀ (A its r x k rows below the pivots),
    // is BLAS' syrk on C's lower triangle, or, for r <= square_update_rows, gemm on the
    // whole r x r square (twice the operations; C's upper triangle is never read). The
    // default is gemm where OpenBLAS runs its AVX-512 kernels, whose syrk is slow on
    // small blocks (perf: its ssyrk_kernel_L), and syrk elsewhere (with the AVX2
    // kernels gemm was 2 to 9 % slower; README, "OpenBLAS' kernels").
    static constexpr int square_update_rows = 128;
    void
    set_square_updates(const bool square)
    {
      square_updates = square;
    }
    bool
    updates_square() const
    {
      return square_updates;
    }

    // The pattern of the upper triangle (0-based, rows[k] <= columns[k], each entry
    // once), and the elimination order: order[p] is the row eliminated p-th (a
    // fill-reducing permutation, e.g. from MUMPS' analysis). Entry k's value will be
    // values[value_index[k]] in factorize() (values[k] if value_index is empty), e.g.
    // its position in a compressed-row matrix's value array that holds both triangles.
    // The last `n_schur` rows of the order (the Schur block S, the others I) are not
    // eliminated: they form one dense front at the root, which after factorize() holds
    // the Schur complement A_SS - A_SI A_II⁻¹ A_IS (George, SIAM J. Numer. Anal. 10,
    // 1973: the top separator of a nested dissection, here left to the caller).
    void
    analyse(int                     n,
            const std::vector<int> &rows,
            const std::vector<int> &columns,
            const std::vector<int> &order,
            const std::vector<int> &value_index = {},
            int                     n_schur     = 0);

    // Factorises the matrix whose upper-triangle entries are in `values` (where
    // analyse() placed them). Returns false if a pivot is not positive (the matrix is not
    // positive definite, or too ill-conditioned for the factors' precision). With `rhs`
    // (n entries), the forward substitution of rhs is done front by front as each is
    // factorised, while its panel is still in cache, and finish_solve() completes x =
    // A⁻¹ rhs with the backward substitution alone (after the Schur block's solve, if
    // there is one): one pass over the factors less than solve() (Newton's tangent and
    // right-hand side arrive together).
    bool
    factorize(const double *values, const double *rhs = nullptr);

    // After factorize(values, rhs): x = A⁻¹ rhs, bit for bit what solve(x, schur_solve)
    // on rhs gives (`schur_solve` as there, needed with a Schur block). Once per such
    // factorize(); throws std::logic_error otherwise.
    void
    finish_solve(double *x, const std::function<void(double *)> &schur_solve = {});

    // With a Schur block: adds the last factorisation's Schur complement to `schur`, the
    // lower triangle of an n_schur x n_schur column-major matrix (row and column i are
    // order[n - n_schur + i]).
    void
    add_schur_complement(double *schur) const;

    // x = A⁻¹ b in place, with the last factors. With a Schur block, after the forward
    // substitution through I, `schur_solve` gets the Schur block's right-hand side
    // b_S - A_SI A_II⁻¹ b_I (in the order of add_schur_complement) and must replace it
    // by x_S; the backward substitution through I follows.
    void
    solve(double *x, const std::function<void(double *)> &schur_solve = {});

    // Floating-point operations of one factorisation, and entries in the factor.
    double
    operations() const
    {
      return n_operations;
    }
    std::int64_t
    factor_entries() const
    {
      return n_factor_entries;
    }
    // Whether the panels are factorised by dense::panel_cholesky (and the substitutions
    // written out too).
    bool
    writes_out_panels() const
    {
      return written_out_panels;
    }
    int
    n_supernodes() const
    {
      return static_cast<int>(first_column.size()) - 1;
    }

  private:
    int n       = 0;
    int n_schur = 0; // the Schur block: the last supernode, not factorised
    // Supernode s holds the permuted columns first_column[s] .. first_column[s + 1] - 1;
    // its front's rows are those columns followed by below_rows[below_start[s] ..
    // below_start[s + 1] - 1] (permuted indices, increasing).
    std::vector<int>          first_column;
    std::vector<int>          below_start;
    std::vector<int>          below_rows;
    std::vector<int>          child_start; // s's children: child_list[child_start[s] ..]
    std::vector<int>          child_list;
    std::vector<int>          parent_map; // s's update rows in its parent's front
    std::vector<int>          parent_map_start;
    std::vector<std::int64_t> factor_start; // s's m x k panel in `factor`
    std::vector<int>          permutation;  // permuted index of each original row
    // Matrix entries, grouped by supernode: value index and position in the front.
    std::vector<int>          entry_start;
    std::vector<int>          entry_index;
    std::vector<std::int64_t> entry_position;

    // The numeric part in the factors' precision.
    template <typename Number>
    struct Numeric
    {
      std::vector<Number> factor;
      // Updates waiting for their parent, by the parity of their supernode's depth.
      std::vector<Number> stacks[2];
      std::vector<Number> work; // solve
      std::vector<Number> rhs;  // solve, permuted
    };
    // Sizes numeric's arrays for this analysis (once: analyse() empties them).
    template <typename Number>
    void
    allocate(Numeric<Number> &numeric) const;
    template <typename Number>
    bool
    factorize(Numeric<Number> &numeric, const double *values, const double *rhs);
    // With `forwarded`, numeric.rhs already holds the forward substitution's result.
    template <typename Number>
    void
    solve(Numeric<Number>                     &numeric,
          double                              *x,
          const std::function<void(double *)> &schur_solve,
          bool                                 forwarded);
    // Supernode s's front in the substitutions: k pivot columns and r rows below, its
    // m x k panel L, its pivots' entries xs of the permuted right-hand side, and the
    // rows below.
    template <typename Number>
    struct Front
    {
      int           k, r, m;
      const Number *L;
      Number       *xs;
      const int    *below;
      // Its rows of the right-hand side in `work`, pivots first (the written-out
      // substitutions work on them there).
      void
      gather(const Number *rhs, Number *work) const
      {
        std::copy(xs, xs + k, work);
        for (int i = 0; i < r; ++i)
          work[k + i] = rhs[below[i]];
      }
    };
    template <typename Number>
    Front<Number>
    front(Numeric<Number> &numeric, int s) const;
    // The forward (L z = b) or backward (Lᵀ x = z) substitution through front s, in
    // place on numeric.rhs.
    template <typename Number>
    void
    substitute(Numeric<Number> &numeric, int s, bool forward) const;

    bool              single;
    bool              written_out_panels;
    bool              square_updates;
    Numeric<float>    in_single;
    Numeric<double>   in_double;
    double            n_operations     = 0.;
    std::int64_t      n_factor_entries = 0;
    std::int64_t      max_stack[2]     = {0, 0};
    std::int64_t      largest_front    = 0; // rows of the largest front
    std::vector<char> parity;               // of each supernode's depth in the tree
    bool              forwarded = false;    // finish_solve() may follow
  };
} // namespace clothsim
