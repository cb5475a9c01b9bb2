#pragma once

// The dense kernels of solvers/supernodal_cholesky in single or double precision: thin
// wrappers of BLAS and LAPACK (OpenBLAS on Debian), column-major, lower triangles.

#include <type_traits>

// BLAS and LAPACK (OpenBLAS on Debian), column-major.
extern "C" {
void
spotrf_(const char *uplo, const int *n, float *a, const int *lda, int *info);
void
dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
void
strsm_(const char  *side,
       const char  *uplo,
       const char  *transa,
       const char  *diag,
       const int   *m,
       const int   *n,
       const float *alpha,
       const float *a,
       const int   *lda,
       float       *b,
       const int   *ldb);
void
dtrsm_(const char   *side,
       const char   *uplo,
       const char   *transa,
       const char   *diag,
       const int    *m,
       const int    *n,
       const double *alpha,
       const double *a,
       const int    *lda,
       double       *b,
       const int    *ldb);
void
ssyrk_(const char  *uplo,
       const char  *trans,
       const int   *n,
       const int   *k,
       const float *alpha,
       const float *a,
       const int   *lda,
       const float *beta,
       float       *c,
       const int   *ldc);
void
dsyrk_(const char   *uplo,
       const char   *trans,
       const int    *n,
       const int    *k,
       const double *alpha,
       const double *a,
       const int    *lda,
       const double *beta,
       double       *c,
       const int    *ldc);
void
strsv_(const char  *uplo,
       const char  *trans,
       const char  *diag,
       const int   *n,
       const float *a,
       const int   *lda,
       float       *x,
       const int   *incx);
void
dtrsv_(const char   *uplo,
       const char   *trans,
       const char   *diag,
       const int    *n,
       const double *a,
       const int    *lda,
       double       *x,
       const int    *incx);
void
sgemm_(const char  *transa,
       const char  *transb,
       const int   *m,
       const int   *n,
       const int   *k,
       const float *alpha,
       const float *a,
       const int   *lda,
       const float *b,
       const int   *ldb,
       const float *beta,
       float       *c,
       const int   *ldc);
void
dgemm_(const char   *transa,
       const char   *transb,
       const int    *m,
       const int    *n,
       const int    *k,
       const double *alpha,
       const double *a,
       const int    *lda,
       const double *b,
       const int    *ldb,
       const double *beta,
       double       *c,
       const int    *ldc);
void
sgemv_(const char  *trans,
       const int   *m,
       const int   *n,
       const float *alpha,
       const float *a,
       const int   *lda,
       const float *x,
       const int   *incx,
       const float *beta,
       float       *y,
       const int   *incy);
void
dgemv_(const char   *trans,
       const int    *m,
       const int    *n,
       const double *alpha,
       const double *a,
       const int    *lda,
       const double *x,
       const int    *incx,
       const double *beta,
       double       *y,
       const int    *incy);
}

namespace clothsim::dense
{
  // The kernels used, in either precision (lower triangles, no transposed A).
  // L L^T = A (k x k, leading dimension lda); false if a pivot is not positive.
  template <typename Number>
  inline bool
  cholesky(const int k, Number *a, const int lda)
  {
    int info = 0;
    if constexpr (std::is_same_v<Number, float>)
      spotrf_("L", &k, a, &lda, &info);
    else
      dpotrf_("L", &k, a, &lda, &info);
    return info == 0;
  }

  // B = B L^-T (B r x k, L k x k).
  template <typename Number>
  inline void
  right_solve_transposed(const int     r,
                         const int     k,
                         const Number *l,
                         const int     ldl,
                         Number       *b,
                         const int     ldb)
  {
    const Number one = 1;
    if constexpr (std::is_same_v<Number, float>)
      strsm_("R", "L", "T", "N", &r, &k, &one, l, &ldl, b, &ldb);
    else
      dtrsm_("R", "L", "T", "N", &r, &k, &one, l, &ldl, b, &ldb);
  }

  // C -= A A^T (C r x r lower, A r x k).
  template <typename Number>
  inline void
  subtract_gram(const int     r,
                const int     k,
                const Number *a,
                const int     lda,
                Number       *c,
                const int     ldc)
  {
    const Number one = 1, minus_one = -1;
    if constexpr (std::is_same_v<Number, float>)
      ssyrk_("L", "N", &r, &k, &minus_one, a, &lda, &one, c, &ldc);
    else
      dsyrk_("L", "N", &r, &k, &minus_one, a, &lda, &one, c, &ldc);
  }

  // C -= A B^T (C m x n, A m x k, B n x k).
  template <typename Number>
  inline void
  subtract_product(const int     m,
                   const int     n,
                   const int     k,
                   const Number *a,
                   const int     lda,
                   const Number *b,
                   const int     ldb,
                   Number       *c,
                   const int     ldc)
  {
    const Number one = 1, minus_one = -1;
    if constexpr (std::is_same_v<Number, float>)
      sgemm_("N", "T", &m, &n, &k, &minus_one, a, &lda, b, &ldb, &one, c, &ldc);
    else
      dgemm_("N", "T", &m, &n, &k, &minus_one, a, &lda, b, &ldb, &one, c, &ldc);
  }

  // x = L^-1 x ("N") or L^-T x ("T").
  template <typename Number>
  inline void
  triangular_solve(const char   *trans,
                   const int     k,
                   const Number *l,
                   const int     ldl,
                   Number       *x)
  {
    const int one = 1;
    if constexpr (std::is_same_v<Number, float>)
      strsv_("L", trans, "N", &k, l, &ldl, x, &one);
    else
      dtrsv_("L", trans, "N", &k, l, &ldl, x, &one);
  }

  // y = alpha op(A) x + beta y (A m x n).
  template <typename Number>
  inline void
  multiply(const char   *trans,
           const int     m,
           const int     n,
           const Number  alpha,
           const Number *a,
           const int     lda,
           const Number *x,
           const Number  beta,
           Number       *y)
  {
    const int one = 1;
    if constexpr (std::is_same_v<Number, float>)
      sgemv_(trans, &m, &n, &alpha, a, &lda, x, &one, &beta, y, &one);
    else
      dgemv_(trans, &m, &n, &alpha, a, &lda, x, &one, &beta, y, &one);
  }

} // namespace clothsim::dense
