/**
 * @file blas.h
 * The Fortran BLAS / LAPACK routines the project calls directly, declared
 * once (deal.II links the libraries; OpenBLAS here, see blas_kernels.h).
 */
#ifndef dualcontact_util_blas_h
#define dualcontact_util_blas_h

extern "C"
{
  /// y = alpha op(A) x + beta y
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
  /// y = alpha A x + beta y, A symmetric (one triangle referenced)
  void
  dsymv_(const char   *uplo,
         const int    *n,
         const double *alpha,
         const double *a,
         const int    *lda,
         const double *x,
         const int    *incx,
         const double *beta,
         double       *y,
         const int    *incy);
  /// C = alpha op(A) op(B) + beta C
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
  /// pivoted Cholesky of a semidefinite A, with its numerical rank
  void
  dpstrf_(const char   *uplo,
          const int    *n,
          double       *a,
          const int    *lda,
          int          *piv,
          int          *rank,
          const double *tol,
          double       *work,
          int          *info);
}

#endif
