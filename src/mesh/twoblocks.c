/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Two stacked rectangles as one mesh with two bodies (paper 000 §7):
 * body 0 (Omega^1) on [x0,x1] x [ym,y1] above body 1 (Omega^2) on
 * [x0,x1] x [y0,ym]. Each block is a structured rectangle with its own cell
 * counts, so the interface y = ym may be non-matching; the interface nodes
 * are duplicated (one copy per body), as two-body contact needs. */
#include "mesh/mesh_impl.h"

#include <stdio.h>
#include <string.h>

/* Append the nodes, elements (with body id b) and boundaries of r to m at
 * node offset off, renaming r's boundary "side" to "side<b+1>". */
static void twoblocks_append(cx_mesh *m, const cx_mesh *r, int node_off, int elem_off,
                             int bound_off, int b)
{
    memcpy(m->x + 2 * node_off, r->x, sizeof(double) * 2 * (size_t)r->nnodes);
    for (int k = 0; k < r->npe * r->nelems; k++)
        m->conn[m->npe * elem_off + k] = r->conn[k] + node_off;
    for (int e = 0; e < r->nelems; e++)
        m->body[elem_off + e] = b;
    for (int s = 0; s < r->nbounds; s++) {
        cx_boundary *dst = &m->bounds[bound_off + s];
        const cx_boundary *src = &r->bounds[s];
        for (int k = 0; k < src->npf * src->nfacets; k++)
            dst->facets[k] = src->facets[k] + node_off;
    }
}

int cx_mesh_twoblocks(cx_mesh **m, double x0, double y0, double ym, double x1, double y1,
                      const int cells_upper[2], const int cells_lower[2], cx_elem_type t,
                      cx_diag *d)
{
    cx_mesh *up = NULL, *lo = NULL, *p = NULL;
    int st;
    *m = NULL;
    if (!(ym > y0) || !(y1 > ym))
        return cx_diag_set(d, CX_EINVAL, "two blocks: need y0 < interface < y1 (got %g, %g, %g)",
                           y0, ym, y1);
    if ((st = cx_mesh_rectangle(&up, x0, ym, x1, y1, cells_upper[0], cells_upper[1], t, d)) ||
        (st = cx_mesh_rectangle(&lo, x0, y0, x1, ym, cells_lower[0], cells_lower[1], t, d)))
        goto done;
    if ((st = cx_mesh_check_size((double)up->nnodes + lo->nnodes, "nodes", d)))
        goto done;
    if (cx_mesh_alloc(&p, 2, up->nnodes + lo->nnodes, t, up->nelems + lo->nelems,
                      up->nbounds + lo->nbounds) ||
        !(p->body = CX_NEW(int, p->nelems))) {
        st = cx_diag_set(d, CX_ENOMEM, "out of memory");
        goto done;
    }
    p->nbodies = 2;
    const cx_mesh *part[2] = {up, lo};
    for (int b = 0, nb = 0; b < 2; b++)
        for (int s = 0; s < part[b]->nbounds; s++, nb++) {
            char name[24];
            const cx_boundary *src = &part[b]->bounds[s];
            snprintf(name, sizeof name, "%.20s%d", src->name, b + 1);
            if (cx_mesh_alloc_boundary(&p->bounds[nb], name, src->nfacets, src->npf)) {
                st = cx_diag_set(d, CX_ENOMEM, "out of memory");
                goto done;
            }
        }
    twoblocks_append(p, up, 0, 0, 0, 0);
    twoblocks_append(p, lo, up->nnodes, up->nelems, up->nbounds, 1);
    *m = p;
    p = NULL;
done:
    cx_mesh_destroy(&up);
    cx_mesh_destroy(&lo);
    cx_mesh_destroy(&p);
    return st;
}
