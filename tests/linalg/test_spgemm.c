/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linalg/spgemm.c: the congruence T' K T in one pass against the two
 * products it replaces (the same pattern, sorted rows, and values to
 * roundoff), symmetry for a symmetric K, the size check, and clean
 * failure on allocation. */
#include "base/alloc.h"
#include "linalg/linalg.h"
#include "check.h"

#include <math.h>
#include <string.h>

/* A deterministic pseudo-random number in [0, 1) (LCG). */
static double rnd(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return (double)((*s >> 8) & 0xffffff) / 16777216.0;
}

/* K: n x n symmetric, a band of a 1D chain of 2-dof nodes with a few far
 * couplings; T: n x n, the identity with a few rows replaced by a pivot
 * and one other entry (the shape of the LCP's change of variables). */
static void build(int n, cx_csc *K, cx_csc *T, unsigned seed)
{
    cx_triplet tk, tt;
    CX_CHECK_OK(cx_triplet_init(&tk, n, n, 1));
    CX_CHECK_OK(cx_triplet_init(&tt, n, n, 1));
    for (int j = 0; j < n; j++) {
        cx_triplet_add(&tk, j, j, 4 + rnd(&seed));
        for (int i = j + 1; i < n && i <= j + 3; i++) {
            double v = rnd(&seed) - 0.5;
            cx_triplet_add(&tk, i, j, v);
            cx_triplet_add(&tk, j, i, v);
        }
        if (j % 7 == 0 && j + 11 < n) {
            double v = rnd(&seed) - 0.5;
            cx_triplet_add(&tk, j + 11, j, v);
            cx_triplet_add(&tk, j, j + 11, v);
        }
    }
    for (int j = 0; j < n; j++) {
        if (j % 5 == 2 && j + 4 < n) {
            cx_triplet_add(&tt, j, j, -1.0 / (1 + rnd(&seed)));
            cx_triplet_add(&tt, j, j + 4, rnd(&seed) - 0.5);
        } else {
            cx_triplet_add(&tt, j, j, 1.0);
        }
    }
    CX_CHECK_OK(cx_csc_from_triplet(K, &tk));
    CX_CHECK_OK(cx_csc_from_triplet(T, &tt));
    cx_triplet_clear(&tk);
    cx_triplet_clear(&tt);
}

static void test_against_products(void)
{
    int n = 60;
    cx_csc K, T, Tt, KT, ref, C;
    build(n, &K, &T, 7u);
    CX_CHECK_OK(cx_csc_transpose(&Tt, &T));
    CX_CHECK_OK(cx_csc_multiply(&KT, &K, &T));
    CX_CHECK_OK(cx_csc_multiply(&ref, &Tt, &KT));
    CX_CHECK_OK(cx_csc_congruence(&C, &K, &T));
    CX_CHECK(C.nrow == n && C.ncol == n);
    CX_CHECK(cx_csc_nnz(&C) == cx_csc_nnz(&ref));
    int same_pattern = 1, sorted = 1;
    double err = 0, scale = 0;
    for (int j = 0; j <= n; j++)
        same_pattern &= C.p[j] == ref.p[j];
    for (int j = 0; j < n && same_pattern; j++)
        for (int q = C.p[j]; q < C.p[j + 1]; q++) {
            same_pattern &= C.i[q] == ref.i[q];
            if (q > C.p[j])
                sorted &= C.i[q] > C.i[q - 1];
            err = fmax(err, fabs(C.x[q] - ref.x[q]));
            scale = fmax(scale, fabs(ref.x[q]));
        }
    CX_CHECK(same_pattern);
    CX_CHECK(sorted);
    CX_CHECK(err <= 1e-14 * scale);
    CX_CHECK(cx_csc_nnz(&C) > (size_t)(3 * n));   /* not the identity: T couples */
    /* a congruence of a symmetric K is symmetric to roundoff (the two
     * triangles' sums run in different orders) */
    CX_CHECK(cx_csc_asymmetry(&C) <= 1e-14 * scale);
    cx_csc_clear(&K), cx_csc_clear(&T), cx_csc_clear(&Tt), cx_csc_clear(&KT);
    cx_csc_clear(&ref), cx_csc_clear(&C);
}

static void test_sizes(void)
{
    cx_csc K, T, T2, C;
    build(20, &K, &T, 3u);
    cx_csc K2;
    build(25, &K2, &T2, 3u);
    CX_CHECK(cx_csc_congruence(&C, &K, &T2) == CX_EINVAL);
    CX_CHECK(C.p == NULL && C.i == NULL && C.x == NULL);
    cx_csc_clear(&K), cx_csc_clear(&T), cx_csc_clear(&K2), cx_csc_clear(&T2);
}

static void test_alloc_failure(void)
{
    cx_csc K, T, C;
    build(30, &K, &T, 11u);
    long live = cx_alloc_live();
    int failed = 0, ok = 0;
    for (long k = 0; k < 40 && !ok; k++) {
        cx_alloc_fail_after(k);
        int st = cx_csc_congruence(&C, &K, &T);
        cx_alloc_fail_after(-1);
        if (st != CX_OK) {
            failed++;
            CX_CHECK(st == CX_ENOMEM);
            CX_CHECK(C.p == NULL && C.i == NULL && C.x == NULL);
            CX_CHECK(cx_alloc_live() == live);
        } else {
            ok = 1;
            cx_csc_clear(&C);
        }
    }
    CX_CHECK(failed > 0 && ok);
    cx_csc_clear(&K), cx_csc_clear(&T);
}

int main(void)
{
    test_against_products();
    test_sizes();
    test_alloc_failure();
    return check_finish("linalg_spgemm");
}
