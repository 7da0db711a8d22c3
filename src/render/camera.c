/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The camera: a rotation into view space and an orthographic fit of the
 * body (and the obstacle near it) into the drawing area of the layout. The
 * same mapping serves GL (cx_render_camera_gl) and the cairo overlays
 * (cx_render_scene_project), so markers sit exactly on the drawn mesh. */
#include "render/render_impl.h"

#include <math.h>
#include <string.h>

double cx_render_font_px(int w, int h, double font_scale)
{
    if (!(font_scale > 0))
        font_scale = 1;
    return font_scale * fmin(0.022 * w, 0.045 * h);
}

/* In units of the font F: title (1.2 F) and subtitle lines above the
 * drawing area, the notes line below it; the colour bar at the right with
 * its tick labels (up to about 4 F wide) and its vertical title. */
void cx_render_layout_font(int w, int h, double font_scale, cx_render_layout *l)
{
    double F = cx_render_font_px(w, h, font_scale), m = 0.75 * F;
    l->font = F;
    l->bar[2] = 0.9 * F;
    l->bar[0] = w - 1.3 * F - 4.2 * F - 0.35 * F - l->bar[2];
    l->area[0] = m;
    l->area[1] = 3.25 * F;
    l->area[2] = l->bar[0] - 1.2 * F - l->area[0];
    l->area[3] = h - 2.1 * F - l->area[1];
    l->bar[1] = l->area[1] + 1.2 * F;
    l->bar[3] = l->area[3] - 2.4 * F;
    l->banner[0] = l->area[0];
    l->banner[1] = l->area[1];
    l->banner[2] = w - m - l->area[0];
    l->banner[3] = 0;
}

void cx_render_layout_get(int w, int h, cx_render_layout *l)
{
    cx_render_layout_font(w, h, 1, l);
}

static void layout_banner(const cx_run_record *run, int always, cx_render_layout *l)
{
    if (!always && !cx_render_unconverged(run))
        return;
    double F = l->font, bh = 1.4 * F, move = bh + 0.3 * F;
    l->banner[3] = bh;
    l->area[1] += move;
    l->area[3] -= move;
    l->bar[1] += move;
    l->bar[3] -= move;
}

int cx_render_unconverged(const cx_run_record *run)
{
    /* an iterate with no error yet (infinite) is a run's start: an
     * animation's first frame, captioned "start (iteration 0)" */
    return run->reason < 0 || (run->reason == CX_ITERATING && (run->iterations > 0 || isinf(run->kkt)));
}

void cx_render_layout_run(const cx_run_record *run, int w, int h, cx_render_layout *l)
{
    cx_render_layout_font(w, h, 1, l);
    layout_banner(run, 0, l);
}

void cx_render_layout_image(const cx_result *r, const cx_render_opts *o, cx_render_layout *l)
{
    cx_render_layout_font(o->width, o->height, o->font_scale, l);
    if (o->no_title) {   /* the drawing moves up into the title's room */
        double up = l->area[1] - 0.75 * l->font;
        l->area[1] -= up;
        l->area[3] += up;
        l->bar[1] -= up;
        l->bar[3] += up;
        l->banner[1] = l->area[1];
    } else {
        /* a title or run record too long for one line wraps: the drawing
         * moves down */
        double down = cx_render_title_room(r, o);
        if (down > 0) {
            l->area[1] += down;
            l->area[3] -= down;
            l->bar[1] += down;
            l->bar[3] -= down;
            l->banner[1] = l->area[1];
        }
    }
    layout_banner(&r->run, o->band_always, l);
}

static void cam_cross(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static void cam_unit(double *a)
{
    double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; k++)
        a[k] /= l;
}

/* Rows of R: right, up, towards the eye (e). */
static void cam_rotation(double *R, const double *e_in, const double *up)
{
    double e[3] = {e_in[0], e_in[1], e_in[2]}, r[3], u[3];
    cam_unit(e);
    cam_cross(up, e, r);
    cam_unit(r);
    cam_cross(e, r, u);
    for (int k = 0; k < 3; k++) {
        R[k] = r[k];
        R[3 + k] = u[k];
        R[6 + k] = e[k];
    }
}

static void cam_view(const double *R, const double *x, double *v)
{
    for (int i = 0; i < 3; i++)
        v[i] = R[3 * i] * x[0] + R[3 * i + 1] * x[1] + R[3 * i + 2] * x[2];
}

typedef struct cam_box {
    double lo[3], hi[3];
} cam_box;

static void cam_add(cam_box *b, const double *R, const double *x)
{
    double v[3];
    cam_view(R, x, v);
    for (int k = 0; k < 3; k++) {
        b->lo[k] = fmin(b->lo[k], v[k]);
        b->hi[k] = fmax(b->hi[k], v[k]);
    }
}

/* Vertices from..to-1 of a. */
static void cam_add_array(cam_box *b, const double *R, const cx_render_array *a, long from, long to)
{
    for (long i = from; i < to; i++) {
        double x[3] = {a->v[CX_RENDER_VFLOATS * i], a->v[CX_RENDER_VFLOATS * i + 1], a->v[CX_RENDER_VFLOATS * i + 2]};
        cam_add(b, R, x);
    }
}

void cx_render_mirror(const cx_render_scene *sc, int c, const double x[3], double y[3])
{
    double t[3] = {x[0], x[1], x[2]};
    for (int j = 0; j < sc->nsym; j++)
        if (c >> j & 1)
            t[sc->sym_axis[j]] = 2 * sc->sym_at[j] - t[sc->sym_axis[j]];
    y[0] = t[0];
    y[1] = t[1];
    y[2] = t[2];
}

/* Do the contact faces look down? The mean outward normal of the contact
 * points (towards the obstacle) points below the xy plane. */
static int cam_contact_down(const cx_render_scene *sc)
{
    const cx_contact_set *cs = &sc->r->contact;
    double nz = 0;
    for (int i = 0; i < cs->m; i++)
        nz += cs->normal[3 * i + 2];
    return cs->m > 0 && nz < -0.5 * cs->m;
}

/* The obstacle contact point i is against: with one, that one (for every
 * point, as body-to-body rows have none); with several, the one whose gap
 * at the point is the point's own. */
static int cam_point_obstacle(const cx_render_scene *sc, int i)
{
    const cx_result *r = sc->r;
    const cx_contact_set *cs = &r->contact;
    int best = 0;
    double dbest = INFINITY;
    for (int j = 0; j < sc->nobst && sc->nobst > 1; j++) {
        double g, nrm[3];
        if (cx_obstacle_gap(&r->obstacles[j], sc->dim, cs->x + sc->dim * i, &g, nrm) == CX_OK &&
            fabs(g - cs->gap[i]) < dbest) {
            dbest = fabs(g - cs->gap[i]);
            best = j;
        }
    }
    return best;
}

void cx_render_camera_orient(cx_render_scene *sc)
{
    const cx_obstacle *ob = sc->nobst ? &sc->obstacles[0] : NULL;
    memset(sc->ghost, 0, sizeof sc->ghost);
    const cx_render_opts *o = sc->o;
    if (sc->dim == 2) {
        const double e[3] = {0, 0, 1}, up[3] = {0, 1, 0};
        cam_rotation(sc->R, e, up);
    } else if (o->view == CX_VIEW_CONTACT) {
        /* from inside the obstacle, looking at the contact faces; the
         * first in-plane world axis to the right */
        double e[3] = {0, 0, -1}, up[3] = {0, 1, 0};
        if (ob && ob->kind == CX_OBST_PLANE)
            for (int k = 0; k < 3; k++)
                e[k] = -ob->normal[k];
        else if (sc->r->contact.m > 0) {
            /* the eye on the obstacle's side: along the mean of the
             * contact normals, which point from the body to the obstacle */
            const cx_contact_set *cs = &sc->r->contact;
            double mn[3] = {0, 0, 0};
            for (int i = 0; i < cs->m; i++)
                for (int k = 0; k < 3; k++)
                    mn[k] += cs->normal[3 * i + k];
            if (mn[0] * mn[0] + mn[1] * mn[1] + mn[2] * mn[2] > 0)
                for (int k = 0; k < 3; k++)
                    e[k] = mn[k];
        }
        if (fabs(e[2]) > 0.9) {   /* x to the right: up = e x x */
            const double xa[3] = {1, 0, 0};
            cam_cross(e, xa, up);
        } else if (fabs(e[1]) > 0.9) {
            up[1] = 0;
            up[2] = 1;
        }
        cam_rotation(sc->R, e, up);
    } else {
        /* default: from the side the contact faces look to (halfball's
         * indentation is on its underside), 35 degrees round from -y */
        double az = 35, el = 30;
        if (o->view == CX_VIEW_BELOW || (o->view == CX_VIEW_BODY && cam_contact_down(sc)))
            el = -35;
        if (o->has_camera) {
            az = o->cam_az;
            el = o->cam_el;
        }
        sc->az = az;
        sc->el = el;
        sc->from_below = el < 0;
        double a = az * CX_PI / 180, b = el * CX_PI / 180;
        double e[3] = {cos(b) * sin(a), -cos(b) * cos(a), sin(b)}, up[3] = {0, 0, 1};
        if (fabs(e[2]) > 0.999) {   /* straight above or below: the limit of z up */
            double sg = e[2] > 0 ? 1 : -1;
            up[0] = -sg * sin(a);
            up[1] = sg * cos(a);
            up[2] = 0;
        }
        cam_rotation(sc->R, e, up);
        /* the eye on an obstacle's side of the contact faces against it:
         * that obstacle would hide them */
        const cx_contact_set *cs = &sc->r->contact;
        double towards[CX_RESULT_MAX_OBSTACLES] = {0};
        for (int i = 0; i < cs->m && sc->nobst; i++) {
            int j = cam_point_obstacle(sc, i);
            for (int k = 0; k < 3; k++)
                towards[j] += cs->normal[3 * i + k] * sc->R[6 + k];
        }
        for (int j = 0; j < sc->nobst; j++)
            sc->ghost[j] = towards[j] > 0;
    }
}

/* --crop contact: the points in contact (all contact points if none is),
 * with a margin of half their extent (at least 5 % of the body). */
static int cam_crop(const cx_render_scene *sc, cam_box *b, double body)
{
    const cx_contact_set *cs = &sc->r->contact;
    int any = 0;
    for (int i = 0; i < cs->m; i++)
        any |= sc->r->status[i] != CX_PT_FREE;
    cam_box c = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    int n = 0;
    for (int cp = 0; cp < sc->ncopies; cp++)
        for (int i = 0; i < cs->m; i++) {
            if (any && sc->r->status[i] == CX_PT_FREE)
                continue;
            double x[3];
            cx_render_mirror(sc, cp, sc->xd + 3 * cs->node[i], x);
            cam_add(&c, sc->R, x);
            n++;
        }
    if (n == 0)
        return 0;
    for (int k = 0; k < 2; k++) {
        double pad = fmax(0.5 * (c.hi[k] - c.lo[k]), 0.05 * body);
        b->lo[k] = c.lo[k] - pad;
        b->hi[k] = c.hi[k] + pad;
    }
    return 1;
}

void cx_render_draw_area(const cx_render_scene *sc, double area[4])
{
    cx_render_layout l;
    cx_render_layout_image(sc->r, sc->o, &l);
    if (sc->dim == 3 && sc->o->view == CX_VIEW_CONTACT) {
        /* room for the axes' ticks and titles (overlay.c) */
        l.area[0] += 4.6 * l.font;
        l.area[2] -= 4.6 * l.font;
        l.area[3] -= 2.8 * l.font;
    } else if (sc->dim == 3) {
        /* the bottom row for the view's caption beside the triad
         * (overlay.c), so that it is not written over the body */
        l.area[3] -= 1.6 * l.font;
    }
    for (int k = 0; k < 4; k++)
        area[k] = l.area[k];
}

void cx_render_camera(cx_render_scene *sc)
{
    cx_render_layout l;
    cx_render_draw_area(sc, l.area);
    cam_box b = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    if (sc->dim == 2) {
        const cx_mesh *m = sc->r->mesh;
        for (int c = 0; c < sc->ncopies; c++)
            for (int i = 0; i < m->nnodes; i++) {
                double x[3];
                cx_render_mirror(sc, c, sc->xd + 3 * i, x);
                cam_add(&b, sc->R, x);
                cx_render_mirror(sc, c, sc->x0 + 3 * i, x);
                cam_add(&b, sc->R, x);
            }
        /* a disc obstacle is shown whole when it is not much larger than
         * the body; a plane is seen as the strip below the body */
        double size = fmax(b.hi[0] - b.lo[0], b.hi[1] - b.lo[1]);
        double lo[2] = {b.lo[0], b.lo[1]}, hi[2] = {b.hi[0], b.hi[1]};   /* the bodies' */
        for (int j = 0; j < sc->nobst; j++) {
            const cx_obstacle *ob = &sc->obstacles[j];
            if (ob->kind == CX_OBST_DISC && ob->radius < 1.5 * size) {
                double q[3] = {ob->point[0] - ob->radius, ob->point[1] - ob->radius, 0};
                cam_add(&b, sc->R, q);
                q[0] += 2 * ob->radius;
                q[1] += 2 * ob->radius;
                cam_add(&b, sc->R, q);
            } else if (ob->kind == CX_OBST_PLANE) {
                for (int c = 0; c < 4; c++) {
                    double q[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], 0}, dist = 0;
                    for (int k = 0; k < 2; k++)
                        dist += (q[k] - ob->point[k]) * ob->normal[k];
                    for (int k = 0; k < 2; k++)
                        q[k] -= (dist + 0.06 * size) * ob->normal[k];
                    cam_add(&b, sc->R, q);
                }
            }
        }
    } else {
        cam_add_array(&b, sc->R, &sc->tris, 0, sc->tris.n);
        /* a plane seen from its side is not drawn (overlay.c): not framed */
        for (int j = 0; j < sc->nobst; j++)
            if (!(sc->ghost[j] && sc->obstacles[j].kind == CX_OBST_PLANE))
                cam_add_array(&b, sc->R, &sc->obst, sc->obst_range[j][0], sc->obst_range[j][1]);
    }
    if (sc->o->crop_contact)
        cam_crop(sc, &b, fmax(b.hi[0] - b.lo[0], b.hi[1] - b.lo[1]));
    double bw = fmax(b.hi[0] - b.lo[0], 1e-300), bh = fmax(b.hi[1] - b.lo[1], 1e-300);
    sc->k = fmin(l.area[2] / (1.06 * bw), l.area[3] / (1.06 * bh));
    sc->cx = l.area[0] + 0.5 * l.area[2] - sc->k * 0.5 * (b.lo[0] + b.hi[0]);
    sc->cy = l.area[1] + 0.5 * l.area[3] + sc->k * 0.5 * (b.lo[1] + b.hi[1]);
    double dz = fmax(b.hi[2] - b.lo[2], 1e-3 * fmax(bw, bh));
    sc->zmin = b.lo[2] - 0.05 * dz;
    sc->zmax = b.hi[2] + 0.05 * dz;
}

void cx_render_scene_project(const cx_render_scene *sc, const double x[3], double px[2])
{
    double v[3], y[3];
    cx_render_mirror(sc, sc->copy, x, y);
    cam_view(sc->R, y, v);
    px[0] = sc->cx + sc->k * v[0];
    px[1] = sc->cy - sc->k * v[1];
}

void cx_render_camera_gl(const cx_render_scene *sc, float mvp[16], float rot[9])
{
    double sx = 2 * sc->k / sc->w, sy = 2 * sc->k / sc->h, sz = -2 / (sc->zmax - sc->zmin);
    double row[3][4];
    for (int k = 0; k < 3; k++) {
        row[0][k] = sx * sc->R[k];
        row[1][k] = sy * sc->R[3 + k];
        row[2][k] = sz * sc->R[6 + k];
    }
    row[0][3] = 2 * sc->cx / sc->w - 1;
    row[1][3] = 1 - 2 * sc->cy / sc->h;
    row[2][3] = 2 * sc->zmin / (sc->zmax - sc->zmin) + 1;
    for (int c = 0; c < 4; c++) {
        for (int r = 0; r < 3; r++)
            mvp[4 * c + r] = (float)row[r][c];
        mvp[4 * c + 3] = c == 3 ? 1.0f : 0.0f;
    }
    for (int i = 0; i < 9; i++)
        rot[i] = (float)sc->R[i];
}
