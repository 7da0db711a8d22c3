/* SPDX-License-Identifier: GPL-3.0-or-later */
/* mesh/rectangle.c and mesh.c: element tables, node and element counts,
 * coordinates, counter-clockwise elements, outward boundary facets,
 * conforming TRI6 mid-edge nodes, boundary node lists, input validation
 * and allocation failures. */
#include "mesh/mesh.h"
#include "mesh_check.h"
#include "check.h"

#include <string.h>

static void test_tables(void)
{
    static const char *names[] = {"tri3", "tri6", "quad4", "hex8", "tet4"};
    static const int npe[] = {3, 6, 4, 8, 4}, dim[] = {2, 2, 2, 3, 3};
    for (int t = 0; t < 5; t++) {
        CX_CHECK(strcmp(cx_elem_name((cx_elem_type)t), names[t]) == 0);
        CX_CHECK(cx_elem_from_name(names[t]) == t);
        CX_CHECK(cx_elem_npe((cx_elem_type)t) == npe[t]);
        CX_CHECK(cx_elem_dim((cx_elem_type)t) == dim[t]);
    }
    CX_CHECK(cx_elem_from_name("tri4") == -1);
    CX_CHECK(cx_elem_from_name(NULL) == -1);
    cx_mesh *m = NULL;
    cx_mesh_destroy(&m);   /* NULL-safe */
    cx_mesh_destroy(NULL);
}

/* Every element edge of a TRI6 mesh, keyed by its sorted vertex pair, has
 * the same mid node from both sides (the mesh is conforming): returns the
 * number of mismatches. */
static int tri6_mismatches(const cx_mesh *m)
{
    int bad = 0;
    for (int e = 0; e < m->nelems; e++)
        for (int a = 0; a < 3; a++) {
            const int *c = m->conn + 6 * e;
            int v0 = c[a], v1 = c[(a + 1) % 3], mid = c[3 + a];
            for (int f = 0; f < m->nelems; f++)
                for (int b = 0; b < 3; b++) {
                    const int *g = m->conn + 6 * f;
                    int w0 = g[b], w1 = g[(b + 1) % 3];
                    if (((w0 == v0 && w1 == v1) || (w0 == v1 && w1 == v0)) && g[3 + b] != mid)
                        bad++;
                }
            /* and it sits at the middle of a straight edge */
            for (int k = 0; k < 2; k++)
                if (fabs(m->x[2 * mid + k] - 0.5 * (m->x[2 * v0 + k] + m->x[2 * v1 + k])) > 1e-15)
                    bad++;
        }
    return bad;
}

static void test_counts(void)
{
    static const struct {
        cx_elem_type t;
        int nx, ny, nnodes, nelems, npf;
    } cases[] = {
        {CX_EL_TRI3, 3, 2, 4 * 3, 12, 2},
        {CX_EL_TRI6, 3, 2, 7 * 5, 12, 3},
        {CX_EL_QUAD4, 3, 2, 4 * 3, 6, 2},
        {CX_EL_QUAD4, 1, 1, 4, 1, 2},
    };
    static const char *sides[] = {"bottom", "right", "top", "left"};
    cx_diag d;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        cx_mesh *m = NULL;
        CX_CHECK_OK(cx_mesh_rectangle(&m, -1, 0.5, 2, 2.5, cases[c].nx, cases[c].ny, cases[c].t, &d));
        if (!m)
            continue;
        CX_CHECK(m->dim == 2 && m->etype == cases[c].t && m->npe == cx_elem_npe(cases[c].t));
        CX_CHECK(m->nnodes == cases[c].nnodes);
        CX_CHECK(m->nelems == cases[c].nelems);
        CX_CHECK(m->nbodies == 1 && m->body == NULL);
        CX_CHECK(m->nbounds == 4);
        CX_CHECK(mc_all_nodes_used(m));
        for (int e = 0; e < m->nelems; e++)
            CX_CHECK(mc_min_corner(m, e) > 0);
        CX_CHECK_NEAR(mc_measure(m), 3.0 * 2.0, 1e-14, 0);
        for (int s = 0; s < 4; s++) {
            const cx_boundary *b = cx_mesh_boundary(m, sides[s]);
            CX_CHECK(b != NULL);
            if (!b)
                continue;
            CX_CHECK(b->npf == cases[c].npf);
            CX_CHECK(b->nfacets == (s % 2 ? cases[c].ny : cases[c].nx));
            CX_CHECK(mc_bad_facets(m, b) == 0);
            /* the facet nodes lie exactly on their side */
            double want = s == 0 ? 0.5 : s == 1 ? 2 : s == 2 ? 2.5 : -1;
            for (int k = 0; k < b->nfacets * b->npf; k++)
                CX_CHECK(m->x[2 * b->facets[k] + (s % 2 ? 0 : 1)] == want);
        }
        CX_CHECK(cx_mesh_boundary(m, "front") == NULL);
        if (cases[c].t == CX_EL_TRI6)
            CX_CHECK(tri6_mismatches(m) == 0);
        cx_mesh_destroy(&m);
        CX_CHECK(m == NULL);
    }
}

static void test_boundary_nodes(void)
{
    cx_mesh *m = NULL;
    cx_diag d;
    CX_CHECK_OK(cx_mesh_rectangle(&m, 0, 0, 3, 1, 3, 1, CX_EL_TRI6, &d));
    int *nodes = NULL, count = 0;
    CX_CHECK_OK(cx_boundary_nodes(cx_mesh_boundary(m, "bottom"), &nodes, &count));
    CX_CHECK(count == 7);
    for (int k = 0; k < count; k++) {
        CX_CHECK(nodes[k] == k);   /* the lattice row J = 0 */
        CX_CHECK_NEAR(m->x[2 * nodes[k]], 0.5 * k, 0, 1e-15);
    }
    cx_free(nodes);
    CX_CHECK_OK(cx_boundary_nodes(cx_mesh_boundary(m, "left"), &nodes, &count));
    CX_CHECK(count == 3 && nodes[0] == 0 && nodes[1] == 7 && nodes[2] == 14);
    cx_free(nodes);
    /* the facets of "bottom" run left to right (outward normal -y on the right) */
    const cx_boundary *b = cx_mesh_boundary(m, "bottom");
    CX_CHECK(b->facets[0] == 0 && b->facets[1] == 2 && b->facets[2] == 1);
    cx_mesh_destroy(&m);
}

static void test_invalid(void)
{
    cx_mesh *m = NULL;
    cx_diag d;
    d.msg[0] = 0;
    CX_CHECK(cx_mesh_rectangle(&m, 0, 0, 1, 1, 0, 1, CX_EL_TRI3, &d) == CX_EINVAL);
    CX_CHECK(m == NULL && strstr(d.msg, "at least") != NULL);
    CX_CHECK(cx_mesh_rectangle(&m, 0, 0, 1, 1, 1, -2, CX_EL_TRI3, &d) == CX_EINVAL);
    CX_CHECK(cx_mesh_rectangle(&m, 0, 0, 1, 1, 1, 1, CX_EL_HEX8, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "hex8") != NULL);
    CX_CHECK(cx_mesh_rectangle(&m, 0, 0, 1, 1, 1, 1, (cx_elem_type)17, &d) == CX_EINVAL);
    CX_CHECK(cx_mesh_rectangle(&m, 1, 0, 1, 1, 1, 1, CX_EL_TRI3, &d) == CX_EINVAL);
    CX_CHECK(cx_mesh_rectangle(&m, 0, 0, 1, NAN, 1, 1, CX_EL_TRI3, &d) == CX_EINVAL);
    CX_CHECK(cx_mesh_rectangle(&m, 0, 0, 1, 1, 100000, 100000, CX_EL_TRI6, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "too large") != NULL);
    CX_CHECK(cx_mesh_rectangle(&m, 0, 0, 1, 1, 1, 1, CX_EL_TRI3, NULL) == CX_OK);   /* d may be NULL */
    cx_mesh_destroy(&m);
    CX_CHECK(m == NULL);
}

static void test_alloc(void)
{
    for (int t = 0; t < 3; t++) {
        int points;
        MC_ALLOC_LOOP(points, cx_mesh_rectangle(&am_, 0, 0, 1, 1, 2, 3, (cx_elem_type)t, NULL));
        CX_CHECK(points > 5);
    }
}

int main(void)
{
    long live = cx_alloc_live();
    test_tables();
    test_counts();
    test_boundary_nodes();
    test_invalid();
    test_alloc();
    CX_CHECK(cx_alloc_live() == live);
    return check_finish("mesh_rectangle");
}
