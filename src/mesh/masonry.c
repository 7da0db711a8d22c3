/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Masonry walls of paper 003 (§5, Fig. 2): stack bond, running bond and
 * laminae on the unit square, every body meshed on its own with P2
 * triangles of size H, coincident nodes on the joints. */
#include "mesh/mesh_impl.h"

#include <string.h>

enum { MB_LEFT, MB_RIGHT, MB_TOP, MB_SETTLE, MB_BASE, MB_JOINTS, MB_NBOUNDS };
static const char *const mb_names[MB_NBOUNDS] = {"left", "right", "top", "settle", "base", "joints"};

long cx_masonry_bodies(cx_bond bond, int N)
{
    switch (bond) {
    case CX_BOND_STACK: return (long)N * N;
    case CX_BOND_RUNNING: return (long)N * (N + 1) / 2;
    case CX_BOND_LAMINAE: return N;
    }
    return 0;
}

/* The bodies of course j as (first cell, width in cells); returns their
 * number. start and width hold at least N entries. */
static int mb_course(cx_bond bond, int N, int j, int *start, int *width)
{
    int nb = 0, x = 0;
    if (bond == CX_BOND_STACK) {
        for (; x < N; x++)
            start[nb] = x, width[nb++] = 1;
    } else if (bond == CX_BOND_LAMINAE) {
        start[nb] = 0, width[nb++] = N;
    } else if (N % 2 == 0) {
        int half = j % 2;   /* odd courses start and end with a half brick */
        while (x < N) {
            int w = (half && (x == 0 || x == N - 1)) ? 1 : 2;
            start[nb] = x, width[nb++] = w;
            x += w;
        }
    } else {
        int half_left = j % 2;   /* the half brick alternates: right end, then left */
        while (x < N) {
            int w = (half_left && x == 0) || (!half_left && x == N - 1) ? 1 : 2;
            start[nb] = x, width[nb++] = w;
            x += w;
        }
    }
    return nb;
}

/* Which boundary a body's edge falls on (side: 0 bottom, 1 right, 2 top,
 * 3 left); k is the cell along the bottom or top. */
static int mb_side_boundary(int N, int j, int x0, int w, int side, int k)
{
    switch (side) {
    case 0:
        if (j > 0)
            return MB_JOINTS;
        return 2 * (x0 + k + 1) <= N ? MB_SETTLE : MB_BASE;   /* ends at x <= 1/2 */
    case 1: return x0 + w == N ? MB_RIGHT : MB_JOINTS;
    case 2: return j == N - 1 ? MB_TOP : MB_JOINTS;
    default: return x0 == 0 ? MB_LEFT : MB_JOINTS;
    }
}

/* Walk every body: count (fill == 0) or fill nodes, elements and facets. */
static void mb_walk(cx_mesh *m, cx_bond bond, int N, int *start, int *width, int fill,
                    int *nnodes, int *nelems, int *nfacets)
{
    int node0 = 0, el = 0, body = 0, nf[MB_NBOUNDS] = {0};
    double scale = 2.0 * N;
    for (int j = 0; j < N; j++) {
        int nb = mb_course(bond, N, j, start, width);
        for (int b = 0; b < nb; b++, body++) {
            int x0 = start[b], w = width[b], lw = 2 * w + 1;   /* lattice width */
#define MB_NODE(I, J) (node0 + (J) * lw + (I))
            if (fill) {
                for (int J = 0; J < 3; J++)
                    for (int I = 0; I < lw; I++) {
                        m->x[2 * MB_NODE(I, J)] = (2 * x0 + I) / scale;
                        m->x[2 * MB_NODE(I, J) + 1] = (2 * j + J) / scale;
                    }
                for (int c = 0; c < w; c++) {
                    /* two triangles along the (0,0)-(1,1) diagonal, as grid2d */
                    int *e = m->conn + 6 * (el + 2 * c);
                    int I = 2 * c;
                    int t0[6] = {MB_NODE(I, 0), MB_NODE(I + 2, 0), MB_NODE(I + 2, 2),
                                 MB_NODE(I + 1, 0), MB_NODE(I + 2, 1), MB_NODE(I + 1, 1)};
                    int t1[6] = {MB_NODE(I, 0), MB_NODE(I + 2, 2), MB_NODE(I, 2),
                                 MB_NODE(I + 1, 1), MB_NODE(I + 1, 2), MB_NODE(I, 1)};
                    memcpy(e, t0, sizeof t0);
                    memcpy(e + 6, t1, sizeof t1);
                    m->body[el + 2 * c] = m->body[el + 2 * c + 1] = body;
                }
            }
            el += 2 * w;
            /* facets, counter-clockwise (body on the left): ends, then middle */
            for (int side = 0; side < 4; side++) {
                int ncell = side % 2 ? 1 : w;
                for (int k = 0; k < ncell; k++) {
                    int a, e, mid;
                    switch (side) {
                    case 0: a = MB_NODE(2 * k, 0), e = MB_NODE(2 * k + 2, 0), mid = MB_NODE(2 * k + 1, 0); break;
                    case 1: a = MB_NODE(lw - 1, 0), e = MB_NODE(lw - 1, 2), mid = MB_NODE(lw - 1, 1); break;
                    case 2: a = MB_NODE(lw - 1 - 2 * k, 2), e = MB_NODE(lw - 3 - 2 * k, 2),
                            mid = MB_NODE(lw - 2 - 2 * k, 2); break;
                    default: a = MB_NODE(0, 2), e = MB_NODE(0, 0), mid = MB_NODE(0, 1); break;
                    }
                    int kk = side == 2 ? w - 1 - k : k;
                    int bd = mb_side_boundary(N, j, x0, w, side, kk);
                    if (fill) {
                        int *f = m->bounds[bd].facets + 3 * nf[bd];
                        f[0] = a, f[1] = e, f[2] = mid;
                    }
                    nf[bd]++;
                }
            }
            node0 += 3 * lw;
#undef MB_NODE
        }
    }
    *nnodes = node0;
    *nelems = el;
    memcpy(nfacets, nf, sizeof nf);
}

int cx_mesh_masonry(cx_mesh **m, cx_bond bond, int N, cx_diag *d)
{
    *m = NULL;
    if (bond != CX_BOND_STACK && bond != CX_BOND_RUNNING && bond != CX_BOND_LAMINAE)
        return cx_diag_set(d, CX_EINVAL, "masonry: unknown bond %d", (int)bond);
    if (N < 1)
        return cx_diag_set(d, CX_EINVAL, "masonry: %d courses: need at least 1", N);
    /* stack bond has the most nodes: 9 per cell */
    CX_TRY(cx_mesh_check_size(9.0 * N * N, "nodes", d));
    CX_TRY(cx_mesh_check_size(12.0 * N * N, "element node slots", d));

    int *start = CX_NEW(int, N), *width = CX_NEW(int, N);
    if (!start || !width) {
        cx_free(start);
        cx_free(width);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    int nnodes, nelems, nf[MB_NBOUNDS];
    mb_walk(NULL, bond, N, start, width, 0, &nnodes, &nelems, nf);
    cx_mesh *p = NULL;
    int st = cx_mesh_alloc(&p, 2, nnodes, CX_EL_TRI6, nelems, MB_NBOUNDS);
    if (st == CX_OK) {
        p->nbodies = (int)cx_masonry_bodies(bond, N);
        p->body = CX_NEW(int, nelems);
        if (!p->body)
            st = CX_ENOMEM;
    }
    for (int k = 0; st == CX_OK && k < MB_NBOUNDS; k++)
        st = cx_mesh_alloc_boundary(&p->bounds[k], mb_names[k], nf[k], 3);
    if (st == CX_OK)
        mb_walk(p, bond, N, start, width, 1, &nnodes, &nelems, nf);
    cx_free(start);
    cx_free(width);
    if (st != CX_OK) {
        cx_mesh_destroy(&p);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    *m = p;
    return CX_OK;
}
