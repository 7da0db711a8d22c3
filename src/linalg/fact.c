/* Sparse factorisations: CHOLMOD for symmetric positive definite matrices,
 * UMFPACK for square ones. The symbolic analysis is kept, so that a new
 * numeric factorisation of the same pattern costs only the numeric part. */
#include "linalg/linalg_impl.h"

#include <stdio.h>
#include <math.h>
#include <string.h>
#include <umfpack.h>

struct cx_fact {
    cx_fact_kind kind;
    cx_counters *cnt;        /* borrowed */
    int n;
    /* CHOLMOD */
    cholmod_common c;
    cholmod_factor *L;
    cholmod_dense *X, *Y, *E;  /* solve workspace, reused */
    /* UMFPACK */
    void *symbolic, *numeric;
    cx_csc A;                /* the factorised matrix (UMFPACK solves need it) */
    double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
};

/* CHOLMOD's error handler has no user pointer: the last message is kept
 * here (the library is single-threaded per session). */
static char cholmod_last_msg[256];

static void cholmod_record(int status, const char *file, int line, const char *message)
{
    (void)file;
    (void)line;
    snprintf(cholmod_last_msg, sizeof cholmod_last_msg, "%s (CHOLMOD status %d)", message, status);
}

void cx_cholmod_start(cholmod_common *c)
{
    cholmod_start(c);
    c->print = 0;
    c->error_handler = cholmod_record;
}

cholmod_sparse cx_cholmod_view(const cx_csc *A, int stype)
{
    cholmod_sparse s;
    memset(&s, 0, sizeof s);
    s.nrow = (size_t)A->nrow;
    s.ncol = (size_t)A->ncol;
    s.nzmax = cx_csc_nnz(A) ? cx_csc_nnz(A) : 1;
    s.p = A->p;
    s.i = A->i;
    s.x = A->x;
    s.stype = stype;
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 1;
    return s;
}

cholmod_dense cx_cholmod_vec(double *x, int n)
{
    cholmod_dense v;
    memset(&v, 0, sizeof v);
    v.nrow = (size_t)n;
    v.ncol = 1;
    v.nzmax = (size_t)n;
    v.d = (size_t)n;
    v.x = x;
    v.xtype = CHOLMOD_REAL;
    v.dtype = CHOLMOD_DOUBLE;
    return v;
}

int cx_cholmod_check(cholmod_common *c, const cholmod_factor *L, const char *what, cx_diag *d)
{
    if (c->status == CHOLMOD_OK)
        return CX_OK;
    if (c->status == CHOLMOD_NOT_POSDEF)
        return cx_diag_set(d, CX_ENUMERIC, "%s: matrix not positive definite (pivot at column %d)", what,
                           L ? (int)L->minor : -1);
    if (c->status == CHOLMOD_OUT_OF_MEMORY)
        return cx_diag_set(d, CX_ENOMEM, "%s: out of memory", what);
    if (c->status > 0) /* a warning, e.g. a tiny pivot: the result stands */
        return CX_OK;
    return cx_diag_set(d, CX_EEXTERNAL, "%s: %s", what, cholmod_last_msg);
}

int cx_cholmod_check_pivots(const cholmod_factor *L, const cx_csc *A, const char *what, cx_diag *d)
{
    /* a positive but vanishing pivot (rounding in a singular matrix) is as
     * fatal as a negative one: solves would be garbage */
    double amax = 0;
    for (int j = 0; j < A->ncol; j++)
        amax = fmax(amax, fabs(cx_csc_get(A, j, j)));
    const int *super = L->super, *pi = L->pi, *px = L->px;
    const double *lx = L->x;
    for (size_t k = 0; k < L->nsuper; k++) {
        int nrow = pi[k + 1] - pi[k];
        for (int j = 0; j < super[k + 1] - super[k]; j++) {
            double l = lx[px[k] + j + j * nrow];
            if (!(l * l > 1e-14 * amax))
                return cx_diag_set(d, CX_ENUMERIC,
                                   "%s: matrix singular to working precision (pivot %g at column %d)",
                                   what, l * l, super[k] + j);
        }
    }
    return CX_OK;
}

int cx_fact_create(cx_fact **F, cx_fact_kind kind, cx_counters *cnt, cx_diag *d)
{
    cx_fact *f = CX_NEW(cx_fact, 1);
    if (!f)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    f->kind = kind;
    f->cnt = cnt;
    if (kind == CX_FACT_CHOLESKY) {
        cx_cholmod_start(&f->c);
        /* LL' always: positivity is then checked at every pivot */
        f->c.supernodal = CHOLMOD_SUPERNODAL;
    }
    else
        umfpack_di_defaults(f->control);
    *F = f;
    return CX_OK;
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
        if (f->numeric)
            umfpack_di_free_numeric(&f->numeric);
        if (f->symbolic)
            umfpack_di_free_symbolic(&f->symbolic);
        cx_csc_clear(&f->A);
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
    if (f->kind == CX_FACT_CHOLESKY) {
        cholmod_free_factor(&f->L, &f->c);
        cholmod_sparse s = cx_cholmod_view(A, 1);
        f->L = cholmod_analyze(&s, &f->c);
        return cx_cholmod_check(&f->c, f->L, "analyse", d);
    }
    if (f->symbolic)
        umfpack_di_free_symbolic(&f->symbolic);
    return umf_check(umfpack_di_symbolic(A->nrow, A->ncol, A->p, A->i, A->x, &f->symbolic, f->control, f->info),
                     "LU analysis", d);
}

int cx_fact_factorize(cx_fact *f, const cx_csc *A, cx_diag *d)
{
    if (f->kind == CX_FACT_CHOLESKY) {
        if (!f->L)
            return cx_diag_set(d, CX_EINVAL, "factorise before analyse");
        cholmod_sparse s = cx_cholmod_view(A, 1);
        cholmod_factorize(&s, f->L, &f->c);
        if (f->cnt)
            f->cnt->factorizations++;
        CX_TRY(cx_cholmod_check(&f->c, f->L, "Cholesky factorisation", d));
        return cx_cholmod_check_pivots(f->L, A, "Cholesky factorisation", d);
    }
    if (!f->symbolic)
        return cx_diag_set(d, CX_EINVAL, "factorise before analyse");
    if (f->numeric)
        umfpack_di_free_numeric(&f->numeric);
    cx_csc_clear(&f->A);
    CX_TRY(cx_csc_copy(&f->A, A));
    if (f->cnt)
        f->cnt->factorizations++;
    return umf_check(umfpack_di_numeric(A->p, A->i, A->x, f->symbolic, &f->numeric, f->control, f->info),
                     "LU factorisation", d);
}

int cx_fact_solve(cx_fact *f, const double *b, double *x, cx_diag *d)
{
    if (f->cnt)
        f->cnt->solves++;
    if (f->kind == CX_FACT_CHOLESKY) {
        cholmod_dense B = cx_cholmod_vec((double *)b, f->n);
        if (!cholmod_solve2(CHOLMOD_A, f->L, &B, NULL, &f->X, NULL, &f->Y, &f->E, &f->c))
            return cx_cholmod_check(&f->c, f->L, "solve", d);
        memcpy(x, f->X->x, sizeof(double) * (size_t)f->n);
        return CX_OK;
    }
    if (!f->numeric)
        return cx_diag_set(d, CX_EINVAL, "solve before factorise");
    /* UMFPACK needs x and b apart */
    double *tmp = CX_NEW(double, f->n);
    if (!tmp)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    int st = umfpack_di_solve(UMFPACK_A, f->A.p, f->A.i, f->A.x, tmp, b, f->numeric, f->control, f->info);
    memcpy(x, tmp, sizeof(double) * (size_t)f->n);
    cx_free(tmp);
    return umf_check(st, "LU solve", d);
}

double cx_fact_nnz(const cx_fact *f)
{
    if (f->kind == CX_FACT_CHOLESKY)
        return f->L ? (f->L->is_super ? (double)f->L->xsize : (double)f->L->nzmax) : 0;
    return f->numeric ? f->info[UMFPACK_LNZ] + f->info[UMFPACK_UNZ] : 0;
}
