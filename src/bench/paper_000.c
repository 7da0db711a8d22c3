/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini bench paper 000: Tables 1 and 2 of paper 000 on 'twoblocks-paper'.
 *
 * Each row is a level L = m/3 (m = 150, 165, ..., 450 contact nodes,
 * n = 4m(m/3 + 1) dofs). After the operator cache is warmed (the Cholesky
 * factor of K, K^-1 f, b and alpha_max: the setup every dual method
 * shares), each method runs with the paper's eps_lambda = 1e-6 on its own
 * criterion: MPRGP (abar = 2/alpha_max, ||g^P|| <= eps ||b||), SNM1
 * (rho = 1, exact inner solves: CG from zero on each face to 1e-12
 * relative to the face's right-hand side, as Matlab's pcg does), SNM2
 * (rho = 1, adaptive), SNM3 (rho = 1/alpha_max, adaptive), SNM4
 * (globalised, rho = 20/alpha_max). nK is the number of solves with the
 * factor of K during the run; kmax the outer iterations. Times are ratios
 * to the baseline (one factorisation and solve of K, median of three) of
 * the same level.
 *
 * The scene is the reading of the paper's set-up that comes closest to its
 * counts (scenes/twoblocks-paper.ini; README "The papers" lists every
 * reading tested). Under each table one line per cell that differs from
 * the paper by more than 20 % (nK or kmax) gives the reason; at the end,
 * the kkt error of each run at its stop. */
#include "bench/bench.h"

#include <math.h>
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
    const char *sets[6];
} p000_run;

static const p000_run p000_runs[5] = {
    {"MPRGP", "mprgp", {"eps=1e-6", "abar_scale=2", NULL}},
    {"SNM1", "ssn-tresca-dual",
     {"eps=1e-6", "rho_unit=abs", "inner=fixed", "inner_start=cold", "inner_ref=face", NULL}},
    {"SNM2", "ssn-tresca-dual", {"eps=1e-6", "rho_unit=abs", "inner=adaptive", NULL}},
    {"SNM3", "ssn-tresca-dual", {"eps=1e-6", "rho_unit=amax", "inner=adaptive", NULL}},
    {"SNM4", "ssn-tresca-glob", {"eps=1e-6", "rho_scale=20", NULL}},
};

typedef struct {
    long nk;
    int kmax, converged;
    double kkt, time;
} p000_result;

static int p000_method(cx_session *s, const p000_run *r, double abar, p000_result *out, cx_diag *d)
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
    if (abar > 0 && strcmp(r->id, "mprgp") == 0) {
        char a[48];
        snprintf(a, sizeof a, "abar_scale=%.17g", abar);
        CX_TRY(cx_param_set_pair(&v, a, r->id, d));
    }
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

static int p000_row(const cx_scene *sc, int row, double slip, double slip_nodal, double abar, int repeat,
                    p000_result res[5], double *t_asm, double *t_setup, double *t_base, int *n, int *m, cx_diag *d)
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
    /* the reading 'g is a nodal force': the same bound at every contact
     * node, not multiplied by the node's share of the boundary */
    double *nodal = NULL;
    if (slip_nodal > 0) {
        if (!(nodal = CX_NEW(double, p->m > 0 ? p->m : 1))) {
            cx_problem_destroy(&p);
            return cx_diag_set(d, CX_ENOMEM, "out of memory");
        }
        for (int i = 0; i < p->m; i++)
            nodal[i] = slip_nodal;
        fr.law = CX_FRICTION_TRESCA;
        fr.slip_bound = slip_nodal;
        fr.s = nodal;   /* copied by the session */
    }
    CX_TRY(cx_session_create(&s, &p, d));
    st = cx_session_set_friction(s, &fr, d);
    cx_free(nodal);
    if (st || (slip > 0 && (st = cx_session_set_tresca(s, slip, d))))
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
            st = p000_method(s, &p000_runs[k], abar, &res[k], d);
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

/* Why a cell still differs from the paper by more than 20 % (README "The
 * papers", Paper 000: what each reading of the set-up gave). */
static const char *const p000_reason[5] = {
    "MPRGP: not the stop (eps 1e-8: +8 %) nor Gamma (0.5-5: -10..+2 %); with abar = 1/alpha_max "
    "instead of the stated 2/alpha_max (--abar 1) rows 1 and 10 give 178 and 260 against 181 and 246: "
    "the paper's alpha_max may be an estimate about twice too high",
    "SNM1: 10-11 Newton steps where the paper has 12-14: under this load the sets change fewer times from "
    "lambda0 = 0 (rho plays no role with exact solves, as the paper notes); each step costs what the "
    "paper's does (60-100 CG steps)",
    "SNM2: the paper's adaptive rule (its ref. [21]) is lost; 19-56 products for 7-17 Newton steps is "
    "below what a converged run needs here (the paper's own MPRGP needs 181-302): with 1-2 CG steps "
    "per Newton step the step criterion err <= 1e-6 stops early (our SNM3 with eta = 0.5: 5/5 at kkt 0.4); "
    "our rule (eta = 0.1) runs to kkt 1e-11 .. 2e-9",
    "SNM3: as SNM2 (the paper's adaptive rule is lost; its counts are below what a converged run "
    "needs here)",
    "SNM4: the paper gives its globalisation only in words; our rule (research/seed_benchmarks.md "
    "2.4) ends an outer iteration at the box or a failed proportioning test, about 4.5 products per "
    "outer iteration where the paper's take 1.7: a comparable nK in fewer outer iterations"};

static double p000_rel(double ours, double paper) { return paper > 0 ? (ours - paper) / paper : 0; }

/* One line per differing cell of method k in rows [first, last): returns
 * the number of lines. */
static int p000_differences(int k, int first, int last, const int *n, const int *m, p000_result (*res)[5])
{
    int lines = 0;
    for (int row = first; row < last; row++) {
        const p000_result *r = &res[row - first][k];
        int pk = k == 0 ? p000_mprgp[row] : p000_snm[k - 1][row][0];
        int pm = k == 0 ? 0 : p000_snm[k - 1][row][1];
        double dn = p000_rel((double)r->nk, pk), dk = k == 0 ? 0 : p000_rel(r->kmax, pm);
        if (fabs(dn) <= 0.2 && fabs(dk) <= 0.2 && r->converged)
            continue;
        char ours[32], paper[32], what[64];
        p000_cell(ours, sizeof ours, r, k > 0);
        if (k == 0)
            snprintf(paper, sizeof paper, "%d", pk), snprintf(what, sizeof what, "nK %+.0f %%", 100 * dn);
        else
            snprintf(paper, sizeof paper, "%d/%d", pk, pm),
                snprintf(what, sizeof what, "nK %+.0f %%, kmax %+.0f %%", 100 * dn, 100 * dk);
        printf("  differs %d/%d %s %s (paper %s, %s): %s%s\n", n[row - first], m[row - first],
               p000_runs[k].label, ours, paper, what, r->converged ? "" : "not converged; ", p000_reason[k]);
        lines++;
    }
    return lines;
}

typedef struct {
    int rows, all, first, repeat;
    double slip, slip_nodal, abar;
    const char *scene;
} p000_args;

static const char p000_usage[] =
    "usage: signorini bench paper 000 [--rows N | --all] [--first R] [--slip S | --slip-nodal G]\n"
    "                                 [--abar A] [--scene ID] [--repeat R]\n"
    "\n"
    "Tables 1 and 2 of paper 000 on 'twoblocks-paper' (the reading of the paper's set-up\n"
    "closest to its counts; README \"The papers\"): rows m = 150, 165, ... (default 10 rows\n"
    "from the first, up to n = 109440; --all: 21 rows). Under each table, one line per\n"
    "cell more than 20 % off the paper, with the reason.\n";

static const cx_opt p000_opts[] = {
    {"rows", 0, CX_OPT_INT, 1, 21, 0, NULL, "N", "the number of rows (default 10)", offsetof(p000_args, rows),
     NULL},
    {"all", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "all 21 rows", offsetof(p000_args, all), NULL},
    {"first", 0, CX_OPT_INT, 1, 21, 0, NULL, "R", "start at row R (default 1)", offsetof(p000_args, first),
     NULL},
    {"slip", 0, CX_OPT_REAL, 0, INFINITY, CX_OPT_MIN_OPEN | CX_OPT_MAX_OPEN, NULL, "S",
     "the Tresca bound, a traction (default: the scene's 1.7e7)", offsetof(p000_args, slip), NULL},
    {"slip-nodal", 0, CX_OPT_REAL, 0, INFINITY, CX_OPT_MIN_OPEN | CX_OPT_MAX_OPEN, NULL, "G",
     "the Tresca bound as a nodal force at every contact node (not multiplied by the boundary share)",
     offsetof(p000_args, slip_nodal), NULL},
    {"abar", 0, CX_OPT_REAL, 0, 2, CX_OPT_MIN_OPEN, NULL, "A",
     "MPRGP's steplength A/alpha_max (the paper's 2 by default)", offsetof(p000_args, abar), NULL},
    {"scene", 0, CX_OPT_STRING, 0, 0, 0, NULL, "ID",
     "another scene, e.g. 'twoblocks' (the top load as printed, -7e7 - (1/3)e7 x)", offsetof(p000_args, scene),
     NULL},
    {"repeat", 0, CX_OPT_INT, 1, 63, 0, NULL, "R",
     "times are medians of R runs (the baseline of max(R, 3))", offsetof(p000_args, repeat), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

int bench_paper_000(int argc, char **argv)
{
    p000_args a = {10, 0, 1, 1, 0, 0, 0, "twoblocks-paper"};
    int code = bench_paper_args("bench paper 000", p000_usage, p000_opts, &a, argc, argv);
    if (code >= 0)
        return code;
    int rows = a.all ? 21 : a.rows, repeat = a.repeat, first = a.first - 1;
    double slip = a.slip, slip_nodal = a.slip_nodal, abar = a.abar;
    const char *scene = a.scene;
    cx_diag d;
    cx_diag_clear(&d);
    if (slip > 0 && slip_nodal > 0) {
        fprintf(stderr, "signorini bench paper 000: --slip and --slip-nodal: give one of them\n");
        return CX_EXIT_USAGE;
    }
    cx_scene sc;
    if (cx_scene_open(scene, &sc, &d))
        return bench_fail("bench paper 000", d.msg);
    int last = first + rows < 21 ? first + rows : 21, nr = last - first;
    int n[21], m[21];
    p000_result res[21][5];
    double tsnm4[21];

    printf("paper 000, Table 1: scene %s, eps_lambda = 1e-6; ours (paper)\n"
           "nK = solves with the factor of K in the run (setup excluded), kmax = outer iterations;\n"
           "time = run time / baseline (factorise + solve K, median of 3; base in seconds, the\n"
           "only absolute figure); asm = assembly, setup = factor of K + b + alpha_max; '!' = the paper's criterion not met\n\n",
           sc.id);
    printf("%-11s %-11s %-15s %-13s %-13s | %-6s %-6s %-6s %-6s %-6s %-6s %-8s\n", "n/m", "MPRGP", "SNM1",
           "SNM2", "SNM3", "asm", "setup", "MPRGP", "SNM1", "SNM2", "SNM3", "base (s)");
    fflush(stdout);
    for (int row = first; row < last; row++) {
        p000_result *r = res[row - first];
        double ta, tsetup = 0, tb;
        if (p000_row(&sc, row, slip, slip_nodal, abar, repeat, r, &ta, &tsetup, &tb, &n[row - first], &m[row - first],
                     &d))
            return bench_interrupted() ? CX_EXIT_INTERRUPTED : bench_fail("bench paper 000", d.msg);
        char nm[24], cell[4][32], both[4][64];
        snprintf(nm, sizeof nm, "%d/%d", n[row - first], m[row - first]);
        for (int k = 0; k < 4; k++) {
            p000_cell(cell[k], sizeof cell[k], &r[k], k > 0);
            if (k == 0)
                snprintf(both[k], sizeof both[k], "%.31s(%d)", cell[k], p000_mprgp[row]);
            else
                snprintf(both[k], sizeof both[k], "%.31s(%d/%d)", cell[k], p000_snm[k - 1][row][0],
                         p000_snm[k - 1][row][1]);
        }
        printf("%-11s %-11s %-15s %-13s %-13s | %-6.2f %-6.2f %-6.2f %-6.2f %-6.2f %-6.2f %-8.3g\n", nm, both[0],
               both[1], both[2], both[3], ta / tb, tsetup / tb, r[0].time / tb, r[1].time / tb, r[2].time / tb,
               r[3].time / tb, tb);
        tsnm4[row - first] = r[4].time / tb;
        fflush(stdout);
    }
    int dl = 0;
    for (int k = 0; k < 4; k++)
        dl += p000_differences(k, first, last, n, m, res);
    if (!dl)
        printf("  every cell within 20 %% of the paper\n");

    printf("\npaper 000, Table 2 (with the globalisation): scene %s; ours (paper)\n\n", sc.id);
    printf("%-11s %-11s %-15s | %-6s\n", "n/m", "MPRGP", "SNM4", "SNM4");
    for (int i = 0; i < nr; i++) {
        int row = first + i;
        char nm[24], c0[32], c4[32], b0[64], b4[64];
        snprintf(nm, sizeof nm, "%d/%d", n[i], m[i]);
        p000_cell(c0, sizeof c0, &res[i][0], 0);
        p000_cell(c4, sizeof c4, &res[i][4], 1);
        snprintf(b0, sizeof b0, "%.31s(%d)", c0, p000_mprgp[row]);
        snprintf(b4, sizeof b4, "%.31s(%d/%d)", c4, p000_snm[3][row][0], p000_snm[3][row][1]);
        printf("%-11s %-11s %-15s | %-6.2f\n", nm, b0, b4, tsnm4[i]);
    }
    dl = p000_differences(0, first, last, n, m, res) + p000_differences(4, first, last, n, m, res);
    if (!dl)
        printf("  every cell within 20 %% of the paper\n");

    /* each run stops on the paper's own criterion, not on ours: how close
     * to the solution that is */
    printf("\nkkt error at the stop (each method stopped by the paper's criterion, eps_lambda = 1e-6)\n");
    for (int i = 0; i < nr; i++) {
        printf("  kkt %d/%d:", n[i], m[i]);
        for (int k = 0; k < 5; k++)
            printf(" %s %.1e%s", p000_runs[k].label, res[i][k].kkt, k < 4 ? "," : "\n");
    }
    return CX_EXIT_OK;
}
