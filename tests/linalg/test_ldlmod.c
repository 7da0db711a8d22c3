/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cx_ldlmod: rows deleted (identity) and added back by CHOLMOD's Modify
 * give the same solutions as a fresh factorisation of the masked matrix,
 * and the counters count one factorisation plus one update per change. */
#include "linalg/linalg.h"
#include "laplacian.h"
#include "check.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A with the rows and columns i where zero[i] replaced by the identity */
static void masked(const cx_csc *A, const unsigned char *zero, cx_csc *M)
{
    cx_csc_copy(M, A);
    for (int j = 0; j < A->ncol; j++)
        for (int q = A->p[j]; q < A->p[j + 1]; q++) {
            int i = A->i[q];
            if (zero[i] || zero[j])
                M->x[q] = i == j;
        }
}

/* Random sequences of row deletes (cx_ldlmod_delete_row: the row of L
 * from the elimination tree) and adds, on a simplicial factor and on a
 * supernodal one converted (whose pattern holds the amalgamation's
 * explicit zeros), checked every few changes against a fresh
 * factorisation of the masked matrix: the solutions agree to 1e-12. A row
 * pattern that missed an entry of row k of L would leave it in the factor
 * and the solutions would differ at O(1). */
static unsigned lcg_next(unsigned *state)
{
    *state = *state * 1103515245u + 12345u;
    return *state >> 8;
}

static void test_delete_row_random(int super)
{
    cx_csc A = {0}, M = {0};
    cx_diag d;
    cx_counters cnt = {0};
    laplacian(&A, 20, 0.05, 0);   /* 400 unknowns */
    int n = A.ncol;
    unsigned char *zero = calloc(n, 1), *keep = calloc(n, 1);
    double *b = malloc(sizeof(double) * n), *x = malloc(sizeof(double) * n);
    double *xr = malloc(sizeof(double) * n), *y = malloc(sizeof(double) * n);
    unsigned seed = 12345u + (unsigned)super;
    for (int i = 0; i < n; i++)
        b[i] = 1.0 + (i % 11) - 0.3 * (i % 5), zero[i] = lcg_next(&seed) % 4 == 0;
    masked(&A, zero, &M);
    cx_ldlmod *F = NULL;
    CX_CHECK_OK(super ? cx_ldlmod_create_super(&F, &M, &cnt, &d) : cx_ldlmod_create(&F, &M, &cnt, &d));
    cx_csc_clear(&M);
    CX_CHECK(cx_ldlmod_factor_nnz(F) >= n);
    double worst = 0;
    int deletes = 0, adds = 0;
    for (int step = 1; step <= 400; step++) {
        int i = (int)(lcg_next(&seed) % (unsigned)n);
        for (int j = 0; j < n; j++)
            keep[j] = !zero[j];
        /* the cost of a row: at least the path from it to the root */
        CX_CHECK(cx_ldlmod_row_cost(F, i, &A, keep) >= 1);
        if (zero[i]) {
            zero[i] = 0;
            keep[i] = 1;
            CX_CHECK_OK(cx_ldlmod_add(F, i, &A, keep, 0.0, &d));
            adds++;
        } else {
            CX_CHECK_OK(cx_ldlmod_delete_row(F, i, &A, keep, &d));
            zero[i] = 1;
            deletes++;
        }
        if (step % 8)
            continue;
        for (int j = 0; j < n; j++)
            y[j] = zero[j] ? 0 : b[j];
        CX_CHECK_OK(cx_ldlmod_solve(F, y, x, &d));
        masked(&A, zero, &M);
        cx_ldlmod *G = NULL;
        CX_CHECK_OK(cx_ldlmod_create(&G, &M, NULL, &d));
        CX_CHECK_OK(cx_ldlmod_solve(G, y, xr, &d));
        cx_ldlmod_destroy(&G);
        cx_csc_clear(&M);
        double e = 0;
        for (int j = 0; j < n; j++)
            e = fmax(e, fabs(x[j] - xr[j]));
        worst = fmax(worst, e / cx_vec_norminf(n, xr));
    }
    fprintf(stderr, "ldlmod %s: %d deletes (etree rows), %d adds, worst difference from a fresh "
            "factor %.2e\n", super ? "supernodal converted" : "simplicial", deletes, adds, worst);
    CX_CHECK_LE(worst, 1e-12);
    CX_CHECK(deletes > 50 && adds > 50);
    CX_CHECK(cnt.factorizations == 1 && cnt.updates == deletes + adds);
    cx_ldlmod_destroy(&F);
    cx_csc_clear(&A);
    free(zero), free(keep), free(b), free(x), free(xr), free(y);
}

int main(void)
{
    test_delete_row_random(0);
    test_delete_row_random(1);

    cx_csc A = {0}, M = {0};
    cx_diag d;
    cx_counters cnt = {0};
    laplacian(&A, 12, 0.1, 0);   /* 144 unknowns, definite */
    int n = A.ncol;
    unsigned char *zero = calloc(n, 1), *keep = calloc(n, 1);
    double *b = malloc(sizeof(double) * n), *x = malloc(sizeof(double) * n), *y = malloc(sizeof(double) * n);
    for (int i = 0; i < n; i++)
        b[i] = 1.0 + (i % 7), zero[i] = i % 3 == 0;
    masked(&A, zero, &M);
    cx_ldlmod *F = NULL;
    CX_CHECK_OK(cx_ldlmod_create(&F, &M, &cnt, &d));
    cx_csc_clear(&M);
    /* delete some, add others back, in an order that is not monotone */
    int order[] = {5, 0, 9, 31, 3, 77, 143, 64, 100, 2};
    for (size_t k = 0; k < sizeof order / sizeof order[0]; k++) {
        int i = order[k];
        if (zero[i]) {
            zero[i] = 0;
            for (int j = 0; j < n; j++)
                keep[j] = !zero[j];
            CX_CHECK_OK(cx_ldlmod_add(F, i, &A, keep, 0.0, &d));
        } else {
            zero[i] = 1;
            CX_CHECK_OK(cx_ldlmod_delete(F, i, &d));
        }
        for (int j = 0; j < n; j++)
            y[j] = zero[j] ? 0 : b[j];
        CX_CHECK_OK(cx_ldlmod_solve(F, y, x, &d));
        masked(&A, zero, &M);
        CX_CHECK_LE(residual(&M, x, y), 1e-12);
        cx_csc_clear(&M);
    }
    CX_CHECK(cnt.factorizations == 1);
    CX_CHECK(cnt.updates == 10);
    CX_CHECK(cnt.solves == 10);
    /* a shift on the diagonal of an added row */
    zero[7] = 1;
    CX_CHECK_OK(cx_ldlmod_delete(F, 7, &d));
    zero[7] = 0;
    for (int j = 0; j < n; j++)
        keep[j] = !zero[j];
    CX_CHECK_OK(cx_ldlmod_add(F, 7, &A, keep, 5.0, &d));
    for (int j = 0; j < n; j++)
        y[j] = zero[j] ? 0 : b[j];
    CX_CHECK_OK(cx_ldlmod_solve(F, y, x, &d));
    masked(&A, zero, &M);
    for (int q = M.p[7]; q < M.p[8]; q++)
        if (M.i[q] == 7)
            M.x[q] += 5.0;
    CX_CHECK_LE(residual(&M, x, y), 1e-12);
    cx_csc_clear(&M);
    cx_ldlmod_destroy(&F);
    cx_csc_clear(&A);
    free(zero), free(keep), free(b), free(x), free(y);
    return check_finish("linalg_ldlmod");
}
