/* SPDX-License-Identifier: GPL-3.0-or-later */
/* mesh/hertz.c: counts; the origin is a node; "arc" and "side" nodes on the
 * circle x^2 + (y-R)^2 = R^2 to 1e-12 R; "top" at y = R, "axis" at x = 0;
 * the arc runs from the origin to the 45 degree point, "quarter" (arc then
 * side) on to (R, R); positive elements and
 * outward facets (also against the circle's centre); the area tends to
 * pi R^2 / 4 (N = 64 within 1e-3, and decreasing error); validation and
 * allocation failures. */
#include "mesh/mesh.h"
#include "mesh_check.h"
#include "check.h"

#include <string.h>

static void test_geometry(cx_elem_type t, int N, double R)
{
    cx_mesh *m = NULL;
    cx_diag d;
    CX_CHECK_OK(cx_mesh_hertz(&m, R, N, t, &d));
    if (!m)
        return;
    int q = t == CX_EL_TRI6 ? 2 : 1, per_cell = t == CX_EL_QUAD4 ? 1 : 2;
    CX_CHECK(m->dim == 2 && m->nnodes == (q * N + 1) * (q * N + 1));
    CX_CHECK(m->nelems == per_cell * N * N && m->nbounds == 5);
    CX_CHECK(mc_all_nodes_used(m));

    int origin = 0;
    for (int k = 0; k < m->nnodes; k++)
        origin += m->x[2 * k] == 0 && m->x[2 * k + 1] == 0;
    CX_CHECK(origin == 1);
    /* lattice node (I = 0, J = qN) is the origin exactly */
    CX_CHECK(m->x[2 * (q * N * (q * N + 1))] == 0 && m->x[2 * (q * N * (q * N + 1)) + 1] == 0);

    int bad_elems = 0;
    for (int e = 0; e < m->nelems; e++)
        bad_elems += !(mc_min_corner(m, e) > 0);
    CX_CHECK(bad_elems == 0);

    static const char *sides[] = {"top", "side", "arc", "axis"};
    for (int s = 0; s < 4; s++) {
        const cx_boundary *b = cx_mesh_boundary(m, sides[s]);
        CX_CHECK(b != NULL);
        if (!b)
            continue;
        CX_CHECK(b->nfacets == N && b->npf == (q == 2 ? 3 : 2));
        CX_CHECK(mc_bad_facets(m, b) == 0);
        double worst = 0;
        for (int k = 0; k < b->nfacets * b->npf; k++) {
            const double *x = m->x + 2 * b->facets[k];
            if (s == 0)
                worst = fmax(worst, fabs(x[1] - R));
            else if (s == 3)
                worst = fmax(worst, fabs(x[0]));
            else
                worst = fmax(worst, fabs(hypot(x[0], x[1] - R) - R));
        }
        CX_CHECK_NEAR(worst, 0, 0, 1e-12 * R);
    }

    /* the arc: from the origin, each facet's end is the next facet's start,
     * to (R/sqrt2, R - R/sqrt2); its outward normals point away from the
     * centre (0, R) */
    const cx_boundary *arc = cx_mesh_boundary(m, "arc");
    const int npf = arc->npf;
    CX_CHECK(arc->facets[0] == q * N * (q * N + 1));
    for (int f = 0; f + 1 < arc->nfacets; f++)
        CX_CHECK(arc->facets[npf * f + 1] == arc->facets[npf * (f + 1)]);
    const double *end = m->x + 2 * arc->facets[npf * (N - 1) + 1];
    CX_CHECK_NEAR(end[0], R / sqrt(2), 1e-15, 0);
    CX_CHECK_NEAR(end[1], R - R / sqrt(2), 1e-14, 0);
    int inward = 0;
    for (int f = 0; f < arc->nfacets; f++) {
        const double *a = m->x + 2 * arc->facets[npf * f], *b = m->x + 2 * arc->facets[npf * f + 1];
        double n[2] = {b[1] - a[1], -(b[0] - a[0])};
        double mid[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]) - R};
        inward += !(n[0] * mid[0] + n[1] * mid[1] > 0);
    }
    CX_CHECK(inward == 0);
    /* "quarter": arc then side, one chain from the origin to (R, R) */
    const cx_boundary *qb = cx_mesh_boundary(m, "quarter");
    CX_CHECK(qb != NULL && qb->nfacets == 2 * N && qb->npf == npf);
    if (qb) {
        CX_CHECK(qb->facets[0] == q * N * (q * N + 1));
        for (int f = 0; f + 1 < qb->nfacets; f++)
            CX_CHECK(qb->facets[npf * f + 1] == qb->facets[npf * (f + 1)]);
        const double *top = m->x + 2 * qb->facets[npf * (2 * N - 1) + 1];
        CX_CHECK_NEAR(top[0], R, 1e-14, 0);
        CX_CHECK_NEAR(top[1], R, 1e-14, 0);
        CX_CHECK(mc_bad_facets(m, qb) == 0);
    }
    cx_mesh_destroy(&m);
}

static double area_error(cx_elem_type t, int N)
{
    cx_mesh *m = NULL;
    double R = 3;
    if (cx_mesh_hertz(&m, R, N, t, NULL))
        return INFINITY;
    double exact = CX_PI * R * R / 4, err = fabs(mc_measure(m) - exact) / exact;
    cx_mesh_destroy(&m);
    return err;
}

static void test_area(void)
{
    cx_elem_type types[] = {CX_EL_TRI3, CX_EL_QUAD4};
    for (int k = 0; k < 2; k++) {
        double e4 = area_error(types[k], 4), e16 = area_error(types[k], 16), e64 = area_error(types[k], 64);
        CX_CHECK_LE(e64, 1e-3);
        /* second order in h: the chords of the arc */
        CX_CHECK_LE(e16, e4 / 10);
        CX_CHECK_LE(e64, e16 / 10);
    }
}

static void test_invalid(void)
{
    cx_mesh *m = NULL;
    cx_diag d;
    CX_CHECK(cx_mesh_hertz(&m, 1, 0, CX_EL_TRI3, &d) == CX_EINVAL && m == NULL);
    CX_CHECK(strstr(d.msg, "level") != NULL);
    CX_CHECK(cx_mesh_hertz(&m, 0, 4, CX_EL_TRI3, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "radius") != NULL);
    CX_CHECK(cx_mesh_hertz(&m, -1, 4, CX_EL_TRI3, &d) == CX_EINVAL);
    CX_CHECK(cx_mesh_hertz(&m, INFINITY, 4, CX_EL_TRI3, &d) == CX_EINVAL);
    CX_CHECK(cx_mesh_hertz(&m, 1, 4, CX_EL_TET4, &d) == CX_EINVAL && m == NULL);
    CX_CHECK(strstr(d.msg, "tet4") != NULL);
}

static void test_alloc(void)
{
    int points;
    MC_ALLOC_LOOP(points, cx_mesh_hertz(&am_, 2, 3, CX_EL_TRI6, NULL));
    CX_CHECK(points > 5);
}

int main(void)
{
    long live = cx_alloc_live();
    cx_elem_type types[] = {CX_EL_TRI3, CX_EL_TRI6, CX_EL_QUAD4};
    for (int k = 0; k < 3; k++) {
        test_geometry(types[k], 1, 2.5);
        test_geometry(types[k], 5, 8);
    }
    test_area();
    test_invalid();
    test_alloc();
    CX_CHECK(cx_alloc_live() == live);
    return check_finish("mesh_hertz");
}
