/* SPDX-License-Identifier: GPL-3.0-or-later */
/* bench/: the benchmarks (signorini bench) and the papers' tables. A
 * program layer above render/, not part of the library.
 *
 * The machinery the benchmarks share (bench/bench_*.c): building and running
 * one case with a time limit, the reference solution and its disk cache,
 * the errors against it, result tables written as text / CSV / JSON through
 * a temporary file and a rename, the progress bar and Ctrl-C.
 *
 * A benchmark is a loop over cases; each case gives one row. A failure of a
 * case (a refused method, a singular system, a time limit) is a row with its
 * reason, never an abort of the benchmark. */
#ifndef CX_BENCH_H
#define CX_BENCH_H

#include "base/args.h"
#include "base/opt_solve.h"
#include "scene/scene.h"

#include <stdint.h>
#include <stdio.h>

/* ---- the problem a case runs on ------------------------------------ */

/* A change applied to the built problem before it is solved (bench stress):
 * returns a status and a diag; arg is the perturbation's own data. */
typedef int (*bench_perturb_fn)(cx_problem *p, const void *arg, cx_diag *d);

typedef struct bench_problem_spec {
    const cx_scene *scene;     /* possibly changed in memory (stress) */
    int level;                 /* <= 0: the scene's */
    cx_friction law;
    double value;              /* Tresca slip bound or Coulomb F */
    const char *variant;       /* "" or the perturbation's key: part of the reference key */
    bench_perturb_fn perturb;  /* may be NULL */
    const void *perturb_arg;
} bench_problem_spec;

/* Build the problem of spec (assembly timed into *t_assemble, may be NULL). */
int bench_build(const bench_problem_spec *spec, cx_problem **p, double *t_assemble, cx_diag *d);
/* The friction state of spec: its law with its value, the scene's other
 * scalar (no per-point values). */
void bench_friction(const bench_problem_spec *spec, cx_friction_state *fr);
/* Build the problem of spec and a new session on it, with spec's friction
 * (*s NULL on failure). */
int bench_session(const bench_problem_spec *spec, cx_session **s, double *t_assemble, cx_diag *d);

/* ---- the reference solution (doc/design.md §3) -------------------------- */

typedef struct bench_ref {
    int n, m, nt;
    double *u, *lN, *lT;
    double uK;                 /* ||u*||_K */
    double lnorm;              /* ||(lN*, lT*)||_2 */
    double kkt;                /* its kkt error */
    int iterations;
    char method[CX_SCENE_NAMELEN];
    int cached;                /* 1: read from the cache, 0: computed now */
    int kept;                  /* 1: in the cache (read or stored) */
    cx_counters work;          /* work of computing it (zero when cached) */
    uint64_t hash;             /* the key it is stored under */
} bench_ref;

/* The reference method for a problem: the first registered entry of a
 * small table per friction law that supports p (see bench_ref.c). */
const cx_method *bench_ref_method(const cx_problem *p, cx_friction law);

/* Key of a reference: FNV-1a over a canonical serialisation of the
 * parsed scene (every field that changes the problem; see bench_ref.c),
 * the level, the law, its value and the variant. Never re-reads the
 * file, so a scene from a pipe or changed in memory has its own key. */
uint64_t bench_ref_key(const bench_problem_spec *spec);
/* The same hash of the parsed scene alone (the headers' "scene hash"). */
uint64_t bench_scene_hash(const cx_scene *s);
/* Where a reference came from, for the headers: "cached", "computed" or
 * "computed, not kept" (the cache is off). */
const char *bench_ref_origin(const bench_ref *r);

/* Where references are kept: --cache DIR, else $XDG_CACHE_HOME/signorini,
 * else ~/.cache/signorini (bench_common_finish). A cache that cannot be
 * created or written gives one warning line on stderr, then the run goes
 * on without it (off). */
typedef struct bench_cache {
    char dir[512];             /* "" : none */
    int off;                   /* 1 once warned: compute, never read or store */
} bench_cache;

/* Read the reference of spec from the cache (its directory created if
 * missing), or compute it with the reference method to kkt < 1e-12 and
 * store it (temp + rename). p is the problem of spec (already built). A
 * cache that fails is turned off with its warning, never an error. */
int bench_ref_get(bench_cache *cache, const bench_problem_spec *spec, const cx_problem *p,
                  double time_limit, bench_ref *r, cx_diag *d);
void bench_ref_clear(bench_ref *r);

/* ---- one run --------------------------------------------------------- */

typedef struct bench_result {
    int failed;                /* could not run: refused, error (msg says) */
    int reason;                /* cx_reason of the run */
    int iterations;
    int active;                /* contact points in contact at the end */
    double kkt;
    double err_u;              /* ||u - u*||_K / ||u*||_K, NaN without reference */
    double err_l;              /* ||l - l*||_2 / ||l*||_2 */
    double t_setup, t_solve;   /* method init, steps (seconds) */
    cx_counters work;          /* the run's counters (cache work included) */
    double heap_mb;            /* heap held by the run at its largest (sampled
                                  after init and every step), MB */
    int nonfinite;             /* NaN/Inf met in the iterate */
    int interrupted;           /* Ctrl-C during the run: not a result */
    char msg[CX_DIAG_LEN];
} bench_result;

/* Run method m with params pv (NULL: defaults) and options opt on the
 * session s (the method is set, the run starts from its initial guess;
 * the session's operator cache is kept, so pass a fresh session for a
 * timing that includes the setup). ref may be NULL. Never fails: a
 * failure is described in r. */
void bench_run(cx_session *s, const cx_method *m, const cx_param_values *pv,
               const cx_options *opt, const bench_ref *ref, bench_result *r);

/* The most runs a median is taken over (--repeat). */
#define BENCH_MAX_REPEAT 1000

/* Medians over the runs of one case, each run on a fresh problem paired
 * with the baseline of that problem measured just before it. */
typedef struct bench_paired {
    int runs;                  /* runs that finished (0: failed or interrupted) */
    double time;               /* setup + solve, seconds */
    double ratio;              /* time / its baseline */
    double setup, solve;
    double baseline;           /* factorise + solve K */
    double assembly;           /* build of the problem */
    double assembly_ratio;     /* assembly / its baseline */
    double setup_ratio;        /* setup / its baseline */
    double end_ratio;          /* (assembly + setup + solve) / its baseline: end to end */
    double peak_mb;            /* the largest heap_mb of the runs */
} bench_paired;

/* The measurement protocol of wp and scaling: repeat times, build the
 * problem of spec (assembly timed), measure its baseline, run m on a new
 * session of it. res is the last run's result (failed: the message of a
 * build or of the run; interrupted: Ctrl-C before a result); out the
 * medians of the runs that finished. */
void bench_run_paired(const bench_problem_spec *spec, const cx_method *m, const cx_param_values *pv,
                      const cx_options *opt, const bench_ref *ref, int repeat, bench_result *res,
                      bench_paired *out);

/* The baseline of p (doc/design.md §5: analyse + factorise + solve K): the
 * median of n timings (n clipped to [1, BENCH_MAX_REPEAT]). */
int bench_baseline(const cx_problem *p, int n, double *seconds, cx_diag *d);

/* Errors of (u, lN, lT) against ref on problem p. */
void bench_errors(const cx_problem *p, cx_friction law, const bench_ref *ref, const double *u,
                  const double *lN, const double *lT, double *err_u, double *err_l);

/* The methods to run on p: the ids in list ("a,b,c"; NULL: every
 * registered method supporting p's law, dimension and bodies: none is
 * CX_EUNSUPPORTED). An unknown id is an error naming it. */
int bench_methods(const char *list, const cx_problem *p, cx_friction law, const cx_method **out,
                  int max, int *count, cx_diag *d);

/* ---- tables ------------------------------------------------------------ */

#define BENCH_MAX_COLS 32
#define BENCH_CELL_LEN 200

typedef struct bench_cell {
    int kind;                  /* 0 empty, 1 number, 2 integer, 3 text */
    double v;
    char s[BENCH_CELL_LEN];
} bench_cell;

typedef struct bench_table {
    int ncols;
    const char *cols[BENCH_MAX_COLS];
    int nrows, cap;
    bench_cell *cells;         /* nrows * ncols */
    /* header: "key: value" lines kept in order */
    int nmeta;
    char meta[24][2][160];
} bench_table;

void bench_table_init(bench_table *t, const char *const *cols);   /* NULL-terminated */
void bench_table_clear(bench_table *t);
/* A new empty row; returns its index (exits on OOM: cli may fail fast). */
int bench_table_row(bench_table *t);
void bench_set_num(bench_table *t, int row, const char *col, double v);
void bench_set_int(bench_table *t, int row, const char *col, long v);
void bench_set_str(bench_table *t, int row, const char *col, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
double bench_get_num(const bench_table *t, int row, const char *col);   /* NaN if not a number */
const char *bench_get_str(const bench_table *t, int row, const char *col);
void bench_meta(bench_table *t, const char *key, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* The common header: program version, machine (cores, BLAS), date. */
void bench_meta_machine(bench_table *t);

void bench_table_print(const bench_table *t, FILE *out);
/* Write the CSV ("# key: value" lines, then the header row and the rows)
 * or the JSON object {"meta": {...}, "rows": [{...}]} (typed: numbers and
 * booleans where the text is one, bench_table.c) to path through a
 * temporary file and a rename; path "-" is stdout. */
int bench_table_write_csv(const bench_table *t, const char *path, cx_diag *d);
int bench_table_write_json(const bench_table *t, const char *path, cx_diag *d);

/* The outcome columns of a row from a result: converged (yes / no / n/a),
 * reason, iterations, kkt, err_u, err_l, nonfinite, message (the columns
 * the table has). */
void bench_set_result(bench_table *t, int r, const bench_result *res);

/* ---- options every benchmark takes ------------------------------------ */

typedef struct bench_common {
    const char *csv;           /* --csv FILE */
    int json;                  /* --json: the JSON on stdout instead of the table */
    const char *png;           /* --png FILE (refused until the renderer lands) */
    const char *cache;         /* --cache DIR (default: see bench_cache) */
    const char *methods;       /* --methods a,b */
    int friction;              /* --friction LAW (-1: the scene's) */
    double value;              /* --slip / --F value (NaN: the scene's) */
    double time_limit;         /* --time-limit S per run (default 60) */
    int max_iter;              /* --max-iter N (0: the default) */
    int repeat;                /* --repeat N: timings are medians of N runs */
    int threads;               /* --threads N (0: as the environment says) */
    bench_cache refs;          /* the reference cache the options give */
} bench_common;

/* The options every benchmark takes (values into a bench_common). */
extern const cx_opt bench_common_opts[];

/* The one argument loop of the benchmarks: the kind's own table (into
 * args) and the common table (into c), with up to maxpos positional
 * arguments (SCENE...) into pos. CX_OK; CX_OPT_HELP when -h/--help was
 * given (nothing printed: see bench_help); CX_EINVAL with one line in d
 * for a malformed command line. */
int bench_parse(int argc, char **argv, const cx_opt *own, void *args, bench_common *c, const char **pos,
                int maxpos, int *npos, cx_diag *d);
/* The argument loop of a paper driver (its own table only; argv[0] is the
 * paper id): -1 to go on, else the exit status: 0 after printing the help
 * (usage, then the table), CX_EXIT_USAGE after one line on stderr. */
int bench_paper_args(const char *cmd, const char *usage, const cx_opt *opts, void *args, int argc,
                     char **argv);
/* The help of a benchmark: usage, then its own options and the common
 * ones, from their tables. */
void bench_help(const char *usage, const cx_opt *own, FILE *out);
/* The exit status of a failed parse or check: CX_EINVAL is a malformed
 * command line (one line "signorini CMD: msg (see ...)", CX_EXIT_USAGE),
 * any other status an error of the run (CX_EXIT_ERROR). */
int bench_parse_fail(const char *cmd, int status, const char *msg);
/* Open the scene id (or path) into sc and describe the problem to run:
 * spec = sc at level (<= 0: the scene's), under the law and value the
 * common options give. */
int bench_open(const bench_common *c, const char *id, int level, cx_scene *sc,
               bench_problem_spec *spec, cx_diag *d);
void bench_common_default(bench_common *c, int repeat);
/* Check what needs checking once the options are read (PNG), set the
 * thread counts and the reference cache's directory. */
int bench_common_finish(bench_common *c, cx_diag *d);
extern const char bench_common_help[];
/* If argv asks for --help / -h: print usage and the common options, return 1. */
int bench_print_help(int argc, char **argv, const char *usage);
/* The friction law and value of a scene under the common options. */
int bench_common_law(const bench_common *c, const cx_scene *s, cx_friction *law, double *value,
                     cx_diag *d);
/* The options of a run under the common options. */
void bench_common_options(const bench_common *c, cx_options *o);
/* Write the table as the options say: the table (or JSON) on stdout,
 * CSV to --csv. */
int bench_output(const bench_common *c, const bench_table *t, cx_diag *d);

/* ---- plots (the renderer wires in here) ------------------------------ */

#define BENCH_PLOT_MAX_SERIES 32
typedef struct bench_series {
    char label[64];
    int n;
    double *x, *y;             /* owned (cx_free) */
} bench_series;

typedef struct bench_plot {
    char title[160];
    char xlabel[64], ylabel[64];
    int xlog, ylog;
    int nseries;
    bench_series series[BENCH_PLOT_MAX_SERIES];
    int nvlines;
    double vline[4];
    char vlabel[4][64];
} bench_plot;

/* Add a point to the series called label (created on first use). */
void bench_plot_point(bench_plot *pl, const char *label, double x, double y);
void bench_plot_clear(bench_plot *pl);
/* Write the plot as a PNG through render/plot.h (temporary file + rename);
 * CX_EUNSUPPORTED in a build without the renderer. */
int bench_plot_write_png(const bench_plot *pl, const char *path, cx_diag *d);
extern const char bench_png_missing[];

/* ---- progress and Ctrl-C ------------------------------------------------ */

/* From now on Ctrl-C (SIGINT) sets a flag that the runs and the loops of
 * the benchmark poll, instead of ending the process; a second Ctrl-C ends
 * it at once (130), removing a temporary file being written. */
void bench_catch_sigint(void);
/* Start a bar of total cases (drawn on stderr only when it is a
 * terminal). */
void bench_progress_start(int total);
/* Case k (0-based) starts: label names it. */
void bench_progress_case(int k, const char *label);
/* Erase the bar; from now on (only output is left to write) Ctrl-C ends
 * the program at once with status 130, removing a temporary file being
 * written (cx_outfile_abandon_pending). */
void bench_progress_end(void);
/* 1 once Ctrl-C was pressed. */
int bench_interrupted(void);
/* An observer that stops a run on Ctrl-C. */
int bench_observer(void *ctx, const cx_session *s, const cx_iterate *it);
/* cx_solver_solve under bench_observer, for the paper drivers: a run
 * stopped by Ctrl-C is CX_EIO "interrupted (Ctrl-C)", never a result. */
int bench_solve(cx_session *s, cx_diag *d);
/* cx_solver_solve with obs, such that Ctrl-C cancels the run inside its
 * step (the session's cancel flag), not only between steps. */
int bench_solve_watched(cx_session *s, cx_observer obs, void *ctx, cx_diag *d);

/* ---- the benchmarks ---------------------------------------------------- */

int bench_wp(int argc, char **argv);
int bench_scaling(int argc, char **argv);
int bench_stress(int argc, char **argv);

/* signorini bench ARGS (argv[0] is "bench"): the exit status. */
int bench_main(int argc, char **argv);
/* The papers' drivers (bench/paper_NNN.c); argv[0] is the paper id. */
int bench_paper_000(int argc, char **argv);
int bench_paper_001(int argc, char **argv);
int bench_paper_002(int argc, char **argv);
int bench_paper_003(int argc, char **argv);

/* Print "signorini CMD: message" on stderr and return CX_EXIT_ERROR. */
int bench_fail(const char *cmd, const char *msg);
/* A malformed command line: "signorini CMD: message (see 'signorini CMD
 * --help')" on stderr; returns CX_EXIT_USAGE. */
int bench_usage(const char *cmd, const char *msg);

/* Median of v[0..n-1] (reorders v); NaN when n <= 0. The one median of
 * the benchmarks: every "median of N" goes through it. */
double bench_median(double *v, int n);

#endif
