/* An image of a solved problem: fields, geometry and camera, the GL pass
 * (composited over the 2D obstacle), the cairo overlays, the PNG. */
#include "render/render_impl.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cx_config.h"
#include "render/pngfile.h"

void cx_render_state_init(cx_render_state *st, const cx_scene *sc, const cx_session *s, int level,
                          char *params, size_t len)
{
    const cx_iterate *it = cx_session_iterate(s);
    const cx_param_values *pv = cx_session_params(s);
    memset(st, 0, sizeof *st);
    st->p = cx_session_problem(s);
    st->u = it->u;
    st->lN = it->lN;
    st->lT = it->lT;
    st->status = it->status;
    st->obstacle = &sc->obstacle;
    st->scene = sc->id;
    st->title = sc->title;
    st->level = level;
    st->method = cx_session_method(s) ? cx_session_method(s)->id : "";
    st->kkt = it->kkt;
    st->reason = it->reason;
    st->iter = it->iter;
    st->tol = cx_session_options(s)->tol;
    st->reason_msg = cx_session_reason_msg(s);
    size_t n = 0;
    if (len > 0)
        params[0] = '\0';
    for (int k = 0; pv && k < pv->n && n + 2 < len; k++) {
        char v[64];
        cx_param_format(pv, k, v, sizeof v);
        int w = snprintf(params + n, len - n, "%s%s=%s", k ? " " : "", pv->table[k].key, v);
        if (w < 0 || (size_t)w >= len - n)
            break;
        n += (size_t)w;
    }
    st->params = params;
}

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

double cx_render_auto_scale(const cx_problem *p, const double *uall)
{
    double umax = img_umax(p->mesh, uall);
    return umax > 0 ? 0.07 * img_body_size(p->mesh) / umax : 1.0;
}

static void img_clear(cx_render_scene *sc)
{
    cx_free(sc->uall);
    cx_free(sc->x0);
    cx_free(sc->xd);
    cx_free(sc->val);
    cx_free(sc->bedges);
    cx_render_array_clear(&sc->tris);
    cx_render_array_clear(&sc->overlay);
    cx_render_array_clear(&sc->lines);
    cx_render_array_clear(&sc->obst);
}

/* The colour range: magnitudes [0, max], signed fields [-M, M]; over the
 * contact nodes for the pressure and the contact view. */
static void img_range(cx_render_scene *sc)
{
    const cx_mesh *m = sc->p->mesh;
    const cx_contact_set *cs = &sc->p->contact;
    int on_contact = sc->o->field == CX_FIELD_PRESSURE || sc->o->view == CX_VIEW_CONTACT;
    double lo = INFINITY, hi = -INFINITY;
    int n = on_contact ? cs->m : m->nnodes;
    for (int i = 0; i < n; i++) {
        double v = sc->val[on_contact ? cs->node[i] : i];
        lo = fmin(lo, v);
        hi = fmax(hi, v);
    }
    if (!(lo <= hi))
        lo = hi = 0;
    if (cx_field_is_signed(sc->o->field)) {
        double M = fmax(fabs(lo), fabs(hi));
        sc->lo = -M;
        sc->hi = M;
    } else {
        sc->lo = fmin(lo, 0.0);
        sc->hi = hi;
    }
    if (!(sc->hi > sc->lo)) {   /* a constant field: a unit range around it */
        double c = sc->lo;
        sc->lo = cx_field_is_signed(sc->o->field) || c != 0 ? c - 1 : 0;
        sc->hi = sc->lo + (c != 0 || cx_field_is_signed(sc->o->field) ? 2 : 1);
    }
}

static int img_prepare(cx_render_scene *sc, const cx_render_state *st, const cx_render_opts *o,
                       double *t_fields, cx_diag *d)
{
    double t0 = cx_clock_now();
    memset(sc, 0, sizeof *sc);
    sc->st = st;
    sc->o = o;
    sc->p = st->p;
    sc->w = o->width;
    sc->h = o->height;
    const cx_problem *p = sc->p;
    const cx_mesh *m = p->mesh;
    int dim = m->dim, nn = m->nnodes, f = sc->o->field;
    sc->dim = dim;
    sc->uall = cx_malloc(sizeof(double) * (size_t)dim * nn);
    sc->x0 = CX_NEW(double, 3 * (size_t)nn);
    sc->xd = CX_NEW(double, 3 * (size_t)nn);
    sc->val = cx_malloc(sizeof(double) * (size_t)nn);
    if (!sc->uall || !sc->x0 || !sc->xd || !sc->val)
        return cx_diag_set(d, CX_ENOMEM, "render: out of memory");
    cx_fem_expand(&p->map, sc->st->u, sc->uall);
    if (cx_field_nodal(p, sc->uall, sc->st->lN, sc->st->status, f, sc->val) != CX_OK)
        return cx_diag_set(d, CX_ENUMERIC, "render: cannot compute the field %s", cx_field_name(f));
    for (int i = 0; i < nn && f != CX_FIELD_STATUS; i++)
        if (!isfinite(sc->val[i]))
            return cx_diag_set(d, CX_ENUMERIC, "render: the field %s is not finite at node %d",
                               cx_field_name(f), i);
    sc->umax = img_umax(m, sc->uall);
    sc->scale = sc->o->scale > 0 ? sc->o->scale : cx_render_auto_scale(p, sc->uall);
    for (int i = 0; i < nn; i++)
        for (int k = 0; k < dim; k++) {
            sc->x0[3 * i + k] = m->x[dim * i + k];
            sc->xd[3 * i + k] = m->x[dim * i + k] + sc->scale * sc->uall[dim * i + k];
        }
    if (f == CX_FIELD_STATUS) {
        sc->lo = 0;
        sc->hi = 1;
    } else {
        img_range(sc);
    }
    /* the body carries the colours, except for contact-only fields seen
     * on the whole body */
    sc->colored = f != CX_FIELD_STATUS &&
                  (f != CX_FIELD_PRESSURE || (dim == 3 && sc->o->view == CX_VIEW_CONTACT));
    if (cx_render_geometry(sc) != CX_OK)
        return cx_diag_set(d, CX_ENOMEM, "render: out of memory");
    cx_render_camera(sc);
    *t_fields = cx_clock_now() - t0;
    return CX_OK;
}

static int img_check(const cx_render_state *st, const cx_render_opts *o, cx_diag *d)
{
    if (o->width < 64 || o->height < 64 || o->width > 16384 || o->height > 16384)
        return cx_diag_set(d, CX_EINVAL, "--size %dx%d: expected 64..16384 pixels each way",
                           o->width, o->height);
    CX_TRY(cx_field_check(o->field, st->p->dim, d));
    if (o->view == CX_VIEW_CONTACT && st->p->dim != 3)
        return cx_diag_set(d, CX_EINVAL, "--view contact: only in 3D");
    if (o->msaa < 0 || o->msaa > 4)
        return cx_diag_set(d, CX_EINVAL, "msaa %d: expected 0..4 samples", o->msaa);
    return CX_OK;
}

int cx_render_project(const cx_render_state *st, const cx_render_opts *o, const double *x,
                      double px[2], cx_diag *d)
{
    CX_TRY(img_check(st, o, d));
    cx_render_scene sc;
    double tf;
    int rc = img_prepare(&sc, st, o, &tf, d);
    if (rc == CX_OK) {
        double x3[3] = {0, 0, 0};
        for (int k = 0; k < st->p->dim; k++)
            x3[k] = x[k];
        cx_render_scene_project(&sc, x3, px);
    }
    img_clear(&sc);
    return rc;
}

int cx_render_png(const cx_render_state *st, const cx_render_opts *o, const char *path,
                  cx_render_timing *t, cx_diag *d)
{
    cx_render_timing tm = {0};
    CX_TRY(img_check(st, o, d));
    cx_render_scene sc;
    int rc = img_prepare(&sc, st, o, &tm.fields, d);
    int stride = cairo_format_stride_for_width(CAIRO_FORMAT_ARGB32, sc.w);
    unsigned char *gl = NULL, *out = NULL;
    if (rc == CX_OK) {
        gl = cx_calloc((size_t)stride, (size_t)sc.h);
        out = cx_calloc((size_t)stride, (size_t)sc.h);
        if (!gl || !out)
            rc = cx_diag_set(d, CX_ENOMEM, "render: out of memory");
    }
    if (rc == CX_OK) {
        double t0 = cx_clock_now();
        rc = cx_render_gl_draw(&sc, gl, stride, &tm.context, &tm.draw_calls, d);
        tm.draw = cx_clock_now() - t0 - tm.context;
    }
    if (rc == CX_OK) {
        double t0 = cx_clock_now();
        cairo_surface_t *so = cairo_image_surface_create_for_data(out, CAIRO_FORMAT_RGB24, sc.w, sc.h, stride);
        cairo_surface_t *sg = cairo_image_surface_create_for_data(gl, CAIRO_FORMAT_ARGB32, sc.w, sc.h, stride);
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
        double t0 = cx_clock_now();
        const cx_problem *p = st->p;
        char level[32], F[32], slip[32], kkt[32], scale[32];
        snprintf(level, sizeof level, "%d", st->level);
        snprintf(F, sizeof F, "%.17g", p->F);
        snprintf(slip, sizeof slip, "%.17g", p->slip_bound);
        snprintf(kkt, sizeof kkt, "%.6e", st->kkt);
        char outcome[CX_DIAG_LEN + 160] = "";   /* the outcome in solve/'s words */
        if (st->reason_msg)
            cx_reason_format(st->reason, st->iter, st->kkt, st->tol, st->reason_msg, outcome, sizeof outcome);
        snprintf(scale, sizeof scale, "%.6g", sc.scale);
        cx_png_text text[] = {
            {"Title", st->title ? st->title : ""},
            {"scene", st->scene ? st->scene : ""},
            {"level", level},
            {"method", st->method ? st->method : ""},
            {"friction", cx_friction_name(p->friction)},
            {"F", F},
            {"slip bound", slip},
            {"parameters", st->params ? st->params : ""},
            {"kkt error", kkt},
            {"outcome", outcome},
            {"field", cx_field_name(o->field)},
            {"displacement scale", scale},
            {"Software", "signorini " CX_VERSION},
        };
        rc = cx_png_write_xrgb(path, out, sc.w, sc.h, stride, text,
                               (int)(sizeof text / sizeof text[0]), d);
        tm.png = cx_clock_now() - t0;
    }
    cx_free(gl);
    cx_free(out);
    img_clear(&sc);
    if (t)
        *t = tm;
    return rc;
}
