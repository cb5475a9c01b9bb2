#pragma once

// The Cholesky factorisation of a supernode's panel, written out with AVX2 and FMA: the
// m x k panel [A11; A21] of a front (k pivot columns) becomes [L11; L21], L11 L11ᵀ = A11
// and L21 = A21 L11⁻ᵀ, in one left-looking pass over its columns. It does what LAPACK's
// potrf on A11 followed by BLAS' trsm on A21 do, in one loop over a panel that stays in
// cache: for the small and middling panels of a 2D mesh's fronts (k up to about 100)
// OpenBLAS spends most of that time on its calls' set-up and on potrf's column-by-column
// dot products (README, "Numerical choices", "Written-out panels": the measurements).

namespace clothsim::dense
{
  // Whether this CPU runs the written-out panel (AVX2 and FMA); without them, the callers
  // use BLAS and LAPACK.
  bool
  panel_kernel_available();

  // P: the m x k panel, column-major with leading dimension m (A11's lower triangle
  // read). Returns false (P partly overwritten) if a pivot is not positive. Only where
  // panel_kernel_available().
  template <typename Number>
  bool
  panel_cholesky(int k, int m, Number *P);
} // namespace clothsim::dense
