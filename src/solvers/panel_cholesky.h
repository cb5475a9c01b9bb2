#pragma once

// The Cholesky factorisation of a supernode's panel, and the substitutions through it,
// written out with AVX2 and FMA: the m x k panel [A11; A21] of a front (k pivot columns)
// becomes [L11; L21], L11 L11ᵀ = A11 and L21 = A21 L11⁻ᵀ, in one left-looking pass over
// its columns. It does what LAPACK's potrf on A11 followed by BLAS' trsm on A21 do, in
// one loop over a panel that stays in cache: for the small and middling panels of a 2D
// mesh's fronts (k up to about 100) OpenBLAS spends most of that time on its calls'
// set-up and on potrf's column-by-column dot products (README, "Numerical choices",
// "Written-out panels": the measurements).

namespace clothsim::dense
{
  // Whether this CPU runs the written-out panel (AVX2 and FMA); without them, the callers
  // use BLAS and LAPACK.
  bool
  panel_kernel_available();

  // P: the m x k panel, column-major with leading dimension ld >= m (A11's lower
  // triangle read). Returns false (P partly overwritten) if a pivot is not positive.
  // Only where panel_kernel_available().
  template <typename Number>
  bool
  panel_cholesky(int k, int m, Number *P, int ld);

  // The same for a panel of any width, in blocks of `block_columns` columns: each
  // block's columns (all rows from its diagonal down) by panel_cholesky, then the
  // columns right of it less the block's contribution, BLAS' syrk on their diagonal
  // square and gemm on the rows below it (right-looking over the blocks; Golub & Van
  // Loan, section 4.2.9). Blocks of 32 to 64 columns measured 5 to 12 % faster than
  // LAPACK's potrf and BLAS' trsm on panels of more than 96 columns (N = 321), 4 % on
  // all (N = 81); 96 and 192 no faster (README, "Large panels in blocks"). Only where
  // panel_kernel_available().
  template <typename Number>
  bool
  blocked_panel_cholesky(int k, int m, Number *P, int block_columns);

  // The substitutions through a factorised panel L = [L11; L21] (m x k, leading
  // dimension m), on z = [z1; z2] (z1 k entries, z2 the m - k rows below), one pass over
  // L each, column by column:
  //   forward:  z1 = L11⁻¹ z1, then z2 -= L21 z1 (each column an axpy);
  //   backward: z1 = L11⁻ᵀ (z1 - L21ᵀ z2)        (each column a dot product).
  // What BLAS' trsv and gemv do in two calls, whose set-up costs more than the work for
  // a 2D mesh's small fronts. Only where panel_kernel_available().
  template <typename Number>
  void
  panel_forward_solve(int k, int m, const Number *L, Number *z);
  template <typename Number>
  void
  panel_backward_solve(int k, int m, const Number *L, Number *z);
} // namespace clothsim::dense
