/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Sparse matrix product C = A B (CSC, Gustavson's column-by-column
 * accumulation), used to form congruence transforms T' K T. */
#include "linalg/linalg.h"

#include <string.h>

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
            double bkj = B->x[q];
            for (int r = A->p[k]; r < A->p[k + 1]; r++) {
                int i = A->i[r];
                if (mark[i] != j) {
                    if (nnz == cap) {
                        size_t nc = 2 * cap;
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
                    mark[i] = j;
                    rows[nnz++] = i;
                    acc[i] = 0;
                }
                acc[i] += A->x[r] * bkj;
            }
        }
        /* sorted rows, as cx_csc requires (columns are short: insertion sort) */
        for (size_t a = (size_t)p[j] + 1; a < nnz; a++) {
            int v = rows[a];
            size_t b = a;
            while (b > (size_t)p[j] && rows[b - 1] > v) {
                rows[b] = rows[b - 1];
                b--;
            }
            rows[b] = v;
        }
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
