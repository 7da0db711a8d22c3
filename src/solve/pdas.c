/* SPDX-License-Identifier: GPL-3.0-or-later */
/* pdas — primal-dual active set (block principal pivoting), paper 003 §4
 * (Hintermüller, Ito & Kunisch), on the regularised LCP A + eps I, then the
 * projection: PDAS again on the unregularised A, started from the
 * regularised solution (003 §4, "the two-stage projection").
 *
 * Each iteration predicts the active set {i in S : lam_i - tau v_i > 0}
 * (v_i = 0 there, lam_i = 0 elsewhere) and solves the principal subsystem
 * of the free unknowns: one numeric Cholesky of A + eps I with the active
 * rows and columns replaced by the identity (same pattern, so the symbolic
 * analysis is done once), or, with schur = 1, of the dense reduced
 * Schur-complement LCP (Table 7). Start v = 0, lam = -b. Own criterion:
 * the set repeats (then the iterate solves the LCP exactly).
 *
 * update = N (sparse systems, both stages): when at most N unknowns change
 * sets and (model = 1, the default) the entries of L the row changes would
 * touch are below CX_LCP_UPDATE_RATIO x nnz(L), the previous factor is
 * changed row by row (CHOLMOD row delete / row add, lcp.c) instead of
 * refactorised; late iterations change a few joints. The updated and the
 * new factor round differently, and the regularised systems (condition
 * near amax / eps = 1e10) can turn a joint at a tie: the solution is the
 * same to 1e-10, the iteration count from the paper's start may differ
 * (test_masonry). update = 0 refactorises every time.
 * With updates the projection's first system (the regularised stage's
 * last set, eps = 0) is solved by CG on the regularised factor instead of
 * a new factorisation (lcp.c, cx_lcp_solver.pre).
 *
 * start = closed (ours): the first set closes every contact and the
 * regularised stage takes plain steps (pdas_warm); on the masonry walls,
 * where 1.5-4 % of the joints end open, the later steps change a few
 * joints and the updates apply: one or two factorisations per run. Where
 * most of the contact ends open it costs iterations (punch: 11 against 3).
 *
 * search = 1 (default, ours): the step towards the new subsystem's solution
 * is shortened until the natural residual falls (lcp.h); a full step is the
 * paper's. Plain block pivoting (search = 0) cycles on running bond from
 * 1/25 on in the stress case g = H/2 (the scenes' g = H/100 does not need
 * the search); Judice-Pires single pivots then end it after hundreds of
 * factorisations, or not at all. */
#include "solve/lcp.h"

#include <string.h>

/* The default cap of "update": high enough that the cost model (model =
 * 1, lcp.h CX_LCP_UPDATE_RATIO) decides; with model = 0 the count alone
 * decides, and 200 was its measured default (stack bond 1/100: a row
 * change costs about 1/250 of a refactorisation there, far more on
 * running bond, whose interlocked bricks give the factor more fill). */
#define CX_PDAS_UPDATE_MAX 100000
#define CX_PDAS_UPDATE_COUNT 200

typedef struct {
    cx_lcp_run run;
    cx_lcp_solver reg;    /* masked solves with A + eps I */
    double eps;           /* current regularisation (continuation down to run.eps) */
    int plain;            /* warm start: plain steps in the regularised stage (pdas_warm) */
} pdas_state;

static const cx_param pdas_params[] = {
    CX_LCP_PARAMS_COMMON,
    {"eps0", CX_PARAM_REAL, 0, 0, 1, NULL,
     "continuation: start with this eps (relative) and divide by 100 down to eps (0: off)", 0},
    {"update", CX_PARAM_INT, -1, -1, 1e9, NULL,
     "update the factor row by row when at most this many unknowns change sets (and, with model "
     "= 1, the rows' work is below a new factor's), else refactorise (0: always refactorise; "
     "-1: 100000 with the model, 200 without)", 0},
    {"model", CX_PARAM_BOOL, 1, 0, 1, NULL,
     "1: update when the changed rows touch at most 38 x nnz(L) entries of the factor (the "
     "break-even with a new factor); 0: the count rule alone (update = N, 200 if not given)", 0},
    {"start", CX_PARAM_CHOICE, 0, 0, 1, "paper|closed",
     "first set: paper (from v = 0, 003 §4) or closed (every contact closed, then plain steps: "
     "fewer iterations where few open, e.g. the masonry walls; more where most do)", 0},
    CX_LCP_PARAM_SCHUR,
    CX_LCP_PARAM_SCHUR_EPS,
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void pdas_destroy(void *state)
{
    pdas_state *st = state;
    cx_lcp_solver_clear(&st->reg);
    cx_lcp_run_clear(&st->run);
}

/* The first set from a start other than the paper's v = 0: start =
 * closed (every constrained unknown active: every joint closed, the
 * bodies bonded), or a start with contact forces (cx_session_set_start),
 * whose points with lN > 0 are closed. On the masonry walls 1.5-4 % of
 * the joints end open: from the closed start the first solve is near the
 * answer and later iterations change a few joints, where factor updates
 * apply (stack bond 1/100: 3 iterations and one factorisation against 19
 * and 17 from v = 0). Only the set is taken; the first step solves on it
 * from v = 0. The regularised stage then takes plain (full) steps: the
 * damping is for the swings from the paper's start, and near the answer
 * it shortens steps the full ones do not need; the Judice-Pires guard
 * keeps them finite. */
static void pdas_warm(pdas_state *st, cx_session *s, int closed)
{
    cx_lcp_run *r = &st->run;
    const cx_problem *p = cx_session_problem(s);
    const cx_iterate *it = cx_session_iterate(s);
    int warm = closed;
    for (int k = 0; k < p->m && !warm; k++)
        warm = it->lN[k] > 0;
    if (!warm)
        return;
    int n = r->L->n;
    /* the slot of row k in r->L: its pivot, or its place among the
     * constrained slots of the reduced LCP */
    int nc = r->map->full.nc;
    for (int i = 0; i < n; i++)
        r->lam[i] = 0;
    for (int k = 0; k < p->m; k++) {
        int j = r->map->piv[k];
        if (r->reduced) {
            int lo = 0, hi = nc - 1;   /* sidx ascending */
            while (lo < hi) {
                int mid = (lo + hi) / 2;
                if (r->map->sidx[mid] < j)
                    lo = mid + 1;
                else
                    hi = mid;
            }
            j = lo;
        }
        r->lam[j] = closed ? 1 : it->lN[k] > 0 ? it->lN[k] : 0;
    }
    /* the first plain step takes the set {lam > 0} at v = 0 */
    for (int i = 0; i < n; i++)
        r->act[i] = 2;
    st->plain = 1;
}

static int pdas_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    pdas_state *st = state;
    int reduced = cx_param_get(params, "schur") != 0;
    CX_TRY(cx_lcp_run_init(&st->run, s, params, reduced, d));
    cx_lcp_run *r = &st->run;
    int status = cx_lcp_solver_init(&st->reg, r->L, cx_session_counters(s), d);
    int upd = (int)cx_param_get(params, "update"), model = cx_param_get(params, "model") != 0;
    if (upd < 0)   /* the default: the model decides, or the count rule's own default */
        upd = model ? CX_PDAS_UPDATE_MAX : CX_PDAS_UPDATE_COUNT;
    if (!status)
        status = cx_lcp_solver_updates(&st->reg, upd, d);
    if (!status && r->project)
        status = cx_lcp_solver_updates(&r->proj, upd, d);
    st->reg.model = r->proj.model = model;
    r->proj.like = &st->reg;   /* the projection's factor: the same pattern when on the same LCP */
    if (status) {
        pdas_destroy(st);
        return status;
    }
    st->eps = cx_param_get(params, "eps0") * (r->L->amax > 0 ? r->L->amax : 1);
    if (st->eps < r->eps)
        st->eps = r->eps;
    for (int i = 0; i < r->L->n; i++) {
        r->lam[i] = r->L->S[i] ? -r->L->b[i] : 0;   /* lam = A v - b at v = 0 */
        r->act[i] = 2;
    }
    st->plain = 0;
    pdas_warm(st, s, cx_param_get(params, "start") == 1);
    return CX_OK;
}

static int pdas_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    pdas_state *st = state;
    cx_lcp_run *r = &st->run;
    if (r->stage == 0) {
        int same = 0;
        if (st->plain)
            CX_TRY(cx_lcp_pdas_step(&st->reg, st->eps, r->c, r->v, r->lam, r->act, &r->guard, &same,
                                    r->work, d));
        else
            CX_TRY(cx_lcp_run_pdas_step(r, &st->reg, st->eps, &same, d));
        if (same && st->eps > r->eps) {
            /* the next eps, started from this set */
            st->eps = st->eps / 100 > r->eps ? st->eps / 100 : r->eps;
            r->guard.best = r->L->n + 1;
            CX_TRY(cx_lcp_pdas_resolve(&st->reg, st->eps, r->v, r->lam, r->act, r->work, d));
            r->ls.Av_valid = r->guard.Av_valid = 0;   /* v moved */
            same = 0;
        }
        if (!same) {
            int active = 0;
            for (int i = 0; i < r->L->n; i++)
                active += r->act[i] != 0;
            it->own = active;
            return cx_lcp_run_publish(r, s, it);
        }
        CX_TRY(cx_lcp_run_stage_done(r, it, d));
        if (r->stage == 2)
            return CX_OK;
    }
    return cx_lcp_run_project(r, s, it, d);
}

const cx_method cx_method_pdas = {
    .id = "pdas",
    .name = "Primal-dual active set + projection",
    .source = "003 §4",
    .summary = "block principal pivoting on the regularised LCP, then one PDAS projection on the "
               "unregularised one; sparse masked Cholesky (or the dense Schur LCP)",
    .supports = CX_FRICTIONLESS | CX_2D | CX_3D | CX_MULTIBODY,
    .state_size = sizeof(pdas_state),
    .params = pdas_params,
    .init = pdas_init,
    .step = pdas_step,
    .destroy = pdas_destroy,
};
