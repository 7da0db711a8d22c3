/* SPDX-License-Identifier: GPL-3.0-or-later */
/* pdpc — primal-dual predictor-corrector interior point for the LCP
 * (paper 003 §4; Wright, Portugal et al.), on the UNregularised A, then
 * (by default) the projection of §4 to land exactly on the solution.
 *
 * Unknowns v (n) and lam >= 0 on S with A v - b - lam = 0 and lam_i v_i = 0
 * on S. Each iteration factorises A + diag(lam / v) (definite: A_EE is,
 * and lam / v > 0 on S) with the symbolic analysis kept, and solves twice:
 * the affine predictor (sigma = 0) and Mehrotra's corrector with
 * sigma = (mu_aff / mu)^3 and the second-order term; step 0.99 of the way
 * to the boundary (sigma = paper: the paper's own alternation, below). The diagonal scaling of §5 (A to unit diagonal) is the
 * start v_i = s d_i, lam_i = s / d_i with d_i = A_ii^-1/2: products
 * lam_i v_i, hence the path, are those of the scaled problem. With
 * schur = 1 the same on the dense reduced LCP (Table 7). Own criterion:
 * mu and the residual below tol (relative). */
#include "solve/lcp.h"

#include <math.h>
#include <string.h>

typedef struct {
    cx_lcp_run run;
    cx_lcp_solver ip;     /* A + diag(lam / v) */
    double *dv, *dl, *dva, *dla, *r, *rhs, *D, *w2;
    double tol, bnorm;
    int paper;            /* sigma = paper: 0 / 0.99 alternating, one solve per iteration */
    int k;                /* interior-point iterations done */
} pdpc_state;

static const cx_param pdpc_params[] = {
    CX_LCP_PARAMS_STAGE,
    CX_LCP_PARAM_SCHUR,
    {"tol", CX_PARAM_REAL, 1e-10, 1e-15, 1e-2, NULL,
     "stop the interior point when mu and the residual fall below tol (relative)", 0},
    {"sigma", CX_PARAM_CHOICE, 0, 0, 1, "mehrotra|paper",
     "centring: Mehrotra's predictor-corrector (two solves per factorisation), or the paper's "
     "alternation sigma = 0 (odd iterations) / 0.99 (even) with its step rule alpha3 (003 §4)", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void pdpc_destroy(void *state)
{
    pdpc_state *st = state;
    cx_lcp_solver_clear(&st->ip);
    cx_free(st->dv), cx_free(st->dl), cx_free(st->dva), cx_free(st->dla);
    cx_free(st->r), cx_free(st->rhs), cx_free(st->D), cx_free(st->w2);
    cx_lcp_run_clear(&st->run);
}

static int pdpc_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    pdpc_state *st = state;
    CX_TRY(cx_lcp_run_init(&st->run, s, params, cx_param_get(params, "schur") != 0, d));
    const cx_lcp *L = st->run.L;
    int n = L->n;
    st->tol = cx_param_get(params, "tol");
    st->paper = (int)cx_param_get(params, "sigma") == 1;
    st->dv = CX_NEW(double, n), st->dl = CX_NEW(double, n);
    st->dva = CX_NEW(double, n), st->dla = CX_NEW(double, n);
    st->r = CX_NEW(double, n), st->rhs = CX_NEW(double, n);
    st->D = CX_NEW(double, n), st->w2 = CX_NEW(double, n);
    int status = CX_ENOMEM;
    if (!st->dv || !st->dl || !st->dva || !st->dla || !st->r || !st->rhs || !st->D || !st->w2 ||
        (status = cx_lcp_solver_init(&st->ip, L, cx_session_counters(s), d))) {
        pdpc_destroy(st);
        return status == CX_ENOMEM ? cx_diag_set(d, CX_ENOMEM, "out of memory") : status;
    }
    /* start: the scaled problem's (e, s e) */
    st->bnorm = cx_vec_norminf(n, L->b);
    double sc = st->bnorm > 0 ? st->bnorm : 1;
    for (int i = 0; i < n; i++) {
        double aii = L->dense ? L->Ad[(size_t)n * i + i] : cx_csc_get(&L->A, i, i);
        double di = aii > 0 ? 1 / sqrt(aii) : 1;
        st->run.v[i] = L->S[i] ? sc * di : 0;
        st->run.lam[i] = L->S[i] ? sc / di : 0;
    }
    return CX_OK;
}

/* largest alpha in (0, 1] keeping x + alpha dx > 0 on S */
static double pdpc_max_step(const cx_lcp *L, const double *x, const double *dx)
{
    double a = 1;
    for (int i = 0; i < L->n; i++)
        if (L->S[i] && dx[i] < 0 && -x[i] / dx[i] < a)
            a = -x[i] / dx[i];
    return a;
}

/* Solve (A + D) dv = -r - lam + comp / v on S, dlam = (comp - lam dv) / v. */
static int pdpc_direction(pdpc_state *st, const double *comp, double *dv, double *dl, cx_diag *d)
{
    const cx_lcp *L = st->run.L;
    const double *v = st->run.v, *lam = st->run.lam;
    for (int i = 0; i < L->n; i++)
        st->rhs[i] = -st->r[i] + (L->S[i] ? -lam[i] + comp[i] / v[i] : 0);
    CX_TRY(cx_lcp_solve(&st->ip, NULL, st->rhs, dv, st->w2, d));
    for (int i = 0; i < L->n; i++)
        dl[i] = L->S[i] ? (comp[i] - lam[i] * dv[i]) / v[i] - lam[i] : 0;
    return CX_OK;
}

static int pdpc_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    pdpc_state *st = state;
    cx_lcp_run *run = &st->run;
    const cx_lcp *L = run->L;
    int n = L->n, nc = L->nc;
    if (run->stage > 0)
        return cx_lcp_run_project(run, s, it, d);
    double *v = run->v, *lam = run->lam;

    /* residual r = A v - b - lam and mu */
    cx_lcp_apply(L, v, st->r);
    double mu = 0;
    for (int i = 0; i < n; i++) {
        st->r[i] -= L->b[i] + lam[i];
        if (L->S[i])
            mu += v[i] * lam[i];
    }
    mu /= nc > 0 ? nc : 1;
    double rn = cx_vec_norminf(n, st->r), sc = st->bnorm > 0 ? st->bnorm : 1;
    double vmax = cx_vec_norminf(n, v), lmax = cx_vec_norminf(n, lam);
    it->own = fmax(rn / sc, mu / (1 + vmax * lmax));
    if (nc == 0 || it->own <= st->tol) {
        CX_TRY(cx_lcp_run_stage_done(run, it, d));
        if (run->stage == 2)
            return CX_OK;
        return cx_lcp_run_project(run, s, it, d);
    }

    for (int i = 0; i < n; i++)
        st->D[i] = L->S[i] ? lam[i] / v[i] : 0;
    CX_TRY(cx_lcp_factor(&st->ip, 0.0, NULL, st->D, d));
    st->k++;
    if (st->paper) {
        /* 003 §4 Steps 3-5: sigma = 0 on odd iterations, 0.99 on even; one
         * direction; alpha = min(alpha1, alpha2[, alpha3]) where alpha3 =
         * 0.99 (1 - sigma) lam'v / (dlam'dv) when dlam'dv > 0 (the paper's
         * dSigma'du < 0) keeps lam'v falling. alpha1, alpha2 are the
         * suprema of open sets (the boundary): taken x 0.9995 to stay
         * interior. */
        double sg = st->k % 2 ? 0.0 : 0.99;
        for (int i = 0; i < n; i++)
            st->w2[i] = L->S[i] ? sg * mu : 0;
        double *cmp = st->dla;
        memcpy(cmp, st->w2, sizeof(double) * (size_t)n);
        CX_TRY(pdpc_direction(st, cmp, st->dv, st->dl, d));
        double a1 = pdpc_max_step(L, v, st->dv), a2 = pdpc_max_step(L, lam, st->dl);
        double a = fmin(a1 < 1 ? 0.9995 * a1 : 1, a2 < 1 ? 0.9995 * a2 : 1), dd = 0;
        for (int i = 0; i < n; i++)
            if (L->S[i])
                dd += st->dl[i] * st->dv[i];
        if (dd > 0)
            a = fmin(a, 0.99 * (1 - sg) * mu * nc / dd);
        cx_vec_axpy(n, a, st->dv, v);
        cx_vec_axpy(n, a, st->dl, lam);
        it->inner = 1;
        return cx_lcp_run_publish(run, s, it);
    }
    /* predictor: sigma = 0 */
    for (int i = 0; i < n; i++)
        st->w2[i] = 0;
    memset(st->dla, 0, sizeof(double) * (size_t)n);
    double *comp = st->dla;   /* zeros */
    CX_TRY(pdpc_direction(st, comp, st->dva, st->dl, d));
    memcpy(st->dla, st->dl, sizeof(double) * (size_t)n);
    double ap = pdpc_max_step(L, v, st->dva), ad = pdpc_max_step(L, lam, st->dla);
    double a = fmin(ap, ad), mua = 0;
    for (int i = 0; i < n; i++)
        if (L->S[i])
            mua += (v[i] + a * st->dva[i]) * (lam[i] + a * st->dla[i]);
    mua /= nc;
    double sigma = pow(mua / mu, 3);
    /* corrector: comp = sigma mu - dv_a dlam_a */
    for (int i = 0; i < n; i++)
        st->rhs[i] = 0;
    double *c2 = st->D;   /* reuse: D is inside the factor already */
    for (int i = 0; i < n; i++)
        c2[i] = L->S[i] ? sigma * mu - st->dva[i] * st->dla[i] : 0;
    CX_TRY(pdpc_direction(st, c2, st->dv, st->dl, d));
    ap = pdpc_max_step(L, v, st->dv), ad = pdpc_max_step(L, lam, st->dl);
    a = fmin(1.0, 0.99 * fmin(ap, ad) / 1.0);
    if (fmin(ap, ad) >= 1)
        a = fmin(1.0, 0.99 * fmin(ap, ad));
    cx_vec_axpy(n, a, st->dv, v);
    cx_vec_axpy(n, a, st->dl, lam);
    it->inner = 2;
    return cx_lcp_run_publish(run, s, it);
}

const cx_method cx_method_pdpc = {
    .id = "pdpc",
    .name = "Primal-dual predictor-corrector + projection",
    .source = "003 §4",
    .summary = "Mehrotra predictor-corrector interior point on the unregularised LCP (sparse "
               "Cholesky of A + diag(lam/v)), then the PDAS projection",
    .supports = CX_FRICTIONLESS | CX_2D | CX_3D | CX_MULTIBODY,
    .state_size = sizeof(pdpc_state),
    .params = pdpc_params,
    .init = pdpc_init,
    .step = pdpc_step,
    .destroy = pdpc_destroy,
};
