/* Global assembly: loop over elements (or boundary facets), call the
 * kernel on gathered coordinates, scatter by dof = dim * node + c. The
 * stiffness goes through one triplet converted once to CSC, which sums the
 * contributions of neighbouring elements. */
#include "fem/fem_impl.h"

#include <limits.h>
#include <string.h>

static void gather(const cx_mesh *m, const int *nodes, int n, double *xe)
{
    for (int a = 0; a < n; a++)
        memcpy(xe + m->dim * a, m->x + m->dim * nodes[a], sizeof(double) * (size_t)m->dim);
}

static int check_mesh(const cx_mesh *m, cx_diag *d)
{
    if (cx_elem_dim(m->etype) != m->dim || cx_elem_npe(m->etype) != m->npe)
        return cx_diag_set(d, CX_EINVAL, "mesh of %s elements in %dD with %d nodes per element",
                           cx_elem_name(m->etype), m->dim, m->npe);
    if (m->nbodies < 1)
        return cx_diag_set(d, CX_EINVAL, "mesh with %d bodies", m->nbodies);
    for (int e = 0; m->body && e < m->nelems; e++)
        if (m->body[e] < 0 || m->body[e] >= m->nbodies)
            return cx_diag_set(d, CX_EINVAL, "element %d: body %d not in [0, %d)", e, m->body[e],
                               m->nbodies);
    return CX_OK;
}

static int check_material(const cx_material *mat, int k, int dim, cx_diag *d)
{
    if (dim == 3 ? mat->model != CX_SOLID : mat->model == CX_SOLID)
        return cx_diag_set(d, CX_EINVAL, "body %d: a %s model on a %dD mesh", k,
                           mat->model == CX_SOLID ? "3D" : "plane", dim);
    if (!(mat->E > 0) || !(mat->nu > -1 && mat->nu < 0.5))
        return cx_diag_set(d, CX_EINVAL, "body %d: need E > 0 and -1 < nu < 0.5 (got E = %g, nu = %g)",
                           k, mat->E, mat->nu);
    return CX_OK;
}

int cx_fem_assemble_stiffness(const cx_mesh *m, const cx_material *mats, cx_csc *K, cx_diag *d)
{
    int dim = m->dim, npe = m->npe, nd = dim * npe, ns = cx_fem_nstress(dim);
    int nall = dim * m->nnodes, status;
    double *D = NULL, xe[3 * CX_FEM_MAXNPE], Ke[CX_FEM_MAXDOF * CX_FEM_MAXDOF];
    cx_triplet T = {0};

    memset(K, 0, sizeof *K);
    CX_TRY(check_mesh(m, d));
    for (int k = 0; k < m->nbodies; k++)
        CX_TRY(check_material(&mats[k], k, dim, d));
    /* the triplet holds every element entry before duplicates are summed,
     * and CSC positions are ints */
    if ((double)m->nelems * nd * nd > INT_MAX)
        return cx_diag_set(d, CX_EINVAL, "mesh too large to assemble: %d elements of %d dofs",
                           m->nelems, nd);
    D = CX_NEW(double, (size_t)m->nbodies * (size_t)(ns * ns));
    if (!D || (status = cx_triplet_init(&T, nall, nall, (size_t)m->nelems * (size_t)(nd * nd)))) {
        status = CX_ENOMEM;
        goto fail;
    }
    for (int k = 0; k < m->nbodies; k++)
        cx_fem_elasticity(&mats[k], D + ns * ns * k);

    for (int e = 0; e < m->nelems; e++) {
        const int *nodes = m->conn + npe * e;
        gather(m, nodes, npe, xe);
        if ((status = cx_fem_element_stiffness(m->etype, xe, D + ns * ns * (m->body ? m->body[e] : 0), Ke))) {
            cx_diag_set(d, status, "element %d (%s) is degenerate or inverted", e, cx_elem_name(m->etype));
            goto fail;
        }
        for (int b = 0; b < npe; b++)
            for (int j = 0; j < dim; j++)
                for (int a = 0; a < npe; a++)
                    for (int i = 0; i < dim; i++)
                        if ((status = cx_triplet_add(&T, dim * nodes[a] + i, dim * nodes[b] + j,
                                                     Ke[nd * (dim * a + i) + dim * b + j])))
                            goto fail;
    }
    status = cx_csc_from_triplet(K, &T);
fail:
    if (status == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "out of memory assembling the stiffness (%d elements)", m->nelems);
    cx_triplet_clear(&T);
    cx_free(D);
    return status;
}

int cx_fem_add_traction(const cx_mesh *m, const cx_boundary *b, const cx_traction *t, double *f)
{
    int dim = m->dim, npf = b->npf;
    double xf[3 * 4], fe[3 * 4];
    if (npf < 2 || npf > 4)
        return CX_EINVAL;
    for (int k = 0; k < b->nfacets; k++) {
        const int *nodes = b->facets + npf * k;
        gather(m, nodes, npf, xf);
        CX_TRY(cx_fem_facet_traction(dim, npf, xf, t, fe));
        for (int a = 0; a < npf; a++)
            for (int i = 0; i < dim; i++)
                f[dim * nodes[a] + i] += fe[dim * a + i];
    }
    return CX_OK;
}

int cx_fem_add_body_force(const cx_mesh *m, const double *bf, double *f)
{
    int dim = m->dim, npe = m->npe;
    double xe[3 * CX_FEM_MAXNPE], fe[CX_FEM_MAXDOF];
    if (cx_elem_dim(m->etype) != dim || cx_elem_npe(m->etype) != npe)
        return CX_EINVAL;
    for (int e = 0; e < m->nelems; e++) {
        const int *nodes = m->conn + npe * e;
        gather(m, nodes, npe, xe);
        CX_TRY(cx_fem_element_body_force(m->etype, xe, bf, fe));
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++)
                f[dim * nodes[a] + i] += fe[dim * a + i];
    }
    return CX_OK;
}
