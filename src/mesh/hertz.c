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
    int n = (t == CX_EL_TRI6 ? 2 : 1) * N, w = n + 1;
    for (int k = 0; k < p->nnodes; k++) {
        double u = (double)(k % w) / n, v = (double)(k / w) / n;
        p->x[2 * k] = R * u * sqrt(1 - 0.5 * v * v);
        p->x[2 * k + 1] = R - R * v * sqrt(1 - 0.5 * u * u);
    }
    return CX_OK;
}
