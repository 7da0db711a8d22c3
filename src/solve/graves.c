/* SPDX-License-Identifier: GPL-3.0-or-later */
/* graves — the principal pivoting simplex method of Graves (1967) on the
 * reduced Schur-complement LCP (paper 003 §4, Step 1-5; Table 7).
 *
 * The tableau y = M x + q starts with y = w = -Sigma_hat, x = u_hat,
 * M = A_hat, q = -b_hat. While some q_i < 0, the row t maximising B_t / q_t
 * lexicographically over q_i < 0 is pivoted on: a single principal pivot
 * when its diagonal entry is not zero (Case 1), else a double pivot with
 * the row s maximising (B_s - q_s B_t / q_t) / M_st over M_st < 0 (Case 2);
 * with no such s the LCP has no solution. B starts as the identity; its
 * rows stay lexico-positive and max B_t / q_t decreases lexicographically
 * (Theorem 4.5), so no basis repeats. Exact: no projection needed.
 *
 * Dense on the reduced problem: each pivot costs O(n_c^2) on an
 * n_c x (2 n_c + 1) tableau, so levels whose n_c exceeds max_nc are refused
 * with the reason (the paper's 1/20 running bond took 5446 s). */
#include "solve/lcp.h"

#include <math.h>
#include <string.h>

#define G_ROW(g, i) ((g)->T + (size_t)(i) * (1 + 2 * (size_t)(g)->n))

int cx_graves_init(cx_graves *g, int n, const double *M, const double *q)
{
    memset(g, 0, sizeof *g);
    g->n = n;
    g->T = CX_NEW(double, (size_t)n * (1 + 2 * (size_t)n));
    g->basic = CX_NEW(int, n);
    g->col = CX_NEW(int, n);
    if (!g->T || !g->basic || !g->col) {
        cx_graves_clear(g);
        return CX_ENOMEM;
    }
    for (int i = 0; i < n; i++) {
        double *r = G_ROW(g, i);
        r[0] = q[i];
        for (int j = 0; j < n; j++)
            r[1 + j] = M[(size_t)n * j + i];
        r[1 + n + i] = 1;   /* B = I */
        g->basic[i] = i;     /* w_i */
        g->col[i] = n + i;   /* z_i */
    }
    return CX_OK;
}

void cx_graves_clear(cx_graves *g)
{
    cx_free(g->T);
    cx_free(g->basic);
    cx_free(g->col);
    memset(g, 0, sizeof *g);
}

/* Exchange: basic variable of row r leaves, nonbasic of column c enters. */
static void g_exchange(cx_graves *g, int r, int c)
{
    int n = g->n, w = 1 + 2 * n;
    double *pr = G_ROW(g, r), piv = pr[1 + c];
    /* the new row r: x_c = (y_r - sum_{j != c} a_rj x_j - q_r) / a_rc */
    for (int k = 0; k < w; k++)
        pr[k] = -pr[k] / piv;
    pr[1 + c] = 1 / piv;
    for (int i = 0; i < n; i++) {
        if (i == r)
            continue;
        double *pi = G_ROW(g, i), aic = pi[1 + c];
        if (aic == 0)
            continue;
        for (int k = 0; k < w; k++)
            pi[k] += aic * pr[k];
        pi[1 + c] = aic * pr[1 + c];
    }
    int t = g->basic[r];
    g->basic[r] = g->col[c];
    g->col[c] = t;
}

/* the column holding the complement of row i's basic variable */
static int g_complement_col(const cx_graves *g, int i)
{
    int n = g->n, k = g->basic[i], want = k < n ? k + n : k - n;
    for (int j = 0; j < n; j++)
        if (g->col[j] == want)
            return j;
    return -1;
}

/* lexicographic a > b over n entries (scaled by sa, sb) */
static int g_lex_greater(const double *a, double sa, const double *b, double sb, int n)
{
    for (int k = 0; k < n; k++) {
        double x = a[k] * sa, y = b[k] * sb;
        if (x != y)
            return x > y;
    }
    return 0;
}

int cx_graves_run(cx_graves *g, long max_pivots, cx_diag *d)
{
    int n = g->n;
    double qs = 0;
    for (int i = 0; i < n; i++)
        qs = fmax(qs, fabs(G_ROW(g, i)[0]));
    double tol = 1e-13 * (qs > 0 ? qs : 1);
    for (long done = 0; done < max_pivots && g->state == 0; done++) {
        /* Step 2-3: the lexico-max of B_i / q_i over q_i < 0 */
        int t = -1;
        for (int i = 0; i < n; i++) {
            double *ri = G_ROW(g, i);
            if (ri[0] < -tol && (t < 0 || g_lex_greater(ri + 1 + n, 1 / ri[0], G_ROW(g, t) + 1 + n,
                                                         1 / G_ROW(g, t)[0], n)))
                t = i;
        }
        if (t < 0) {
            g->state = 1;
            break;
        }
        int ct = g_complement_col(g, t);
        double *rt = G_ROW(g, t), mscale = 0;
        for (int j = 0; j < n; j++)
            mscale = fmax(mscale, fabs(rt[1 + j]));
        if (fabs(rt[1 + ct]) > 1e-8 * (mscale > 0 ? mscale : 1)) {   /* else Case 2: roundoff must not make a pivot of a zero */
            g_exchange(g, t, ct);   /* Case 1 */
            g->pivots++;
            continue;
        }
        /* Case 2: a row s with M_s,ct < 0, lexico-max (B_s - q_s B_t / q_t) / M_s,ct */
        int s = -1;
        double best_scale = 0;
        double *bt = rt + 1 + n, qt = rt[0];
        for (int i = 0; i < n; i++) {
            double *ri = G_ROW(g, i), a = ri[1 + ct];
            if (i == t || !(a < -1e-12 * (mscale > 0 ? mscale : 1)))
                continue;
            if (s < 0) {
                s = i, best_scale = a;
                continue;
            }
            double *rs = G_ROW(g, s);
            int greater = 0;
            for (int k = 0; k < n; k++) {
                double x = (ri[1 + n + k] - ri[0] * bt[k] / qt) / a;
                double y = (rs[1 + n + k] - rs[0] * bt[k] / qt) / best_scale;
                if (x != y) {
                    greater = x > y;
                    break;
                }
            }
            if (greater)
                s = i, best_scale = a;
        }
        if (s < 0) {
            g->state = -1;
            return cx_diag_set(d, CX_OK, "graves: the LCP has no solution (row %d: zero diagonal, "
                               "no negative entry in its column)", t);
        }
        int cs = g_complement_col(g, s);
        g_exchange(g, s, ct);
        g_exchange(g, t, cs);
        g->pivots += 2;
    }
    return CX_OK;
}

void cx_graves_z(const cx_graves *g, double *z)
{
    int n = g->n;
    memset(z, 0, sizeof(double) * (size_t)n);
    for (int i = 0; i < n; i++)
        if (g->basic[i] >= n)
            z[g->basic[i] - n] = G_ROW(g, i)[0];
}

/* ---- the method ------------------------------------------------------------ */

typedef struct {
    cx_lcp_map *map;
    cx_graves g;
    double *q, *z, *work;
    long per_step;
} graves_state;

static const cx_param graves_params[] = {
    {"max_nc", CX_PARAM_INT, 3000, 1, 20000, NULL,
     "largest reduced LCP (contact unknowns) accepted: the tableau is dense", 0},
    {"pivots", CX_PARAM_INT, 50, 1, 1e9, NULL, "principal pivots per step", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void graves_destroy(void *state)
{
    graves_state *st = state;
    cx_graves_clear(&st->g);
    cx_free(st->q), cx_free(st->z), cx_free(st->work);
}

static int graves_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    graves_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    int max_nc = (int)cx_param_get(params, "max_nc");
    if (p->m > max_nc)
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "method 'graves': the reduced LCP has %d contact unknowns (max_nc %d): the "
                           "dense tableau (%.1f GB) and O(n_c^3) pivoting are for small levels",
                           p->m, max_nc, 8.0 * p->m * (2.0 * p->m + 1) / 1e9);
    CX_TRY(cx_lcp_get_reduced(s, &st->map, d));
    const cx_lcp *R = &st->map->red;
    int n = R->n;
    st->per_step = (long)cx_param_get(params, "pivots");
    st->q = CX_NEW(double, n);
    st->z = CX_NEW(double, n);
    st->work = CX_NEW(double, st->map->full.n);
    if (!st->q || !st->z || !st->work) {
        graves_destroy(st);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    for (int i = 0; i < n; i++)
        st->q[i] = -R->b[i];
    if (cx_graves_init(&st->g, n, R->Ad, st->q)) {
        graves_destroy(st);
        return cx_diag_set(d, CX_ENOMEM, "out of memory (Graves tableau of order %d)", n);
    }
    return CX_OK;
}

static int graves_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    graves_state *st = state;
    long before = st->g.pivots;
    /* the pivots of a step in chunks: each costs O(n^2) on the dense
     * tableau, and a cancel or the time limit acts between chunks */
    for (long done = 0; done < st->per_step && st->g.state == 0; done += CX_CHECK_INTERVAL) {
        if (done > 0 && cx_session_interrupted(s))
            break;
        long chunk = st->per_step - done < CX_CHECK_INTERVAL ? st->per_step - done : CX_CHECK_INTERVAL;
        CX_TRY(cx_graves_run(&st->g, chunk, d));
    }
    it->inner = st->g.pivots - before;
    it->own = (double)st->g.pivots;
    if (st->g.state < 0) {
        it->reason = CX_DIVERGED_BREAKDOWN;
        return CX_OK;
    }
    if (st->g.state > 0)
        it->own_done = 1;
    cx_graves_z(&st->g, st->z);
    return cx_lcp_result(st->map, 1, st->z, st->work, cx_session_problem(s), it->u, it->lN);
}

const cx_method cx_method_graves = {
    .id = "graves",
    .name = "Graves principal pivoting simplex",
    .source = "003 §4",
    .summary = "lexicographic principal pivoting on the dense reduced Schur-complement LCP; exact, "
               "says when there is no solution; small levels only",
    .supports = CX_FRICTIONLESS | CX_2D | CX_3D | CX_MULTIBODY,
    .state_size = sizeof(graves_state),
    .params = graves_params,
    .init = graves_init,
    .step = graves_step,
    .destroy = graves_destroy,
};
