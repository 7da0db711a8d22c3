/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Loads: consistent nodal forces of surface tractions and body forces.
 *  - a constant traction over a boundary gives traction * length (area);
 *  - an affine traction t = t0 + G x gives the closed-form total force and
 *    moment (first and second moments of the facet), on single slanted
 *    facets of every kind and over whole sides of distorted meshes;
 *  - a planar non-parallelogram bilinear face agrees with its two triangles;
 *  - lumped weights sum to the length/area, TRI6 edges 1/6, 4/6, 1/6;
 *  - body force totals are b * area/volume on distorted meshes (also curved
 *    TRI6), and the Hertz TRI6 area tends to pi R^2 / 4. */
#include "fem/fem.h"
#include "fem_fixture.h"
#include "check.h"

#include <stdio.h>

/* Moments of a facet (or a union of them): m0 = measure, m1[k] = int x_k,
 * m2[k][l] = int x_k x_l. */
typedef struct moments {
    double m0, m1[3], m2[3][3];
} moments;

static void mom_add(moments *s, const moments *a)
{
    s->m0 += a->m0;
    for (int k = 0; k < 3; k++) {
        s->m1[k] += a->m1[k];
        for (int l = 0; l < 3; l++)
            s->m2[k][l] += a->m2[k][l];
    }
}

/* segment p-q in 2D: int x_k x_l = L ((p_k p_l + q_k q_l)/3 + (p_k q_l + q_k p_l)/6) */
static moments mom_segment(const double *p, const double *q)
{
    moments s = {0};
    s.m0 = hypot(q[0] - p[0], q[1] - p[1]);
    for (int k = 0; k < 2; k++) {
        s.m1[k] = s.m0 * 0.5 * (p[k] + q[k]);
        for (int l = 0; l < 2; l++)
            s.m2[k][l] = s.m0 * ((p[k] * p[l] + q[k] * q[l]) / 3 + (p[k] * q[l] + q[k] * p[l]) / 6);
    }
    return s;
}

/* triangle in 3D: int lambda_i lambda_j = A (1 + delta_ij) / 12, so
 * int x_k x_l = A/12 (sum_a x_ak x_al + s_k s_l) with s = sum of vertices */
static moments mom_triangle(const double *a, const double *b, const double *c)
{
    moments s = {0};
    double u[3], v[3], n[3], sum[3];
    for (int k = 0; k < 3; k++)
        u[k] = b[k] - a[k], v[k] = c[k] - a[k], sum[k] = a[k] + b[k] + c[k];
    n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
    s.m0 = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) {
        s.m1[k] = s.m0 * sum[k] / 3;
        for (int l = 0; l < 3; l++)
            s.m2[k][l] = s.m0 / 12 * (a[k] * a[l] + b[k] * b[l] + c[k] * c[l] + sum[k] * sum[l]);
    }
    return s;
}

/* Axis-aligned side {x_a = c, lo <= x <= hi elsewhere}: a product of 1D
 * moments (1, c, c^2 on the fixed axis). */
static moments mom_box_side(int dim, int a, double c, const double *lo, const double *hi)
{
    double p0[3], p1[3], p2[3];
    for (int k = 0; k < dim; k++) {
        if (k == a)
            p0[k] = 1, p1[k] = c, p2[k] = c * c;
        else
            p0[k] = hi[k] - lo[k], p1[k] = (hi[k] * hi[k] - lo[k] * lo[k]) / 2,
            p2[k] = (hi[k] * hi[k] * hi[k] - lo[k] * lo[k] * lo[k]) / 3;
    }
    moments s = {0};
    s.m0 = 1;
    for (int k = 0; k < dim; k++)
        s.m0 *= p0[k];
    for (int k = 0; k < dim; k++)
        for (int l = 0; l < dim; l++) {
            double v = 1;
            for (int j = 0; j < dim; j++)
                v *= (j == k && j == l) ? p2[j] : (j == k || j == l) ? p1[j] : p0[j];
            s.m2[k][l] = v;
        }
    for (int k = 0; k < dim; k++) {
        double v = 1;
        for (int j = 0; j < dim; j++)
            v *= j == k ? p1[j] : p0[j];
        s.m1[k] = v;
    }
    return s;
}

/* F_i = t0_i m0 + G_ik m1_k; X[j][i] = int x_j t_i = t0_i m1_j + G_ik m2_jk */
static void exact_loads(int dim, const cx_traction *t, const moments *s, double *F, double X[3][3])
{
    for (int i = 0; i < dim; i++) {
        F[i] = t->t0[i] * s->m0;
        for (int k = 0; k < dim; k++)
            F[i] += t->G[dim * i + k] * s->m1[k];
        for (int j = 0; j < dim; j++) {
            X[j][i] = t->t0[i] * s->m1[j];
            for (int k = 0; k < dim; k++)
                X[j][i] += t->G[dim * i + k] * s->m2[j][k];
        }
    }
}

/* the same from nodal forces f at nodes x (n nodes) */
static void nodal_loads(int dim, int n, const double *x, const double *f, double *F, double X[3][3])
{
    for (int i = 0; i < dim; i++) {
        F[i] = 0;
        for (int j = 0; j < dim; j++)
            X[j][i] = 0;
    }
    for (int a = 0; a < n; a++)
        for (int i = 0; i < dim; i++) {
            F[i] += f[dim * a + i];
            for (int j = 0; j < dim; j++)
                X[j][i] += x[dim * a + j] * f[dim * a + i];
        }
}

static void check_loads(int dim, const double *F, double X[3][3], const double *Fe, double Xe[3][3],
                        double scale)
{
    for (int i = 0; i < dim; i++) {
        CX_CHECK_NEAR(F[i], Fe[i], 1e-13, 1e-14 * scale);
        for (int j = 0; j < dim; j++)
            CX_CHECK_NEAR(X[j][i], Xe[j][i], 1e-13, 1e-14 * scale);
    }
}

static const cx_traction trac2 = {.t0 = {3, -4}, .G = {0.5, -1.5, 2, 0.25}};
static const cx_traction trac3 = {.t0 = {3, -4, 1}, .G = {0.5, -1.5, 2, 0.25, 1, -1, 0.3, 0.7, -0.2}};

static void test_single_facets(void)
{
    double F[3], X[3][3], Fe[3], Xe[3][3], fe[12], w[4];

    /* 2-node and 3-node slanted edges */
    double p[2] = {0.3, -0.2}, q[2] = {1.1, 0.9};
    double e2[4] = {p[0], p[1], q[0], q[1]};
    double e3[6] = {p[0], p[1], q[0], q[1], 0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])};
    moments s = mom_segment(p, q);
    exact_loads(2, &trac2, &s, Fe, Xe);
    CX_CHECK_OK(cx_fem_facet_traction(2, 2, e2, &trac2, fe));
    nodal_loads(2, 2, e2, fe, F, X);
    check_loads(2, F, X, Fe, Xe, 10);
    CX_CHECK_OK(cx_fem_facet_traction(2, 3, e3, &trac2, fe));
    nodal_loads(2, 3, e3, fe, F, X);
    check_loads(2, F, X, Fe, Xe, 10);
    cx_fem_facet_lumped(2, 2, e2, w);
    CX_CHECK_NEAR(w[0], s.m0 / 2, 1e-15, 0);
    CX_CHECK_NEAR(w[1], s.m0 / 2, 1e-15, 0);
    cx_fem_facet_lumped(2, 3, e3, w);
    CX_CHECK_NEAR(w[0], s.m0 / 6, 1e-15, 0);
    CX_CHECK_NEAR(w[1], s.m0 / 6, 1e-15, 0);
    CX_CHECK_NEAR(w[2], 4 * s.m0 / 6, 1e-15, 0);

    /* a slanted triangle */
    double t3[9] = {0.1, 0.2, 0.3, 1.4, -0.1, 0.8, 0.5, 1.3, -0.4};
    s = mom_triangle(t3, t3 + 3, t3 + 6);
    exact_loads(3, &trac3, &s, Fe, Xe);
    CX_CHECK_OK(cx_fem_facet_traction(3, 3, t3, &trac3, fe));
    nodal_loads(3, 3, t3, fe, F, X);
    check_loads(3, F, X, Fe, Xe, 10);
    cx_fem_facet_lumped(3, 3, t3, w);
    for (int a = 0; a < 3; a++)
        CX_CHECK_NEAR(w[a], s.m0 / 3, 1e-15, 0);

    /* a planar general quadrilateral on z = 0.1 x + 0.3 y: the same as its
     * two triangles (2 x 2 Gauss is exact on the bilinear map) */
    double xy[4][2] = {{0, 0}, {2, 0}, {1.5, 1}, {0.3, 1.2}}, q4[12];
    for (int a = 0; a < 4; a++)
        q4[3 * a] = xy[a][0], q4[3 * a + 1] = xy[a][1], q4[3 * a + 2] = 0.1 * xy[a][0] + 0.3 * xy[a][1];
    s = mom_triangle(q4, q4 + 3, q4 + 6);
    moments s2 = mom_triangle(q4, q4 + 6, q4 + 9);
    mom_add(&s, &s2);
    exact_loads(3, &trac3, &s, Fe, Xe);
    CX_CHECK_OK(cx_fem_facet_traction(3, 4, q4, &trac3, fe));
    nodal_loads(3, 4, q4, fe, F, X);
    check_loads(3, F, X, Fe, Xe, 10);
    cx_fem_facet_lumped(3, 4, q4, w);
    CX_CHECK_NEAR(w[0] + w[1] + w[2] + w[3], s.m0, 1e-14, 0);
    double sq[12] = {0, 0, 1, 2, 0, 1, 2, 3, 1, 0, 3, 1};
    cx_fem_facet_lumped(3, 4, sq, w);
    for (int a = 0; a < 4; a++)
        CX_CHECK_NEAR(w[a], 1.5, 1e-15, 0);

    CX_CHECK(cx_fem_facet_traction(2, 4, q4, &trac2, fe) == CX_EINVAL);
    CX_CHECK(cx_fem_facet_traction(3, 2, q4, &trac3, fe) == CX_EINVAL);
}

/* Constant and affine tractions over whole sides of the distorted meshes,
 * through cx_fem_add_traction, and the lumped weights over the side. */
static void test_sides(cx_elem_type t)
{
    cx_mesh *m = fx_mesh(t, 1);
    CX_CHECK(m != NULL);
    if (!m)
        return;
    int dim = m->dim, nall = dim * m->nnodes;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 2, 1.5};
    if (dim == 2)
        hi[0] = 2, hi[1] = 1.5;
    static const char *names2[] = {"bottom", "right", "top", "left"};
    static const char *names3[] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
    double *f = calloc((size_t)nall, sizeof(double));
    for (int s = 0; s < (dim == 2 ? 4 : 6); s++) {
        int axis = dim == 2 ? (s % 2 ? 0 : 1) : s / 2;
        int at_hi = dim == 2 ? (s == 1 || s == 2) : s % 2;
        const cx_boundary *b = cx_mesh_boundary(m, dim == 2 ? names2[s] : names3[s]);
        CX_CHECK(b != NULL);
        if (!b)
            continue;
        moments mo = mom_box_side(dim, axis, at_hi ? hi[axis] : lo[axis], lo, hi);

        /* constant */
        cx_traction tc = {.t0 = {3, -4, 1}};
        memset(f, 0, sizeof(double) * (size_t)nall);
        CX_CHECK_OK(cx_fem_add_traction(m, b, &tc, f));
        for (int i = 0; i < dim; i++) {
            double tot = 0;
            for (int k = 0; k < m->nnodes; k++)
                tot += f[dim * k + i];
            CX_CHECK_NEAR(tot, tc.t0[i] * mo.m0, 1e-14, 1e-14);
        }
        /* affine */
        const cx_traction *ta = dim == 2 ? &trac2 : &trac3;
        double F[3], X[3][3], Fe[3], Xe[3][3];
        memset(f, 0, sizeof(double) * (size_t)nall);
        CX_CHECK_OK(cx_fem_add_traction(m, b, ta, f));
        nodal_loads(dim, m->nnodes, m->x, f, F, X);
        exact_loads(dim, ta, &mo, Fe, Xe);
        check_loads(dim, F, X, Fe, Xe, 10);
        /* lumped weights over the side */
        double wsum = 0, w[4], xf[12];
        for (int k = 0; k < b->nfacets; k++) {
            for (int a = 0; a < b->npf; a++)
                memcpy(xf + dim * a, m->x + dim * b->facets[b->npf * k + a], sizeof(double) * (size_t)dim);
            cx_fem_facet_lumped(dim, b->npf, xf, w);
            for (int a = 0; a < b->npf; a++)
                wsum += w[a];
        }
        CX_CHECK_NEAR(wsum, mo.m0, 1e-14, 0);
    }
    free(f);
    cx_mesh_destroy(&m);
}

static void test_body_force(cx_elem_type t, int straight)
{
    cx_mesh *m = fx_mesh(t, straight);
    CX_CHECK(m != NULL);
    if (!m)
        return;
    int dim = m->dim, nall = dim * m->nnodes;
    double b[3] = {1.5, -2, 0.5}, measure = 3.0;   /* 2 x 1.5, and 1 x 2 x 1.5 */
    double *f = calloc((size_t)nall, sizeof(double));
    CX_CHECK_OK(cx_fem_add_body_force(m, b, f));
    for (int i = 0; i < dim; i++) {
        double tot = 0;
        for (int k = 0; k < m->nnodes; k++)
            tot += f[dim * k + i];
        CX_CHECK_NEAR(tot, b[i] * measure, 1e-14, 0);
    }
    free(f);
    cx_mesh_destroy(&m);
}

static double hertz_area(cx_elem_type t, int N, double R)
{
    cx_mesh *m = NULL;
    double b[2] = {1, 0}, area = 0;
    if (cx_mesh_hertz(&m, R, N, t, NULL))
        return NAN;
    double *f = calloc((size_t)(2 * m->nnodes), sizeof(double));
    if (cx_fem_add_body_force(m, b, f) == CX_OK)
        for (int k = 0; k < m->nnodes; k++)
            area += f[2 * k];
    free(f);
    cx_mesh_destroy(&m);
    return area;
}

static void test_hertz_area(void)
{
    double R = 2, exact = CX_PI * R * R / 4;
    double e3 = fabs(hertz_area(CX_EL_TRI3, 16, R) - exact) / exact;
    double e6 = fabs(hertz_area(CX_EL_TRI6, 16, R) - exact) / exact;
    double e6f = fabs(hertz_area(CX_EL_TRI6, 32, R) - exact) / exact;
    fprintf(stderr, "hertz area errors: tri3 N=16 %.2e, tri6 N=16 %.2e, tri6 N=32 %.2e\n", e3, e6, e6f);
    CX_CHECK_LE(e3, 1e-3);
    /* curved P2 edges: fourth order in h, against second for chords */
    CX_CHECK_LE(e6, e3 / 100);
    CX_CHECK_LE(e6f, e6 / 10);
}

int main(void)
{
    long live = cx_alloc_live();
    test_single_facets();
    cx_elem_type types[5] = {CX_EL_TRI3, CX_EL_TRI6, CX_EL_QUAD4, CX_EL_HEX8, CX_EL_TET4};
    for (int k = 0; k < 5; k++) {
        test_sides(types[k]);
        test_body_force(types[k], 1);
    }
    test_body_force(CX_EL_TRI6, 0);
    test_hertz_area();
    CX_CHECK(cx_alloc_live() == live);
    return check_finish("fem_loads");
}
