/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini bench paper 000: Tables 1 and 2 of paper 000 on 'twoblocks'.
 *
 * Each row is a level L = m/3 (m = 150, 165, ..., 450 contact nodes,
 * n = 4m(m/3 + 1) dofs). After the operator cache is warmed (the Cholesky
 * factor of K, K^-1 f, b and alpha_max: the setup every dual method
 * shares), each method runs with the paper's eps_lambda = 1e-6 on its own
 * criterion: MPRGP (abar = 2/alpha_max), SNM1 (rho = 1, inner 1e-12),
 * SNM2 (rho = 1, adaptive), SNM3 (rho = 1/alpha_max, adaptive), SNM4
 * (globalised, rho = 20/alpha_max). nK is the number of solves with the
 * factor of K during the run; kmax the outer iterations. Times are ratios
 * to the baseline (one factorisation and solve of K, median of three) of
 * the same level. */
#include "bench/bench.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 000 Tables 1 and 2: MPRGP nK; SNM1-4 nK / kmax. */
static const int p000_mprgp[21] = {181, 181, 193, 210, 213, 217, 221, 231, 224, 246, 248,
                                   265, 255, 263, 266, 288, 281, 296, 291, 298, 302};
static const int p000_snm[4][21][2] = {
    {{712, 12}, {747, 12}, {826, 13}, {802, 12}, {828, 12}, {898, 13}, {889, 12}, {895, 12}, {981, 13},
     {997, 13}, {1067, 14}, {1043, 13}, {1082, 13}, {1140, 14}, {1110, 13}, {1130, 13}, {1198, 14},
     {1173, 13}, {1205, 13}, {1270, 14}, {1224, 13}},
    {{19, 7}, {55, 13}, {57, 12}, {50, 12}, {35, 11}, {41, 11}, {46, 12}, {55, 14}, {42, 11}, {35, 11},
     {47, 12}, {37, 11}, {46, 13}, {39, 11}, {41, 11}, {45, 11}, {49, 13}, {49, 13}, {37, 11}, {47, 12},
     {55, 14}},
    {{19, 7}, {63, 12}, {37, 11}, {50, 12}, {35, 11}, {41, 11}, {46, 12}, {49, 13}, {42, 11}, {35, 11},
     {47, 12}, {37, 11}, {37, 11}, {39, 11}, {41, 11}, {45, 11}, {66, 17}, {49, 13}, {37, 11}, {47, 12},
     {56, 14}},
    {{95, 56}, {100, 57}, {111, 62}, {113, 67}, {119, 72}, {139, 81}, {116, 66}, {117, 69}, {142, 84},
     {127, 74}, {146, 88}, {142, 82}, {156, 93}, {145, 85}, {144, 83}, {147, 86}, {151, 87}, {151, 86},
     {175, 105}, {159, 94}, {149, 85}}};

typedef struct {
    const char *label, *id;
    const char *sets[4];
} p000_run;

static const p000_run p000_runs[5] = {
    {"MPRGP", "mprgp", {"eps=1e-6", "abar_scale=2", NULL}},
    {"SNM1", "ssn-tresca-dual", {"eps=1e-6", "rho_unit=abs", "inner=fixed", NULL}},
    {"SNM2", "ssn-tresca-dual", {"eps=1e-6", "rho_unit=abs", "inner=adaptive", NULL}},
    {"SNM3", "ssn-tresca-dual", {"eps=1e-6", "rho_unit=amax", "inner=adaptive", NULL}},
    {"SNM4", "ssn-tresca-glob", {"eps=1e-6", "rho_scale=20", NULL}},
};

typedef struct {
    long nk;
    int kmax, converged;
    double kkt, time;
} p000_result;

static int p000_method(cx_session *s, const p000_run *r, p000_result *out, cx_diag *d)
{
    const cx_method *m = cx_method_find(r->id);
    cx_param_values v;
    cx_options o;
    cx_options_default(&o);
    o.tol = 0;             /* the paper's own criterion decides */
    o.own_stop = 1;
    o.max_iter = 1000000;
    o.stall_window = 0;
    cx_param_default(&v, m->params);
    for (int k = 0; r->sets[k]; k++)
        CX_TRY(cx_param_set_pair(&v, r->sets[k], r->id, d));
    CX_TRY(cx_session_set_method(s, m, &v, &o, d));
    long s0 = cx_session_iterate(s)->counters.solves;
    CX_TRY(bench_solve(s, d));
    const cx_iterate *it = cx_session_iterate(s);
    out->nk = it->counters.solves - s0;
    out->kmax = it->iter;
    out->converged = cx_reason_criterion_met(it->reason);   /* tol 0: the paper's criterion */
    out->kkt = it->kkt;
    out->time = it->time;
    return CX_OK;
}

static int p000_row(const cx_scene *sc, int row, double slip, int repeat, p000_result res[5], double *t_asm,
                    double *t_setup, double *t_base, int *n, int *m, cx_diag *d)
{
    cx_problem *p = NULL;
    cx_session *s = NULL;
    double t0 = cx_clock_now();
    cx_friction_state fr;
    CX_TRY(cx_scene_build(sc, 50 + 5 * row, &p, &fr, d));
    *t_asm = cx_clock_now() - t0;
    int st = bench_baseline(p, repeat > 3 ? repeat : 3, t_base, d);
    if (st) {
        cx_problem_destroy(&p);
        return st;
    }
    *n = p->n;
    *m = p->m;
    CX_TRY(cx_session_create(&s, &p, d));
    if ((st = cx_session_set_friction(s, &fr, d)) ||
        (slip > 0 && (st = cx_session_set_tresca(s, slip, d))))
        goto done;
    /* warm the operator cache: factor of K, b, alpha_max */
    t0 = cx_clock_now();
    if ((st = cx_session_set_method(s, cx_method_find("mprgp"), NULL, NULL, d)))
        goto done;
    *t_setup = cx_clock_now() - t0;
    /* the counts repeat exactly; the time is the median of the runs */
    for (int k = 0; k < 5 && !st; k++) {
        double t[BENCH_MAX_REPEAT];
        int nt = 0;
        for (int r = 0; r < repeat && r < BENCH_MAX_REPEAT && !st; r++) {
            st = p000_method(s, &p000_runs[k], &res[k], d);
            t[nt++] = res[k].time;
        }
        res[k].time = bench_median(t, nt);
    }
done:
    cx_session_destroy(&s);
    return st;
}

static void p000_cell(char *buf, size_t len, const p000_result *r, int with_k)
{
    if (with_k)
        snprintf(buf, len, "%ld/%d%s", r->nk, r->kmax, r->converged ? "" : "!");
    else
        snprintf(buf, len, "%ld%s", r->nk, r->converged ? "" : "!");
}

typedef struct {
    int rows, all, first, repeat;
    double slip;
} p000_args;

static const char p000_usage[] =
    "usage: signorini bench paper 000 [--rows N | --all] [--first R] [--slip S] [--repeat R]\n"
    "\n"
    "Tables 1 and 2 of paper 000 on 'twoblocks': rows m = 150, 165, ... (default 10\n"
    "rows from the first, up to n = 109440; --all: 21 rows).\n";

static const cx_opt p000_opts[] = {
    {"rows", 0, CX_OPT_INT, 1, 21, 0, NULL, "N", "the number of rows (default 10)", offsetof(p000_args, rows),
     NULL},
    {"all", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "all 21 rows", offsetof(p000_args, all), NULL},
    {"first", 0, CX_OPT_INT, 1, 21, 0, NULL, "R", "start at row R (default 1)", offsetof(p000_args, first),
     NULL},
    {"slip", 0, CX_OPT_REAL, 0, INFINITY, CX_OPT_MIN_OPEN | CX_OPT_MAX_OPEN, NULL, "S",
     "the Tresca bound, a traction (default: the scene's 1.7e7)", offsetof(p000_args, slip), NULL},
    {"repeat", 0, CX_OPT_INT, 1, 63, 0, NULL, "R",
     "times are medians of R runs (the baseline of max(R, 3))", offsetof(p000_args, repeat), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

int bench_paper_000(int argc, char **argv)
{
    p000_args a = {10, 0, 1, 1, 0};
    int code = bench_paper_args("bench paper 000", p000_usage, p000_opts, &a, argc, argv);
    if (code >= 0)
        return code;
    int rows = a.all ? 21 : a.rows, repeat = a.repeat, first = a.first - 1;
    double slip = a.slip;
    cx_diag d;
    cx_diag_clear(&d);
    cx_scene sc;
    if (cx_scene_open("twoblocks", &sc, &d))
        return bench_fail("bench paper 000", d.msg);

    printf("paper 000, Tables 1 and 2: scene twoblocks, eps_lambda = 1e-6; ours (paper)\n"
           "nK = solves with the factor of K in the run (setup excluded), kmax = outer iterations;\n"
           "time = run time / baseline (factorise + solve K, median of 3; base in seconds, the\n"
           "only absolute figure); asm = assembly, setup = factor of K + b + alpha_max; '!' = the paper's criterion not met\n\n");
    printf("%-11s %-11s %-15s %-12s %-12s %-13s | %-6s %-6s %-6s %-6s %-6s %-6s %-6s %-8s\n", "n/m", "MPRGP",
           "SNM1", "SNM2", "SNM3", "SNM4", "asm", "setup", "MPRGP", "SNM1", "SNM2", "SNM3", "SNM4",
           "base (s)");
    fflush(stdout);
    for (int row = first; row < first + rows && row < 21; row++) {
        p000_result res[5];
        double ta, tsetup = 0, tb;
        int n, m;
        if (p000_row(&sc, row, slip, repeat, res, &ta, &tsetup, &tb, &n, &m, &d))
            return bench_interrupted() ? CX_EXIT_INTERRUPTED : bench_fail("bench paper 000", d.msg);
        char nm[24], cell[5][32], both[5][64];
        snprintf(nm, sizeof nm, "%d/%d", n, m);
        for (int k = 0; k < 5; k++) {
            p000_cell(cell[k], sizeof cell[k], &res[k], k > 0);
            if (k == 0)
                snprintf(both[k], sizeof both[k], "%.31s(%d)", cell[k], p000_mprgp[row]);
            else
                snprintf(both[k], sizeof both[k], "%.31s(%d/%d)", cell[k], p000_snm[k - 1][row][0],
                         p000_snm[k - 1][row][1]);
        }
        printf("%-11s %-11s %-15s %-12s %-12s %-13s | %-6.2f %-6.2f %-6.2f %-6.2f %-6.2f %-6.2f %-6.2f %-8.3g\n",
               nm, both[0], both[1], both[2], both[3], both[4], ta / tb, tsetup / tb, res[0].time / tb,
               res[1].time / tb, res[2].time / tb, res[3].time / tb, res[4].time / tb, tb);
        fflush(stdout);
    }
    return CX_EXIT_OK;
}
