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
 * stress residual, exactly, which is what makes the patch test pass. */
#include "fem/fem_impl.h"

#include <math.h>
#include <string.h>

/* ---- reference elements ------------------------------------------------ */

static const double ref_tri3[] = {0, 0, 1, 0, 0, 1};
static const double ref_tri6[] = {0, 0, 1, 0, 0, 1, 0.5, 0, 0.5, 0.5, 0, 0.5};
static const double ref_quad4[] = {-1, -1, 1, -1, 1, 1, -1, 1};
static const double ref_hex8[] = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                                  -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
static const double ref_tet4[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};

const double *cx_fem_ref_nodes(cx_elem_type t)
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

int cx_fem_rule(cx_elem_type t, const double **xi, const double **w)
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

/* ---- geometry ------------------------------------------------------------ */

/* The size below which det J counts as zero: rounding of an exactly
 * degenerate element leaves ~1e-16 h^dim, never exactly 0. */
static double det_floor(int dim, int npe, const double *xe)
{
    double h = 0;
    for (int k = 0; k < dim; k++) {
        double lo = xe[k], hi = xe[k];
        for (int a = 1; a < npe; a++) {
            lo = fmin(lo, xe[dim * a + k]);
            hi = fmax(hi, xe[dim * a + k]);
        }
        h = fmax(h, hi - lo);
    }
    return 1e-12 * pow(h, dim);
}

int cx_fem_eval(cx_elem_type t, const double *xe, const double *xi, double *N, double *G,
                double *detJ)
{
    int dim = cx_elem_dim(t), npe = cx_elem_npe(t);
    double dN[3 * CX_FEM_MAXNPE], J[9] = {0}, Ji[9];
    if (!dim)
        return CX_EINVAL;
    shape(t, xi, N, dN);
    /* J[i][k] = dx_i / dxi_k */
    for (int a = 0; a < npe; a++)
        for (int i = 0; i < dim; i++)
            for (int k = 0; k < dim; k++)
                J[dim * i + k] += xe[dim * a + i] * dN[dim * a + k];
    double det;
    if (dim == 2) {
        det = J[0] * J[3] - J[1] * J[2];
        Ji[0] = J[3] / det, Ji[1] = -J[1] / det;
        Ji[2] = -J[2] / det, Ji[3] = J[0] / det;
    } else {
        double c00 = J[4] * J[8] - J[5] * J[7], c01 = J[5] * J[6] - J[3] * J[8],
               c02 = J[3] * J[7] - J[4] * J[6];
        det = J[0] * c00 + J[1] * c01 + J[2] * c02;
        Ji[0] = c00 / det;
        Ji[1] = (J[2] * J[7] - J[1] * J[8]) / det;
        Ji[2] = (J[1] * J[5] - J[2] * J[4]) / det;
        Ji[3] = c01 / det;
        Ji[4] = (J[0] * J[8] - J[2] * J[6]) / det;
        Ji[5] = (J[2] * J[3] - J[0] * J[5]) / det;
        Ji[6] = c02 / det;
        Ji[7] = (J[1] * J[6] - J[0] * J[7]) / det;
        Ji[8] = (J[0] * J[4] - J[1] * J[3]) / det;
    }
    *detJ = det;
    if (!(det > det_floor(dim, npe, xe)))
        return CX_ENUMERIC;
    /* grad N_a = J^-T dN_a: G[a][i] = sum_k dN[a][k] Ji[k][i] */
    for (int a = 0; a < npe; a++)
        for (int i = 0; i < dim; i++) {
            double s = 0;
            for (int k = 0; k < dim; k++)
                s += dN[dim * a + k] * Ji[dim * k + i];
            G[dim * a + i] = s;
        }
    return CX_OK;
}

/* det J > 0 at every node as well as at the quadrature points: a
 * non-convex quadrilateral or a folded hexahedron can pass at the Gauss
 * points and still be inverted near a corner. */
static int check_nodes(cx_elem_type t, const double *xe)
{
    int dim = cx_elem_dim(t), npe = cx_elem_npe(t);
    const double *ref = cx_fem_ref_nodes(t);
    double N[CX_FEM_MAXNPE], G[3 * CX_FEM_MAXNPE], det;
    for (int a = 0; a < npe; a++)
        CX_TRY(cx_fem_eval(t, xe, ref + dim * a, N, G, &det));
    return CX_OK;
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

int cx_fem_element_stiffness(cx_elem_type t, const double *xe, const double *D, double *Ke)
{
    int dim = cx_elem_dim(t), npe = cx_elem_npe(t);
    if (!dim)
        return CX_EINVAL;
    int nd = dim * npe, ns = cx_fem_nstress(dim);
    const double *xi, *w;
    int nq = cx_fem_rule(t, &xi, &w);
    double N[CX_FEM_MAXNPE], G[3 * CX_FEM_MAXNPE], B[6 * CX_FEM_MAXDOF], DB[6 * CX_FEM_MAXDOF];

    memset(Ke, 0, sizeof(double) * (size_t)(nd * nd));
    CX_TRY(check_nodes(t, xe));
    for (int q = 0; q < nq; q++) {
        double det;
        CX_TRY(cx_fem_eval(t, xe, xi + dim * q, N, G, &det));
        cx_fem_strain_matrix(dim, npe, G, B);
        double s = w[q] * det;
        for (int r = 0; r < ns; r++)
            for (int j = 0; j < nd; j++) {
                double v = 0;
                for (int k = 0; k < ns; k++)
                    v += D[ns * r + k] * B[nd * k + j];
                DB[nd * r + j] = s * v;
            }
        /* the upper triangle, mirrored below: Ke is then exactly symmetric
         * (summing B'(DB) both ways round would differ in rounding) */
        for (int i = 0; i < nd; i++)
            for (int j = i; j < nd; j++) {
                double v = 0;
                for (int k = 0; k < ns; k++)
                    v += B[nd * k + i] * DB[nd * k + j];
                Ke[nd * i + j] += v;
            }
    }
    for (int i = 0; i < nd; i++)
        for (int j = 0; j < i; j++)
            Ke[nd * i + j] = Ke[nd * j + i];
    return CX_OK;
}

int cx_fem_element_body_force(cx_elem_type t, const double *xe, const double *b, double *fe)
{
    int dim = cx_elem_dim(t), npe = cx_elem_npe(t);
    if (!dim)
        return CX_EINVAL;
    const double *xi, *w;
    int nq = cx_fem_rule(t, &xi, &w);
    double N[CX_FEM_MAXNPE], G[3 * CX_FEM_MAXNPE];
    memset(fe, 0, sizeof(double) * (size_t)(dim * npe));
    CX_TRY(check_nodes(t, xe));
    for (int q = 0; q < nq; q++) {
        double det;
        CX_TRY(cx_fem_eval(t, xe, xi + dim * q, N, G, &det));
        for (int a = 0; a < npe; a++)
            for (int c = 0; c < dim; c++)
                fe[dim * a + c] += w[q] * det * N[a] * b[c];
    }
    return CX_OK;
}
