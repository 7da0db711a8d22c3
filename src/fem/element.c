/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Element kernels: reference shape functions and quadrature for TRI3,
 * TRI6, QUAD4, HEX8 and TET4, and the element stiffness and body force.
 * Pure functions of the element's coordinates and material: no global
 * numbering here (STYLE C11). Every element is isoparametric.
 *
 * Quadrature: TRI3 and TET4 one point (constant B); TRI6 the 3-point
 * degree-2 rule (B'DB is quadratic on a straight-sided P2 triangle);
 * QUAD4 2x2 and HEX8 2x2x2 Gauss. For straight edges / affine elements the
 * stiffness is exact, and for every element (also curved P2 and distorted
 * Q1) the rule integrates cof(J) grad N, the integrand of the constant-
 * stress residual, exactly, which is what makes the patch test pass.
 *
 * The shape functions are evaluated once per element type (cx_fem_ref):
 * the per-element work is the Jacobian, its inverse and B'DB. */
#include "fem/element_impl.h"

#include <string.h>

/* ---- reference elements ------------------------------------------------ */

static const double ref_tri3[] = {0, 0, 1, 0, 0, 1};
static const double ref_tri6[] = {0, 0, 1, 0, 0, 1, 0.5, 0, 0.5, 0.5, 0, 0.5};
static const double ref_quad4[] = {-1, -1, 1, -1, 1, 1, -1, 1};
static const double ref_hex8[] = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                                  -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
static const double ref_tet4[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};

static const double *ref_nodes(cx_elem_type t)
{
    switch (t) {
    case CX_EL_TRI3: return ref_tri3;
    case CX_EL_TRI6: return ref_tri6;
    case CX_EL_QUAD4: return ref_quad4;
    case CX_EL_HEX8: return ref_hex8;
    case CX_EL_TET4: return ref_tet4;
    }
    return NULL;
}

#define G1 0.57735026918962576451   /* 1/sqrt(3): 2-point Gauss */

static const double q_tri1[] = {1.0 / 3, 1.0 / 3}, w_tri1[] = {0.5};
static const double q_tri3[] = {1.0 / 6, 1.0 / 6, 2.0 / 3, 1.0 / 6, 1.0 / 6, 2.0 / 3};
static const double w_tri3[] = {1.0 / 6, 1.0 / 6, 1.0 / 6};
static const double q_quad[] = {-G1, -G1, G1, -G1, G1, G1, -G1, G1};
static const double w_quad[] = {1, 1, 1, 1};
static const double q_hex[] = {-G1, -G1, -G1, G1, -G1, -G1, G1, G1, -G1, -G1, G1, -G1,
                               -G1, -G1, G1,  G1, -G1, G1,  G1, G1, G1,  -G1, G1, G1};
static const double w_hex[] = {1, 1, 1, 1, 1, 1, 1, 1};
static const double q_tet1[] = {0.25, 0.25, 0.25}, w_tet1[] = {1.0 / 6};

static int rule(cx_elem_type t, const double **xi, const double **w)
{
    switch (t) {
    case CX_EL_TRI3: *xi = q_tri1, *w = w_tri1; return 1;
    case CX_EL_TRI6: *xi = q_tri3, *w = w_tri3; return 3;
    case CX_EL_QUAD4: *xi = q_quad, *w = w_quad; return 4;
    case CX_EL_HEX8: *xi = q_hex, *w = w_hex; return 8;
    case CX_EL_TET4: *xi = q_tet1, *w = w_tet1; return 1;
    }
    *xi = *w = NULL;
    return 0;
}

/* N and reference gradients dN (npe x dim) at xi. */
static void shape(cx_elem_type t, const double *xi, double *N, double *dN)
{
    switch (t) {
    case CX_EL_TRI3:
        N[0] = 1 - xi[0] - xi[1], N[1] = xi[0], N[2] = xi[1];
        dN[0] = -1, dN[1] = -1, dN[2] = 1, dN[3] = 0, dN[4] = 0, dN[5] = 1;
        break;
    case CX_EL_TRI6: {
        /* barycentric L0, L1, L2; vertices L(2L-1), mid-edges 4 La Lb */
        double L[3] = {1 - xi[0] - xi[1], xi[0], xi[1]};
        static const double dL[3][2] = {{-1, -1}, {1, 0}, {0, 1}};
        for (int a = 0; a < 3; a++) {
            int b = (a + 1) % 3;
            N[a] = L[a] * (2 * L[a] - 1);
            N[3 + a] = 4 * L[a] * L[b];
            for (int k = 0; k < 2; k++) {
                dN[2 * a + k] = (4 * L[a] - 1) * dL[a][k];
                dN[2 * (3 + a) + k] = 4 * (dL[a][k] * L[b] + L[a] * dL[b][k]);
            }
        }
        break;
    }
    case CX_EL_QUAD4:
        for (int a = 0; a < 4; a++) {
            double sx = ref_quad4[2 * a], sy = ref_quad4[2 * a + 1];
            double fx = 1 + sx * xi[0], fy = 1 + sy * xi[1];
            N[a] = 0.25 * fx * fy;
            dN[2 * a] = 0.25 * sx * fy;
            dN[2 * a + 1] = 0.25 * fx * sy;
        }
        break;
    case CX_EL_HEX8:
        for (int a = 0; a < 8; a++) {
            const double *s = ref_hex8 + 3 * a;
            double f[3] = {1 + s[0] * xi[0], 1 + s[1] * xi[1], 1 + s[2] * xi[2]};
            N[a] = 0.125 * f[0] * f[1] * f[2];
            dN[3 * a] = 0.125 * s[0] * f[1] * f[2];
            dN[3 * a + 1] = 0.125 * f[0] * s[1] * f[2];
            dN[3 * a + 2] = 0.125 * f[0] * f[1] * s[2];
        }
        break;
    case CX_EL_TET4:
        N[0] = 1 - xi[0] - xi[1] - xi[2], N[1] = xi[0], N[2] = xi[1], N[3] = xi[2];
        memset(dN, 0, 12 * sizeof(double));
        for (int k = 0; k < 3; k++) {
            dN[k] = -1;
            dN[3 * (k + 1) + k] = 1;
        }
        break;
    }
}

/* ---- the reference element of a type ------------------------------------ */

int cx_fem_ref_init(cx_fem_ref *r, cx_elem_type t)
{
    const double *xi, *w;
    memset(r, 0, sizeof *r);
    r->dim = cx_elem_dim(t);
    r->npe = cx_elem_npe(t);
    r->nq = rule(t, &xi, &w);
    if (!r->dim || !r->nq)
        return CX_EINVAL;
    r->t = t;
    r->affine = t == CX_EL_TRI3 || t == CX_EL_TET4;
    for (int q = 0; q < r->nq; q++) {
        r->w[q] = w[q];
        shape(t, xi + r->dim * q, r->Nq[q], r->dNq[q]);
    }
    const double *ref = ref_nodes(t);
    double N[CX_FEM_MAXNPE];
    for (int a = 0; a < r->npe; a++)
        shape(t, ref + r->dim * a, N, r->dNn[a]);
    return CX_OK;
}

/* ---- geometry ------------------------------------------------------------ */

int cx_fem_ref_node_gradients(const cx_fem_ref *r, const double *xe, int a, double *G)
{
    double lim = cx_fem_det_floor(r->dim, r->npe, xe);
    return cx_fem_jacobian(r->dim, r->npe, r->dNn[a], xe, G) > lim ? CX_OK : CX_ENUMERIC;
}

void cx_fem_strain_matrix(int dim, int npe, const double *G, double *B)
{
    int nd = dim * npe;
    memset(B, 0, sizeof(double) * (size_t)(cx_fem_nstress(dim) * nd));
    for (int a = 0; a < npe; a++) {
        const double *g = G + dim * a;
        if (dim == 2) {
            B[2 * a] = g[0];
            B[nd + 2 * a + 1] = g[1];
            B[2 * nd + 2 * a] = g[1], B[2 * nd + 2 * a + 1] = g[0];
        } else {
            for (int i = 0; i < 3; i++)
                B[i * nd + 3 * a + i] = g[i];
            B[3 * nd + 3 * a + 1] = g[2], B[3 * nd + 3 * a + 2] = g[1];   /* yz */
            B[4 * nd + 3 * a] = g[2], B[4 * nd + 3 * a + 2] = g[0];       /* xz */
            B[5 * nd + 3 * a] = g[1], B[5 * nd + 3 * a + 1] = g[0];       /* xy */
        }
    }
}

/* ---- kernels ------------------------------------------------------------- */

int cx_fem_ref_stiffness(const cx_fem_ref *r, const double *xe, const double *D, double *Ke)
{
    switch (r->t) {
    case CX_EL_TRI3: return cx_fem_stiffness_kernel(2, 3, 1, 1, r, xe, D, Ke);
    case CX_EL_TRI6: return cx_fem_stiffness_kernel(2, 6, 3, 0, r, xe, D, Ke);
    case CX_EL_QUAD4: return cx_fem_stiffness_kernel(2, 4, 4, 0, r, xe, D, Ke);
    case CX_EL_HEX8: return cx_fem_stiffness_kernel(3, 8, 8, 0, r, xe, D, Ke);
    case CX_EL_TET4: return cx_fem_stiffness_kernel(3, 4, 1, 1, r, xe, D, Ke);
    }
    return CX_EINVAL;
}

int cx_fem_ref_body_force(const cx_fem_ref *r, const double *xe, const double *b, double *fe)
{
    int dim = r->dim, npe = r->npe;
    double lim = cx_fem_det_floor(dim, npe, xe);
    memset(fe, 0, sizeof(double) * (size_t)(dim * npe));
    if (!r->affine && cx_fem_check_nodes(dim, npe, r, xe, lim))
        return CX_ENUMERIC;
    for (int q = 0; q < r->nq; q++) {
        double det = cx_fem_jacobian(dim, npe, r->dNq[q], xe, NULL);
        if (!(det > lim))
            return CX_ENUMERIC;
        for (int a = 0; a < npe; a++)
            for (int c = 0; c < dim; c++)
                fe[dim * a + c] += r->w[q] * det * r->Nq[q][a] * b[c];
    }
    return CX_OK;
}

int cx_fem_element_stiffness(cx_elem_type t, const double *xe, const double *D, double *Ke)
{
    cx_fem_ref r;
    CX_TRY(cx_fem_ref_init(&r, t));
    return cx_fem_ref_stiffness(&r, xe, D, Ke);
}

int cx_fem_element_body_force(cx_elem_type t, const double *xe, const double *b, double *fe)
{
    cx_fem_ref r;
    CX_TRY(cx_fem_ref_init(&r, t));
    return cx_fem_ref_body_force(&r, xe, b, fe);
}
