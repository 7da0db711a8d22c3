/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The mesh view's geometry: the outline of the body (mesh/surface.c), the
 * edges of a 2D element, the automatic displacement scale. No curses
 * here; panels.c draws. */
#include "tui/tui_impl.h"

#include <math.h>

void tui_meshview_clear(tui_meshview *v)
{
    cx_free(v->outline);
    v->outline = NULL;
    v->noutline = 0;
}

void tui_meshview_update(tui_meshview *v, const cx_mesh *mesh)
{
    tui_meshview_clear(v);
    if (mesh && cx_mesh_outline(mesh, &v->outline, &v->noutline) != CX_OK)
        tui_oom("out of memory");
}

int tui_meshview_elem_edges(const cx_mesh *mesh, int e, int seg[6][2])
{
    const int (*lf)[4];
    int npf, nf = cx_elem_facets(mesh->etype, &lf, &npf), n = 0;
    if (mesh->dim != 2)
        return 0;
    const int *c = mesh->conn + (size_t)mesh->npe * e;
    for (int k = 0; k < nf; k++) {
        int a = c[lf[k][0]], b = c[lf[k][1]];
        if (lf[k][2] >= 0) {
            int mid = c[lf[k][2]];
            seg[n][0] = a, seg[n++][1] = mid;
            seg[n][0] = mid, seg[n++][1] = b;
        } else {
            seg[n][0] = a, seg[n++][1] = b;
        }
    }
    return n;
}

const int *tui_state_outline(const tui_state *st, int *n)
{
    *n = st->mesh_view.noutline;
    return st->mesh_view.outline;
}

double tui_mesh_auto_scale(const tui_state *st)
{
    const cx_mesh *mesh = st->info->mesh;
    if (!mesh || !st->uall)
        return 1;
    int dim = mesh->dim;
    double size = 0, umax = 0;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < mesh->nnodes; k++)
        for (int c = 0; c < dim; c++) {
            lo[c] = fmin(lo[c], mesh->x[dim * k + c]);
            hi[c] = fmax(hi[c], mesh->x[dim * k + c]);
            umax = fmax(umax, fabs(st->uall[dim * k + c]));
        }
    for (int c = 0; c < dim; c++)
        size = fmax(size, hi[c] - lo[c]);
    /* the largest displacement drawn as 10% of the body */
    return umax > 0 ? 0.1 * size / umax : 1;
}
