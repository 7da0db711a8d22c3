/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The mesh view's geometry: the outline of the body (mesh/surface.c), the
 * edges of a 2D element, the automatic displacement scale. No curses
 * here; panels.c draws. */
#include "tui/tui_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void tui_meshview_clear(tui_meshview *v)
{
    cx_free(v->outline);
    free(v->features);
    memset(v, 0, sizeof *v);
}

/* An edge of a surface facet: its nodes (smaller first) and the facet. */
typedef struct mv_edge {
    int a, b, facet;
} mv_edge;

static int mv_edge_cmp(const void *x, const void *y)
{
    const mv_edge *p = x, *q = y;
    return p->a != q->a ? (p->a > q->a) - (p->a < q->a) : (p->b > q->b) - (p->b < q->b);
}

/* The feature edges of a 3D mesh's surface: each edge of the surface
 * facets whose two facets' normals part by more than 30 degrees, or that
 * has one facet only. */
static void mv_features(tui_meshview *v, const cx_mesh *mesh)
{
    cx_facets f;
    memset(&f, 0, sizeof f);
    if (cx_mesh_facets(mesh, 1, &f) != CX_OK)
        tui_oom("out of memory");
    int npf = f.npf, ne = 0;
    mv_edge *e = tui_xalloc(NULL, sizeof *e * ((size_t)f.n * (size_t)npf + 1));
    double *nrm = tui_xalloc(NULL, sizeof *nrm * 3 * ((size_t)f.n + 1));
    for (int k = 0; k < f.n; k++) {
        const int *c = f.nodes + (size_t)npf * k;
        const double *x0 = mesh->x + 3 * c[0], *x1 = mesh->x + 3 * c[1], *x2 = mesh->x + 3 * c[npf - 1];
        double u[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
        double w[3] = {x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]};
        double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int d = 0; d < 3; d++)
            nrm[3 * k + d] = l > 0 ? n[d] / l : 0;
        for (int i = 0; i < npf; i++) {
            int a = c[i], b = c[(i + 1) % npf];
            e[ne++] = (mv_edge){a < b ? a : b, a < b ? b : a, k};
        }
    }
    qsort(e, (size_t)ne, sizeof *e, mv_edge_cmp);
    v->features = tui_xalloc(NULL, sizeof(int) * 2 * ((size_t)ne + 1));
    const double cos30 = 0.866;
    for (int i = 0; i < ne;) {
        int j = i + 1;
        while (j < ne && e[j].a == e[i].a && e[j].b == e[i].b)
            j++;
        int fold = j - i != 2;
        if (!fold) {
            const double *p = nrm + 3 * e[i].facet, *q = nrm + 3 * e[i + 1].facet;
            fold = fabs(p[0] * q[0] + p[1] * q[1] + p[2] * q[2]) < cos30;
        }
        if (fold) {
            v->features[2 * v->nfeatures] = e[i].a;
            v->features[2 * v->nfeatures + 1] = e[i].b;
            v->nfeatures++;
        }
        i = j;
    }
    free(e);
    free(nrm);
    cx_facets_clear(&f);
}

void tui_meshview_update(tui_meshview *v, const cx_mesh *mesh, const cx_scene *scene, int level)
{
    tui_meshview_clear(v);
    if (mesh && cx_mesh_outline(mesh, &v->outline, &v->noutline) != CX_OK)
        tui_oom("out of memory");
    if (mesh && mesh->dim == 3)
        mv_features(v, mesh);
    if (scene && !scene->contact_master[0]) {
        cx_scene_obstacle(scene, level, &v->obstacle);
        v->has_obstacle = 1;
    }
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
