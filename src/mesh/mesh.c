/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The mesh object: element tables, destruction, boundary look-up, and the
 * allocation helpers the generators share. */
#include "mesh/mesh_impl.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const struct {
    const char *name;
    int npe, dim;
} elem_table[] = {
    [CX_EL_TRI3] = {"tri3", 3, 2},
    [CX_EL_TRI6] = {"tri6", 6, 2},
    [CX_EL_QUAD4] = {"quad4", 4, 2},
    [CX_EL_HEX8] = {"hex8", 8, 3},
    [CX_EL_TET4] = {"tet4", 4, 3},
};
#define ELEM_COUNT ((int)(sizeof elem_table / sizeof elem_table[0]))

static int elem_known(cx_elem_type t) { return (int)t >= 0 && (int)t < ELEM_COUNT; }

int cx_elem_npe(cx_elem_type t) { return elem_known(t) ? elem_table[t].npe : 0; }
int cx_elem_dim(cx_elem_type t) { return elem_known(t) ? elem_table[t].dim : 0; }
const char *cx_elem_name(cx_elem_type t) { return elem_known(t) ? elem_table[t].name : "unknown"; }

int cx_elem_from_name(const char *name)
{
    for (int k = 0; name && k < ELEM_COUNT; k++)
        if (strcmp(name, elem_table[k].name) == 0)
            return k;
    return -1;
}

void cx_mesh_destroy(cx_mesh **m)
{
    if (!m || !*m)
        return;
    cx_mesh *p = *m;
    cx_free(p->x);
    cx_free(p->conn);
    cx_free(p->body);
    cx_free(p->mat);
    for (int k = 0; p->bounds && k < p->nbounds; k++)
        cx_free(p->bounds[k].facets);
    cx_free(p->bounds);
    cx_free(p);
    *m = NULL;
}

const cx_boundary *cx_mesh_boundary(const cx_mesh *m, const char *name)
{
    for (int k = 0; m && name && k < m->nbounds; k++)
        if (strcmp(m->bounds[k].name, name) == 0)
            return &m->bounds[k];
    return NULL;
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

int cx_boundary_nodes(const cx_boundary *b, int **nodes, int *count)
{
    size_t n = (size_t)b->nfacets * (size_t)b->npf;
    int *v = CX_NEW(int, n);
    *nodes = NULL;
    *count = 0;
    if (!v)
        return CX_ENOMEM;
    memcpy(v, b->facets, sizeof(int) * n);
    qsort(v, n, sizeof(int), cmp_int);
    size_t w = 0;
    for (size_t k = 0; k < n; k++)
        if (w == 0 || v[w - 1] != v[k])
            v[w++] = v[k];
    *nodes = v;
    *count = (int)w;
    return CX_OK;
}

int cx_mesh_alloc(cx_mesh **m, int dim, int nnodes, cx_elem_type t, int nelems, int nbounds)
{
    cx_mesh *p = CX_NEW(cx_mesh, 1);
    *m = NULL;
    if (!p)
        return CX_ENOMEM;
    p->dim = dim;
    p->nnodes = nnodes;
    p->etype = t;
    p->npe = cx_elem_npe(t);
    p->nelems = nelems;
    p->nbodies = 1;
    p->nbounds = nbounds;
    p->x = CX_NEW(double, (size_t)dim * (size_t)nnodes);
    p->conn = CX_NEW(int, (size_t)p->npe * (size_t)nelems);
    p->bounds = CX_NEW(cx_boundary, nbounds);
    if (!p->x || !p->conn || !p->bounds) {
        cx_mesh_destroy(&p);
        return CX_ENOMEM;
    }
    *m = p;
    return CX_OK;
}

int cx_mesh_alloc_boundary(cx_boundary *b, const char *name, int nfacets, int npf)
{
    snprintf(b->name, sizeof b->name, "%s", name);
    b->nfacets = nfacets;
    b->npf = npf;
    b->facets = CX_NEW(int, (size_t)nfacets * (size_t)npf);
    return b->facets ? CX_OK : CX_ENOMEM;
}

int cx_mesh_check_size(double count, const char *what, cx_diag *d)
{
    /* 3 * count must still be an int: coordinates and dofs are indexed by
     * dim * node, and the dof count dim * nnodes by int everywhere */
    if (count > INT_MAX / 3)
        return cx_diag_set(d, CX_EINVAL, "mesh too large: %.0f %s (at most %d)", count, what,
                           INT_MAX / 3);
    return CX_OK;
}
