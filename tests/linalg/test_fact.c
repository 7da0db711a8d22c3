/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linalg/fact.c: CHOLMOD Cholesky and UMFPACK LU. Residuals, reuse of the
 * analysis with new values, counters, and the failures: not positive
 * definite (the column named, in the original numbering), singular, solve
 * without a factor, wrong pattern. Never a NaN. */
#include "linalg/linalg.h"
#include "check.h"
#include "laplacian.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void test_cholesky(void)
{
    cx_csc A;
    cx_counters cnt = {0};
    cx_diag d;
    laplacian(&A, 30, 0.0, 0);
    int n = A.nrow;
    CX_CHECK(n == 900);
    CX_CHECK_NEAR(cx_csc_asymmetry(&A), 0, 0, 0);
    double *b = malloc(sizeof(double) * (size_t)n), *x = malloc(sizeof(double) * (size_t)n);
    for (int i = 0; i < n; i++)
        b[i] = sin(i);
    cx_fact *F = NULL;
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_CHOLESKY, &cnt, &d));
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    CX_CHECK_NEAR(cx_fact_nnz(F), 0, 0, 0);   /* before factorize */
    CX_CHECK_OK(cx_fact_factorize(F, &A, &d));
    CX_CHECK_OK(cx_fact_solve(F, b, x, &d));
    CX_CHECK_LE(residual(&A, x, b), 1e-12);
    CX_CHECK(cx_fact_nnz(F) >= cx_csc_nnz(&A) / 2);

    /* same pattern, new values (not a multiple: a second diagonal shift) */
    for (int j = 0; j < n; j++)
        for (int q = A.p[j]; q < A.p[j + 1]; q++)
            A.x[q] = A.i[q] == j ? A.x[q] + 1.0 + (j % 7) : 0.5 * A.x[q];
    memcpy(x, b, sizeof(double) * (size_t)n);
    CX_CHECK_OK(cx_fact_factorize(F, &A, &d));
    CX_CHECK_OK(cx_fact_solve(F, x, x, &d));   /* aliased */
    CX_CHECK_LE(residual(&A, x, b), 1e-12);
    CX_CHECK_OK(cx_fact_solve(F, b, x, &d));
    CX_CHECK(cnt.factorizations == 2);
    CX_CHECK(cnt.solves == 3);

    /* indefinite (-A): CX_ENUMERIC with a column, the factor unusable */
    for (size_t k = 0; k < cx_csc_nnz(&A); k++)
        A.x[k] = -A.x[k];
    cx_diag_clear(&d);
    CX_CHECK(cx_fact_factorize(F, &A, &d) == CX_ENUMERIC);
    CX_CHECK(strstr(d.msg, "not positive definite (pivot at column") != NULL);
    CX_CHECK(cnt.factorizations == 3);
    for (int i = 0; i < n; i++)
        x[i] = 7;
    CX_CHECK(cx_fact_solve(F, b, x, &d) == CX_EINVAL);   /* no NaN from a broken factor */
    CX_CHECK_NEAR(x[0], 7, 0, 0);
    CX_CHECK_NEAR(cx_fact_nnz(F), 0, 0, 0);

    /* a different pattern than analysed is refused */
    cx_csc B;
    laplacian(&B, 29, 0.0, 0);
    CX_CHECK(cx_fact_factorize(F, &B, &d) == CX_EINVAL);
    cx_csc_clear(&B);
    cx_fact_destroy(&F);
    CX_CHECK(F == NULL);
    cx_fact_destroy(&F);   /* NULL-safe */
    cx_fact_destroy(NULL);
    cx_csc_clear(&A);
    free(b);
    free(x);
}

/* A diagonal matrix with one negative entry at dof 7: whatever the
 * ordering, the failing pivot is column 7 of the original numbering. */
static void test_cholesky_column(void)
{
    cx_triplet t;
    cx_csc A;
    cx_diag d;
    int n = 12;
    cx_triplet_init(&t, n, n, (size_t)n);
    for (int i = 0; i < n; i++)
        cx_triplet_add(&t, i, i, i == 7 ? -1.0 : 1.0 + i);
    cx_csc_from_triplet(&A, &t);
    cx_fact *F = NULL;
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_CHOLESKY, NULL, &d));
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    CX_CHECK(cx_fact_factorize(F, &A, &d) == CX_ENUMERIC);
    CX_CHECK(d.status == CX_ENUMERIC);
    CX_CHECK(strstr(d.msg, "(pivot at column 7)") != NULL);
    cx_fact_destroy(&F);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);
}

/* Singular positive semi-definite matrices: an exact zero pivot (two equal
 * rows [1 1; 1 1] coupled into an SPD chain) and the Neumann Laplacian
 * (the zero pivot appears only up to rounding). Both CX_ENUMERIC. */
static void test_cholesky_singular(void)
{
    cx_triplet t;
    cx_csc A;
    cx_diag d;
    int n = 6;
    cx_triplet_init(&t, n, n, 32);
    for (int i = 0; i < n; i++)
        cx_triplet_add(&t, i, i, i < 2 ? 1.0 : 4.0);
    cx_triplet_add(&t, 0, 1, 1.0);
    cx_triplet_add(&t, 1, 0, 1.0);
    for (int i = 2; i + 1 < n; i++) {
        cx_triplet_add(&t, i, i + 1, -1.0);
        cx_triplet_add(&t, i + 1, i, -1.0);
    }
    cx_csc_from_triplet(&A, &t);
    cx_fact *F = NULL;
    double b[6] = {1, 2, 3, 4, 5, 6}, x[6];
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_CHOLESKY, NULL, &d));
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    int st = cx_fact_factorize(F, &A, &d);
    CX_CHECK(st == CX_ENUMERIC);
    CX_CHECK(strstr(d.msg, "column 0") != NULL || strstr(d.msg, "column 1") != NULL);
    CX_CHECK(cx_fact_solve(F, b, x, &d) == CX_EINVAL);
    cx_fact_destroy(&F);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);

    laplacian(&A, 10, 0.0, 1);
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_CHOLESKY, NULL, &d));
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    cx_diag_clear(&d);
    CX_CHECK(cx_fact_factorize(F, &A, &d) == CX_ENUMERIC);
    CX_CHECK(strstr(d.msg, "column") != NULL);
    cx_fact_destroy(&F);
    cx_csc_clear(&A);

    /* solve or factorize before analyse */
    double one = 1, y;
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_CHOLESKY, NULL, &d));
    CX_CHECK(cx_fact_solve(F, &one, &y, &d) == CX_EINVAL);
    laplacian(&A, 3, 0.0, 0);
    CX_CHECK(cx_fact_factorize(F, &A, &d) == CX_EINVAL);
    cx_fact_destroy(&F);
    cx_csc_clear(&A);
}

/* Non-symmetric: a 2D convection-diffusion operator (upwind), m x m grid. */
static void convection(cx_csc *A, int m, double v)
{
    cx_triplet t;
    int n = m * m;
    cx_triplet_init(&t, n, n, (size_t)5 * (size_t)n);
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++) {
            int k = i * m + j;
            cx_triplet_add(&t, k, k, 4 + v);
            if (i > 0)
                cx_triplet_add(&t, k, k - m, -1 - v);
            if (i + 1 < m)
                cx_triplet_add(&t, k, k + m, -1);
            if (j > 0)
                cx_triplet_add(&t, k, k - 1, -1);
            if (j + 1 < m)
                cx_triplet_add(&t, k, k + 1, -1 + 0.3 * v);
        }
    cx_csc_from_triplet(A, &t);
    cx_triplet_clear(&t);
}

static void test_lu(void)
{
    cx_csc A;
    cx_diag d;
    cx_counters cnt = {0};
    convection(&A, 20, 2.0);
    int n = A.nrow;
    CX_CHECK(cx_csc_asymmetry(&A) > 1);
    double *b = malloc(sizeof(double) * (size_t)n), *x = malloc(sizeof(double) * (size_t)n);
    for (int i = 0; i < n; i++)
        b[i] = cos(0.1 * i) + 1;
    cx_fact *F = NULL;
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_LU, &cnt, &d));
    CX_CHECK(cx_fact_solve(F, b, x, &d) == CX_EINVAL);
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    CX_CHECK_OK(cx_fact_factorize(F, &A, &d));
    CX_CHECK_OK(cx_fact_solve(F, b, x, &d));
    CX_CHECK_LE(residual(&A, x, b), 1e-12);
    CX_CHECK(cx_fact_nnz(F) >= cx_csc_nnz(&A));
    /* new values, same pattern, symbolic analysis reused */
    cx_csc B;
    convection(&B, 20, 5.0);
    CX_CHECK_OK(cx_fact_factorize(F, &B, &d));
    memcpy(x, b, sizeof(double) * (size_t)n);
    CX_CHECK_OK(cx_fact_solve(F, x, x, &d));   /* aliased */
    CX_CHECK_LE(residual(&B, x, b), 1e-12);
    CX_CHECK(cnt.factorizations == 2 && cnt.solves == 2);
    cx_fact_destroy(&F);
    cx_csc_clear(&A);
    cx_csc_clear(&B);
    free(b);
    free(x);

    /* hand-checked 3 x 3: [4 1 0; 2 5 1; 0 3 6] x = (5, 8, 9) has x = (1, 1, 1) */
    cx_triplet t;
    double v[3][3] = {{4, 1, 0}, {2, 5, 1}, {0, 3, 6}}, b3[3] = {5, 8, 9}, x3[3];
    cx_triplet_init(&t, 3, 3, 9);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (v[i][j] != 0)
                cx_triplet_add(&t, i, j, v[i][j]);
    cx_csc_from_triplet(&A, &t);
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_LU, NULL, &d));
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    CX_CHECK_OK(cx_fact_factorize(F, &A, &d));
    CX_CHECK_OK(cx_fact_solve(F, b3, x3, &d));
    for (int i = 0; i < 3; i++)
        CX_CHECK_NEAR(x3[i], 1, 1e-14, 0);
    cx_fact_destroy(&F);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);
}

static void test_lu_singular(void)
{
    cx_triplet t;
    cx_csc A;
    cx_diag d;
    cx_fact *F = NULL;
    double b[4] = {1, 2, 3, 4}, x[4];
    /* the third row a copy of the first */
    double s[3][3] = {{4, 1, 0}, {2, 5, 1}, {4, 1, 0}};
    cx_triplet_init(&t, 3, 3, 9);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            cx_triplet_add(&t, i, j, s[i][j]);
    cx_csc_from_triplet(&A, &t);
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_LU, NULL, &d));
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    CX_CHECK(cx_fact_factorize(F, &A, &d) == CX_ENUMERIC);
    CX_CHECK(strstr(d.msg, "singular") != NULL && strstr(d.msg, "column") != NULL);
    CX_CHECK(cx_fact_solve(F, b, x, &d) == CX_EINVAL);
    cx_fact_destroy(&F);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);

    /* column 2 stored but all zero: the zero pivot is column 2 */
    cx_triplet_init(&t, 4, 4, 16);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            cx_triplet_add(&t, i, j, j == 2 ? 0.0 : (i == j ? 5.0 : 1.0 + i - j));
    cx_csc_from_triplet(&A, &t);
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_LU, NULL, &d));
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    CX_CHECK(cx_fact_factorize(F, &A, &d) == CX_ENUMERIC);
    CX_CHECK(strstr(d.msg, "column 2)") != NULL);
    cx_fact_destroy(&F);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);

    /* singular in exact arithmetic, not in floating point (0.1 etc. are
     * rounded): the last pivot is rounding noise */
    double e[3][3] = {{0.1, 0.2, 0.3}, {0.4, 0.5, 0.6}, {0.7, 0.8, 0.9}};
    cx_triplet_init(&t, 3, 3, 9);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            cx_triplet_add(&t, i, j, e[i][j]);
    cx_csc_from_triplet(&A, &t);
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_LU, NULL, &d));
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    CX_CHECK(cx_fact_factorize(F, &A, &d) == CX_ENUMERIC);
    cx_fact_destroy(&F);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);

    /* not square */
    cx_triplet_init(&t, 2, 3, 1);
    cx_triplet_add(&t, 0, 0, 1);
    cx_csc_from_triplet(&A, &t);
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_LU, NULL, &d));
    CX_CHECK(cx_fact_analyze(F, &A, &d) == CX_EINVAL);
    cx_fact_destroy(&F);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);
}

/* Out of memory in our own allocations of the LU path: CX_ENOMEM, no leak. */
static void test_alloc_failure(void)
{
    cx_csc A;
    cx_diag d;
    convection(&A, 5, 1.0);
    long live = cx_alloc_live();
    int st = CX_ENOMEM, k;
    for (k = 0; k < 20 && st != CX_OK; k++) {
        cx_fact *F = NULL;
        cx_alloc_fail_after(k);
        st = cx_fact_create(&F, CX_FACT_LU, NULL, &d);
        if (st == CX_OK && (st = cx_fact_analyze(F, &A, &d)) == CX_OK)
            st = cx_fact_factorize(F, &A, &d);
        cx_alloc_fail_after(-1);
        CX_CHECK(st == CX_OK || st == CX_ENOMEM);
        cx_fact_destroy(&F);
        CX_CHECK(cx_alloc_live() == live);
    }
    CX_CHECK(st == CX_OK && k > 1);
    cx_csc_clear(&A);
}

int main(void)
{
    test_cholesky();
    test_cholesky_column();
    test_cholesky_singular();
    test_lu();
    test_lu_singular();
    test_alloc_failure();
    return check_finish("linalg_fact");
}
