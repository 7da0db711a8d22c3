/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini bench wp: work against precision. For each method, a sweep of
 * the tolerance on the kkt error (and of the parameter its paper tunes);
 * each run records time, iterations, solves with K, the kkt error and the
 * errors against the reference solution. The baseline (one factorisation
 * and solve of K) is measured in the same run. */
#include "bench/bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char wp_usage[] =
    "usage: signorini bench wp SCENE [--level L] [--tols t1,t2,...] [--sweep KEY=v1,v2,...] [options]\n"
    "\n"
    "Work-precision: each method runs to each tolerance on the kkt error (runs\n"
    "stop on the kkt error only) from a fresh session (the setup is timed), for\n"
    "each value of its main parameter. Errors are against the reference solution\n"
    "(computed once, cached). Default tolerances 1e-2,1e-4,1e-6,1e-8,1e-10,1e-12.\n";

/* The parameter each method's paper tunes, and the values swept. A method
 * not listed runs with its defaults. */
static const struct {
    const char *method, *key;
    double values[6];   /* 0-terminated */
} wp_sweeps[] = {
    {"ssn-tresca", "rho", {1e-4, 1e-3, 1e-2, 0}},
    {"ssn-c", "rho", {1e-4, 1e-3, 1e-2, 0}},
    {"ubr-tf", "r", {0.1, 1, 10, 0}},
    {"ubr-c", "r", {0.1, 1, 10, 0}},
};

static const char *const wp_cols[] = {
    "scene", "level", "friction", "method", "param", "value", "tol", "converged", "reason",
    "iterations", "time", "ratio", "setup", "solve", "factorizations", "solves", "kkt", "err_u",
    "err_l", "message", NULL};

#define WP_MAX_VALUES 16

typedef struct {
    bench_common c;
    const char *scene;
    int level;
    const char *tols_text, *sweep_text;   /* --tols, --sweep as given */
    double tols[WP_MAX_VALUES];
    int ntols;
    char sweep_key[CX_PARAM_STRLEN];   /* "": each method's own (wp_sweeps) */
    double sweep[WP_MAX_VALUES];
    int nsweep;
} wp_args;

static int wp_list(const char *opt, const char *text, double *out, int *n, cx_diag *d)
{
    *n = cx_parse_doubles(text, out, WP_MAX_VALUES);
    for (int k = 0; k < *n; k++)
        if (!(out[k] > 0))
            *n = -1;
    if (*n <= 0)
        return cx_diag_set(d, CX_EINVAL, "%s '%s': expected up to %d positive numbers separated by commas",
                           opt, text, WP_MAX_VALUES);
    return CX_OK;
}

static const cx_opt wp_opts[] = {
    CX_OPT_ROW_LEVEL(wp_args, level),
    {"tols", 0, CX_OPT_STRING, 0, 0, 0, NULL, "LIST", "tolerances", offsetof(wp_args, tols_text), NULL},
    {"sweep", 0, CX_OPT_STRING, 0, 0, 0, NULL, "KEY=LIST",
     "values of the parameter KEY, for every method that has it\n"
     "(default: the parameter each method's paper tunes)", offsetof(wp_args, sweep_text), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

/* CX_OK, CX_OPT_HELP, CX_EINVAL (a malformed line) or the status of
 * bench_common_finish. */
static int wp_parse(int argc, char **argv, wp_args *a, cx_diag *d)
{
    memset(a, 0, sizeof *a);
    bench_common_default(&a->c, 1);
    static const double tols[] = {1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12};
    a->ntols = 6;
    memcpy(a->tols, tols, sizeof tols);
    int npos = 0;
    int r = bench_parse(argc, argv, wp_opts, a, &a->c, &a->scene, 1, &npos, d);
    if (r)
        return r;
    if (a->tols_text)
        CX_TRY(wp_list("--tols", a->tols_text, a->tols, &a->ntols, d));
    if (a->sweep_text) {
        const char *v = a->sweep_text, *eq = strchr(v, '=');
        if (!eq || eq == v)
            return cx_diag_set(d, CX_EINVAL, "--sweep '%s': expected KEY=v1,v2,...", v);
        snprintf(a->sweep_key, sizeof a->sweep_key, "%.*s", (int)(eq - v), v);
        CX_TRY(wp_list("--sweep", eq + 1, a->sweep, &a->nsweep, d));
    }
    if (npos == 0)
        return cx_diag_set(d, CX_EINVAL, "missing SCENE");
    return bench_common_finish(&a->c, d);
}

/* The parameter swept for m and its values (n = 0: defaults only). */
static const char *wp_sweep_of(const wp_args *a, const cx_method *m, double *values, int *n)
{
    cx_param_values pv;
    cx_param_default(&pv, m->params);
    *n = 0;
    if (a->sweep_key[0]) {
        if (cx_param_find(&pv, a->sweep_key) < 0)
            return NULL;
        memcpy(values, a->sweep, sizeof(double) * (size_t)a->nsweep);
        *n = a->nsweep;
        return a->sweep_key;
    }
    for (size_t k = 0; k < sizeof wp_sweeps / sizeof wp_sweeps[0]; k++)
        if (strcmp(wp_sweeps[k].method, m->id) == 0 && cx_param_find(&pv, wp_sweeps[k].key) >= 0) {
            while (*n < 6 && wp_sweeps[k].values[*n] > 0) {
                values[*n] = wp_sweeps[k].values[*n];
                (*n)++;
            }
            return wp_sweeps[k].key;
        }
    return NULL;
}

/* The plot of time against the error in the energy norm, one curve per
 * method and parameter value, the baseline as a vertical line. */
static int bench_wp_plot(const bench_table *t, double baseline, const char *png, cx_diag *d)
{
    bench_plot pl;
    memset(&pl, 0, sizeof pl);
    snprintf(pl.title, sizeof pl.title, "work-precision: %s level %.0f", bench_get_str(t, 0, "scene"),
             t->nrows ? bench_get_num(t, 0, "level") : 0.0);
    snprintf(pl.xlabel, sizeof pl.xlabel, "time (s)");
    /* the reference method's own runs have error 0: the plot draws exact
     * zeros in a labelled band under the decades */
    snprintf(pl.ylabel, sizeof pl.ylabel, "||u - u*||_K / ||u*||_K");
    pl.xlog = pl.ylog = 1;
    for (int r = 0; r < t->nrows; r++) {
        char label[64];
        const char *key = bench_get_str(t, r, "param");
        snprintf(label, sizeof label, "%s%s%s%s%s", bench_get_str(t, r, "method"), key[0] ? " " : "", key,
                 key[0] ? "=" : "", key[0] ? bench_get_str(t, r, "value") : "");
        bench_plot_point(&pl, label, bench_get_num(t, r, "time"), bench_get_num(t, r, "err_u"));
    }
    pl.nvlines = 1;
    pl.vline[0] = baseline;
    snprintf(pl.vlabel[0], sizeof pl.vlabel[0], "factorise + solve K");
    int st = bench_plot_write_png(&pl, png, d);
    bench_plot_clear(&pl);
    return st;
}

/* The fastest run to kkt 1e-8 (the README's time-to-accuracy table). */
static void wp_time_to_accuracy(bench_table *t, double baseline)
{
    int best = -1;
    for (int r = 0; r < t->nrows; r++) {
        double tol = bench_get_num(t, r, "tol"), kkt = bench_get_num(t, r, "kkt");
        if (fabs(tol - 1e-8) < 1e-20 && kkt <= 1e-8 && strcmp(bench_get_str(t, r, "converged"), "yes") == 0 &&
            (best < 0 || bench_get_num(t, r, "time") < bench_get_num(t, best, "time")))
            best = r;
    }
    if (best < 0) {
        bench_meta(t, "time to kkt 1e-8", "no run reached it");
        return;
    }
    (void)baseline;
    bench_meta(t, "time to kkt 1e-8", "%s %s=%s: %.3g s = %.2f x baseline, %ld iterations",
               bench_get_str(t, best, "method"), bench_get_str(t, best, "param"),
               bench_get_str(t, best, "value"), bench_get_num(t, best, "time"),
               bench_get_num(t, best, "ratio"), (long)bench_get_num(t, best, "iterations"));
}

int bench_wp(int argc, char **argv)
{
    cx_diag d;
    cx_diag_clear(&d);
    wp_args a;
    cx_scene sc;
    bench_problem_spec spec;
    int parsed = wp_parse(argc, argv, &a, &d);
    if (parsed == CX_OPT_HELP) {
        bench_help(wp_usage, wp_opts, stdout);
        return CX_EXIT_OK;
    }
    if (parsed)
        return bench_parse_fail("bench wp", parsed, d.msg);
    if (bench_open(&a.c, a.scene, a.level, &sc, &spec, &d))
        return bench_fail("bench wp", d.msg);
    int level = a.level > 0 ? a.level : sc.level;

    /* the problem, the methods, the baseline and the reference */
    cx_problem *p = NULL;
    double t_asm;
    const cx_method *methods[64];
    int nm;
    double baseline;
    bench_ref ref;
    uint64_t shash = bench_scene_hash(&sc);
    if (bench_build(&spec, &p, &t_asm, &d) ||
        bench_methods(a.c.methods, p, spec.law, methods, 64, &nm, &d) ||
        bench_baseline(p, a.c.repeat < 3 ? 3 : a.c.repeat, &baseline, &d)) {
        cx_problem_destroy(&p);
        return bench_fail("bench wp", d.msg);
    }
    int ref_ok = bench_ref_get(&a.c.refs, &spec, p, 10 * a.c.time_limit, &ref, &d) == CX_OK;

    bench_table t;
    bench_table_init(&t, wp_cols);
    bench_meta_machine(&t);
    bench_meta(&t, "benchmark", "wp %s level %d friction %s", sc.id, level, cx_friction_name(spec.law));
    bench_meta(&t, "scene hash", "%016llx (%s)", (unsigned long long)shash, sc.path);
    bench_meta(&t, "problem", "%dD, %d dofs, %d contact points, assembly %.3g s", p->dim, p->n, p->m, t_asm);
    bench_meta(&t, "baseline", "%.4g s (factorise + solve K, median of %d)", baseline,
               a.c.repeat < 3 ? 3 : a.c.repeat);
    if (ref_ok)
        bench_meta(&t, "reference", "%s, kkt %.2e%s, %d iterations, %s (key %016llx, %ld factorisations)",
                   ref.method, ref.kkt, ref.kkt > 1e-12 ? " (above 1e-12: the best it reached)" : "",
                   ref.iterations, bench_ref_origin(&ref), (unsigned long long)ref.hash,
                   ref.work.factorizations);
    else
        bench_meta(&t, "reference", "none: %s", d.msg);

    /* count the runs for the progress bar */
    int total = 0;
    for (int k = 0; k < nm; k++) {
        double vals[WP_MAX_VALUES];
        int nv;
        wp_sweep_of(&a, methods[k], vals, &nv);
        total += (nv ? nv : 1) * a.ntols;
    }
    bench_progress_start(total);
    int done = 0;
    for (int k = 0; k < nm && !bench_interrupted(); k++) {
        const cx_method *m = methods[k];
        double vals[WP_MAX_VALUES];
        int nv;
        const char *key = wp_sweep_of(&a, m, vals, &nv);
        for (int v = 0; v < (nv ? nv : 1) && !bench_interrupted(); v++) {
            cx_param_values pv;
            cx_param_default(&pv, m->params);
            char vtext[32] = "default";
            if (key) {
                snprintf(vtext, sizeof vtext, "%g", vals[v]);
                if (cx_param_set(&pv, key, vtext, m->id, &d)) {
                    fprintf(stderr, "signorini bench wp: %s\n", d.msg);
                    continue;
                }
            }
            for (int q = 0; q < a.ntols && !bench_interrupted(); q++) {
                char label[128];
                snprintf(label, sizeof label, "%s %s=%s tol %.0e", m->id, key ? key : "", vtext, a.tols[q]);
                bench_progress_case(done++, label);
                cx_options opt;
                bench_common_options(&a.c, &opt);
                opt.tol = a.tols[q];
                opt.own_stop = 0;
                bench_result res;
                bench_paired med;
                bench_run_paired(&spec, m, &pv, &opt, ref_ok ? &ref : NULL, a.c.repeat, &res, &med);
                if (res.interrupted)
                    break;
                int r = bench_table_row(&t);
                bench_set_str(&t, r, "scene", "%s", sc.id);
                bench_set_int(&t, r, "level", level);
                bench_set_str(&t, r, "friction", "%s", cx_friction_name(spec.law));
                bench_set_str(&t, r, "method", "%s", m->id);
                bench_set_str(&t, r, "param", "%s", key ? key : "");
                bench_set_str(&t, r, "value", "%s", vtext);
                bench_set_num(&t, r, "tol", a.tols[q]);
                bench_set_result(&t, r, &res);
                if (res.failed)
                    continue;
                bench_set_num(&t, r, "time", med.time);
                bench_set_num(&t, r, "ratio", med.ratio);
                bench_set_num(&t, r, "setup", med.setup);
                bench_set_num(&t, r, "solve", med.solve);
                bench_set_int(&t, r, "factorizations", res.work.factorizations);
                bench_set_int(&t, r, "solves", res.work.solves);
            }
        }
    }
    bench_progress_end();
    wp_time_to_accuracy(&t, baseline);
    if (bench_interrupted())
        bench_meta(&t, "interrupted", "yes: %d of %d runs done", t.nrows, total);
    int code = bench_output(&a.c, &t, &d) ? bench_fail("bench wp", d.msg) : CX_EXIT_OK;
    if (code == CX_EXIT_OK && a.c.png && bench_wp_plot(&t, baseline, a.c.png, &d))
        code = bench_fail("bench wp", d.msg);
    bench_table_clear(&t);
    bench_ref_clear(&ref);
    cx_problem_destroy(&p);
    return bench_interrupted() ? CX_EXIT_INTERRUPTED : code;
}
