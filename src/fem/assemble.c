/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Global assembly: loop over elements (or boundary facets), call the
 * kernel on gathered coordinates, scatter by dof = dim * node + c.
 *
 * The stiffness goes straight into its compressed-column pattern, computed
 * first from the mesh: nodes a and b are coupled when an element holds
 * both, and then so are all their dim x dim dof pairs, so K is made of
 * dim x dim blocks. Column (b, j) lists, for each neighbour a of b in
 * ascending order, the rows dim a .. dim a + dim - 1 (sorted, as cx_csc
 * requires); it starts at dim^2 p[b] + j dim deg(b), p the offsets of the
 * node graph. An element entry (a i, b j) lands at that start plus
 * dim k + i, k the place of a among the neighbours of b: a short search
 * (about 7 neighbours for TRI3, 27 for HEX8), which costs less than
 * storing npe^2 places per element would in memory. No triplets and no
 * sort; each entry is the sum of its element contributions in element
 * order. */
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
    for (int e = 0; m->mat && e < m->nelems; e++)
        if (m->mat[e] < 0 || m->mat[e] >= m->nmats)
            return cx_diag_set(d, CX_EINVAL, "element %d: material %d not in [0, %d)", e, m->mat[e],
                               m->nmats);
    /* the pattern indexes by node: a node out of range would write anywhere */
    for (size_t k = 0; k < (size_t)m->nelems * (size_t)m->npe; k++)
        if (m->conn[k] < 0 || m->conn[k] >= m->nnodes)
            return cx_diag_set(d, CX_EINVAL, "element %d: node %d not in [0, %d)", (int)(k / (size_t)m->npe),
                               m->conn[k], m->nnodes);
    return CX_OK;
}

static int check_material(const cx_material *mat, int k, int dim, cx_diag *d)
{
    if (dim == 3 ? mat->model != CX_SOLID : mat->model == CX_SOLID)
        return cx_diag_set(d, CX_EINVAL, "material %d: a %s model on a %dD mesh", k,
                           mat->model == CX_SOLID ? "3D" : "plane", dim);
    if (!(mat->E > 0) || !(mat->nu > -1 && mat->nu < 0.5))
        return cx_diag_set(d, CX_EINVAL, "material %d: need E > 0 and -1 < nu < 0.5 (got E = %g, nu = %g)",
                           k, mat->E, mat->nu);
    return CX_OK;
}

/* The node graph of the mesh: the neighbours of each node through the
 * elements (itself included), ascending. */
typedef struct node_graph {
    int *p;       /* nnodes + 1 */
    int *adj;     /* p[nnodes] */
} node_graph;

static void node_graph_clear(node_graph *g)
{
    cx_free(g->p);
    cx_free(g->adj);
    memset(g, 0, sizeof *g);
}

/* Visit the nodes of the elements around node b (ep/el: the elements of
 * each node), each once (mark[c] == b once visited): count them, or, with
 * adj, write them there. Returns the count. */
static int node_neighbours(const cx_mesh *m, const int *ep, const int *el, int b, int *mark,
                           int *adj)
{
    int deg = 0, npe = m->npe;
    for (int q = ep[b]; q < ep[b + 1]; q++) {
        const int *nodes = m->conn + npe * el[q];
        for (int a = 0; a < npe; a++) {
            int c = nodes[a];
            if (mark[c] != b) {
                mark[c] = b;
                if (adj)
                    adj[deg] = c;
                deg++;
            }
        }
    }
    /* insertion sort: a few dozen at most */
    for (int k = 1; adj && k < deg; k++) {
        int c = adj[k], l = k;
        for (; l > 0 && adj[l - 1] > c; l--)
            adj[l] = adj[l - 1];
        adj[l] = c;
    }
    return deg;
}

/* CX_EINVAL (message in d) if K would hold more than INT_MAX entries. */
static int node_graph_build(const cx_mesh *m, node_graph *g, cx_diag *d)
{
    int nn = m->nnodes, npe = m->npe, dim = m->dim, status = CX_ENOMEM;
    size_t ninc = (size_t)m->nelems * (size_t)npe;
    int *ep = NULL, *el = NULL, *mark = NULL;

    memset(g, 0, sizeof *g);
    if (ninc > INT_MAX)
        return cx_diag_set(d, CX_EINVAL, "mesh too large to assemble: %d elements of %d nodes",
                           m->nelems, npe);
    ep = CX_NEW(int, nn + 1);
    el = CX_NEW(int, ninc);
    mark = CX_NEW(int, nn);
    g->p = CX_NEW(int, nn + 1);
    if (!ep || !el || !mark || !g->p)
        goto done;
    /* the elements of each node */
    for (size_t k = 0; k < ninc; k++)
        ep[m->conn[k] + 1]++;
    for (int b = 0; b < nn; b++)
        ep[b + 1] += ep[b];
    memcpy(mark, ep, sizeof(int) * (size_t)nn);
    for (int e = 0; e < m->nelems; e++)
        for (int a = 0; a < npe; a++)
            el[mark[m->conn[npe * e + a]]++] = e;
    /* count, then fill */
    long long nnz = 0;
    for (int b = 0; b < nn; b++)
        mark[b] = -1;
    for (int b = 0; b < nn; b++) {
        nnz += node_neighbours(m, ep, el, b, mark, NULL);
        if (nnz * dim * dim > INT_MAX) {
            status = cx_diag_set(d, CX_EINVAL, "mesh too large to assemble: over %d entries in K",
                                 INT_MAX);
            goto done;
        }
        g->p[b + 1] = (int)nnz;
    }
    if (!(g->adj = CX_NEW(int, nnz)))
        goto done;
    for (int b = 0; b < nn; b++)
        mark[b] = -1;
    for (int b = 0; b < nn; b++)
        node_neighbours(m, ep, el, b, mark, g->adj + g->p[b]);
    status = CX_OK;
done:
    if (status)
        node_graph_clear(g);
    cx_free(ep);
    cx_free(el);
    cx_free(mark);
    return status;
}

/* K's pattern from the node graph, values zero. */
static int pattern_alloc(const node_graph *g, int nn, int dim, cx_csc *K)
{
    size_t nnz = (size_t)dim * (size_t)dim * (size_t)g->p[nn];
    int nall = dim * nn;
    K->nrow = K->ncol = nall;
    K->p = CX_NEW(int, nall + 1);
    K->i = CX_NEW(int, nnz);
    K->x = CX_NEW(double, nnz);
    if (!K->p || !K->i || !K->x) {
        cx_csc_clear(K);
        return CX_ENOMEM;
    }
    for (int b = 0; b < nn; b++) {
        int deg = g->p[b + 1] - g->p[b], q = dim * dim * g->p[b];
        const int *adj = g->adj + g->p[b];
        for (int j = 0; j < dim; j++) {
            K->p[dim * b + j] = q;
            for (int k = 0; k < deg; k++)
                for (int i = 0; i < dim; i++)
                    K->i[q++] = dim * adj[k] + i;
        }
    }
    K->p[nall] = (int)nnz;
    return CX_OK;
}

/* K += Ke of every element (kernel, then scatter at the places the
 * pattern gives), inlined with constant dim and npe so that the gather
 * and the scatter are fixed-size loops. Returns the first element whose
 * kernel fails, or -1. */
static inline __attribute__((always_inline)) int
assemble_elements(int dim, int npe, const cx_mesh *restrict m, const cx_fem_ref *restrict ref,
                  const double *restrict D, const node_graph *restrict g, double *restrict Kx)
{
    const int nd = dim * npe, ns = cx_fem_nstress(dim);
    double xe[3 * CX_FEM_MAXNPE], Ke[CX_FEM_MAXDOF * CX_FEM_MAXDOF];
    for (int e = 0; e < m->nelems; e++) {
        const int *nodes = m->conn + npe * e;
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++)
                xe[dim * a + i] = m->x[dim * nodes[a] + i];
        if (cx_fem_ref_stiffness(ref, xe, D + ns * ns * cx_mesh_elem_mat(m, e), Ke))
            return e;
        for (int b = 0; b < npe; b++) {
            int nb = nodes[b], deg = g->p[nb + 1] - g->p[nb];
            const int *adj = g->adj + g->p[nb];
            double *col = Kx + (size_t)dim * (size_t)dim * (size_t)g->p[nb];
            for (int a = 0; a < npe; a++) {
                int k = 0;
                while (adj[k] != nodes[a])
                    k++;
                for (int j = 0; j < dim; j++)
                    for (int i = 0; i < dim; i++)
                        col[dim * (j * deg + k) + i] += Ke[nd * (dim * a + i) + dim * b + j];
            }
        }
    }
    return -1;
}

int cx_fem_assemble_stiffness(const cx_mesh *m, const cx_material *mats, cx_csc *K, cx_diag *d)
{
    int dim = m->dim, ns = cx_fem_nstress(dim), status;
    double *D = NULL;
    node_graph g = {0};
    cx_fem_ref ref;

    memset(K, 0, sizeof *K);
    CX_TRY(check_mesh(m, d));
    for (int k = 0; k < cx_mesh_nmats(m); k++)
        CX_TRY(check_material(&mats[k], k, dim, d));
    if (cx_fem_ref_init(&ref, m->etype))
        return cx_diag_set(d, CX_EINVAL, "no stiffness kernel for %s elements", cx_elem_name(m->etype));
    D = CX_NEW(double, (size_t)cx_mesh_nmats(m) * (size_t)(ns * ns));
    if (!D) {
        status = CX_ENOMEM;
        goto fail;
    }
    for (int k = 0; k < cx_mesh_nmats(m); k++)
        cx_fem_elasticity(&mats[k], D + ns * ns * k);
    if ((status = node_graph_build(m, &g, d)) || (status = pattern_alloc(&g, m->nnodes, dim, K)))
        goto fail;

    int bad;
    switch (m->etype) {
    case CX_EL_TRI3: bad = assemble_elements(2, 3, m, &ref, D, &g, K->x); break;
    case CX_EL_TRI6: bad = assemble_elements(2, 6, m, &ref, D, &g, K->x); break;
    case CX_EL_QUAD4: bad = assemble_elements(2, 4, m, &ref, D, &g, K->x); break;
    case CX_EL_HEX8: bad = assemble_elements(3, 8, m, &ref, D, &g, K->x); break;
    case CX_EL_TET4: bad = assemble_elements(3, 4, m, &ref, D, &g, K->x); break;
    default: bad = 0;   /* refused by cx_fem_ref_init above */
    }
    if (bad >= 0)
        status = cx_diag_set(d, CX_ENUMERIC, "element %d (%s) is degenerate or inverted", bad,
                             cx_elem_name(m->etype));
fail:
    if (status == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "out of memory assembling the stiffness (%d elements)", m->nelems);
    if (status)
        cx_csc_clear(K);
    node_graph_clear(&g);
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
    cx_fem_ref ref;
    if (cx_fem_ref_init(&ref, m->etype) || ref.dim != dim || ref.npe != npe)
        return CX_EINVAL;
    for (int e = 0; e < m->nelems; e++) {
        const int *nodes = m->conn + npe * e;
        gather(m, nodes, npe, xe);
        CX_TRY(cx_fem_ref_body_force(&ref, xe, bf, fe));
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++)
                f[dim * nodes[a] + i] += fe[dim * a + i];
    }
    return CX_OK;
}
