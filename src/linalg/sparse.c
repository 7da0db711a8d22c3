/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Triplet and compressed-column matrices. */
#include "linalg/linalg.h"

#include <assert.h>
#include <math.h>
#include <string.h>

int cx_triplet_init(cx_triplet *t, int nrow, int ncol, size_t cap)
{
    memset(t, 0, sizeof *t);
    t->nrow = nrow;
    t->ncol = ncol;
    t->cap = cap ? cap : 16;
    t->i = CX_NEW(int, t->cap);
    t->j = CX_NEW(int, t->cap);
    t->x = CX_NEW(double, t->cap);
    if (!t->i || !t->j || !t->x) {
        cx_triplet_clear(t);
        return CX_ENOMEM;
    }
    return CX_OK;
}

int cx_triplet_add(cx_triplet *t, int i, int j, double x)
{
    assert(i >= 0 && i < t->nrow && j >= 0 && j < t->ncol);
    if (t->nnz == t->cap) {
        size_t cap = 2 * t->cap;
        int *ni = cx_realloc(t->i, cap * sizeof(int));
        if (!ni)
            return CX_ENOMEM;
        t->i = ni;
        int *nj = cx_realloc(t->j, cap * sizeof(int));
        if (!nj)
            return CX_ENOMEM;
        t->j = nj;
        double *nx = cx_realloc(t->x, cap * sizeof(double));
        if (!nx)
            return CX_ENOMEM;
        t->x = nx;
        t->cap = cap;
    }
    t->i[t->nnz] = i;
    t->j[t->nnz] = j;
    t->x[t->nnz] = x;
    t->nnz++;
    return CX_OK;
}

void cx_triplet_clear(cx_triplet *t)
{
    cx_free(t->i);
    cx_free(t->j);
    cx_free(t->x);
    memset(t, 0, sizeof *t);
}

void cx_csc_clear(cx_csc *A)
{
    cx_free(A->p);
    cx_free(A->i);
    cx_free(A->x);
    memset(A, 0, sizeof *A);
}

/* Allocate A for nz entries; p zeroed. */
static int csc_alloc(cx_csc *A, int nrow, int ncol, size_t nz)
{
    A->nrow = nrow;
    A->ncol = ncol;
    A->p = CX_NEW(int, ncol + 1);
    A->i = CX_NEW(int, nz);
    A->x = CX_NEW(double, nz);
    if (!A->p || !A->i || !A->x) {
        cx_csc_clear(A);
        return CX_ENOMEM;
    }
    return CX_OK;
}

int cx_csc_from_triplet(cx_csc *A, const cx_triplet *T)
{
    /* bucket by row (a transpose into CSR), then by column: the second pass
     * visits rows in ascending order, so columns come out sorted; then
     * duplicates are adjacent and summed in place. */
    int nrow = T->nrow, ncol = T->ncol;
    size_t nz = T->nnz;
    int *rp = CX_NEW(int, nrow + 1), *rj = CX_NEW(int, nz);
    double *rx = CX_NEW(double, nz);
    int *cur = CX_NEW(int, (nrow > ncol ? nrow : ncol) + 1);
    int st = CX_ENOMEM;
    memset(A, 0, sizeof *A);
    if (!rp || !rj || !rx || !cur || (st = csc_alloc(A, nrow, ncol, nz)) != CX_OK)
        goto done;
    for (size_t k = 0; k < nz; k++)
        rp[T->i[k] + 1]++;
    for (int r = 0; r < nrow; r++)
        rp[r + 1] += rp[r];
    memcpy(cur, rp, sizeof(int) * (size_t)nrow);
    for (size_t k = 0; k < nz; k++) {
        int q = cur[T->i[k]]++;
        rj[q] = T->j[k];
        rx[q] = T->x[k];
    }
    for (size_t k = 0; k < nz; k++)
        A->p[rj[k] + 1]++;
    for (int c = 0; c < ncol; c++)
        A->p[c + 1] += A->p[c];
    memcpy(cur, A->p, sizeof(int) * (size_t)ncol);
    for (int r = 0; r < nrow; r++)
        for (int q = rp[r]; q < rp[r + 1]; q++) {
            int d = cur[rj[q]]++;
            A->i[d] = r;
            A->x[d] = rx[q];
        }
    /* sum duplicates, compacting each column */
    int w = 0;
    for (int c = 0; c < ncol; c++) {
        int start = A->p[c], end = A->p[c + 1], first = w;
        for (int q = start; q < end; q++) {
            if (w > first && A->i[w - 1] == A->i[q])
                A->x[w - 1] += A->x[q];
            else {
                A->i[w] = A->i[q];
                A->x[w] = A->x[q];
                w++;
            }
        }
        A->p[c] = first;
    }
    A->p[ncol] = w;
    st = CX_OK;
done:
    cx_free(rp);
    cx_free(rj);
    cx_free(rx);
    cx_free(cur);
    return st;
}

int cx_csc_copy(cx_csc *dst, const cx_csc *src)
{
    size_t nz = cx_csc_nnz(src);
    memset(dst, 0, sizeof *dst);
    CX_TRY(csc_alloc(dst, src->nrow, src->ncol, nz));
    memcpy(dst->p, src->p, sizeof(int) * (size_t)(src->ncol + 1));
    memcpy(dst->i, src->i, sizeof(int) * nz);
    memcpy(dst->x, src->x, sizeof(double) * nz);
    return CX_OK;
}

int cx_csc_transpose(cx_csc *At, const cx_csc *A)
{
    size_t nz = cx_csc_nnz(A);
    memset(At, 0, sizeof *At);
    CX_TRY(csc_alloc(At, A->ncol, A->nrow, nz));
    int *cur = CX_NEW(int, A->nrow + 1);
    if (!cur) {
        cx_csc_clear(At);
        return CX_ENOMEM;
    }
    for (size_t k = 0; k < nz; k++)
        At->p[A->i[k] + 1]++;
    for (int r = 0; r < A->nrow; r++)
        At->p[r + 1] += At->p[r];
    memcpy(cur, At->p, sizeof(int) * (size_t)A->nrow);
    for (int c = 0; c < A->ncol; c++)
        for (int q = A->p[c]; q < A->p[c + 1]; q++) {
            int d = cur[A->i[q]]++;
            At->i[d] = c;
            At->x[d] = A->x[q];
        }
    cx_free(cur);
    return CX_OK;
}

void cx_csc_gemv(const cx_csc *A, double alpha, const double *x, double beta, double *y)
{
    for (int r = 0; r < A->nrow; r++)
        y[r] = beta == 0 ? 0 : beta * y[r];
    for (int c = 0; c < A->ncol; c++) {
        double xc = alpha * x[c];
        if (xc == 0)
            continue;
        for (int q = A->p[c]; q < A->p[c + 1]; q++)
            y[A->i[q]] += A->x[q] * xc;
    }
}

void cx_csc_gemv_t(const cx_csc *A, double alpha, const double *x, double beta, double *y)
{
    for (int c = 0; c < A->ncol; c++) {
        double s = 0;
        for (int q = A->p[c]; q < A->p[c + 1]; q++)
            s += A->x[q] * x[A->i[q]];
        y[c] = (beta == 0 ? 0 : beta * y[c]) + alpha * s;
    }
}

int cx_csc_find(const cx_csc *A, int i, int j)
{
    int lo = A->p[j], hi = A->p[j + 1] - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        if (A->i[mid] == i)
            return mid;
        if (A->i[mid] < i)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

double cx_csc_get(const cx_csc *A, int i, int j)
{
    int q = cx_csc_find(A, i, j);
    return q >= 0 ? A->x[q] : 0;
}

double cx_csc_asymmetry(const cx_csc *A)
{
    double worst = 0;
    for (int c = 0; c < A->ncol; c++)
        for (int q = A->p[c]; q < A->p[c + 1]; q++) {
            /* outside the square part, the mirror entry is 0 */
            double m = A->i[q] < A->ncol && c < A->nrow ? cx_csc_get(A, c, A->i[q]) : 0;
            double e = fabs(A->x[q] - m);
            if (isnan(e))
                return e;
            worst = fmax(worst, e);
        }
    return worst;
}

/* ---- K + B'WB on a fixed pattern ---------------------------------------- */

void cx_csc_aug_clear(cx_csc_aug *S)
{
    cx_csc_clear(&S->A);
    cx_free(S->kpos);
    cx_free(S->prow);
    cx_free(S->ppos);
    cx_free(S->pval);
    memset(S, 0, sizeof *S);
}

/* The row products of the blocks Bt[0..nb) (rows as columns): their count,
 * or, with t, their entries added to t (value 0: the pattern only). */
static int aug_products(const cx_csc *Bt, int nb, cx_triplet *t, size_t *count)
{
    size_t c = 0;
    for (int b = 0; b < nb; b++)
        for (int r = 0; r < Bt[b].ncol; r++)
            for (int qa = Bt[b].p[r]; qa < Bt[b].p[r + 1]; qa++)
                for (int qb = Bt[b].p[r]; qb < Bt[b].p[r + 1]; qb++, c++)
                    if (t)
                        CX_TRY(cx_triplet_add(t, Bt[b].i[qa], Bt[b].i[qb], 0.0));
    *count = c;
    return CX_OK;
}

/* Where K's entries and the row products go in the pattern S->A. */
static void aug_places(cx_csc_aug *S, const cx_csc *K, const cx_csc *Bt, int nb)
{
    size_t e = 0;
    for (int j = 0; j < K->ncol; j++)
        for (int q = K->p[j]; q < K->p[j + 1]; q++)
            S->kpos[q] = cx_csc_find(&S->A, K->i[q], j);
    for (int b = 0, row = 0; b < nb; row += Bt[b].ncol, b++)
        for (int r = 0; r < Bt[b].ncol; r++)
            for (int qa = Bt[b].p[r]; qa < Bt[b].p[r + 1]; qa++)
                for (int qb = Bt[b].p[r]; qb < Bt[b].p[r + 1]; qb++, e++) {
                    S->prow[e] = row + r;
                    S->ppos[e] = cx_csc_find(&S->A, Bt[b].i[qa], Bt[b].i[qb]);
                    S->pval[e] = Bt[b].x[qa] * Bt[b].x[qb];
                }
}

int cx_csc_aug_build(cx_csc_aug *S, const cx_csc *K, const cx_csc *const *B, int nb)
{
    enum { AUG_MAX_BLOCKS = 4 };
    cx_csc Bt[AUG_MAX_BLOCKS] = {{0}};
    cx_triplet t = {0};
    memset(S, 0, sizeof *S);
    if (nb < 0 || nb > AUG_MAX_BLOCKS || K->nrow != K->ncol)
        return CX_EINVAL;
    int st = CX_OK;
    for (int b = 0; b < nb && !st; b++)
        st = B[b]->ncol != K->ncol ? CX_EINVAL : cx_csc_transpose(&Bt[b], B[b]);
    if (!st)
        st = aug_products(Bt, nb, NULL, &S->nprod);
    if (!st)
        st = cx_triplet_init(&t, K->nrow, K->ncol, cx_csc_nnz(K) + S->nprod);
    for (int j = 0; !st && j < K->ncol; j++)
        for (int q = K->p[j]; !st && q < K->p[j + 1]; q++)
            st = cx_triplet_add(&t, K->i[q], j, 0.0);
    if (!st)
        st = aug_products(Bt, nb, &t, &S->nprod);
    if (!st)
        st = cx_csc_from_triplet(&S->A, &t);
    if (!st) {
        S->kpos = CX_NEW(int, cx_csc_nnz(K) + 1);
        S->prow = CX_NEW(int, S->nprod + 1);
        S->ppos = CX_NEW(int, S->nprod + 1);
        S->pval = CX_NEW(double, S->nprod + 1);
        st = S->kpos && S->prow && S->ppos && S->pval ? CX_OK : CX_ENOMEM;
    }
    if (!st)
        aug_places(S, K, Bt, nb);
    cx_triplet_clear(&t);
    for (int b = 0; b < nb; b++)
        cx_csc_clear(&Bt[b]);
    if (st)
        cx_csc_aug_clear(S);
    return st;
}

void cx_csc_aug_fill(cx_csc_aug *S, const cx_csc *K, const double *w)
{
    memset(S->A.x, 0, sizeof(double) * cx_csc_nnz(&S->A));
    for (size_t q = 0; q < cx_csc_nnz(K); q++)
        S->A.x[S->kpos[q]] += K->x[q];
    for (size_t e = 0; e < S->nprod; e++)
        if (w[S->prow[e]] != 0)
            S->A.x[S->ppos[e]] += w[S->prow[e]] * S->pval[e];
}
