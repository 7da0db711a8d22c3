/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Nodal stresses, computed only on request: sigma = D B u_e evaluated at
 * each node's reference position inside each element, averaged over the
 * elements that share the node. For P1 elements this is the element's
 * constant stress; for the others it avoids the extrapolation from Gauss
 * points (and its overshoot) at the price of some accuracy. */
#include "fem/fem_impl.h"

#include <string.h>

int cx_fem_nodal_stress(const cx_mesh *m, const cx_material *mats, const double *uall, double *sig)
{
    int dim = m->dim, npe = m->npe, nd = dim * npe, ns = cx_fem_nstress(dim);
    cx_fem_ref ref;
    if (cx_fem_ref_init(&ref, m->etype) || ref.dim != dim || ref.npe != npe)
        return CX_EINVAL;
    int *count = CX_NEW(int, m->nnodes);
    double *D = CX_NEW(double, (size_t)cx_mesh_nmats(m) * (size_t)(ns * ns));
    if (!count || !D) {
        cx_free(count);
        cx_free(D);
        return CX_ENOMEM;
    }
    for (int k = 0; k < cx_mesh_nmats(m); k++)
        cx_fem_elasticity(&mats[k], D + ns * ns * k);
    memset(sig, 0, sizeof(double) * (size_t)ns * (size_t)m->nnodes);

    int status = CX_OK;
    for (int e = 0; e < m->nelems && !status; e++) {
        const int *nodes = m->conn + npe * e;
        const double *De = D + ns * ns * cx_mesh_elem_mat(m, e);
        double xe[3 * CX_FEM_MAXNPE], ue[CX_FEM_MAXDOF];
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++) {
                xe[dim * a + i] = m->x[dim * nodes[a] + i];
                ue[dim * a + i] = uall[dim * nodes[a] + i];
            }
        for (int a = 0; a < npe; a++) {
            double G[3 * CX_FEM_MAXNPE], B[6 * CX_FEM_MAXDOF], eps[6];
            if ((status = cx_fem_ref_node_gradients(&ref, xe, a, G)))
                break;
            cx_fem_strain_matrix(dim, npe, G, B);
            for (int r = 0; r < ns; r++) {
                eps[r] = 0;
                for (int j = 0; j < nd; j++)
                    eps[r] += B[nd * r + j] * ue[j];
            }
            double *s = sig + ns * nodes[a];
            for (int r = 0; r < ns; r++)
                for (int k = 0; k < ns; k++)
                    s[r] += De[ns * r + k] * eps[k];
            count[nodes[a]]++;
        }
    }
    for (int k = 0; k < m->nnodes && !status; k++)
        for (int r = 0; count[k] && r < ns; r++)
            sig[ns * k + r] /= count[k];
    cx_free(count);
    cx_free(D);
    return status;
}
