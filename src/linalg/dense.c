/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Dense kernels over LAPACK/BLAS (column-major). The Fortran prototypes are
 * declared here rather than through LAPACKE, which Debian ships apart.
 * LAPACK reports only exactly zero pivots; a NaN or Inf in the data goes
 * through silently, so the results are checked to be finite as well. */
#include "linalg/linalg.h"

#include <math.h>

extern void dsysv_(const char *uplo, const int *n, const int *nrhs, double *a, const int *lda,
                   int *ipiv, double *b, const int *ldb, double *work, const int *lwork, int *info);
extern void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
extern void dpotrs_(const char *uplo, const int *n, const int *nrhs, const double *a, const int *lda,
                    double *b, const int *ldb, int *info);
extern void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b,
                   const int *ldb, int *info);
extern void dgemv_(const char *trans, const int *m, const int *n, const double *alpha, const double *a,
                   const int *lda, const double *x, const int *incx, const double *beta, double *y,
                   const int *incy);

/* Count a dense factorisation (apart from the sparse ones) and turn LAPACK's info into a status: info > 0 is a
 * singular (or not definite) matrix, info < 0 a bad argument. */
static int dense_outcome(int info, cx_counters *cnt)
{
    if (cnt)
        cnt->dense_factorizations++;
    if (info > 0)
        return CX_ENUMERIC;
    return info < 0 ? CX_EEXTERNAL : CX_OK;
}

int cx_dense_sym_solve(int n, double *A, double *b, int *ipiv, double *work, int lwork,
                       cx_counters *cnt)
{
    int one = 1, info = 0, ld = n > 0 ? n : 1;
    if (n == 0)
        return CX_OK;
    dsysv_("L", &n, &one, A, &ld, ipiv, b, &ld, work, &lwork, &info);
    CX_TRY(dense_outcome(info, cnt));
    return cx_vec_finite(n, b) ? CX_OK : CX_ENUMERIC;
}

int cx_dense_cholesky(int n, double *A, cx_counters *cnt)
{
    int info = 0, ld = n > 0 ? n : 1;
    if (n == 0)
        return CX_OK;
    dpotrf_("L", &n, A, &ld, &info);
    CX_TRY(dense_outcome(info, cnt));
    for (int j = 0; j < n; j++)   /* a NaN pivot passes dpotrf's test */
        if (!isfinite(A[j + (size_t)j * (size_t)n]))
            return CX_ENUMERIC;
    return CX_OK;
}

void cx_dense_cholesky_solve(int n, const double *L, double *b, int nrhs)
{
    int info = 0, ld = n > 0 ? n : 1;
    if (n > 0)
        dpotrs_("L", &n, &nrhs, L, &ld, b, &ld, &info);
}

int cx_dense_lu_solve(int n, double *A, double *b, int *ipiv, cx_counters *cnt)
{
    int one = 1, info = 0, ld = n > 0 ? n : 1;
    if (n == 0)
        return CX_OK;
    dgesv_(&n, &one, A, &ld, ipiv, b, &ld, &info);
    CX_TRY(dense_outcome(info, cnt));
    return cx_vec_finite(n, b) ? CX_OK : CX_ENUMERIC;
}

void cx_dense_gemv(int m, int n, double alpha, const double *A, const double *x, double beta, double *y)
{
    int one = 1, ld = m > 0 ? m : 1;
    if (m > 0 && n > 0)
        dgemv_("N", &m, &n, &alpha, A, &ld, x, &one, &beta, y, &one);
}
