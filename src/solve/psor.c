/* psor — projected successive over-relaxation (paper 003 §4; Glowinski,
 * Lions & Trémolières) on the regularised LCP A + eps I, then the
 * projection of §4.
 *
 * One sweep updates v_i += omega (b - (A + eps I) v)_i / (A_ii + eps) in
 * order and projects v_i onto [0, inf) for constrained i; A is symmetric,
 * so its columns are its rows (no transpose). omega = 2 / (1 + sin(pi / n))
 * as in the paper, u0 = 0. One step is 'sweeps' sweeps; the own criterion
 * is the paper's: the largest change in a sweep below tol times the
 * largest |v|, tol = n eps_machine by default; after max_sweeps the
 * projection starts anyway (it needs only the right active set). Slow by nature (Table 3):
 * the floating bodies make A + eps I badly conditioned. */
#include "solve/lcp.h"

#include <float.h>
#include <math.h>
#include <string.h>

typedef struct {
    cx_lcp_run run;
    double omega, tol;
    int sweeps;
    long max_sweeps, done;
    double *diag;
} psor_state;

static const cx_param psor_params[] = {
    /* eps 1e-6 (relative) rather than the others' 1e-10: PSOR's sweeps grow
     * with the condition of A + eps I (1e-8 did not finish 1/5 in 10^5) */
    {"eps", CX_PARAM_REAL, 1e-6, 0, 1e-2, NULL,
     "regularisation A + eps I, relative to the largest diagonal entry of A", 0},
    CX_LCP_PARAMS_STAGE,
    {"omega", CX_PARAM_REAL, 0, 0, 2, NULL, "relaxation in (0, 2); 0: 2 / (1 + sin(pi / n))", 0},
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
    if (!(st->omega > 0 && st->omega < 2))
        st->omega = 2 / (1 + sin(3.14159265358979323846 / (n > 1 ? n : 2)));
    st->tol = cx_param_get(params, "tol");
    if (!(st->tol > 0))
        st->tol = n * DBL_EPSILON;
    st->sweeps = (int)cx_param_get(params, "sweeps");
    st->max_sweeps = (long)cx_param_get(params, "max_sweeps");
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
    for (int k = 0; k < st->sweeps; k++) {
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
    it->inner = st->sweeps;
    st->done += st->sweeps;
    double vmax = cx_vec_norminf(L->n, v);
    it->own = vmax > 0 ? change / vmax : change;
    if (it->own <= st->tol || st->done >= st->max_sweeps) {
        cx_lcp_run_stage_done(r, it);
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
