/* What every benchmark shares on the command line: the common options,
 * the outputs, the progress bar, Ctrl-C, and the plot data. */
#define _GNU_SOURCE   /* dlsym(RTLD_DEFAULT) for the thread counts */
#include "bench/bench.h"
#include "out/outfile.h"
#include "cx_config.h"

#if CX_HAVE_RENDER
#include "render/plot.h"
#endif

#include <dlfcn.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

const char bench_common_help[] =
    "  --methods a,b,...    methods to run (default: every registered method\n"
    "                       that supports the scene's law, dimension and bodies)\n"
    "  --friction LAW       none | tresca | coulomb (default: the scene's)\n"
    "  --slip S / --F F     Tresca slip bound / Coulomb coefficient (default: the scene's)\n"
    "  --max-iter N         iteration limit of every run (default 500)\n"
    "  --time-limit S       seconds per run before it is stopped (default 60)\n"
    "  --repeat N           timings are medians of N runs\n"
    "  --threads N          BLAS (OpenBLAS) and OpenMP threads (default: as the\n"
    "                       environment says); 1 gives steadier ratios on a busy machine\n"
    "  --csv FILE           also write the rows as CSV (header lines start with '#')\n"
    "  --json               print JSON {meta, rows} on stdout instead of the table\n"
    "  --png FILE           the plot of the runs (PNG, through the renderer)\n"
    "  --cache DIR          reference solutions (default: $XDG_CACHE_HOME/signorini,\n"
    "                       else ~/.cache/signorini)\n";

const char bench_png_missing[] = "PNG plots need the renderer (not in this build)";

void bench_common_default(bench_common *c, int repeat)
{
    memset(c, 0, sizeof *c);
    c->time_limit = 60;
    c->repeat = repeat;
}

int bench_fail(const char *cmd, const char *msg)
{
    fprintf(stderr, "signorini %s: %s\n", cmd, msg);
    return CX_EXIT_ERROR;
}

/* An integer option's value in [lo, hi]: 1, or -1 with the range in d. */
static int common_int(const char *name, const char *v, long lo, long hi, int *out, cx_diag *d)
{
    long n;
    if (cx_parse_int(v, lo, hi, &n)) {
        cx_diag_set(d, CX_EINVAL, "%s '%s': expected an integer in [%ld, %ld]", name, v, lo, hi);
        return -1;
    }
    *out = (int)n;
    return 1;
}

int bench_common_option(int argc, char **argv, int *i, bench_common *c, cx_diag *d)
{
    static const char *const names[] = {"--csv", "--png", "--cache", "--methods", "--friction",
                                        "--slip", "--F", "--time-limit", "--max-iter", "--repeat",
                                        "--threads", NULL};
    if (strcmp(argv[*i], "--json") == 0) {
        c->json = 1;
        return 1;
    }
    for (int k = 0; names[k]; k++) {
        const char *v;
        int r = cx_arg_option(argc, argv, i, names[k], &v, d);
        if (r <= 0) {
            if (r < 0)
                return -1;
            continue;
        }
        switch (k) {
        case 0: c->csv = v; break;
        case 1: c->png = v; break;
        case 2: c->cache = v; break;
        case 3: c->methods = v; break;
        case 4: c->friction = v; break;
        case 5: case 6: c->value = v; break;
        case 7:
            if (cx_parse_double(v, &c->time_limit) || !(c->time_limit > 0)) {
                cx_diag_set(d, CX_EINVAL, "--time-limit '%s': expected a positive number of seconds", v);
                return -1;
            }
            break;
        case 8:
            return common_int(names[k], v, 1, 100000000, &c->max_iter, d);
        case 9:
            return common_int(names[k], v, 1, BENCH_MAX_REPEAT, &c->repeat, d);
        case 10:
            return common_int(names[k], v, 1, 1024, &c->threads, d);
        }
        return 1;
    }
    return 0;
}

int bench_parse(int argc, char **argv, const char *kind, bench_common *c, bench_arg_fn own, void *args,
                cx_diag *d)
{
    for (int i = 1; i < argc; i++) {
        int r = bench_common_option(argc, argv, &i, c, d);
        if (r == 0)
            r = own(args, argc, argv, &i, d);
        if (r < 0)
            return CX_EINVAL;
        if (r > 0)
            continue;
        if (argv[i][0] == '-' && argv[i][1])
            return cx_diag_set(d, CX_EINVAL, "unknown option '%s' (see 'signorini bench %s --help')", argv[i],
                               kind);
        return cx_diag_set(d, CX_EINVAL, "unexpected argument '%s' (see 'signorini bench %s --help')",
                           argv[i], kind);
    }
    return CX_OK;
}

int bench_arg_scene(char **argv, const int *i, const char **scene, cx_diag *d)
{
    if (argv[*i][0] == '-' && argv[*i][1])
        return 0;
    if (*scene)
        return cx_diag_set(d, CX_EINVAL, "unexpected argument '%s': one scene only", argv[*i]);
    *scene = argv[*i];
    return 1;
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

int bench_print_help(int argc, char **argv, const char *usage)
{
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            printf("%s%s", usage, bench_common_help);
            return 1;
        }
    return 0;
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
    int l = s->friction;
    if (c->friction && (l = cx_friction_from_name(c->friction)) < 0)
        return cx_diag_set(d, CX_EINVAL, "--friction '%s': expected none, tresca or coulomb", c->friction);
    *law = (cx_friction)l;
    *value = l == CX_FRICTION_COULOMB ? s->F : s->slip_bound;
    if (l == CX_FRICTION_NONE)
        *value = 0;
    if (c->value && (cx_parse_double(c->value, value) || *value < 0))
        return cx_diag_set(d, CX_EINVAL, "--slip/--F '%s': expected a non-negative number", c->value);
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
static void progress_on_sigint(int sig)
{
    (void)sig;
    if (progress_stop) {
        cx_outfile_abandon_pending();
        _exit(CX_EXIT_INTERRUPTED);
    }
    progress_stop = 1;
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

int bench_solve(cx_session *s, cx_diag *d)
{
    CX_TRY(cx_solver_solve(s, bench_observer, NULL, d));
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
