/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Test matrices shared by the linalg tests: the 2D 5-point Laplacian and a
 * relative residual. */
#ifndef CX_TEST_LAPLACIAN_H
#define CX_TEST_LAPLACIAN_H

#include "linalg/linalg.h"

#include <stdlib.h>

/* 5-point Laplacian on an m x m grid (dof i*m + j), plus shift on the
 * diagonal. neumann: the diagonal is the number of neighbours, so every row
 * sums to shift (shift 0: singular, null vector = ones); otherwise 4 + shift
 * (Dirichlet-like, SPD). */
static inline void laplacian(cx_csc *A, int m, double shift, int neumann)
{
    cx_triplet t;
    int n = m * m;
    cx_triplet_init(&t, n, n, (size_t)5 * (size_t)n);
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++) {
            int k = i * m + j, deg = 0;
            int nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
            for (int q = 0; q < 4; q++) {
                int a = nb[q][0], b = nb[q][1];
                if (a < 0 || b < 0 || a >= m || b >= m)
                    continue;
                cx_triplet_add(&t, k, a * m + b, -1);
                deg++;
            }
            cx_triplet_add(&t, k, k, (neumann ? deg : 4) + shift);
        }
    cx_csc_from_triplet(A, &t);
    cx_triplet_clear(&t);
}

/* ||A x - b|| / ||b|| */
static inline double residual(const cx_csc *A, const double *x, const double *b)
{
    int n = A->nrow;
    double *r = malloc(sizeof(double) * (size_t)n);
    cx_csc_gemv(A, 1.0, x, 0.0, r);
    cx_vec_axpy(n, -1.0, b, r);
    double v = cx_vec_norm2(n, r) / cx_vec_norm2(n, b);
    free(r);
    return v;
}

#endif
