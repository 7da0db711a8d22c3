/* SPDX-License-Identifier: GPL-3.0-or-later */
/* psor — projected successive over-relaxation (paper 003 §4; Glowinski,
 * Lions & Trémolières) on the regularised LCP A + eps I, then the
 * projection of §4.
 *
 * One sweep updates v_i += omega (b - (A + eps I) v)_i / (A_ii + eps) in
 * order and projects v_i onto [0, inf) for constrained i; A is symmetric,
 * so its columns are its rows (no transpose). u0 = 0. One step is 'sweeps'
 * sweeps; the own criterion is the paper's: the largest change in a sweep
 * below tol times the largest |v|, tol = n eps_machine by default; after
 * max_sweeps the projection starts anyway (it needs only the right active
 * set). Slow by nature (Table 3): the floating bodies make A + eps I badly
 * conditioned.
 *
 * omega: the paper writes 2 / (1 + sin(pi / n)). Read with n the order of A
 * that is 1.9994 at 1/25, and the set still flipped at 2e5 sweeps; we read
 * n as in Glowinski's optimal omega for a grid of spacing 1 / N, with N
 * the nodes per side of a square (cubic) grid of n unknowns: 1.91 at 1/25,
 * where PSOR converges in 1e4 - 5e4 sweeps. */
#include "solve/lcp.h"

#include <float.h>
#include <math.h>
#include <string.h>

typedef struct {
    cx_lcp_run run;
    double omega, tol;
    double best_own;      /* smallest own criterion so far */
    int sweeps;
    long max_sweeps, done;
    double *diag;
} psor_state;

static const cx_param psor_params[] = {
    /* eps 1e-7 (relative) rather than the others' 1e-10: the sweeps that
     * settle the floating bodies grow like 1 / eps (1e-8: 1/15 running bond
     * unfinished after 1e5), and 1e-6 leaves the regularised set wrong at a
     * few running-bond joints (the projection then takes 2 iterations) */
    {"eps", CX_PARAM_REAL, 1e-7, 0, 1e-2, NULL,
     "regularisation A + eps I, relative to the largest diagonal entry of A", 0},
    CX_LCP_PARAMS_STAGE,
    {"omega", CX_PARAM_REAL, 0, 0, 2, NULL,
     "relaxation in (0, 2); 0: 2 / (1 + sin(pi / N)), N = (n / dim)^(1 / dim)", 0},
    {"sweeps", CX_PARAM_INT, 2000, 1, 1e6, NULL, "sweeps per step", 0},
    {"tol", CX_PARAM_REAL, 0, 0, 1, NULL, "largest change per sweep, relative; 0: n eps_machine", 0},
    {"max_sweeps", CX_PARAM_INT, 80000, 1, 1e9, NULL,
     "sweeps after which the projection starts anyway (it is exact once the set is right)", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void psor_destroy(void *state)
{
    psor_state *st = state;
    cx_free(st->diag);
    cx_lcp_run_clear(&st->run);
}

static int psor_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    psor_state *st = state;
    CX_TRY(cx_lcp_run_init(&st->run, s, params, 0, d));
    const cx_lcp *L = st->run.L;
    int n = L->n;
    st->omega = cx_param_get(params, "omega");
    if (!(st->omega > 0 && st->omega < 2)) {
        /* Glowinski's 2 / (1 + sin(pi / N)) with N the node intervals per
         * side of the equivalent square (cubic) grid of n unknowns */
        int dim = cx_session_problem(s)->dim;
        double N = pow((double)n / dim, 1.0 / dim);
        st->omega = 2 / (1 + sin(3.14159265358979323846 / (N > 2 ? N : 2)));
    }
    st->tol = cx_param_get(params, "tol");
    if (!(st->tol > 0))
        st->tol = n * DBL_EPSILON;
    st->sweeps = (int)cx_param_get(params, "sweeps");
    st->max_sweeps = (long)cx_param_get(params, "max_sweeps");
    st->best_own = INFINITY;
    st->diag = CX_NEW(double, n);
    if (!st->diag) {
        psor_destroy(st);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    for (int i = 0; i < n; i++)
        st->diag[i] = cx_csc_get(&L->A, i, i) + st->run.eps;
    return CX_OK;
}

static int psor_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    psor_state *st = state;
    cx_lcp_run *r = &st->run;
    if (r->stage > 0)
        return cx_lcp_run_project(r, s, it, d);
    const cx_lcp *L = r->L;
    const cx_csc *A = &L->A;
    double *v = r->v, change = 0;
    int k = 0;
    for (; k < st->sweeps; k++) {
        /* a cancel or the time limit acts within CX_CHECK_INTERVAL sweeps */
        if (k > 0 && k % CX_CHECK_INTERVAL == 0 && cx_session_interrupted(s))
            break;
        change = 0;
        for (int i = 0; i < L->n; i++) {
            double res = L->b[i] - r->eps * v[i];
            for (int q = A->p[i]; q < A->p[i + 1]; q++)
                res -= A->x[q] * v[A->i[q]];
            double vi = v[i] + st->omega * res / st->diag[i];
            if (L->S[i] && vi < 0)
                vi = 0;
            change = fmax(change, fabs(vi - v[i]));
            v[i] = vi;
        }
    }
    it->inner = k;
    st->done += k;
    double vmax = cx_vec_norminf(L->n, v);
    it->own = vmax > 0 ? change / vmax : change;
    /* near the regularised solution the kkt error rests at its O(eps)
     * floor while the sweeps still converge: not a stall */
    if (it->own < 0.5 * st->best_own) {
        st->best_own = it->own;
        it->progress = 1;
    }
    if (it->own <= st->tol || st->done >= st->max_sweeps) {
        CX_TRY(cx_lcp_run_stage_done(r, it, d));
        if (r->stage == 1) {
            CX_TRY(cx_lcp_run_project(r, s, it, d));
            return CX_OK;
        }
    }
    return cx_lcp_run_publish(r, s, it);
}

const cx_method cx_method_psor = {
    .id = "psor",
    .name = "Projected SOR + projection",
    .source = "003 §4",
    .summary = "projected successive over-relaxation on the regularised LCP (sparse rows), then "
               "the PDAS projection",
    .supports = CX_FRICTIONLESS | CX_2D | CX_3D | CX_MULTIBODY,
    .state_size = sizeof(psor_state),
    .params = psor_params,
    .init = psor_init,
    .step = psor_step,
    .destroy = psor_destroy,
};
