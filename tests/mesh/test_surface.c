/* SPDX-License-Identifier: GPL-3.0-or-later */
/* mesh/surface.c: the facets of a mesh, its surface and its outline, by
 * counts computed by hand on a rectangle, a brick and two stacked blocks,
 * and the orientation of the surface facets (outward). */
#include "mesh/mesh.h"
#include "check.h"

#include <math.h>
#include <string.h>

static const double *mc_node(const cx_mesh *m, int k) { return m->x + m->dim * k; }

typedef struct {
    int all, surface, outline;
} counts;

static counts count(const cx_mesh *m)
{
    counts c = {-1, -1, -1};
    cx_facets f;
    int *pairs = NULL;
    if (cx_mesh_facets(m, 0, &f) == CX_OK) {
        c.all = f.n;
        int one = 0;
        for (int i = 0; i < f.n; i++) {
            CX_CHECK(f.uses[i] == 1 || f.uses[i] == 2);
            one += f.uses[i] == 1;
        }
        cx_facets_clear(&f);
        CX_CHECK_OK(cx_mesh_facets(m, 1, &f));
        CX_CHECK(f.n == one);
        c.surface = f.n;
        cx_facets_clear(&f);
    }
    if (cx_mesh_outline(m, &pairs, &c.outline) == CX_OK) {
        for (int k = 0; k < c.outline; k++) {
            CX_CHECK(pairs[2 * k] < pairs[2 * k + 1]);
            if (k)   /* sorted, each once */
                CX_CHECK(pairs[2 * k - 2] < pairs[2 * k] ||
                         (pairs[2 * k - 2] == pairs[2 * k] && pairs[2 * k - 1] < pairs[2 * k + 1]));
        }
        cx_free(pairs);
    }
    return c;
}

/* Every surface facet points out of the box [lo, hi]: its centre lies on a
 * side of the box and its normal (2D: right of the edge; 3D: right-hand
 * rule) is that side's outward normal. Returns the facets that do not. */
static int outward_misses(const cx_mesh *m, const double *lo, const double *hi)
{
    cx_facets f;
    if (cx_mesh_facets(m, 1, &f) != CX_OK)
        return -1;
    int bad = 0, dim = m->dim;
    for (int i = 0; i < f.n; i++) {
        const int *q = f.nodes + (size_t)f.npf * i;
        double c[3] = {0, 0, 0}, n[3] = {0, 0, 0};
        for (int k = 0; k < f.npf; k++)
            for (int a = 0; a < dim; a++)
                c[a] += m->x[dim * q[k] + a] / f.npf;
        const double *p0 = mc_node(m, q[0]), *p1 = mc_node(m, q[1]);
        if (dim == 2) {
            n[0] = p1[1] - p0[1];
            n[1] = -(p1[0] - p0[0]);
        } else {
            const double *p2 = mc_node(m, q[2]);
            double u[3], v[3];
            for (int a = 0; a < 3; a++)
                u[a] = p1[a] - p0[a], v[a] = p2[a] - p0[a];
            n[0] = u[1] * v[2] - u[2] * v[1];
            n[1] = u[2] * v[0] - u[0] * v[2];
            n[2] = u[0] * v[1] - u[1] * v[0];
        }
        int side = 0;
        for (int a = 0; a < dim; a++) {
            if (fabs(c[a] - lo[a]) < 1e-12)
                side += n[a] < 0 ? 1 : -100;
            if (fabs(c[a] - hi[a]) < 1e-12)
                side += n[a] > 0 ? 1 : -100;
        }
        bad += side != 1;
    }
    cx_facets_clear(&f);
    return bad;
}

/* The surface is what the generator names as boundaries. */
static int named_facets(const cx_mesh *m)
{
    int n = 0;
    for (int b = 0; b < m->nbounds; b++)
        n += m->bounds[b].nfacets;
    return n;
}

static void test_rectangle(void)
{
    /* 3 x 2 cells: 3 x 3 horizontal + 4 x 2 vertical edges = 17, of which
     * 2 (3 + 2) = 10 on the boundary; triangles add 6 diagonals */
    static const struct {
        cx_elem_type t;
        counts want;
    } cases[] = {
        {CX_EL_QUAD4, {17, 10, 10}},
        {CX_EL_TRI3, {23, 10, 10}},
        {CX_EL_TRI6, {23, 10, 20}},   /* the outline splits each edge at its mid node */
    };
    double lo[2] = {0, 0}, hi[2] = {3, 2};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        cx_mesh *m = NULL;
        CX_CHECK_OK(cx_mesh_rectangle(&m, 0, 0, 3, 2, 3, 2, cases[k].t, NULL));
        counts c = count(m);
        CX_CHECK(c.all == cases[k].want.all);
        CX_CHECK(c.surface == cases[k].want.surface);
        CX_CHECK(c.outline == cases[k].want.outline);
        CX_CHECK(c.surface == named_facets(m));
        CX_CHECK(outward_misses(m, lo, hi) == 0);
        cx_facets f;
        CX_CHECK_OK(cx_mesh_facets(m, 1, &f));
        CX_CHECK((f.mid != NULL) == (cases[k].t == CX_EL_TRI6) && f.npf == 2);
        /* a TRI6 mid node lies halfway along its edge */
        for (int i = 0; f.mid && i < f.n; i++)
            for (int a = 0; a < 2; a++)
                CX_CHECK_NEAR(m->x[2 * f.mid[i] + a],
                              0.5 * (m->x[2 * f.nodes[2 * i] + a] + m->x[2 * f.nodes[2 * i + 1] + a]), 0, 1e-15);
        cx_facets_clear(&f);
        cx_mesh_destroy(&m);
    }
}

static void test_brick(void)
{
    /* hex 1x1x1: the 6 faces, the 12 edges of a cube. hex 2x2x2: 3 x 12 = 36
     * faces, 6 x 4 = 24 outside; 3 x 18 = 54 edges less the 6 interior ones.
     * tet 1x1x1 (6 tets): 24 tet faces = 12 outside (two per side) + 2 x 6
     * inside; outline = 12 cube edges + 6 side diagonals. */
    static const struct {
        cx_elem_type t;
        int n;
        counts want;
    } cases[] = {
        {CX_EL_HEX8, 1, {6, 6, 12}},
        {CX_EL_HEX8, 2, {36, 24, 48}},
        {CX_EL_TET4, 1, {18, 12, 18}},
    };
    double lo[3] = {0, 0, 0}, hi[3] = {1, 2, 3};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        cx_mesh *m = NULL;
        int n = cases[k].n;
        CX_CHECK_OK(cx_mesh_brick(&m, lo, hi, n, n, n, cases[k].t, NULL));
        counts c = count(m);
        CX_CHECK(c.all == cases[k].want.all);
        CX_CHECK(c.surface == cases[k].want.surface);
        CX_CHECK(c.outline == cases[k].want.outline);
        CX_CHECK(c.surface == named_facets(m));
        CX_CHECK(outward_misses(m, lo, hi) == 0);
        cx_mesh_destroy(&m);
    }
}

static void test_twoblocks(void)
{
    /* upper 2 x 1 cells (7 edges, 6 outside), lower 3 x 2 (17, 10): the
     * interface nodes exist once per body, so both sides of it are surface */
    cx_mesh *m = NULL;
    int up[2] = {2, 1}, low[2] = {3, 2};
    CX_CHECK_OK(cx_mesh_twoblocks(&m, 0, 0, 1, 2, 2, up, low, CX_EL_QUAD4, NULL));
    counts c = count(m);
    CX_CHECK(c.all == 24);
    CX_CHECK(c.surface == 16);
    CX_CHECK(c.outline == 16);
    CX_CHECK(c.surface == named_facets(m));
    cx_mesh_destroy(&m);
}

static void test_alloc(void)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    cx_mesh *m = NULL;
    CX_CHECK_OK(cx_mesh_brick(&m, lo, hi, 2, 1, 1, CX_EL_TET4, NULL));
    for (int what = 0; what < 2; what++) {
        int ok = 0;
        for (long n = 0; n < 100 && !ok; n++) {
            long live = cx_alloc_live();
            cx_facets f;
            int *pairs = NULL, np = 0;
            cx_alloc_fail_after(n);
            int st = what == 0 ? cx_mesh_facets(m, 0, &f) : cx_mesh_outline(m, &pairs, &np);
            cx_alloc_fail_after(-1);
            if (st == CX_OK) {
                ok = 1;
                if (what == 0)
                    cx_facets_clear(&f);
                cx_free(pairs);
            } else {
                CX_CHECK(st == CX_ENOMEM && pairs == NULL && cx_alloc_live() == live);
            }
        }
        CX_CHECK(ok);
    }
    cx_mesh_destroy(&m);
}

int main(void)
{
    long live = cx_alloc_live();
    test_rectangle();
    test_brick();
    test_twoblocks();
    test_alloc();
    CX_CHECK(cx_alloc_live() == live);
    return check_finish("mesh_surface");
}
