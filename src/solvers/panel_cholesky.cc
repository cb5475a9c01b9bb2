#include "solvers/panel_cholesky.h"

#include "solvers/dense_kernels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace clothsim::dense
{
  bool
  panel_kernel_available()
  {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }


  // Compiled for any CPU (it calls the BLAS wrappers of dense_kernels.h, which must not
  // be compiled for AVX2 here); its blocks go to panel_cholesky below.
  template <typename Number>
  bool
  blocked_panel_cholesky(const int k, const int m, Number *P, const int block_columns)
  {
    for (int j0 = 0; j0 < k; j0 += block_columns)
      {
        const int w = std::min(block_columns, k - j0), rows = m - j0, rest = k - j0 - w;
        Number   *block = P + static_cast<std::int64_t>(j0) * m + j0;
        if (!panel_cholesky(w, rows, block, m))
          return false;
        if (rest == 0)
          continue;
        const Number *below    = block + w; // the block's rows past its own columns
        Number       *trailing = block + static_cast<std::int64_t>(w) * m + w;
        subtract_gram(rest, w, below, m, trailing, m);
        if (rows - w > rest)
          subtract_product(
            rows - w - rest, rest, w, below + rest, m, below, m, trailing + rest, m);
      }
    return true;
  }

  template bool
  blocked_panel_cholesky(int, int, float *, int);
  template bool
  blocked_panel_cholesky(int, int, double *, int);
} // namespace clothsim::dense


// Everything below is compiled for AVX2 and FMA, and runs only where
// panel_kernel_available() said so.
#pragma GCC push_options
#pragma GCC target("avx2,fma")

namespace clothsim::dense
{
  namespace
  {
    // y[0 .. len) -= A x: A len x q (column-major, leading dimension lda), x[p] =
    // x_first[p * x_stride] (a row of the panel). Rows in blocks of four 256-bit
    // vectors held in registers over the whole sum, so that each entry of A is loaded
    // once and each of y once (GCC's vector extension; `a - s * b` contracts to FMA).
    template <typename Number>
    inline void
    subtract_row_product(const int     len,
                         const int     q,
                         const Number *A,
                         const int     lda,
                         const Number *x_first,
                         const int     x_stride,
                         Number       *y)
    {
      // Any alignment: the panel's columns start where they start.
      typedef Number Vector __attribute__((vector_size(32), aligned(sizeof(Number))));
      constexpr int  width = 32 / sizeof(Number);
      const auto     at    = [](const Number *p) {
        return *reinterpret_cast<const Vector *>(p);
      };
      // Rows [len - width, len) first, into a register, from y as given: stored last,
      // they overwrite the rows that the blocks below computed twice with the same
      // value, and no row is left to a scalar loop (for len >= width).
      const bool overhang = len > width && len % width != 0;
      Vector     last;
      if (overhang)
        {
          last = at(y + len - width);
          for (int p = 0; p < q; ++p)
            last -=
              x_first[p * x_stride] * at(A + static_cast<long>(p) * lda + len - width);
        }
      int i = 0;
      for (; i + 4 * width <= len; i += 4 * width)
        {
          Vector y0 = at(y + i), y1 = at(y + i + width), y2 = at(y + i + 2 * width),
                 y3 = at(y + i + 3 * width);
          for (int p = 0; p < q; ++p)
            {
              const Number  s = x_first[p * x_stride];
              const Number *a = A + static_cast<long>(p) * lda + i;
              y0 -= s * at(a);
              y1 -= s * at(a + width);
              y2 -= s * at(a + 2 * width);
              y3 -= s * at(a + 3 * width);
            }
          *reinterpret_cast<Vector *>(y + i)             = y0;
          *reinterpret_cast<Vector *>(y + i + width)     = y1;
          *reinterpret_cast<Vector *>(y + i + 2 * width) = y2;
          *reinterpret_cast<Vector *>(y + i + 3 * width) = y3;
        }
      for (; i + width <= len; i += width)
        {
          Vector y0 = at(y + i);
          for (int p = 0; p < q; ++p)
            y0 -= x_first[p * x_stride] * at(A + static_cast<long>(p) * lda + i);
          *reinterpret_cast<Vector *>(y + i) = y0;
        }
      if (overhang)
        *reinterpret_cast<Vector *>(y + len - width) = last;
      else
        for (; i < len; ++i)
          {
            Number sum = y[i];
            for (int p = 0; p < q; ++p)
              sum -= x_first[p * x_stride] * A[static_cast<long>(p) * lda + i];
            y[i] = sum;
          }
    }

    // t[c] = Σ_i A[i + c lda] y[i] over i in [0, len), for the Q columns c of A: Q vector
    // sums that share each load of y, then their lanes, then a scalar tail.
    template <int Q, typename Number>
    inline void
    column_dots(const int len, const Number *A, const int lda, const Number *y, Number *t)
    {
      typedef Number Vector __attribute__((vector_size(32), aligned(sizeof(Number))));
      constexpr int  width = 32 / sizeof(Number);
      const auto     at    = [](const Number *p) {
        return *reinterpret_cast<const Vector *>(p);
      };
      Vector sums[Q] = {};
      int    i       = 0;
      for (; i + width <= len; i += width)
        {
          const Vector yi = at(y + i);
          for (int c = 0; c < Q; ++c)
            sums[c] += at(A + static_cast<long>(c) * lda + i) * yi;
        }
      for (int c = 0; c < Q; ++c)
        {
          Number sum = 0;
          for (int l = 0; l < width; ++l)
            sum += sums[c][l];
          for (int tail = i; tail < len; ++tail)
            sum += A[static_cast<long>(c) * lda + tail] * y[tail];
          t[c] = sum;
        }
    }
  } // namespace


  template <typename Number>
  bool
  panel_cholesky(const int k, const int m, Number *P, const int ld)
  {
    // Column j, rows j .. m - 1: a_j - [L]_{j.., 0..j-1} [L]_{j, 0..j-1}ᵀ, then divided
    // by the root of its diagonal entry (left-looking Cholesky; Golub & Van Loan,
    // Matrix Computations, 4th ed., algorithm 4.2.1, over the panel's rows).
    for (int j = 0; j < k; ++j)
      {
        Number *column = P + static_cast<long>(j) * ld + j;
        subtract_row_product(m - j, j, P + j, ld, P + j, ld, column);
        if (!(column[0] > 0))
          return false;
        const Number root = std::sqrt(column[0]), inverse = Number(1) / root;
        column[0] = root;
        for (int i = 1; i < m - j; ++i)
          column[i] *= inverse;
      }
    return true;
  }

  template <typename Number>
  void
  panel_forward_solve(const int k, const int m, const Number *L, Number *z)
  {
    // Columns in blocks of 8 (column-oriented forward substitution; Golub & Van Loan,
    // section 3.1): the block's own triangle, then the rows below it less the block's
    // columns times its solved entries, in one pass that loads each entry of L and z
    // once.
    constexpr int block = 8;
    for (int j0 = 0; j0 < k; j0 += block)
      {
        const int j1 = std::min(k, j0 + block);
        for (int j = j0; j < j1; ++j)
          {
            const Number *column = L + static_cast<long>(j) * m;
            z[j] /= column[j];
            for (int i = j + 1; i < j1; ++i)
              z[i] -= column[i] * z[j];
          }
        subtract_row_product(
          m - j1, j1 - j0, L + static_cast<long>(j0) * m + j1, m, z + j0, 1, z + j1);
      }
  }


  template <typename Number>
  void
  panel_backward_solve(const int k, const int m, const Number *L, Number *z)
  {
    // Columns in blocks of 4, the last first: t_j = L_{j1 .., j}ᵀ z_{j1 ..} for the
    // block's columns j (below the block, four dot products sharing each load of z), then
    // z_j = (z_j - t_j - Σ_{j < i < j1} L_ij z_i) / L_jj up the block's triangle.
    constexpr int block = 4;
    for (int j1 = k; j1 > 0; j1 -= block)
      {
        const int j0 = std::max(0, j1 - block);
        Number    t[block];
        if (j1 - j0 == block)
          column_dots<block>(m - j1, L + static_cast<long>(j0) * m + j1, m, z + j1, t);
        else
          for (int j = j0; j < j1; ++j)
            column_dots<1>(
              m - j1, L + static_cast<long>(j) * m + j1, m, z + j1, t + j - j0);
        for (int j = j1 - 1; j >= j0; --j)
          {
            const Number *column = L + static_cast<long>(j) * m;
            Number        sum    = z[j] - t[j - j0];
            for (int i = j + 1; i < j1; ++i)
              sum -= column[i] * z[i];
            z[j] = sum / column[j];
          }
      }
  }

  template bool
  panel_cholesky(int, int, float *, int);
  template bool
  panel_cholesky(int, int, double *, int);
  template void
  panel_forward_solve(int, int, const float *, float *);
  template void
  panel_forward_solve(int, int, const double *, double *);
  template void
  panel_backward_solve(int, int, const float *, float *);
  template void
  panel_backward_solve(int, int, const double *, double *);
} // namespace clothsim::dense

#pragma GCC pop_options
