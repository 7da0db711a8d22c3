/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linalg/sparse.c and vec.c: triplet to CSC (duplicates summed, rows
 * sorted, explicit zeros kept), copy, transpose, products, entry lookup,
 * asymmetry, the vector kernels, and clean failure on allocation. */
#include "linalg/linalg.h"
#include "check.h"

#include <math.h>
#include <string.h>

/* The 3 x 3 matrix
 *     [ 2  3  0 ]
 *     [ 0 -1  0 ]
 *     [ 0  1.5 4 ]
 * added out of order, with (2,1) as 1 + 0.5 and an explicit zero at (1,0). */
static void build(cx_triplet *t)
{
    CX_CHECK_OK(cx_triplet_init(t, 3, 3, 1));   /* grows */
    cx_triplet_add(t, 2, 1, 1.0);
    cx_triplet_add(t, 0, 0, 2.0);
    cx_triplet_add(t, 2, 2, 4.0);
    cx_triplet_add(t, 2, 1, 0.5);
    cx_triplet_add(t, 1, 1, -1.0);
    cx_triplet_add(t, 1, 0, 0.0);
    cx_triplet_add(t, 0, 1, 3.0);
    CX_CHECK(t->nnz == 7 && t->cap >= 7);
}

static void test_from_triplet(void)
{
    cx_triplet t;
    cx_csc A;
    build(&t);
    CX_CHECK_OK(cx_csc_from_triplet(&A, &t));
    CX_CHECK(A.nrow == 3 && A.ncol == 3 && cx_csc_nnz(&A) == 6);
    int p[4] = {0, 2, 5, 6}, i[6] = {0, 1, 0, 1, 2, 2};
    double x[6] = {2, 0, 3, -1, 1.5, 4};
    for (int k = 0; k < 4; k++)
        CX_CHECK(A.p[k] == p[k]);
    for (int k = 0; k < 6; k++) {
        CX_CHECK(A.i[k] == i[k]);
        CX_CHECK_NEAR(A.x[k], x[k], 0, 0);   /* exact: one addition at most */
    }
    CX_CHECK_NEAR(cx_csc_get(&A, 2, 1), 1.5, 0, 0);
    CX_CHECK_NEAR(cx_csc_get(&A, 2, 0), 0, 0, 0);   /* not stored */
    CX_CHECK_NEAR(cx_csc_get(&A, 1, 0), 0, 0, 0);   /* stored zero */

    cx_csc B;
    CX_CHECK_OK(cx_csc_copy(&B, &A));
    CX_CHECK(cx_csc_nnz(&B) == 6 && memcmp(B.i, A.i, sizeof(int) * 6) == 0);
    cx_csc_clear(&B);
    CX_CHECK(B.p == NULL && B.ncol == 0 && cx_csc_nnz(&B) == 0);

    /* transpose: rows of A become columns, still sorted */
    cx_csc At;
    CX_CHECK_OK(cx_csc_transpose(&At, &A));
    CX_CHECK(At.p[0] == 0 && At.p[1] == 2 && At.p[2] == 4 && At.p[3] == 6);
    int it[6] = {0, 1, 0, 1, 1, 2};
    for (int k = 0; k < 6; k++)
        CX_CHECK(At.i[k] == it[k]);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            CX_CHECK_NEAR(cx_csc_get(&At, r, c), cx_csc_get(&A, c, r), 0, 0);

    /* y = 2 A x + 0.5 y, x = (1, 2, -1): A x = (8, -2, -1) */
    double xv[3] = {1, 2, -1}, y[3] = {2, 4, 6};
    cx_csc_gemv(&A, 2.0, xv, 0.5, y);
    CX_CHECK_NEAR(y[0], 17, 1e-15, 0);
    CX_CHECK_NEAR(y[1], -2, 1e-15, 0);
    CX_CHECK_NEAR(y[2], 1, 1e-15, 0);
    double ynan[3] = {NAN, NAN, NAN};   /* beta = 0 ignores the old y */
    cx_csc_gemv(&A, 1.0, xv, 0.0, ynan);
    CX_CHECK_NEAR(ynan[0], 8, 1e-15, 0);
    CX_CHECK_NEAR(ynan[1], -2, 1e-15, 0);
    CX_CHECK_NEAR(ynan[2], -1, 1e-15, 0);
    /* A' x = (2, 3 - 2 - 1.5, -4) = (2, -0.5, -4); y = -A' x + 1 y */
    double z[3] = {1, 1, 1};
    cx_csc_gemv_t(&A, -1.0, xv, 1.0, z);
    CX_CHECK_NEAR(z[0], -1, 1e-15, 0);
    CX_CHECK_NEAR(z[1], 1.5, 1e-15, 0);
    CX_CHECK_NEAR(z[2], 5, 1e-15, 0);
    double znan[3] = {NAN, NAN, NAN};
    cx_csc_gemv_t(&A, 1.0, xv, 0.0, znan);
    CX_CHECK_NEAR(znan[1], -0.5, 1e-15, 0);

    /* asymmetry: max over stored entries |A(i,j) - A(j,i)| = |3 - 0| */
    CX_CHECK_NEAR(cx_csc_asymmetry(&A), 3, 0, 0);
    cx_csc_clear(&A);
    cx_csc_clear(&At);
    cx_triplet_clear(&t);

    /* a symmetric one: 0 */
    CX_CHECK_OK(cx_triplet_init(&t, 2, 2, 4));
    cx_triplet_add(&t, 0, 1, -1);
    cx_triplet_add(&t, 1, 0, -1);
    cx_triplet_add(&t, 0, 0, 2);
    CX_CHECK_OK(cx_csc_from_triplet(&A, &t));
    CX_CHECK_NEAR(cx_csc_asymmetry(&A), 0, 0, 0);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);

    /* rectangular 2 x 3 and an empty matrix */
    CX_CHECK_OK(cx_triplet_init(&t, 2, 3, 0));
    cx_triplet_add(&t, 1, 2, 5);
    CX_CHECK_OK(cx_csc_from_triplet(&A, &t));
    CX_CHECK(A.p[0] == 0 && A.p[2] == 0 && A.p[3] == 1 && A.i[0] == 1);
    CX_CHECK_NEAR(cx_csc_asymmetry(&A), 5, 0, 0);
    double x3[3] = {1, 1, 2}, y2[2];
    cx_csc_gemv(&A, 1.0, x3, 0.0, y2);
    CX_CHECK_NEAR(y2[0], 0, 0, 0);
    CX_CHECK_NEAR(y2[1], 10, 0, 0);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);
    CX_CHECK_OK(cx_triplet_init(&t, 4, 4, 0));
    CX_CHECK_OK(cx_csc_from_triplet(&A, &t));
    CX_CHECK(A.ncol == 4 && cx_csc_nnz(&A) == 0 && A.p[4] == 0);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);
}

/* Every allocation of the conversion may fail: CX_ENOMEM, A left empty,
 * nothing leaked. */
static void test_alloc_failure(void)
{
    cx_triplet t;
    cx_csc A;
    build(&t);
    long live = cx_alloc_live();
    int st = CX_ENOMEM, k;
    for (k = 0; k < 20 && st != CX_OK; k++) {
        cx_alloc_fail_after(k);
        st = cx_csc_from_triplet(&A, &t);
        cx_alloc_fail_after(-1);
        if (st != CX_OK) {
            CX_CHECK(st == CX_ENOMEM);
            CX_CHECK(A.p == NULL && A.i == NULL && A.x == NULL);
            CX_CHECK(cx_alloc_live() == live);
        }
    }
    CX_CHECK(st == CX_OK && k > 1);
    cx_csc_clear(&A);
    cx_triplet_clear(&t);
    CX_CHECK(cx_alloc_live() == live - 3);   /* the triplet's three arrays */
}

static void test_vec(void)
{
    double x[3] = {3, -4, 0}, y[3] = {1, 2, 3};
    CX_CHECK_NEAR(cx_vec_dot(3, x, y), -5, 0, 0);
    CX_CHECK_NEAR(cx_vec_norm2(3, x), 5, 1e-15, 0);
    CX_CHECK_NEAR(cx_vec_norminf(3, x), 4, 0, 0);
    cx_vec_axpy(3, 2.0, x, y);
    CX_CHECK_NEAR(y[0], 7, 0, 0);
    CX_CHECK_NEAR(y[1], -6, 0, 0);
    CX_CHECK_NEAR(y[2], 3, 0, 0);
    CX_CHECK(cx_vec_finite(3, y));
    y[1] = INFINITY;
    CX_CHECK(!cx_vec_finite(3, y));
    y[1] = NAN;
    CX_CHECK(!cx_vec_finite(3, y));
    CX_CHECK(cx_vec_finite(0, y));
}

int main(void)
{
    test_from_triplet();
    test_alloc_failure();
    test_vec();
    return check_finish("linalg_sparse");
}
