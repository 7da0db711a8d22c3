/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The structured 2D grid behind the rectangle and the Hertz quarter disc:
 * connectivity and boundaries in lattice indices, coordinates left to the
 * caller. */
#include "mesh/mesh_impl.h"

#include <string.h>

typedef struct grid {
    int q;      /* lattice points per cell edge: 2 for TRI6, else 1 */
    int w;      /* lattice width q nx + 1 */
} grid;

static int grid_node(const grid *g, int I, int J) { return J * g->w + I; }

/* The node halfway (in the lattice) between two vertex nodes: a P2
 * mid-edge node, shared by both triangles of the edge because it depends
 * only on the edge's ends. */
static int grid_mid(const grid *g, int a, int b)
{
    int I = (a % g->w + b % g->w) / 2, J = (a / g->w + b / g->w) / 2;
    return grid_node(g, I, J);
}

static void put_triangle(const grid *g, int *c, int v0, int v1, int v2, int flip, int p2)
{
    if (flip) {
        int t = v1;
        v1 = v2;
        v2 = t;
    }
    c[0] = v0, c[1] = v1, c[2] = v2;
    if (p2)
        c[3] = grid_mid(g, v0, v1), c[4] = grid_mid(g, v1, v2), c[5] = grid_mid(g, v2, v0);
}

/* Side s walked counter-clockwise in the lattice (body on the left), one
 * cell edge per facet; flip reverses the walk, which is counter-clockwise
 * again after the orientation-reversing map. */
static void put_side(const grid *g, cx_boundary *b, int s, int nx, int ny, int flip, int p2)
{
    int n = b->nfacets, q = g->q;
    for (int k = 0; k < n; k++) {
        int a, e;   /* lattice nodes at the start and end of edge k */
        switch (s) {
        case 0: a = grid_node(g, q * k, 0), e = grid_node(g, q * (k + 1), 0); break;
        case 1: a = grid_node(g, q * nx, q * k), e = grid_node(g, q * nx, q * (k + 1)); break;
        case 2: a = grid_node(g, q * (nx - k), q * ny), e = grid_node(g, q * (nx - k - 1), q * ny); break;
        default: a = grid_node(g, 0, q * (ny - k)), e = grid_node(g, 0, q * (ny - k - 1)); break;
        }
        int *f = b->facets + b->npf * (flip ? n - 1 - k : k);
        f[0] = flip ? e : a;
        f[1] = flip ? a : e;
        if (p2)
            f[2] = grid_mid(g, a, e);
    }
}

int cx_mesh_grid2d(cx_mesh **m, int nx, int ny, cx_elem_type t, int flip,
                   const char *const side[4], cx_diag *d)
{
    *m = NULL;
    if (t != CX_EL_TRI3 && t != CX_EL_TRI6 && t != CX_EL_QUAD4)
        return cx_diag_set(d, CX_EINVAL, "element '%s' is not a 2D element (tri3, tri6 or quad4)",
                           cx_elem_name(t));
    if (nx < 1 || ny < 1)
        return cx_diag_set(d, CX_EINVAL, "cells %d x %d: need at least 1 x 1", nx, ny);
    grid g = {.q = t == CX_EL_TRI6 ? 2 : 1};
    int per_cell = t == CX_EL_QUAD4 ? 1 : 2;
    CX_TRY(cx_mesh_check_size(((double)g.q * nx + 1) * ((double)g.q * ny + 1), "nodes", d));
    CX_TRY(cx_mesh_check_size((double)nx * ny * per_cell * cx_elem_npe(t), "element node slots", d));
    g.w = g.q * nx + 1;

    cx_mesh *p;
    int nnodes = g.w * (g.q * ny + 1), p2 = t == CX_EL_TRI6;
    if (cx_mesh_alloc(&p, 2, nnodes, t, per_cell * nx * ny, 4))
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    int *c = p->conn;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            int n00 = grid_node(&g, g.q * i, g.q * j), n10 = grid_node(&g, g.q * (i + 1), g.q * j);
            int n11 = grid_node(&g, g.q * (i + 1), g.q * (j + 1)), n01 = grid_node(&g, g.q * i, g.q * (j + 1));
            if (t == CX_EL_QUAD4) {
                c[0] = n00, c[1] = flip ? n01 : n10, c[2] = n11, c[3] = flip ? n10 : n01;
                c += 4;
            } else {
                put_triangle(&g, c, n00, n10, n11, flip, p2);
                c += p->npe;
                put_triangle(&g, c, n00, n11, n01, flip, p2);
                c += p->npe;
            }
        }
    for (int s = 0; s < 4; s++) {
        if (cx_mesh_alloc_boundary(&p->bounds[s], side[s], s % 2 ? ny : nx, p2 ? 3 : 2)) {
            cx_mesh_destroy(&p);
            return cx_diag_set(d, CX_ENOMEM, "out of memory");
        }
        put_side(&g, &p->bounds[s], s, nx, ny, flip, p2);
    }
    *m = p;
    return CX_OK;
}
