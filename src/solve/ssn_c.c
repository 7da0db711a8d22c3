/* SPDX-License-Identifier: GPL-3.0-or-later */
/* ssn-c — semismooth Newton for frictionless contact with parameter r,
 * paper 002 §7 (Algorithm SSN-C, the paper's comparison method), 2D and 3D.
 *
 * The Moreau-Yosida regularised problem: with lam = (lhat + r(u_N - g))+
 * (lhat = 0 as in the paper, a penalty of the boundary-integral form
 * r (u_N - g, v_N)_W), each Newton step predicts the active set
 * A = {lhat + r(u_N - g) > 0} from the last iterate and solves
 *     (K + r N_A'W N_A) u = f + N_A'W (r g - lhat),
 * then lam = lhat + r(u_N - g) on A, 0 elsewhere; lN = W lam. It stops when
 * the active set repeats (its own criterion: the iterate then solves the
 * regularised problem exactly). The answer carries the penetration of the
 * penalty, O(lam / r): a large r (default 1e3 E) approaches the contact
 * solution, which the kkt error measures. The first set comes from the
 * paper's start u0 = -u0 along the normal (0.01 in the paper, fixing the
 * vertical rigid mode of hertz): A = {g < u0}. Linear algebra: the matrix
 * has the pattern of K + N'WN for every active set (inactive rows are
 * explicit zeros), so the symbolic analysis is done once and each
 * iteration is one numeric factorisation and one solve. */
#include "solve/solve.h"

#include <math.h>
#include <string.h>

typedef struct {
    cx_fact *F;           /* owned: analysed once, factorised per iteration */
    cx_csc_aug A;         /* n x n: K + r N_A'W N_A on the pattern of K + N'N */
    double *wr;           /* m: the rows' weights r w_i on A, 0 elsewhere */
    double r;             /* absolute r */
    double u0;            /* the start's normal displacement */
    unsigned char *act;   /* m: active set of this iteration */
    unsigned char *prev;  /* m: of the previous iteration */
    double *Nu;           /* m */
    double *rhs;          /* n */
    double *tmp;          /* m */
} ssnc_state;

static const cx_param ssnc_params[] = {
    {"r", CX_PARAM_REAL, 1e3, 1e-12, 1e16, NULL, "penalty r in units of E (paper: 1e3)", 0},
    {"u0", CX_PARAM_REAL, 0.01, 0, 1e30, NULL,
     "the start: a normal displacement u0 towards the obstacle (paper: 0.01)", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void ssnc_destroy(void *state)
{
    ssnc_state *st = state;
    cx_fact_destroy(&st->F);
    cx_csc_aug_clear(&st->A);
    cx_free(st->wr);
    cx_free(st->act);
    cx_free(st->prev);
    cx_free(st->Nu);
    cx_free(st->rhs);
    cx_free(st->tmp);
    memset(st, 0, sizeof *st);
}

static int ssnc_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    ssnc_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    double E = cx_problem_stiffness(p);
    st->r = cx_param_get(params, "r") * E;
    st->u0 = cx_param_get(params, "u0");
    st->act = CX_NEW(unsigned char, p->m);
    st->prev = CX_NEW(unsigned char, p->m);
    st->Nu = CX_NEW(double, p->m);
    st->tmp = CX_NEW(double, p->m);
    st->rhs = CX_NEW(double, p->n);
    st->wr = CX_NEW(double, p->m + 1);
    int status = st->act && st->prev && st->Nu && st->tmp && st->rhs && st->wr ? CX_OK : CX_ENOMEM;
    const cx_csc *rows = &p->N;
    /* as the operator cache does: a cancel stops the system's build and
     * analysis before they start (the explorer screens methods this way,
     * at no cost) */
    if (!status && cx_session_interrupted(s)) {
        ssnc_destroy(st);
        return cx_diag_set(d, CX_ENUMERIC, "interrupted before building ssn-c's system");
    }
    if (!status)
        status = cx_csc_aug_build(&st->A, &p->K, &rows, 1);
    if (status)
        cx_diag_set(d, status, status == CX_ENOMEM ? "out of memory" : "ssn-c: the sizes of K and N do not fit");
    if (!status && !(status = cx_fact_create(&st->F, CX_FACT_CHOLESKY, cx_session_counters(s), d)))
        status = cx_fact_analyze(st->F, &st->A.A, d);
    if (status) {
        ssnc_destroy(st);
        return status;
    }
    /* the paper's start: u0 along the normal, lhat = 0 */
    for (int i = 0; i < p->m; i++)
        st->act[i] = st->r * (st->u0 - p->g[i]) > 0;
    memset(st->prev, 2, (size_t)p->m);   /* no previous set */
    return CX_OK;
}

static int ssnc_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    ssnc_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    int m = p->m;
    const double *w = p->contact.weight;

    if (it->iter > 0) {
        cx_csc_gemv(&p->N, 1.0, it->u, 0.0, st->Nu);
        for (int i = 0; i < m; i++)
            st->act[i] = st->r * (st->Nu[i] - p->g[i]) > 0;
    }
    if (memcmp(st->act, st->prev, (size_t)m) == 0) {
        it->own = 0;
        it->own_done = 1;
        return CX_OK;
    }
    int changed = 0;
    for (int i = 0; i < m; i++)
        changed += st->act[i] != st->prev[i];
    memcpy(st->prev, st->act, (size_t)m);

    /* (K + r N_A'W N_A) u = f + r N_A'W g */
    for (int i = 0; i < m; i++) {
        st->wr[i] = st->act[i] ? st->r * w[i] : 0;
        st->tmp[i] = st->wr[i] * p->g[i];
    }
    cx_csc_aug_fill(&st->A, &p->K, st->wr);
    memcpy(st->rhs, p->f, sizeof(double) * (size_t)p->n);
    cx_csc_gemv_t(&p->N, 1.0, st->tmp, 1.0, st->rhs);
    int status = cx_fact_factorize(st->F, &st->A.A, d);
    if (status)
        return cx_diag_set(d, status, "ssn-c: the active set of iteration %d (%d points) does not "
                           "hold the body: %s", it->iter + 1, m, cx_diag_msg(d, status));
    CX_TRY(cx_fact_solve(st->F, st->rhs, it->u, d));

    /* lam = r (u_N - g) on A */
    cx_csc_gemv(&p->N, 1.0, it->u, 0.0, st->Nu);
    for (int i = 0; i < m; i++)
        it->lN[i] = st->act[i] ? w[i] * fmax(st->r * (st->Nu[i] - p->g[i]), 0.0) : 0;
    it->own = changed;   /* points whose set changed */
    return CX_OK;
}

const cx_method cx_method_ssn_c = {
    .id = "ssn-c",
    .name = "Semismooth Newton with parameter r (frictionless)",
    .source = "002 §7",
    .summary = "active set of the regularised problem, pattern fixed: one analysis, a factorisation per iteration",
    .supports = CX_FRICTIONLESS | CX_2D | CX_3D,
    .state_size = sizeof(ssnc_state),
    .params = ssnc_params,
    .init = ssnc_init,
    .step = ssnc_step,
    .destroy = ssnc_destroy,
};
