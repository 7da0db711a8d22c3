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

#include "out/palette.h"
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

static double ov_font(const cx_render_scene *sc)
{
    return cx_render_font_px(sc->w, sc->h, sc->o->font_scale);
}

/* The run-record line under the title, in parts joined by " · ". */
static int ov_subtitle_parts(const cx_result *r, const cx_render_opts *o, char parts[5][320])
{
    const cx_run_record *run = &r->run;
    snprintf(parts[0], 320, "%s", cx_field_label(o->field));
    snprintf(parts[1], 320, "scene %s, level %d, %d dofs, %d contact points", run->scene, run->level, r->n, r->m);
    snprintf(parts[2], 320, "%s%s%s", run->method, run->params_text[0] ? " " : "", run->params_text);
    if (run->friction == CX_FRICTION_COULOMB)
        snprintf(parts[3], 320, "Coulomb F = %g", run->F);
    else if (run->friction == CX_FRICTION_TRESCA)
        snprintf(parts[3], 320, "Tresca slip bound %g", run->slip_bound);
    else
        snprintf(parts[3], 320, "frictionless");
    /* an animation's first frame is the method's starting iterate: it has
     * no error yet, and "kkt error inf" would read as a blow-up */
    if (run->reason == CX_ITERATING && isinf(run->kkt))
        snprintf(parts[4], 320, "start (iteration %d)", run->iterations);
    else
        snprintf(parts[4], 320, "kkt error %.2e", run->kkt);
    return 5;
}

/* out = a · b (a or b alone when the other is empty), cut to len */
static void ov_join(char *out, size_t len, const char *a, const char *b)
{
    size_t na = strlen(a), nb = strlen(b), n = 0;
    const char *sep = na && b[0] ? " · " : "";
    size_t ns = strlen(sep);
    if (na + ns + nb + 1 > len)
        nb = len > na + ns + 1 ? len - na - ns - 1 : 0;
    if (na + ns + 1 > len)
        na = ns = 0;
    memcpy(out, a, na);
    n += na;
    memcpy(out + n, sep, ns);
    n += ns;
    memcpy(out + n, b, nb);
    out[n + nb] = '\0';
}

/* The subtitle's lines (0 with --no-title, 1, or 2 when one line would have
 * to shrink below 90 % of its size to fit the width): line 2 starts at the
 * first part that does not fit on line 1. The layout makes room for the
 * second line (cx_render_layout_image), so that nothing is cut or shrunk
 * out of legibility. */
int cx_render_subtitle(const cx_result *r, const cx_render_opts *o, char *l1, char *l2, size_t len)
{
    l1[0] = l2[0] = '\0';
    if (o->no_title)
        return 0;
    char parts[5][320];
    int np = ov_subtitle_parts(r, o, parts);
    double F = cx_render_font_px(o->width, o->height, o->font_scale), size = 0.75 * F;
    double maxw = o->width - 1.5 * F;
    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1);
    cairo_t *cr = cairo_create(surf);
    /* the last part measured as the wider of the start's words and an
     * error, so that every frame of an animation wraps alike (and its
     * drawing does not jump between frames) */
    double wl = cx_text_width(cr, parts[np - 1], size, 0);
    double pad = fmax(cx_text_width(cr, "start (iteration 0)", size, 0),
                      cx_text_width(cr, "kkt error 8.88e-88", size, 0)) - wl;
    pad = fmax(pad, 0);
    int lines = 1;
    for (int i = 0; i < np; i++) {
        char *dst = lines == 1 ? l1 : l2;
        size_t n = strlen(dst);
        char trial[1024];
        ov_join(trial, sizeof trial, dst, parts[i]);
        if (lines == 1 && n > 0 && cx_text_width(cr, trial, size, 0) + (i == np - 1 ? pad : 0) > maxw / 0.9) {
            lines = 2;
            ov_join(l2, len, "", parts[i]);
            continue;
        }
        ov_join(dst, len, "", trial);
    }
    /* one line that fits within 90 %: it stays one line */
    if (lines == 2) {
        char all[1024];
        ov_join(all, sizeof all, l1, l2);
        if (cx_text_width(cr, all, size, 0) + pad <= maxw / 0.9) {
            ov_join(l1, len, "", all);
            l2[0] = '\0';
            lines = 1;
        }
    }
    cairo_destroy(cr);
    cairo_surface_destroy(surf);
    return lines;
}

static const char *ov_title_text(const cx_result *r, const cx_render_opts *o)
{
    return o->title ? o->title : r->run.title[0] ? r->run.title : r->run.scene;
}

/* The title's lines (0 with --no-title, 1, or 2 when it would have to
 * shrink below 90 % to fit): cut at the last space that lets line 1 fit
 * (prism's title is 88 characters). */
int cx_render_title_split(const cx_result *r, const cx_render_opts *o, char *t1, char *t2, size_t len)
{
    t1[0] = t2[0] = '\0';
    if (o->no_title)
        return 0;
    const char *t = ov_title_text(r, o);
    double F = cx_render_font_px(o->width, o->height, o->font_scale), size = 1.2 * F;
    double maxw = o->width - 1.5 * F;
    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1);
    cairo_t *cr = cairo_create(surf);
    int lines = 1;
    snprintf(t1, len, "%s", t);
    if (cx_text_width(cr, t, size, 1) > maxw / 0.9) {
        size_t n = strlen(t), cut = 0;
        for (size_t i = 1; i < n && i < len; i++) {
            if (t[i] != ' ')
                continue;
            memcpy(t1, t, i);
            t1[i] = '\0';
            if (cx_text_width(cr, t1, size, 1) > maxw)
                break;
            cut = i;
        }
        if (cut > 0) {
            memcpy(t1, t, cut);
            t1[cut] = '\0';
            snprintf(t2, len, "%s", t + cut + 1);
            lines = 2;
        } else {
            snprintf(t1, len, "%s", t);
        }
    }
    cairo_destroy(cr);
    cairo_surface_destroy(surf);
    return lines;
}

/* The extra room (pixels) the title block takes beyond one title and one
 * subtitle line: the layout moves the drawing down by it. */
double cx_render_title_room(const cx_result *r, const cx_render_opts *o)
{
    char a[512], b[512];
    double F = cx_render_font_px(o->width, o->height, o->font_scale), room = 0;
    if (cx_render_title_split(r, o, a, b, sizeof a) == 2)
        room += CX_RENDER_TITLE_LINE * F;
    if (cx_render_subtitle(r, o, a, b, sizeof a) == 2)
        room += CX_RENDER_SUBTITLE_LINE * F;
    return room;
}

/* The scene's title (1.2 F, bold), then the field and the run in smaller
 * grey (0.75 F), each on two lines when one would not fit. */
static void ov_title(const cx_render_scene *sc, cairo_t *cr)
{
    double F = ov_font(sc), m = 0.75 * F;
    char l1[512], l2[512];
    if (sc->o->no_title)
        return;
    int tl = cx_render_title_split(sc->r, sc->o, l1, l2, sizeof l1);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cx_text_fit(cr, l1, m, 0.45 * F, 1.2 * F, 1, 0, 0, sc->w - 2 * m);
    double y = 2.05 * F;
    if (tl == 2) {
        cx_text_fit(cr, l2, m, 0.45 * F + CX_RENDER_TITLE_LINE * F, 1.2 * F, 1, 0, 0, sc->w - 2 * m);
        y += CX_RENDER_TITLE_LINE * F;
    }
    int lines = cx_render_subtitle(sc->r, sc->o, l1, l2, sizeof l1);
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    cx_text_fit(cr, l1, m, y, 0.75 * F, 0, 0, 0, sc->w - 2 * m);
    if (lines == 2)
        cx_text_fit(cr, l2, m, y + CX_RENDER_SUBTITLE_LINE * F, 0.75 * F, 0, 0, 0, sc->w - 2 * m);
}

/* A run that did not converge says so above the drawing, in the outcome
 * sentence of solve/ (cx_reason_format), on a band no reader can miss. */
static void ov_banner(const cx_render_scene *sc, cairo_t *cr)
{
    const cx_run_record *run = &sc->r->run;
    cx_render_layout l;
    cx_render_layout_image(sc->r, sc->o, &l);
    if (!(l.banner[3] > 0))
        return;
    char outcome[CX_DIAG_LEN + 160], line[CX_DIAG_LEN + 200];
    int start = run->reason == CX_ITERATING && isinf(run->kkt);
    /* an animation's first frame and its converged last: a caption, not a
     * warning */
    int neutral = start || !cx_render_unconverged(run);
    if (start)
        snprintf(outcome, sizeof outcome, "start (iteration %d)", run->iterations);
    else if (run->reason == CX_ITERATING)
        snprintf(outcome, sizeof outcome, "still running: iteration %d, kkt error %.1e > tol %.0e",
                 run->iterations, run->kkt, run->tol);
    else
        cx_reason_format(run->reason, run->iterations, run->kkt, run->tol, run->message, outcome,
                         sizeof outcome);
    /* the sentence says it already when it is "did not converge ..." */
    snprintf(line, sizeof line, "%s%s", neutral || strstr(outcome, "not converge") ? "" : "not converged: ", outcome);
    if (neutral)   /* dark grey: one of the GIF table's greys */
        cairo_set_source_rgb(cr, 89 / 255.0, 89 / 255.0, 89 / 255.0);
    else
        cairo_set_source_rgb(cr, CX_PALETTE_WARNING_RGB);
    cairo_rectangle(cr, l.banner[0], l.banner[1], l.banner[2], l.banner[3]);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cx_text_fit(cr, line, l.banner[0] + 0.45 * l.font, l.banner[1] + 0.5 * l.banner[3], 0.8 * l.font, 1,
                0, 0.5, l.banner[2] - 0.9 * l.font);
}

static void ov_colorbar(const cx_render_scene *sc, cairo_t *cr, double s)
{
    cx_render_layout l;
    cx_render_layout_image(sc->r, sc->o, &l);
    double x = l.bar[0], y = l.bar[1], bw = l.bar[2], bh = l.bar[3];
    int div = sc->diverging;
    int nb = (int)ceil(bh);
    for (int i = 0; i < nb; i++) {
        unsigned char c[3];
        cx_colormap_named(sc->o->cmap, div, 1.0 - (i + 0.5) / nb, c);
        ov_rgb(cr, c);
        cairo_rectangle(cr, x, y + bh * i / nb, bw, bh / nb + 0.6);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_set_line_width(cr, 1.0 * s);
    cairo_rectangle(cr, x, y, bw, bh);
    cairo_stroke(cr);
    /* large or small values: ticks in units of 10^n, named in the title;
     * --log: decades (sc->lo, sc->hi are their log10) */
    double F = l.font, vlo = sc->o->log ? pow(10.0, sc->lo) : sc->lo;
    double vhi = sc->o->log ? pow(10.0, sc->hi) : sc->hi;
    cx_axis ax;
    cx_axis_colorbar(&ax, vlo, vhi, sc->o->log, (int)fmax(3, fmin(8, bh / (2.2 * F))));
    char lab[64];
    /* --log: the unlabelled 2..9 of each decade, half as long, so that a bar
     * spanning few decades still reads as a log scale */
    for (int i = 0; i < ax.nminor; i++) {
        double ty = y + bh * (1 - cx_axis_frac(&ax, ax.minor[i]));
        cairo_move_to(cr, x + bw, ty);
        cairo_line_to(cr, x + bw + 0.14 * F, ty);
        cairo_stroke(cr);
    }
    for (int i = 0; i < ax.nticks; i++) {
        double ty = y + bh * (1 - cx_axis_frac(&ax, ax.ticks[i]));
        cairo_move_to(cr, x + bw, ty);
        cairo_line_to(cr, x + bw + 0.25 * F, ty);
        cairo_stroke(cr);
        cx_axis_label(&ax, ax.ticks[i], lab, sizeof lab);
        cx_text(cr, lab, x + bw + 0.35 * F, ty, F, 0, 0, 0.5);
    }
    char title[200];
    cx_field_axis_label(&sc->r->run, sc->o->field, title, sizeof title);
    size_t tn = strlen(title);
    cx_axis_unit_suffix(&ax, title + tn, sizeof title - tn);
    cx_text_vertical(cr, title, sc->w - 0.75 * F, y + 0.5 * bh, 0.9 * F, 0);
}

/* 2D obstacle ob: a hatched strip beyond the plane, or the disc. */
static void ov_obstacle2d(const cx_render_scene *sc, const cx_obstacle *ob, cairo_t *cr, double s)
{
    cx_render_layout l;
    cx_render_layout_image(sc->r, sc->o, &l);
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
        if (sc->nsym > 0 && cx_render_on_plane(sc, e[0], e[2]))
            continue;   /* inside the whole body (--mirror) */
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

/* Is the boundary edge a-b (contact points ia, ib) on the contact
 * boundary, across the contact normals, and not a side edge between two
 * contact boundaries (a laminae strip's end)? */
static int ov_along_contact(const cx_render_scene *sc, int a, int b, int ia, int ib)
{
    const double *n = sc->r->contact.normal;
    double t[2] = {sc->x0[3 * b] - sc->x0[3 * a], sc->x0[3 * b + 1] - sc->x0[3 * a + 1]};
    double l = hypot(t[0], t[1]);
    if (!(l > 0))
        return 0;
    return fabs(t[0] * n[2 * ia] + t[1] * n[2 * ia + 1]) < 0.5 * l &&
           fabs(t[0] * n[2 * ib] + t[1] * n[2 * ib + 1]) < 0.5 * l;
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
        if (!ci[e[0]] || !ci[e[2]] || !ov_along_contact(sc, e[0], e[2], ci[e[0]] - 1, ci[e[2]] - 1))
            continue;
        double pa[2], pb[2];
        cx_render_scene_project(sc, sc->xd + 3 * e[0], pa);
        cx_render_scene_project(sc, sc->xd + 3 * e[2], pb);
        unsigned char c[3];
        if (status) {
            /* each half of the segment takes the status of its end, so
             * that the band changes colour half-way between two points of
             * different status (stick | slip, not a "free" grey) */
            int a = sc->r->status[ci[e[0]] - 1];
            int b = sc->r->status[ci[e[2]] - 1];
            if (a != b) {
                double mid[2] = {0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])};
                cx_status_color(a, c);
                ov_rgb(cr, c);
                cairo_move_to(cr, pa[0], pa[1]);
                cairo_line_to(cr, mid[0], mid[1]);
                cairo_stroke(cr);
                cx_status_color(b, c);
                ov_rgb(cr, c);
                cairo_move_to(cr, mid[0], mid[1]);
                cairo_line_to(cr, pb[0], pb[1]);
                cairo_stroke(cr);
                continue;
            }
            cx_status_color(a, c);
        } else {
            double v = 0.5 * (sc->val[e[0]] + sc->val[e[2]]);
            cx_colormap_named(sc->o->cmap, 0, (v - sc->lo) / (sc->hi - sc->lo), c);
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
    if (sc->dim != 3 || sc->o->view == CX_VIEW_CONTACT)
        return 1;
    double n[3] = {sc->r->contact.normal[3 * i], sc->r->contact.normal[3 * i + 1],
                   sc->r->contact.normal[3 * i + 2]};
    for (int j = 0; j < sc->nsym; j++)   /* the copy's normal (--mirror) */
        if (sc->copy >> j & 1)
            n[sc->sym_axis[j]] = -n[sc->sym_axis[j]];
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

/* The bottom line: the status legend at the right (drawn first, so that
 * the note beside it is fitted into what is left), then the displacement
 * scale, the obstacle's offset and caveats at the left. */
/* The status legend at the right of the notes row y; returns where it
 * starts (x), drawing it only when draw is set. */
static double ov_legend(const cx_render_scene *sc, cairo_t *cr, double y, double fs, int draw)
{
    static const int codes[4] = {CX_PT_FREE, CX_PT_CONTACT, CX_PT_STICK, CX_PT_SLIP_POS};
    double x = sc->w - 0.75 * ov_font(sc);
    for (int i = 3; i >= 0; i--) {
        if (sc->r->run.friction == CX_FRICTION_NONE ? i >= 2 : i == 1)
            continue;
        const char *name = cx_palette_status_name[codes[i]];
        unsigned char c[3];
        cx_status_color(codes[i], c);
        x -= cx_text_width(cr, name, fs, 0);
        if (draw) {
            cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
            cx_text(cr, name, x, y, fs, 0, 0, 0.5);
        }
        x -= 0.65 * fs;
        if (draw) {
            cairo_new_sub_path(cr);
            cairo_arc(cr, x, y, 0.3 * fs, 0, 2 * CX_PI);
            ov_rgb(cr, c);
            cairo_fill(cr);
        }
        x -= 1.2 * fs;
    }
    return x;
}

static void ov_notes(const cx_render_scene *sc, cairo_t *cr, int legend, int hidden)
{
    char line[512];
    double F = ov_font(sc), fs = 0.8 * F, y = sc->h - 1.05 * F;
    double x = legend ? ov_legend(sc, cr, y, fs, 0) : sc->w - 0.75 * F;
    if (sc->o->scale > 0)
        snprintf(line, sizeof line, "displacement × %.3g (set), max |u| = %.3g", sc->scale, sc->umax);
    else if (sc->scale == 1 && sc->r->m > 0 && sc->umax > 0)
        snprintf(line, sizeof line, "displacement × 1 (auto: true scale with contact, max |u| = %.3g)", sc->umax);
    else
        snprintf(line, sizeof line, "displacement × %.3g (auto: max |u| = %.3g drawn as 7 %% of the body size)",
                 sc->scale, sc->umax);
    /* the settlement and the magnification notes: on the line, or on a
     * line of their own above it when the legend leaves too little room
     * (both lines then move down into the bottom margin, below the
     * drawing area: nothing is cut off and nothing covers the ground) */
    char extra[320];
    size_t ne = 0;
    extra[0] = '\0';
    if (sc->obstacle_gap > 0)
        /* the settlement: the obstacle moved with the scale (image.c) */
        ne += (size_t)snprintf(extra, sizeof extra, "obstacle drawn %.3g × its gap %.3g from the body", sc->scale,
                               sc->obstacle_gap);
    if (sc->contact_inexact && ne < sizeof extra)
        snprintf(extra + ne, sizeof extra - ne, "%smagnified: contact drawn inexactly (exact at --scale 1)",
                 ne ? " · " : "");
    char all[840];
    ov_join(all, sizeof all, line, extra);
    int two = extra[0] && cx_text_width(cr, all, fs, 0) > x - 0.75 * F;
    if (two)
        y = sc->h - 0.55 * F;
    double above = y - 0.95 * fs;
    if (legend)
        ov_legend(sc, cr, y, fs, 1);
    cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
    if (two) {
        cx_text_fit(cr, line, 0.75 * F, y, fs, 0, 0, 0.5, x - 0.75 * F);
        cx_text_fit(cr, extra, 0.75 * F, above, fs, 0, 0, 0.5, sc->w - 1.5 * F);
        above -= 0.95 * fs;
    } else {
        cx_text_fit(cr, all, 0.75 * F, y, fs, 0, 0, 0.5, x - 0.75 * F);
    }
    if (hidden)
        cx_text(cr, "the contact faces are hidden from here: --view contact shows them", 0.75 * F,
                two ? above : y - 1.1 * fs, fs, 0, 0, 0.5);
}

void cx_render_underlay(const cx_render_scene *sc, cairo_t *cr)
{
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    for (int j = 0; j < sc->nobst && sc->dim == 2; j++)
        ov_obstacle2d(sc, &sc->obstacles[j], cr, ov_scale(sc));
}

/* 3D: the undeformed shape as a thin wireframe of its feature edges
 * (hidden ones too: it is a reference, not a surface). */
static void ov_wire0(const cx_render_scene *sc, cairo_t *cr, double s)
{
    cairo_set_source_rgba(cr, 0.2, 0.2, 0.2, 0.55);
    cairo_set_line_width(cr, 0.9 * s);
    double dash[2] = {5 * s, 3 * s};
    cairo_set_dash(cr, dash, 2, 0);
    for (int i = 0; i < sc->nfeat0; i++) {
        double a[2], b[2];
        cx_render_scene_project(sc, sc->x0 + 3 * sc->feat0[2 * i], a);
        cx_render_scene_project(sc, sc->x0 + 3 * sc->feat0[2 * i + 1], b);
        cairo_move_to(cr, a[0], a[1]);
        cairo_line_to(cr, b[0], b[1]);
    }
    cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0);
}

/* 3D, obstacle j seen from its side: a sphere or cylinder as its outline
 * (dashed), so that it does not hide the contact zone behind it; a plane
 * not at all (it would only frame the picture). */
static void ov_obstacle_ghost(const cx_render_scene *sc, int j, cairo_t *cr, double s)
{
    const cx_obstacle *ob = &sc->obstacles[j];
    long from = sc->obst_range[j][0], to = sc->obst_range[j][1];
    if (!sc->ghost[j] || from == to)
        return;
    cairo_save(cr);
    cairo_set_source_rgba(cr, 0.35, 0.32, 0.28, 0.9);
    cairo_set_line_width(cr, 1.4 * s);
    double dash[2] = {7 * s, 4 * s};
    cairo_set_dash(cr, dash, 2, 0);
    const float *v = sc->obst.v;
    if (ob->kind == CX_OBST_SPHERE) {
        double p[2];
        cx_render_scene_project(sc, ob->point, p);
        cairo_arc(cr, p[0], p[1], ob->radius * sc->k, 0, 2 * CX_PI);
    } else if (ob->kind == CX_OBST_CYLINDER) {
        /* the two silhouette lines: the axis moved by +-R across the view */
        const double *ax = ob->normal, *e = sc->R + 6;
        double w[3] = {ax[1] * e[2] - ax[2] * e[1], ax[2] * e[0] - ax[0] * e[2], ax[0] * e[1] - ax[1] * e[0]};
        double wl = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]), t0 = INFINITY, t1 = -INFINITY;
        for (long i = from; i < to; i++) {
            double t = 0;
            for (int k = 0; k < 3; k++)
                t += (v[CX_RENDER_VFLOATS * i + k] - ob->point[k]) * ax[k];
            t0 = fmin(t0, t);
            t1 = fmax(t1, t);
        }
        for (int side = -1; side <= 1 && wl > 1e-9; side += 2)
            for (int end = 0; end < 2; end++) {
                double x[3], p[2];
                for (int k = 0; k < 3; k++)
                    x[k] = ob->point[k] + (end ? t1 : t0) * ax[k] + side * ob->radius * w[k] / wl;
                cx_render_scene_project(sc, x, p);
                if (end == 0)
                    cairo_move_to(cr, p[0], p[1]);
                else
                    cairo_line_to(cr, p[0], p[1]);
            }
    }
    cairo_stroke(cr);
    cairo_restore(cr);
}

/* Is some obstacle drawn as its outline (a ghost that is not a plane)? */
static int ov_outlined(const cx_render_scene *sc)
{
    for (int j = 0; j < sc->nobst; j++)
        if (sc->ghost[j] && sc->obstacles[j].kind != CX_OBST_PLANE)
            return 1;
    return 0;
}

/* 3D: the axis triad in the lower left corner of the drawing area, the
 * axes further from the viewer first. */
static void ov_triad(const cx_render_scene *sc, cairo_t *cr, double s)
{
    cx_render_layout l;
    cx_render_layout_image(sc->r, sc->o, &l);
    double F = l.font, L = 2.0 * F;
    double o[2] = {l.area[0] + 0.6 * F + L, l.area[1] + l.area[3] - 0.6 * F - L};
    int order[3] = {0, 1, 2};
    for (int i = 0; i < 3; i++)
        for (int j = i + 1; j < 3; j++)
            if (sc->R[6 + order[j]] < sc->R[6 + order[i]]) {
                int t = order[i];
                order[i] = order[j];
                order[j] = t;
            }
    static const char *const names[3] = {"x", "y", "z"};
    char line[160];
    snprintf(line, sizeof line, "from %s: az %g°, el %g°%s%s", sc->from_below ? "below" : "above", sc->az,
             sc->el, sc->nfeat0 > 0 ? " · dashed: undeformed" : "",
             ov_outlined(sc) ? ", obstacle outline" : "");
    for (int q = 0; q < 3; q++) {
        int k = order[q];
        double d[2] = {sc->R[k], -sc->R[3 + k]}, len = hypot(d[0], d[1]);
        double tip[2] = {o[0] + L * d[0], o[1] + L * d[1]};
        /* a white halo, so that the triad reads over the body too */
        cairo_set_source_rgba(cr, 1, 1, 1, 0.8);
        cairo_set_line_width(cr, 4.0 * s);
        cairo_move_to(cr, o[0], o[1]);
        cairo_line_to(cr, tip[0], tip[1]);
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
        cairo_set_line_width(cr, 1.6 * s);
        cairo_move_to(cr, o[0], o[1]);
        cairo_line_to(cr, tip[0], tip[1]);
        cairo_stroke(cr);
        if (len > 0.15) {   /* an arrow head, unless the axis points at the viewer */
            double u[2] = {d[0] / len, d[1] / len}, h = 0.3 * F;
            cairo_move_to(cr, tip[0], tip[1]);
            cairo_line_to(cr, tip[0] - 1.6 * h * u[0] + 0.6 * h * u[1], tip[1] - 1.6 * h * u[1] - 0.6 * h * u[0]);
            cairo_line_to(cr, tip[0] - 1.6 * h * u[0] - 0.6 * h * u[1], tip[1] - 1.6 * h * u[1] + 0.6 * h * u[0]);
            cairo_close_path(cr);
            cairo_fill(cr);
        }
        double lx = o[0] + (L + 0.55 * F) * d[0], ly = o[1] + (L + 0.55 * F) * d[1];
        if (len < 0.15)   /* towards or away from the viewer: beside the origin */
            lx += 0.6 * F;
        cx_text(cr, names[k], lx, ly, 0.8 * F, 1, 0.5, 0.5);
    }
    /* how the body is seen, beside the triad, on a light backing (legible
     * over the body when --crop contact fills the area) */
    double tw = cx_text_width(cr, line, 0.75 * F, 0), tx = o[0] + L + 1.3 * F, ty = o[1] + 0.5 * L;
    cairo_set_source_rgba(cr, 1, 1, 1, 0.7);
    cairo_rectangle(cr, tx - 0.2 * F, ty - 0.5 * F, tw + 0.4 * F, F);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
    cx_text(cr, line, tx, ty, 0.75 * F, 0, 0, 0.5);
}

/* The world axis along view row `row` (0: right, 1: up) when it is one
 * (an axis-aligned view), with its sign; -1 otherwise. */
static int ov_view_axis(const cx_render_scene *sc, int row, double *sign)
{
    for (int k = 0; k < 3; k++)
        if (fabs(sc->R[3 * row + k]) > 0.999) {
            *sign = sc->R[3 * row + k] > 0 ? 1 : -1;
            return k;
        }
    return -1;
}

/* The contact view: a frame around the contact faces with ticks in world
 * coordinates along the two in-plane axes (when the view is along an axis). */
static void ov_contact_axes(const cx_render_scene *sc, cairo_t *cr, double s)
{
    double sa, sb;
    int a = ov_view_axis(sc, 0, &sa), b = ov_view_axis(sc, 1, &sb);
    if (a < 0 || b < 0 || sc->tris.n == 0)
        return;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (long i = 0; i < sc->tris.n; i++) {
        const float *q = sc->tris.v + CX_RENDER_VFLOATS * i;
        double x[3] = {q[0], q[1], q[2]}, p[2];
        cx_render_scene_project(sc, x, p);
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], p[k]);
            hi[k] = fmax(hi[k], p[k]);
        }
    }
    double F = ov_font(sc), pad = 0.4 * F, da[4];
    cx_render_draw_area(sc, da);   /* --crop contact: the frame is the area's */
    double X0 = fmax(lo[0] - pad, da[0]), X1 = fmin(hi[0] + pad, da[0] + da[2]);
    double Y0 = fmax(lo[1] - pad, da[1]), Y1 = fmin(hi[1] + pad, da[1] + da[3]);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_set_line_width(cr, 1.0 * s);
    cairo_rectangle(cr, X0, Y0, X1 - X0, Y1 - Y0);
    cairo_stroke(cr);
    static const char *const names = "xyz";
    for (int dir = 0; dir < 2; dir++) {
        /* world coordinate w at pixel p: horizontal p = cx + k sa w,
         * vertical p = cy - k sb w */
        double sg = dir == 0 ? sa : sb, c0 = dir == 0 ? sc->cx : sc->cy, kk = dir == 0 ? sc->k : -sc->k;
        double p0 = dir == 0 ? X0 : Y1, p1 = dir == 0 ? X1 : Y0;
        double w0 = (p0 - c0) / (kk * sg), w1 = (p1 - c0) / (kk * sg);
        cx_axis ax;
        double span = fabs(p1 - p0);
        cx_axis_make(&ax, fmin(w0, w1), fmax(w0, w1), 0, (int)fmax(2, fmin(8, span / (4.5 * F))), 0);
        char lab[64];
        for (int i = 0; i < ax.nticks; i++) {
            double p = c0 + kk * sg * ax.ticks[i];
            if (dir == 0) {
                cairo_move_to(cr, p, Y1);
                cairo_line_to(cr, p, Y1 + 0.3 * F);
                cairo_stroke(cr);
                cx_axis_label(&ax, ax.ticks[i], lab, sizeof lab);
                cx_text(cr, lab, p, Y1 + 0.4 * F, 0.85 * F, 0, 0.5, 0);
            } else {
                cairo_move_to(cr, X0, p);
                cairo_line_to(cr, X0 - 0.3 * F, p);
                cairo_stroke(cr);
                cx_axis_label(&ax, ax.ticks[i], lab, sizeof lab);
                cx_text(cr, lab, X0 - 0.4 * F, p, 0.85 * F, 0, 1, 0.5);
            }
        }
        char what[8], title[96];
        snprintf(what, sizeof what, "%c", names[dir == 0 ? a : b]);
        cx_quantity_label(&sc->r->run, what, 0, title, sizeof title);
        if (dir == 0) {
            size_t n = strlen(title);
            snprintf(title + n, sizeof title - n, " · seen from the obstacle");
            cx_text(cr, title, 0.5 * (X0 + X1), Y1 + 1.5 * F, 0.85 * F, 0, 0.5, 0);
        }
        else
            cx_text_vertical(cr, title, X0 - 3.6 * F, 0.5 * (Y0 + Y1), 0.85 * F, 0);
    }
}

/* 2D supports of the scene: a roller (one component held: circles between
 * the boundary and a hatched base line) or a clamp (the hatched line alone)
 * on the outer side of each held boundary. */
static void ov_supports(const cx_render_scene *sc, cairo_t *cr, double s)
{
    const cx_scene *scn = sc->o->scene;
    const cx_mesh *m = sc->r->mesh;
    if (!scn || sc->dim != 2)
        return;
    double F = ov_font(sc), rr = fmax(0.22 * F, 2 * s), ctr[2] = {0, 0};
    for (int i = 0; i < m->nnodes; i++)
        for (int k = 0; k < 2; k++)
            ctr[k] += sc->x0[3 * i + k] / m->nnodes;
    for (int q = 0; q < scn->nsupports; q++) {
        const cx_scene_support *sp = &scn->supports[q];
        const cx_boundary *bd = NULL;
        for (int b = 0; b < m->nbounds; b++)
            if (strcmp(m->bounds[b].name, sp->boundary) == 0)
                bd = &m->bounds[b];
        unsigned comps = sp->comps & 3u;
        if (!bd || bd->nfacets == 0 || !comps)
            continue;
        int roller = comps != 3u, c = comps == 2u ? 1 : 0;
        /* the held direction (a roller's) or the boundary's normal (a
         * clamp's), pointing away from the body */
        double mean[2] = {0, 0}, dir[2] = {0, 0};
        for (int f = 0; f < bd->nfacets; f++)
            for (int k = 0; k < 2; k++)
                mean[k] += 0.5 * (sc->x0[3 * bd->facets[bd->npf * f] + k] +
                                  sc->x0[3 * bd->facets[bd->npf * f + 1] + k]) / bd->nfacets;
        if (roller) {
            dir[c] = mean[c] >= ctr[c] ? 1 : -1;
        } else {
            const int *e = bd->facets;
            double t[2] = {sc->x0[3 * e[1]] - sc->x0[3 * e[0]], sc->x0[3 * e[1] + 1] - sc->x0[3 * e[0] + 1]};
            double l = hypot(t[0], t[1]);
            dir[0] = l > 0 ? -t[1] / l : 0;
            dir[1] = l > 0 ? t[0] / l : 0;
            if (dir[0] * (mean[0] - ctr[0]) + dir[1] * (mean[1] - ctr[1]) < 0) {
                dir[0] = -dir[0];
                dir[1] = -dir[1];
            }
        }
        double o[2] = {dir[0], -dir[1]};   /* in pixels (y down) */
        double base = roller ? 2 * rr + 0.8 * s : 0.6 * s, run = 0;
        for (int f = 0; f < bd->nfacets; f++) {
            /* 2D facets: the two ends first (then a TRI6 mid node) */
            int na = bd->facets[bd->npf * f], nb = bd->facets[bd->npf * f + 1];
            if (sc->nsym > 0 && cx_render_on_plane(sc, na, nb))
                continue;   /* inside the whole body (--mirror) */
            double pa[2], pb[2];
            cx_render_scene_project(sc, sc->xd + 3 * na, pa);
            cx_render_scene_project(sc, sc->xd + 3 * nb, pb);
            double len = hypot(pb[0] - pa[0], pb[1] - pa[1]);
            if (!(len > 0))
                continue;
            double t[2] = {(pb[0] - pa[0]) / len, (pb[1] - pa[1]) / len};
            cairo_set_source_rgb(cr, 0.3, 0.28, 0.25);
            cairo_set_line_width(cr, 1.0 * s);
            if (roller)   /* circles every 3.2 radii along the boundary */
                for (double at = fmod(run, 3.2 * rr); at < len; at += 3.2 * rr) {
                    double cxy[2] = {pa[0] + at * t[0] + rr * o[0], pa[1] + at * t[1] + rr * o[1]};
                    cairo_new_sub_path(cr);
                    cairo_arc(cr, cxy[0], cxy[1], 0.85 * rr, 0, 2 * CX_PI);
                    cairo_stroke(cr);
                }
            run = fmod(run + len, 3.2 * rr);
            cairo_set_line_width(cr, 1.6 * s);
            cairo_move_to(cr, pa[0] + base * o[0], pa[1] + base * o[1]);
            cairo_line_to(cr, pb[0] + base * o[0], pb[1] + base * o[1]);
            cairo_stroke(cr);
            cairo_set_line_width(cr, 0.9 * s);
            double hl = 0.55 * F;
            for (double at = 0.3 * hl; at < len; at += 0.6 * hl) {
                double p[2] = {pa[0] + at * t[0] + base * o[0], pa[1] + at * t[1] + base * o[1]};
                cairo_move_to(cr, p[0], p[1]);
                cairo_line_to(cr, p[0] + hl * (0.7 * o[0] - 0.7 * t[0]), p[1] + hl * (0.7 * o[1] - 0.7 * t[1]));
            }
            cairo_stroke(cr);
        }
    }
}

void cx_render_overlay(const cx_render_scene *sc, cairo_t *cr)
{
    double s = ov_scale(sc);
    int f = sc->o->field;
    int markers = sc->dim == 2 || f == CX_FIELD_STATUS;
    cx_render_layout l;
    cx_render_layout_image(sc->r, sc->o, &l);
    cairo_save(cr);
    if (sc->o->crop_contact) {   /* the zoomed drawing stays in its area */
        double a[4];
        cx_render_draw_area(sc, a);
        cairo_rectangle(cr, a[0], a[1], a[2], a[3]);
        cairo_clip(cr);
    }
    int shown = 0;
    double r = ov_marker_radius(sc, s);
    /* once per copy of --mirror (cx_render_scene_project reflects) */
    for (int c = 0; c < sc->ncopies; c++) {
        cx_render_scene cp = *sc;
        cp.copy = c;
        if (sc->dim == 2) {
            ov_outline(&cp, cr, sc->x0, 1.2 * s, 0.3, 0.3, 0.3, 0.35);
            ov_outline(&cp, cr, sc->xd, 1.2 * s, 0.1, 0.1, 0.1, 0.9);
            ov_supports(&cp, cr, s);
            if (f == CX_FIELD_PRESSURE || f == CX_FIELD_STATUS)
                ov_band2d(&cp, cr, s);
        } else if (sc->o->view != CX_VIEW_CONTACT) {
            for (int j = 0; j < sc->nobst && c == 0; j++)
                ov_obstacle_ghost(sc, j, cr, s);
            ov_wire0(&cp, cr, s);
        }
        if (markers)
            shown += ov_status(&cp, cr, s, f == CX_FIELD_STATUS ? fmin(1.4 * r, 4 * s) : r);
    }
    cairo_restore(cr);
    int seen = 0;
    for (int i = 0; i < sc->r->m && !seen; i++)
        seen = ov_visible(sc, i);
    int hidden = sc->dim == 3 && sc->o->view != CX_VIEW_CONTACT && sc->r->m > 0 && !seen &&
                 (f == CX_FIELD_PRESSURE || (f == CX_FIELD_STATUS && shown == 0));
    if (sc->dim == 3 && sc->o->view == CX_VIEW_CONTACT)
        ov_contact_axes(sc, cr, s);
    else if (sc->dim == 3)
        ov_triad(sc, cr, s);
    ov_title(sc, cr);
    ov_banner(sc, cr);
    if (f != CX_FIELD_STATUS)
        ov_colorbar(sc, cr, s);
    ov_notes(sc, cr, markers, hidden);
}
