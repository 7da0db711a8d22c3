/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cx_ldlmod_create_masked / cx_ldlmod_refactor_masked: the factor of A
 * masked (rows and columns held at the identity, a shift on the kept
 * diagonal) from A itself, the masked matrix never formed, solves as the
 * factor of the masked matrix formed explicitly does (supernodal, whose
 * input is gathered through the permuted pattern, and simplicial), also
 * after a refactorisation with another mask and after row changes checked
 * by cx_ldlmod_check_updated; a mask that leaves the matrix indefinite is
 * reported singular. */
#include "linalg/linalg.h"
#include "laplacian.h"
#include "check.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static unsigned lcg_next(unsigned *state)
{
    *state = *state * 1103515245u + 12345u;
    return *state >> 8;
}

/* M = A with rows and columns where !keep[i] the identity's, shift added
 * to the kept diagonal */
static void masked(const cx_csc *A, const unsigned char *keep, double shift, cx_csc *M)
{
    CX_CHECK_OK(cx_csc_copy(M, A));
    for (int j = 0; j < A->ncol; j++)
        for (int q = A->p[j]; q < A->p[j + 1]; q++) {
            int i = A->i[q];
            M->x[q] = (!keep[i] || !keep[j]) ? (i == j) : A->x[q] + (i == j ? shift : 0);
        }
}

/* largest |x - y| over n entries, relative to the largest |y| */
static double rel_diff(int n, const double *x, const double *y)
{
    double e = 0, s = 0;
    for (int i = 0; i < n; i++)
        e = fmax(e, fabs(x[i] - y[i])), s = fmax(s, fabs(y[i]));
    return s > 0 ? e / s : e;
}

/* F (masked by ldlmod) against G refactorised from the masked matrix
 * formed: their solutions of b agree to tol. */
static double against_formed(cx_ldlmod *F, cx_ldlmod *G, const cx_csc *A, const unsigned char *keep, double shift,
                             const double *b, double *x, double *y)
{
    cx_csc M = {0};
    cx_diag d;
    masked(A, keep, shift, &M);
    CX_CHECK_OK(cx_ldlmod_refactor(G, &M, &d));
    CX_CHECK_OK(cx_ldlmod_solve(F, b, x, &d));
    CX_CHECK_OK(cx_ldlmod_solve(G, b, y, &d));
    cx_csc_clear(&M);
    return rel_diff(A->ncol, x, y);
}

static void test_masked(int super)
{
    cx_csc A = {0}, M = {0};
    cx_diag d;
    laplacian(&A, 18, 0.05, 0);   /* 324 unknowns */
    int n = A.ncol;
    double shift = 0.25;
    unsigned char *keep = malloc(n);
    double *b = malloc(sizeof(double) * n), *x = malloc(sizeof(double) * n), *y = malloc(sizeof(double) * n);
    unsigned seed = 777u + (unsigned)super;
    for (int i = 0; i < n; i++)
        b[i] = 1.0 + (i % 7) - 0.4 * (i % 3), keep[i] = lcg_next(&seed) % 3 != 0;
    cx_ldlmod *F = NULL, *G = NULL, *H = NULL;
    if (super) {
        CX_CHECK_OK(cx_ldlmod_create_masked(&F, &A, keep, shift, NULL, NULL, &d));
    } else {
        /* a simplicial factor to take the analysis from (like) */
        CX_CHECK_OK(cx_ldlmod_create(&H, &A, NULL, &d));
        CX_CHECK_OK(cx_ldlmod_create_masked(&F, &A, keep, shift, H, NULL, &d));
    }
    masked(&A, keep, shift, &M);
    CX_CHECK_OK(super ? cx_ldlmod_create_super(&G, &M, NULL, &d) : cx_ldlmod_create(&G, &M, NULL, &d));
    CX_CHECK_OK(cx_ldlmod_solve(F, b, x, &d));
    CX_CHECK_OK(cx_ldlmod_solve(G, b, y, &d));
    CX_CHECK(rel_diff(n, x, y) <= 1e-13);
    /* the held rows solve to the right-hand side (identity rows) */
    int held = -1;
    for (int i = 0; i < n && held < 0; i++)
        if (!keep[i])
            held = i;
    CX_CHECK(held >= 0);
    if (held >= 0)
        CX_CHECK(fabs(x[held] - b[held]) <= 1e-14 * fabs(b[held]));
    /* another mask, refactorised from the kept analysis */
    for (int i = 0; i < n; i++)
        keep[i] = lcg_next(&seed) % 4 != 0;
    CX_CHECK_OK(cx_ldlmod_refactor_masked(F, &A, keep, shift, &d));
    CX_CHECK(against_formed(F, G, &A, keep, shift, b, x, y) <= 1e-13);
    /* row changes on the masked factor, then the check of their pivots */
    for (int step = 0; step < 30; step++) {
        int i = (int)(lcg_next(&seed) % (unsigned)n);
        if (keep[i]) {
            CX_CHECK_OK(cx_ldlmod_delete_row(F, i, &A, keep, &d));
            keep[i] = 0;
        } else {
            keep[i] = 1;
            CX_CHECK_OK(cx_ldlmod_add(F, i, &A, keep, shift, &d));
        }
    }
    CX_CHECK_OK(cx_ldlmod_check_updated(F, 8.25, &d));
    CX_CHECK(against_formed(F, G, &A, keep, shift, b, x, y) <= 1e-11);
    /* a shift that leaves the kept block indefinite is singular */
    CX_CHECK(cx_ldlmod_refactor_masked(F, &A, keep, -100.0, &d) == CX_ENUMERIC);
    cx_ldlmod_destroy(&F);
    cx_ldlmod_destroy(&G);
    cx_ldlmod_destroy(&H);
    cx_csc_clear(&A);
    cx_csc_clear(&M);
    free(keep), free(b), free(x), free(y);
}

int main(void)
{
    test_masked(1);
    test_masked(0);
    return check_finish("linalg_ldlmod_masked");
}
