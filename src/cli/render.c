/* signorini render SCENE [solve options] --png FILE [...]: solve, then draw
 * (render/); also the --png/--vtu/--plot outputs of 'signorini solve'. */
#include "cli/cli.h"
#include "out/out.h"
#include "cx_config.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#if CX_HAVE_RENDER
#include "render/render.h"
#endif

static const char render_usage[] =
    "usage: signorini render SCENE [solve options] --png FILE [options]\n"
    "\n"
    "Solve SCENE (options as for 'signorini solve') and draw the solution.\n"
    "\n"
    "  --png FILE           the image (written to a temporary file, then renamed;\n"
    "                       '-' for standard output)\n"
    "  --field F            von-mises (default), sxx, syy, sxy, szz, syz, sxz (3D),\n"
    "                       u, ux, uy, uz, pressure, status\n"
    "  --scale S            displacement magnification (default: auto, the largest\n"
    "                       displacement drawn as 7 % of the body size)\n"
    "  --size WxH           image size in pixels (default 1200x900)\n"
    "  --view body|contact  3D: the whole body, or the contact faces alone\n"
    "  --edges              draw the mesh edges\n"
    "  --vtu FILE           also write a VTK XML UnstructuredGrid (ParaView; '-' for\n"
    "                       standard output; works without the renderer)\n"
    "  --vtu-ascii          ASCII instead of base64 binary data in the VTU\n"
    "  --plot pressure|convergence|work  a line plot instead of the image: the\n"
    "                       contact pressure along the boundary (with Hertz's where\n"
    "                       the scene has it); the kkt error per iteration of every\n"
    "                       method of the scene (semilog); or work-precision: the\n"
    "                       kkt error against the time spent (log-log), with the\n"
    "                       baseline (one factorisation + solve of K) marked\n"
    "  --timing             print the time of each rendering stage\n";

void cli_render_args_init(cli_render_args *r)
{
    memset(r, 0, sizeof *r);
    r->w = 1200;
    r->h = 900;
}

int cli_render_option(int argc, char **argv, int *i, cli_render_args *r, cx_diag *d)
{
    const char *v = NULL;
    int k;
    if (strcmp(argv[*i], "--edges") == 0) { r->edges = 1; return 1; }
    if (strcmp(argv[*i], "--vtu-ascii") == 0) { r->vtu_ascii = 1; return 1; }
    if (strcmp(argv[*i], "--timing") == 0) { r->timing = 1; return 1; }
    if ((k = cx_arg_option(argc, argv, i, "--png", &v, d)) != 0) {
        r->png = v;
        return k;
    }
    if ((k = cx_arg_option(argc, argv, i, "--vtu", &v, d)) != 0) {
        r->vtu = v;
        return k;
    }
    if ((k = cx_arg_option(argc, argv, i, "--plot", &v, d)) != 0) {
        if (k > 0 && (r->plot = (int)cx_parse_choice(v, "pressure|convergence|work") + 1) <= 0) {
            cx_diag_set(d, CX_EINVAL, "--plot '%s': expected pressure, convergence or work", v);
            return -1;
        }
        return k;
    }
    if ((k = cx_arg_option(argc, argv, i, "--field", &v, d)) != 0) {
        r->field_name = v;
        return k;
    }
    if ((k = cx_arg_option(argc, argv, i, "--scale", &v, d)) != 0) {
        if (k > 0 && (cx_parse_double(v, &r->scale) || !(r->scale > 0) || !isfinite(r->scale))) {
            cx_diag_set(d, CX_EINVAL, "--scale '%s': expected a positive number", v);
            return -1;
        }
        return k;
    }
    if ((k = cx_arg_option(argc, argv, i, "--size", &v, d)) != 0) {
        char extra;
        if (k > 0 && (sscanf(v, "%dx%d%c", &r->w, &r->h, &extra) != 2 || r->w < 64 || r->h < 64 ||
                      r->w > 16384 || r->h > 16384)) {
            cx_diag_set(d, CX_EINVAL, "--size '%s': expected WxH, 64..16384 pixels each way", v);
            return -1;
        }
        return k;
    }
    if ((k = cx_arg_option(argc, argv, i, "--view", &v, d)) != 0) {
        if (k > 0 && (r->view = (int)cx_parse_choice(v, "body|contact")) < 0) {
            cx_diag_set(d, CX_EINVAL, "--view '%s': expected body or contact", v);
            return -1;
        }
        return k;
    }
    return 0;
}

#if CX_HAVE_RENDER

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
    for (int i = 0; i < m; i++) {
        x[i] = cs->x[dim * i];   /* the first coordinate */
        y[i] = cs->weight[i] > 0 ? res->lN[i] / cs->weight[i] : 0;
        yh[i] = cx_scene_hertz_pressure(sc, x[i]);
    }
    char title[200];
    snprintf(title, sizeof title, "%s level %d: contact pressure (%s, kkt %.1e)", sc->id,
             res->run.level, res->run.method, res->run.kkt);
    cx_plot pl;
    cx_plot_init(&pl, title, "x (position along the contact boundary)", "contact pressure [units of E]");
    cx_plot_add_series(&pl, "computed (nodal force / lumped length)", m, x, y, CX_PLOT_MARKERS);
    if (sc->has_hertz) {
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
    int rc = cx_plot_write_png(&pl, r->png, r->w, r->h, d);
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

/* The kkt error per iteration of every method of the scene that supports
 * the problem, on one semilog plot (the session keeps the operators); or
 * (work) the kkt error against the time spent, log-log, with the baseline
 * time as a vertical line. */
static int render_plot_convergence(const cli_render_args *r, const cx_scene *sc, cx_session *s,
                                   int level, int work, cx_diag *d)
{
    conv_rec rec[CX_SCENE_MAX_METHODS];
    memset(rec, 0, sizeof rec);
    char title[200];
    snprintf(title, sizeof title, "%s level %d, friction %s: %s", sc->id, level,
             cx_friction_name(cx_session_friction(s)->law),
             work ? "work-precision" : "convergence");
    cx_plot pl;
    cx_plot_init(&pl, title, work ? "time [s] (setup included)" : "iteration", "kkt error");
    pl.logy = 1;
    pl.logx = work;
    cx_options opt = *cx_session_options(s);
    int rc = CX_OK;
    const cx_problem *p0 = cx_session_problem(s);
    for (int k = 0; k < sc->nmethods && rc == CX_OK; k++) {
        const cx_method *m = cx_method_find(sc->methods[k]);
        if (!m || cx_method_check(m, p0, cx_session_friction(s)->law, NULL) != CX_OK)
            continue;
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
        if (cx_session_set_method(run, m, NULL, &opt, d) == CX_OK) {
            rc = cx_solver_solve(run, render_conv_observe, &rec[k], d);
            if (rc == CX_OK)
                cx_plot_add_series(&pl, m->id, rec[k].n, work ? rec[k].time : rec[k].it, rec[k].kkt,
                                   CX_PLOT_LINE | CX_PLOT_MARKERS | (k % 2 ? CX_PLOT_DASHED : 0));
        }
        cx_session_destroy(&fresh);
    }
    cx_plot_add_hline(&pl, opt.tol, "tolerance");
    double t_base = 0;
    if (work && rc == CX_OK && (rc = cx_problem_baseline(cx_session_problem(s), &t_base, d)) == CX_OK)
        cx_plot_add_vline(&pl, t_base, "baseline: factorise + solve K");
    cx_plot_add_text(&pl, "scene", sc->id);
    if (rc == CX_OK)
        rc = cx_plot_write_png(&pl, r->png, r->w, r->h, d);
    for (int k = 0; k < CX_SCENE_MAX_METHODS; k++) {
        cx_free(rec[k].it);
        cx_free(rec[k].kkt);
        cx_free(rec[k].time);
    }
    return rc;
}

static int render_png(const cli_render_args *r, const cx_scene *sc, cx_session *s, cx_result *res,
                      cx_diag *d)
{
    if (r->plot == 1)
        return render_plot_pressure(r, sc, res, d);
    if (r->plot >= 2)
        return render_plot_convergence(r, sc, s, res->run.level, r->plot == 3, d);
    cx_render_opts o;
    cx_render_opts_default(&o);
    o.width = r->w;
    o.height = r->h;
    o.scale = r->scale;
    o.edges = r->edges;
    o.view = r->view;
    if (r->field_name && (o.field = cx_field_from_name(r->field_name)) < 0)
        return cx_diag_set(d, CX_EINVAL, "--field '%s': unknown field (see 'signorini render --help')",
                           r->field_name);
    cx_render_timing t;
    CX_TRY(cx_render_png(res, &o, r->png, &t, d));
    if (r->timing)
        fprintf(stderr, "render %s %dx%d: context %.3f s, fields+geometry %.3f s, draw %.3f s, "
                "text %.3f s, png %.3f s\n", r->png, o.width, o.height, t.context, t.fields,
                t.draw, t.text, t.png);
    return CX_OK;
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
    if (r->view == CX_VIEW_CONTACT && dim != 3)
        return cx_diag_set(d, CX_EINVAL, "--view contact: only in 3D");
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
    if (r->png)
        return cx_diag_set(d, CX_EUNSUPPORTED, "--png: built without rendering (meson -Drender=disabled)");
    return CX_OK;
}

#endif

int cli_render_stdout_users(const cli_render_args *r)
{
    return cx_outfile_is_stdout(r->png) + cx_outfile_is_stdout(r->vtu);
}

int cli_render_outputs(const cli_render_args *r, const cx_scene *sc, cx_session *s, cx_result *res,
                       int quiet, cx_diag *d)
{
    if (r->vtu) {
        CX_TRY(cx_vtu_write(res, r->vtu, r->vtu_ascii, d));
        if (!quiet && !cx_outfile_is_stdout(r->vtu))
            fprintf(stderr, "wrote %s\n", r->vtu);
    }
    return r->png ? render_png(r, sc, s, res, d) : CX_OK;
}

int cli_render(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            fputs(render_usage, stdout);
            return CX_EXIT_OK;
        }
    int png = 0;
    for (int i = 1; i < argc; i++)
        png |= strcmp(argv[i], "--png") == 0 || strncmp(argv[i], "--png=", 6) == 0;
    if (!png)
        return cli_fail("render", "missing --png FILE (see 'signorini render --help')");
    return cli_solve_as("render", argc, argv);
}
