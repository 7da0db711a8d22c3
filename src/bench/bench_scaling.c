/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini bench scaling: per mesh level, the size of the problem, the
 * assembly, the baseline (one factorisation + solve of K) and each method's
 * time as a ratio to it, iterations and peak memory against the factor's;
 * the slope of log time against log dofs per method. */
#include "bench/bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char scaling_usage[] =
    "usage: signorini bench scaling SCENE --levels a..b [options]\n"
    "\n"
    "Mesh scaling: for each level (a..b doubles from a up to b; or a list a,b,c):\n"
    "dofs, contact points, assembly, the baseline (factorise + solve K), the\n"
    "factor's size and the fill (predicted nnz(L)) of both contact-last\n"
    "orderings (CAMD; METIS on the interior, when analysed) with the one chosen,\n"
    "and for each method its time (setup + solve, from a fresh\n"
    "session) as a ratio to the baseline (ratio; setup/baseline; end_to_end,\n"
    "assembly + setup + solve), iterations, peak memory of the run against the\n"
    "factor's, and the error against the reference solution. Timings are\n"
    "medians of --repeat runs (default 3), ratios medians of each run's ratio\n"
    "to the baseline measured just before it.\n";

static const char *const scaling_cols[] = {
    "scene", "level", "friction", "dofs", "contact", "assembly", "baseline", "assembly/baseline",
    "factor_mb", "ordering", "fill_camd", "fill_metis", "method", "converged", "reason", "iterations", "time", "ratio", "setup", "setup/baseline", "solve", "end_to_end",
    "peak_mb", "peak/factor", "kkt", "err_u", "message", NULL};

#define SCALING_MAX_LEVELS 24

typedef struct {
    bench_common c;
    const char *scene;
    const char *levels_text;   /* --levels as given */
    int levels[SCALING_MAX_LEVELS];
    int nlevels;
    double tol;
    int no_ref;
} scaling_args;

static int scaling_levels(const char *v, scaling_args *a, cx_diag *d)
{
    long lo, hi;
    const char *dots = strstr(v, "..");
    a->nlevels = 0;
    if (dots) {
        char first[32];
        snprintf(first, sizeof first, "%.*s", (int)(dots - v), v);
        if (cx_parse_int(first, 1, CX_OPT_LEVEL_MAX, &lo) || cx_parse_int(dots + 2, 1, CX_OPT_LEVEL_MAX, &hi) || hi < lo)
            return cx_diag_set(d, CX_EINVAL, "--levels '%s': expected a..b with 1 <= a <= b", v);
        for (long l = lo; l <= hi && a->nlevels < SCALING_MAX_LEVELS; l *= 2)
            a->levels[a->nlevels++] = (int)l;
        return CX_OK;
    }
    double vals[SCALING_MAX_LEVELS];
    int n = cx_parse_doubles(v, vals, SCALING_MAX_LEVELS);
    for (int k = 0; k < n; k++) {
        if (!(vals[k] >= 1 && vals[k] == floor(vals[k])))
            n = -1;
        else
            a->levels[k] = (int)vals[k];
    }
    if (n <= 0)
        return cx_diag_set(d, CX_EINVAL, "--levels '%s': expected a..b or a list of positive integers", v);
    a->nlevels = n;
    return CX_OK;
}

static const cx_opt scaling_opts[] = {
    {"levels", 0, CX_OPT_STRING, 0, 0, 0, NULL, "a..b|a,b,c", "mesh levels",
     offsetof(scaling_args, levels_text), NULL},
    CX_OPT_ROW_TOL(scaling_args, tol, "kkt tolerance of the runs (default 1e-10)"),
    {"no-reference", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "skip the reference solutions (no err_u column)",
     offsetof(scaling_args, no_ref), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

/* CX_OK, CX_OPT_HELP, CX_EINVAL (a malformed line) or the status of
 * bench_common_finish. */
static int scaling_parse(int argc, char **argv, scaling_args *a, cx_diag *d)
{
    memset(a, 0, sizeof *a);
    bench_common_default(&a->c, 3);
    a->tol = 1e-10;
    int npos = 0;
    int r = bench_parse(argc, argv, scaling_opts, a, &a->c, &a->scene, 1, &npos, d);
    if (r)
        return r;
    if (a->levels_text)
        CX_TRY(scaling_levels(a->levels_text, a, d));
    if (npos == 0)
        return cx_diag_set(d, CX_EINVAL, "missing SCENE");
    if (a->nlevels == 0)
        return cx_diag_set(d, CX_EINVAL, "missing --levels a..b");
    return bench_common_finish(&a->c, d);
}

/* Least-squares slope of log y against log x over the rows of one method. */
static double scaling_slope(const bench_table *t, const char *method, const char *xcol, const char *ycol)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (int r = 0; r < t->nrows; r++) {
        if (method && strcmp(bench_get_str(t, r, "method"), method) != 0)
            continue;
        double x = bench_get_num(t, r, xcol), y = bench_get_num(t, r, ycol);
        if (!(x > 0 && y > 0))
            continue;
        x = log(x);
        y = log(y);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
        n++;
    }
    double den = n * sxx - sx * sx;
    return n >= 2 && den > 0 ? (n * sxy - sx * sy) / den : NAN;
}

/* A slope as text: "n/a" with fewer than two levels. */
static void scaling_fmt_slope(double v, char *buf, size_t len)
{
    if (isfinite(v))
        snprintf(buf, len, "%.2f", v);
    else
        snprintf(buf, len, "n/a");
}

/* The plot of time against dofs (log-log): one line per method, the
 * baseline and the assembly, the fitted slopes in the labels. */
static int bench_scaling_plot(const bench_table *t, const char *png, cx_diag *d)
{
    bench_plot pl;
    memset(&pl, 0, sizeof pl);
    snprintf(pl.title, sizeof pl.title, "mesh scaling: %s", t->nrows ? bench_get_str(t, 0, "scene") : "");
    snprintf(pl.xlabel, sizeof pl.xlabel, "dofs");
    snprintf(pl.ylabel, sizeof pl.ylabel, "time (s)");
    pl.xlog = pl.ylog = 1;
    for (int r = 0; r < t->nrows; r++) {
        char label[64];
        const char *m = bench_get_str(t, r, "method");
        char v[16];
        scaling_fmt_slope(scaling_slope(t, m, "dofs", "time"), v, sizeof v);
        snprintf(label, sizeof label, "%s (slope %s)", m, v);
        bench_plot_point(&pl, label, bench_get_num(t, r, "dofs"), bench_get_num(t, r, "time"));
        scaling_fmt_slope(scaling_slope(t, NULL, "dofs", "baseline"), v, sizeof v);
        snprintf(label, sizeof label, "baseline (slope %s)", v);
        bench_plot_point(&pl, label, bench_get_num(t, r, "dofs"), bench_get_num(t, r, "baseline"));
        scaling_fmt_slope(scaling_slope(t, NULL, "dofs", "assembly"), v, sizeof v);
        snprintf(label, sizeof label, "assembly (slope %s)", v);
        bench_plot_point(&pl, label, bench_get_num(t, r, "dofs"), bench_get_num(t, r, "assembly"));
    }
    int st = bench_plot_write_png(&pl, png, d);
    bench_plot_clear(&pl);
    return st;
}

/* Medians over repeat builds of the assembly and of the baseline; the
 * factor's size in MB (values and row indices) and the orderings' fills. */
static int scaling_level_costs(const bench_problem_spec *spec, int repeat, double *t_asm,
                               double *t_base, double *factor_mb, cx_schur_ordering *ord,
                               cx_problem **p, cx_diag *d)
{
    double ta[BENCH_MAX_REPEAT];
    int n = repeat < BENCH_MAX_REPEAT ? repeat : BENCH_MAX_REPEAT;
    for (int k = 0; k < n; k++) {
        cx_problem_destroy(p);
        CX_TRY(bench_build(spec, p, &ta[k], d));
    }
    *t_asm = bench_median(ta, n);
    /* the level's baseline for rows without a run (each run is paired
     * with its own) */
    CX_TRY(bench_baseline(*p, n, t_base, d));
    /* the factor of the constrained-order Cholesky every Schur method uses */
    cx_schur *S = NULL;
    int st = cx_schur_create(&S, &(*p)->K, (*p)->cdofs, (*p)->nc, NULL, d);
    *factor_mb = st == CX_OK ? cx_schur_factor_nnz(S) * (sizeof(double) + sizeof(int)) / 1048576.0 : NAN;
    memset(ord, 0, sizeof *ord);
    if (st == CX_OK)
        *ord = *cx_schur_ordering_of(S);
    else
        ord->chosen = CX_ORDER_AUTO;   /* none */
    cx_schur_destroy(&S);
    return CX_OK;
}

int bench_scaling(int argc, char **argv)
{
    cx_diag d;
    cx_diag_clear(&d);
    scaling_args a;
    cx_scene sc;
    bench_problem_spec spec;
    int parsed = scaling_parse(argc, argv, &a, &d);
    if (parsed == CX_OPT_HELP) {
        bench_help(scaling_usage, scaling_opts, stdout);
        return CX_EXIT_OK;
    }
    if (parsed)
        return bench_parse_fail("bench scaling", parsed, d.msg);
    if (bench_open(&a.c, a.scene, 0, &sc, &spec, &d))
        return bench_fail("bench scaling", d.msg);
    uint64_t shash = bench_scene_hash(&sc);
    for (int k = 0; k < a.nlevels; k++)
        if (a.levels[k] > sc.level_max) {
            cx_diag_set(&d, CX_EINVAL, "--levels: level %d: scene '%s' allows levels 1 to %d", a.levels[k],
                        sc.id, sc.level_max);
            return bench_fail("bench scaling", d.msg);
        }

    bench_table t;
    bench_table_init(&t, scaling_cols);
    bench_meta_machine(&t);
    bench_meta(&t, "benchmark", "scaling %s friction %s, tol %g, medians of %d", sc.id,
               cx_friction_name(spec.law), a.tol, a.c.repeat);
    bench_meta(&t, "scene hash", "%016llx (%s)", (unsigned long long)shash, sc.path);
    bench_progress_start(a.nlevels);
    int code = CX_EXIT_OK;
    for (int l = 0; l < a.nlevels && !bench_interrupted(); l++) {
        spec.level = a.levels[l];
        char label[64];
        snprintf(label, sizeof label, "level %d", spec.level);
        bench_progress_case(l, label);
        cx_problem *p = NULL;
        double t_asm, t_base, fmb;
        cx_schur_ordering ord;
        const cx_method *methods[64];
        int nm;
        if (scaling_level_costs(&spec, a.c.repeat, &t_asm, &t_base, &fmb, &ord, &p, &d) ||
            bench_methods(a.c.methods, p, spec.law, methods, 64, &nm, &d)) {
            cx_problem_destroy(&p);
            code = bench_fail("bench scaling", d.msg);
            break;
        }
        bench_ref ref = {0};
        int ref_ok = !a.no_ref && bench_ref_get(&a.c.refs, &spec, p, 10 * a.c.time_limit, &ref, &d) == CX_OK;
        if (!a.no_ref)
            bench_meta(&t, label, ref_ok ? "reference %s kkt %.2e%s (%s)" : "no reference: %s",
                       ref_ok ? ref.method : d.msg, ref.kkt,
                       ref.kkt > 1e-12 ? " (above 1e-12: the best it reached)" : "",
                       bench_ref_origin(&ref));
        for (int k = 0; k < nm && !bench_interrupted(); k++) {
            cx_options opt;
            bench_common_options(&a.c, &opt);
            opt.tol = a.tol;
            bench_result res;
            bench_paired med;
            bench_run_paired(&spec, methods[k], NULL, &opt, ref_ok ? &ref : NULL, a.c.repeat, &res, &med);
            if (res.interrupted)
                break;
            int r = bench_table_row(&t);
            bench_set_str(&t, r, "scene", "%s", sc.id);
            bench_set_int(&t, r, "level", spec.level);
            bench_set_str(&t, r, "friction", "%s", cx_friction_name(spec.law));
            bench_set_int(&t, r, "dofs", p->n);
            bench_set_int(&t, r, "contact", p->m);
            bench_set_num(&t, r, "assembly", t_asm);
            bench_set_num(&t, r, "baseline", t_base);
            bench_set_num(&t, r, "assembly/baseline", t_asm / t_base);
            bench_set_num(&t, r, "factor_mb", fmb);
            if (ord.chosen != CX_ORDER_AUTO) {
                bench_set_str(&t, r, "ordering", "%s", ord.chosen == CX_ORDER_METIS ? "metis" : "camd");
                bench_set_num(&t, r, "fill_camd", ord.lnz[CX_ORDER_CAMD]);
                if (ord.tried)
                    bench_set_num(&t, r, "fill_metis", ord.lnz[CX_ORDER_METIS]);
            }
            bench_set_str(&t, r, "method", "%s", methods[k]->id);
            bench_set_result(&t, r, &res);
            if (res.failed)
                continue;
            bench_set_num(&t, r, "time", med.time);
            bench_set_num(&t, r, "baseline", med.baseline);
            bench_set_num(&t, r, "assembly", med.assembly);
            bench_set_num(&t, r, "assembly/baseline", med.assembly_ratio);
            bench_set_num(&t, r, "ratio", med.ratio);
            bench_set_num(&t, r, "setup", med.setup);
            bench_set_num(&t, r, "setup/baseline", med.setup_ratio);
            bench_set_num(&t, r, "end_to_end", med.end_ratio);
            bench_set_num(&t, r, "solve", med.solve);
            bench_set_num(&t, r, "peak_mb", med.peak_mb);
            bench_set_num(&t, r, "peak/factor", med.peak_mb / fmb);
        }
        bench_ref_clear(&ref);
        cx_problem_destroy(&p);
    }
    bench_progress_end();
    if (code == CX_EXIT_OK) {
        char slopes[160] = "";
        size_t len = 0;
        for (int r = 0; r < t.nrows && len < sizeof slopes - 40; r++) {
            const char *m = bench_get_str(&t, r, "method");
            if (strstr(slopes, m))
                continue;
            char v[16];
            scaling_fmt_slope(scaling_slope(&t, m, "dofs", "time"), v, sizeof v);
            len += (size_t)snprintf(slopes + len, sizeof slopes - len, "%s%s %s", len ? ", " : "", m, v);
        }
        char vb[16], va[16];
        scaling_fmt_slope(scaling_slope(&t, NULL, "dofs", "baseline"), vb, sizeof vb);
        scaling_fmt_slope(scaling_slope(&t, NULL, "dofs", "assembly"), va, sizeof va);
        bench_meta(&t, "slopes (log time / log dofs)", "%s; baseline %s; assembly %s", slopes, vb, va);
        if (bench_interrupted())
            bench_meta(&t, "interrupted", "yes: %d rows done", t.nrows);
        if (bench_output(&a.c, &t, &d))
            code = bench_fail("bench scaling", d.msg);
        else if (a.c.png && bench_scaling_plot(&t, a.c.png, &d))
            code = bench_fail("bench scaling", d.msg);
    }
    bench_table_clear(&t);
    return bench_interrupted() ? CX_EXIT_INTERRUPTED : code;
}
