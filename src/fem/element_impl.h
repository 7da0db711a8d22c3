/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Private to fem/: the element kernels as static inline functions of
 * constant sizes, so that a caller that passes the sizes of one element
 * type (the assembly's loop over the elements, the public kernels of
 * element.c) gets one instance per type with every loop of fixed trip
 * count, which the compiler unrolls or vectorises. The assembly calls
 * cx_fem_stiffness_kernel inside its element loop: no call per element,
 * no switch on the type, Ke kept in registers and L1. The arithmetic, and
 * so every bit of Ke, is the same whichever caller inlines it. */
#ifndef CX_FEM_ELEMENT_IMPL_H
#define CX_FEM_ELEMENT_IMPL_H

#include "fem/fem_impl.h"

#define CX_FEM_INLINE static inline __attribute__((always_inline))

/* The size below which det J counts as zero: rounding of an exactly
 * degenerate element leaves ~1e-16 h^dim, never exactly 0. */
CX_FEM_INLINE double cx_fem_det_floor(int dim, int npe, const double *restrict xe)
{
    double h = 0;
    for (int k = 0; k < dim; k++) {
        double lo = xe[k], hi = xe[k];
        for (int a = 1; a < npe; a++) {
            double v = xe[dim * a + k];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        h = hi - lo > h ? hi - lo : h;
    }
    return dim == 3 ? 1e-12 * h * h * h : 1e-12 * h * h;
}

/* det J at reference gradients dN, J[i][k] = dx_i / dxi_k = sum_a
 * x_a,i dN_a,k, and, when G is not NULL, the physical gradients
 * G_a = J^-T dN_a (node-major). */
CX_FEM_INLINE double cx_fem_jacobian(int dim, int npe, const double *restrict dN,
                                     const double *restrict xe, double *restrict G)
{
    double J[9] = {0}, Ji[9], det;
    for (int a = 0; a < npe; a++)
        for (int i = 0; i < dim; i++)
            for (int k = 0; k < dim; k++)
                J[dim * i + k] += xe[dim * a + i] * dN[dim * a + k];
    if (dim == 2) {
        det = J[0] * J[3] - J[1] * J[2];
        if (!G)
            return det;
        Ji[0] = J[3] / det, Ji[1] = -J[1] / det;
        Ji[2] = -J[2] / det, Ji[3] = J[0] / det;
    } else {
        double c00 = J[4] * J[8] - J[5] * J[7], c01 = J[5] * J[6] - J[3] * J[8],
               c02 = J[3] * J[7] - J[4] * J[6];
        det = J[0] * c00 + J[1] * c01 + J[2] * c02;
        if (!G)
            return det;
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
    /* G[a][i] = sum_k dN[a][k] Ji[k][i] */
    for (int a = 0; a < npe; a++)
        for (int i = 0; i < dim; i++) {
            double s = 0;
            for (int k = 0; k < dim; k++)
                s += dN[dim * a + k] * Ji[dim * k + i];
            G[dim * a + i] = s;
        }
    return det;
}

/* det J > 0 at every node as well as at the quadrature points: a
 * non-convex quadrilateral or a folded hexahedron can pass at the Gauss
 * points and still be inverted near a corner. On an affine element J is
 * the same everywhere and the quadrature point's check is this one. */
CX_FEM_INLINE int cx_fem_check_nodes(int dim, int npe, const cx_fem_ref *restrict r,
                                      const double *restrict xe, double lim)
{
    for (int a = 0; a < npe; a++)
        if (!(cx_fem_jacobian(dim, npe, r->dNn[a], xe, NULL) > lim))
            return CX_ENUMERIC;
    return CX_OK;
}

/* Ke's upper triangle += B'(DB) at one quadrature point (B from the
 * gradients G, as cx_fem_strain_matrix; the rows of node a from its own
 * columns on). first: Ke holds nothing yet, and each entry is its terms
 * added to 0.0, the same sums bit for bit (signed zeros included) as
 * after a pass that zeroes Ke. */
CX_FEM_INLINE void cx_fem_add_btdb(int dim, int npe, int first, const double *restrict G,
                                   const double (*restrict DB)[CX_FEM_MAXDOF], double *restrict Ke)
{
    const int nd = dim * npe;
    for (int a = 0; a < npe; a++) {
        const double *g = G + dim * a;
        double *restrict kx = Ke + nd * (dim * a), *restrict ky = kx + nd;
        if (dim == 2) {
            /* Voigt (xx, yy, xy): column (a, x) of B is gx e0 + gy e2,
             * column (a, y) is gy e1 + gx e2 */
            for (int j = 2 * a; j < nd; j++) {
                kx[j] = (first ? 0.0 : kx[j]) + (g[0] * DB[0][j] + g[1] * DB[2][j]);
                ky[j] = (first ? 0.0 : ky[j]) + (g[1] * DB[1][j] + g[0] * DB[2][j]);
            }
        } else {
            /* Voigt (xx, yy, zz, yz, xz, xy): column (a, x) of B is
             * gx e0 + gz e4 + gy e5, (a, y) gy e1 + gz e3 + gx e5,
             * (a, z) gz e2 + gy e3 + gx e4 */
            double *restrict kz = ky + nd;
            for (int j = 3 * a; j < nd; j++) {
                kx[j] = (first ? 0.0 : kx[j]) + (g[0] * DB[0][j] + g[2] * DB[4][j] + g[1] * DB[5][j]);
                ky[j] = (first ? 0.0 : ky[j]) + (g[1] * DB[1][j] + g[2] * DB[3][j] + g[0] * DB[5][j]);
                kz[j] = (first ? 0.0 : kz[j]) + (g[2] * DB[2][j] + g[1] * DB[3][j] + g[0] * DB[4][j]);
            }
        }
    }
}

/* Ke = sum_q w_q det J_q B_q' D B_q. B has three non-zeros per column in
 * 3D (two in 2D), at the rows of cx_fem_strain_matrix, so DB = s D B costs
 * ns x nd x 3 and each row of B'(DB) three rows of DB: contiguous rows of
 * fixed length nd, which the compiler vectorises. The sums run in the
 * order of the dense product over the Voigt rows (the zeros of B skipped
 * add nothing), so Ke is the same to the last bit as B'(DB) with a dense
 * B. Only the upper triangle is summed (the rows of node a from its own
 * columns on) and mirrored below at the end, so that Ke is exactly
 * symmetric (the two triangles of B'(DB) would differ in rounding) for
 * about half the work of the full product. */
CX_FEM_INLINE int cx_fem_stiffness_kernel(int dim, int npe, int nq, int affine,
                                           const cx_fem_ref *restrict r, const double *restrict xe,
                                           const double *restrict D, double *restrict Ke)
{
    const int nd = dim * npe;
    double G[3 * CX_FEM_MAXNPE], DB[6][CX_FEM_MAXDOF];
    double lim = cx_fem_det_floor(dim, npe, xe);

    if (!affine && cx_fem_check_nodes(dim, npe, r, xe, lim))
        return CX_ENUMERIC;
    /* one point (TRI3, TET4): its terms are added to 0.0 (the zeroing pass
     * cost a tenth of TRI3's assembly); more: to Ke zeroed first (peeling
     * the first point made HEX8's larger loop slower) */
    for (int k = 0; nq > 1 && k < nd * nd; k++)
        Ke[k] = 0;
    for (int q = 0; q < nq; q++) {
        double det = cx_fem_jacobian(dim, npe, r->dNq[q], xe, G);
        if (!(det > lim))
            return CX_ENUMERIC;
        double s = r->w[q] * det;
        /* DB = s D B, B's columns as cx_fem_add_btdb states */
        if (dim == 2) {
            for (int a = 0; a < npe; a++) {
                double gx = G[2 * a], gy = G[2 * a + 1];
                for (int k = 0; k < 3; k++) {
                    DB[k][2 * a] = s * (D[3 * k] * gx + D[3 * k + 2] * gy);
                    DB[k][2 * a + 1] = s * (D[3 * k + 1] * gy + D[3 * k + 2] * gx);
                }
            }
        } else {
            for (int a = 0; a < npe; a++) {
                double gx = G[3 * a], gy = G[3 * a + 1], gz = G[3 * a + 2];
                for (int k = 0; k < 6; k++) {
                    const double *Dk = D + 6 * k;
                    DB[k][3 * a] = s * (Dk[0] * gx + Dk[4] * gz + Dk[5] * gy);
                    DB[k][3 * a + 1] = s * (Dk[1] * gy + Dk[3] * gz + Dk[5] * gx);
                    DB[k][3 * a + 2] = s * (Dk[2] * gz + Dk[3] * gy + Dk[4] * gx);
                }
            }
        }
        cx_fem_add_btdb(dim, npe, nq == 1, G, (const double (*)[CX_FEM_MAXDOF])DB, Ke);
    }
    for (int i = 0; i < nd; i++)
        for (int j = 0; j < i; j++)
            Ke[nd * i + j] = Ke[nd * j + i];
    return CX_OK;
}

#endif
