/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Boundary facets: consistent nodal forces of a surface traction and the
 * lumped facet measure. A facet is parametrised like an element of one
 * dimension less (2-node and 3-node edges on [-1, 1]; 3-node triangles on
 * the unit triangle; 4-node bilinear quadrilaterals on [-1, 1]^2) and
 * integrated with rules that are exact for an affine traction on a
 * straight facet: the integrand N_a t |x'| is then of degree <= 3 on
 * edges (2- and 3-point Gauss), 2 on triangles (3 points) and <= 3 per
 * variable on planar bilinear quadrilaterals (2 x 2 Gauss, |x_s x x_t|
 * being affine there). */
#include "fem/fem_impl.h"

#include <math.h>
#include <string.h>

#define G1 0.57735026918962576451   /* 1/sqrt(3) */
#define G3 0.77459666924148337704   /* sqrt(3/5) */

static const double e2_s[] = {-G1, G1}, e2_w[] = {1, 1};
static const double e3_s[] = {-G3, 0, G3}, e3_w[] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
static const double t3_s[] = {1.0 / 6, 1.0 / 6, 2.0 / 3, 1.0 / 6, 1.0 / 6, 2.0 / 3};
static const double t3_w[] = {1.0 / 6, 1.0 / 6, 1.0 / 6};
static const double q4_s[] = {-G1, -G1, G1, -G1, G1, G1, -G1, G1}, q4_w[] = {1, 1, 1, 1};

typedef struct facet_rule {
    int n, pdim;            /* points, parameter dimension */
    const double *s, *w;
} facet_rule;

static int facet_rule_of(int dim, int npf, facet_rule *r)
{
    if (dim == 2 && npf == 2)
        *r = (facet_rule){2, 1, e2_s, e2_w};
    else if (dim == 2 && npf == 3)
        *r = (facet_rule){3, 1, e3_s, e3_w};
    else if (dim == 3 && npf == 3)
        *r = (facet_rule){3, 2, t3_s, t3_w};
    else if (dim == 3 && npf == 4)
        *r = (facet_rule){4, 2, q4_s, q4_w};
    else
        return CX_EINVAL;
    return CX_OK;
}

/* Shape values N at parameter s, the point x and the measure factor
 * |dx/ds| (edges) or |x_s x x_t| (faces). */
static void facet_eval(int dim, int npf, const double *xf, const double *s, double *N,
                       double *x, double *ds)
{
    double dN[2 * 4];
    if (dim == 2 && npf == 2) {
        N[0] = 0.5 * (1 - s[0]), N[1] = 0.5 * (1 + s[0]);
        dN[0] = -0.5, dN[1] = 0.5;
    } else if (dim == 2) {
        /* ends, then the middle node */
        N[0] = 0.5 * s[0] * (s[0] - 1), N[1] = 0.5 * s[0] * (s[0] + 1), N[2] = 1 - s[0] * s[0];
        dN[0] = s[0] - 0.5, dN[1] = s[0] + 0.5, dN[2] = -2 * s[0];
    } else if (npf == 3) {
        N[0] = 1 - s[0] - s[1], N[1] = s[0], N[2] = s[1];
        dN[0] = -1, dN[1] = -1, dN[2] = 1, dN[3] = 0, dN[4] = 0, dN[5] = 1;
    } else {
        static const double c[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (int a = 0; a < 4; a++) {
            double fs = 1 + c[a][0] * s[0], ft = 1 + c[a][1] * s[1];
            N[a] = 0.25 * fs * ft;
            dN[2 * a] = 0.25 * c[a][0] * ft;
            dN[2 * a + 1] = 0.25 * fs * c[a][1];
        }
    }
    int pd = dim - 1;
    double T[2][3] = {{0}};
    for (int k = 0; k < dim; k++)
        x[k] = 0;
    for (int a = 0; a < npf; a++)
        for (int k = 0; k < dim; k++) {
            x[k] += N[a] * xf[dim * a + k];
            for (int p = 0; p < pd; p++)
                T[p][k] += dN[pd * a + p] * xf[dim * a + k];
        }
    if (dim == 2) {
        *ds = hypot(T[0][0], T[0][1]);
    } else {
        double n0 = T[0][1] * T[1][2] - T[0][2] * T[1][1];
        double n1 = T[0][2] * T[1][0] - T[0][0] * T[1][2];
        double n2 = T[0][0] * T[1][1] - T[0][1] * T[1][0];
        *ds = sqrt(n0 * n0 + n1 * n1 + n2 * n2);
    }
}

int cx_fem_facet_traction(int dim, int npf, const double *xf, const cx_traction *t, double *fe)
{
    facet_rule r;
    CX_TRY(facet_rule_of(dim, npf, &r));
    memset(fe, 0, sizeof(double) * (size_t)(dim * npf));
    for (int q = 0; q < r.n; q++) {
        double N[4], x[3], ds, tq[3];
        facet_eval(dim, npf, xf, r.s + r.pdim * q, N, x, &ds);
        for (int i = 0; i < dim; i++) {
            tq[i] = t->t0[i];
            for (int k = 0; k < dim; k++)
                tq[i] += t->G[dim * i + k] * x[k];
        }
        for (int a = 0; a < npf; a++)
            for (int i = 0; i < dim; i++)
                fe[dim * a + i] += r.w[q] * ds * N[a] * tq[i];
    }
    return CX_OK;
}

void cx_fem_facet_lumped(int dim, int npf, const double *xf, double *w)
{
    facet_rule r;
    if (facet_rule_of(dim, npf, &r))
        return;
    for (int a = 0; a < npf; a++)
        w[a] = 0;
    for (int q = 0; q < r.n; q++) {
        double N[4], x[3], ds;
        facet_eval(dim, npf, xf, r.s + r.pdim * q, N, x, &ds);
        for (int a = 0; a < npf; a++)
            w[a] += r.w[q] * ds * N[a];
    }
}
