/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Sparse matrix product C = A B (CSC, Gustavson's column-by-column
 * accumulation), used to form congruence transforms T' K T. */
#include "linalg/linalg.h"

#include <string.h>

/* Sort rows[0..n) ascending (a column of a product: short, insertion). */
static void spgemm_sort(int *rows, size_t n)
{
    for (size_t a = 1; a < n; a++) {
        int v = rows[a];
        size_t b = a;
        for (; b > 0 && rows[b - 1] > v; b--)
            rows[b] = rows[b - 1];
        rows[b] = v;
    }
}

/* acc += x A(:, k) on a sparse accumulator for column j: a row first met
 * in column j is marked, appended to list[n..) and its sum started; the
 * new length of list is returned. */
static size_t spgemm_axpy(const cx_csc *A, int k, double x, int j, int *mark, int *list, size_t n, double *acc)
{
    for (int r = A->p[k]; r < A->p[k + 1]; r++) {
        int i = A->i[r];
        if (mark[i] != j) {
            mark[i] = j;
            list[n++] = i;
            acc[i] = 0;
        }
        acc[i] += A->x[r] * x;
    }
    return n;
}

int cx_csc_multiply(cx_csc *C, const cx_csc *A, const cx_csc *B)
{
    int m = A->nrow, n = B->ncol;
    memset(C, 0, sizeof *C);
    if (A->ncol != B->nrow)
        return CX_EINVAL;
    int *mark = CX_NEW(int, m), *p = CX_NEW(int, n + 1);
    double *acc = CX_NEW(double, m);
    int *rows = NULL;
    double *vals = NULL;
    size_t cap = cx_csc_nnz(A) + cx_csc_nnz(B) + (size_t)m + 1, nnz = 0;
    rows = CX_NEW(int, cap);
    vals = CX_NEW(double, cap);
    if (!mark || !p || !acc || !rows || !vals)
        goto nomem;
    for (int i = 0; i < m; i++)
        mark[i] = -1;
    for (int j = 0; j < n; j++) {
        p[j] = (int)nnz;
        for (int q = B->p[j]; q < B->p[j + 1]; q++) {
            int k = B->i[q];
            size_t len = (size_t)(A->p[k + 1] - A->p[k]);
            if (nnz + len > cap) {   /* room for all of A(:, k) */
                size_t nc = 2 * cap > nnz + len ? 2 * cap : nnz + len;
                int *nr = cx_realloc(rows, sizeof(int) * nc);
                if (!nr)
                    goto nomem;
                rows = nr;
                double *nv = cx_realloc(vals, sizeof(double) * nc);
                if (!nv)
                    goto nomem;
                vals = nv;
                cap = nc;
            }
            nnz = spgemm_axpy(A, k, B->x[q], j, mark, rows, nnz, acc);
        }
        spgemm_sort(rows + p[j], nnz - (size_t)p[j]);   /* sorted rows, as cx_csc requires */
        for (size_t a = (size_t)p[j]; a < nnz; a++)
            vals[a] = acc[rows[a]];
    }
    p[n] = (int)nnz;
    cx_free(mark);
    cx_free(acc);
    C->nrow = m, C->ncol = n, C->p = p, C->i = rows, C->x = vals;
    return CX_OK;
nomem:
    cx_free(mark);
    cx_free(acc);
    cx_free(p);
    cx_free(rows);
    cx_free(vals);
    return CX_ENOMEM;
}

int cx_csc_congruence(cx_csc *C, const cx_csc *K, const cx_csc *T)
{
    int m = K->nrow, n = T->ncol, st = CX_ENOMEM;
    memset(C, 0, sizeof *C);
    if (K->ncol != m || T->nrow != m)
        return CX_EINVAL;
    cx_csc Tt = {0};
    int *mark1 = CX_NEW(int, m), *list1 = CX_NEW(int, m), *mark2 = CX_NEW(int, n);
    double *acc1 = CX_NEW(double, m), *acc2 = CX_NEW(double, n);
    int *p = CX_NEW(int, n + 1), *rows = NULL;
    double *vals = NULL;
    if (!mark1 || !list1 || !mark2 || !acc1 || !acc2 || !p || cx_csc_transpose(&Tt, T))
        goto done;
    /* A bound on the entries written, so that the output is allocated
     * once (the product's realloc copies were a fifth of the LCP build):
     * column j of K T has at most the entries of the columns of K it
     * combines, and each is spread over at most the longest row of T.
     * Pages beyond what is written are never touched; the arrays are
     * shrunk at the end. */
    int rmax = 0;
    for (int i = 0; i < m; i++)
        if (Tt.p[i + 1] - Tt.p[i] > rmax)
            rmax = Tt.p[i + 1] - Tt.p[i];
    size_t cap = 1;
    for (int j = 0; j < n; j++) {
        size_t kt = 0;
        for (int q = T->p[j]; q < T->p[j + 1]; q++)
            kt += (size_t)(K->p[T->i[q] + 1] - K->p[T->i[q]]);
        size_t b = kt * (size_t)rmax;
        cap += b < (size_t)n ? b : (size_t)n;
    }
    rows = CX_NEW(int, cap);
    vals = CX_NEW(double, cap);
    if (!rows || !vals)
        goto done;
    for (int i = 0; i < m; i++)
        mark1[i] = -1;
    for (int i = 0; i < n; i++)
        mark2[i] = -1;
    size_t nnz = 0;
    for (int j = 0; j < n; j++) {
        /* w = K T(:, j) on the rows list1[0..n1) */
        size_t n1 = 0;
        for (int q = T->p[j]; q < T->p[j + 1]; q++)
            n1 = spgemm_axpy(K, T->i[q], T->x[q], j, mark1, list1, n1, acc1);
        /* C(:, j) = T' w: row i of T spread by w_i */
        p[j] = (int)nnz;
        for (size_t a = 0; a < n1; a++)
            nnz = spgemm_axpy(&Tt, list1[a], acc1[list1[a]], j, mark2, rows, nnz, acc2);
        spgemm_sort(rows + p[j], nnz - (size_t)p[j]);
        for (size_t a = (size_t)p[j]; a < nnz; a++)
            vals[a] = acc2[rows[a]];
    }
    p[n] = (int)nnz;
    /* shrink to what was written (never fails to keep the old block) */
    int *r2 = cx_realloc(rows, sizeof(int) * (nnz ? nnz : 1));
    double *v2 = cx_realloc(vals, sizeof(double) * (nnz ? nnz : 1));
    if (r2)
        rows = r2;
    if (v2)
        vals = v2;
    C->nrow = C->ncol = n, C->p = p, C->i = rows, C->x = vals;
    p = NULL, rows = NULL, vals = NULL;
    st = CX_OK;
done:
    cx_csc_clear(&Tt);
    cx_free(mark1), cx_free(list1), cx_free(mark2), cx_free(acc1), cx_free(acc2);
    cx_free(p), cx_free(rows), cx_free(vals);
    return st;
}
