/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini render SCENE [solve options] --png FILE [...]: solve, then draw
 * (render/); also the --png/--vtu/--plot outputs of 'signorini solve'. */
#include "cli/cli.h"
#include "out/out.h"
#include "cx_config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if CX_HAVE_RENDER
#include "render/anim.h"
#include "render/render.h"
#include "render/vector.h"
#endif

static const char render_usage[] =
    "usage: signorini render SCENE [solve options] --png FILE [options]\n"
    "\n"
    "Solve SCENE (options as for 'signorini solve') and draw the solution:\n"
    "the image of a field, a line plot (--plot) or a VTU file (--vtu).\n";

/* --field: a name the renderer knows (whether it exists in the scene's
 * dimension is checked once the problem is built). */
static int render_check_field(const char *text, cx_diag *d)
{
#if CX_HAVE_RENDER
    if (cx_field_from_name(text) < 0)
        return cx_diag_set(d, CX_EINVAL, "--field '%s': unknown field", text);
#else
    (void)text;
    (void)d;
#endif
    return CX_OK;
}

static int render_check_size(const char *text, cx_diag *d)
{
    int w, h;
    char extra;
    if (sscanf(text, "%dx%d%c", &w, &h, &extra) != 2 || w < 64 || h < 64 || w > 16384 || h > 16384)
        return cx_diag_set(d, CX_EINVAL, "--size '%s': expected WxH, 64..16384 pixels each way", text);
    return CX_OK;
}

/* "A<sep>B": two finite numbers and nothing else. */
static int render_parse_pair(const char *text, char sep, double *a, double *b)
{
    char *end;
    *a = strtod(text, &end);
    if (end == text || *end != sep)
        return 0;
    const char *rest = end + 1;
    *b = strtod(rest, &end);
    return end != rest && *end == '\0' && isfinite(*a) && isfinite(*b);
}

/* --range MIN:MAX: finite numbers, MIN < MAX */
static int render_parse_range(const char *text, double *lo, double *hi)
{
    return render_parse_pair(text, ':', lo, hi) && *lo < *hi;
}

static int render_check_range(const char *text, cx_diag *d)
{
    double lo, hi;
    if (!render_parse_range(text, &lo, &hi))
        return cx_diag_set(d, CX_EINVAL, "--range '%s': expected MIN:MAX, finite numbers, MIN < MAX", text);
    return CX_OK;
}

/* --camera AZ,EL: degrees, |EL| <= 90 */
static int render_parse_camera(const char *text, double *az, double *el)
{
    return render_parse_pair(text, ',', az, el) && fabs(*el) <= 90;
}

static int render_check_camera(const char *text, cx_diag *d)
{
    double az, el;
    if (!render_parse_camera(text, &az, &el))
        return cx_diag_set(d, CX_EINVAL, "--camera '%s': expected AZ,EL in degrees (e.g. 35,-35), |EL| <= 90",
                           text);
    return CX_OK;
}

const cx_opt cli_render_opts[] = {
    {"png", 0, CX_OPT_STRING, 0, 0, 0, NULL, "FILE",
     "also draw the solution (written to a temporary file,\n"
     "then renamed; '-' for standard output)", offsetof(cli_render_args, png), NULL},
    {"field", 0, CX_OPT_STRING, 0, 0, 0, NULL, "F",
     "von-mises (default), sxx, syy, sxy, szz, syz, sxz (3D),\n"
     "u, ux, uy, uz, pressure, status", offsetof(cli_render_args, field_name), render_check_field},
    {"scale", 0, CX_OPT_REAL, 0, INFINITY, CX_OPT_MIN_OPEN | CX_OPT_MAX_OPEN, NULL, "S",
     "displacement magnification (default: auto, the largest\n"
     "displacement drawn as 7 % of the body size)", offsetof(cli_render_args, scale), NULL},
    {"font-scale", 0, CX_OPT_REAL, 0.25, 4, 0, NULL, "K",
     "text size factor (default 1: tick labels 2.2 % of the image\n"
     "width, legible when printed a column wide)", offsetof(cli_render_args, font_scale), NULL},
    {"cmap", 0, CX_OPT_CHOICE, 0, 0, 0, "auto|viridis|cividis|magma|coolwarm|gray",
     "auto|viridis|cividis|magma|coolwarm|gray",
     "colormap (default auto: viridis for magnitudes, coolwarm\n"
     "for signed fields)", offsetof(cli_render_args, cmap), NULL},
    {"range", 0, CX_OPT_STRING, 0, 0, 0, NULL, "MIN:MAX",
     "fixed colour range, so that several figures share one\n"
     "(default: the field's)", offsetof(cli_render_args, range), render_check_range},
    {"title", 0, CX_OPT_STRING, 0, 0, 0, NULL, "TEXT", "the image's title (default: the scene's)",
     offsetof(cli_render_args, title), NULL},
    {"no-title", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "no title lines (for a figure with a caption)",
     offsetof(cli_render_args, no_title), NULL},
    {"size", 0, CX_OPT_STRING, 0, 0, 0, NULL, "WxH", "image size in pixels (default 1200x900)",
     offsetof(cli_render_args, size), render_check_size},
    {"view", 0, CX_OPT_CHOICE, 0, 0, 0, "body|contact|below|above", "body|contact|below|above",
     "3D: the whole body (default: from below when the contact\n"
     "faces look down, as on halfball, else from above), the\n"
     "contact faces alone seen from the obstacle (with axes), or\n"
     "the body from below or above", offsetof(cli_render_args, view), NULL},
    {"camera", 0, CX_OPT_STRING, 0, 0, 0, NULL, "AZ,EL",
     "3D: look from azimuth AZ (degrees from -y towards +x) and\n"
     "elevation EL (above the xy plane; negative: below); the\n"
     "default is 35,30 or 35,-35", offsetof(cli_render_args, camera), render_check_camera},
    {"crop", 0, CX_OPT_CHOICE, 0, 0, 0, "contact", "contact",
     "zoom to the contact zone (the points in contact, with a\n"
     "margin of half their extent)", offsetof(cli_render_args, crop), NULL},
    {"mirror", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL,
     "draw the whole body of a half or quarter model across the\n"
     "scene's symmetry planes (key 'symmetry' of [scene])", offsetof(cli_render_args, mirror), NULL},
    {"edges", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "draw the mesh edges", offsetof(cli_render_args, edges),
     NULL},
    {"vtu", 0, CX_OPT_STRING, 0, 0, 0, NULL, "FILE",
     "also write a VTK XML UnstructuredGrid for ParaView ('-' for\n"
     "standard output: the summary goes to stderr; works\n"
     "without the renderer)", offsetof(cli_render_args, vtu), NULL},
    {"vtu-ascii", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "ASCII instead of base64 binary data in the VTU",
     offsetof(cli_render_args, vtu_ascii), NULL},
    {"plot", 0, CX_OPT_CHOICE, 0, 0, 0, "pressure|convergence|work", "pressure|convergence|work",
     "a line plot instead of the image: the contact pressure along\n"
     "the boundary (with Hertz's where the scene has it; 3D: a\n"
     "colour map of the contact face seen from the obstacle); the kkt\n"
     "error per iteration of the method run, with its --set (each\n"
     "--method given; with --method auto every method of the\n"
     "scene for the law) (semilog); or work-precision: the kkt\n"
     "error against the time spent (log-log), with the baseline\n"
     "(one factorisation + solve of K) marked", offsetof(cli_render_args, plot), NULL},
    {"timing", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "print the time of each rendering stage",
     offsetof(cli_render_args, timing), NULL},
    {"svg", 0, CX_OPT_STRING, 0, 0, 0, NULL, "FILE",
     "also the figure as SVG: plots as vectors with <text>\n"
     "labels; an image as its rendered body under vector\n"
     "text, colour bar and markers", offsetof(cli_render_args, svg), NULL},
    {"pdf", 0, CX_OPT_STRING, 0, 0, 0, NULL, "FILE", "also the figure as PDF (as --svg, searchable text)",
     offsetof(cli_render_args, pdf), NULL},
    {"log", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL,
     "logarithmic colour scale (von-mises, u, pressure; with\n"
     "--range MIN:MAX, 0 < MIN, so that figures share one)", offsetof(cli_render_args, log), NULL},
    {"frames", 0, CX_OPT_STRING, 0, 0, 0, NULL, "DIR",
     "an animation: run the method again from the start and\n"
     "draw every iterate, DIR/frame_0000.png ... (iterations +\n"
     "1 frames; the last iterate's camera, scale and colour\n"
     "range in every frame)", offsetof(cli_render_args, frames), NULL},
    {"gif", 0, CX_OPT_STRING, 0, 0, 0, NULL, "FILE",
     "the same animation as a looping GIF (0.5 s a frame, the\n"
     "last 3 s)", offsetof(cli_render_args, gif), NULL},
    {"every", 0, CX_OPT_INT, 1, 1000000, 0, NULL, "K",
     "--frames, --gif: every K-th iterate only, and the last\n"
     "(default 1: all; for runs of hundreds of iterations)", offsetof(cli_render_args, every), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

void cli_render_args_init(cli_render_args *r)
{
    memset(r, 0, sizeof *r);
    r->plot = -1;
    r->crop = -1;
    r->font_scale = 1;
    r->every = 1;
    r->w = 1200;
    r->h = 900;
}

void cli_render_finish(cli_render_args *r)
{
    /* checked by render_check_size while parsing */
    if (r->size && sscanf(r->size, "%dx%d", &r->w, &r->h) != 2) {
        r->w = 1200;
        r->h = 900;
    }
}

int cli_param_set_for(cx_param_values *pv, const char *pair, int nmethods, const char *owner, cx_diag *d)
{
    char key[64];
    size_t n = strcspn(pair, "=");
    snprintf(key, sizeof key, "%.*s", (int)(n < sizeof key ? n : sizeof key - 1), pair);
    if (nmethods > 1 && cx_param_find(pv, key) < 0)
        return CX_OK;
    return cx_param_set_pair(pv, pair, owner, d);
}

int cli_sets_check(const cx_opt_list *methods, const cx_opt_list *sets, cx_diag *d)
{
    for (int i = 0; i < sets->n; i++) {
        char key[64];
        size_t n = strcspn(sets->v[i], "=");
        snprintf(key, sizeof key, "%.*s", (int)(n < sizeof key ? n : sizeof key - 1), sets->v[i]);
        int had = 0;
        for (int k = 0; k < methods->n && !had; k++) {
            const cx_method *m = cx_method_find(methods->v[k]);
            cx_param_values pv;
            if (m) {
                cx_param_default(&pv, m->params);
                had = cx_param_find(&pv, key) >= 0;
            }
        }
        if (!had)
            return cx_diag_set(d, CX_EINVAL, "--set '%s': none of the methods named has '%s'", sets->v[i], key);
    }
    return CX_OK;
}

#if CX_HAVE_RENDER

/* A plot to each file asked for: PNG, SVG, PDF. */
static int render_plot_out(const cli_render_args *r, const cx_plot *pl, cx_diag *d)
{
    if (r->png)
        CX_TRY(cx_plot_write_png(pl, r->png, r->w, r->h, d));
    if (r->svg)
        CX_TRY(cx_plot_write_vector(pl, r->svg, r->w, r->h, CX_VECTOR_SVG, d));
    if (r->pdf)
        CX_TRY(cx_plot_write_vector(pl, r->pdf, r->w, r->h, CX_VECTOR_PDF, d));
    return CX_OK;
}

/* The contact pressure lN / weight along the boundary, with Hertz's. */
static int render_plot_pressure(const cli_render_args *r, const cx_scene *sc, const cx_result *res,
                                cx_diag *d)
{
    const cx_contact_set *cs = &res->contact;
    int m = cs->m, dim = res->dim;
    enum { NH = 400 };
    double *x = CX_NEW(double, 3 * (size_t)m + 2 * NH), *y = x + m, *yh = y + m;
    double *hx = yh + m, *hy = hx + NH;
    if (!x)
        return cx_diag_set(d, CX_ENOMEM, "plot: out of memory");
    /* 2D: every point against its x (3D draws the map of the contact
     * face instead: render_png) */
    int n = 0;
    for (int i = 0; i < m; i++) {
        x[n] = cs->x[dim * i];
        y[n] = cs->weight[i] > 0 ? res->lN[i] / cs->weight[i] : 0;
        yh[n] = cx_scene_hertz_pressure(sc, x[n]);
        n++;
    }
    /* in order along x (insertion sort) */
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && x[j - 1] > x[j]; j--) {
            double t = x[j]; x[j] = x[j - 1]; x[j - 1] = t;
            t = y[j]; y[j] = y[j - 1]; y[j - 1] = t;
        }
    char title[200], what[160];
    snprintf(title, sizeof title, "%s level %d: contact pressure (%s, kkt %.1e)", sc->id, res->run.level,
             res->run.method, res->run.kkt);
    snprintf(what, sizeof what, "x, position along the contact boundary");
    m = n;
    cx_plot pl;
    char xlab[200], ylab[128];
    cx_quantity_label(&res->run, what, 0, xlab, sizeof xlab);
    cx_field_axis_label(&res->run, CX_FIELD_PRESSURE, ylab, sizeof ylab);
    cx_plot_init(&pl, title, xlab, ylab);
    pl.font_scale = r->font_scale;
    cx_plot_add_series(&pl, "computed (nodal force / lumped length)", m, x, y, CX_PLOT_MARKERS);
    if (sc->has_hertz && m > 0) {
        /* the analytical curve on a fine grid, so that it is smooth */
        double x1 = x[m - 1] > x[0] ? x[m - 1] : x[0];
        for (int i = 0; i < NH; i++) {
            hx[i] = x1 * i / (NH - 1);
            hy[i] = cx_scene_hertz_pressure(sc, hx[i]);
        }
        cx_plot_add_series(&pl, "Hertz", NH, hx, hy, CX_PLOT_LINE | CX_PLOT_DASHED);
        cx_plot_add_vline(&pl, cx_scene_hertz_halfwidth(sc), "b (Hertz half-width)");
    }
    cx_plot_add_text(&pl, "scene", sc->id);
    cx_plot_add_text(&pl, "method", res->run.method);
    int rc = render_plot_out(r, &pl, d);
    cx_free(x);
    return rc;
}

typedef struct conv_rec {
    int n, cap;
    double *it, *kkt, *time;
} conv_rec;

static int render_conv_observe(void *ctx, const cx_session *s, const cx_iterate *it)
{
    (void)s;
    conv_rec *c = ctx;
    if (c->n == c->cap) {
        int cap = c->cap ? 2 * c->cap : 64;
        double *a = cx_realloc(c->it, sizeof(double) * (size_t)cap);
        if (!a)
            return 1;
        c->it = a;
        double *b = cx_realloc(c->kkt, sizeof(double) * (size_t)cap);
        if (!b)
            return 1;
        c->kkt = b;
        double *t = cx_realloc(c->time, sizeof(double) * (size_t)cap);
        if (!t)
            return 1;
        c->time = t;
        c->cap = cap;
    }
    c->time[c->n] = it->time;
    c->it[c->n] = it->iter;
    c->kkt[c->n++] = it->kkt;
    return 0;
}

/* The legend entry of a run: the method and the parameters that differ
 * from its defaults ("ssn-tresca rho=0.001"), so that two runs of one
 * method are told apart. */
static void render_run_label(const cx_method *m, const cx_param_values *pv, char *buf, size_t len)
{
    snprintf(buf, len, "%s", m->id);
    if (!pv)
        return;
    cx_param_values def;
    cx_param_default(&def, m->params);
    for (int i = 0; i < pv->n; i++) {
        int same = def.num[i] == pv->num[i] || (isnan(def.num[i]) && isnan(pv->num[i]));
        if (same && strcmp(def.str[i], pv->str[i]) == 0)
            continue;
        char v[64];
        cx_param_format(pv, i, v, sizeof v);
        size_t n = strlen(buf);
        snprintf(buf + n, len - n, " %s=%s", m->params[i].key, v);
    }
}

/* The kkt error per iteration of the run asked for (--method and --set:
 * the session's method and parameters) or, for --method auto, of every
 * method of the scene that supports the problem and the law, on one
 * semilog plot (the session keeps the operators); or (work) the kkt error
 * against the time spent, log-log, with the baseline time as a vertical
 * line. */
static int render_plot_convergence(const cli_render_args *r, const cx_scene *sc, cx_session *s,
                                   const cx_result *res, int work, cx_diag *d)
{
    int level = res->run.level;
    conv_rec rec[CX_SCENE_MAX_METHODS + 1];
    memset(rec, 0, sizeof rec);
    /* the runs: the session's own (a named method with its --set), or the
     * scene's list with the auto choice among them */
    const cx_method *runs[CX_SCENE_MAX_METHODS + 1];
    cx_param_values pvs[CX_SCENE_MAX_METHODS + 1];
    int nruns = 0;
    const cx_method *own = cx_session_method(s);
    const cx_problem *p0 = cx_session_problem(s);
    cx_friction law = cx_session_friction(s)->law;
    int named = r->methods ? r->methods->n : 0;
    if (own) {
        runs[nruns] = own;
        pvs[nruns++] = *cx_session_params(s);
    }
    /* the other --method, each with the --set keys it has */
    for (int k = 1; k < named && nruns < CX_SCENE_MAX_METHODS + 1; k++) {
        const cx_method *m = cx_method_find(r->methods->v[k]);
        char owner[64];
        snprintf(owner, sizeof owner, "method '%s'", m->id);
        CX_TRY(cx_method_check(m, p0, law, d));
        cx_param_default(&pvs[nruns], m->params);
        for (int i = 0; r->sets && i < r->sets->n; i++)
            CX_TRY(cli_param_set_for(&pvs[nruns], r->sets->v[i], named, owner, d));
        runs[nruns++] = m;
    }
    if (res->run.method_auto)
        for (int k = 0; k < sc->nmethods && nruns < CX_SCENE_MAX_METHODS + 1; k++) {
            const cx_method *m = cx_method_find(sc->methods[k]);
            if (!m || m == own || cx_method_check(m, p0, law, NULL) != CX_OK)
                continue;
            runs[nruns] = m;
            cx_param_default(&pvs[nruns++], m->params);
        }
    char title[200];
    snprintf(title, sizeof title, "%s level %d, friction %s: %s", sc->id, level, cx_friction_name(law),
             work ? "work-precision" : "convergence");
    cx_plot pl;
    cx_plot_init(&pl, title, work ? "time [s] (setup included)" : "iteration", "kkt error");
    pl.logy = 1;
    pl.logx = work;
    pl.integer_x = !work;
    pl.font_scale = r->font_scale;
    cx_options opt = *cx_session_options(s);
    /* the baseline before the runs, as solve --baseline and bench time it */
    double t_base = 0;
    int rc = work ? cx_problem_baseline(cx_session_problem(s), &t_base, d) : CX_OK;
    char methods[256] = "";
    for (int k = 0; k < nruns && rc == CX_OK; k++) {
        const cx_method *m = runs[k];
        /* work-precision: a fresh session per method, so that each pays
         * for its own factorisations (the session's cache would hide them) */
        cx_session *run = s, *fresh = NULL;
        if (work) {
            cx_problem *q = NULL;
            if ((rc = cx_scene_build(sc, level, &q, NULL, d)) != CX_OK)
                break;
            if ((rc = cx_session_create(&fresh, &q, d)) != CX_OK ||
                (rc = cx_session_set_friction(fresh, cx_session_friction(s), d)) != CX_OK) {
                cx_problem_destroy(&q);
                cx_session_destroy(&fresh);
                break;
            }
            run = fresh;
        }
        char label[CX_PLOT_LABELLEN];
        render_run_label(m, &pvs[k], label, sizeof label);
        if ((rc = cx_session_set_method(run, m, &pvs[k], &opt, d)) == CX_OK &&
            (rc = cx_solver_solve(run, render_conv_observe, &rec[k], d)) == CX_OK) {
            cx_plot_add_series(&pl, label, rec[k].n, work ? rec[k].time : rec[k].it, rec[k].kkt,
                               CX_PLOT_LINE | CX_PLOT_MARKERS);
            size_t n = strlen(methods);
            snprintf(methods + n, sizeof methods - n, "%s%s", n ? "; " : "", label);
        }
        cx_session_destroy(&fresh);
    }
    cx_plot_add_hline(&pl, opt.tol, "tolerance");
    if (work && rc == CX_OK)
        cx_plot_add_vline(&pl, t_base, "baseline: factorise + solve K");
    cx_plot_add_text(&pl, "scene", sc->id);
    cx_plot_add_text(&pl, "friction", cx_friction_name(law));
    cx_plot_add_text(&pl, "methods", methods);
    if (rc == CX_OK)
        rc = render_plot_out(r, &pl, d);
    for (int k = 0; k < CX_SCENE_MAX_METHODS + 1; k++) {
        cx_free(rec[k].it);
        cx_free(rec[k].kkt);
        cx_free(rec[k].time);
    }
    return rc;
}

/* The image options from the command line; map3d: 3D --plot pressure,
 * the map of the pressure on the contact face seen from the obstacle. */
static int render_image_opts(const cli_render_args *r, const cx_scene *sc, int map3d, cx_render_opts *o,
                             cx_diag *d)
{
    cx_render_opts_default(o);
    o->width = r->w;
    o->height = r->h;
    o->scale = r->scale;
    o->font_scale = r->font_scale;
    o->cmap = r->cmap - 1;
    o->no_title = r->no_title;
    o->title = r->title;
    o->log = r->log;
    if (r->range && render_parse_range(r->range, &o->range_lo, &o->range_hi))
        o->has_range = 1;
    o->edges = r->edges;
    o->view = r->view;
    /* 3D camera and framing */
    o->has_camera = r->camera && render_parse_camera(r->camera, &o->cam_az, &o->cam_el);
    o->crop_contact = r->crop == 0;
    o->mirror = r->mirror;
    o->scene = sc;
    if (map3d) {
        o->field = CX_FIELD_PRESSURE;
        o->view = CX_VIEW_CONTACT;
    }
    if (!map3d && r->field_name && (o->field = cx_field_from_name(r->field_name)) < 0)
        return cx_diag_set(d, CX_EINVAL, "--field '%s': unknown field (see 'signorini render --help')",
                           r->field_name);
    return CX_OK;
}

static int render_png(const cli_render_args *r, const cx_scene *sc, cx_session *s, cx_result *res,
                      cx_diag *d)
{
    /* 3D --plot pressure: the map of the contact face (the image of the
     * pressure seen from the obstacle, with axes) */
    int map3d = r->plot == 0 && res->dim == 3;
    if (r->plot == 0 && !map3d)
        return render_plot_pressure(r, sc, res, d);
    if (r->plot >= 1)
        return render_plot_convergence(r, sc, s, res, r->plot == 2, d);
    cx_render_opts o;
    CX_TRY(render_image_opts(r, sc, map3d, &o, d));
    cx_render_timing t;
    if (r->png) {
        CX_TRY(cx_render_png(res, &o, r->png, &t, d));
        if (r->timing)
            fprintf(stderr, "render %s %dx%d: context %.3f s, fields+geometry %.3f s, draw %.3f s, "
                    "text %.3f s, png %.3f s\n", r->png, o.width, o.height, t.context, t.fields,
                    t.draw, t.text, t.png);
    }
    double t0 = cx_clock_now();
    if (r->svg)
        CX_TRY(cx_render_vector(res, &o, r->svg, CX_VECTOR_SVG, d));
    if (r->pdf)
        CX_TRY(cx_render_vector(res, &o, r->pdf, CX_VECTOR_PDF, d));
    if (r->timing && (r->svg || r->pdf))
        fprintf(stderr, "render svg/pdf: %.3f s\n", cx_clock_now() - t0);
    return CX_OK;
}

typedef struct anim_watch {
    cx_anim *a;
    int every;           /* draw iterates k with k % every == 0, and the last */
    cx_session *s;       /* the session stepped (to complete its iterate) */
    const cx_scene *sc;
    int level;
    cx_diag *d;
    int failed;
} anim_watch;

/* One frame: the session's iterate, whole. */
static int render_anim_frame(anim_watch *w)
{
    cx_result *fr = NULL;
    int rc = cx_session_complete_iterate(w->s, w->d);
    if (rc == CX_OK)
        rc = cx_result_from_session(&fr, w->s, w->sc, w->level, w->d);
    if (rc == CX_OK)
        rc = cx_anim_add(w->a, fr, w->d);
    cx_result_destroy(&fr);
    w->failed = rc != CX_OK;
    return rc;
}

static int render_anim_observe(void *ctx, const cx_session *s, const cx_iterate *it)
{
    (void)s;
    anim_watch *w = ctx;
    if (it->iter % w->every != 0 && it->reason == CX_ITERATING)
        return 0;
    return render_anim_frame(w) != CX_OK;
}

/* --frames and --gif: the run again from its start (the method, its
 * parameters and options, on the session's operators), a frame per
 * iterate, with res (the first run's last iterate) fixing the camera,
 * scale and colour range. */
static int render_animate(const cli_render_args *r, const cx_scene *sc, cx_session *s, cx_result *res,
                          int quiet, cx_diag *d)
{
    cx_render_opts o;
    CX_TRY(render_image_opts(r, sc, 0, &o, d));
    cx_anim *a = NULL;
    int rc = cx_anim_create(&a, res, &o, r->frames, r->gif, d);
    if (rc == CX_OK) {
        const cx_method *m = cx_session_method(s);
        cx_param_values pv = *cx_session_params(s);
        cx_options opt = *cx_session_options(s);
        rc = cx_session_set_method(s, m, &pv, &opt, d);
    }
    anim_watch w = {a, r->every > 0 ? r->every : 1, s, sc, res->run.level, d, 0};
    if (rc == CX_OK)
        rc = render_anim_frame(&w);
    if (rc == CX_OK) {
        rc = cx_solver_solve(s, render_anim_observe, &w, d);
        if (rc == CX_OK && w.failed)
            rc = CX_EIO;   /* the frame's error is in d */
    }
    if (rc == CX_OK)
        rc = cx_anim_finish(a, d);
    if (rc == CX_OK && !quiet) {
        double lo, hi;
        cx_anim_range(a, &lo, &hi);
        int n = cx_anim_count(a);
        fprintf(stderr, "animation: %d frames (iterations 0..%d%s), colour range %.4g:%.4g%s, %.2f s%s%s%s%s\n", n,
                cx_session_iterate(s)->iter, r->every > 1 ? ", every few" : "", lo, hi, o.log ? " (log)" : "", cx_anim_seconds(a), r->frames ? "; " : "",
                r->frames ? r->frames : "", r->gif ? "; " : "", r->gif ? r->gif : "");
    }
    cx_anim_destroy(&a);
    return rc;
}

int cli_render_check(const cli_render_args *r, int dim, cx_diag *d)
{
    if (r->field_name) {
        int f = cx_field_from_name(r->field_name);
        if (f < 0)
            return cx_diag_set(d, CX_EINVAL, "--field '%s': unknown field (see 'signorini render --help')",
                               r->field_name);
        CX_TRY(cx_field_check(f, dim, d));
    }
    if (r->view != CX_VIEW_BODY && dim != 3)
        return cx_diag_set(d, CX_EINVAL, "--view %s: only in 3D",
                           r->view == CX_VIEW_CONTACT ? "contact" : r->view == CX_VIEW_BELOW ? "below" : "above");
    if (r->camera && dim != 3)
        return cx_diag_set(d, CX_EINVAL, "--camera: only in 3D");
    return CX_OK;
}

#else

static int render_png(const cli_render_args *r, const cx_scene *sc, cx_session *s, cx_result *res,
                      cx_diag *d)
{
    (void)r; (void)sc; (void)s; (void)res;
    return cx_diag_set(d, CX_EUNSUPPORTED, "--png: built without rendering (meson -Drender=disabled)");
}

/* VTU files need no GL: only images are refused in this build. */
int cli_render_check(const cli_render_args *r, int dim, cx_diag *d)
{
    (void)dim;
    if (cli_render_wanted(r))
        return cx_diag_set(d, CX_EUNSUPPORTED, "%s: built without rendering (meson -Drender=disabled)",
                           r->png ? "--png" : r->svg ? "--svg" : r->pdf ? "--pdf" : r->gif ? "--gif" : "--frames");
    return CX_OK;
}

#endif

int cli_render_wanted(const cli_render_args *r)
{
    return r->png || r->svg || r->pdf || r->gif || r->frames;
}

int cli_render_stdout_users(const cli_render_args *r)
{
    return cx_outfile_is_stdout(r->png) + cx_outfile_is_stdout(r->vtu) + cx_outfile_is_stdout(r->svg) +
           cx_outfile_is_stdout(r->pdf) + cx_outfile_is_stdout(r->gif);
}

int cli_render_outputs(const cli_render_args *r, const cx_scene *sc, cx_session *s, cx_result *res,
                       int quiet, cx_diag *d)
{
    if (r->vtu) {
        CX_TRY(cx_vtu_write(res, r->vtu, r->vtu_ascii, d));
        if (!quiet && !cx_outfile_is_stdout(r->vtu))
            fprintf(stderr, "wrote %s\n", r->vtu);
    }
    if (r->png || r->svg || r->pdf)
        CX_TRY(render_png(r, sc, s, res, d));
#if CX_HAVE_RENDER
    if (r->frames || r->gif)
        CX_TRY(render_animate(r, sc, s, res, quiet, d));
#endif
    return CX_OK;
}

int cli_render(int argc, char **argv)
{
    return cli_solve_as("render", render_usage, argc, argv);
}
