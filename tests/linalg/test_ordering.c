/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linalg/schur.c's orderings: nested dissection (METIS) on the interior
 * with the c dofs last, and AMD with the c dofs moved last (2 dofs per
 * node), give the same Schur complement, condensed load and
 * expansion as CAMD's constrained ordering, to 1e-12 relative, on a 3D
 * grid (SPD and singular); on that grid it predicts less fill; the
 * automatic choice reports both analyses and takes the cheaper one, and
 * does not run METIS on a small 2D problem whose cost it could not win
 * back. */
#include "linalg/linalg.h"
#include "check.h"
#include "laplacian.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* 7-point Laplacian on an m x m x m grid (dof (i*m + j)*m + k); neumann as
 * in laplacian(): rows sum to shift, so shift 0 is singular. */
static void laplacian3(cx_csc *A, int m, double shift, int neumann)
{
    cx_triplet t;
    int n = m * m * m;
    cx_triplet_init(&t, n, n, (size_t)7 * (size_t)n);
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++)
            for (int k = 0; k < m; k++) {
                int r = (i * m + j) * m + k, deg = 0;
                int nb[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k},
                                {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
                for (int q = 0; q < 6; q++) {
                    int a = nb[q][0], b = nb[q][1], c = nb[q][2];
                    if (a < 0 || b < 0 || c < 0 || a >= m || b >= m || c >= m)
                        continue;
                    cx_triplet_add(&t, r, (a * m + b) * m + c, -1);
                    deg++;
                }
                cx_triplet_add(&t, r, r, (neumann ? deg : 6) + shift);
            }
    CX_CHECK_OK(cx_csc_from_triplet(A, &t));
    cx_triplet_clear(&t);
}

static double max_diff(size_t n, const double *x, const double *y)
{
    double e = 0;
    for (size_t i = 0; i < n; i++)
        e = fmax(e, fabs(x[i] - y[i]));
    return e;
}

static double max_abs(size_t n, const double *x)
{
    double e = 0;
    for (size_t i = 0; i < n; i++)
        e = fmax(e, fabs(x[i]));
    return e;
}

/* Two reductions of one matrix onto the same nc dofs c condense the load
 * f and expand (f, uc) to the same vectors, to 1e-12 relative, and both
 * expansions hold u_c exactly as given. */
static void check_same_reduction(cx_schur *Sa, cx_schur *Sb, int n, int nc, const int *c, const double *f,
                                 const double *uc)
{
    double *fc1 = malloc(sizeof(double) * (size_t)nc), *fc2 = malloc(sizeof(double) * (size_t)nc);
    double *u1 = malloc(sizeof(double) * (size_t)n), *u2 = malloc(sizeof(double) * (size_t)n);
    CX_CHECK_OK(cx_schur_condense(Sa, f, fc1));
    CX_CHECK_OK(cx_schur_condense(Sb, f, fc2));
    CX_CHECK_LE(max_diff((size_t)nc, fc1, fc2), 1e-12 * max_abs((size_t)nc, fc1));
    CX_CHECK_OK(cx_schur_expand(Sa, f, uc, u1));
    CX_CHECK_OK(cx_schur_expand(Sb, f, uc, u2));
    CX_CHECK_LE(max_diff((size_t)n, u1, u2), 1e-12 * max_abs((size_t)n, u1));
    for (int k = 0; k < nc; k++)
        CX_CHECK(u1[c[k]] == uc[k] && u2[c[k]] == uc[k]);
    free(fc1);
    free(fc2);
    free(u1);
    free(u2);
}

/* c = the top face (k = m - 1), listed in reverse so that the caller's
 * order is not the trailing block's. */
static void compare_orderings(int m, int neumann)
{
    cx_csc A = {0};
    laplacian3(&A, m, neumann ? 0 : 0.1, neumann);
    int n = A.nrow, nc = m * m;
    int *c = malloc(sizeof(int) * (size_t)nc);
    for (int q = 0; q < nc; q++)
        c[nc - 1 - q] = q * m + (m - 1);
    double *f = malloc(sizeof(double) * (size_t)n), *uc = malloc(sizeof(double) * (size_t)nc);
    for (int i = 0; i < n; i++)
        f[i] = sin(0.37 * i) + (neumann ? 0 : 0.5);
    if (neumann) {   /* a singular A needs a load it can carry: sum f = 0 */
        double sum = 0;
        for (int i = 0; i < n; i++)
            sum += f[i];
        for (int i = 0; i < n; i++)
            f[i] -= sum / n;
    }
    for (int k = 0; k < nc; k++)
        uc[k] = cos(0.21 * k);
    cx_schur *Sc = NULL, *Sm = NULL;
    cx_counters cnt = {0};
    CX_CHECK_OK(cx_schur_create_ordered(&Sc, &A, c, nc, CX_ORDER_CAMD, &cnt, NULL));
    CX_CHECK_OK(cx_schur_create_ordered(&Sm, &A, c, nc, CX_ORDER_METIS, &cnt, NULL));
    CX_CHECK(cnt.factorizations == 2);
    const cx_schur_ordering *oc = cx_schur_ordering_of(Sc), *om = cx_schur_ordering_of(Sm);
    CX_CHECK(oc->chosen == CX_ORDER_CAMD && !oc->tried);
    CX_CHECK(om->chosen == CX_ORDER_METIS && om->tried);
    CX_CHECK(om->lnz[CX_ORDER_CAMD] > 0 && om->lnz[CX_ORDER_METIS] > 0);
    /* the same CAMD analysis in both, and on a 3D grid nested dissection
     * fills less: the point of trying it */
    CX_CHECK(om->flops[CX_ORDER_CAMD] == oc->flops[CX_ORDER_CAMD]);
    CX_CHECK_LE(om->flops[CX_ORDER_METIS], om->flops[CX_ORDER_CAMD]);
    CX_CHECK_LE(cx_schur_factor_nnz(Sm), cx_schur_factor_nnz(Sc));

    size_t nn = (size_t)nc * (size_t)nc;
    const double *S1 = cx_schur_matrix(Sc), *S2 = cx_schur_matrix(Sm);
    CX_CHECK_LE(max_diff(nn, S1, S2), 1e-12 * max_abs(nn, S1));
    check_same_reduction(Sc, Sm, n, nc, c, f, uc);

    /* the automatic choice analyses both here (CAMD's flops exceed METIS's
     * cost on this grid) and factorises the one it reports */
    cx_schur *Sa = NULL;
    CX_CHECK_OK(cx_schur_create(&Sa, &A, c, nc, NULL, NULL));
    const cx_schur_ordering *oa = cx_schur_ordering_of(Sa);
    CX_CHECK(oa->tried_amd);   /* one dof per vertex: the 2D path */
    /* CAMD's fill as CAMD counts it while ordering (all the automatic
     * choice looks at, and what it keeps where CAMD loses: most grids
     * here) is CHOLMOD's analysis of that ordering (Sc's) */
    CX_CHECK(oa->lnz[CX_ORDER_CAMD] == oc->lnz[CX_ORDER_CAMD]);
    CX_CHECK_LE(fabs(oa->flops[CX_ORDER_CAMD] - oc->flops[CX_ORDER_CAMD]), 1e-12 * oc->flops[CX_ORDER_CAMD]);
    if (oa->tried) {
        int metis = oa->flops[CX_ORDER_METIS] < oa->flops[CX_ORDER_CAMD];
        if (oa->chosen == CX_ORDER_METIS)
            CX_CHECK(metis);
        if (oa->chosen != CX_ORDER_AMD)
            CX_CHECK(cx_schur_factor_nnz(Sa) == cx_schur_factor_nnz(oa->chosen == CX_ORDER_METIS ? Sm : Sc));
    } else {
        CX_CHECK(oa->chosen == CX_ORDER_CAMD || oa->chosen == CX_ORDER_AMD);
    }
    CX_CHECK_LE(max_diff(nn, cx_schur_matrix(Sa), S1), 1e-12 * max_abs(nn, S1));

    cx_schur_destroy(&Sa);
    cx_schur_destroy(&Sc);
    cx_schur_destroy(&Sm);
    free(c);
    free(f);
    free(uc);
    cx_csc_clear(&A);
}

/* A small 2D problem: CAMD's fill is below what a METIS run would cost, so
 * METIS is not run at all. */
static void test_small_2d_skips_metis(void)
{
    cx_csc A = {0};
    laplacian(&A, 30, 0.1, 0);
    int nc = 30, c[30];
    for (int k = 0; k < nc; k++)
        c[k] = k;
    cx_schur *S = NULL;
    CX_CHECK_OK(cx_schur_create(&S, &A, c, nc, NULL, NULL));
    const cx_schur_ordering *o = cx_schur_ordering_of(S);
    CX_CHECK(!o->tried && o->chosen == CX_ORDER_CAMD);
    CX_CHECK(o->lnz[CX_ORDER_CAMD] > 0 && o->flops[CX_ORDER_CAMD] > 0);
    cx_schur_destroy(&S);
    cx_csc_clear(&A);
}

/* The 2D 5-point Laplacian on an m x m grid times a 2 x 2 SPD block: 2
 * dofs per node, coupled as in 2D elasticity. */
static void vector_laplacian2(cx_csc *A, int m)
{
    static const double B[2][2] = {{2.0, 0.6}, {0.6, 1.5}};
    cx_csc Ls = {0};
    laplacian(&Ls, m, 0.05, 0);
    cx_triplet t;
    int n = 2 * Ls.nrow;
    cx_triplet_init(&t, n, n, 4 * cx_csc_nnz(&Ls));
    for (int j = 0; j < Ls.ncol; j++)
        for (int q = Ls.p[j]; q < Ls.p[j + 1]; q++)
            for (int a = 0; a < 2; a++)
                for (int b = 0; b < 2; b++)
                    cx_triplet_add(&t, 2 * Ls.i[q] + a, 2 * j + b, Ls.x[q] * B[a][b]);
    CX_CHECK_OK(cx_csc_from_triplet(A, &t));
    cx_triplet_clear(&t);
    cx_csc_clear(&Ls);
}

/* AMD with c moved last against CAMD, 2 dofs per node, c the first grid
 * row's nodes (both dofs, as under friction, or the second only, as the
 * normal dofs of a frictionless run), listed out of order: S, the
 * condensed load and the expansion agree to 1e-12 relative with CAMD's
 * and S with cx_schur_by_solves; the automatic choice analyses both and
 * factorises the one with the fewer predicted flops. */
static void compare_amd_last(int m, int normal_only)
{
    cx_csc A = {0};
    vector_laplacian2(&A, m);
    int n = A.nrow, per = normal_only ? 1 : 2, nc = m * per;
    int *c = malloc(sizeof(int) * (size_t)nc);
    for (int q = 0, k = 0; q < m; q++)
        for (int a = 0; a < per; a++, k++)
            c[nc - 1 - k] = 2 * q + (normal_only ? 1 : a);
    double *f = malloc(sizeof(double) * (size_t)n), *uc = malloc(sizeof(double) * (size_t)nc);
    for (int i = 0; i < n; i++)
        f[i] = sin(0.37 * i);
    for (int k = 0; k < nc; k++)
        uc[k] = cos(0.21 * k);
    cx_schur *Sc = NULL, *Sd = NULL, *Sa = NULL;
    CX_CHECK_OK(cx_schur_create_ordered(&Sc, &A, c, nc, CX_ORDER_CAMD, NULL, NULL));
    CX_CHECK_OK(cx_schur_create_ordered(&Sd, &A, c, nc, CX_ORDER_AMD, NULL, NULL));
    CX_CHECK_OK(cx_schur_create(&Sa, &A, c, nc, NULL, NULL));
    const cx_schur_ordering *oc = cx_schur_ordering_of(Sc), *od = cx_schur_ordering_of(Sd),
                            *oa = cx_schur_ordering_of(Sa);
    CX_CHECK(oc->chosen == CX_ORDER_CAMD && !oc->tried_amd);
    CX_CHECK(od->chosen == CX_ORDER_AMD && od->tried_amd && od->lnz[CX_ORDER_AMD] > 0);
    size_t nn = (size_t)nc * (size_t)nc;
    double *Sref = malloc(sizeof(double) * nn);
    CX_CHECK_OK(cx_schur_by_solves(&A, c, nc, Sref, NULL, NULL));
    double smax = max_abs(nn, Sref);
    CX_CHECK_LE(max_diff(nn, cx_schur_matrix(Sc), Sref), 1e-12 * smax);
    CX_CHECK_LE(max_diff(nn, cx_schur_matrix(Sd), Sref), 1e-12 * smax);
    check_same_reduction(Sc, Sd, n, nc, c, f, uc);

    /* the automatic choice: both analysed, the same numbers as the forced
     * runs', the one with fewer flops factorised */
    CX_CHECK(oa->tried_amd && !oa->tried);   /* too small for METIS */
    CX_CHECK(oa->flops[CX_ORDER_CAMD] == oc->flops[CX_ORDER_CAMD]);
    CX_CHECK(oa->flops[CX_ORDER_AMD] == od->flops[CX_ORDER_AMD]);
    int amd = oa->flops[CX_ORDER_AMD] < oa->flops[CX_ORDER_CAMD];
    CX_CHECK(oa->chosen == (amd ? CX_ORDER_AMD : CX_ORDER_CAMD));
    CX_CHECK(cx_schur_factor_nnz(Sa) == cx_schur_factor_nnz(amd ? Sd : Sc));
    CX_CHECK_LE(max_diff(nn, cx_schur_matrix(Sa), Sref), 1e-12 * smax);

    cx_schur_destroy(&Sa);
    cx_schur_destroy(&Sc);
    cx_schur_destroy(&Sd);
    free(c);
    free(f);
    free(uc);
    free(Sref);
    cx_csc_clear(&A);
}

/* laplacian3 (m^3 nodes) times a 3 x 3 SPD block: 3 dofs per node
 * (dof 3 node + component) coupled as in 3D elasticity, every dof of a
 * node with the same column pattern, which the METIS path compresses to
 * one vertex. */
static void vector_laplacian3(cx_csc *A, int m, double shift, int neumann)
{
    static const double B[3][3] = {{2.0, 0.5, 0.3}, {0.5, 2.0, 0.4}, {0.3, 0.4, 2.0}};
    cx_csc Ls = {0};
    laplacian3(&Ls, m, shift, neumann);
    cx_triplet t;
    int n = 3 * Ls.nrow;
    cx_triplet_init(&t, n, n, 9 * cx_csc_nnz(&Ls));
    for (int j = 0; j < Ls.ncol; j++)
        for (int q = Ls.p[j]; q < Ls.p[j + 1]; q++)
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++)
                    cx_triplet_add(&t, 3 * Ls.i[q] + a, 3 * j + b, Ls.x[q] * B[a][b]);
    CX_CHECK_OK(cx_csc_from_triplet(A, &t));
    cx_triplet_clear(&t);
    cx_csc_clear(&Ls);
}

/* The Schur complement onto the top face of a 3-dof-per-node grid: all 3
 * dofs of each face node (as under Tresca friction) or the normal one
 * only (frictionless), listed out of order. Both orderings' S, condensed
 * load and expansion agree to 1e-12 relative, and S agrees with the one
 * computed column by column from a factorisation of A_ii
 * (cx_schur_by_solves). */
static void compare_vector(int m, int neumann, int normal_only)
{
    cx_csc A = {0};
    vector_laplacian3(&A, m, neumann ? 0 : 0.05, neumann);
    int n = A.nrow, per = normal_only ? 1 : 3, nc = m * m * per;
    int *c = malloc(sizeof(int) * (size_t)nc);
    for (int q = 0, k = 0; q < m * m; q++)
        for (int a = 0; a < per; a++, k++)
            c[(11 * k + 3) % nc] = 3 * (q * m + (m - 1)) + (normal_only ? 2 : a);   /* 11, nc coprime */
    double *f = malloc(sizeof(double) * (size_t)n), *uc = malloc(sizeof(double) * (size_t)nc);
    for (int i = 0; i < n; i++)
        f[i] = sin(0.37 * i);
    for (int k = 0; k < nc; k++)
        uc[k] = cos(0.21 * k);
    cx_schur *Sc = NULL, *Sm = NULL;
    CX_CHECK_OK(cx_schur_create_ordered(&Sc, &A, c, nc, CX_ORDER_CAMD, NULL, NULL));
    CX_CHECK_OK(cx_schur_create_ordered(&Sm, &A, c, nc, CX_ORDER_METIS, NULL, NULL));
    size_t nn = (size_t)nc * (size_t)nc;
    double *Sref = malloc(sizeof(double) * nn);
    CX_CHECK_OK(cx_schur_by_solves(&A, c, nc, Sref, NULL, NULL));
    const double *S1 = cx_schur_matrix(Sc), *S2 = cx_schur_matrix(Sm);
    double smax = max_abs(nn, Sref);
    CX_CHECK(smax > 0);
    CX_CHECK_LE(max_diff(nn, S1, Sref), 1e-12 * smax);
    CX_CHECK_LE(max_diff(nn, S2, Sref), 1e-12 * smax);
    for (int a = 0; a < nc; a++)   /* stored full, exactly symmetric */
        for (int b = 0; b < a; b++)
            CX_CHECK(S2[a + (size_t)b * nc] == S2[b + (size_t)a * nc]);
    check_same_reduction(Sc, Sm, n, nc, c, f, uc);

    /* the automatic choice on 3 dofs per node: METIS analysed first, CAMD
     * predicted from its column counts alone, the same numbers as CAMD's
     * full analysis; the factor is the chosen one's */
    cx_schur *Sa = NULL;
    CX_CHECK_OK(cx_schur_create(&Sa, &A, c, nc, NULL, NULL));
    const cx_schur_ordering *oa = cx_schur_ordering_of(Sa), *oc = cx_schur_ordering_of(Sc),
                            *om = cx_schur_ordering_of(Sm);
    CX_CHECK(oa->tried);
    CX_CHECK(oa->lnz[CX_ORDER_CAMD] == oc->lnz[CX_ORDER_CAMD] && oa->flops[CX_ORDER_CAMD] == oc->flops[CX_ORDER_CAMD]);
    CX_CHECK(oa->lnz[CX_ORDER_METIS] == om->lnz[CX_ORDER_METIS]);
    CX_CHECK(cx_schur_factor_nnz(Sa) == cx_schur_factor_nnz(oa->chosen == CX_ORDER_METIS ? Sm : Sc));
    if (oa->chosen == CX_ORDER_METIS)
        CX_CHECK(oa->flops[CX_ORDER_METIS] < oa->flops[CX_ORDER_CAMD]);
    if (m >= 18)   /* METIS's flops (5.2e9 at m = 18) now win back its cost */
        CX_CHECK(oa->chosen == CX_ORDER_METIS);
    CX_CHECK_LE(max_diff(nn, cx_schur_matrix(Sa), Sref), 1e-12 * smax);
    cx_schur_destroy(&Sa);

    cx_schur_destroy(&Sc);
    cx_schur_destroy(&Sm);
    free(c);
    free(f);
    free(uc);
    free(Sref);
    cx_csc_clear(&A);
}

int main(void)
{
    compare_orderings(16, 0);   /* 4096 dofs, 256 on the face */
    compare_orderings(14, 1);   /* singular: held only through c */
    test_small_2d_skips_metis();
    compare_amd_last(40, 0);   /* 3200 dofs, the 80 of the first row */
    compare_amd_last(40, 1);   /* its 40 "normal" dofs */
    compare_vector(7, 0, 0);   /* 1029 dofs, 147 on the face: Tresca-like */
    compare_vector(7, 0, 1);   /* the 49 normal dofs: frictionless-like */
    compare_vector(6, 1, 0);   /* singular: held only through c */
    compare_vector(12, 0, 0);  /* 5184 dofs, 432 on the face: CAMD still chosen */
    compare_vector(18, 0, 0);  /* 17496 dofs, 972 on the face: METIS chosen */
    return check_finish("linalg_ordering");
}
