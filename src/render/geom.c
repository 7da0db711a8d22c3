/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Vertex arrays of an image: the body's triangles (2D: all elements; 3D:
 * the boundary faces, from mesh/surface.c), its edges, the contact faces, and the 3D obstacle. Every body of the mesh
 * goes into the same arrays (one draw call per field). */
#include "render/render_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int cx_render_array_push(cx_render_array *a, const double x[3], const double nrm[3], double value)
{
    if (a->n == a->cap) {
        long cap = a->cap ? 2 * a->cap : 1024;
        float *v = cx_realloc(a->v, sizeof(float) * CX_RENDER_VFLOATS * (size_t)cap);
        if (!v)
            return CX_ENOMEM;
        a->v = v;
        a->cap = cap;
    }
    float *q = a->v + CX_RENDER_VFLOATS * a->n++;
    for (int k = 0; k < 3; k++) {
        q[k] = (float)x[k];
        q[3 + k] = (float)nrm[k];
    }
    q[6] = (float)value;
    return CX_OK;
}

void cx_render_array_clear(cx_render_array *a)
{
    cx_free(a->v);
    memset(a, 0, sizeof *a);
}

static double geom_val(const cx_render_scene *sc, int node)
{
    return sc->val ? sc->val[node] : 0.0;
}

static void geom_normal(const double *a, const double *b, const double *c, double n[3])
{
    double u[3], v[3];
    for (int k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        n[k] = l > 0 ? n[k] / l : (k == 2);
}

static int geom_tri(const cx_render_scene *sc, cx_render_array *a, int i, int j, int k)
{
    const double *X = sc->xd;
    double n[3];
    geom_normal(X + 3 * i, X + 3 * j, X + 3 * k, n);
    CX_TRY(cx_render_array_push(a, X + 3 * i, n, geom_val(sc, i)));
    CX_TRY(cx_render_array_push(a, X + 3 * j, n, geom_val(sc, j)));
    return cx_render_array_push(a, X + 3 * k, n, geom_val(sc, k));
}

static int geom_line(const cx_render_scene *sc, int i, int j)
{
    static const double n[3] = {0, 0, 1};
    CX_TRY(cx_render_array_push((cx_render_array *)&sc->lines, sc->xd + 3 * i, n, 0));
    return cx_render_array_push((cx_render_array *)&sc->lines, sc->xd + 3 * j, n, 0);
}

/* A polygon face (3 or 4 nodes) as triangles, and its edges. */
static int geom_face(cx_render_scene *sc, cx_render_array *a, const int *f, int nf, int edges)
{
    CX_TRY(geom_tri(sc, a, f[0], f[1], f[2]));
    if (nf == 4)
        CX_TRY(geom_tri(sc, a, f[0], f[2], f[3]));
    if (edges)
        for (int e = 0; e < nf; e++)
            CX_TRY(geom_line(sc, f[e], f[(e + 1) % nf]));
    return CX_OK;
}

/* ---- 2D ------------------------------------------------------------------ */

static int geom_2d(cx_render_scene *sc)
{
    const cx_mesh *m = sc->r->mesh;
    const int *c;
    for (int e = 0; e < m->nelems; e++) {
        c = m->conn + (size_t)m->npe * e;
        if (m->etype == CX_EL_TRI3) {
            CX_TRY(geom_tri(sc, &sc->tris, c[0], c[1], c[2]));
        } else if (m->etype == CX_EL_QUAD4) {
            CX_TRY(geom_tri(sc, &sc->tris, c[0], c[1], c[2]));
            CX_TRY(geom_tri(sc, &sc->tris, c[0], c[2], c[3]));
        } else {   /* TRI6: four sub-triangles on the mid-edge nodes */
            CX_TRY(geom_tri(sc, &sc->tris, c[0], c[3], c[5]));
            CX_TRY(geom_tri(sc, &sc->tris, c[3], c[1], c[4]));
            CX_TRY(geom_tri(sc, &sc->tris, c[5], c[4], c[2]));
            CX_TRY(geom_tri(sc, &sc->tris, c[3], c[4], c[5]));
        }
    }
    /* edges once each, and the boundary edges (used by one element) */
    cx_facets f;
    CX_TRY(cx_mesh_facets(m, 0, &f));
    int nb = 0, rc = CX_OK;
    for (int i = 0; i < f.n; i++)
        nb += f.uses[i] == 1;
    sc->bedges = cx_malloc(sizeof(int) * 3 * (size_t)(nb + 1));
    if (!sc->bedges)
        rc = CX_ENOMEM;
    for (int i = 0; i < f.n && rc == CX_OK; i++) {
        int ed[3] = {f.nodes[2 * i], f.mid ? f.mid[i] : -1, f.nodes[2 * i + 1]};
        if (sc->o->edges) {
            if (ed[1] >= 0) {
                rc = geom_line(sc, ed[0], ed[1]);
                if (rc == CX_OK)
                    rc = geom_line(sc, ed[1], ed[2]);
            } else {
                rc = geom_line(sc, ed[0], ed[2]);
            }
        }
        if (f.uses[i] == 1)
            memcpy(sc->bedges + 3 * sc->nbedges++, ed, sizeof ed);
    }
    cx_facets_clear(&f);
    return rc;
}

/* ---- 3D ------------------------------------------------------------------ */

/* The contact facets: boundary facets whose nodes are all contact nodes. */
static int geom_contact_faces(cx_render_scene *sc, cx_render_array *a, int edges)
{
    const cx_mesh *m = sc->r->mesh;
    const cx_contact_set *cs = &sc->r->contact;
    unsigned char *is_c = CX_NEW(unsigned char, m->nnodes);
    if (!is_c)
        return CX_ENOMEM;
    for (int i = 0; i < cs->m; i++)
        is_c[cs->node[i]] = 1;
    int rc = CX_OK;
    for (int b = 0; b < m->nbounds && rc == CX_OK; b++) {
        const cx_boundary *bd = &m->bounds[b];
        for (int f = 0; f < bd->nfacets && rc == CX_OK; f++) {
            const int *q = bd->facets + (size_t)bd->npf * f;
            int all = 1;
            for (int i = 0; i < bd->npf; i++)
                all &= is_c[q[i]];
            if (all && (bd->npf == 3 || bd->npf == 4))
                rc = geom_face(sc, a, q, bd->npf, edges);
        }
    }
    cx_free(is_c);
    return rc;
}

/* Feature edges of the surface facets f at coordinates X (3 per node):
 * the edges where two facets meet at more than 30 degrees, and those of
 * one facet or of more than two. Node pairs into *pairs (cx_free). */
typedef struct geom_edge {
    int a, b;
    float n[3];
} geom_edge;

static int geom_edge_cmp(const void *p, const void *q)
{
    const geom_edge *x = p, *y = q;
    if (x->a != y->a)
        return x->a < y->a ? -1 : 1;
    return x->b < y->b ? -1 : x->b > y->b;
}

static int geom_features(const cx_facets *f, const double *X, int **pairs, int *count)
{
    *pairs = NULL;
    *count = 0;
    size_t ne = (size_t)f->n * (size_t)f->npf;
    geom_edge *e = cx_malloc(sizeof *e * (ne ? ne : 1));
    if (!e)
        return CX_ENOMEM;
    size_t k = 0;
    for (int i = 0; i < f->n; i++) {
        const int *q = f->nodes + (size_t)f->npf * i;
        double n[3];
        geom_normal(X + 3 * q[0], X + 3 * q[1], X + 3 * q[2], n);
        for (int j = 0; j < f->npf; j++) {
            int a = q[j], b = q[(j + 1) % f->npf];
            e[k].a = a < b ? a : b;
            e[k].b = a < b ? b : a;
            for (int c = 0; c < 3; c++)
                e[k].n[c] = (float)n[c];
            k++;
        }
    }
    qsort(e, ne, sizeof *e, geom_edge_cmp);
    int *out = cx_malloc(sizeof(int) * 2 * (ne ? ne : 1));
    if (!out) {
        cx_free(e);
        return CX_ENOMEM;
    }
    int n = 0;
    for (size_t i = 0; i < ne;) {
        size_t j = i + 1;
        while (j < ne && e[j].a == e[i].a && e[j].b == e[i].b)
            j++;
        double dot = e[i].n[0] * e[j - 1].n[0] + e[i].n[1] * e[j - 1].n[1] + e[i].n[2] * e[j - 1].n[2];
        if (j - i != 2 || dot < cos(30 * CX_PI / 180)) {
            out[2 * n] = e[i].a;
            out[2 * n + 1] = e[i].b;
            n++;
        }
        i = j;
    }
    cx_free(e);
    *pairs = out;
    *count = n;
    return CX_OK;
}

int cx_render_on_plane(const cx_render_scene *sc, int a, int b)
{
    for (int j = 0; j < sc->nsym; j++) {
        int ax = sc->sym_axis[j];
        double tol = 1e-9 * (1 + fabs(sc->sym_at[j])) + 1e-6 * sc->size;
        if (fabs(sc->x0[3 * a + ax] - sc->sym_at[j]) <= tol && fabs(sc->x0[3 * b + ax] - sc->sym_at[j]) <= tol)
            return 1;
    }
    return 0;
}

/* The feature edges not on a symmetry plane of --mirror (inside the whole). */
static void geom_drop_plane_edges(const cx_render_scene *sc, int *pairs, int *n)
{
    int k = 0;
    for (int i = 0; i < *n; i++)
        if (!cx_render_on_plane(sc, pairs[2 * i], pairs[2 * i + 1])) {
            pairs[2 * k] = pairs[2 * i];
            pairs[2 * k + 1] = pairs[2 * i + 1];
            k++;
        }
    *n = k;
}

static int geom_3d(cx_render_scene *sc)
{
    const cx_mesh *m = sc->r->mesh;
    if (sc->o->view == CX_VIEW_CONTACT)
        return geom_contact_faces(sc, &sc->tris, sc->o->edges);
    /* the boundary faces (used by one element), in element order */
    cx_facets f;
    CX_TRY(cx_mesh_facets(m, 1, &f));
    int rc = CX_OK;
    for (int i = 0; i < f.n && rc == CX_OK; i++)
        rc = geom_face(sc, &sc->tris, f.nodes + (size_t)f.npf * i, f.npf, sc->o->edges);
    /* the edges of the shape: the undeformed one as a wireframe
     * (overlay.c), the deformed one as dark lines, a cue to the shape
     * that the soft lighting no longer gives */
    int *pairs = NULL, np = 0;
    if (rc == CX_OK)
        rc = geom_features(&f, sc->x0, &sc->feat0, &sc->nfeat0);
    if (rc == CX_OK)
        rc = geom_features(&f, sc->xd, &pairs, &np);
    if (rc == CX_OK) {
        geom_drop_plane_edges(sc, sc->feat0, &sc->nfeat0);
        geom_drop_plane_edges(sc, pairs, &np);
    }
    static const double nz[3] = {0, 0, 1};
    for (int i = 0; i < np && rc == CX_OK; i++) {
        rc = cx_render_array_push(&sc->feature, sc->xd + 3 * pairs[2 * i], nz, 0);
        if (rc == CX_OK)
            rc = cx_render_array_push(&sc->feature, sc->xd + 3 * pairs[2 * i + 1], nz, 0);
    }
    cx_free(pairs);
    cx_facets_clear(&f);
    if (rc == CX_OK && sc->o->field == CX_FIELD_PRESSURE)
        rc = geom_contact_faces(sc, &sc->overlay, 0);
    return rc;
}

/* --mirror: the copies 1..ncopies-1 of an array, reflected (positions and
 * normals) across the symmetry planes. */
static int geom_mirror(const cx_render_scene *sc, cx_render_array *a)
{
    long n = a->n;
    for (int c = 1; c < sc->ncopies; c++)
        for (long i = 0; i < n; i++) {
            const float *q = a->v + CX_RENDER_VFLOATS * i;
            double x[3] = {q[0], q[1], q[2]}, nr[3] = {q[3], q[4], q[5]}, val = q[6];
            cx_render_mirror(sc, c, x, x);
            for (int j = 0; j < sc->nsym; j++)
                if (c >> j & 1)
                    nr[sc->sym_axis[j]] = -nr[sc->sym_axis[j]];
            CX_TRY(cx_render_array_push(a, x, nr, val));
        }
    return CX_OK;
}

/* ---- the 3D obstacle ------------------------------------------------------- */

static int geom_quad(cx_render_array *a, const double *c, const double *e1, const double *e2,
                     const double *n)
{
    double q[4][3];
    for (int k = 0; k < 3; k++) {
        q[0][k] = c[k] - e1[k] - e2[k];
        q[1][k] = c[k] + e1[k] - e2[k];
        q[2][k] = c[k] + e1[k] + e2[k];
        q[3][k] = c[k] - e1[k] + e2[k];
    }
    static const int t[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++)
        CX_TRY(cx_render_array_push(a, q[t[i]], n, 0));
    return CX_OK;
}

/* The centre c and the diagonal of the drawn bodies' box (with --mirror,
 * of every copy). */
static double geom_body_box(const cx_render_scene *sc, double c[3])
{
    const cx_mesh *m = sc->r->mesh;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int cp = 0; cp < sc->ncopies; cp++)
        for (int i = 0; i < m->nnodes; i++) {
            double x[3];
            cx_render_mirror(sc, cp, sc->xd + 3 * i, x);
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], x[k]);
                hi[k] = fmax(hi[k], x[k]);
            }
        }
    double diag = 0;
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        diag += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    return sqrt(diag);
}

/* Obstacle ob into a: a plane patch under the bodies, or the sphere /
 * cylinder surface, sized by their box (centre c, diagonal diag). */
static int geom_obstacle3d(cx_render_array *a, const cx_obstacle *ob, const double c[3], double diag)
{
    if (ob->kind == CX_OBST_PLANE) {
        const double *n = ob->normal;
        double t[6], pc[3], dist = 0;
        cx_tangent_basis(3, n, t);
        for (int k = 0; k < 3; k++)
            dist += (c[k] - ob->point[k]) * n[k];
        for (int k = 0; k < 3; k++)
            pc[k] = c[k] - dist * n[k];
        double e1[3], e2[3], r = 0.85 * diag;
        for (int k = 0; k < 3; k++) {
            e1[k] = r * t[k];
            e2[k] = r * t[3 + k];
        }
        return geom_quad(a, pc, e1, e2, n);
    }
    if (ob->kind == CX_OBST_SPHERE || ob->kind == CX_OBST_CYLINDER) {
        /* parameterised surface: sphere (theta, phi), cylinder (angle, axial) */
        const int nu = 64, nv = 32;
        double R = ob->radius, ax[3] = {0, 0, 1}, t[6];
        if (ob->kind == CX_OBST_CYLINDER)
            for (int k = 0; k < 3; k++)
                ax[k] = ob->normal[k];
        cx_tangent_basis(3, ax, t);
        double half = 0.6 * diag;
        for (int i = 0; i < nu; i++)
            for (int j = 0; j < nv; j++) {
                double P[4][3], N[4][3];
                for (int q = 0; q < 4; q++) {
                    double a = 2 * CX_PI * (i + (q == 1 || q == 2)) / nu;
                    double b = (double)(j + (q >= 2)) / nv;
                    double dir[3], along;
                    if (ob->kind == CX_OBST_SPHERE) {
                        double ph = CX_PI * b;
                        for (int k = 0; k < 3; k++)
                            dir[k] = sin(ph) * (cos(a) * t[k] + sin(a) * t[3 + k]) + cos(ph) * ax[k];
                        along = 0;
                    } else {
                        for (int k = 0; k < 3; k++)
                            dir[k] = cos(a) * t[k] + sin(a) * t[3 + k];
                        double ca = 0;
                        for (int k = 0; k < 3; k++)
                            ca += (c[k] - ob->point[k]) * ax[k];
                        along = ca + (2 * b - 1) * half;
                    }
                    for (int k = 0; k < 3; k++) {
                        P[q][k] = ob->point[k] + R * dir[k] + along * ax[k];
                        N[q][k] = dir[k];
                    }
                }
                static const int tt[6] = {0, 1, 2, 0, 2, 3};
                for (int z = 0; z < 6; z++)
                    CX_TRY(cx_render_array_push(a, P[tt[z]], N[tt[z]], 0));
            }
    }
    return CX_OK;
}

/* Every obstacle of the result: those drawn first, then the ghosts
 * (sc->ghost), each one's vertices in sc->obst_range. */
static int geom_obstacles3d(cx_render_scene *sc)
{
    if (sc->nobst == 0)
        return CX_OK;
    double c[3], diag = geom_body_box(sc, c);
    for (int ghosts = 0; ghosts < 2; ghosts++) {
        for (int j = 0; j < sc->nobst; j++) {
            if (!sc->ghost[j] != !ghosts)
                continue;
            sc->obst_range[j][0] = sc->obst.n;
            CX_TRY(geom_obstacle3d(&sc->obst, &sc->obstacles[j], c, diag));
            sc->obst_range[j][1] = sc->obst.n;
        }
        if (!ghosts)
            sc->obst_drawn = sc->obst.n;
    }
    return CX_OK;
}

int cx_render_geometry(cx_render_scene *sc)
{
    if (sc->dim == 2) {
        CX_TRY(geom_2d(sc));
    } else {
        CX_TRY(geom_3d(sc));
        if (sc->o->view != CX_VIEW_CONTACT)
            CX_TRY(geom_obstacles3d(sc));
    }
    CX_TRY(geom_mirror(sc, &sc->tris));
    CX_TRY(geom_mirror(sc, &sc->overlay));
    CX_TRY(geom_mirror(sc, &sc->lines));
    return geom_mirror(sc, &sc->feature);
}
