/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cf-fp — Coulomb friction by successive Tresca problems, paper 002 §5
 * (Algorithm CF-FP), 2D and 3D.
 *
 * The fixed point s^(m+1) = F lN^m: each outer iteration solves the Tresca
 * problem with the per-point slip bounds s_i = F_i lN_i of the previous
 * iterate (the first with s = 0) by any registered method that supports
 * Tresca friction (the parameter inner; inner_set passes it parameters,
 * e.g. "r=0.29"). inner=auto (the default) takes ssn-tresca, exact and
 * warm-started from the last fixed-point step's sets, so that a step
 * costs one small dense solve once the sets settle; where it refuses the
 * problem (its dense condensed system would be too large) ubr-tf, the
 * paper's choice. The inner method runs in a nested session
 * (solve.h): ordinary stepping with all its bookkeeping, the parent's
 * operator cache (so ubr-tf's factorisation of K + r(N'WN + T'WT) is built
 * once and reused by every fixed-point step: one factorisation per run)
 * and the parent's counters; each inner run starts from the previous
 * fixed-point iterate (warm start; warm=0 starts from zero, which the
 * paper's Tresca counts suggest it did: about twice ours). The inner tolerance follows the paper,
 * eps_f^m = max(0.1^m, eps_min): given to the inner method's own 'eps' if it
 * has one (ubr-tf's criterion (5.6)), else used as its kkt tolerance. Own
 * criterion: |s^(m+1) - s^m| / |s^(m+1)| < eps_fp (1e-4 in the paper).
 * Allocation happens at each inner init (one per step); the paper notes the
 * fixed point converges for small F only, which the kkt error shows. */
#include "solve/solve.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

extern const cx_method cx_method_cf_fp;

typedef struct {
    cx_session *child;        /* nested session running the inner method */
    const cx_method *inner;   /* the inner Tresca method */
    cx_param_values iparams;  /* its parameters */
    int has_eps;              /* 1 if the inner method has an 'eps' parameter */
    double eps_fp, eps_min;   /* outer criterion, floor of the inner tolerance */
    int inner_max_iter;       /* iteration limit of each inner run */
    int warm;                 /* 1: each inner run starts from the last iterate */
    double *sb;               /* m: slip bounds of the current Tresca problem */
    double *snew;             /* m: F lN of its solution */
} cffp_state;

static const cx_param cffp_params[] = {
    {"inner", CX_PARAM_STRING, 0, 0, 0, "auto",
     "id of the inner method (any method that supports Tresca friction), or auto: ssn-tresca where "
     "it takes the problem, else ubr-tf", 0},
    {"inner_set", CX_PARAM_STRING, 0, 0, 0, "default",
     "parameters of the inner method, key=value[,key=value] (default: its own)", 0},
    {"eps_fp", CX_PARAM_REAL, 1e-4, 1e-16, 1, NULL,
     "fixed-point criterion on the relative change of the slip bounds", 0},
    {"eps_min", CX_PARAM_REAL, 1e-5, 1e-16, 1, NULL,
     "floor of the inner tolerance max(0.1^m, eps_min)", 0},
    {"inner_max_iter", CX_PARAM_INT, 5000, 1, 1e8, NULL, "iteration limit of each inner run", 0},
    {"warm", CX_PARAM_BOOL, 1, 0, 1, NULL,
     "start each inner run from the last fixed-point iterate (else from zero, as the paper)", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void cffp_destroy(void *state)
{
    cffp_state *st = state;
    cx_session_destroy(&st->child);
    cx_free(st->sb);
    cx_free(st->snew);
    memset(st, 0, sizeof *st);
}

/* "r=0.29,eps=1e-6" into the inner method's parameters. */
static int cffp_parse_inner_set(cffp_state *st, const char *text, cx_diag *d)
{
    char buf[CX_PARAM_STRLEN], owner[64];
    snprintf(owner, sizeof owner, "method '%s' (cf-fp inner_set)", st->inner->id);
    if (strcmp(text, "default") == 0)
        return CX_OK;
    snprintf(buf, sizeof buf, "%s", text);
    char *save = NULL;   /* strtok_r: strtok's hidden state is shared by every thread */
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save))
        CX_TRY(cx_param_set_pair(&st->iparams, tok, owner, d));
    return CX_OK;
}

static int cffp_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    cffp_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    const char *id = cx_param_get_str(params, "inner");
    int automatic = strcmp(id, "auto") == 0;
    st->inner = cx_method_find(automatic ? "ssn-tresca" : id);
    if (!st->inner)
        return cx_diag_set(d, CX_EINVAL, "parameter 'inner' of method 'cf-fp': unknown method '%s' "
                           "(see 'signorini list')", id);
    if (st->inner == &cx_method_cf_fp)
        return cx_diag_set(d, CX_EINVAL, "parameter 'inner' of method 'cf-fp': cf-fp cannot be its own "
                           "inner method");
    if (!(st->inner->supports & CX_TRESCA))
        return cx_diag_set(d, CX_EINVAL, "parameter 'inner' of method 'cf-fp': method '%s' does not "
                           "support Tresca friction", id);
    cx_param_default(&st->iparams, st->inner->params);
    CX_TRY(cffp_parse_inner_set(st, cx_param_get_str(params, "inner_set"), d));
    st->eps_fp = cx_param_get(params, "eps_fp");
    st->eps_min = cx_param_get(params, "eps_min");
    st->inner_max_iter = (int)cx_param_get(params, "inner_max_iter");
    st->warm = cx_param_get(params, "warm") != 0;
    st->sb = CX_NEW(double, p->m);
    st->snew = CX_NEW(double, p->m);
    if (!st->sb || !st->snew) {
        cffp_destroy(st);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    int status = cx_session_nested_create(&st->child, s, d);
    if (status == CX_OK)
        status = cx_session_set_slip_bounds(st->child, st->sb, d);
    if (status == CX_OK) {
        status = cx_method_check(st->inner, cx_session_problem(st->child),
                                     cx_session_friction(st->child)->law, d);
        if (status != CX_OK)
            status = cx_diag_set(d, CX_EUNSUPPORTED, "method 'cf-fp': inner %s", cx_diag_msg(d, status));
    }
    if (status == CX_OK && automatic) {
        /* the choice of auto: ssn-tresca unless its init refuses the problem */
        status = cx_session_set_method(st->child, st->inner, &st->iparams, NULL, d);
        if (status == CX_EUNSUPPORTED || status == CX_ENUMERIC) {
            st->inner = cx_method_find("ubr-tf");
            cx_param_default(&st->iparams, st->inner->params);
            status = cffp_parse_inner_set(st, cx_param_get_str(params, "inner_set"), d);
        }
        cx_session_clear_method(st->child);
    }
    if (status != CX_OK) {
        cffp_destroy(st);
        return status;
    }
    st->has_eps = cx_param_find(&st->iparams, "eps") >= 0;
    return CX_OK;
}

static int cffp_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    cffp_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    const cx_friction_state *fr = cx_session_friction(s);
    int m = p->m, fp = it->iter + 1;   /* fixed-point step, from 1 */

    /* the Tresca problem of this step: s = F lN of the last iterate */
    for (int i = 0; i < m; i++)
        st->sb[i] = fr->Fi[i] * (it->lN[i] > 0 ? it->lN[i] : 0);
    double eps_m = fmax(pow(0.1, fp), st->eps_min);
    cx_options o;
    cx_options_default(&o);
    o.max_iter = st->inner_max_iter;
    o.stall_window = 0;
    o.tol = st->has_eps ? 1e-15 : eps_m;
    if (st->has_eps)
        st->iparams.num[cx_param_find(&st->iparams, "eps")] = eps_m;
    /* bounds and start first, with no method selected, so that the inner
     * method is initialised once */
    cx_session_clear_method(st->child);
    CX_TRY(cx_session_set_slip_bounds(st->child, st->sb, d));
    if (st->warm)
        CX_TRY(cx_session_set_start(st->child, it->u, it->lN, it->lT, d));
    CX_TRY(cx_session_set_method(st->child, st->inner, &st->iparams, &o, d));
    CX_TRY(cx_solver_solve(st->child, NULL, NULL, d));
    const cx_iterate *in = cx_session_iterate(st->child);
    it->inner = in->iter;
    /* an inner run that stops on its own criterion above its (loose)
     * tolerance is an inexact inner solve, which the fixed point allows */
    if (in->reason < 0 && in->reason != CX_STOPPED_OWN) {
        char outcome[CX_DIAG_LEN];
        return cx_diag_set(d, CX_ENUMERIC, "cf-fp: inner method '%s' at fixed-point step %d: %s",
                           st->inner->id, fp, cx_session_outcome(st->child, outcome, sizeof outcome));
    }
    memcpy(it->u, in->u, sizeof(double) * (size_t)p->n);
    it->u_partial = in->u_partial;   /* expanded once, when the whole run ends */
    memcpy(it->lN, in->lN, sizeof(double) * (size_t)m);
    memcpy(it->lT, in->lT, sizeof(double) * (size_t)p->nt);

    /* the paper's |s^(m+1) - s^m|^2 / |s^(m+1)|^2 < eps_fp^2 */
    double num = 0, den = 0;
    for (int i = 0; i < m; i++) {
        st->snew[i] = fr->Fi[i] * (it->lN[i] > 0 ? it->lN[i] : 0);
        num += (st->snew[i] - st->sb[i]) * (st->snew[i] - st->sb[i]);
        den += st->snew[i] * st->snew[i];
    }
    it->own = den > 0 ? sqrt(num / den) : (num > 0 ? INFINITY : 0);
    it->own_done = it->own < st->eps_fp;
    return CX_OK;
}

const cx_method cx_method_cf_fp = {
    .id = "cf-fp",
    .name = "Coulomb by successive Tresca problems (fixed point)",
    .source = "002 §5",
    .summary = "fixed point s = F lN over any Tresca method (inner=auto: ssn-tresca, else ubr-tf), one factorisation for all steps",
    .supports = CX_COULOMB | CX_2D | CX_3D,
    .state_size = sizeof(cffp_state),
    .params = cffp_params,
    .init = cffp_init,
    .step = cffp_step,
    .destroy = cffp_destroy,
};
