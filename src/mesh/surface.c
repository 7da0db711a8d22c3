/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The facets of a mesh and its surface: every element facet (2D edges, 3D
 * faces) once, with the number of elements that share it, and the outline
 * (the edges of the surface facets). The one extraction that the explorer's
 * mesh view and the renderer both use. Facets are matched by their sorted
 * corner nodes, so nodes repeated per body (twoblocks, masonry) keep the
 * bodies' surfaces apart. */
#include "mesh/mesh.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

/* Local facets: 2D edges (end, end, TRI6 mid node or -1), 3D faces with
 * the outward normal by the right-hand rule for a right-handed element. */
static const int surf_tri3[][4] = {{0, 1, -1, -1}, {1, 2, -1, -1}, {2, 0, -1, -1}};
static const int surf_tri6[][4] = {{0, 1, 3, -1}, {1, 2, 4, -1}, {2, 0, 5, -1}};
static const int surf_quad4[][4] = {{0, 1, -1, -1}, {1, 2, -1, -1}, {2, 3, -1, -1}, {3, 0, -1, -1}};
static const int surf_hex8[][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                   {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
static const int surf_tet4[][4] = {{0, 2, 1, -1}, {0, 1, 3, -1}, {1, 2, 3, -1}, {0, 3, 2, -1}};

int cx_elem_facets(cx_elem_type t, const int (**local)[4], int *npf)
{
    switch (t) {
    case CX_EL_TRI3: *local = surf_tri3, *npf = 2; return 3;
    case CX_EL_TRI6: *local = surf_tri6, *npf = 2; return 3;
    case CX_EL_QUAD4: *local = surf_quad4, *npf = 2; return 4;
    case CX_EL_HEX8: *local = surf_hex8, *npf = 4; return 6;
    case CX_EL_TET4: *local = surf_tet4, *npf = 3; return 4;
    }
    *local = NULL;
    *npf = 0;
    return 0;
}

typedef struct {
    int key[4];   /* sorted corner nodes, INT_MAX padded */
    long tag;     /* nf e + local facet: ties broken by it, so the first
                   * element of a group is the one that has it first */
} surf_item;

static int surf_cmp(const void *a, const void *b)
{
    const surf_item *x = a, *y = b;
    for (int k = 0; k < 4; k++)
        if (x->key[k] != y->key[k])
            return x->key[k] < y->key[k] ? -1 : 1;
    return (x->tag > y->tag) - (x->tag < y->tag);
}

static int surf_same(const surf_item *x, const surf_item *y)
{
    return memcmp(x->key, y->key, sizeof x->key) == 0;
}

static void surf_sort4(int *k)
{
    for (int i = 1; i < 4; i++)
        for (int j = i; j > 0 && k[j - 1] > k[j]; j--) {
            int t = k[j];
            k[j] = k[j - 1];
            k[j - 1] = t;
        }
}

void cx_facets_clear(cx_facets *f)
{
    if (!f)
        return;
    cx_free(f->nodes);
    cx_free(f->mid);
    cx_free(f->uses);
    memset(f, 0, sizeof *f);
}

int cx_mesh_facets(const cx_mesh *m, int surface, cx_facets *out)
{
    memset(out, 0, sizeof *out);
    const int (*lf)[4];
    int npf, nf = cx_elem_facets(m->etype, &lf, &npf);
    size_t n = (size_t)nf * (size_t)m->nelems;
    surf_item *it = CX_NEW(surf_item, n + 1);
    int *uses = CX_NEW(int, n + 1);   /* by tag: group size at its first tag, else 0 */
    if (!it || !uses) {
        cx_free(it);
        cx_free(uses);
        return CX_ENOMEM;
    }
    for (int e = 0; e < m->nelems; e++) {
        const int *c = m->conn + (size_t)m->npe * e;
        for (int k = 0; k < nf; k++) {
            surf_item *q = &it[(size_t)e * nf + k];
            for (int i = 0; i < 4; i++)
                q->key[i] = i < npf ? c[lf[k][i]] : INT_MAX;
            surf_sort4(q->key);
            q->tag = (long)e * nf + k;
        }
    }
    qsort(it, n, sizeof *it, surf_cmp);
    size_t count = 0;
    for (size_t i = 0, j; i < n; i = j) {
        for (j = i + 1; j < n && surf_same(&it[i], &it[j]); j++)
            ;
        if (!surface || j == i + 1) {
            uses[it[i].tag] = (int)(j - i);
            count++;
        }
    }
    cx_free(it);
    out->npf = npf;
    out->nodes = CX_NEW(int, (size_t)npf * count + 1);
    out->uses = CX_NEW(int, count + 1);
    if (m->etype == CX_EL_TRI6)
        out->mid = CX_NEW(int, count + 1);
    if (!out->nodes || !out->uses || (m->etype == CX_EL_TRI6 && !out->mid)) {
        cx_free(uses);
        cx_facets_clear(out);
        return CX_ENOMEM;
    }
    /* in the order of the elements: depends only on the mesh */
    for (size_t t = 0; t < n; t++) {
        if (!uses[t])
            continue;
        const int *c = m->conn + (size_t)m->npe * (t / (size_t)nf);
        const int *l = lf[t % (size_t)nf];
        for (int i = 0; i < npf; i++)
            out->nodes[(size_t)npf * out->n + i] = c[l[i]];
        if (out->mid)
            out->mid[out->n] = c[l[2]];
        out->uses[out->n++] = uses[t];
    }
    cx_free(uses);
    return CX_OK;
}

static int surf_cmp_pair(const void *a, const void *b)
{
    const int *x = a, *y = b;
    if (x[0] != y[0])
        return x[0] < y[0] ? -1 : 1;
    return (x[1] > y[1]) - (x[1] < y[1]);
}

int cx_mesh_outline(const cx_mesh *m, int **pairs, int *count)
{
    *pairs = NULL;
    *count = 0;
    cx_facets f;
    CX_TRY(cx_mesh_facets(m, 1, &f));
    /* at most npf edges per facet (2 for a split TRI6 edge) */
    size_t cap = (size_t)f.n * (f.npf == 2 ? 2 : (size_t)f.npf);
    int *e = CX_NEW(int, 2 * cap + 2);
    if (!e) {
        cx_facets_clear(&f);
        return CX_ENOMEM;
    }
    size_t ne = 0;
    for (int i = 0; i < f.n; i++) {
        const int *q = f.nodes + (size_t)f.npf * i;
        int poly[5], np = 0;
        /* the facet's boundary as a closed polygon or an open path */
        if (f.npf == 2) {
            poly[np++] = q[0];
            if (f.mid)
                poly[np++] = f.mid[i];
            poly[np++] = q[1];
        } else {
            for (int k = 0; k <= f.npf; k++)
                poly[np++] = q[k % f.npf];
        }
        for (int k = 0; k + 1 < np; k++) {
            int a = poly[k], b = poly[k + 1];
            e[2 * ne] = a < b ? a : b;
            e[2 * ne + 1] = a < b ? b : a;
            ne++;
        }
    }
    cx_facets_clear(&f);
    /* an edge shared by two surface faces once */
    qsort(e, ne, 2 * sizeof(int), surf_cmp_pair);
    size_t w = 0;
    for (size_t k = 0; k < ne; k++)
        if (w == 0 || e[2 * (w - 1)] != e[2 * k] || e[2 * (w - 1) + 1] != e[2 * k + 1]) {
            e[2 * w] = e[2 * k];
            e[2 * w + 1] = e[2 * k + 1];
            w++;
        }
    *pairs = e;
    *count = (int)w;
    return CX_OK;
}
