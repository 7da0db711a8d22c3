/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linalg/schur_numeric.c below the public API: cx_schur_arrange reorders
 * the interior columns within each supernode of a contact-last symbolic
 * factor and leaves its structure alone (the same supernodes, the same
 * original dofs in each, the contact columns in place, rows sorted); after
 * it, the interior rows a descendant is the first to update are
 * consecutive in every supernode it updates, and the updates land in fewer runs than
 * before. cx_schur_numeric on the arranged factor gives S equal to the one
 * computed column by column (cx_schur_by_solves), to 1e-12 relative, also
 * when every large update is formed a panel of its columns at a time. */
#include "linalg/linalg_impl.h"
#include "check.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* 3 dofs per node on an m x m x m grid (dof 3 node + component), each
 * node coupled to its 6 neighbours through an SPD 3 x 3 block, as in 3D
 * elasticity; shift > 0 keeps it definite. */
static void vector_grid(cx_csc *A, int m, double shift)
{
    static const double B[3][3] = {{2.0, 0.5, 0.3}, {0.5, 2.0, 0.4}, {0.3, 0.4, 2.0}};
    int nn = m * m * m;
    cx_triplet t;
    cx_triplet_init(&t, 3 * nn, 3 * nn, (size_t)63 * (size_t)nn);
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
                    deg++;
                    for (int x = 0; x < 3; x++)
                        for (int y = 0; y < 3; y++)
                            cx_triplet_add(&t, 3 * r + x, 3 * ((a * m + b) * m + c) + y, -B[x][y]);
                }
                for (int x = 0; x < 3; x++)
                    for (int y = 0; y < 3; y++)
                        cx_triplet_add(&t, 3 * r + x, 3 * r + y, B[x][y] * deg + (x == y ? shift : 0));
            }
    CX_CHECK_OK(cx_csc_from_triplet(A, &t));
    cx_triplet_clear(&t);
}

/* first[k]: the first supernode (in factorisation order) whose rows below
 * its own columns hold column k; nsuper if none. */
static void first_updaters(const cholmod_factor *L, int *first)
{
    const int *super = L->super, *pi = L->pi, *ls = L->s;
    int ns = (int)L->nsuper;
    for (size_t k = 0; k < L->n; k++)
        first[k] = ns;
    for (int d = 0; d < ns; d++)
        for (int p = pi[d] + super[d + 1] - super[d]; p < pi[d + 1]; p++)
            if (first[ls[p]] == ns)
                first[ls[p]] = d;
}

/* The runs of consecutive rows over every update (descendant d into a
 * later supernode s): the count the scatter loops over. If first is
 * given, also check that the interior rows (before nstop) of d in s whose
 * first updater is d are consecutive (one run) where s has at least
 * CX_SCHUR_ARRANGE_MIN interior columns (narrower ones keep their order);
 * *bad counts the pairs where they are not. (The contact rows keep the
 * caller's order.) */
static long count_runs(const cholmod_factor *L, int nstop, const int *first, int *bad)
{
    const int *super = L->super, *pi = L->pi, *ls = L->s;
    int *smap = malloc(sizeof(int) * L->n);
    for (size_t s = 0; s < L->nsuper; s++)
        for (int k = super[s]; k < super[s + 1]; k++)
            smap[k] = (int)s;
    long runs = 0;
    for (size_t d = 0; d < L->nsuper; d++) {
        int p = pi[d] + super[d + 1] - super[d];
        while (p < pi[d + 1]) {   /* one target supernode at a time */
            int s = smap[ls[p]], q = p, own_last = -2, own_runs = 0;
            for (; q < pi[d + 1] && smap[ls[q]] == s; q++) {
                if (q == p || ls[q] != ls[q - 1] + 1)
                    runs++;
                if (first && ls[q] < nstop && first[ls[q]] == (int)d) {
                    if (ls[q] != own_last + 1)
                        own_runs++;
                    own_last = ls[q];
                }
            }
            int width = (super[s + 1] < nstop ? super[s + 1] : nstop) - super[s];
            if (first && own_runs > 1 && width >= CX_SCHUR_ARRANGE_MIN)
                (*bad)++;
            p = q;
        }
    }
    free(smap);
    return runs;
}

static void test_arrange(int m)
{
    cholmod_common cc;
    cx_cholmod_start(&cc);
    cx_csc A = {0};
    vector_grid(&A, m, 0.05);
    int n = A.nrow, nc = 3 * m * m, ni = n - nc;
    /* c: the 3 dofs of each node of the face k = m - 1, listed out of order */
    int *c = malloc(sizeof(int) * (size_t)nc), *cmember = calloc((size_t)n, sizeof(int));
    for (int q = 0, t = 0; q < m * m; q++)
        for (int a = 0; a < 3; a++, t++)
            c[(7 * t + 2) % nc] = 3 * (q * m + m - 1) + a;   /* 7, nc coprime for the m used */
    for (int k = 0; k < nc; k++)
        cmember[c[k]] = 1;
    /* contact last: the interior by CAMD's constrained ordering, then c as given */
    cholmod_sparse view = cx_cholmod_view(&A, 1);
    int *perm = malloc(sizeof(int) * (size_t)n);
    CX_CHECK(cholmod_camd(&view, NULL, 0, cmember, perm, &cc));
    memcpy(perm + ni, c, sizeof(int) * (size_t)nc);
    for (int k = 0; k < ni; k++)
        CX_CHECK(!cmember[perm[k]]);
    cc.nmethods = 1;
    cc.method[0].ordering = CHOLMOD_GIVEN;
    cc.postorder = 0;
    cholmod_factor *L = cholmod_analyze_p(&view, perm, NULL, 0, &cc);
    CX_CHECK(L && L->is_super && L->xtype == CHOLMOD_PATTERN);
    if (!L)
        return;
    size_t ns = L->nsuper;
    int *super0 = malloc(sizeof(int) * (ns + 1)), *pi0 = malloc(sizeof(int) * (ns + 1));
    int *perm0 = malloc(sizeof(int) * (size_t)n), *s0 = malloc(sizeof(int) * L->ssize);
    memcpy(super0, L->super, sizeof(int) * (ns + 1));
    memcpy(pi0, L->pi, sizeof(int) * (ns + 1));
    memcpy(perm0, L->Perm, sizeof(int) * (size_t)n);
    memcpy(s0, L->s, sizeof(int) * L->ssize);
    size_t xsize0 = L->xsize;
    long runs0 = count_runs(L, ni, NULL, NULL);

    CX_CHECK_OK(cx_schur_arrange(L, ni));

    /* the same supernodes, sizes and contact columns */
    CX_CHECK(L->nsuper == ns && L->xsize == xsize0);
    CX_CHECK(memcmp(super0, L->super, sizeof(int) * (ns + 1)) == 0);
    CX_CHECK(memcmp(pi0, L->pi, sizeof(int) * (ns + 1)) == 0);
    const int *P = L->Perm, *super = L->super, *pi = L->pi, *ls = L->s;
    CX_CHECK(memcmp(perm0 + ni, P + ni, sizeof(int) * (size_t)nc) == 0);
    /* each supernode: the same original dofs as columns and as rows, its
     * own columns first, the rows below ascending */
    int *mark = calloc((size_t)n, sizeof(int)), moved = 0;
    for (size_t s = 0; s < ns; s++) {
        int nscol = super[s + 1] - super[s];
        for (int k = super[s]; k < super[s + 1]; k++) {
            mark[perm0[k]] = (int)s + 1;
            moved += P[k] != perm0[k];
        }
        for (int k = super[s]; k < super[s + 1]; k++)
            CX_CHECK(mark[P[k]] == (int)s + 1);
        for (int t = 0; t < nscol; t++)
            CX_CHECK(ls[pi[s] + t] == super[s] + t);
        for (int p = pi[s] + nscol + 1; p < pi[s + 1]; p++)
            CX_CHECK(ls[p] > ls[p - 1]);
    }
    CX_CHECK(moved > 0);   /* CAMD's order within supernodes was not already this one */
    int *rows0 = calloc((size_t)n, sizeof(int));
    for (size_t s = 0; s < ns; s++) {
        for (int p = pi0[s]; p < pi0[s + 1]; p++)
            rows0[perm0[s0[p]]] = (int)s + 1;
        for (int p = pi[s]; p < pi[s + 1]; p++)
            CX_CHECK(rows0[P[ls[p]]] == (int)s + 1);
    }
    /* the rows a descendant brings first: one run in each target; fewer
     * runs over all updates */
    int *first = malloc(sizeof(int) * (size_t)n), bad = 0;
    first_updaters(L, first);
    long runs1 = count_runs(L, ni, first, &bad);
    CX_CHECK(bad == 0);
    CX_CHECK(runs1 < runs0);
    printf("arrange, m = %d: %zu supernodes, %d columns moved, runs over all updates %ld -> %ld\n", m, ns,
           moved, runs0, runs1);

    /* S from the arranged factor: equal to the column-by-column one */
    size_t nn = (size_t)nc * (size_t)nc;
    double *W = calloc(nn, sizeof(double)), *Sref = malloc(sizeof(double) * nn);
    cx_diag d;
    CX_CHECK_OK(cx_schur_numeric(L, &A, ni, W, &cc, &d));
    CX_CHECK_OK(cx_schur_by_solves(&A, c, nc, Sref, NULL, NULL));
    double smax = 0, err = 0;
    for (int b = 0; b < nc; b++)   /* W: lower triangle, trailing order = the order of c */
        for (int a = b; a < nc; a++) {
            smax = fmax(smax, fabs(Sref[a + (size_t)b * nc]));
            err = fmax(err, fabs(W[a + (size_t)b * nc] - Sref[a + (size_t)b * nc]));
        }
    CX_CHECK(smax > 0);
    CX_CHECK_LE(err, 1e-12 * smax);
    cholmod_free_factor(&L, &cc);

    /* the same with the updates formed a panel of 64 columns at a time
     * (the panel size 1 stands for the smallest): the factor's largest
     * update must then be wider than one panel */
    L = cholmod_analyze_p(&view, perm, NULL, 0, &cc);
    CX_CHECK(L != NULL);
    if (L) {
        size_t maxrow = 0;
        for (size_t s = 0; s < L->nsuper; s++) {
            size_t r = (size_t)(((int *)L->pi)[s + 1] - ((int *)L->pi)[s]);
            maxrow = r > maxrow ? r : maxrow;
        }
        CX_CHECK(L->maxcsize > 64 * maxrow);
        memset(W, 0, sizeof(double) * nn);
        CX_CHECK_OK(cx_schur_numeric_panel(L, &A, ni, W, 1, &cc, &d));
        double err2 = 0;
        for (int b = 0; b < nc; b++)
            for (int a = b; a < nc; a++)
                err2 = fmax(err2, fabs(W[a + (size_t)b * nc] - Sref[a + (size_t)b * nc]));
        CX_CHECK_LE(err2, 1e-12 * smax);
        printf("panels of 64 columns (largest update %zu entries, %zu rows at most): error %.2g of %.2g\n",
               L->maxcsize, maxrow, err2, smax);
    }

    cholmod_free_factor(&L, &cc);
    cholmod_finish(&cc);
    cx_csc_clear(&A);
    free(c);
    free(cmember);
    free(perm);
    free(super0);
    free(pi0);
    free(perm0);
    free(s0);
    free(mark);
    free(rows0);
    free(first);
    free(W);
    free(Sref);
}

int main(void)
{
    test_arrange(6);    /* 648 dofs, 108 on the face */
    test_arrange(11);   /* 3993 dofs, 363 on the face */
    return check_finish("linalg_schur_numeric");
}
