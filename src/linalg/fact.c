/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Sparse factorisations: CHOLMOD for symmetric positive definite matrices,
 * UMFPACK for square ones. The symbolic analysis is kept, so that a new
 * numeric factorisation of the same pattern costs only the numeric part;
 * the solve workspace is kept too, so that a solve allocates nothing. */
#include "linalg/linalg_impl.h"

#include <math.h>
#include <string.h>
#include <umfpack.h>

struct cx_fact {
    cx_fact_kind kind;
    cx_counters *cnt;        /* borrowed */
    int n;
    size_t nnz;              /* of the analysed pattern */
    int analysed, factored;  /* factored: the last factorize succeeded */
    /* CHOLMOD */
    cholmod_common c;
    cholmod_factor *L;
    cholmod_dense *X, *Y, *E;  /* solve workspace, reused */
    /* UMFPACK */
    void *symbolic, *numeric;
    cx_csc A;                /* the factorised matrix (iterative refinement needs it) */
    int *wi;                 /* n: umfpack_di_wsolve workspace */
    double *w;               /* 5 n: idem (5 n with iterative refinement) */
    double *x;               /* n: solution (UMFPACK needs x and b apart) */
    double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
};

int cx_fact_create(cx_fact **F, cx_fact_kind kind, cx_counters *cnt, cx_diag *d)
{
    cx_fact *f = CX_NEW(cx_fact, 1);
    if (!f)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    f->kind = kind;
    f->cnt = cnt;
    if (kind == CX_FACT_CHOLESKY)
        cx_cholmod_start(&f->c);
    else
        umfpack_di_defaults(f->control);
    *F = f;
    return CX_OK;
}

static void umf_free_numeric(cx_fact *f)
{
    if (f->numeric)
        umfpack_di_free_numeric(&f->numeric);
    f->numeric = NULL;
}

void cx_fact_destroy(cx_fact **F)
{
    if (!F || !*F)
        return;
    cx_fact *f = *F;
    if (f->kind == CX_FACT_CHOLESKY) {
        cholmod_free_factor(&f->L, &f->c);
        cholmod_free_dense(&f->X, &f->c);
        cholmod_free_dense(&f->Y, &f->c);
        cholmod_free_dense(&f->E, &f->c);
        cholmod_finish(&f->c);
    } else {
        umf_free_numeric(f);
        if (f->symbolic)
            umfpack_di_free_symbolic(&f->symbolic);
        cx_csc_clear(&f->A);
        cx_free(f->wi);
        cx_free(f->w);
        cx_free(f->x);
    }
    cx_free(f);
    *F = NULL;
}

static int umf_check(int status, const char *what, cx_diag *d)
{
    if (status == UMFPACK_OK)
        return CX_OK;
    if (status == UMFPACK_WARNING_singular_matrix)
        return cx_diag_set(d, CX_ENUMERIC, "%s: matrix is singular", what);
    if (status == UMFPACK_ERROR_out_of_memory)
        return cx_diag_set(d, CX_ENOMEM, "%s: out of memory", what);
    return cx_diag_set(d, CX_EEXTERNAL, "%s: UMFPACK status %d", what, status);
}

int cx_fact_analyze(cx_fact *f, const cx_csc *A, cx_diag *d)
{
    if (A->nrow != A->ncol)
        return cx_diag_set(d, CX_EINVAL, "factorisation: matrix is %d x %d, not square", A->nrow, A->ncol);
    f->n = A->nrow;
    f->nnz = cx_csc_nnz(A);
    f->analysed = f->factored = 0;
    if (f->kind == CX_FACT_CHOLESKY) {
        cholmod_free_factor(&f->L, &f->c);
        cholmod_sparse s = cx_cholmod_view(A, 1);
        cx_progress_step("ordering", f->n);
        f->L = cholmod_analyze(&s, &f->c);
        CX_TRY(cx_cholmod_check(&f->c, f->L, "Cholesky analysis", d));
        if (!f->L)
            return cx_diag_set(d, CX_EEXTERNAL, "Cholesky analysis failed");
        f->analysed = 1;
        return CX_OK;
    }
    umf_free_numeric(f);
    if (f->symbolic)
        umfpack_di_free_symbolic(&f->symbolic);
    f->symbolic = NULL;
    CX_TRY(umf_check(umfpack_di_symbolic(A->nrow, A->ncol, A->p, A->i, A->x, &f->symbolic, f->control, f->info),
                     "LU analysis", d));
    f->analysed = 1;
    return CX_OK;
}

/* The original column of the smallest pivot |U_kk| (PAQ = LU, so pivot k
 * sits in column Q[k]), -1 if it cannot be found. */
static int umf_weakest_column(cx_fact *f)
{
    int n = f->n, col = -1, do_recip = 0;
    int *q = CX_NEW(int, n);
    double *dx = CX_NEW(double, n);
    if (q && dx &&
        umfpack_di_get_numeric(NULL, NULL, NULL, NULL, NULL, NULL, NULL, q, dx, &do_recip, NULL, f->numeric) ==
            UMFPACK_OK) {
        double best = INFINITY;
        for (int k = 0; k < n; k++)
            if (!(fabs(dx[k]) >= best)) {   /* NaN first */
                best = fabs(dx[k]);
                col = q[k];
            }
    }
    cx_free(q);
    cx_free(dx);
    return col;
}

static int lu_factorize(cx_fact *f, const cx_csc *A, cx_diag *d)
{
    int n = f->n;
    umf_free_numeric(f);
    /* keep a copy of A for the refinement in the solves; same pattern,
     * so the buffers of the previous factorisation are reused */
    if (!f->A.p || cx_csc_nnz(&f->A) != cx_csc_nnz(A) || f->A.ncol != n) {
        cx_csc_clear(&f->A);
        CX_TRY(cx_csc_copy(&f->A, A));
    } else {
        memcpy(f->A.p, A->p, sizeof(int) * (size_t)(n + 1));
        memcpy(f->A.i, A->i, sizeof(int) * cx_csc_nnz(A));
        memcpy(f->A.x, A->x, sizeof(double) * cx_csc_nnz(A));
    }
    if (!f->wi) {
        f->wi = CX_NEW(int, n);
        f->w = CX_NEW(double, 5 * (size_t)n);
        f->x = CX_NEW(double, n);
        if (!f->wi || !f->w || !f->x) {
            cx_free(f->wi);
            cx_free(f->w);
            cx_free(f->x);
            f->wi = NULL;
            f->w = f->x = NULL;
            return cx_diag_set(d, CX_ENOMEM, "LU factorisation: out of memory");
        }
    }
    if (f->cnt)
        f->cnt->factorizations++;
    int st = umfpack_di_numeric(A->p, A->i, A->x, f->symbolic, &f->numeric, f->control, f->info);
    if (st == UMFPACK_WARNING_singular_matrix)
        return cx_diag_set(d, CX_ENUMERIC, "LU factorisation: matrix is singular (zero pivot at column %d)",
                           umf_weakest_column(f));
    CX_TRY(umf_check(st, "LU factorisation", d));
    /* min |U_kk| / max |U_kk| (also NaN when the data holds one) */
    double rcond = f->info[UMFPACK_RCOND];
    if (!(rcond >= CX_PIVOT_RTOL))
        return cx_diag_set(d, CX_ENUMERIC,
                           "LU factorisation: matrix singular to working precision (rcond %g, column %d)", rcond,
                           umf_weakest_column(f));
    return CX_OK;
}

int cx_fact_factorize(cx_fact *f, const cx_csc *A, cx_diag *d)
{
    if (!f->analysed)
        return cx_diag_set(d, CX_EINVAL, "factorise before analyse");
    if (A->nrow != f->n || A->ncol != f->n || cx_csc_nnz(A) != f->nnz)
        return cx_diag_set(d, CX_EINVAL, "factorisation: the matrix is not the pattern analysed");
    f->factored = 0;
    cx_progress_step("factorising", f->n);
    if (f->kind == CX_FACT_LU) {
        CX_TRY(lu_factorize(f, A, d));
        f->factored = 1;
        return CX_OK;
    }
    cholmod_sparse s = cx_cholmod_view(A, 1);
    cholmod_factorize(&s, f->L, &f->c);
    if (f->cnt)
        f->cnt->factorizations++;
    CX_TRY(cx_cholmod_check(&f->c, f->L, "Cholesky factorisation", d));
    CX_TRY(cx_cholmod_check_pivots(f->L, A, "Cholesky factorisation", d));
    f->factored = 1;
    return CX_OK;
}

int cx_fact_solve(cx_fact *f, const double *b, double *x, cx_diag *d)
{
    if (!f->factored)
        return cx_diag_set(d, CX_EINVAL, "solve without a successful factorisation");
    if (f->cnt)
        f->cnt->solves++;
    size_t bytes = sizeof(double) * (size_t)f->n;
    if (f->kind == CX_FACT_CHOLESKY) {
        cholmod_dense B = cx_cholmod_vec((double *)b, f->n);
        int ok = cholmod_solve2(CHOLMOD_A, f->L, &B, NULL, &f->X, NULL, &f->Y, &f->E, &f->c);
        CX_TRY(cx_cholmod_check(&f->c, f->L, "Cholesky solve", d));
        if (!ok || !f->X)
            return cx_diag_set(d, CX_EEXTERNAL, "Cholesky solve failed");
        memcpy(x, f->X->x, bytes);
        return CX_OK;
    }
    int st = umfpack_di_wsolve(UMFPACK_A, f->A.p, f->A.i, f->A.x, f->x, b, f->numeric, f->control, f->info,
                               f->wi, f->w);
    CX_TRY(umf_check(st, "LU solve", d));
    memcpy(x, f->x, bytes);
    return CX_OK;
}

double cx_fact_nnz(const cx_fact *f)
{
    if (!f->factored)
        return 0;
    if (f->kind == CX_FACT_CHOLESKY)
        return f->L->is_super ? (double)f->L->xsize : (double)f->L->nzmax;
    return f->info[UMFPACK_LNZ] + f->info[UMFPACK_UNZ];
}
