/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linalg/dense.c: the LAPACK kernels against hand solutions; singular and
 * non-finite input give CX_ENUMERIC; counters. */
#include "linalg/linalg.h"
#include "check.h"

#include <math.h>

static void test_sym_solve(void)
{
    cx_counters cnt = {0};
    /* indefinite (eigenvalues of both signs; zero first pivot):
     * [0 1 0; 1 0 2; 0 2 1] x = (1, 2, 3). Row 1: x2 = 1; row 3: 2 + x3 = 3,
     * x3 = 1; row 2: x1 + 2 = 2, x1 = 0. */
    double A[9] = {0, 1, 0, 1, 0, 2, 0, 2, 1}, b[3] = {1, 2, 3}, work[192];
    int ipiv[3];
    CX_CHECK_OK(cx_dense_sym_solve(3, A, b, ipiv, work, 192, &cnt));
    CX_CHECK_NEAR(b[0], 0, 0, 1e-15);
    CX_CHECK_NEAR(b[1], 1, 1e-15, 0);
    CX_CHECK_NEAR(b[2], 1, 1e-15, 0);
    CX_CHECK(cnt.dense_factorizations == 1);
    /* minimal workspace lwork = n */
    double A2[9] = {0, 1, 0, 1, 0, 2, 0, 2, 1}, b2[3] = {1, 2, 3};
    CX_CHECK_OK(cx_dense_sym_solve(3, A2, b2, ipiv, work, 3, &cnt));
    CX_CHECK_NEAR(b2[2], 1, 1e-15, 0);
    /* singular [1 2; 2 4] */
    double Z[4] = {1, 2, 2, 4}, z[2] = {1, 1};
    CX_CHECK(cx_dense_sym_solve(2, Z, z, ipiv, work, 128, &cnt) == CX_ENUMERIC);
    CX_CHECK(cnt.dense_factorizations == 3);
    /* NaN in the data: refused, not passed on */
    double Q[4] = {1, NAN, NAN, 2}, q[2] = {1, 1};
    CX_CHECK(cx_dense_sym_solve(2, Q, q, ipiv, work, 128, NULL) == CX_ENUMERIC);
    /* n = 0: nothing to do, nothing counted */
    CX_CHECK_OK(cx_dense_sym_solve(0, NULL, NULL, ipiv, work, 1, &cnt));
    CX_CHECK(cnt.dense_factorizations == 3);
}

static void test_cholesky(void)
{
    cx_counters cnt = {0};
    /* [4 2 0; 2 5 3; 0 3 10] = L L' with L = [2 0 0; 1 2 0; 0 1.5 sqrt(7.75)] */
    double P[9] = {4, 2, 0, 2, 5, 3, 0, 3, 10};
    CX_CHECK_OK(cx_dense_cholesky(3, P, &cnt));
    CX_CHECK_NEAR(P[0], 2, 1e-15, 0);
    CX_CHECK_NEAR(P[1], 1, 1e-15, 0);
    CX_CHECK_NEAR(P[4], 2, 1e-15, 0);
    CX_CHECK_NEAR(P[5], 1.5, 1e-15, 0);
    CX_CHECK_NEAR(P[8], sqrt(7.75), 1e-15, 0);
    /* x = (1, -1, 2): b = (2, 3, 17); two right-hand sides at once */
    double B[6] = {2, 3, 17, 4, 6, 34};
    cx_dense_cholesky_solve(3, P, B, 2);
    CX_CHECK_NEAR(B[0], 1, 1e-14, 0);
    CX_CHECK_NEAR(B[1], -1, 1e-14, 0);
    CX_CHECK_NEAR(B[2], 2, 1e-14, 0);
    CX_CHECK_NEAR(B[3], 2, 1e-14, 0);
    CX_CHECK_NEAR(B[5], 4, 1e-14, 0);
    CX_CHECK(cnt.dense_factorizations == 1);
    double N[4] = {1, 2, 2, 1};   /* indefinite */
    CX_CHECK(cx_dense_cholesky(2, N, &cnt) == CX_ENUMERIC);
    double S[4] = {1, 1, 1, 1};   /* singular semi-definite */
    CX_CHECK(cx_dense_cholesky(2, S, &cnt) == CX_ENUMERIC);
    double Q[4] = {NAN, 0, 0, 1};
    CX_CHECK(cx_dense_cholesky(2, Q, &cnt) == CX_ENUMERIC);
}

static void test_lu(void)
{
    cx_counters cnt = {0};
    int ipiv[3];
    /* zero first pivot: row exchange needed. [0 1; 1 0] x = (3, 4) -> (4, 3) */
    double G[4] = {0, 1, 1, 0}, g[2] = {3, 4};
    CX_CHECK_OK(cx_dense_lu_solve(2, G, g, ipiv, &cnt));
    CX_CHECK_NEAR(g[0], 4, 1e-15, 0);
    CX_CHECK_NEAR(g[1], 3, 1e-15, 0);
    /* [4 1 0; 2 5 1; 0 3 6] (row-major) x = (5, 8, 9): x = (1, 1, 1) */
    double A[9] = {4, 2, 0, 1, 5, 3, 0, 1, 6}, b[3] = {5, 8, 9};
    CX_CHECK_OK(cx_dense_lu_solve(3, A, b, ipiv, &cnt));
    for (int i = 0; i < 3; i++)
        CX_CHECK_NEAR(b[i], 1, 1e-15, 0);
    double Z[4] = {1, 2, 2, 4}, z[2] = {1, 1};
    CX_CHECK(cx_dense_lu_solve(2, Z, z, ipiv, &cnt) == CX_ENUMERIC);
    CX_CHECK(cnt.dense_factorizations == 3);
}

static void test_gemv(void)
{
    /* 2 x 3 [1 2 3; 4 5 6] (column-major), x = (1, 0, -1): A x = (-2, -2) */
    double A[6] = {1, 4, 2, 5, 3, 6}, x[3] = {1, 0, -1}, y[2] = {10, 20};
    cx_dense_gemv(2, 3, 2.0, A, x, 0.5, y);
    CX_CHECK_NEAR(y[0], 1, 1e-15, 0);
    CX_CHECK_NEAR(y[1], 6, 1e-15, 0);
    double ynan[2] = {NAN, NAN};
    cx_dense_gemv(2, 3, 1.0, A, x, 0.0, ynan);   /* BLAS: beta = 0 ignores y */
    CX_CHECK_NEAR(ynan[0], -2, 1e-15, 0);
    CX_CHECK_NEAR(ynan[1], -2, 1e-15, 0);
}

int main(void)
{
    test_sym_solve();
    test_cholesky();
    test_lu();
    test_gemv();
    return check_finish("linalg_dense");
}
