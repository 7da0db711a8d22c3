/* linalg/: CSC assembly, CHOLMOD and UMFPACK factorisations, the Schur
 * complement onto a dof subset (against a dense reference, also for a
 * singular matrix), dense kernels and PCG. */
#include "linalg/linalg.h"
#include "check.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* 2D 5-point Laplacian on an m x m grid plus shift on the diagonal
 * (shift 0 with Neumann rows: zero row sums, singular). */
static void laplacian(cx_csc *A, int m, double shift, int neumann)
{
    cx_triplet t;
    int n = m * m;
    cx_triplet_init(&t, n, n, (size_t)5 * n);
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

static double residual(const cx_csc *A, const double *x, const double *b)
{
    int n = A->nrow;
    double *r = malloc(sizeof(double) * (size_t)n);
    cx_csc_gemv(A, 1.0, x, 0.0, r);
    cx_vec_axpy(n, -1.0, b, r);
    double v = cx_vec_norm2(n, r) / cx_vec_norm2(n, b);
    free(r);
    return v;
}

static void test_csc(void)
{
    cx_triplet t;
    cx_csc A, At;
    CX_CHECK_OK(cx_triplet_init(&t, 3, 2, 1));
    cx_triplet_add(&t, 2, 1, 1.0);
    cx_triplet_add(&t, 0, 0, 2.0);
    cx_triplet_add(&t, 2, 1, 0.5);   /* duplicate: summed */
    cx_triplet_add(&t, 1, 1, -1.0);
    cx_triplet_add(&t, 0, 1, 3.0);
    CX_CHECK_OK(cx_csc_from_triplet(&A, &t));
    CX_CHECK(cx_csc_nnz(&A) == 4);
    CX_CHECK(A.p[0] == 0 && A.p[1] == 1 && A.p[2] == 4);
    CX_CHECK(A.i[1] == 0 && A.i[2] == 1 && A.i[3] == 2);   /* sorted rows */
    CX_CHECK_NEAR(cx_csc_get(&A, 2, 1), 1.5, 0, 0);
    double x[2] = {1, 2}, y[3], z[2];
    cx_csc_gemv(&A, 1.0, x, 0.0, y);
    CX_CHECK_NEAR(y[0], 8, 0, 0);
    CX_CHECK_NEAR(y[1], -2, 0, 0);
    CX_CHECK_NEAR(y[2], 3, 0, 0);
    double w[3] = {1, 1, 1};
    cx_csc_gemv_t(&A, 2.0, w, 0.0, z);
    CX_CHECK_NEAR(z[0], 4, 0, 0);
    CX_CHECK_NEAR(z[1], 7, 0, 0);
    CX_CHECK_OK(cx_csc_transpose(&At, &A));
    CX_CHECK(At.nrow == 2 && At.ncol == 3);
    CX_CHECK_NEAR(cx_csc_get(&At, 1, 2), 1.5, 0, 0);
    cx_csc_clear(&A);
    cx_csc_clear(&At);
    cx_triplet_clear(&t);
}

static void test_cholesky(void)
{
    cx_csc A;
    cx_counters cnt = {0};
    cx_diag d;
    laplacian(&A, 30, 0.0, 0);
    int n = A.nrow;
    CX_CHECK_NEAR(cx_csc_asymmetry(&A), 0, 0, 0);
    double *b = malloc(sizeof(double) * (size_t)n), *x = malloc(sizeof(double) * (size_t)n);
    for (int i = 0; i < n; i++)
        b[i] = sin(i);
    cx_fact *F = NULL;
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_CHOLESKY, &cnt, &d));
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    CX_CHECK_OK(cx_fact_factorize(F, &A, &d));
    CX_CHECK_OK(cx_fact_solve(F, b, x, &d));
    CX_CHECK_LE(residual(&A, x, b), 1e-12);
    for (size_t k = 0; k < cx_csc_nnz(&A); k++)   /* same pattern, new values */
        A.x[k] *= 3;
    CX_CHECK_OK(cx_fact_factorize(F, &A, &d));
    CX_CHECK_OK(cx_fact_solve(F, b, x, &d));
    CX_CHECK_LE(residual(&A, x, b), 1e-12);
    CX_CHECK(cnt.factorizations == 2 && cnt.solves == 2);
    CX_CHECK(cx_fact_nnz(F) > cx_csc_nnz(&A) / 2);
    /* indefinite: a clear error naming the column, never NaN */
    for (size_t k = 0; k < cx_csc_nnz(&A); k++)
        A.x[k] = -A.x[k];
    CX_CHECK(cx_fact_factorize(F, &A, &d) == CX_ENUMERIC);
    CX_CHECK(strstr(d.msg, "column") != NULL);
    cx_fact_destroy(&F);
    CX_CHECK(F == NULL);
    cx_fact_destroy(&F);   /* NULL-safe */
    /* singular (Neumann): refused too */
    cx_csc_clear(&A);
    laplacian(&A, 10, 0.0, 1);
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_CHOLESKY, NULL, &d));
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    CX_CHECK(cx_fact_factorize(F, &A, &d) == CX_ENUMERIC);
    cx_fact_destroy(&F);
    cx_csc_clear(&A);
    free(b);
    free(x);
}

static void test_lu(void)
{
    cx_triplet t;
    cx_csc A;
    cx_diag d;
    cx_counters cnt = {0};
    cx_triplet_init(&t, 3, 3, 8);
    double v[3][3] = {{4, 1, 0}, {2, 5, 1}, {0, 3, 6}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (v[i][j] != 0)
                cx_triplet_add(&t, i, j, v[i][j]);
    cx_csc_from_triplet(&A, &t);
    double b[3] = {1, 2, 3}, x[3];
    cx_fact *F = NULL;
    CX_CHECK_OK(cx_fact_create(&F, CX_FACT_LU, &cnt, &d));
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    CX_CHECK_OK(cx_fact_factorize(F, &A, &d));
    CX_CHECK_OK(cx_fact_solve(F, b, x, &d));
    CX_CHECK_LE(residual(&A, x, b), 1e-14);
    /* singular: the third row a copy of the first */
    cx_csc_clear(&A);
    cx_triplet_clear(&t);
    cx_triplet_init(&t, 3, 3, 8);
    double s[3][3] = {{4, 1, 0}, {2, 5, 1}, {4, 1, 0}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            cx_triplet_add(&t, i, j, s[i][j]);
    cx_csc_from_triplet(&A, &t);
    CX_CHECK_OK(cx_fact_analyze(F, &A, &d));
    CX_CHECK(cx_fact_factorize(F, &A, &d) == CX_ENUMERIC);
    CX_CHECK(strstr(d.msg, "singular") != NULL);
    cx_fact_destroy(&F);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);
}

/* Dense reference S = A_cc - A_ci A_ii^-1 A_ic through LAPACK. */
static void dense_schur(const cx_csc *A, const int *c, int nc, double *S)
{
    int n = A->nrow, ni = n - nc;
    int *isc = calloc((size_t)n, sizeof(int)), *ii = malloc(sizeof(int) * (size_t)ni);
    for (int k = 0; k < nc; k++)
        isc[c[k]] = 1;
    for (int j = 0, k = 0; j < n; j++)
        if (!isc[j])
            ii[k++] = j;
    double *Aii = malloc(sizeof(double) * (size_t)ni * ni), *Aic = malloc(sizeof(double) * (size_t)ni * nc);
    for (int a = 0; a < ni; a++) {
        for (int b = 0; b < ni; b++)
            Aii[a + (size_t)b * ni] = cx_csc_get(A, ii[a], ii[b]);
        for (int b = 0; b < nc; b++)
            Aic[a + (size_t)b * ni] = cx_csc_get(A, ii[a], c[b]);
    }
    CX_CHECK_OK(cx_dense_cholesky(ni, Aii, NULL));
    double *X = malloc(sizeof(double) * (size_t)ni * nc);
    memcpy(X, Aic, sizeof(double) * (size_t)ni * nc);
    cx_dense_cholesky_solve(ni, Aii, X, nc);
    for (int a = 0; a < nc; a++)
        for (int b = 0; b < nc; b++) {
            double s = cx_csc_get(A, c[a], c[b]);
            for (int k = 0; k < ni; k++)
                s -= Aic[k + (size_t)a * ni] * X[k + (size_t)b * ni];
            S[a + (size_t)b * nc] = s;
        }
    free(isc);
    free(ii);
    free(Aii);
    free(Aic);
    free(X);
}

static void test_schur(int neumann)
{
    cx_csc A;
    cx_diag d;
    cx_counters cnt = {0};
    int m = 14, n = m * m, nc = 15;
    laplacian(&A, m, neumann ? 0.0 : 0.1, neumann);
    int c[15];
    for (int k = 0; k < nc; k++)
        c[k] = (37 * k + 11) % n;   /* scattered, not the last ones */
    cx_schur *S = NULL;
    CX_CHECK_OK(cx_schur_create(&S, &A, c, nc, &cnt, &d));
    CX_CHECK(cnt.factorizations == 1 && cx_schur_size(S) == nc);
    double ref[15 * 15];
    dense_schur(&A, c, nc, ref);
    const double *Sm = cx_schur_matrix(S);
    double smax = 0, err = 0;
    for (int k = 0; k < nc * nc; k++) {
        smax = fmax(smax, fabs(ref[k]));
        err = fmax(err, fabs(Sm[k] - ref[k]));
    }
    CX_CHECK_LE(err, 1e-10 * smax);
    if (neumann) {
        /* S inherits the constant null vector */
        for (int a = 0; a < nc; a++) {
            double s = 0;
            for (int b = 0; b < nc; b++)
                s += Sm[a + (size_t)b * nc];
            CX_CHECK_NEAR(s, 0, 0, 1e-10 * smax);
        }
    }
    /* condense and expand: A u = f on the i rows, u_c as given */
    double *f = malloc(sizeof(double) * (size_t)n), *u = malloc(sizeof(double) * (size_t)n);
    double *r = malloc(sizeof(double) * (size_t)n), fc[15], uc[15];
    for (int i = 0; i < n; i++)
        f[i] = cos(0.3 * i);
    CX_CHECK_OK(cx_schur_condense(S, f, fc));
    for (int k = 0; k < nc; k++)
        uc[k] = 0.01 * k - 0.05;
    CX_CHECK_OK(cx_schur_expand(S, f, uc, u));
    CX_CHECK(cnt.solves == 2);
    cx_csc_gemv(&A, 1.0, u, 0.0, r);
    int *isc = calloc((size_t)n, sizeof(int));
    for (int k = 0; k < nc; k++) {
        isc[c[k]] = 1;
        CX_CHECK_NEAR(u[c[k]], uc[k], 0, 0);
    }
    double rmax = 0;
    for (int i = 0; i < n; i++)
        if (!isc[i])
            rmax = fmax(rmax, fabs(r[i] - f[i]));
    CX_CHECK_LE(rmax, 1e-11);
    /* on the c rows: (A u)_c = S u_c + (f_c - fc) */
    for (int a = 0; a < nc; a++) {
        double s = f[c[a]] - fc[a];
        for (int b = 0; b < nc; b++)
            s += Sm[a + (size_t)b * nc] * uc[b];
        CX_CHECK_NEAR(r[c[a]], s, 0, 1e-10 * (1 + fabs(s)));
    }
    free(isc);
    free(f);
    free(u);
    free(r);
    cx_schur_destroy(&S);
    cx_csc_clear(&A);
}

static void test_schur_large(void)
{
    cx_csc A;
    cx_diag d;
    int m = 300, n = m * m, nc = 300;
    laplacian(&A, m, 0.0, 1);   /* singular; held by the edge dofs */
    int *c = malloc(sizeof(int) * (size_t)nc);
    for (int k = 0; k < nc; k++)
        c[k] = k;   /* the first grid row */
    cx_schur *S = NULL;
    CX_CHECK_OK(cx_schur_create(&S, &A, c, nc, NULL, &d));
    double *f = calloc((size_t)n, sizeof(double)), *u = malloc(sizeof(double) * (size_t)n);
    double *r = malloc(sizeof(double) * (size_t)n), *uc = calloc((size_t)nc, sizeof(double));
    for (int i = nc; i < n; i++)
        f[i] = 1.0 / n;
    CX_CHECK_OK(cx_schur_expand(S, f, uc, u));
    cx_csc_gemv(&A, 1.0, u, 0.0, r);
    double rmax = 0;
    for (int i = nc; i < n; i++)
        rmax = fmax(rmax, fabs(r[i] - f[i]));
    CX_CHECK_LE(rmax, 1e-12);
    cx_schur_destroy(&S);
    cx_csc_clear(&A);
    free(c);
    free(f);
    free(u);
    free(r);
    free(uc);
}

static void test_dense(void)
{
    /* indefinite symmetric: [[0,1,0],[1,0,2],[0,2,1]] x = [1,2,3] -> x = (0,1,1)... by hand:
     * x2 = 1 from row 1; row 2: x1 + 2 x3 = 2; row 3: 2 + x3 = 3 -> x3 = 1, x1 = 0 */
    double A[9] = {0, 1, 0, 1, 0, 2, 0, 2, 1}, b[3] = {1, 2, 3}, work[192];
    int ipiv[3];
    CX_CHECK_OK(cx_dense_sym_solve(3, A, b, ipiv, work, 192, NULL));
    CX_CHECK_NEAR(b[0], 0, 0, 1e-15);
    CX_CHECK_NEAR(b[1], 1, 1e-15, 0);
    CX_CHECK_NEAR(b[2], 1, 1e-15, 0);
    double Z[4] = {1, 2, 2, 4}, z[2] = {1, 1};
    CX_CHECK(cx_dense_sym_solve(2, Z, z, ipiv, work, 128, NULL) == CX_ENUMERIC);
    double P[4] = {4, 2, 2, 3}, p[2] = {2, 1};
    CX_CHECK_OK(cx_dense_cholesky(2, P, NULL));
    cx_dense_cholesky_solve(2, P, p, 1);   /* [4 2; 2 3] x = [2 1] -> x = (0.5, 0) */
    CX_CHECK_NEAR(p[0], 0.5, 1e-15, 0);
    CX_CHECK_NEAR(p[1], 0, 0, 1e-15);
    double N[4] = {1, 2, 2, 1};
    CX_CHECK(cx_dense_cholesky(2, N, NULL) == CX_ENUMERIC);
    double G[4] = {0, 1, 1, 0}, g[2] = {3, 4};
    CX_CHECK_OK(cx_dense_lu_solve(2, G, g, ipiv, NULL));
    CX_CHECK_NEAR(g[0], 4, 1e-15, 0);
    CX_CHECK_NEAR(g[1], 3, 1e-15, 0);
}

static void apply_csc(void *ctx, const double *x, double *y) { cx_csc_gemv(ctx, 1.0, x, 0.0, y); }

static void test_pcg(void)
{
    cx_csc A;
    cx_diag d;
    laplacian(&A, 20, 0.0, 0);
    int n = A.nrow, it = 0;
    double *b = malloc(sizeof(double) * (size_t)n), *x = calloc((size_t)n, sizeof(double));
    double *w = malloc(sizeof(double) * 4 * (size_t)n), *inv = malloc(sizeof(double) * (size_t)n);
    for (int i = 0; i < n; i++) {
        b[i] = 1;
        inv[i] = 1 / cx_csc_get(&A, i, i);
    }
    CX_CHECK_OK(cx_pcg(n, apply_csc, &A, inv, b, x, 1e-10, 1000, &it, w, &d));
    CX_CHECK_LE(residual(&A, x, b), 1e-10);
    CX_CHECK(it > 5 && it < n);
    memset(x, 0, sizeof(double) * (size_t)n);
    CX_CHECK(cx_pcg(n, apply_csc, &A, NULL, b, x, 1e-10, 3, &it, w, &d) == CX_ENUMERIC);
    free(b);
    free(x);
    free(w);
    free(inv);
    cx_csc_clear(&A);
}

int main(void)
{
    test_csc();
    test_cholesky();
    test_lu();
    test_schur(0);
    test_schur(1);
    test_schur_large();
    test_dense();
    test_pcg();
    return check_finish("linalg");
}
