/* SPDX-License-Identifier: GPL-3.0-or-later */
/* lssnn — linear least squares with (selected) non-negativity constraints,
 * Lawson & Hanson's NNLS (paper 003 §4, single principal pivoting) on the
 * regularised LCP: with A + eps I = R'R and y = R^-T b, the LCP is
 * min ||R v - y|| over v_S >= 0, whose residual falls at every step
 * (Theorem 4.2; reported as the method's criterion through the equal
 * quantity q(v) = 1/2 v'(A + eps I)v - b'v = (||Rv - y||^2 - ||y||^2) / 2).
 *
 * v starts with every contact closed (v_S = 0, v_E solving the rest). Each
 * outer step moves the constrained unknown with the largest positive
 * w = b - (A + eps I) v into the passive set P and solves on P; while a
 * passive value is not positive it steps back to the boundary and drops
 * the unknowns that reach zero (the inner loop). Every solve is one numeric
 * Cholesky of A + eps I with the unknowns outside P replaced by the
 * identity. By default (update = 1) that factor is not recomputed: each
 * pivot adds or deletes one row and column of a simplicial LDL' factor
 * (CHOLMOD's rowadd/rowdel, linalg/ldlmod.c); update = 0 refactorises
 * (same pattern, symbolic analysis once).
 * schur = 1: the same on the dense reduced LCP. Then the projection. */
#include "solve/lcp.h"

#include <math.h>
#include <string.h>

typedef struct {
    cx_lcp_run run;
    cx_lcp_solver reg;
    cx_ldlmod *ldl;       /* update = 1: the factor changed row by row */
    int update;
    unsigned char *zero;  /* n: 1 outside P (held at zero) */
    double *z, *w;        /* n: trial solution, work */
    int started;
    double q;             /* the objective after the last step */
} lssnn_state;

static const cx_param lssnn_params[] = {
    CX_LCP_PARAMS_COMMON,
    CX_LCP_PARAM_SCHUR,
    CX_LCP_PARAM_SCHUR_EPS,
    {"update", CX_PARAM_BOOL, 1, 0, 1, NULL,
     "1: add/delete one row of the LDL' factor per pivot (CHOLMOD Modify); 0: refactorise", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void lssnn_destroy(void *state)
{
    lssnn_state *st = state;
    cx_lcp_solver_clear(&st->reg);
    cx_ldlmod_destroy(&st->ldl);
    cx_free(st->zero), cx_free(st->z), cx_free(st->w);
    cx_lcp_run_clear(&st->run);
}

static int lssnn_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    lssnn_state *st = state;
    CX_TRY(cx_lcp_run_init(&st->run, s, params, cx_param_get(params, "schur") != 0, d));
    int n = st->run.L->n, status = CX_ENOMEM;
    st->zero = CX_NEW(unsigned char, n);
    st->z = CX_NEW(double, n);
    st->w = CX_NEW(double, 2 * (size_t)n);
    if (!st->zero || !st->z || !st->w ||
        (status = cx_lcp_solver_init(&st->reg, st->run.L, cx_session_counters(s), d))) {
        lssnn_destroy(st);
        return status == CX_ENOMEM ? cx_diag_set(d, CX_ENOMEM, "out of memory") : status;
    }
    memcpy(st->zero, st->run.L->S, (size_t)n);
    st->update = cx_param_get(params, "update") != 0 && !st->run.L->dense;
    if (st->update) {
        /* the first matrix: every constrained unknown held at zero */
        cx_lcp_factor_values(&st->reg, st->run.eps, st->zero, NULL);
        if ((status = cx_ldlmod_create(&st->ldl, &st->reg.M, cx_session_counters(s), d))) {
            lssnn_destroy(st);
            return status;
        }
    }
    return CX_OK;
}

/* P gains (enter = 1) or loses unknown i: one row of the factor */
static int lssnn_change(lssnn_state *st, int i, int enter, cx_diag *d)
{
    st->zero[i] = !enter;
    if (!st->update)
        return CX_OK;
    if (!enter)
        return cx_ldlmod_delete(st->ldl, i, d);
    unsigned char *keep = (unsigned char *)st->w;   /* n bytes of the 2 n doubles */
    for (int k = 0; k < st->run.L->n; k++)
        keep[k] = !st->zero[k];
    return cx_ldlmod_add(st->ldl, i, &st->run.L->A, keep, st->run.eps, d);
}

/* z = solution on P (zero elsewhere) */
static int lssnn_solve_p(lssnn_state *st, cx_diag *d)
{
    if (st->update) {
        const cx_lcp *L = st->run.L;
        for (int i = 0; i < L->n; i++)
            st->w[i] = st->zero[i] ? 0 : L->b[i];
        CX_TRY(cx_ldlmod_solve(st->ldl, st->w, st->z, d));
        for (int i = 0; i < L->n; i++)
            if (st->zero[i])
                st->z[i] = 0;
        return CX_OK;
    }
    CX_TRY(cx_lcp_factor(&st->reg, st->run.eps, st->zero, NULL, d));
    return cx_lcp_solve(&st->reg, st->zero, st->run.L->b, st->z, st->w, d);
}

static double lssnn_objective(lssnn_state *st)
{
    const cx_lcp *L = st->run.L;
    const double *v = st->run.v;
    cx_lcp_apply(L, v, st->w);
    double q = 0;
    for (int i = 0; i < L->n; i++)
        q += v[i] * (0.5 * (st->w[i] + st->run.eps * v[i]) - L->b[i]);
    return q;
}

static int lssnn_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    lssnn_state *st = state;
    cx_lcp_run *r = &st->run;
    const cx_lcp *L = r->L;
    int n = L->n;
    if (r->stage > 0)
        return cx_lcp_run_project(r, s, it, d);
    double *v = r->v;
    if (!st->started) {
        /* every contact closed: v_S = 0, v_E from the rest */
        st->started = 1;
        CX_TRY(lssnn_solve_p(st, d));
        memcpy(v, st->z, sizeof(double) * (size_t)n);
        it->own = st->q = lssnn_objective(st);
        return cx_lcp_run_publish(r, s, it);
    }
    /* w = b - (A + eps I) v; the most positive one outside P enters */
    cx_lcp_apply(L, v, st->w);
    double wmax = 0, bn = cx_vec_norminf(n, L->b);
    int t = -1;
    for (int i = 0; i < n; i++) {
        double wi = L->b[i] - st->w[i] - r->eps * v[i];
        if (st->zero[i] && wi > wmax)
            wmax = wi, t = i;
    }
    if (t < 0 || wmax <= 1e-13 * (bn > 0 ? bn : 1)) {
        CX_TRY(cx_lcp_run_stage_done(r, it, d));
        if (r->stage == 2)
            return CX_OK;
        return cx_lcp_run_project(r, s, it, d);
    }
    CX_TRY(lssnn_change(st, t, 1, d));
    long inner = 0;
    for (;;) {
        CX_TRY(lssnn_solve_p(st, d));
        inner++;
        double alpha = 2;
        for (int i = 0; i < n; i++)
            if (L->S[i] && !st->zero[i] && st->z[i] <= 0) {
                double a = v[i] / (v[i] - st->z[i]);
                if (a < alpha)
                    alpha = a;
            }
        if (alpha > 1) {
            memcpy(v, st->z, sizeof(double) * (size_t)n);
            break;
        }
        /* back to the boundary: drop the unknowns that reach zero */
        for (int i = 0; i < n; i++) {
            v[i] += alpha * (st->z[i] - v[i]);
            if (L->S[i] && !st->zero[i] && v[i] <= 1e-15 * (1 + fabs(st->z[i]))) {
                v[i] = 0;
                CX_TRY(lssnn_change(st, i, 0, d));
            }
        }
        if (inner > n) {
            it->reason = CX_DIVERGED_BREAKDOWN;
            return cx_diag_set(d, CX_ENUMERIC, "lssnn: the inner loop does not end (rounding)");
        }
    }
    it->inner = inner;
    it->own = lssnn_objective(st);
    /* one pivot per step: the kkt error of the iterates need not fall,
     * the objective does (Theorem 4.2), and the method is finite */
    it->progress = it->own < st->q;
    st->q = it->own;
    return cx_lcp_run_publish(r, s, it);
}

const cx_method cx_method_lssnn = {
    .id = "lssnn",
    .name = "Lawson-Hanson NNLS + projection",
    .source = "003 §4",
    .summary = "single principal pivoting (Lawson & Hanson) on the regularised LCP, masked sparse "
               "Cholesky per pivot, then the PDAS projection",
    .supports = CX_FRICTIONLESS | CX_2D | CX_3D | CX_MULTIBODY,
    .state_size = sizeof(lssnn_state),
    .params = lssnn_params,
    .init = lssnn_init,
    .step = lssnn_step,
    .destroy = lssnn_destroy,
};
