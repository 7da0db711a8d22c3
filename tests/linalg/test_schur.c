/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linalg/schur.c: the Schur complement S = A_cc - A_ci A_ii^-1 A_ic from one
 * constrained-order Cholesky, with condense and expand, against a dense
 * reference (LAPACK on the blocks). An SPD matrix, a SINGULAR one (Neumann
 * Laplacian, held only through the c dofs), a tiny one, a large one (no
 * dense n x n anywhere), and the failures. */
#include "linalg/linalg.h"
#include "check.h"
#include "laplacian.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Dense reference by blocks: S, fc = f_c - A_ci A_ii^-1 f_i and
 * u (u_c = uc, u_i = A_ii^-1 (f_i - A_ic uc)), through a dense Cholesky of
 * A_ii. */
static void dense_reference(const cx_csc *A, const int *c, int nc, const double *f, const double *uc,
                            double *S, double *fc, double *u)
{
    int n = A->nrow, ni = n - nc;
    int *isc = calloc((size_t)n, sizeof(int)), *ii = malloc(sizeof(int) * (size_t)ni);
    for (int k = 0; k < nc; k++)
        isc[c[k]] = 1;
    for (int j = 0, k = 0; j < n; j++)
        if (!isc[j])
            ii[k++] = j;
    double *Aii = malloc(sizeof(double) * (size_t)ni * (size_t)ni);
    double *X = malloc(sizeof(double) * (size_t)ni * (size_t)(nc + 2));   /* [A_ic, f_i, f_i - A_ic uc] */
    for (int a = 0; a < ni; a++) {
        for (int b = 0; b < ni; b++)
            Aii[a + (size_t)b * ni] = cx_csc_get(A, ii[a], ii[b]);
        double r = f[ii[a]];
        for (int b = 0; b < nc; b++) {
            X[a + (size_t)b * ni] = cx_csc_get(A, ii[a], c[b]);
            r -= X[a + (size_t)b * ni] * uc[b];
        }
        X[a + (size_t)nc * ni] = f[ii[a]];
        X[a + (size_t)(nc + 1) * ni] = r;
    }
    double *Aic = malloc(sizeof(double) * (size_t)ni * (size_t)nc);
    memcpy(Aic, X, sizeof(double) * (size_t)ni * (size_t)nc);
    CX_CHECK_OK(cx_dense_cholesky(ni, Aii, NULL));
    cx_dense_cholesky_solve(ni, Aii, X, nc + 2);
    for (int a = 0; a < nc; a++) {
        for (int b = 0; b < nc; b++) {
            double s = cx_csc_get(A, c[a], c[b]);
            for (int k = 0; k < ni; k++)
                s -= Aic[k + (size_t)a * ni] * X[k + (size_t)b * ni];
            S[a + (size_t)b * nc] = s;
        }
        double s = f[c[a]];
        for (int k = 0; k < ni; k++)
            s -= Aic[k + (size_t)a * ni] * X[k + (size_t)nc * ni];
        fc[a] = s;
        u[c[a]] = uc[a];
    }
    for (int k = 0; k < ni; k++)
        u[ii[k]] = X[k + (size_t)(nc + 1) * ni];
    free(isc);
    free(ii);
    free(Aii);
    free(X);
    free(Aic);
}

static double max_abs(int n, const double *x) { return cx_vec_norminf(n, x); }

static double max_diff(int n, const double *x, const double *y)
{
    double e = 0;
    for (int i = 0; i < n; i++)
        e = fmax(e, fabs(x[i] - y[i]));
    return e;
}

/* S, condense and expand against the dense reference to 1e-10 relative;
 * A u = f on the i rows; u_c = uc exactly. */
static void check_against_dense(const cx_csc *A, const int *c, int nc, int singular)
{
    cx_diag d;
    cx_counters cnt = {0};
    int n = A->nrow;
    cx_schur *S = NULL;
    CX_CHECK_OK(cx_schur_create(&S, A, c, nc, &cnt, &d));
    if (!S)
        return;
    CX_CHECK(cnt.factorizations == 1 && cnt.solves == 0);
    CX_CHECK(cx_schur_size(S) == nc);
    CX_CHECK(cx_schur_factor_nnz(S) > 0);

    double *f = malloc(sizeof(double) * (size_t)n), *u = malloc(sizeof(double) * (size_t)n);
    double *uref = malloc(sizeof(double) * (size_t)n), *r = malloc(sizeof(double) * (size_t)n);
    double *uc = malloc(sizeof(double) * (size_t)nc), *fc = malloc(sizeof(double) * (size_t)nc);
    double *fcref = malloc(sizeof(double) * (size_t)nc);
    double *Sref = malloc(sizeof(double) * (size_t)nc * (size_t)nc);
    for (int i = 0; i < n; i++)
        f[i] = cos(0.3 * i) + 0.2;
    for (int k = 0; k < nc; k++)
        uc[k] = 0.01 * k - 0.05;
    dense_reference(A, c, nc, f, uc, Sref, fcref, uref);

    const double *Sm = cx_schur_matrix(S);
    double smax = max_abs(nc * nc, Sref);   /* the scale of S (0 if nc = 1 and A singular) */
    for (int k = 0; k < nc; k++)
        smax = fmax(smax, cx_csc_get(A, c[k], c[k]));
    CX_CHECK_LE(max_diff(nc * nc, Sm, Sref), 1e-10 * smax);
    for (int a = 0; a < nc; a++)   /* stored full, symmetric */
        for (int b = 0; b < a; b++)
            CX_CHECK_NEAR(Sm[a + (size_t)b * nc], Sm[b + (size_t)a * nc], 0, 1e-14 * smax);
    if (singular) {
        /* S inherits the constant null vector: S ones = 0 */
        for (int a = 0; a < nc; a++) {
            double s = 0;
            for (int b = 0; b < nc; b++)
                s += Sm[a + (size_t)b * nc];
            CX_CHECK_NEAR(s, 0, 0, 1e-10 * smax);
        }
    }

    CX_CHECK_OK(cx_schur_condense(S, f, fc));
    CX_CHECK_LE(max_diff(nc, fc, fcref), 1e-10 * fmax(max_abs(nc, fcref), max_abs(n, f)));
    CX_CHECK_OK(cx_schur_expand(S, f, uc, u));
    CX_CHECK_LE(max_diff(n, u, uref), 1e-10 * max_abs(n, uref));
    CX_CHECK(cnt.solves == 2 && cnt.factorizations == 1);

    int *isc = calloc((size_t)n, sizeof(int));
    for (int k = 0; k < nc; k++) {
        isc[c[k]] = 1;
        CX_CHECK_NEAR(u[c[k]], uc[k], 0, 0);   /* exactly */
    }
    cx_csc_gemv(A, 1.0, u, 0.0, r);
    double rmax = 0;
    for (int i = 0; i < n; i++)
        if (!isc[i])
            rmax = fmax(rmax, fabs(r[i] - f[i]));
    CX_CHECK_LE(rmax, 1e-10 * max_abs(n, f));
    /* and on the c rows: (A u)_c = S u_c + (f_c - fc) */
    for (int a = 0; a < nc; a++) {
        double s = f[c[a]] - fc[a];
        for (int b = 0; b < nc; b++)
            s += Sm[a + (size_t)b * nc] * uc[b];
        CX_CHECK_NEAR(r[c[a]], s, 0, 1e-10 * max_abs(n, f));
    }
    /* the forward half of the solve kept for f gives the same u again;
     * another f is not served from it */
    CX_CHECK_OK(cx_schur_expand(S, f, uc, r));
    CX_CHECK_LE(max_diff(n, r, u), 0);
    for (int i = 0; i < n; i++)
        f[i] = sin(0.7 * i) - 0.1;
    dense_reference(A, c, nc, f, uc, Sref, fcref, uref);
    CX_CHECK_OK(cx_schur_expand(S, f, uc, u));
    CX_CHECK_LE(max_diff(n, u, uref), 1e-10 * max_abs(n, uref));
    CX_CHECK_OK(cx_schur_condense(S, f, fc));
    CX_CHECK_LE(max_diff(nc, fc, fcref), 1e-10 * fmax(max_abs(nc, fcref), max_abs(n, f)));
    CX_CHECK(cnt.solves == 5 && cnt.factorizations == 1);
    free(isc);
    free(f);
    free(u);
    free(uref);
    free(r);
    free(uc);
    free(fc);
    free(fcref);
    free(Sref);
    cx_schur_destroy(&S);
    CX_CHECK(S == NULL);
}

/* ~200 dofs, 15 c dofs scattered through the numbering (not the last). */
static void test_spd(void)
{
    cx_csc A;
    int m = 14, nc = 15, c[15];
    laplacian(&A, m, 0.1, 0);
    for (int k = 0; k < nc; k++)
        c[k] = (37 * k + 11) % (m * m);   /* 11, 48, 85, ..., 5: not sorted */
    check_against_dense(&A, c, nc, 0);
    cx_csc_clear(&A);
}

/* Neumann Laplacian: zero row sums, singular (null vector ones); A_ii is
 * SPD since c is not empty. */
static void test_singular(void)
{
    cx_csc A;
    int m = 14, nc = 15, c[15];
    laplacian(&A, m, 0.0, 1);
    for (int k = 0; k < nc; k++)
        c[k] = (53 * k + 100) % (m * m);
    check_against_dense(&A, c, nc, 1);
    cx_csc_clear(&A);
}

/* 10 dofs (1D Neumann chain), c = {7, 2}: also when nc = 1 and nc = n. */
static void test_small(void)
{
    cx_triplet t;
    cx_csc A;
    int n = 10;
    cx_triplet_init(&t, n, n, 32);
    for (int i = 0; i < n; i++) {
        cx_triplet_add(&t, i, i, (i == 0 || i == n - 1) ? 1.0 : 2.0);
        if (i + 1 < n) {
            cx_triplet_add(&t, i, i + 1, -1.0);
            cx_triplet_add(&t, i + 1, i, -1.0);
        }
    }
    cx_csc_from_triplet(&A, &t);
    int c[2] = {7, 2};
    check_against_dense(&A, c, 2, 1);
    /* S for the chain: the path 2-7 is 5 springs in series, so
     * S = (1/5) [1 -1; -1 1] */
    cx_schur *S = NULL;
    cx_diag d;
    CX_CHECK_OK(cx_schur_create(&S, &A, c, 2, NULL, &d));
    const double *Sm = cx_schur_matrix(S);
    CX_CHECK_NEAR(Sm[0], 0.2, 1e-13, 0);
    CX_CHECK_NEAR(Sm[1], -0.2, 1e-13, 0);
    CX_CHECK_NEAR(Sm[2], -0.2, 1e-13, 0);
    CX_CHECK_NEAR(Sm[3], 0.2, 1e-13, 0);
    cx_schur_destroy(&S);
    int c1[1] = {4};
    check_against_dense(&A, c1, 1, 1);
    int call[10] = {9, 0, 1, 2, 3, 4, 5, 6, 7, 8};   /* S = A reordered */
    CX_CHECK_OK(cx_schur_create(&S, &A, call, n, NULL, &d));
    Sm = cx_schur_matrix(S);
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++)
            CX_CHECK_NEAR(Sm[a + (size_t)b * n], cx_csc_get(&A, call[a], call[b]), 0, 1e-14);
    cx_schur_destroy(&S);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);
}

/* 300 x 300 Neumann grid (90 000 dofs, singular), the 300 dofs of one edge
 * as c: must run with sparse work only. */
static void test_large(void)
{
    cx_csc A;
    cx_diag d;
    int m = 300, n = m * m, nc = m;
    laplacian(&A, m, 0.0, 1);
    int *c = malloc(sizeof(int) * (size_t)nc);
    for (int k = 0; k < nc; k++)
        c[k] = k * m + (m - 1);   /* the edge j = m - 1 */
    cx_schur *S = NULL;
    CX_CHECK_OK(cx_schur_create(&S, &A, c, nc, NULL, &d));
    if (!S) {
        fprintf(stderr, "%s\n", d.msg);
        return;
    }
    CX_CHECK_LE(cx_schur_factor_nnz(S), 0.01 * (double)n * n);
    const double *Sm = cx_schur_matrix(S);
    double smax = cx_vec_norminf(nc * nc, Sm), rs = 0;
    for (int a = 0; a < nc; a++) {
        double s = 0;
        for (int b = 0; b < nc; b++)
            s += Sm[a + (size_t)b * nc];
        rs = fmax(rs, fabs(s));
    }
    CX_CHECK_LE(rs, 1e-10 * smax);   /* S ones = 0 */
    double *f = malloc(sizeof(double) * (size_t)n), *u = malloc(sizeof(double) * (size_t)n);
    double *r = malloc(sizeof(double) * (size_t)n), *uc = malloc(sizeof(double) * (size_t)nc);
    for (int i = 0; i < n; i++)
        f[i] = sin(0.001 * i);
    for (int k = 0; k < nc; k++)
        uc[k] = 1e-3 * k;
    CX_CHECK_OK(cx_schur_expand(S, f, uc, u));
    cx_csc_gemv(&A, 1.0, u, 0.0, r);
    double rmax = 0;
    for (int i = 0; i < n; i++)
        if (i % m != m - 1)
            rmax = fmax(rmax, fabs(r[i] - f[i]));
    CX_CHECK_LE(rmax, 1e-10 * cx_vec_norminf(n, f));
    cx_schur_destroy(&S);
    cx_csc_clear(&A);
    free(c);
    free(f);
    free(u);
    free(r);
    free(uc);
}

static void test_failures(void)
{
    cx_csc A;
    cx_diag d;
    cx_schur *S = NULL;
    laplacian(&A, 6, 0.0, 1);
    int dup[3] = {1, 5, 1}, out[2] = {3, 36};
    CX_CHECK(cx_schur_create(&S, &A, dup, 3, NULL, &d) == CX_EINVAL);
    CX_CHECK(S == NULL && strstr(d.msg, "twice") != NULL);
    CX_CHECK(cx_schur_create(&S, &A, out, 2, NULL, &d) == CX_EINVAL);
    CX_CHECK(S == NULL);
    /* no c dofs: A_ii = A, singular -> refused, naming a column */
    cx_diag_clear(&d);
    CX_CHECK(cx_schur_create(&S, &A, NULL, 0, NULL, &d) == CX_ENUMERIC);
    CX_CHECK(S == NULL && strstr(d.msg, "column") != NULL);
    cx_schur_destroy(&S);   /* NULL-safe */
    cx_schur_destroy(NULL);

    /* out of memory at each of our allocations: CX_ENOMEM, nothing leaked */
    int c[4] = {0, 7, 20, 35};
    long live = cx_alloc_live();
    int st = CX_ENOMEM, k;
    for (k = 0; k < 40 && st != CX_OK; k++) {
        cx_alloc_fail_after(k);
        st = cx_schur_create(&S, &A, c, 4, NULL, &d);
        cx_alloc_fail_after(-1);
        if (st != CX_OK) {
            CX_CHECK(st == CX_ENOMEM && S == NULL);
            CX_CHECK(cx_alloc_live() == live);
        }
    }
    CX_CHECK(st == CX_OK && k > 5);
    cx_schur_destroy(&S);
    CX_CHECK(cx_alloc_live() == live);
    cx_csc_clear(&A);
}

int main(void)
{
    test_spd();
    test_singular();
    test_small();
    test_large();
    test_failures();
    return check_finish("linalg_schur");
}
