/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The cairo layer over the GL image: title, colour bar with nice ticks,
 * the undeformed outline, the 2D obstacle, contact points by status (slip
 * with its direction), the pressure along the contact boundary, and notes
 * (displacement scale, status legend). */
#include "render/render_impl.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "render/axis.h"
#include "render/text.h"

static double ov_scale(const cx_render_scene *sc)
{
    return fmin(sc->w / 1200.0, sc->h / 900.0);
}

static void ov_rgb(cairo_t *cr, const unsigned char c[3])
{
    cairo_set_source_rgb(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
}

static void ov_title(const cx_render_scene *sc, cairo_t *cr, double s)
{
    const cx_run_record *run = &sc->r->run;
    char line[512], fr[96];
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    snprintf(line, sizeof line, "%s — %s", run->title[0] ? run->title : run->scene,
             cx_field_label(sc->o->field));
    cx_text_fit(cr, line, 20 * s, 14 * s, 22 * s, 1, 0, 0, sc->w - 40 * s);
    if (run->friction == CX_FRICTION_COULOMB)
        snprintf(fr, sizeof fr, "Coulomb F = %g", run->F);
    else if (run->friction == CX_FRICTION_TRESCA)
        snprintf(fr, sizeof fr, "Tresca slip bound %g", run->slip_bound);
    else
        snprintf(fr, sizeof fr, "frictionless");
    snprintf(line, sizeof line, "scene %s, level %d, %d dofs, %d contact points · %s%s%s · %s · kkt error %.2e",
             run->scene, run->level, sc->r->n, sc->r->m, run->method, run->params_text[0] ? " " : "",
             run->params_text, fr, run->kkt);
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    cx_text_fit(cr, line, 20 * s, 46 * s, 15 * s, 0, 0, 0, sc->w - 40 * s);
}

static const char *ov_units(int f)
{
    if (f >= CX_FIELD_UMAG && f <= CX_FIELD_UZ)
        return "length units";
    return "units of E";
}

static void ov_colorbar(const cx_render_scene *sc, cairo_t *cr, double s)
{
    cx_render_layout l;
    cx_render_layout_get(sc->w, sc->h, &l);
    double x = l.bar[0], y = l.bar[1], bw = l.bar[2], bh = l.bar[3];
    int div = cx_field_is_signed(sc->o->field);
    int nb = (int)ceil(bh);
    for (int i = 0; i < nb; i++) {
        unsigned char c[3];
        cx_colormap(div, 1.0 - (i + 0.5) / nb, c);
        ov_rgb(cr, c);
        cairo_rectangle(cr, x, y + bh * i / nb, bw, bh / nb + 0.6);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_set_line_width(cr, 1.0 * s);
    cairo_rectangle(cr, x, y, bw, bh);
    cairo_stroke(cr);
    cx_axis ax;
    cx_axis_make(&ax, sc->lo, sc->hi, 0, 6, 0);
    char lab[64];
    for (int i = 0; i < ax.nticks; i++) {
        double ty = y + bh * (1 - cx_axis_frac(&ax, ax.ticks[i]));
        cairo_move_to(cr, x + bw, ty);
        cairo_line_to(cr, x + bw + 6 * s, ty);
        cairo_stroke(cr);
        cx_axis_label(&ax, ax.ticks[i], lab, sizeof lab);
        cx_text(cr, lab, x + bw + 9 * s, ty, 14 * s, 0, 0, 0.5);
    }
    char title[128];
    snprintf(title, sizeof title, "%s [%s]", cx_field_label(sc->o->field), ov_units(sc->o->field));
    cx_text_vertical(cr, title, sc->w - 16 * s, y + 0.5 * bh, 15 * s, 0);
}

/* 2D obstacle: a hatched strip beyond the plane, or the disc. */
static void ov_obstacle2d(const cx_render_scene *sc, cairo_t *cr, double s)
{
    const cx_obstacle *ob = sc->obstacle;
    if (!ob)
        return;
    cx_render_layout l;
    cx_render_layout_get(sc->w, sc->h, &l);
    cairo_save(cr);
    cairo_rectangle(cr, l.area[0], l.area[1], l.area[2], l.area[3]);
    cairo_clip(cr);
    if (ob->kind == CX_OBST_PLANE) {
        /* the plane's line in pixels, and the side away from the normal */
        double t[2] = {-ob->normal[1], ob->normal[0]}, big = 4.0 * (sc->w + sc->h) / sc->k;
        double a[3] = {ob->point[0] - big * t[0], ob->point[1] - big * t[1], 0};
        double b[3] = {ob->point[0] + big * t[0], ob->point[1] + big * t[1], 0};
        double c[3] = {b[0] - big * ob->normal[0], b[1] - big * ob->normal[1], 0};
        double e[3] = {a[0] - big * ob->normal[0], a[1] - big * ob->normal[1], 0};
        double pa[2], pb[2], pc[2], pe[2];
        cx_render_scene_project(sc, a, pa);
        cx_render_scene_project(sc, b, pb);
        cx_render_scene_project(sc, c, pc);
        cx_render_scene_project(sc, e, pe);
        cairo_move_to(cr, pa[0], pa[1]);
        cairo_line_to(cr, pb[0], pb[1]);
        cairo_line_to(cr, pc[0], pc[1]);
        cairo_line_to(cr, pe[0], pe[1]);
        cairo_close_path(cr);
        cairo_set_source_rgb(cr, 0.86, 0.84, 0.80);
        cairo_fill_preserve(cr);
        cairo_clip(cr);
        cairo_set_source_rgb(cr, 0.62, 0.58, 0.52);
        cairo_set_line_width(cr, 1.2 * s);
        for (double q = -(double)sc->h; q < sc->w + sc->h; q += 14 * s) {
            cairo_move_to(cr, q, 0);
            cairo_line_to(cr, q - sc->h, sc->h);
        }
        cairo_stroke(cr);
        cairo_reset_clip(cr);
        cairo_rectangle(cr, l.area[0], l.area[1], l.area[2], l.area[3]);
        cairo_clip(cr);
        cairo_set_source_rgb(cr, 0.35, 0.32, 0.28);
        cairo_set_line_width(cr, 2.0 * s);
        cairo_move_to(cr, pa[0], pa[1]);
        cairo_line_to(cr, pb[0], pb[1]);
        cairo_stroke(cr);
    } else if (ob->kind == CX_OBST_DISC) {
        double c[2];
        cx_render_scene_project(sc, ob->point, c);
        cairo_arc(cr, c[0], c[1], ob->radius * sc->k, 0, 2 * CX_PI);
        cairo_set_source_rgb(cr, 0.86, 0.84, 0.80);
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, 0.35, 0.32, 0.28);
        cairo_set_line_width(cr, 2.0 * s);
        cairo_stroke(cr);
    }
    cairo_restore(cr);
}

static void ov_outline(const cx_render_scene *sc, cairo_t *cr, const double *X, double width,
                       double r, double g, double b, double a)
{
    cairo_set_source_rgba(cr, r, g, b, a);
    cairo_set_line_width(cr, width);
    for (int i = 0; i < sc->nbedges; i++) {
        const int *e = sc->bedges + 3 * i;
        double p[2];
        cx_render_scene_project(sc, X + 3 * e[0], p);
        cairo_move_to(cr, p[0], p[1]);
        if (e[1] >= 0) {
            cx_render_scene_project(sc, X + 3 * e[1], p);
            cairo_line_to(cr, p[0], p[1]);
        }
        cx_render_scene_project(sc, X + 3 * e[2], p);
        cairo_line_to(cr, p[0], p[1]);
    }
    cairo_stroke(cr);
}

/* The pressure (or the status) along the 2D contact boundary: a thick
 * coloured band on every boundary edge whose two ends are contact points
 * (so that points of different bodies are never joined); it stays
 * readable when the points are too dense for markers. */
static void ov_band2d(const cx_render_scene *sc, cairo_t *cr, double s)
{
    const cx_contact_set *cs = &sc->r->contact;
    int status = sc->o->field == CX_FIELD_STATUS;
    /* contact index + 1 of each node (0: not a contact point) */
    int *ci = CX_NEW(int, sc->r->mesh->nnodes);
    if (!ci)
        return;
    for (int i = 0; i < cs->m; i++)
        ci[cs->node[i]] = i + 1;
    cairo_set_line_width(cr, (status ? 5 : 7) * s);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    for (int i = 0; i < sc->nbedges; i++) {
        const int *e = sc->bedges + 3 * i;
        if (!ci[e[0]] || !ci[e[2]])
            continue;
        double pa[2], pb[2];
        cx_render_scene_project(sc, sc->xd + 3 * e[0], pa);
        cx_render_scene_project(sc, sc->xd + 3 * e[2], pb);
        unsigned char c[3];
        if (status) {
            /* the segment takes the status of its ends when they agree,
             * else that of the free end (the boundary of the zone) */
            int a = sc->r->status[ci[e[0]] - 1];
            int b = sc->r->status[ci[e[2]] - 1];
            cx_status_color(a == b ? a : CX_PT_FREE, c);
        } else {
            double v = 0.5 * (sc->val[e[0]] + sc->val[e[2]]);
            cx_colormap(0, (v - sc->lo) / (sc->hi - sc->lo), c);
        }
        ov_rgb(cr, c);
        cairo_move_to(cr, pa[0], pa[1]);
        cairo_line_to(cr, pb[0], pb[1]);
        cairo_stroke(cr);
    }
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
    cx_free(ci);
}

/* Is contact point i seen? 3D body view: only where its outward normal
 * (towards the obstacle) faces the viewer (row 2 of R points to the eye). */
static int ov_visible(const cx_render_scene *sc, int i)
{
    if (sc->dim != 3 || sc->o->view != CX_VIEW_BODY)
        return 1;
    const double *n = sc->r->contact.normal + 3 * i;
    return n[0] * sc->R[6] + n[1] * sc->R[7] + n[2] * sc->R[8] > 0;
}

/* The slip direction of point i on the image (unit, pixels), that of lT
 * (doc/design.md §2: T u = c lT; the friction force on the body is -T' lT). */
static int ov_slip_dir(const cx_render_scene *sc, int i, double u[2])
{
    const cx_contact_set *cs = &sc->r->contact;
    int dim = sc->dim, dt = dim - 1;
    double dir[3] = {0, 0, 0}, q0[3], q1[3], a[2], b[2];
    for (int k = 0; k < dim; k++)
        for (int j = 0; j < dt; j++)
            dir[k] += sc->r->lT[dt * i + j] * cs->tangent[dim * (dt * i + j) + k];
    double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (!(len > 0))
        return 0;
    for (int k = 0; k < 3; k++) {
        q0[k] = sc->xd[3 * cs->node[i] + k];
        q1[k] = q0[k] + dir[k] / len;
    }
    cx_render_scene_project(sc, q0, a);
    cx_render_scene_project(sc, q1, b);
    u[0] = b[0] - a[0];
    u[1] = b[1] - a[1];
    double ul = hypot(u[0], u[1]);
    if (!(ul > 0))
        return 0;
    u[0] /= ul;
    u[1] /= ul;
    return 1;
}

/* Contact points coloured by status, then arrows in the direction of slip
 * (at every k-th slipping point, so that arrows never overlap). */
static int ov_status(const cx_render_scene *sc, cairo_t *cr, double s, double r)
{
    const cx_contact_set *cs = &sc->r->contact;
    const unsigned char *status = sc->r->status;
    int shown = 0;
    for (int i = 0; i < cs->m; i++) {
        if (!ov_visible(sc, i))
            continue;
        shown++;
        double p[2];
        cx_render_scene_project(sc, sc->xd + 3 * cs->node[i], p);
        unsigned char c[3];
        cx_status_color(status[i], c);
        cairo_new_sub_path(cr);
        cairo_arc(cr, p[0], p[1], r, 0, 2 * CX_PI);
        ov_rgb(cr, c);
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        cairo_set_line_width(cr, fmin(0.8 * s, 0.25 * r));
        cairo_stroke(cr);
    }
    if (sc->r->run.friction == CX_FRICTION_NONE)
        return shown;
    double L = fmax(5.0 * r, 18 * s), h = fmax(1.6 * r, 5 * s);
    double last[2] = {-1e30, -1e30};
    unsigned char c[3];
    cx_status_color(CX_PT_SLIP_POS, c);
    for (int i = 0; i < cs->m; i++) {
        double p[2], u[2];
        if ((status[i] != CX_PT_SLIP_POS && status[i] != CX_PT_SLIP_NEG) ||
            !ov_visible(sc, i) || !ov_slip_dir(sc, i, u))
            continue;
        cx_render_scene_project(sc, sc->xd + 3 * cs->node[i], p);
        if (hypot(p[0] - last[0], p[1] - last[1]) < 1.3 * L)
            continue;
        last[0] = p[0];
        last[1] = p[1];
        if (sc->dim == 2) {
            /* beside the markers, on the obstacle's side */
            double q[3], a[2];
            for (int k = 0; k < 3; k++)
                q[k] = sc->xd[3 * cs->node[i] + k] + (k < 2 ? cs->normal[2 * i + k] : 0);
            cx_render_scene_project(sc, q, a);
            double nx = a[0] - p[0], ny = a[1] - p[1], nl = hypot(nx, ny);
            if (nl > 0) {
                p[0] += (r + 6 * s) * nx / nl;
                p[1] += (r + 6 * s) * ny / nl;
            }
        }
        double tip[2] = {p[0] + L * u[0], p[1] + L * u[1]};
        ov_rgb(cr, c);
        cairo_set_line_width(cr, 2.0 * s);
        cairo_move_to(cr, p[0], p[1]);
        cairo_line_to(cr, tip[0] - 0.5 * h * u[0], tip[1] - 0.5 * h * u[1]);
        cairo_stroke(cr);
        cairo_move_to(cr, tip[0], tip[1]);
        cairo_line_to(cr, tip[0] - 1.8 * h * u[0] + 0.8 * h * u[1], tip[1] - 1.8 * h * u[1] - 0.8 * h * u[0]);
        cairo_line_to(cr, tip[0] - 1.8 * h * u[0] - 0.8 * h * u[1], tip[1] - 1.8 * h * u[1] + 0.8 * h * u[0]);
        cairo_close_path(cr);
        cairo_fill(cr);
    }
    return shown;
}

/* Marker radius: about 0.4 of the spacing of the contact points on the
 * image (2D: mean length of the boundary edges between contact points;
 * 3D: from the projected area they cover), between 1.2 and 4 (x s) pixels. */
static double ov_marker_radius(const cx_render_scene *sc, double s)
{
    const cx_contact_set *cs = &sc->r->contact;
    double spacing = 0;
    if (sc->dim == 2) {
        unsigned char *is_c = CX_NEW(unsigned char, sc->r->mesh->nnodes);
        int n = 0;
        if (is_c) {
            for (int i = 0; i < cs->m; i++)
                is_c[cs->node[i]] = 1;
            for (int i = 0; i < sc->nbedges; i++) {
                const int *e = sc->bedges + 3 * i;
                if (!is_c[e[0]] || !is_c[e[2]])
                    continue;
                double a[2], b[2];
                cx_render_scene_project(sc, sc->xd + 3 * e[0], a);
                cx_render_scene_project(sc, sc->xd + 3 * e[2], b);
                spacing += hypot(b[0] - a[0], b[1] - a[1]);
                n++;
            }
            cx_free(is_c);
        }
        spacing = n > 0 ? spacing / n : 0;
    } else if (cs->m > 0) {
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
        for (int i = 0; i < cs->m; i++) {
            double p[2];
            cx_render_scene_project(sc, sc->xd + 3 * cs->node[i], p);
            for (int k = 0; k < 2; k++) {
                lo[k] = fmin(lo[k], p[k]);
                hi[k] = fmax(hi[k], p[k]);
            }
        }
        spacing = sqrt(fmax(hi[0] - lo[0], 1.0) * fmax(hi[1] - lo[1], 1.0) / cs->m);
    }
    double r = spacing > 0 ? 0.42 * spacing : 4 * s;
    return fmin(fmax(r, 1.2 * s), 4 * s);
}

static void ov_notes(const cx_render_scene *sc, cairo_t *cr, double s, int legend, int hidden)
{
    char line[256];
    double y = sc->h - 30 * s;
    cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
    if (sc->o->scale > 0)
        snprintf(line, sizeof line, "displacement × %.3g (set), max |u| = %.3g", sc->scale, sc->umax);
    else
        snprintf(line, sizeof line, "displacement × %.3g (auto: max |u| = %.3g drawn as 7 %% of the body size)",
                 sc->scale, sc->umax);
    cx_text(cr, line, 20 * s, y, 14 * s, 0, 0, 0.5);
    if (hidden)
        cx_text(cr, "the contact faces are hidden from here: --view contact shows them",
                20 * s, y - 20 * s, 14 * s, 0, 0, 0.5);
    if (!legend)
        return;
    static const int codes[4] = {CX_PT_FREE, CX_PT_CONTACT, CX_PT_STICK, CX_PT_SLIP_POS};
    static const char *names[4] = {"free", "contact", "stick", "slip"};
    double x = sc->w - 20 * s;
    for (int i = 3; i >= 0; i--) {
        if (sc->r->run.friction == CX_FRICTION_NONE ? i >= 2 : i == 1)
            continue;
        unsigned char c[3];
        cx_status_color(codes[i], c);
        x -= cx_text_width(cr, names[i], 14 * s, 0);
        cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
        cx_text(cr, names[i], x, y, 14 * s, 0, 0, 0.5);
        x -= 12 * s;
        cairo_new_sub_path(cr);
        cairo_arc(cr, x, y, 5 * s, 0, 2 * CX_PI);
        ov_rgb(cr, c);
        cairo_fill(cr);
        x -= 22 * s;
    }
}

void cx_render_underlay(const cx_render_scene *sc, cairo_t *cr)
{
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    if (sc->dim == 2)
        ov_obstacle2d(sc, cr, ov_scale(sc));
}

void cx_render_overlay(const cx_render_scene *sc, cairo_t *cr)
{
    double s = ov_scale(sc);
    int f = sc->o->field;
    int markers = sc->dim == 2 || f == CX_FIELD_STATUS;
    if (sc->dim == 2) {
        ov_outline(sc, cr, sc->x0, 1.2 * s, 0.3, 0.3, 0.3, 0.35);
        ov_outline(sc, cr, sc->xd, 1.2 * s, 0.1, 0.1, 0.1, 0.9);
        if (f == CX_FIELD_PRESSURE || f == CX_FIELD_STATUS)
            ov_band2d(sc, cr, s);
    }
    int shown = 0;
    if (markers) {
        double r = ov_marker_radius(sc, s);
        shown = ov_status(sc, cr, s, f == CX_FIELD_STATUS ? fmin(1.4 * r, 4 * s) : r);
    }
    int hidden = sc->dim == 3 && sc->o->view == CX_VIEW_BODY && sc->r->m > 0 &&
                 (f == CX_FIELD_PRESSURE || (f == CX_FIELD_STATUS && shown == 0));
    ov_title(sc, cr, s);
    if (f != CX_FIELD_STATUS)
        ov_colorbar(sc, cr, s);
    ov_notes(sc, cr, s, markers, hidden);
}
