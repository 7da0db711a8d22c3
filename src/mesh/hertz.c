/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The Hertz quarter disc: the lower-right quarter of the disc of radius R
 * centred at (0, R), touching the plane y = 0 at the origin. The unit
 * square maps onto it by
 *     x = R u sqrt(1 - v^2/2),   y = R - R v sqrt(1 - u^2/2),
 * a smooth bijection (the elliptical grid mapping of a square onto a
 * disc) whose sides v = 1 and u = 1 land on the circle, so every node of
 * "arc" and "side" is on it to rounding. The map reverses orientation (x
 * grows with u, y falls with v): the grid is built flipped. */
#include "mesh/mesh_impl.h"

#include <math.h>
#include <string.h>

int cx_mesh_hertz(cx_mesh **m, double R, int N, cx_elem_type t, cx_diag *d)
{
    static const char *const side[4] = {"top", "side", "arc", "axis"};
    *m = NULL;
    if (!isfinite(R) || !(R > 0))
        return cx_diag_set(d, CX_EINVAL, "hertz: radius %g must be positive", R);
    if (N < 1)
        return cx_diag_set(d, CX_EINVAL, "hertz: level N = %d must be at least 1", N);
    CX_TRY(cx_mesh_grid2d(m, N, N, t, 1, side, d));
    cx_mesh *p = *m;
    /* "quarter": arc then side, one chain from the origin to (R, R), the
     * contact boundary Gc = (0, R) of paper 002's Hertz problem */
    cx_boundary *nb = cx_realloc(p->bounds, 5 * sizeof *nb);
    if (!nb) {
        cx_mesh_destroy(m);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    p->bounds = nb;
    const cx_boundary *arc = &nb[2], *sd = &nb[1];
    size_t na = (size_t)arc->nfacets * (size_t)arc->npf;
    if (cx_mesh_alloc_boundary(&nb[4], "quarter", arc->nfacets + sd->nfacets, arc->npf)) {
        p->nbounds = 4;
        cx_mesh_destroy(m);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    p->nbounds = 5;
    memcpy(nb[4].facets, arc->facets, na * sizeof(int));
    memcpy(nb[4].facets + na, sd->facets, (size_t)sd->nfacets * (size_t)sd->npf * sizeof(int));
    int n = (t == CX_EL_TRI6 ? 2 : 1) * N, w = n + 1;
    for (int k = 0; k < p->nnodes; k++) {
        double u = (double)(k % w) / n, v = (double)(k / w) / n;
        p->x[2 * k] = R * u * sqrt(1 - 0.5 * v * v);
        p->x[2 * k + 1] = R - R * v * sqrt(1 - 0.5 * u * u);
    }
    return CX_OK;
}
