/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini bench scaling: per mesh level, the size of the problem, the
 * assembly, the baseline (one factorisation + solve of K) and each method's
 * time as a ratio to it, iterations and peak memory against the factor's;
 * the slope of log time against log dofs per method. */
#include "bench/bench.h"
#include "out/outfile.h"
#include "cx_config.h"

#if CX_HAVE_PETSC
#include "petsc/petsc.h"
#endif

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

static const char scaling_usage[] =
    "usage: signorini bench scaling SCENE --levels a..b [options]\n"
    "\n"
    "Mesh scaling: for each level (a..b doubles from a up to b; or a list a,b,c):\n"
    "dofs, contact points, assembly, the baseline (factorise + solve K), the\n"
    "factor's size and the fill (predicted nnz(L)) of the contact-last\n"
    "orderings (CAMD; AMD then contact last, METIS on the interior, when\n"
    "analysed) with the one chosen,\n"
    "and for each method its time (setup + solve, from a fresh\n"
    "session) as a ratio to the baseline (ratio; setup/baseline; end_to_end,\n"
    "assembly + setup + solve), iterations, peak memory of the run against the\n"
    "factor's, and the error against the reference solution. Timings are\n"
    "medians of --repeat runs (default 3), ratios medians of each run's ratio\n"
    "to the baseline measured just before it.\n"
    "\n"
    "--backend direct,petsc adds, per level, the PETSc backend's runs of the\n"
    "same methods where it has them (default ssn-tresca on both), on the MPI\n"
    "ranks the program was started with (mpirun -n N; rank 0 prints), and ends\n"
    "with the level from which PETSc is faster than the direct path. Its time is\n"
    "the parallel assembly of K + the method (the serial build of the problem,\n"
    "done on every rank, is the assembly column); its peak_mb the processes'\n"
    "peak resident memory summed over the ranks (the direct rows: the run's\n"
    "heap at its largest). --backend petsc alone measures no baseline and\n"
    "computes no reference (levels a direct factorisation cannot reach).\n";

static const char *const scaling_cols[] = {
    "scene", "level", "friction", "backend", "ranks", "dofs", "contact", "assembly", "baseline", "assembly/baseline",
    "factor_mb", "ordering", "fill_camd", "fill_amd", "fill_metis", "method", "converged", "reason", "iterations", "time", "ratio", "setup", "setup/baseline", "solve", "end_to_end",
    "peak_mb", "peak/factor", "krylov", "kkt", "err_u", "message", NULL};

#define SCALING_MAX_LEVELS 24

typedef struct {
    bench_common c;
    const char *scene;
    const char *levels_text;   /* --levels as given */
    int levels[SCALING_MAX_LEVELS];
    int nlevels;
    double tol;
    int no_ref;
    const char *backend_text;  /* --backend as given */
    int direct, petsc;         /* the backends to run */
    cx_opt_list sets;          /* --set KEY=VALUE: the direct methods' parameters */
} scaling_args;

/* --backend direct|petsc|direct,petsc (either order). */
static int scaling_backends(const char *v, scaling_args *a, cx_diag *d)
{
    char buf[64];
    a->direct = a->petsc = 0;
    if (snprintf(buf, sizeof buf, "%s", v) >= (int)sizeof buf)
        return cx_diag_set(d, CX_EINVAL, "--backend '%s': expected direct, petsc or direct,petsc", v);
    for (char *save = NULL, *w = strtok_r(buf, ",", &save); w; w = strtok_r(NULL, ",", &save)) {
        if (strcmp(w, "direct") == 0)
            a->direct = 1;
        else if (strcmp(w, "petsc") == 0)
            a->petsc = 1;
        else
            return cx_diag_set(d, CX_EINVAL, "--backend '%s': expected direct, petsc or direct,petsc", v);
    }
    if (!a->direct && !a->petsc)
        return cx_diag_set(d, CX_EINVAL, "--backend '%s': expected direct, petsc or direct,petsc", v);
#if !CX_HAVE_PETSC
    if (a->petsc)
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "--backend petsc: this build has no PETSc backend (meson setup -Dpetsc=enabled)");
#endif
    return CX_OK;
}

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
    {"backend", 0, CX_OPT_STRING, 0, 0, 0, NULL, "direct|petsc|direct,petsc",
     "the backends to run (default direct)", offsetof(scaling_args, backend_text), NULL},
    {"set", 0, CX_OPT_LIST, 0, 0, 0, NULL, "KEY=VALUE",
     "a parameter of the direct path's methods (repeatable, with --methods; each\n"
     "method takes the keys it has, as solve --set: pdas --set start=closed)",
     offsetof(scaling_args, sets), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

/* Does pv's table have the key of "key=value"? */
static int scaling_param_has(const cx_param_values *pv, const char *pair)
{
    char key[64];
    size_t n = strcspn(pair, "=");
    snprintf(key, sizeof key, "%.*s", (int)(n < sizeof key ? n : sizeof key - 1), pair);
    return cx_param_find(pv, key) >= 0;
}

/* m's parameters: its defaults with the --set pairs it has (checked when
 * parsed). */
static void scaling_params(const scaling_args *a, const cx_method *m, cx_param_values *pv)
{
    cx_param_default(pv, m->params);
    for (int i = 0; i < a->sets.n; i++)
        if (scaling_param_has(pv, a->sets.v[i]))
            cx_param_set_pair(pv, a->sets.v[i], m->id, NULL);
}

static int scaling_check_sets(const scaling_args *a, cx_diag *d);

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
    a->direct = 1;
    if (a->backend_text)
        CX_TRY(scaling_backends(a->backend_text, a, d));
    /* both backends compare one method each by default: the one they share */
    if (a->petsc && !a->c.methods)
        a->c.methods = "ssn-tresca";
    if (npos == 0)
        return cx_diag_set(d, CX_EINVAL, "missing SCENE");
    if (a->nlevels == 0)
        return cx_diag_set(d, CX_EINVAL, "missing --levels a..b");
    CX_TRY(scaling_check_sets(a, d));
    return bench_common_finish(&a->c, d);
}

/* Every --set names a parameter of one of the --methods at least, with a
 * value it takes. */
static int scaling_check_sets(const scaling_args *a, cx_diag *d)
{
    if (a->sets.n && !a->c.methods)
        return cx_diag_set(d, CX_EINVAL, "--set '%s': name the methods it is for (--methods)", a->sets.v[0]);
    for (int i = 0; i < a->sets.n; i++) {
        int had = 0;
        char buf[512];
        snprintf(buf, sizeof buf, "%s", a->c.methods ? a->c.methods : "");
        for (char *save = NULL, *id = strtok_r(buf, ",", &save); id; id = strtok_r(NULL, ",", &save)) {
            const cx_method *m = cx_method_find(id);
            cx_param_values pv;
            if (!m)
                continue;
            cx_param_default(&pv, m->params);
            char owner[64];
            snprintf(owner, sizeof owner, "method '%s'", m->id);
            if (scaling_param_has(&pv, a->sets.v[i])) {
                CX_TRY(cx_param_set_pair(&pv, a->sets.v[i], owner, d));
                had = 1;
            }
        }
        if (!had)
            return cx_diag_set(d, CX_EINVAL, "--set '%s': none of --methods %s has that parameter",
                               a->sets.v[i], a->c.methods);
    }
    return CX_OK;
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

/* The ids of list (NULL: none given) that one backend has: into out as
 * "a,b" (empty: none of them). petsc 0 asks the direct path's registry. */
static void scaling_method_list(const char *list, int petsc, char *out, size_t len)
{
    char buf[512];
    size_t n = 0;
    out[0] = 0;
    snprintf(buf, sizeof buf, "%s", list ? list : "");
    for (char *save = NULL, *id = strtok_r(buf, ",", &save); id; id = strtok_r(NULL, ",", &save)) {
        int has = petsc ? 0 : cx_method_find(id) != NULL;
#if CX_HAVE_PETSC
        if (petsc)
            has = cx_petsc_method_find(id) != NULL;
#endif
        if (has && n < len)
            n += (size_t)snprintf(out + n, len - n, "%s%s", n ? "," : "", id);
    }
}

/* The columns a level shares between its rows. */
static void scaling_row_level(bench_table *t, int r, const cx_scene *sc, const bench_problem_spec *spec,
                              const cx_problem *p, const char *backend, int ranks)
{
    bench_set_str(t, r, "scene", "%s", sc->id);
    bench_set_int(t, r, "level", spec->level);
    bench_set_str(t, r, "friction", "%s", cx_friction_name(spec->law));
    bench_set_str(t, r, "backend", "%s", backend);
    bench_set_int(t, r, "ranks", ranks);
    bench_set_int(t, r, "dofs", p->n);
    bench_set_int(t, r, "contact", p->m);
}

#if CX_HAVE_PETSC
/* The process's peak resident memory starts again from what it holds now
 * (Linux: /proc/self/clear_refs "5"), so that a PETSc run's peak is its
 * own, not the direct path's run before it on rank 0 (its freed heap
 * given back first). Where the kernel refuses, the peak is that of the
 * process so far (the header says so). */
static int scaling_reset_peak(void)
{
#ifdef __GLIBC__
    malloc_trim(0);   /* the direct path's freed heap back to the system first */
#endif
    FILE *f = fopen("/proc/self/clear_refs", "w");
    if (!f)
        return 0;
    int ok = fputs("5", f) >= 0;
    return fclose(f) == 0 && ok;
}

/* This process's peak resident memory since the last reset (VmHWM, in
 * bytes), or -1. Not getrusage's ru_maxrss, which keeps the peak of the
 * threads that have ended (the direct path's) across the reset. */
static double scaling_own_peak(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    double kb = -1;
    while (f && fgets(line, sizeof line, f))
        if (strncmp(line, "VmHWM:", 6) == 0)
            kb = atof(line + 6);
    if (f)
        fclose(f);
    return kb >= 0 ? 1024.0 * kb : -1;
}

static int scaling_petsc_observer(void *ctx, const cx_petsc_step *st)
{
    (void)ctx, (void)st;
    return bench_interrupted();
}

/* The PETSc backend's rows of one level: each method in ids run repeat
 * times on p (built on every rank), its medians. Collective: every rank
 * calls it with the same arguments; rank 0 fills the table. t_base <= 0:
 * no baseline (no ratios). */
static void scaling_petsc_rows(bench_table *t, const cx_scene *sc, const bench_problem_spec *spec,
                               const cx_problem *p, const char *ids, const cx_options *opt, int repeat,
                               double t_asm, double t_base, const bench_ref *ref, int *peak_reset)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", ids);
    cx_friction_state fr;
    bench_friction(spec, &fr);
    int rank = cx_petsc_rank(), n = repeat < BENCH_MAX_REPEAT ? repeat : BENCH_MAX_REPEAT;
    for (char *save = NULL, *id = strtok_r(buf, ",", &save); id && !bench_interrupted();
         id = strtok_r(NULL, ",", &save)) {
        double tt[BENCH_MAX_REPEAT], ts[BENCH_MAX_REPEAT], tv[BENCH_MAX_REPEAT];
        double peak = 0;
        int runs = 0;
        cx_petsc_result r = {0};
        bench_result res;
        memset(&res, 0, sizeof res);
        cx_diag d;
        cx_diag_clear(&d);
        if (cx_petsc_check(p, id, spec->law, &d)) {
            res.failed = 1;
            snprintf(res.msg, sizeof res.msg, "%s", d.msg);
        }
        for (int k = 0; k < n && !res.failed && !bench_interrupted(); k++) {
            cx_petsc_result_clear(&r);
            *peak_reset = scaling_reset_peak();
            if (cx_petsc_solve(p, &fr, id, opt, scaling_petsc_observer, NULL, &r, &d)) {
                res.failed = 1;
                snprintf(res.msg, sizeof res.msg, "%s", d.msg);
                break;
            }
            if (r.reason == CX_CANCELLED)
                break;
            /* rank 0's own peak from VmHWM (it ran the direct path before),
             * the others' as the backend measured them */
            double mem = 0, own = *peak_reset ? scaling_own_peak() : -1;
            for (int q = 0; q < r.nranks; q++)
                mem += q == rank && own >= 0 ? own : r.mem_peak[q];
            peak = fmax(peak, mem / 1048576.0);
            ts[runs] = r.t_setup;
            tv[runs] = r.t_solve;
            tt[runs] = r.t_setup + r.t_solve;
            runs++;
        }
        if (rank == 0 && (res.failed || runs > 0)) {
            int row = bench_table_row(t);
            scaling_row_level(t, row, sc, spec, p, "petsc", cx_petsc_size());
            bench_set_str(t, row, "method", "%s", id);
            if (!res.failed) {
                res.reason = r.reason;
                res.iterations = r.iterations;
                res.kkt = r.kkt;
                res.err_u = res.err_l = NAN;
                if (ref)
                    bench_errors(p, spec->law, ref, r.u, r.lN, r.lT, &res.err_u, &res.err_l);
                snprintf(res.msg, sizeof res.msg, "%s", r.message);
                double time = bench_median(tt, runs), setup = bench_median(ts, runs);
                bench_set_num(t, row, "assembly", t_asm);
                bench_set_num(t, row, "time", time);
                bench_set_num(t, row, "setup", setup);
                bench_set_num(t, row, "solve", bench_median(tv, runs));
                bench_set_num(t, row, "peak_mb", peak);
                bench_set_int(t, row, "krylov", r.krylov);
                if (t_base > 0) {
                    bench_set_num(t, row, "baseline", t_base);
                    bench_set_num(t, row, "assembly/baseline", t_asm / t_base);
                    bench_set_num(t, row, "ratio", time / t_base);
                    bench_set_num(t, row, "setup/baseline", setup / t_base);
                    bench_set_num(t, row, "end_to_end", (t_asm + time) / t_base);
                }
            }
            bench_set_result(t, row, &res);
        }
        cx_petsc_result_clear(&r);
    }
}
#endif

#if CX_HAVE_PETSC
/* A rank that runs the PETSc backend alone (no direct path, baseline or
 * reference here: every rank but 0, and rank 0 with --backend petsc)
 * builds the scene without the serial K, which the backend does not read
 * (it assembles its own); bench_build's checks otherwise. A perturbed
 * problem is built whole (its perturbation may read K). */
static int scaling_build_petsc(const bench_problem_spec *spec, cx_problem **p, double *t_assemble, cx_diag *d)
{
    if (spec->perturb)
        return bench_build(spec, p, t_assemble, d);
    double t0 = cx_clock_now();
    CX_TRY(cx_scene_build_flags(spec->scene, spec->level, CX_SCENE_BUILD_NO_K, p, NULL, d));
    cx_friction_state fr;
    bench_friction(spec, &fr);
    int st = cx_friction_check(&fr, 0, d);
    if (st != CX_OK) {
        cx_problem_destroy(p);
        return st;
    }
    *t_assemble = cx_clock_now() - t0;
    return CX_OK;
}
#endif

/* The level from which the PETSc backend is faster than the direct path,
 * for one method both ran (method NULL: the fastest converged row of each
 * backend per level): the first level of the last run of levels, up to
 * the largest one run, at which every PETSc time is below the direct
 * path's; none when the largest level the two share has PETSc slower.
 * Into the header as "crossover (method)". Returns 1 if the two share a
 * level. */
static int scaling_crossover(bench_table *t, const char *method)
{
    int lev[SCALING_MAX_LEVELS], n = 0;
    double td[SCALING_MAX_LEVELS], tp[SCALING_MAX_LEVELS];
    for (int r = 0; r < t->nrows; r++) {
        const char *be = bench_get_str(t, r, "backend");
        double time = bench_get_num(t, r, "time");
        if ((method && strcmp(bench_get_str(t, r, "method"), method) != 0) ||
            strcmp(bench_get_str(t, r, "converged"), "yes") != 0 || !(time > 0))
            continue;
        int level = (int)bench_get_num(t, r, "level"), k;
        for (k = 0; k < n && lev[k] != level; k++)
            ;
        if (k == n) {
            if (n == SCALING_MAX_LEVELS)
                continue;
            lev[n] = level;
            td[n] = tp[n] = INFINITY;
            n++;
        }
        double *slot = strcmp(be, "petsc") == 0 ? &tp[k] : &td[k];
        *slot = fmin(*slot, time);
    }
    /* the levels both backends finished, in the order run (ascending) */
    int m = 0;
    for (int k = 0; k < n; k++)
        if (isfinite(td[k]) && isfinite(tp[k])) {
            lev[m] = lev[k], td[m] = td[k], tp[m] = tp[k];
            m++;
        }
    if (m == 0)
        return 0;
    char key[96];
    snprintf(key, sizeof key, "crossover (%s)", method ? method : "fastest of each");
    int first = m;
    while (first > 0 && tp[first - 1] < td[first - 1])
        first--;
    if (first == m)
        bench_meta(t, key, "not within the levels run (level %d: petsc %.3g s, direct %.3g s)", lev[m - 1],
                   tp[m - 1], td[m - 1]);
    else
        bench_meta(t, key, "level %d (petsc %.3g s against direct %.3g s; faster at every level run above it)",
                   lev[first], tp[first], td[first]);
    return 1;
}

/* The levels, on every rank (rank 0 alone prints, measures the baseline
 * and runs the direct path); the exit status. */
static int bench_scaling_run(scaling_args *a, int rank, int nranks)
{
    cx_diag d;
    cx_diag_clear(&d);
    cx_scene sc;
    bench_problem_spec spec;
    if (bench_open(&a->c, a->scene, 0, &sc, &spec, &d))
        return rank == 0 ? bench_fail("bench scaling", d.msg) : CX_EXIT_ERROR;
    uint64_t shash = bench_scene_hash(&sc);
    for (int k = 0; k < a->nlevels; k++)
        if (a->levels[k] > sc.level_max) {
            cx_diag_set(&d, CX_EINVAL, "--levels: level %d: scene '%s' allows levels 1 to %d", a->levels[k],
                        sc.id, sc.level_max);
            return rank == 0 ? bench_fail("bench scaling", d.msg) : CX_EXIT_ERROR;
        }
    char direct_ids[512] = "", petsc_ids[512] = "";
    int direct_all = a->direct && !a->c.methods;   /* every method that supports the problem */
    if (a->direct && a->c.methods) {
        scaling_method_list(a->c.methods, 0, direct_ids, sizeof direct_ids);
        if (!direct_ids[0] && rank == 0)
            fprintf(stderr, "signorini bench scaling: the direct path has none of --methods %s\n", a->c.methods);
    }
    if (a->petsc) {
        scaling_method_list(a->c.methods, 1, petsc_ids, sizeof petsc_ids);
        if (!petsc_ids[0] && rank == 0)
            fprintf(stderr, "signorini bench scaling: the PETSc backend has none of --methods %s\n", a->c.methods);
    }
    int run_direct = rank == 0 && (direct_all || direct_ids[0]);
    int need_base = rank == 0 && a->direct;   /* petsc alone: levels a factorisation may not reach */

    bench_table t;
    bench_table_init(&t, scaling_cols);
    bench_meta_machine(&t);
    bench_meta(&t, "benchmark", "scaling %s friction %s, tol %g, medians of %d", sc.id,
               cx_friction_name(spec.law), a->tol, a->c.repeat);
    bench_meta(&t, "scene hash", "%016llx (%s)", (unsigned long long)shash, sc.path);
    if (a->sets.n) {
        char sets[512];
        size_t n = 0;
        sets[0] = '\0';
        for (int i = 0; i < a->sets.n && n < sizeof sets; i++)
            n += (size_t)snprintf(sets + n, sizeof sets - n, "%s%s", i ? " " : "", a->sets.v[i]);
        bench_meta(&t, "parameters", "%s (the direct path's methods that have them; the others' defaults)", sets);
    }
    if (a->petsc)
        bench_meta(&t, "backends", "%s%s (%d MPI rank%s; the direct path on rank 0)", a->direct ? "direct, " : "",
                   "petsc", nranks, nranks > 1 ? "s" : "");
    if (rank == 0)
        bench_progress_start(a->nlevels);
    int code = CX_EXIT_OK, peak_reset = 1;
    for (int l = 0; l < a->nlevels && !bench_interrupted(); l++) {
        spec.level = a->levels[l];
        char label[64];
        snprintf(label, sizeof label, "level %d", spec.level);
        if (rank == 0)
            bench_progress_case(l, label);
        cx_problem *p = NULL;
        double t_asm = NAN, t_base = NAN, fmb = NAN;
        cx_schur_ordering ord = {0};
        ord.chosen = CX_ORDER_AUTO;
        const cx_method *methods[64];
        int nm = 0, st;
        if (need_base)
            st = scaling_level_costs(&spec, a->c.repeat, &t_asm, &t_base, &fmb, &ord, &p, &d);
#if CX_HAVE_PETSC
        else if (a->petsc)
            st = scaling_build_petsc(&spec, &p, &t_asm, &d);
#endif
        else
            st = bench_build(&spec, &p, &t_asm, &d);
        if (!st && run_direct && bench_methods(direct_all ? NULL : direct_ids, p, spec.law, methods, 64, &nm, &d)) {
            if (!a->petsc)
                st = CX_EUNSUPPORTED;
            else   /* the other ranks are on their way to the PETSc runs: go with them */
                bench_meta(&t, "direct path", "%s", d.msg);
        }
        if (st) {
            /* the same on every rank but for the direct path's (rank 0):
             * the others end with it, their collectives not yet entered */
            cx_problem_destroy(&p);
            code = rank == 0 ? bench_fail("bench scaling", d.msg) : CX_EXIT_ERROR;
            break;
        }
        bench_ref ref = {0};
        int ref_ok = rank == 0 && a->direct && !a->no_ref &&
                     bench_ref_get(&a->c.refs, &spec, p, 10 * a->c.time_limit, &ref, &d) == CX_OK;
        if (rank == 0 && a->direct && !a->no_ref)
            bench_meta(&t, label, ref_ok ? "reference %s kkt %.2e%s (%s)" : "no reference: %s",
                       ref_ok ? ref.method : d.msg, ref.kkt,
                       ref.kkt > 1e-12 ? " (above 1e-12: the best it reached)" : "",
                       bench_ref_origin(&ref));
        for (int k = 0; k < nm && !bench_interrupted(); k++) {
            cx_options opt;
            bench_common_options(&a->c, &opt);
            opt.tol = a->tol;
            bench_result res;
            bench_paired med;
            cx_param_values pv;
            scaling_params(a, methods[k], &pv);
            bench_run_paired(&spec, methods[k], a->sets.n ? &pv : NULL, &opt, ref_ok ? &ref : NULL, a->c.repeat,
                             &res, &med);
            if (res.interrupted)
                break;
            int r = bench_table_row(&t);
            scaling_row_level(&t, r, &sc, &spec, p, "direct", 1);
            bench_set_num(&t, r, "assembly", t_asm);
            bench_set_num(&t, r, "baseline", t_base);
            bench_set_num(&t, r, "assembly/baseline", t_asm / t_base);
            bench_set_num(&t, r, "factor_mb", fmb);
            if (ord.chosen != CX_ORDER_AUTO) {
                bench_set_str(&t, r, "ordering", "%s",
                              ord.chosen == CX_ORDER_METIS ? "metis" : ord.chosen == CX_ORDER_AMD ? "amd" : "camd");
                bench_set_num(&t, r, "fill_camd", ord.lnz[CX_ORDER_CAMD]);
                if (ord.tried_amd)
                    bench_set_num(&t, r, "fill_amd", ord.lnz[CX_ORDER_AMD]);
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
#if CX_HAVE_PETSC
        if (a->petsc && petsc_ids[0]) {
            cx_options opt;
            bench_common_options(&a->c, &opt);
            opt.tol = a->tol;
            scaling_petsc_rows(&t, &sc, &spec, p, petsc_ids, &opt, a->c.repeat, t_asm, need_base ? t_base : 0,
                               ref_ok ? &ref : NULL, &peak_reset);
        }
#endif
        bench_ref_clear(&ref);
        cx_problem_destroy(&p);
    }
    if (rank == 0)
        bench_progress_end();
    if (code == CX_EXIT_OK && rank == 0) {
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
        if (a->direct && a->petsc) {
            /* per method both ran; else the fastest of each backend */
            int shared = 0;
            char buf[512];
            snprintf(buf, sizeof buf, "%s", petsc_ids);
            for (char *save = NULL, *id = strtok_r(buf, ",", &save); id; id = strtok_r(NULL, ",", &save))
                shared += scaling_crossover(&t, id);
            if (!shared && !scaling_crossover(&t, NULL))
                bench_meta(&t, "crossover", "not within the levels run (no level where both backends converged)");
        }
        if (a->petsc)
            bench_meta(&t, "peak_mb", "direct: the run's heap at its largest; petsc: the processes' peak resident "
                       "memory summed over the ranks (libraries, mesh and K on every rank included)%s",
                       peak_reset ? "" : ", since they started (/proc/self/clear_refs refused)");
        if (bench_interrupted())
            bench_meta(&t, "interrupted", "yes: %d rows done", t.nrows);
        if (bench_output(&a->c, &t, &d))
            code = bench_fail("bench scaling", d.msg);
        else if (a->c.png && bench_scaling_plot(&t, a->c.png, &d))
            code = bench_fail("bench scaling", d.msg);
        else if (!a->c.json)
            /* the answer the comparison is for, again under the table (the
             * header's copy goes into the CSV and JSON) */
            for (int k = 0; k < t.nmeta; k++)
                if (strncmp(t.meta[k][0], "crossover", 9) == 0)
                    fprintf(cx_outfile_is_stdout(a->c.csv) || cx_outfile_is_stdout(a->c.png) ? stderr : stdout,
                            "%s: %s\n", t.meta[k][0], t.meta[k][1]);
    }
    bench_table_clear(&t);
    return bench_interrupted() ? CX_EXIT_INTERRUPTED : code;
}

int bench_scaling(int argc, char **argv)
{
    cx_diag d;
    cx_diag_clear(&d);
    scaling_args a;
    int parsed = scaling_parse(argc, argv, &a, &d);
    if (parsed == CX_OPT_HELP) {
        bench_help(scaling_usage, scaling_opts, stdout);
        return CX_EXIT_OK;
    }
    if (parsed)
        return bench_parse_fail("bench scaling", parsed, d.msg);
    int rank = 0, nranks = 1;
#if CX_HAVE_PETSC
    /* every rank runs this function; only rank 0 prints and runs the
     * direct path (the others wait for it in the PETSc runs' collectives) */
    if (a.petsc) {
        if (cx_petsc_initialize(&d))
            return bench_fail("bench scaling", d.msg);
        rank = cx_petsc_rank();
        nranks = cx_petsc_size();
    }
#endif
    int code = bench_scaling_run(&a, rank, nranks);
#if CX_HAVE_PETSC
    if (a.petsc)
        cx_petsc_finalize();
#endif
    return code;
}
