/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linalg/pcg.c: Jacobi-preconditioned CG on the 2D Laplacian; the
 * iteration limit, a breakdown and b = 0. */
#include "linalg/linalg.h"
#include "check.h"
#include "laplacian.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void apply_csc(void *ctx, const double *x, double *y) { cx_csc_gemv(ctx, 1.0, x, 0.0, y); }
static void apply_neg(void *ctx, const double *x, double *y) { cx_csc_gemv(ctx, -1.0, x, 0.0, y); }

int main(void)
{
    cx_csc A;
    cx_diag d;
    int m = 20;
    laplacian(&A, m, 0.0, 0);
    /* a varying diagonal, so that Jacobi matters */
    for (int j = 0; j < A.ncol; j++)
        for (int q = A.p[j]; q < A.p[j + 1]; q++)
            if (A.i[q] == j)
                A.x[q] += (j % 10);
    int n = A.nrow, it = -1;
    double *b = malloc(sizeof(double) * (size_t)n), *x = calloc((size_t)n, sizeof(double));
    double *w = malloc(sizeof(double) * 4 * (size_t)n), *inv = malloc(sizeof(double) * (size_t)n);
    for (int i = 0; i < n; i++) {
        b[i] = 1 + sin(i);
        inv[i] = 1 / cx_csc_get(&A, i, i);
    }
    CX_CHECK_OK(cx_pcg(n, apply_csc, &A, inv, b, x, 1e-10, 1000, &it, w, &d));
    CX_CHECK_LE(residual(&A, x, b), 1e-10);
    CX_CHECK(it > 5 && it < n);
    int it_jacobi = it;
    /* without preconditioner, from a non-zero start */
    for (int i = 0; i < n; i++)
        x[i] = 1;
    CX_CHECK_OK(cx_pcg(n, apply_csc, &A, NULL, b, x, 1e-10, 1000, &it, w, &d));
    CX_CHECK_LE(residual(&A, x, b), 1e-10);
    CX_CHECK(it > 5 && it < n);
    fprintf(stderr, "pcg: %d iterations with Jacobi, %d without (n = %d)\n", it_jacobi, it, n);
    /* the iteration limit */
    memset(x, 0, sizeof(double) * (size_t)n);
    CX_CHECK(cx_pcg(n, apply_csc, &A, NULL, b, x, 1e-10, 3, &it, w, &d) == CX_ENUMERIC);
    CX_CHECK(it == 3 && strstr(d.msg, "no convergence") != NULL);
    /* negative definite operator: breakdown at the first step */
    memset(x, 0, sizeof(double) * (size_t)n);
    CX_CHECK(cx_pcg(n, apply_neg, &A, NULL, b, x, 1e-10, 100, &it, w, &d) == CX_ENUMERIC);
    CX_CHECK(it == 0 && strstr(d.msg, "breakdown") != NULL);
    /* b = 0: x = 0 at once */
    memset(b, 0, sizeof(double) * (size_t)n);
    for (int i = 0; i < n; i++)
        x[i] = 1;
    CX_CHECK_OK(cx_pcg(n, apply_csc, &A, inv, b, x, 1e-10, 100, &it, w, &d));
    CX_CHECK(it == 0);
    CX_CHECK_NEAR(cx_vec_norminf(n, x), 0, 0, 0);
    /* NaN in the right-hand side: a failure, not success */
    b[3] = NAN;
    CX_CHECK(cx_pcg(n, apply_csc, &A, inv, b, x, 1e-10, 100, &it, w, &d) == CX_ENUMERIC);
    free(b);
    free(x);
    free(w);
    free(inv);
    cx_csc_clear(&A);
    return check_finish("linalg_pcg");
}
