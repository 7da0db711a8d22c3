/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini bench paper 001: Table 1 of paper 001 (semismooth* Newton for
 * 3D Tresca friction on the prism), our figures beside the paper's MATLAB
 * ones, and our times as ratios to the baseline of the same level (one
 * analysis + factorisation + solve of K, median of --repeat runs).
 * Per level: assembly (scene build: mesh, K, loads, contact rows), the
 * reduction to the contact face both ways (the factor's trailing block,
 * doc/design.md §5, and one solve per contact dof as the paper), the ssstar
 * solve from zero to its own stopping rule (Newton steps = the paper's
 * iterations), one post-processing expansion, the process's peak memory. */
#include "bench/bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#define P001_LEVELS 8

/* Table 1 of paper 001: level, nodes, assembly, Cholesky + Schur, contact
 * nodes, solver time, iterations. */
static const struct {
    int nodes;
    double assembly, schur;
    int contact;
    double solver;
    int iters;
} p001_table[P001_LEVELS + 1] = {
    {0, 0, 0, 0, 0, 0},
    {225, 0.078, 0.003, 40, 0.017, 5},
    {225, 0.031, 0.003, 40, 0.017, 6},
    {637, 0.094, 0.021, 84, 0.047, 6},
    {1377, 0.141, 0.092, 144, 0.101, 6},
    {4056, 0.516, 0.701, 299, 0.507, 7},
    {9537, 1.297, 3.968, 544, 1.928, 7},
    {27072, 3.156, 32.110, 1104, 9.734, 7},
    {70785, 18.672, 1242.211, 2112, 48.275, 8},
};

static const char p001_usage[] =
    "usage: signorini bench paper 001 [options]\n"
    "\n"
    "Table 1 of paper 001 on scene 'prism': ours beside the paper's.\n";

typedef struct {
    int level, nodes, contact, iters, reason;
    double assembly, baseline, schur, solves, solver, post, kkt, sdiff, rss_mib;
} p001_row;

/* "1-7", "8", "2,4,6" into want[1..8]; 0 or -1 (bad). */
static int p001_levels(const char *text, int want[P001_LEVELS + 1])
{
    memset(want, 0, sizeof(int) * (P001_LEVELS + 1));
    const char *s = text;
    int any = 0;
    while (*s) {
        char *end;
        long a = strtol(s, &end, 10), b = a;
        if (end == s)
            return -1;
        s = end;
        if (*s == '-') {
            b = strtol(s + 1, &end, 10);
            if (end == s + 1)
                return -1;
            s = end;
        }
        if (a < 1 || b > P001_LEVELS || a > b)
            return -1;
        for (long l = a; l <= b; l++)
            want[l] = any = 1;
        if (*s == ',')
            s++;
        else if (*s)
            return -1;
    }
    return any ? 0 : -1;
}

static double p001_rss_mib(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_maxrss / 1024.0;   /* Linux: KiB */
}

static int p001_level(const cx_scene *sc, int level, int repeat, int solves, double gamma,
                      const cx_opt_list *sets, p001_row *row, cx_diag *d)
{
    cx_problem *p = NULL;
    cx_session *s = NULL;
    double *S2 = NULL, *u = NULL;
    memset(row, 0, sizeof *row);
    row->level = level;

    double t0 = cx_clock_now();
    cx_friction_state fr;
    CX_TRY(cx_scene_build(sc, level, &p, &fr, d));
    row->assembly = cx_clock_now() - t0;
    row->nodes = p->mesh->nnodes;
    unsigned char *hit = CX_NEW(unsigned char, p->m > 0 ? p->m : 1);
    if (!hit) {
        cx_problem_destroy(&p);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    for (size_t q = 0; q < cx_csc_nnz(&p->N); q++)
        hit[p->N.i[q]] = 1;
    for (int i = 0; i < p->m; i++)
        row->contact += hit[i];
    cx_free(hit);

    int st = bench_baseline(p, repeat, &row->baseline, d);
    if (st) {
        cx_problem_destroy(&p);
        return st;
    }

    if ((st = cx_session_create(&s, &p, d)) || (st = cx_session_set_friction(s, &fr, d)))
        goto done;
    const cx_problem *pp = cx_session_problem(s);
    cx_schur *S = NULL;
    t0 = cx_clock_now();
    if ((st = cx_session_schur(s, &S, NULL, d)))
        goto done;
    row->schur = cx_clock_now() - t0;

    row->solves = NAN;
    row->sdiff = NAN;
    if (solves) {
        size_t nc = (size_t)pp->nc;
        S2 = CX_NEW(double, nc * nc);
        if (!S2) {
            st = cx_diag_set(d, CX_ENOMEM, "out of memory");
            goto done;
        }
        t0 = cx_clock_now();
        if ((st = cx_schur_by_solves(&pp->K, pp->cdofs, pp->nc, S2, NULL, d)))
            goto done;
        row->solves = cx_clock_now() - t0;
        const double *S1 = cx_schur_matrix(S);
        double diff = 0, big = 0;
        for (size_t k = 0; k < nc * nc; k++) {
            diff = fmax(diff, fabs(S1[k] - S2[k]));
            big = fmax(big, fabs(S1[k]));
        }
        row->sdiff = big > 0 ? diff / big : diff;
        cx_free(S2);
        S2 = NULL;
    }

    /* ssstar from zero to the paper's stopping rule (kkt tolerance out of reach) */
    cx_options o;
    cx_options_default(&o);
    o.tol = 1e-300;
    o.max_iter = 100;
    const cx_method *m = cx_method_find("ssstar");
    cx_param_values pv;
    cx_param_default(&pv, m->params);
    if (gamma > 0) {
        char g[32];
        snprintf(g, sizeof g, "%.17g", gamma);
        if ((st = cx_param_set(&pv, "gamma", g, "ssstar", d)))
            goto done;
    }
    for (int k = 0; k < sets->n; k++)
        if ((st = cx_param_set_pair(&pv, sets->v[k], "ssstar", d)))
            goto done;
    if ((st = cx_session_set_method(s, m, &pv, &o, d)) || (st = bench_solve(s, d)))
        goto done;
    const cx_iterate *it = cx_session_iterate(s);
    row->solver = it->time;
    row->iters = (int)it->inner_total;
    row->kkt = it->kkt;
    row->reason = it->reason;

    /* the post-processing u_i = K_ii^-1 (f_i - K_ic u_c), once */
    u = CX_NEW(double, pp->n);
    double *uc = CX_NEW(double, pp->nc);
    if (!u || !uc) {
        cx_free(uc);
        st = cx_diag_set(d, CX_ENOMEM, "out of memory");
        goto done;
    }
    for (int k = 0; k < pp->nc; k++)
        uc[k] = it->u[pp->cdofs[k]];
    t0 = cx_clock_now();
    st = cx_schur_expand(S, pp->f, uc, u);
    row->post = cx_clock_now() - t0;
    cx_free(uc);
    if (st)
        cx_diag_set(d, st, "post-processing failed");
done:
    row->rss_mib = p001_rss_mib();
    cx_free(S2);
    cx_free(u);
    cx_session_destroy(&s);
    cx_problem_destroy(&p);
    return st;
}

static void p001_print(const p001_row *r, int n, double gamma, const cx_opt_list *sets)
{
    printf("Table 1 (paper 001): ours | the paper's (MATLAB, machine not stated)\n");
    printf("%5s %7s %7s | %9s %8s | %10s %9s %9s | %7s %7s | %9s %8s | %5s %5s\n", "level", "nodes",
           "paper", "assembly", "paper", "Chol+Schur", "per-dof", "paper", "contact", "paper",
           "solver", "paper", "iters", "paper");
    for (int k = 0; k < n; k++) {
        int L = r[k].level;
        char solves[16];
        if (isnan(r[k].solves))
            snprintf(solves, sizeof solves, "%9s", "-");
        else
            snprintf(solves, sizeof solves, "%9.3f", r[k].solves);
        printf("%5d %7d %7d | %9.3f %8.3f | %10.3f %s %9.3f | %7d %7d | %9.3f %8.3f | %5d %5d\n", L,
               r[k].nodes, p001_table[L].nodes, r[k].assembly, p001_table[L].assembly, r[k].schur,
               solves, p001_table[L].schur, r[k].contact, p001_table[L].contact, r[k].solver,
               p001_table[L].solver, r[k].iters, p001_table[L].iters);
    }
    /* the verdict: nodes, contact nodes and Newton steps within 20 % of the
     * paper's, else one line with the reason (times: another machine) */
    int ndiff = 0;
    for (int k = 0; k < n; k++) {
        int L = r[k].level;
        const struct { const char *what; int ours, paper; const char *why; } c[3] = {
            {"nodes", r[k].nodes, p001_table[L].nodes,
             "our level 1 follows the paper's level rule (112 nodes); the paper's Table 1 repeats level 2's mesh there"},
            {"contact nodes", r[k].contact, p001_table[L].contact,
             "the same: our level 1 is coarser than the paper's"},
            {"Newton steps", r[k].iters, p001_table[L].iters,
             "gamma and eps are ours (lost in the paper, see below), and so are the prism's material, "
             "tractions and slip bound; no gamma, tuned or principled, gives 5-7 at every level at "
             "eps = 1e-12; the looser eps = 1e-3 with gamma = 16 (--gamma 16 --set eps=1e-3) gives "
             "6 6 8 7 8 8 8 on levels 1-7 but stops up to 4e-4 short of the solution (README \"Paper 001\")"}};
        for (int q = 0; q < 3; q++)
            if (fabs((double)c[q].ours - c[q].paper) > 0.2 * c[q].paper) {
                printf("  differs: level %d, %s %d against the paper's %d (%+.0f %%): %s\n", L, c[q].what,
                       c[q].ours, c[q].paper, 100.0 * (c[q].ours - c[q].paper) / c[q].paper, c[q].why);
                ndiff++;
            }
    }
    if (n > 0 && !ndiff)
        printf("  verdict: nodes, contact nodes and Newton steps within 20 %% of the paper's (reproduced)\n");
    printf("  times are not compared row by row: the paper's are MATLAB on a machine it does not name\n");
    printf("\nOur times as ratios to the baseline (one factorisation + solve of K, median)\n");
    printf("%5s %10s %9s %10s %9s %8s %8s %8s %9s %9s %9s %s\n", "level", "baseline s", "assembly",
           "Chol+Schur", "per-dof", "solver", "post", "total", "kkt", "S diff", "peak MiB", "outcome");
    for (int k = 0; k < n; k++) {
        double b = r[k].baseline > 0 ? r[k].baseline : 1e-300;
        double total = r[k].assembly + r[k].schur + r[k].solver + r[k].post;
        char solves[16], sdiff[16];
        if (isnan(r[k].solves)) {
            snprintf(solves, sizeof solves, "%9s", "-");
            snprintf(sdiff, sizeof sdiff, "%9s", "-");
        } else {
            snprintf(solves, sizeof solves, "%9.1f", r[k].solves / b);
            snprintf(sdiff, sizeof sdiff, "%9.1e", r[k].sdiff);
        }
        printf("%5d %10.4f %9.1f %10.1f %s %8.1f %8.2f %8.1f %9.1e %s %9.0f %s\n", r[k].level,
               r[k].baseline, r[k].assembly / b, r[k].schur / b, solves, r[k].solver / b,
               r[k].post / b, total / b, r[k].kkt, sdiff, r[k].rss_mib, cx_reason_id(r[k].reason));
    }
    /* the two parameters the paper does not give, as the runs used them */
    const cx_method *m = cx_method_find("ssstar");
    cx_param_values pv;
    cx_param_default(&pv, m->params);
    cx_diag d;
    for (int k = 0; k < sets->n; k++)   /* checked when the runs took them */
        cx_param_set_pair(&pv, sets->v[k], "ssstar", &d);
    double g_def = cx_param_get(&pv, "gamma"), eps = cx_param_get(&pv, "eps");
    printf("\nNot in the paper (lost), chosen by us: gamma = %g, the approximation step\n"
           "gamma / kappa_j (kappa_j the largest diagonal entry of the Schur complement at\n"
           "point j)%s;\neps = %g, the relative residual of the stopping rule%s.\n",
           gamma > 0 ? gamma : g_def,
           gamma > 0 ? " (--gamma; the default is tuned on this prism)"
                     : ", tuned on this prism (gamma <= 1 cycles from level 4 on;\n"
                       "10 to 20 give 8-12 steps on levels 1-7, see src/solve/ssstar.c)",
           eps, eps < 1e-9 ? " (the run ends at the solution)" : " (looser than ours, 1e-12: the run may stop short of the solution; see the kkt column)");
    int lo = 1 << 30, hi = 0, plo = 1 << 30, phi = 0;
    for (int k = 0; k < n; k++) {
        lo = r[k].iters < lo ? r[k].iters : lo, hi = r[k].iters > hi ? r[k].iters : hi;
        int pi = p001_table[r[k].level].iters;
        plo = pi < plo ? pi : plo, phi = pi > phi ? pi : phi;
    }
    if (n > 0)
        printf("Our %d-%d steps against the paper's %d-%d on these levels are with these\n"
               "choices and our material, tractions and slip bound (the paper's are lost too).\n",
               lo, hi, plo, phi);
    printf("\niters: Newton steps of ssstar from zero to its stopping rule (eps %g).\n"
           "solver: ssstar's setup (rotation of the Schur complement, condensed load) and\n"
           "steps, each with an expansion to the full u for the kkt error.\n"
           "total: assembly + Chol+Schur + solver + post. S diff: the two Schur\n"
           "complements, max |difference| / max |entry|. peak MiB: the process so far.\n"
           "Material, tractions and slip bound are our choice (scenes/prism.ini):\n"
           "the paper's values are lost, so its iteration counts compare in shape only.\n",
           eps);
}

typedef struct {
    const char *levels;
    int repeat, no_solves;
    double gamma;
    cx_opt_list sets;
} p001_args;

static int p001_check_levels(const char *text, cx_diag *d)
{
    int want[P001_LEVELS + 1];
    if (p001_levels(text, want))
        return cx_diag_set(d, CX_EINVAL, "--levels '%s': expected levels 1 to 8 as a list, e.g. 1-7 or 2,4,8",
                           text);
    return CX_OK;
}

static const cx_opt p001_opts[] = {
    {"levels", 0, CX_OPT_STRING, 0, 0, 0, NULL, "LIST", "levels, e.g. 1-7 (default), 8, 2,4,6 (1 to 8)",
     offsetof(p001_args, levels), p001_check_levels},
    {"repeat", 0, CX_OPT_INT, 1, 15, 0, NULL, "N", "baseline runs per level, median taken (default 3)",
     offsetof(p001_args, repeat), NULL},
    {"no-solves", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "skip the reduction one solve per contact dof",
     offsetof(p001_args, no_solves), NULL},
    {"gamma", 0, CX_OPT_REAL, 0, 1e6, CX_OPT_MIN_OPEN, NULL, "G",
     "ssstar's approximation step gamma (default: the method's,\ntuned on this prism)",
     offsetof(p001_args, gamma), NULL},
    {"set", 0, CX_OPT_LIST, 0, 0, 0, NULL, "KEY=VALUE",
     "another ssstar parameter, e.g. sweep=seidel, step=compliance,\neps=1e-6 (repeatable; "
     "`signorini methods ssstar` lists them)",
     offsetof(p001_args, sets), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

int bench_paper_001(int argc, char **argv)
{
    p001_args a = {"1-7", 3, 0, 0, {{0}, 0}};
    int code = bench_paper_args("bench paper 001", p001_usage, p001_opts, &a, argc, argv);
    if (code >= 0)
        return code;
    int want[P001_LEVELS + 1], repeat = a.repeat, solves = !a.no_solves;
    p001_levels(a.levels, want);
    cx_diag d;
    {   /* every --set names a parameter of ssstar with a valid value */
        cx_param_values pv;
        cx_param_default(&pv, cx_method_find("ssstar")->params);
        for (int k = 0; k < a.sets.n; k++)
            if (cx_param_set_pair(&pv, a.sets.v[k], "ssstar", &d))
                return bench_usage("bench paper 001", d.msg);
    }
    cx_scene sc;
    if (cx_scene_open("prism", &sc, &d))
        return bench_fail("bench paper 001", d.msg);
    p001_row rows[P001_LEVELS];
    int n = 0;
    for (int L = 1; L <= P001_LEVELS; L++) {
        if (!want[L])
            continue;
        if (p001_level(&sc, L, repeat, solves, a.gamma, &a.sets, &rows[n], &d)) {
            if (!bench_interrupted())
                return bench_fail("bench paper 001", d.msg);
            break;   /* Ctrl-C: the table of the levels that finished */
        }
        fprintf(stderr, "level %d done (%.1f s)\n", L,
                rows[n].assembly + rows[n].schur + (isnan(rows[n].solves) ? 0 : rows[n].solves) +
                    rows[n].solver);
        n++;
    }
    p001_print(rows, n, a.gamma, &a.sets);
    return CX_EXIT_OK;
}
