/* SPDX-License-Identifier: GPL-3.0-or-later */
/* What every benchmark shares on the command line: the common options,
 * the outputs, the progress bar, Ctrl-C, and the plot data. */
#define _GNU_SOURCE   /* dlsym(RTLD_DEFAULT) for the thread counts */
#include "bench/bench.h"
#include "out/outfile.h"
#include "cx_config.h"

#if CX_HAVE_RENDER
#include "render/plot.h"
#endif
#if CX_HAVE_PETSC
#include "petsc/petsc.h"
#endif

#include <dlfcn.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* --methods a,b,...: every id in the registry or, in a build with the
 * PETSc backend, in its table (bench scaling --backend petsc runs those). */
static int common_check_methods(const char *text, cx_diag *d)
{
    char buf[512];
    if (snprintf(buf, sizeof buf, "%s", text) >= (int)sizeof buf)
        return cx_diag_set(d, CX_EINVAL, "--methods: list too long");
    for (char *save = NULL, *id = strtok_r(buf, ",", &save); id; id = strtok_r(NULL, ",", &save))
        if (!cx_method_find(id)
#if CX_HAVE_PETSC
            && !cx_petsc_method_find(id)
#endif
        )
            return cx_diag_set(d, CX_EINVAL, "--methods: unknown method '%s' (see 'signorini list')", id);
    return CX_OK;
}

const cx_opt bench_common_opts[] = {
    {"methods", 0, CX_OPT_STRING, 0, 0, 0, NULL, "a,b,...",
     "methods to run (default: every registered method\n"
     "that supports the scene's law, dimension and bodies)", offsetof(bench_common, methods),
     common_check_methods},
    CX_OPT_ROW_FRICTION(bench_common, friction),
    CX_OPT_ROW_SLIP(bench_common, value),
    CX_OPT_ROW_F(bench_common, value),
    CX_OPT_ROW_MAX_ITER(bench_common, max_iter, "iteration limit of every run (default 500)"),
    CX_OPT_ROW_TIME_LIMIT(bench_common, time_limit, "seconds per run before it is stopped (default 60)"),
    {"repeat", 0, CX_OPT_INT, 1, BENCH_MAX_REPEAT, 0, NULL, "N", "timings are medians of N runs",
     offsetof(bench_common, repeat), NULL},
    {"threads", 0, CX_OPT_INT, 1, 1024, 0, NULL, "N",
     "BLAS (OpenBLAS) and OpenMP threads (default: as the\n"
     "environment says); 1 gives steadier ratios on a busy machine", offsetof(bench_common, threads), NULL},
    {"csv", 0, CX_OPT_STRING, 0, 0, 0, NULL, "FILE",
     "also write the rows as CSV (header lines start with '#')", offsetof(bench_common, csv), NULL},
    {"json", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "print JSON {meta, rows} on stdout instead of the table",
     offsetof(bench_common, json), NULL},
    {"png", 0, CX_OPT_STRING, 0, 0, 0, NULL, "FILE", "the plot of the runs (PNG, through the renderer)",
     offsetof(bench_common, png), NULL},
    {"cache", 0, CX_OPT_STRING, 0, 0, 0, NULL, "DIR",
     "reference solutions (default: $XDG_CACHE_HOME/signorini,\n"
     "else ~/.cache/signorini)", offsetof(bench_common, cache), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

const char bench_png_missing[] = "PNG plots need the renderer (not in this build)";

void bench_common_default(bench_common *c, int repeat)
{
    memset(c, 0, sizeof *c);
    c->friction = -1;
    c->value = NAN;
    c->time_limit = 60;
    c->repeat = repeat;
}

int bench_fail(const char *cmd, const char *msg)
{
    return cx_arg_report(stderr, cmd, msg, CX_EXIT_ERROR);
}

int bench_usage(const char *cmd, const char *msg)
{
    return cx_arg_report(stderr, cmd, msg, CX_EXIT_USAGE);
}

int bench_parse_fail(const char *cmd, int status, const char *msg)
{
    return status == CX_EINVAL ? bench_usage(cmd, msg) : bench_fail(cmd, msg);
}

int bench_parse(int argc, char **argv, const cx_opt *own, void *args, bench_common *c, const char **pos,
                int maxpos, int *npos, cx_diag *d)
{
    cx_opt_group groups[] = {{own, args}, {bench_common_opts, c}, {NULL, NULL}};
    return cx_opt_parse(groups, argc, argv, pos, maxpos, npos, d);
}

int bench_paper_args(const char *cmd, const char *usage, const cx_opt *opts, void *args, int argc,
                     char **argv)
{
    cx_opt_group groups[] = {{opts, args}, {NULL, NULL}};
    cx_diag d;
    cx_diag_clear(&d);
    int r = cx_opt_parse(groups, argc, argv, NULL, 0, NULL, &d);
    if (r == CX_OPT_HELP) {
        fputs(usage, stdout);
        fputs("\n  -h, --help           this help\n", stdout);
        cx_opt_help(opts, stdout);
        return CX_EXIT_OK;
    }
    return r ? bench_usage(cmd, d.msg) : -1;
}

void bench_help(const char *usage, const cx_opt *own, FILE *out)
{
    fputs(usage, out);
    fputs("\n  -h, --help           this help\n", out);
    cx_opt_help(own, out);
    fputs("\noptions of every benchmark:\n", out);
    cx_opt_help(bench_common_opts, out);
}

int bench_open(const bench_common *c, const char *id, int level, cx_scene *sc,
               bench_problem_spec *spec, cx_diag *d)
{
    CX_TRY(cx_scene_open(id, sc, d));
    *spec = (bench_problem_spec){sc, level, CX_FRICTION_NONE, 0, "", NULL, NULL};
    return bench_common_law(c, sc, &spec->law, &spec->value, d);
}

/* Thread counts of the libraries loaded (OpenBLAS, the OpenMP runtime
 * CHOLMOD uses), found at run time so that no header or link is needed. */
static void common_set_threads(int n)
{
    void (*blas)(int) = (void (*)(int))dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
    void (*omp)(int) = (void (*)(int))dlsym(RTLD_DEFAULT, "omp_set_num_threads");
    if (blas)
        blas(n);
    if (omp)
        omp(n);
}

int bench_common_finish(bench_common *c, cx_diag *d)
{
    if (c->threads > 0)
        common_set_threads(c->threads);
#if CX_HAVE_RENDER
    (void)d;
#else
    if (c->png)
        return cx_diag_set(d, CX_EUNSUPPORTED, "%s", bench_png_missing);
#endif
    /* the XDG base directory rule: a relative $XDG_CACHE_HOME is ignored */
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    char *dir = c->refs.dir;
    size_t len = sizeof c->refs.dir;
    if (c->cache && c->cache[0])
        snprintf(dir, len, "%s", c->cache);
    else if (xdg && xdg[0] == '/')
        snprintf(dir, len, "%s/signorini", xdg);
    else if (home && home[0])
        snprintf(dir, len, "%s/.cache/signorini", home);
    else
        dir[0] = '\0';   /* bench_ref_get warns once and runs uncached */
    c->refs.off = 0;
    return CX_OK;
}

int bench_common_law(const bench_common *c, const cx_scene *s, cx_friction *law, double *value,
                     cx_diag *d)
{
    int l = c->friction >= 0 ? c->friction : (int)s->friction;
    (void)d;
    *law = (cx_friction)l;
    *value = l == CX_FRICTION_COULOMB ? s->F : s->slip_bound;
    if (l == CX_FRICTION_NONE)
        *value = 0;
    if (!isnan(c->value))
        *value = c->value;   /* its range was checked by the table */
    return CX_OK;
}

void bench_common_options(const bench_common *c, cx_options *o)
{
    cx_options_default(o);
    o->time_limit = c->time_limit;
    if (c->max_iter > 0)
        o->max_iter = c->max_iter;
}

int bench_output(const bench_common *c, const bench_table *t, cx_diag *d)
{
    /* standard output holds one thing: with a CSV or PNG there ('-'), the
     * text table goes to stderr */
    int to_stdout = cx_outfile_is_stdout(c->csv) + cx_outfile_is_stdout(c->png);
    if (to_stdout + c->json > 1)
        return cx_diag_set(d, CX_EINVAL, "--json, --csv - and --png -: only one can go to standard output");
    if (c->csv)
        CX_TRY(bench_table_write_csv(t, c->csv, d));
    if (c->json)
        return bench_table_write_json(t, "-", d);
    FILE *out = to_stdout ? stderr : stdout;
    bench_table_print(t, out);
    return fflush(out) == 0 && !ferror(out) ? CX_OK : cx_diag_set(d, CX_EIO, "standard output: cannot write");
}

/* ---- plots ------------------------------------------------------------- */

void bench_plot_point(bench_plot *pl, const char *label, double x, double y)
{
    if (!isfinite(x) || !isfinite(y))
        return;
    int k;
    for (k = 0; k < pl->nseries; k++)
        if (strcmp(pl->series[k].label, label) == 0)
            break;
    if (k == pl->nseries) {
        if (k == BENCH_PLOT_MAX_SERIES)
            return;
        pl->nseries++;
        snprintf(pl->series[k].label, sizeof pl->series[k].label, "%s", label);
    }
    bench_series *s = &pl->series[k];
    double *x2 = realloc(s->x, sizeof(double) * (size_t)(s->n + 1));
    double *y2 = x2 ? realloc(s->y, sizeof(double) * (size_t)(s->n + 1)) : NULL;
    if (x2)
        s->x = x2;
    if (!y2)
        return;
    s->y = y2;
    s->x[s->n] = x;
    s->y[s->n++] = y;
}

void bench_plot_clear(bench_plot *pl)
{
    for (int k = 0; k < pl->nseries; k++) {
        free(pl->series[k].x);
        free(pl->series[k].y);
    }
    memset(pl, 0, sizeof *pl);
}

/* The one place the renderer is wired in: pl as a cx_plot (one line with
 * markers per series, the vertical reference lines), 1200 x 900. */
int bench_plot_write_png(const bench_plot *pl, const char *path, cx_diag *d)
{
#if CX_HAVE_RENDER
    cx_plot plot;
    cx_plot_init(&plot, pl->title, pl->xlabel, pl->ylabel);
    plot.logx = pl->xlog;
    plot.logy = pl->ylog;
    for (int k = 0; k < pl->nseries; k++)
        CX_TRY(cx_plot_add_series(&plot, pl->series[k].label, pl->series[k].n, pl->series[k].x,
                                  pl->series[k].y, CX_PLOT_LINE | CX_PLOT_MARKERS));
    for (int k = 0; k < pl->nvlines; k++)
        CX_TRY(cx_plot_add_vline(&plot, pl->vline[k], pl->vlabel[k]));
    return cx_plot_write_png(&plot, path, 1200, 900, d);
#else
    (void)pl;
    (void)path;
    return cx_diag_set(d, CX_EUNSUPPORTED, "%s", bench_png_missing);
#endif
}

/* ---- progress and Ctrl-C ---------------------------------------------- */

static volatile sig_atomic_t progress_stop;
static int progress_total, progress_tty;
static double progress_t0;

/* Ctrl-C during the runs: the runs stop and the table keeps those that
 * finished; a second Ctrl-C ends the program at once. */
/* The session whose run is in progress: Ctrl-C cancels it (an atomic
 * store, safe in a handler), so a long step ends within the method's check
 * interval instead of at the next step. */
static cx_session *volatile progress_running;

static void progress_on_sigint(int sig)
{
    (void)sig;
    if (progress_stop) {
        cx_outfile_abandon_pending();
        _exit(CX_EXIT_INTERRUPTED);
    }
    progress_stop = 1;
    cx_session *s = progress_running;
    if (s)
        cx_session_cancel(s);
}

/* Ctrl-C while the output is written: end now, leaving no temporary. */
static void progress_on_sigint_exit(int sig)
{
    (void)sig;
    cx_outfile_abandon_pending();
    _exit(CX_EXIT_INTERRUPTED);
}

static void progress_handle_sigint(void (*handler)(int))
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = handler;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
}

int bench_interrupted(void) { return progress_stop != 0; }

int bench_observer(void *ctx, const cx_session *s, const cx_iterate *it)
{
    (void)ctx;
    (void)s;
    (void)it;
    return progress_stop != 0;
}

int bench_solve_watched(cx_session *s, cx_observer obs, void *ctx, cx_diag *d)
{
    progress_running = s;
    int st = cx_solver_solve(s, obs, ctx, d);
    progress_running = NULL;
    return st;
}

int bench_solve(cx_session *s, cx_diag *d)
{
    CX_TRY(bench_solve_watched(s, bench_observer, NULL, d));
    return bench_interrupted() ? cx_diag_set(d, CX_EIO, "interrupted (Ctrl-C)") : CX_OK;
}

void bench_catch_sigint(void)
{
    progress_handle_sigint(progress_on_sigint);
}

void bench_progress_start(int total)
{
    progress_total = total;
    progress_tty = isatty(STDERR_FILENO);
    progress_t0 = cx_clock_now();
}

void bench_progress_case(int k, const char *label)
{
    if (!progress_tty || progress_total <= 0)
        return;
    enum { WIDTH = 24 };
    int done = WIDTH * k / progress_total;
    char bar[WIDTH + 1];
    for (int c = 0; c < WIDTH; c++)
        bar[c] = c < done ? '#' : '.';
    bar[WIDTH] = '\0';
    double spent = cx_clock_now() - progress_t0;
    char left[32] = "";
    if (k > 0)
        snprintf(left, sizeof left, ", ~%.0f s left", spent / k * (progress_total - k));
    fprintf(stderr, "\r\033[K[%s] %d/%d %s%s", bar, k + 1, progress_total, label, left);
    fflush(stderr);
}

void bench_progress_end(void)
{
    if (progress_tty && progress_total > 0)
        fputs("\r\033[K", stderr);
    progress_handle_sigint(progress_on_sigint_exit);
    if (progress_stop)
        fputs("signorini bench: interrupted: the table keeps the runs that finished\n", stderr);
}
