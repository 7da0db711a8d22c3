/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini bench paper 003: Ainsworth & Mihai's masonry walls. Tables 1-2
 * (bodies, unknowns n, constraints n_c: ours beside the paper's) and
 * Tables 3-7 (time per method and geometry beside the paper's CPU times,
 * as a ratio to the baseline of the same problem measured in the same run,
 * with iterations and the kkt error). Each solve gets a fresh session, so
 * its time includes building its operators (the LCP transform, factors). */
#include "bench/bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

static const char p003_usage[] =
    "usage: signorini bench paper 003 [options]\n"
    "\n"
    "Masonry walls: Tables 1-7 of paper 003 beside ours.\n";

static const int p003_levels[] = {5, 10, 15, 20, 25, 50, 75, 100, 125, 150, 175, 200, 225};
#define P003_NLEVELS 13
static const char *const p003_geo[3] = {"stackbond", "runningbond", "laminae"};

/* Tables 1-2 of the paper (research notes §4.4, cleaned). */
static const long p003_nb[3][P003_NLEVELS] = {
    {25, 100, 225, 400, 625, 2500, 5625, 10000, 15625, 22500, 30625, 40000, 50625},
    {15, 55, 120, 210, 325, 1275, 2850, 5050, 7875, 11325, 15400, 20100, 25425},
    {5, 10, 15, 20, 25, 50, 75, 100, 125, 150, 175, 200, 225}};
static const long p003_n[3][P003_NLEVELS] = {
    {411, 1725, 3936, 7050, 11061, 44625, 100686, 179250, 280311, 403875, 549936, 718500, 909561},
    {355, 1461, 3317, 5924, 9280, 37311, 84092, 149624, 233905, 336936, 458717, 599249, 758530},
    {298, 1198, 2698, 4798, 7498, 29998, 67498, 119998, 187498, 269998, 367498, 479998, 607498}};
static const long p003_nc[3][P003_NLEVELS] = {
    {126, 555, 1281, 2310, 3636, 14775, 33411, 59550, 93186, 134325, 182961, 239100, 302736},
    {96, 417, 963, 1735, 2731, 11087, 25068, 44675, 69906, 100762, 137243, 179350, 227081},
    {49, 199, 449, 799, 1249, 4999, 11249, 19999, 31249, 44999, 61249, 79999, 101249}};

/* Tables 3-7: the paper's CPU times (s) per geometry and level; 0 = not
 * given. Tables 5 and 6 have two rows each (ours and the paper's variant). */
typedef const double p003_times[3][P003_NLEVELS];
static p003_times p003_paper_pdas = {
    {0.03, 0.07, 0.19, 0.46, 0.90, 7.00, 30.46, 78.73, 180.87, 358.26, 685.34, 1193.68, 2080.83},
    {0.01, 0.13, 0.47, 0.80, 1.67, 17.85, 74.91, 180.03, 524.65, 951.23, 2407.42, 4266.14, 6232.46},
    {0.01, 0.04, 0.09, 0.20, 0.32, 2.36, 27.49, 70.12, 155.27, 303.13, 486.24, 900.73, 1429.85}};
static p003_times p003_paper_pdpc = {
    {0.22, 1.02, 2.53, 4.26, 6.97, 32.24, 84.14, 152.46, 259.07, 419.73, 621.93, 869.02, 1334.01},
    {0.25, 1.20, 3.29, 5.92, 10.98, 69.65, 194.67, 459.27, 873.51, 1421.10, 2275.98, 3365.44, 4634.23},
    {0.12, 0.58, 1.37, 2.65, 4.41, 21.44, 61.04, 123.76, 194.22, 333.70, 434.53, 818.48, 971.18}};

typedef struct {
    int table;
    const char *title;
    const char *method, *set;
    int big;                      /* runs up to --max-level (else --small) */
    const double (*paper)[P003_NLEVELS];
} p003_table;

static const p003_table p003_tables[] = {
    {3, "PSOR + projection", "psor", NULL, 0,
     (p003_times){{0.61, 8.75, 60.27, 264.27},
                  {4.92, 147.23, 1187.39, 6344.70}, {1.36, 25.24, 151.38, 587.78}}},
    {4, "LSSNN + projection", "lssnn", NULL, 0,
     (p003_times){{0.01, 0.05, 0.14, 0.26, 0.45, 4.84},
                  {0.10, 1.79, 9.70, 36.05, 92.25, 2974.0},
                  {0.03, 0.24, 0.89, 2.55, 5.17, 77.09}}},
    {5, "PDAS + projection", "pdas", NULL, 1, p003_paper_pdas},
    {5, "PDAS, plain block pivoting (the paper's steps, search=0) + projection", "pdas", "search=0", 0,
     p003_paper_pdas},
    {6, "PDPC (unregularised) + projection", "pdpc", NULL, 1, p003_paper_pdpc},
    {6, "PDPC with the paper's sigma = 0 / 0.99 alternation + projection", "pdpc", "sigma=paper", 1,
     p003_paper_pdpc},
    {7, "Graves (reduced Schur LCP)", "graves", NULL, 0,
     (p003_times){{1.19, 1.17, 10.18, 41.85},
                  {0.26, 28.06, 530.76, 5445.91}, {0.01, 0.32, 2.50, 11.53}}},
    {7, "LSSNN + projection (reduced Schur LCP)", "lssnn", "schur=1", 0,
     (p003_times){{0.01, 0.07, 0.62, 2.25}, {0.03, 0.75, 10.43, 74.34}, {0.01, 0.03, 0.14, 0.50}}},
    {7, "PDAS + projection (reduced Schur LCP)", "pdas", "schur=1", 0,
     (p003_times){{0.02, 0.01, 0.03, 0.02}, {0.01, 0.04, 0.18, 0.62}, {0.0, 0.02, 0.01, 0.02}}},
    {7, "PDPC (reduced Schur LCP)", "pdpc", "schur=1", 0,
     (p003_times){{1.28, 115.86, 1664.70, 8155.70},
                  {0.33, 25.40, 407.92, 1547.82}, {0.07, 1.96, 27.55, 175.37}}},
};
#define P003_NTABLES ((int)(sizeof p003_tables / sizeof p003_tables[0]))

static double p003_peak_mb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss / 1024.0;
}

typedef struct {
    int ok;                 /* solved */
    double time, base;
    int iter;
    double kkt, own;
    char why[600];
} p003_result;

static void p003_solve(const cx_scene *sc, int level, const p003_table *tb, double time_limit,
                       p003_result *r)
{
    cx_diag d;
    cx_problem *p = NULL;
    cx_session *s = NULL;
    memset(r, 0, sizeof *r);
    cx_friction_state fr;
    if (cx_scene_build(sc, level, &p, &fr, &d) || bench_baseline(p, 3, &r->base, &d)) {
        snprintf(r->why, sizeof r->why, "%s", d.msg);
        cx_problem_destroy(&p);
        return;
    }
    if (cx_session_create(&s, &p, &d) || cx_session_set_friction(s, &fr, &d)) {
        snprintf(r->why, sizeof r->why, "%s", d.msg);
        cx_problem_destroy(&p);
        cx_session_destroy(&s);
        return;
    }
    const cx_method *m = cx_method_find(tb->method);
    cx_param_values pv;
    cx_param_default(&pv, m->params);
    cx_options o;
    cx_options_default(&o);
    o.time_limit = time_limit;
    o.max_iter = 100000;
    o.stall_window = 100000;   /* the methods end on their own criteria */
    o.tol = 1e-15;
    if ((tb->set && cx_param_set_pair(&pv, tb->set, tb->method, &d)) ||
        cx_session_set_method(s, m, &pv, &o, &d) || bench_solve(s, &d)) {
        snprintf(r->why, sizeof r->why, "%s", d.msg);
        cx_session_destroy(&s);
        return;
    }
    const cx_iterate *it = cx_session_iterate(s);
    r->time = it->time;
    r->iter = it->iter;
    r->kkt = it->kkt;
    r->own = it->own;
    r->ok = cx_reason_criterion_met(it->reason) && it->kkt <= 1e-8;
    if (!r->ok)
        cx_session_outcome(s, r->why, sizeof r->why);
    cx_session_destroy(&s);
}

static int p003_in_list(const char *list, int x)
{
    if (!list)
        return 1;
    for (const char *q = list; *q;) {
        char *end;
        long v = strtol(q, &end, 10);
        if (end == q)
            break;
        if (v == x)
            return 1;
        q = *end ? end + 1 : end;
    }
    return 0;
}

/* The bodies of a built mesh: connected components of its elements (two
 * elements sharing a node are one body), counted from the mesh rather than
 * taken from the generator's mesh->nbodies (the closed formula). */
static long p003_count_bodies(const cx_mesh *m)
{
    int *up = malloc(sizeof(int) * (size_t)m->nnodes);
    unsigned char *used = calloc((size_t)m->nnodes, 1);
    if (!up || !used) {
        free(up), free(used);
        return -1;
    }
    for (int i = 0; i < m->nnodes; i++)
        up[i] = i;
    for (int e = 0; e < m->nelems; e++) {
        const int *c = m->conn + (size_t)m->npe * e;
        for (int k = 0; k < m->npe; k++) {
            int a = c[0], b = c[k];
            used[b] = 1;
            while (up[a] != a)
                a = up[a] = up[up[a]];
            while (up[b] != b)
                b = up[b] = up[up[b]];
            if (a != b)
                up[a < b ? b : a] = a < b ? a : b;
        }
    }
    long n = 0;
    for (int i = 0; i < m->nnodes; i++)
        n += used[i] && up[i] == i;
    free(up), free(used);
    return n;
}

/* The verdict on one size: within 20 % of the paper's, else one line with
 * its reason; n counts the lines. */
static void p003_cmp(int *n, int N, const char *what, double ours, double paper, const char *why)
{
    if (!(paper > 0) || fabs(ours - paper) <= 0.2 * paper)
        return;
    printf("  differs: 1/%d, %s %g against the paper's %g (%+.0f %%): %s\n", N, what, ours, paper,
           100 * (ours - paper) / paper, why);
    (*n)++;
}

static int p003_sizes(const cx_scene *sc, int g, int max_build)
{
    int ndiff = 0;
    printf("\n%s (Tables 1-2): bodies, unknowns n, constraints n_c; ours | paper's\n", p003_geo[g]);
    printf("  %-6s %8s %8s %9s %9s %8s %8s\n", "h", "n_b", "paper", "n", "paper", "n_c", "paper");
    for (int l = 0; l < P003_NLEVELS; l++) {
        int N = p003_levels[l];
        long nb = cx_masonry_bodies((cx_bond)g, N);
        if (N > max_build) {
            printf("  1/%-4d %7ldf %8ld %9s %9ld %8s %8ld\n", N, nb, p003_nb[g][l], "-", p003_n[g][l],
                   "-", p003_nc[g][l]);
            continue;
        }
        cx_problem *p = NULL;
        cx_diag d;
        if (cx_scene_build(sc, N, &p, NULL, &d)) {
            fprintf(stderr, "signorini bench: %s\n", d.msg);
            return CX_EXIT_ERROR;
        }
        long counted = p003_count_bodies(p->mesh);
        printf("  1/%-4d %8ld %8ld %9d %9ld %8d %8ld%s\n", N, counted, p003_nb[g][l], p->n,
               p003_n[g][l], p->m, p003_nc[g][l],
               counted != nb ? "  (the closed formula says otherwise)" : "");
        const char *why = "our generator's wall (scenes/*.ini) against the paper's mesh";
        p003_cmp(&ndiff, N, "n_b", counted, p003_nb[g][l], why);
        p003_cmp(&ndiff, N, "n", p->n, p003_n[g][l], why);
        p003_cmp(&ndiff, N, "n_c", p->m, p003_nc[g][l], why);
        cx_problem_destroy(&p);
    }
    if (!ndiff)
        printf("  verdict: n_b, n and n_c within 20 %% of the paper's on every level built (reproduced)\n");
    printf("  n_b: connected components of the built mesh's elements; f: the closed formula (the\n"
           "  mesh is built up to --max-level)\n");
    return CX_EXIT_OK;
}

typedef struct {
    int max_level, small;
    double time_limit, gap;
    const char *tables, *only;
} p003_args;

static int p003_check_geometry(const char *text, cx_diag *d)
{
    if (cx_parse_choice(text, "stackbond|runningbond|laminae") < 0)
        return cx_diag_set(d, CX_EINVAL, "--geometry '%s': expected stackbond|runningbond|laminae", text);
    return CX_OK;
}

static const cx_opt p003_opts[] = {
    {"max-level", 0, CX_OPT_INT, 5, 225, 0, NULL, "N",
     "largest level 1/H for PDAS and PDPC (default 100; 225 is\nthe paper's)",
     offsetof(p003_args, max_level), NULL},
    {"small", 0, CX_OPT_INT, 5, 225, 0, NULL, "N",
     "largest level for PSOR, LSSNN, Graves and the Schur\nvariants (default 25)", offsetof(p003_args, small),
     NULL},
    CX_OPT_ROW_TIME_LIMIT(p003_args, time_limit, "seconds per solve before it is given up (default 30)"),
    {"tables", 0, CX_OPT_STRING, 0, 0, 0, NULL, "LIST", "which of 3,4,5,6,7 (default all), e.g. --tables 5,6",
     offsetof(p003_args, tables), NULL},
    {"geometry", 0, CX_OPT_STRING, 0, 0, 0, NULL, "G", "stackbond, runningbond or laminae only (default all three)",
     offsetof(p003_args, only), p003_check_geometry},
    {"gap", 0, CX_OPT_REAL, 0, 1, CX_OPT_MIN_OPEN | CX_OPT_MAX_OPEN, NULL, "G",
     "settlement gap g as a fraction of H (default: the\n"
     "scenes', 0.01; 0.5 is the stress case where the joints\n"
     "slide by a node spacing)", offsetof(p003_args, gap), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

int bench_paper_003(int argc, char **argv)
{
    p003_args a = {100, 25, 30, 0, NULL, NULL};
    int code = bench_paper_args("bench paper 003", p003_usage, p003_opts, &a, argc, argv);
    if (code >= 0)
        return code;
    int max_level = a.max_level, small = a.small;
    double time_limit = a.time_limit, gap = a.gap;
    const char *tables = a.tables, *only = a.only;
    cx_diag d;

    cx_scene sc[3];
    for (int g = 0; g < 3; g++) {
        if (cx_scene_open(p003_geo[g], &sc[g], &d))
            return bench_fail("bench paper 003", d.msg);
        if (gap > 0)
            sc[g].gap_h = gap;
    }
    printf("Paper 003 (Ainsworth & Mihai), masonry walls; settlement gap g = %g H (stack bond), "
           "%g H (running bond), %g H (laminae) (not in the paper)\n",
           sc[0].gap_h, sc[1].gap_h, sc[2].gap_h);
    printf("times: ours = method setup + solve (s), median baseline = analyse + factorise + solve of "
           "K with springs, same run; paper = Matlab 7 on a 2005 workstation, dense\n");
    for (int g = 0; g < 3; g++)
        if ((!only || strcmp(only, p003_geo[g]) == 0) && p003_sizes(&sc[g], g, max_level))
            return CX_EXIT_ERROR;

    for (int t = 0; t < P003_NTABLES && !bench_interrupted(); t++) {
        const p003_table *tb = &p003_tables[t];
        if (!p003_in_list(tables, tb->table))
            continue;
        int top = tb->big ? max_level : small;
        printf("\nTable %d: %s [%s%s%s]\n", tb->table, tb->title, tb->method, tb->set ? " " : "",
               tb->set ? tb->set : "");
        if (strcmp(tb->method, "pdpc") == 0 && tb->paper)
            printf("  the paper's PDPC has no projection: ours adds one (own = its iterations, 2-8 on\n"
                   "  running bond, 2-3 on laminae), so ours solves the LCP exactly where the paper\n"
                   "  stops at PDPC's own criterion\n");
        printf("  %-12s %-6s %10s %8s %7s %9s %10s %9s %8s\n", "geometry", "h", "ours (s)",
               "ratio", "iters", "kkt", "paper (s)", "own", "peak MB");
        for (int g = 0; g < 3 && !bench_interrupted(); g++) {
            if (only && strcmp(only, p003_geo[g]) != 0)
                continue;
            int failed = 0, l0 = -1, l1 = -1;
            double t0 = 0, t1 = 0;
            for (int l = 0; l < P003_NLEVELS && p003_levels[l] <= top && !bench_interrupted(); l++) {
                int N = p003_levels[l];
                double paper = tb->paper[g][l];
                char ptxt[16];
                snprintf(ptxt, sizeof ptxt, paper > 0 || (l < 4 && tb->table == 7) ? "%.2f" : "-", paper);
                if (failed) {
                    printf("  %-12s 1/%-4d %10s %8s %7s %9s %10s   (skipped: a smaller level failed)\n",
                           p003_geo[g], N, "-", "-", "-", "-", ptxt);
                    continue;
                }
                p003_result r;
                p003_solve(&sc[g], N, tb, time_limit, &r);
                if (r.ok) {
                    printf("  %-12s 1/%-4d %10.4f %8.1f %7d %9.1e %10s %9g %8.0f\n", p003_geo[g], N,
                           r.time, r.base > 0 ? r.time / r.base : NAN, r.iter, r.kkt, ptxt, r.own,
                           p003_peak_mb());
                    if (paper > 0 && N >= 10) {
                        if (l0 < 0)
                            l0 = l, t0 = r.time;
                        l1 = l, t1 = r.time;
                    }
                } else {
                    printf("  %-12s 1/%-4d %10s %8s %7d %9s %10s   (%s)\n", p003_geo[g], N, "-", "-",
                           r.iter, "-", ptxt, r.why);
                    failed = 1;
                }
                fflush(stdout);
            }
            /* the verdict: times are not comparable row by row, their growth is */
            if (l1 > l0 && l0 >= 0)
                printf("  %-12s differs in time (the paper's: Matlab 7 on a 2005 workstation, ours this "
                       "machine); growth 1/%d -> 1/%d: ours x%.0f, the paper's x%.0f\n", p003_geo[g],
                       p003_levels[l0], p003_levels[l1], t1 / t0, tb->paper[g][l1] / tb->paper[g][l0]);
        }
    }
    printf("\nown: projection iterations at the end (Graves: principal pivots); peak MB: the "
           "process's peak resident memory so far\n");
    return CX_EXIT_OK;
}
