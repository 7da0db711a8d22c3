/* SPDX-License-Identifier: GPL-3.0-or-later */
/* An image of a solved problem: fields, geometry and camera, the GL pass
 * (composited over the 2D obstacle), the cairo overlays, the PNG. */
#include "render/render_impl.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cx_config.h"
#include "render/image_impl.h"
#include "render/pngfile.h"

void cx_render_opts_default(cx_render_opts *o)
{
    memset(o, 0, sizeof *o);
    o->width = 1200;
    o->height = 900;
    o->field = CX_FIELD_VON_MISES;
    o->scale = 0;
    o->edges = 0;
    o->view = CX_VIEW_BODY;
    o->msaa = 4;
    o->font_scale = 1;
    o->cmap = CX_CMAP_AUTO;
}

static double img_body_size(const cx_mesh *m)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, d2 = 0;
    for (int i = 0; i < m->nnodes; i++)
        for (int k = 0; k < m->dim; k++) {
            lo[k] = fmin(lo[k], m->x[m->dim * i + k]);
            hi[k] = fmax(hi[k], m->x[m->dim * i + k]);
        }
    for (int k = 0; k < m->dim; k++)
        d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return sqrt(d2);
}

static double img_umax(const cx_mesh *m, const double *uall)
{
    double umax = 0;
    for (int i = 0; i < m->nnodes; i++) {
        double s = 0;
        for (int k = 0; k < m->dim; k++)
            s += uall[m->dim * i + k] * uall[m->dim * i + k];
        umax = fmax(umax, sqrt(s));
    }
    return umax;
}

double cx_render_auto_scale(const cx_result *r)
{
    double umax = img_umax(r->mesh, r->u);
    double s = umax > 0 ? 0.07 * img_body_size(r->mesh) / umax : 1.0;
    /* shrinking would draw points in contact off the obstacle: at s = 1
     * the drawn contact is the solver's */
    return r->m > 0 ? fmax(s, 1.0) : s;
}

/* One obstacle ob (the result's, moved in place as drawn); the uniform
 * gap of its plane's nearest points in *gap. */
static void img_obstacle_one(cx_render_scene *sc, cx_obstacle *ob, double *gap)
{
    const cx_result *r = sc->r;
    const cx_contact_set *cs = &r->contact;
    int dim = sc->dim;
    double size = img_body_size(r->mesh), tolg = 1e-9 * size;
    *gap = 0;
    if (ob->kind != CX_OBST_PLANE || cs->m == 0) {
        /* curved obstacles: contact at gaps > 0 is inexact when s != 1 */
        for (int i = 0; i < cs->m; i++)
            if (r->status[i] != CX_PT_FREE && cs->gap[i] > tolg && sc->scale != 1)
                sc->contact_inexact = 1;
        return;
    }
    /* the points against the plane: their gap is their distance to it
     * (body-to-body points, e.g. masonry's joints, and the points against
     * another obstacle are not) */
    double g0 = INFINITY, tolc = 1e-6 * size;
    int *against = CX_NEW(int, cs->m > 0 ? cs->m : 1);
    for (int i = 0; i < cs->m; i++) {
        double dist = 0;
        for (int k = 0; k < dim; k++)
            dist += (cs->x[dim * i + k] - ob->point[k]) * ob->normal[k];
        int on = fabs(dist - cs->gap[i]) <= tolc;
        if (against)
            against[i] = on;
        if (on)
            g0 = fmin(g0, dist);
    }
    if (!(g0 > tolg) || !isfinite(g0))
        g0 = 0;
    *gap = g0;
    double shift = (1 - sc->scale) * g0;
    for (int k = 0; k < dim; k++)
        ob->point[k] += shift * ob->normal[k];
    /* points in contact that started at another gap are drawn off it */
    for (int i = 0; i < cs->m && sc->scale != 1; i++)
        if (r->status[i] != CX_PT_FREE && (!against || against[i]) && fabs(cs->gap[i] - g0) > tolc)
            sc->contact_inexact = 1;
    cx_free(against);
}

/* The obstacles where the drawn bodies meet them. A point in contact with
 * initial gap g moves by g towards the obstacle, and is drawn moved by
 * s g: a plane whose nearest points all start at the gap g (masonry's
 * settlement) is drawn moved by (1 - s) g along its normal, so that they
 * touch it at any scale s. Where the points in contact start at other
 * gaps (a curved body) and s != 1, the image says that the contact is not
 * drawn exactly. Every obstacle of the result is drawn, in 2D and 3D. */
static void img_obstacle(cx_render_scene *sc)
{
    const cx_result *r = sc->r;
    /* r->obstacle is the first (a result made by hand may set it alone) */
    sc->nobst = !r->has_obstacle ? 0 : r->nobstacles > 1 ? r->nobstacles : 1;
    for (int j = 0; j < sc->nobst; j++) {
        double g;
        sc->obstacles[j] = j ? r->obstacles[j] : r->obstacle;
        img_obstacle_one(sc, &sc->obstacles[j], &g);
        if (j == 0)
            sc->obstacle_gap = g;
    }
}

static void img_clear(cx_render_scene *sc)
{
    cx_free(sc->x0);
    cx_free(sc->xd);
    cx_free(sc->val);
    cx_free(sc->bedges);
    cx_free(sc->feat0);
    cx_render_array_clear(&sc->feature);
    cx_render_array_clear(&sc->tris);
    cx_render_array_clear(&sc->overlay);
    cx_render_array_clear(&sc->lines);
    cx_render_array_clear(&sc->obst);
}

/* The colour range: magnitudes [0, max], signed fields [-M, M]; over the
 * contact nodes for the pressure and the contact view. Under --log the
 * range of the positive values (at most 6 decades below the largest),
 * and the values and range as their log10, which the GL and the overlays
 * map linearly; what is below the range takes its lowest colour. */
static void img_range(cx_render_scene *sc)
{
    const cx_mesh *m = sc->r->mesh;
    const cx_contact_set *cs = &sc->r->contact;
    int on_contact = sc->o->field == CX_FIELD_PRESSURE || sc->o->view == CX_VIEW_CONTACT;
    double lo = INFINITY, hi = -INFINITY, pos = INFINITY;
    int n = on_contact ? cs->m : m->nnodes;
    for (int i = 0; i < n; i++) {
        double v = sc->val[on_contact ? cs->node[i] : i];
        lo = fmin(lo, v);
        hi = fmax(hi, v);
        if (v > 0)
            pos = fmin(pos, v);
    }
    if (!(lo <= hi))
        lo = hi = 0;
    if (sc->o->log) {
        if (sc->o->has_range) {
            lo = sc->o->range_lo;
            hi = sc->o->range_hi;
        } else if (!(hi > 0)) {   /* nothing positive: three decades below 1 */
            lo = 1e-3;
            hi = 1;
        } else {
            lo = fmax(pos, 1e-6 * hi);
            if (!(hi > lo))
                lo = 0.1 * hi;
        }
        sc->lo = log10(lo);
        sc->hi = log10(hi);
        for (int i = 0; i < m->nnodes; i++)
            sc->val[i] = sc->val[i] > 0 ? log10(sc->val[i]) : sc->lo - 1;
        return;
    }
    if (cx_field_is_signed(sc->o->field) && lo < 0 && hi > 0) {
        double M = fmax(fabs(lo), fabs(hi));
        sc->lo = -M;
        sc->hi = M;
    } else if (cx_field_is_signed(sc->o->field) && hi <= 0 && lo < 0) {
        /* one-signed (e.g. uz of a body pushed down): [min, 0] on a
         * sequential map, not half of a diverging one */
        sc->lo = lo;
        sc->hi = 0;
    } else {
        sc->lo = fmin(lo, 0.0);
        sc->hi = hi;
    }
    if (sc->o->has_range) {   /* the user's: shared by several figures */
        sc->lo = sc->o->range_lo;
        sc->hi = sc->o->range_hi;
    }
    /* diverging only about a zero inside the range */
    sc->diverging = cx_field_is_signed(sc->o->field) && sc->lo < 0 && sc->hi > 0;
    if (sc->o->has_range)
        return;
    if (!(sc->hi > sc->lo)) {   /* a constant field: a unit range around it */
        double c = sc->lo;
        sc->lo = cx_field_is_signed(sc->o->field) || c != 0 ? c - 1 : 0;
        sc->hi = sc->lo + (c != 0 || cx_field_is_signed(sc->o->field) ? 2 : 1);
        sc->diverging = cx_field_is_signed(sc->o->field) && sc->lo < 0 && sc->hi > 0;
    }
}

static int img_prepare(cx_render_scene *sc, cx_result *r, const cx_render_opts *o, const cx_render_fix *fix,
                       double *t_fields, cx_diag *d)
{
    double t0 = cx_clock_now();
    memset(sc, 0, sizeof *sc);
    sc->r = r;
    sc->o = o;
    sc->w = o->width;
    sc->h = o->height;
    const cx_mesh *m = r->mesh;
    int dim = m->dim, nn = m->nnodes, f = sc->o->field;
    sc->dim = dim;
    sc->uall = r->u;
    sc->x0 = CX_NEW(double, 3 * (size_t)nn);
    sc->xd = CX_NEW(double, 3 * (size_t)nn);
    sc->val = cx_malloc(sizeof(double) * (size_t)nn);
    if (!sc->x0 || !sc->xd || !sc->val)
        return cx_diag_set(d, CX_ENOMEM, "render: out of memory");
    if (cx_field_nodal(r, f, sc->val, NULL) != CX_OK)
        return cx_diag_set(d, CX_ENUMERIC, "render: cannot compute the field %s", cx_field_name(f));
    for (int i = 0; i < nn && f != CX_FIELD_STATUS; i++)
        if (!isfinite(sc->val[i]))
            return cx_diag_set(d, CX_ENUMERIC, "render: the field %s is not finite at node %d",
                               cx_field_name(f), i);
    sc->umax = img_umax(m, sc->uall);
    sc->size = img_body_size(m);
    sc->ncopies = 1;
    if (o->mirror && o->scene) {   /* checked by img_check */
        sc->nsym = o->scene->nsymmetry;
        for (int j = 0; j < sc->nsym; j++) {
            sc->sym_axis[j] = o->scene->symmetry_axis[j];
            sc->sym_at[j] = o->scene->symmetry_at[j];
        }
        sc->ncopies = 1 << sc->nsym;
    }
    sc->scale = fix ? fix->scale : sc->o->scale > 0 ? sc->o->scale : cx_render_auto_scale(r);
    for (int i = 0; i < nn; i++)
        for (int k = 0; k < dim; k++) {
            sc->x0[3 * i + k] = m->x[dim * i + k];
            sc->xd[3 * i + k] = m->x[dim * i + k] + sc->scale * sc->uall[dim * i + k];
        }
    img_obstacle(sc);
    if (f == CX_FIELD_STATUS) {
        sc->lo = 0;
        sc->hi = 1;
    } else {
        img_range(sc);
        if (fix) {   /* an animation's: every frame in the final iterate's colours */
            sc->lo = fix->lo;
            sc->hi = fix->hi;
            sc->diverging = !o->log && cx_field_is_signed(f) && sc->lo < 0 && sc->hi > 0;
        }
    }
    /* the body carries the colours, except for contact-only fields seen
     * on the whole body */
    sc->colored = f != CX_FIELD_STATUS &&
                  (f != CX_FIELD_PRESSURE || (dim == 3 && sc->o->view == CX_VIEW_CONTACT));
    cx_render_camera_orient(sc);
    if (cx_render_geometry(sc) != CX_OK)
        return cx_diag_set(d, CX_ENOMEM, "render: out of memory");
    cx_render_camera(sc);
    if (fix) {   /* and seen from where it is seen */
        memcpy(sc->R, fix->R, sizeof sc->R);
        sc->k = fix->k;
        sc->cx = fix->cx;
        sc->cy = fix->cy;
        sc->zmin = fix->zmin;
        sc->zmax = fix->zmax;
    }
    *t_fields = cx_clock_now() - t0;
    return CX_OK;
}

static int img_check(const cx_result *r, const cx_render_opts *o, cx_diag *d)
{
    if (o->width < 64 || o->height < 64 || o->width > 16384 || o->height > 16384)
        return cx_diag_set(d, CX_EINVAL, "--size %dx%d: expected 64..16384 pixels each way",
                           o->width, o->height);
    CX_TRY(cx_field_check(o->field, r->dim, d));
    if (o->view == CX_VIEW_CONTACT && r->dim != 3)
        return cx_diag_set(d, CX_EINVAL, "--view contact: only in 3D");
    if (o->mirror && (!o->scene || o->scene->nsymmetry == 0))
        return cx_diag_set(d, CX_EINVAL, "--mirror: the scene%s%s names no symmetry plane (key "
                           "'symmetry' of [scene])", o->scene ? " " : "", o->scene ? o->scene->id : "");
    if (o->crop_contact && r->m == 0)
        return cx_diag_set(d, CX_EINVAL, "--crop contact: the problem has no contact points");
    if (o->has_camera && !(isfinite(o->cam_az) && isfinite(o->cam_el) && fabs(o->cam_el) <= 90))
        return cx_diag_set(d, CX_EINVAL, "--camera %g,%g: expected AZ,EL in degrees, |EL| <= 90",
                           o->cam_az, o->cam_el);
    if (o->cmap < CX_CMAP_AUTO || o->cmap >= CX_CMAP_COUNT)
        return cx_diag_set(d, CX_EINVAL, "--cmap %d: unknown colormap", o->cmap);
    if (o->has_range && !(isfinite(o->range_lo) && isfinite(o->range_hi) && o->range_lo < o->range_hi))
        return cx_diag_set(d, CX_EINVAL, "--range %g:%g: expected finite MIN < MAX", o->range_lo,
                           o->range_hi);
    if (o->log && cx_field_is_signed(o->field))
        return cx_diag_set(d, CX_EINVAL, "--log: only for magnitudes (von-mises, u, pressure), not %s",
                           cx_field_name(o->field));
    if (o->log && o->has_range && !(o->range_lo > 0))
        return cx_diag_set(d, CX_EINVAL, "--range %g:%g with --log: expected 0 < MIN < MAX", o->range_lo,
                           o->range_hi);
    if (!(o->font_scale >= 0.25 && o->font_scale <= 4))
        return cx_diag_set(d, CX_EINVAL, "--font-scale %g: expected 0.25..4", o->font_scale);
    if (o->msaa < 0 || o->msaa > 4)
        return cx_diag_set(d, CX_EINVAL, "msaa %d: expected 0..4 samples", o->msaa);
    return CX_OK;
}

int cx_render_project(cx_result *r, const cx_render_opts *o, const double *x, double px[2],
                      cx_diag *d)
{
    CX_TRY(img_check(r, o, d));
    cx_render_scene sc;
    double tf;
    int rc = img_prepare(&sc, r, o, NULL, &tf, d);
    if (rc == CX_OK) {
        double x3[3] = {0, 0, 0};
        for (int k = 0; k < r->dim; k++)
            x3[k] = x[k];
        cx_render_scene_project(&sc, x3, px);
    }
    img_clear(&sc);
    return rc;
}

static void img_fix_of(const cx_render_scene *sc, cx_render_fix *fix)
{
    memcpy(fix->R, sc->R, sizeof sc->R);
    fix->k = sc->k;
    fix->cx = sc->cx;
    fix->cy = sc->cy;
    fix->zmin = sc->zmin;
    fix->zmax = sc->zmax;
    fix->scale = sc->scale;
    fix->lo = sc->lo;
    fix->hi = sc->hi;
}

int cx_render_image_fix(cx_result *r, const cx_render_opts *o, cx_render_fix *fix, cx_diag *d)
{
    CX_TRY(img_check(r, o, d));
    cx_render_scene sc;
    double tf;
    int rc = img_prepare(&sc, r, o, NULL, &tf, d);
    if (rc == CX_OK)
        img_fix_of(&sc, fix);
    img_clear(&sc);
    return rc;
}

void cx_render_buf_clear(cx_render_buf *b)
{
    cx_free(b->rgb);
    cx_free(b->gl);
    memset(b, 0, sizeof *b);
}

int cx_render_image_draw(cx_result *r, const cx_render_opts *o, const cx_render_fix *fix, int compose,
                         cx_render_buf *b, cx_render_timing *t, cx_diag *d)
{
    cx_render_timing tm = {0};
    memset(b, 0, sizeof *b);
    CX_TRY(img_check(r, o, d));
    cx_render_scene sc;
    int rc = img_prepare(&sc, r, o, fix, &tm.fields, d);
    b->w = sc.w;
    b->h = sc.h;
    b->stride = cairo_format_stride_for_width(CAIRO_FORMAT_ARGB32, sc.w);
    if (rc == CX_OK) {
        b->gl = cx_calloc((size_t)b->stride, (size_t)sc.h);
        b->rgb = compose ? cx_calloc((size_t)b->stride, (size_t)sc.h) : NULL;
        if (!b->gl || (compose && !b->rgb))
            rc = cx_diag_set(d, CX_ENOMEM, "render: out of memory");
    }
    if (rc == CX_OK) {
        double t0 = cx_clock_now();
        rc = cx_render_gl_draw(&sc, b->gl, b->stride, &tm.context, &tm.draw_calls, d);
        tm.draw = cx_clock_now() - t0 - tm.context;
    }
    if (rc == CX_OK && compose) {
        double t0 = cx_clock_now();
        cairo_surface_t *so = cairo_image_surface_create_for_data(b->rgb, CAIRO_FORMAT_RGB24, sc.w, sc.h,
                                                                  b->stride);
        cairo_surface_t *sg = cairo_image_surface_create_for_data(b->gl, CAIRO_FORMAT_ARGB32, sc.w, sc.h,
                                                                  b->stride);
        cairo_t *cr = cairo_create(so);
        cx_render_underlay(&sc, cr);
        cairo_set_source_surface(cr, sg, 0, 0);
        cairo_paint(cr);
        cx_render_overlay(&sc, cr);
        if (cairo_status(cr) != CAIRO_STATUS_SUCCESS)
            rc = cx_diag_set(d, CX_EEXTERNAL, "cairo: %s", cairo_status_to_string(cairo_status(cr)));
        cairo_destroy(cr);
        cairo_surface_flush(so);
        cairo_surface_destroy(so);
        cairo_surface_destroy(sg);
        tm.text = cx_clock_now() - t0;
    }
    if (rc == CX_OK) {
        /* where the camera stood, for the PNG's text */
        if (sc.dim == 2)
            snprintf(b->camera, sizeof b->camera, "2d%s%s", o->crop_contact ? " crop contact" : "",
                     sc.ncopies > 1 ? " mirror" : "");
        else if (o->view == CX_VIEW_CONTACT)
            snprintf(b->camera, sizeof b->camera, "contact view%s", o->crop_contact ? " crop contact" : "");
        else
            snprintf(b->camera, sizeof b->camera, "az %g el %g%s%s", sc.az, sc.el,
                     o->crop_contact ? " crop contact" : "", sc.ncopies > 1 ? " mirror" : "");
        img_fix_of(&sc, &b->fix);
        b->lo = o->log ? pow(10.0, sc.lo) : sc.lo;
        b->hi = o->log ? pow(10.0, sc.hi) : sc.hi;
    } else {
        cx_render_buf_clear(b);
    }
    img_clear(&sc);
    if (t)
        *t = tm;
    return rc;
}

int cx_render_image_vector(cx_result *r, const cx_render_opts *o, const cx_render_buf *b, cairo_t *cr,
                           cx_diag *d)
{
    cx_render_scene sc;
    double tf;
    int rc = img_prepare(&sc, r, o, &b->fix, &tf, d);
    if (rc == CX_OK) {
        cairo_surface_t *sg = cairo_image_surface_create_for_data(b->gl, CAIRO_FORMAT_ARGB32, b->w, b->h,
                                                                  b->stride);
        cx_render_underlay(&sc, cr);
        cairo_save(cr);
        cairo_set_source_surface(cr, sg, 0, 0);
        cairo_paint(cr);
        cairo_restore(cr);
        cx_render_overlay(&sc, cr);
        if (cairo_status(cr) != CAIRO_STATUS_SUCCESS)
            rc = cx_diag_set(d, CX_EEXTERNAL, "cairo: %s", cairo_status_to_string(cairo_status(cr)));
        cairo_surface_destroy(sg);
    }
    img_clear(&sc);
    return rc;
}

int cx_render_image_write_png(const cx_result *r, const cx_render_opts *o, const cx_render_buf *b,
                              const char *path, const char *const *extra, cx_diag *d)
{
    const cx_run_record *run = &r->run;
    char level[32], F[32], slip[32], kkt[32], scale[32];
    snprintf(level, sizeof level, "%d", run->level);
    snprintf(F, sizeof F, "%.17g", run->F);
    snprintf(slip, sizeof slip, "%.17g", run->slip_bound);
    snprintf(kkt, sizeof kkt, "%.6e", run->kkt);
    char outcome[CX_DIAG_LEN + 160];   /* the outcome in solve/'s words */
    if (run->reason == CX_ITERATING && isinf(run->kkt))   /* an animation's first frame */
        snprintf(outcome, sizeof outcome, "start (iteration %d)", run->iterations);
    else
        cx_reason_format(run->reason, run->iterations, run->kkt, run->tol, run->message, outcome,
                         sizeof outcome);
    snprintf(scale, sizeof scale, "%.6g", b->fix.scale);
    char tol[32], iters[32], args[1024];
    snprintf(tol, sizeof tol, "%.6g", run->tol);
    char range[80];
    snprintf(range, sizeof range, "%.9g:%.9g%s%s", b->lo, b->hi, o->has_range ? " (set)" : "",
             o->log ? " (log)" : "");
    snprintf(iters, sizeof iters, "%d", run->iterations);
    cx_run_record_solve_args(run, args, sizeof args);
    cx_png_text text[32] = {
        {"Title", run->title},
        {"scene", run->scene},
        {"level", level},
        {"method", run->method},
        {"friction", cx_friction_name(run->friction)},
        {"F", F},
        {"slip bound", slip},
        {"parameters", run->params_text},
        {"kkt error", kkt},
        {"converged", run->converged ? "yes" : "no"},
        {"reason", cx_reason_id(run->reason)},
        {"tolerance", tol},
        {"iterations", iters},
        {"outcome", outcome},
        {"solve options", args},
        {"field", cx_field_name(o->field)},
        {"displacement scale", scale},
        {"colour range", range},
        {"colormap", cx_cmap_name(o->cmap)},
        {"camera", b->camera},
    };
    int nt = 20;
    for (int i = 0; extra && extra[i] && nt < 31; i += 2)
        text[nt++] = (cx_png_text){extra[i], extra[i + 1]};
    text[nt++] = (cx_png_text){"Software", "signorini " CX_VERSION};
    return cx_png_write_xrgb(path, b->rgb, b->w, b->h, b->stride, text, nt, d);
}

int cx_render_png(cx_result *r, const cx_render_opts *o, const char *path, cx_render_timing *t,
                  cx_diag *d)
{
    cx_render_buf b;
    cx_render_timing tm = {0};
    int rc = cx_render_image_draw(r, o, NULL, 1, &b, &tm, d);
    if (rc == CX_OK) {
        double t0 = cx_clock_now();
        rc = cx_render_image_write_png(r, o, &b, path, NULL, d);
        tm.png = cx_clock_now() - t0;
    }
    cx_render_buf_clear(&b);
    if (t)
        *t = tm;
    return rc;
}
