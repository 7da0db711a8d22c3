/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The rectangle [x0,x1] x [y0,y1]: a structured grid, mapped affinely. */
#include "mesh/mesh_impl.h"

#include <math.h>

/* Lattice coordinate k of n between a and b, exact at both ends so that
 * boundary nodes lie exactly on the sides. */
static double lerp(double a, double b, int k, int n)
{
    return k == n ? b : a + (b - a) * ((double)k / n);
}

int cx_mesh_rectangle(cx_mesh **m, double x0, double y0, double x1, double y1,
                      int nx, int ny, cx_elem_type t, cx_diag *d)
{
    static const char *const side[4] = {"bottom", "right", "top", "left"};
    *m = NULL;
    if (!isfinite(x0) || !isfinite(x1) || !isfinite(y0) || !isfinite(y1) || !(x1 > x0) || !(y1 > y0))
        return cx_diag_set(d, CX_EINVAL, "rectangle [%g, %g] x [%g, %g]: need x0 < x1 and y0 < y1",
                           x0, x1, y0, y1);
    CX_TRY(cx_mesh_grid2d(m, nx, ny, t, 0, side, d));
    cx_mesh *p = *m;
    int q = t == CX_EL_TRI6 ? 2 : 1, w = q * nx + 1;
    for (int k = 0; k < p->nnodes; k++) {
        p->x[2 * k] = lerp(x0, x1, k % w, q * nx);
        p->x[2 * k + 1] = lerp(y0, y1, k / w, q * ny);
    }
    return CX_OK;
}
