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
 * records per element and node pair (pos: npe^2 bytes or ints per
 * element), plus the rank of i among a's free dofs: the scatter searches
 * nothing. Each
 * entry is the sum of its element contributions in element order, the
 * same sums, bitwise, as the reduction of the matrix over all dofs
 * (cx_fem_reduce) gives. */
#define _DEFAULT_SOURCE   /* madvise */
#include "fem/element_impl.h"

#include <limits.h>
#include <stdint.h>
#include <string.h>
#include <sys/mman.h>

/* Ask for transparent huge pages on the 2 MiB-aligned part of a large
 * array not yet touched (K's rows and values, the positions): a fresh
 * array of 4 KiB pages faults once per page on its first write, some 5600
 * faults for K of hertz 256 (22 MB), which cost as much as the assembly's
 * arithmetic; with huge pages they are a dozen. Only advice: where the
 * kernel has THP off, or the array is small, nothing changes. */
static void advise_huge(void *p, size_t bytes)
{
#ifdef MADV_HUGEPAGE
    const uintptr_t huge = (uintptr_t)2 << 20;
    if (bytes < 2 * huge)
        return;
    uintptr_t lo = ((uintptr_t)p + huge - 1) & ~(huge - 1), hi = ((uintptr_t)p + bytes) & ~(huge - 1);
    if (hi > lo)
        (void)madvise((void *)lo, hi - lo, MADV_HUGEPAGE);
#else
    (void)p;
    (void)bytes;
#endif
}

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
 * go (header). The positions are bytes when every column is short enough
 * (at most 256 entries: every 2D mesh and structured hexahedra), a
 * quarter of the memory the scatter reads, else ints. */
typedef struct pattern {
    int *cbase;            /* nnodes: first entry of the node's first free column */
    int *len;              /* nnodes: entries of each free column of the node */
    unsigned char *fm;     /* nnodes: bit c set when dof (node, c) is free */
    unsigned char *pos8;   /* nelems npe^2: element e, column node b, row node a at */
    int *pos32;            /* npe (npe e + b) + a: offset of a's rows in b's columns */
} pattern;

static void pattern_clear(pattern *g)
{
    cx_free(g->cbase);
    cx_free(g->len);
    cx_free(g->fm);
    cx_free(g->pos8);
    cx_free(g->pos32);
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
CX_FEM_INLINE int node_neighbours(const int *conn, int npe, const int *ip, const int *inc, int b,
                                  int *mark, int *adj)
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

/* The pass over the nodes of pattern_build, inlined with constant dim,
 * npe and position size: per node b, its neighbours, the offsets of their
 * rows in its columns (off, by node), its elements' positions, its
 * columns' rows. Returns K's entries, -1 past INT_MAX; *cols counts the
 * free columns met. */
CX_FEM_INLINE long long pattern_nodes(int dim, int npe, int bytes, const cx_mesh *m,
                                      const cx_dofmap *map, const int *restrict ip,
                                      const int *restrict inc, int *restrict mark,
                                      int *restrict off, int *restrict nb, pattern *g, cx_csc *K,
                                      int *cols)
{
    const int *restrict conn = m->conn, *restrict free_of = map ? map->free_of : NULL;
    const unsigned char *restrict fm = g->fm;
    unsigned char *restrict pos8 = g->pos8;
    int *restrict pos32 = g->pos32, *restrict len_of = g->len, *restrict cbase = g->cbase;
    int *restrict Kp = K->p, *restrict Ki = K->i;
    int nn = m->nnodes, ncol = K->ncol, col = 0;
    long long nnz = 0;
    for (int b = 0; b < nn; b++)
        mark[b] = -1;
    for (int b = 0; b < nn; b++) {
        int deg = node_neighbours(conn, npe, ip, inc, b, mark, nb), len = 0;
        for (int k = 0; k < deg; k++) {
            off[nb[k]] = len;
            len += popcount(fm[nb[k]]);
        }
        for (int q = ip[b]; q < ip[b + 1]; q++) {
            int e = inc[q] / npe, lb = inc[q] % npe;
            const int *nodes = conn + (size_t)npe * (size_t)e;
            size_t at = (size_t)npe * ((size_t)npe * (size_t)e + (size_t)lb);
            for (int a = 0; a < npe; a++) {
                if (bytes)
                    pos8[at + (size_t)a] = (unsigned char)off[nodes[a]];
                else
                    pos32[at + (size_t)a] = off[nodes[a]];
            }
        }
        int nf = popcount(fm[b]);
        len_of[b] = len;
        cbase[b] = (int)nnz;
        if (nnz + (long long)len * nf > INT_MAX)
            return -1;
        if (nf > 0) {   /* no column, no rows */
            int *ki = Ki + nnz;
            for (int k = 0; k < deg; k++) {
                int a = nb[k];
                for (int i = 0; i < dim; i++)
                    if ((fm[a] >> i) & 1u)
                        *ki++ = free_of ? free_of[dim * a + i] : dim * a + i;
            }
            for (int t = 0; t < nf && col < ncol; t++) {   /* col < ncol: a map not of this mesh */
                Kp[col++] = (int)nnz + t * len;
                if (t > 0)
                    memcpy(Ki + nnz + t * len, Ki + nnz, sizeof(int) * (size_t)len);
            }
        }
        nnz += (long long)len * nf;
        *cols += nf;
    }
    return nnz;
}

/* pattern_nodes for the mesh's element type, one instance per type and
 * position size. */
static long long pattern_type(const cx_mesh *m, const cx_dofmap *map, const int *ip, const int *inc,
                              int *mark, int *off, int *nb, pattern *g, cx_csc *K, int *cols)
{
#define CX_PATTERN_CASE(t, dim, npe)                                                                     \
    case t:                                                                                              \
        return g->pos8 ? pattern_nodes(dim, npe, 1, m, map, ip, inc, mark, off, nb, g, K, cols)         \
                       : pattern_nodes(dim, npe, 0, m, map, ip, inc, mark, off, nb, g, K, cols);
    switch (m->etype) {
        CX_PATTERN_CASE(CX_EL_TRI3, 2, 3)
        CX_PATTERN_CASE(CX_EL_TRI6, 2, 6)
        CX_PATTERN_CASE(CX_EL_QUAD4, 2, 4)
        CX_PATTERN_CASE(CX_EL_HEX8, 3, 8)
        CX_PATTERN_CASE(CX_EL_TET4, 3, 4)
    }
#undef CX_PATTERN_CASE
    return 0;   /* checked by the caller (cx_fem_ref_init) */
}

/* The pattern over the free dofs of map (NULL: every dof), K's p and i
 * with zero values, in one pass over the nodes: node b's neighbours, the
 * offsets of its elements' entries, then its columns' rows written
 * straight into K->i (the first column, then its copies while they are
 * in cache). K->i is allocated at a bound on its size known before the
 * pass (each incidence of b brings at most npe neighbours of dim dofs),
 * of which only the pages written are ever touched, and shrunk after.
 * CX_EINVAL (message in d) if K would hold more than INT_MAX entries. */
static int pattern_build(const cx_mesh *m, const cx_dofmap *map, pattern *g, cx_csc *K, cx_diag *d)
{
    int nn = m->nnodes, npe = m->npe, dim = m->dim, status = CX_ENOMEM;
    const unsigned full = (1u << dim) - 1;
    size_t ninc = (size_t)m->nelems * (size_t)npe, npair = ninc * (size_t)npe;
    int *ip = NULL, *inc = NULL, *mark = NULL, *off = NULL, *nb = NULL;

    memset(g, 0, sizeof *g);
    memset(K, 0, sizeof *K);
    if (npair > INT_MAX)
        return cx_diag_set(d, CX_EINVAL, "mesh too large to assemble: %d elements of %d nodes",
                           m->nelems, npe);
    ip = CX_NEW(int, nn + 1);
    inc = CX_NEW(int, ninc ? ninc : 1);
    mark = CX_NEW(int, nn);
    off = CX_NEW(int, nn);
    g->cbase = CX_NEW(int, nn);
    g->len = CX_NEW(int, nn);
    g->fm = CX_NEW(unsigned char, nn);
    if (!ip || !inc || !mark || !off || !g->cbase || !g->len || !g->fm)
        goto done;
    for (int b = 0; b < nn; b++) {
        unsigned f = full;
        for (int c = 0; map && c < dim; c++)
            if (map->free_of[dim * b + c] < 0)
                f &= ~(1u << c);
        g->fm[b] = (unsigned char)f;
    }
    /* the incidences of each node, and the bounds: on a column's length
     * (dim npe incidences) and on K's entries */
    for (size_t k = 0; k < ninc; k++)
        ip[m->conn[k] + 1]++;
    int maxinc = 0;
    size_t bound = 0;
    for (int b = 0; b < nn; b++) {
        maxinc = ip[b + 1] > maxinc ? ip[b + 1] : maxinc;
        bound += (size_t)popcount(g->fm[b]) * (size_t)(dim * npe) * (size_t)ip[b + 1];
        ip[b + 1] += ip[b];
    }
    memcpy(mark, ip, sizeof(int) * (size_t)nn);
    for (size_t k = 0; k < ninc; k++)
        inc[mark[m->conn[k]]++] = (int)k;
    if ((long long)dim * npe * maxinc <= 256)
        g->pos8 = cx_malloc(npair ? npair : 1);
    else
        g->pos32 = cx_malloc(sizeof(int) * (npair ? npair : 1));
    nb = CX_NEW(int, npe * maxinc + 1);
    int ncol = map ? map->nfree : dim * nn;
    K->nrow = K->ncol = ncol;
    K->p = CX_NEW(int, ncol + 1);
    K->i = cx_malloc(sizeof(int) * (bound ? bound : 1));
    if (!nb || (!g->pos8 && !g->pos32) || !K->p || !K->i)
        goto done;
    advise_huge(K->i, sizeof(int) * bound);
    advise_huge(g->pos8 ? (void *)g->pos8 : (void *)g->pos32, npair * (g->pos8 ? 1 : sizeof(int)));
    int cols = 0;
    long long nnz = pattern_type(m, map, ip, inc, mark, off, nb, g, K, &cols);
    if (nnz < 0) {
        status = cx_diag_set(d, CX_EINVAL, "mesh too large to assemble: over %d entries in K", INT_MAX);
        goto done;
    }
    if (cols != ncol) {   /* a map not of this mesh */
        status = CX_EINVAL;
        goto done;
    }
    K->p[ncol] = (int)nnz;
    int *shrunk = cx_realloc(K->i, sizeof(int) * (size_t)(nnz ? nnz : 1));
    if (shrunk)
        K->i = shrunk;
    /* zeroed by writing, not calloc: fresh pages from calloc are mapped
     * to the zero page and the scatter's first += then faults twice on
     * each (a read, then a copy on write) */
    K->x = cx_malloc(sizeof(double) * (size_t)(nnz ? nnz : 1));
    if (!K->x)
        goto done;
    advise_huge(K->x, sizeof(double) * (size_t)nnz);
    memset(K->x, 0, sizeof(double) * (size_t)nnz);
    status = CX_OK;
done:
    if (status) {
        pattern_clear(g);
        cx_csc_clear(K);
    }
    cx_free(ip);
    cx_free(inc);
    cx_free(mark);
    cx_free(off);
    cx_free(nb);
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
 * scatter of the nodes whose dofs are all free are fixed-size loops. Ke
 * is exactly symmetric: column (b j) is read along its contiguous row (a
 * scatter reading the upper triangle only, without the kernel's mirror
 * copy, was slower: strided reads). Returns the first element whose
 * kernel fails, or -1. */
CX_FEM_INLINE int assemble_elements(int dim, int npe, int nq, int affine, int bytes,
                                    const cx_mesh *restrict m, const cx_dofmap *map,
                                    const cx_fem_ref *restrict ref,
                                    const double *restrict D, const pattern *restrict g,
                                    double *restrict Kx, double *restrict fd)
{
    const int nd = dim * npe, ns = cx_fem_nstress(dim);
    const unsigned full = (1u << dim) - 1;
    double xe[3 * CX_FEM_MAXNPE], Ke[CX_FEM_MAXDOF * CX_FEM_MAXDOF];
    for (int e = 0; e < m->nelems; e++) {
        const int *nodes = m->conn + npe * e;
        size_t pe = (size_t)npe * (size_t)npe * (size_t)e;
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
                size_t at = pe + (size_t)(npe * b + a);
                double *restrict blk = col + (bytes ? g->pos8[at] : g->pos32[at]);
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

/* assemble_elements for the mesh's element type, one instance per type
 * and position size (bytes: constant where this is inlined). */
CX_FEM_INLINE int assemble_type(const cx_mesh *m, const cx_dofmap *map, const cx_fem_ref *ref,
                                const double *D, const pattern *g, double *Kx, double *fd, int bytes)
{
    switch (m->etype) {
    case CX_EL_TRI3: return assemble_elements(2, 3, 1, 1, bytes, m, map, ref, D, g, Kx, fd);
    case CX_EL_TRI6: return assemble_elements(2, 6, 3, 0, bytes, m, map, ref, D, g, Kx, fd);
    case CX_EL_QUAD4: return assemble_elements(2, 4, 4, 0, bytes, m, map, ref, D, g, Kx, fd);
    case CX_EL_HEX8: return assemble_elements(3, 8, 8, 0, bytes, m, map, ref, D, g, Kx, fd);
    case CX_EL_TET4: return assemble_elements(3, 4, 1, 1, bytes, m, map, ref, D, g, Kx, fd);
    }
    return 0;   /* refused by cx_fem_ref_init before */
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

    int bad = g.pos8 ? assemble_type(m, map, &ref, D, &g, K->x, fd, 1)
                     : assemble_type(m, map, &ref, D, &g, K->x, fd, 0);
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
