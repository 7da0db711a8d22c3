/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Global assembly: loop over elements (or boundary facets), call the
 * kernel on gathered coordinates, scatter by dof = dim * node + c.
 *
 * The stiffness goes straight into its compressed-column pattern, computed
 * first from the mesh, over all dofs or (cx_fem_assemble_free) over the
 * free dofs of a Dirichlet map, so that no matrix over all dofs is made
 * and reduced afterwards. Nodes a and b are coupled when an element holds
 * both, and then so are all their free dof pairs. Every free column of
 * node b holds the same rows: for each neighbour a of b in ascending
 * order, a's free dofs (sorted, as cx_csc requires; with every dof free,
 * dim a .. dim a + dim - 1). Its length len(b) is the sum of the free dofs
 * of b's neighbours, and b's t-th free column starts at
 * cbase(b) + t len(b). An element entry (a i, b j) lands there plus the
 * offset of a's rows in b's columns, which the pattern's construction
 * records per element and node pair (pos: npe^2 ints per element), plus
 * the rank of i among a's free dofs: the scatter searches nothing. Each
 * entry is the sum of its element contributions in element order, the
 * same sums, bitwise, as the reduction of the matrix over all dofs
 * (cx_fem_reduce) gives. */
#include "fem/element_impl.h"

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

/* The pattern of K over the free dofs and where each element's entries
 * go (header). */
typedef struct pattern {
    int *cbase;            /* nnodes: first entry of the node's first free column */
    int *len;              /* nnodes: entries of each free column of the node */
    unsigned char *fm;     /* nnodes: bit c set when dof (node, c) is free */
    int *pos;              /* nelems npe^2: element e, column node b, row node a at
                              npe (npe e + b) + a: offset of a's rows in b's columns */
} pattern;

static void pattern_clear(pattern *g)
{
    cx_free(g->cbase);
    cx_free(g->len);
    cx_free(g->fm);
    cx_free(g->pos);
    memset(g, 0, sizeof *g);
}

static int popcount(unsigned v)
{
    int n = 0;
    for (; v; v &= v - 1)
        n++;
    return n;
}

/* The neighbours of node b (itself included) through its elements
 * (incidences inc[ip[b] .. ip[b + 1]), each e npe + the node's place in
 * e), each once (mark[c] == b once seen), ascending, into adj; returns
 * their count. */
static int node_neighbours(const int *conn, int npe, const int *ip, const int *inc, int b, int *mark,
                           int *adj)
{
    int deg = 0;
    for (int q = ip[b]; q < ip[b + 1]; q++) {
        const int *nodes = conn + (inc[q] - inc[q] % npe);
        for (int a = 0; a < npe; a++) {
            int c = nodes[a];
            if (mark[c] != b) {
                mark[c] = b;
                adj[deg++] = c;
            }
        }
    }
    /* insertion sort: a few dozen at most */
    for (int k = 1; k < deg; k++) {
        int c = adj[k], l = k;
        for (; l > 0 && adj[l - 1] > c; l--)
            adj[l] = adj[l - 1];
        adj[l] = c;
    }
    return deg;
}

/* The pattern over the free dofs of map (NULL: every dof), K's p and i
 * with zero values. One pass over the nodes finds each node's neighbours
 * (kept, at most npe per incidence, for K's rows) and writes the offsets
 * of its elements' entries. CX_EINVAL (message in d) if K would hold more
 * than INT_MAX entries. */
static int pattern_build(const cx_mesh *m, const cx_dofmap *map, pattern *g, cx_csc *K, cx_diag *d)
{
    int nn = m->nnodes, npe = m->npe, dim = m->dim, status = CX_ENOMEM;
    const unsigned full = (1u << dim) - 1;
    size_t ninc = (size_t)m->nelems * (size_t)npe, npair = ninc * (size_t)npe;
    int *ip = NULL, *inc = NULL, *mark = NULL, *off = NULL, *ap = NULL, *adj = NULL;

    memset(g, 0, sizeof *g);
    memset(K, 0, sizeof *K);
    if (npair > INT_MAX)
        return cx_diag_set(d, CX_EINVAL, "mesh too large to assemble: %d elements of %d nodes",
                           m->nelems, npe);
    ip = CX_NEW(int, nn + 1);
    inc = CX_NEW(int, ninc ? ninc : 1);
    mark = CX_NEW(int, nn);
    off = CX_NEW(int, nn);
    ap = CX_NEW(int, nn + 1);
    adj = CX_NEW(int, npair ? npair : 1);
    g->cbase = CX_NEW(int, nn);
    g->len = CX_NEW(int, nn);
    g->fm = CX_NEW(unsigned char, nn);
    g->pos = CX_NEW(int, npair ? npair : 1);
    if (!ip || !inc || !mark || !off || !ap || !adj || !g->cbase || !g->len || !g->fm || !g->pos)
        goto done;
    for (int b = 0; b < nn; b++) {
        unsigned f = full;
        for (int c = 0; map && c < dim; c++)
            if (map->free_of[dim * b + c] < 0)
                f &= ~(1u << c);
        g->fm[b] = (unsigned char)f;
    }
    /* the incidences of each node */
    for (size_t k = 0; k < ninc; k++)
        ip[m->conn[k] + 1]++;
    for (int b = 0; b < nn; b++)
        ip[b + 1] += ip[b];
    memcpy(mark, ip, sizeof(int) * (size_t)nn);
    for (size_t k = 0; k < ninc; k++)
        inc[mark[m->conn[k]]++] = (int)k;
    /* per node: its neighbours, the offsets of their rows in its columns
     * (off, by node), its elements' entries, its columns' length */
    long long nnz = 0;
    for (int b = 0; b < nn; b++)
        mark[b] = -1;
    for (int b = 0; b < nn; b++) {
        int *nb = adj + ap[b];
        int deg = node_neighbours(m->conn, npe, ip, inc, b, mark, nb), len = 0;
        for (int k = 0; k < deg; k++) {
            off[nb[k]] = len;
            len += popcount(g->fm[nb[k]]);
        }
        for (int q = ip[b]; q < ip[b + 1]; q++) {
            int e = inc[q] / npe, lb = inc[q] % npe;
            const int *nodes = m->conn + (size_t)npe * (size_t)e;
            int *pe = g->pos + (size_t)npe * ((size_t)npe * (size_t)e + (size_t)lb);
            for (int a = 0; a < npe; a++)
                pe[a] = off[nodes[a]];
        }
        ap[b + 1] = ap[b] + deg;
        g->len[b] = len;
        g->cbase[b] = (int)nnz;
        nnz += (long long)len * popcount(g->fm[b]);
        if (nnz > INT_MAX) {
            status = cx_diag_set(d, CX_EINVAL, "mesh too large to assemble: over %d entries in K",
                                 INT_MAX);
            goto done;
        }
    }
    /* K's columns, in dof order: node b's free dofs, each the rows of its
     * neighbours' free dofs */
    int ncol = map ? map->nfree : dim * nn;
    K->nrow = K->ncol = ncol;
    K->p = CX_NEW(int, ncol + 1);
    K->i = CX_NEW(int, nnz ? nnz : 1);
    /* zeroed by writing, not calloc: fresh pages from calloc are mapped
     * to the zero page and the scatter's first += then faults twice on
     * each (a read, then a copy on write) */
    K->x = cx_malloc(sizeof(double) * (size_t)(nnz ? nnz : 1));
    if (!K->p || !K->i || !K->x)
        goto done;
    memset(K->x, 0, sizeof(double) * (size_t)nnz);
    int col = 0;
    for (int b = 0; b < nn; b++) {
        int *ki = K->i + g->cbase[b], nf = popcount(g->fm[b]);
        for (int k = ap[b]; nf > 0 && k < ap[b + 1]; k++) {   /* no column, no rows */
            int a = adj[k];
            for (int i = 0; i < dim; i++)
                if ((g->fm[a] >> i) & 1u)
                    *ki++ = map ? map->free_of[dim * a + i] : dim * a + i;
        }
        for (int t = 0; t < nf; t++) {
            K->p[col++] = g->cbase[b] + t * g->len[b];
            if (t > 0)
                memcpy(K->i + g->cbase[b] + t * g->len[b], K->i + g->cbase[b],
                       sizeof(int) * (size_t)g->len[b]);
        }
    }
    K->p[ncol] = (int)nnz;
    status = col == ncol ? CX_OK : CX_EINVAL;   /* a map not of this mesh */
done:
    if (status) {
        pattern_clear(g);
        cx_csc_clear(K);
    }
    cx_free(ip);
    cx_free(inc);
    cx_free(mark);
    cx_free(off);
    cx_free(ap);
    cx_free(adj);
    return status;
}

/* The material of element e: its D (ns x ns) in the table of the
 * materials' D (cx_mesh_elem_mat: the element's material, its body's
 * where the mesh has no per-element materials). */
static inline const double *element_D(const cx_mesh *m, const double *D, int ns, int e)
{
    return D + ns * ns * cx_mesh_elem_mat(m, e);
}

/* Ke of node pair (a, b) with some dof prescribed: its free entries into
 * K's block at blk (column stride L), and, for a prescribed column dof of
 * b with a non-zero value, -Ke times the value into fd at the free rows. */
static void scatter_partial(int dim, int nd, const double *restrict Ke, int a, int b, unsigned fa,
                            unsigned fb, const int *restrict arow, const double *restrict bval,
                            double *restrict blk, int L, double *restrict fd)
{
    for (int j = 0, t = 0; j < dim; j++) {
        const double *kc = Ke + nd * (dim * b + j) + dim * a;   /* column (b j), Ke symmetric */
        if ((fb >> j) & 1u) {
            for (int i = 0, r = 0; i < dim; i++)
                if ((fa >> i) & 1u)
                    blk[t * L + r++] += kc[i];
            t++;
        } else if (fd && bval[j] != 0) {
            for (int i = 0; i < dim; i++)
                if ((fa >> i) & 1u)
                    fd[arow[i]] -= kc[i] * bval[j];
        }
    }
}

/* K += Ke of every element (kernel, then scatter at the places the
 * pattern gives), inlined with constant dim, npe and quadrature so that
 * the gather, the kernel (element_impl.h, no call per element) and the
 * scatter of the nodes whose dofs are all free are fixed-size loops. Ke is exactly symmetric: column (b j) is read along its
 * contiguous row. Returns the first element whose kernel fails, or -1. */
CX_FEM_INLINE int assemble_elements(int dim, int npe, int nq, int affine, const cx_mesh *restrict m,
                                    const cx_dofmap *map, const cx_fem_ref *restrict ref,
                                    const double *restrict D, const pattern *restrict g,
                                    double *restrict Kx, double *restrict fd)
{
    const int nd = dim * npe, ns = cx_fem_nstress(dim);
    const unsigned full = (1u << dim) - 1;
    double xe[3 * CX_FEM_MAXNPE], Ke[CX_FEM_MAXDOF * CX_FEM_MAXDOF];
    for (int e = 0; e < m->nelems; e++) {
        const int *nodes = m->conn + npe * e;
        const int *pe = g->pos + (size_t)npe * (size_t)npe * (size_t)e;
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++)
                xe[dim * a + i] = m->x[dim * nodes[a] + i];
        if (cx_fem_stiffness_kernel(dim, npe, nq, affine, ref, xe, element_D(m, D, ns, e), Ke))
            return e;
        for (int b = 0; b < npe; b++) {
            int nb = nodes[b], L = g->len[nb];
            unsigned fb = g->fm[nb];
            double *col = Kx + g->cbase[nb];
            for (int a = 0; a < npe; a++) {
                unsigned fa = g->fm[nodes[a]];
                double *restrict blk = col + pe[npe * b + a];
                if ((fa & fb) == full) {
                    for (int j = 0; j < dim; j++)
                        for (int i = 0; i < dim; i++)
                            blk[j * L + i] += Ke[nd * (dim * b + j) + dim * a + i];
                } else {
                    int arow[3];
                    for (int i = 0; i < dim; i++)
                        arow[i] = map ? map->free_of[dim * nodes[a] + i] : dim * nodes[a] + i;
                    scatter_partial(dim, nd, Ke, a, b, fa, fb, arow,
                                    map ? map->value + dim * nb : NULL, blk, L, fd);
                }
            }
        }
    }
    return -1;
}

/* The assembly over all dofs (map NULL) or the free dofs of map, fd as
 * cx_fem_assemble_free states. */
static int assemble(const cx_mesh *m, const cx_material *mats, const cx_dofmap *map, cx_csc *K,
                    double *fd, cx_diag *d)
{
    int dim = m->dim, ns = cx_fem_nstress(dim), status;
    double *D = NULL;
    pattern g = {0};
    cx_fem_ref ref;

    memset(K, 0, sizeof *K);
    CX_TRY(check_mesh(m, d));
    for (int k = 0; k < cx_mesh_nmats(m); k++)
        CX_TRY(check_material(&mats[k], k, dim, d));
    if (map && (map->nfree < 0 || map->nall != dim * m->nnodes))
        return cx_diag_set(d, CX_EINVAL, "a Dirichlet map of %d dofs (%s) for a mesh of %d",
                           map->nall, map->nfree < 0 ? "not finished" : "finished", dim * m->nnodes);
    if (cx_fem_ref_init(&ref, m->etype))
        return cx_diag_set(d, CX_EINVAL, "no stiffness kernel for %s elements", cx_elem_name(m->etype));
    D = CX_NEW(double, (size_t)cx_mesh_nmats(m) * (size_t)(ns * ns));
    if (!D) {
        status = CX_ENOMEM;
        goto fail;
    }
    for (int k = 0; k < cx_mesh_nmats(m); k++)
        cx_fem_elasticity(&mats[k], D + ns * ns * k);
    if ((status = pattern_build(m, map, &g, K, d)))
        goto fail;

    int bad;
    switch (m->etype) {
    case CX_EL_TRI3: bad = assemble_elements(2, 3, 1, 1, m, map, &ref, D, &g, K->x, fd); break;
    case CX_EL_TRI6: bad = assemble_elements(2, 6, 3, 0, m, map, &ref, D, &g, K->x, fd); break;
    case CX_EL_QUAD4: bad = assemble_elements(2, 4, 4, 0, m, map, &ref, D, &g, K->x, fd); break;
    case CX_EL_HEX8: bad = assemble_elements(3, 8, 8, 0, m, map, &ref, D, &g, K->x, fd); break;
    case CX_EL_TET4: bad = assemble_elements(3, 4, 1, 1, m, map, &ref, D, &g, K->x, fd); break;
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
    pattern_clear(&g);
    cx_free(D);
    return status;
}

int cx_fem_assemble_stiffness(const cx_mesh *m, const cx_material *mats, cx_csc *K, cx_diag *d)
{
    return assemble(m, mats, NULL, K, NULL, d);
}

int cx_fem_assemble_free(const cx_mesh *m, const cx_material *mats, const cx_dofmap *map, cx_csc *K,
                         double *fd, cx_diag *d)
{
    if (!map)
        return cx_diag_set(d, CX_EINVAL, "no Dirichlet map");
    return assemble(m, mats, map, K, fd, d);
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
