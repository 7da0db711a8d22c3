/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The numeric half of the Schur reduction (schur.c): a left-looking
 * supernodal Cholesky of P A P' on CHOLMOD's symbolic factor that stops
 * at the contact columns. With the c dofs last,
 *     P A P' = [A11 A12; A21 A22] = [L11 0; L21 I] [L11' L21'; 0 S],
 * S = A22 - L21 L21': the updates of the interior supernodes are gathered
 * into the trailing columns as a factorisation would gather them, but the
 * trailing block is neither factorised (nc^3/3 flops) nor multiplied back
 * (another nc^3/3, S = L22 L22' - D) as it must be when CHOLMOD factorises
 * all of A + D. S is copied out and the trailing block of L set to the
 * identity, so that CHOLMOD's solves with L and L' are the partial solves
 * that condense and expand (schur.c). The interior supernodes run the
 * BLAS calls CHOLMOD's own supernodal factorisation runs (dsyrk and dgemm
 * for each descendant's update, dpotrf and dtrsm for the supernode).
 * No code of CHOLMOD's is used here: only its symbolic factor's layout
 * (super, pi, px, s), which cholmod.h documents. */
#include "linalg/linalg_impl.h"

#include <math.h>
#include <string.h>

extern void dsyrk_(const char *uplo, const char *trans, const int *n, const int *k, const double *alpha,
                   const double *a, const int *lda, const double *beta, double *c, const int *ldc);
extern void dgemm_(const char *ta, const char *tb, const int *m, const int *n, const int *k,
                   const double *alpha, const double *a, const int *lda, const double *b, const int *ldb,
                   const double *beta, double *c, const int *ldc);
extern void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
extern void dtrsm_(const char *side, const char *uplo, const char *ta, const char *diag, const int *m,
                   const int *n, const double *alpha, const double *a, const int *lda, double *b,
                   const int *ldb);

typedef struct numeric_work {
    int *map;       /* n: row -> its position in the current supernode */
    int *smap;      /* n: column -> its supernode */
    int *pinv;      /* n: original dof -> position */
    int *head;      /* nsuper: the descendants that update a supernode next */
    int *next;      /* nsuper: the list's links */
    int *lpos;      /* nsuper: a supernode's first row not yet used */
    int *rmap;      /* the rows of one update, in the target supernode */
    double *C;      /* one descendant's update */
} numeric_work;

static void work_free(numeric_work *w)
{
    cx_free(w->map);
    cx_free(w->smap);
    cx_free(w->pinv);
    cx_free(w->head);
    cx_free(w->next);
    cx_free(w->lpos);
    cx_free(w->rmap);
    cx_free(w->C);
}

/* The largest update a descendant sends: rows below its columns squared
 * (CHOLMOD's maxcsize when its analysis set it). */
static size_t work_csize(const cholmod_factor *L)
{
    if (L->maxcsize > 0)
        return L->maxcsize;
    const int *super = L->super, *pi = L->pi;
    size_t m = 1;
    for (size_t s = 0; s < L->nsuper; s++) {
        size_t r = (size_t)(pi[s + 1] - pi[s] - (super[s + 1] - super[s]));
        m = r * r > m ? r * r : m;
    }
    return m;
}

static int work_alloc(numeric_work *w, const cholmod_factor *L)
{
    size_t n = L->n, ns = L->nsuper, maxrow = 1;
    for (size_t s = 0; s < ns; s++) {
        size_t r = (size_t)(((const int *)L->pi)[s + 1] - ((const int *)L->pi)[s]);
        maxrow = r > maxrow ? r : maxrow;
    }
    memset(w, 0, sizeof *w);
    w->map = CX_NEW(int, n + 1);
    w->smap = CX_NEW(int, n + 1);
    w->pinv = CX_NEW(int, n + 1);
    w->head = CX_NEW(int, ns + 1);
    w->next = CX_NEW(int, ns + 1);
    w->lpos = CX_NEW(int, ns + 1);
    w->rmap = CX_NEW(int, maxrow);
    w->C = CX_NEW(double, work_csize(L));
    if (!w->map || !w->smap || !w->pinv || !w->head || !w->next || !w->lpos || !w->rmap || !w->C) {
        work_free(w);
        return CX_ENOMEM;
    }
    return CX_OK;
}

/* Supernode s's columns [k1, k2) of P A P', lower part, into its block
 * (zeroed first). A holds both triangles. The block's strict upper
 * triangle is never read (every BLAS call here and every CHOLMOD solve
 * takes the lower one) and is not zeroed: those pages of a fresh
 * allocation are then never touched (on prism 7 the last supernode alone
 * is 4968 x 4968, half of it above the diagonal). */
static void numeric_assemble(const cholmod_factor *L, const cx_csc *A, numeric_work *w, int s)
{
    const int *super = L->super, *pi = L->pi, *px = L->px, *ls = L->s, *perm = L->Perm;
    double *lx = (double *)L->x + px[s];
    int k1 = super[s], k2 = super[s + 1], nsrow = pi[s + 1] - pi[s];
    for (int k = k1; k < k2; k++)
        memset(lx + (size_t)(k - k1) * (size_t)nsrow + (k - k1), 0, sizeof(double) * (size_t)(nsrow - (k - k1)));
    for (int r = 0; r < nsrow; r++)
        w->map[ls[pi[s] + r]] = r;
    for (int k = k1; k < k2; k++) {
        int j = perm[k];
        double *col = lx + (size_t)(k - k1) * (size_t)nsrow;
        for (int q = A->p[j]; q < A->p[j + 1]; q++) {
            int i = w->pinv[A->i[q]];
            if (i >= k)
                col[w->map[i]] += A->x[q];
        }
    }
}

/* Subtract from supernode s the updates of every descendant listed in
 * head[s] (their factored columns times their rows in s), then pass each
 * descendant on to the next supernode its rows reach. */
static void numeric_updates(const cholmod_factor *L, numeric_work *w, int s, int nstop)
{
    const int *super = L->super, *pi = L->pi, *px = L->px, *ls = L->s;
    const double one = 1, zero = 0;
    double *lxs = (double *)L->x + px[s];
    int k1 = super[s], k2 = super[s + 1], nsrow = pi[s + 1] - pi[s];
    for (int dd = w->head[s], dnext; dd >= 0; dd = dnext) {
        dnext = w->next[dd];
        int kd2 = super[dd + 1] < nstop ? super[dd + 1] : nstop;
        int ndcol = kd2 - super[dd], pdi = pi[dd], pdend = pi[dd + 1], ndrow = pdend - pdi;
        int p1 = pdi + w->lpos[dd], p2 = p1;
        while (p2 < pdend && ls[p2] < k2)
            p2++;
        int ndrow1 = p2 - p1, ndrow2 = pdend - p1, ndrow3 = ndrow2 - ndrow1;
        const double *lr = (const double *)L->x + px[dd] + (p1 - pdi);
        double *C = w->C;
        dsyrk_("L", "N", &ndrow1, &ndcol, &one, lr, &ndrow, &zero, C, &ndrow2);
        if (ndrow3 > 0)
            dgemm_("N", "T", &ndrow3, &ndrow1, &ndcol, &one, lr + ndrow1, &ndrow, lr, &ndrow, &zero,
                   C + ndrow1, &ndrow2);
        for (int ii = 0; ii < ndrow2; ii++)
            w->rmap[ii] = w->map[ls[p1 + ii]];
        for (int jj = 0; jj < ndrow1; jj++) {
            double *col = lxs + (size_t)(ls[p1 + jj] - k1) * (size_t)nsrow;
            const double *cj = C + (size_t)jj * (size_t)ndrow2;
            for (int ii = jj; ii < ndrow2; ii++)
                col[w->rmap[ii]] -= cj[ii];
        }
        w->lpos[dd] = p2 - pdi;
        if (p2 < pdend) {
            int sp = w->smap[ls[p2]];
            w->next[dd] = w->head[sp];
            w->head[sp] = dd;
        }
    }
    w->head[s] = -1;
}

/* Factorise supernode s's columns before nstop: dpotrf on their diagonal
 * block, dtrsm below it; a supernode that straddles nstop then updates
 * its own trailing columns with its factored ones. */
static int numeric_factor(const cholmod_factor *L, numeric_work *w, int s, int nstop, double amax,
                          cx_diag *d)
{
    const int *super = L->super, *pi = L->pi, *px = L->px, *ls = L->s;
    const double one = 1, mone = -1;
    double *lx = (double *)L->x + px[s];
    int k1 = super[s], k2 = super[s + 1], nscol = k2 - k1, nsrow = pi[s + 1] - pi[s];
    int nf = (k2 < nstop ? k2 : nstop) - k1, info = 0;
    if (nf <= 0)
        return CX_OK;
    dpotrf_("L", &nf, lx, &nsrow, &info);
    if (info != 0)
        return cx_diag_set(d, CX_ENUMERIC, "schur: Cholesky factorisation: matrix not positive definite "
                           "(pivot at column %d)", cx_cholmod_column(L, k1 + info - 1));
    for (int j = 0; j < nf; j++) {
        double l = lx[j + (size_t)j * (size_t)nsrow];
        if (!(l * l > CX_PIVOT_RTOL * amax))   /* also catches NaN */
            return cx_diag_set(d, CX_ENUMERIC, "schur: Cholesky factorisation: matrix singular to "
                               "working precision (pivot %g at column %d)", l * l, cx_cholmod_column(L, k1 + j));
    }
    int m = nsrow - nf;
    if (m > 0)
        dtrsm_("R", "L", "T", "N", &m, &nf, &one, lx, &nsrow, lx + nf, &nsrow);
    if (nf < nscol) {
        int nt = nscol - nf, mb = m - nt;
        double *B = lx + nf, *T = lx + nf + (size_t)nf * (size_t)nsrow;
        dsyrk_("L", "N", &nt, &nf, &mone, B, &nsrow, &one, T, &nsrow);
        if (mb > 0)
            dgemm_("N", "T", &mb, &nt, &nf, &mone, B + nt, &nsrow, B, &nsrow, &one, T + nt, &nsrow);
    }
    if (nsrow > nscol) {
        int sp = w->smap[ls[pi[s] + nscol]];
        w->lpos[s] = nscol;
        w->next[s] = w->head[sp];
        w->head[sp] = s;
    }
    return CX_OK;
}

/* W (nc x nc, lower, trailing order) = the trailing block of L; that
 * block then set to the identity. */
static void numeric_take_trailing(const cholmod_factor *L, int nstop, double *W)
{
    const int *super = L->super, *pi = L->pi, *px = L->px, *ls = L->s;
    size_t nc = L->n - (size_t)nstop;
    for (size_t s = 0; s < L->nsuper; s++) {
        int k1 = super[s], k2 = super[s + 1], nsrow = pi[s + 1] - pi[s];
        if (k2 <= nstop)
            continue;
        double *lx = (double *)L->x + px[s];
        for (int k = k1 > nstop ? k1 : nstop; k < k2; k++) {
            double *col = lx + (size_t)(k - k1) * (size_t)nsrow;
            double *wk = W + (size_t)(k - nstop) * nc;
            for (int r = k - k1; r < nsrow; r++) {
                int row = ls[pi[s] + r];
                wk[row - nstop] = col[r];
                col[r] = row == k ? 1 : 0;
            }
        }
    }
}

int cx_schur_numeric(cholmod_factor *L, const cx_csc *A, int nstop, double *W, cholmod_common *cc, cx_diag *d)
{
    if (!L->is_super)
        return cx_diag_set(d, CX_EEXTERNAL, "schur: expected a supernodal analysis");
    if (L->xtype == CHOLMOD_PATTERN) {
        cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, L, cc);
        CX_TRY(cx_cholmod_check(cc, L, "schur: factor values", d));
        if (L->xtype != CHOLMOD_REAL || !L->is_super)
            return cx_diag_set(d, CX_EEXTERNAL, "schur: factor values not allocated");
    }
    numeric_work w;
    if (work_alloc(&w, L))
        return cx_diag_set(d, CX_ENOMEM, "schur: out of memory");
    int n = (int)L->n, ns = (int)L->nsuper, st = CX_OK;
    const int *perm = L->Perm, *super = L->super;
    for (int k = 0; k < n; k++)
        w.pinv[perm[k]] = k;
    for (int s = 0; s < ns; s++) {
        w.head[s] = -1;
        for (int k = super[s]; k < super[s + 1]; k++)
            w.smap[k] = s;
    }
    double amax = 0;
    for (int j = 0; j < A->ncol; j++)
        amax = fmax(amax, fabs(cx_csc_get(A, j, j)));
    for (int s = 0; s < ns && st == CX_OK; s++) {
        numeric_assemble(L, A, &w, s);
        numeric_updates(L, &w, s, nstop);
        st = numeric_factor(L, &w, s, nstop, amax, d);
    }
    if (st == CX_OK) {
        numeric_take_trailing(L, nstop, W);
        L->minor = L->n;
        L->is_ll = 1;
    }
    work_free(&w);
    return st;
}
