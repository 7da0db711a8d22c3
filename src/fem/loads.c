/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The loads of user geometry: pressure normal to a boundary, body force
 * over a region's elements, a force on nodes. The tractions and the body
 * force over the whole mesh are in assemble.c. */
#include "fem/fem_impl.h"

#include <math.h>
#include <string.h>

/* The outward unit normal of a facet (2D: to the right of the edge from
 * its first node to its second; 3D: by the right-hand rule over the
 * corners, the diagonals' cross product for a quadrilateral). */
static int loads_normal(int dim, int npf, const double *xf, double *n)
{
    double l;
    if (dim == 2) {
        double tx = xf[2] - xf[0], ty = xf[3] - xf[1];
        l = hypot(tx, ty);
        n[0] = ty, n[1] = -tx;
    } else {
        double u[3], v[3];
        int a = npf == 4 ? 2 : 1, b = npf == 4 ? 3 : 2, c = npf == 4 ? 1 : 0;
        for (int k = 0; k < 3; k++) {
            u[k] = xf[3 * a + k] - xf[k];             /* tri: x1 - x0; quad: x2 - x0 */
            v[k] = xf[3 * b + k] - xf[3 * c + k];     /* tri: x2 - x0; quad: x3 - x1 */
        }
        n[0] = u[1] * v[2] - u[2] * v[1];
        n[1] = u[2] * v[0] - u[0] * v[2];
        n[2] = u[0] * v[1] - u[1] * v[0];
        l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    if (!(l > 0))
        return CX_ENUMERIC;
    for (int k = 0; k < dim; k++)
        n[k] /= l;
    return CX_OK;
}

int cx_fem_add_pressure(const cx_mesh *m, const cx_boundary *b, double p, double *f)
{
    int dim = m->dim, npf = b->npf;
    double xf[3 * 4], fe[3 * 4];
    if (npf < 2 || npf > 4)
        return CX_EINVAL;
    for (int k = 0; k < b->nfacets; k++) {
        const int *nodes = b->facets + npf * k;
        for (int a = 0; a < npf; a++)
            memcpy(xf + dim * a, m->x + dim * nodes[a], sizeof(double) * (size_t)dim);
        cx_traction t = {{0, 0, 0}, {0}};
        double n[3] = {0, 0, 0};
        CX_TRY(loads_normal(dim, npf, xf, n));
        for (int c = 0; c < dim; c++)
            t.t0[c] = -p * n[c];
        CX_TRY(cx_fem_facet_traction(dim, npf, xf, &t, fe));
        for (int a = 0; a < npf; a++)
            for (int i = 0; i < dim; i++)
                f[dim * nodes[a] + i] += fe[dim * a + i];
    }
    return CX_OK;
}

int cx_fem_add_body_force_on(const cx_mesh *m, const int *elems, int count, const double *bf,
                             double *f)
{
    int dim = m->dim, npe = m->npe;
    double xe[3 * CX_FEM_MAXNPE], fe[CX_FEM_MAXDOF];
    cx_fem_ref ref;
    if (cx_fem_ref_init(&ref, m->etype) || ref.dim != dim || ref.npe != npe)
        return CX_EINVAL;
    for (int k = 0; k < count; k++) {
        int e = elems[k];
        if (e < 0 || e >= m->nelems)
            return CX_EINVAL;
        const int *nodes = m->conn + npe * e;
        for (int a = 0; a < npe; a++)
            memcpy(xe + dim * a, m->x + dim * nodes[a], sizeof(double) * (size_t)dim);
        CX_TRY(cx_fem_ref_body_force(&ref, xe, bf, fe));
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++)
                f[dim * nodes[a] + i] += fe[dim * a + i];
    }
    return CX_OK;
}
