/* The generic step: the method's step, then in one place the kkt error,
 * the contact status and its changes, the timing, and the outcome. */
#include "solve/session_impl.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const struct {
    int value;
    const char *id, *text;
} reason_table[] = {
#define CX_REASON_ROW_(name, value, text) {value, #name, text},
    CX_REASON_LIST(CX_REASON_ROW_)
#undef CX_REASON_ROW_
};

const char *cx_reason_str(int reason)
{
    for (size_t k = 0; k < sizeof reason_table / sizeof reason_table[0]; k++)
        if (reason_table[k].value == reason)
            return reason_table[k].text;
    return "unknown reason";
}

const char *cx_reason_id(int reason)
{
    /* "CX_CONVERGED_KKT" -> "converged_kkt" */
    static char ids[sizeof reason_table / sizeof reason_table[0]][32];
    for (size_t k = 0; k < sizeof reason_table / sizeof reason_table[0]; k++)
        if (reason_table[k].value == reason) {
            if (!ids[k][0]) {
                const char *src = reason_table[k].id + 3;
                size_t i = 0;
                for (; src[i] && i < sizeof ids[k] - 1; i++)
                    ids[k][i] = (char)(src[i] >= 'A' && src[i] <= 'Z' ? src[i] - 'A' + 'a' : src[i]);
                ids[k][i] = '\0';
            }
            return ids[k];
        }
    return "unknown";
}

/* Status of every contact point from the iterate, by the same natural maps
 * as the kkt error: in contact if lN + rho (N u - g) > 0; sticking if
 * |lT + rho T u| <= s. Every method is classified the same way. */
static void solver_classify(cx_session *s)
{
    const cx_problem *p = s->p;
    cx_iterate *it = &s->it;
    int m = p->m, dt = p->dim - 1;
    double *Nu = s->work, *Tu = s->work + m;
    double L, U;
    cx_kkt_scales(p, it->u, it->lN, it->lT, &L, &U);
    double rho = L / U;
    cx_csc_gemv(&p->N, 1.0, it->u, 0.0, Nu);
    if (p->friction != CX_FRICTION_NONE)
        cx_csc_gemv(&p->T, 1.0, it->u, 0.0, Tu);
    it->nfree = it->ncontact = it->nstick = it->nslip = it->nchanged = 0;
    for (int i = 0; i < m; i++) {
        unsigned char st = CX_PT_FREE;
        /* a relative margin keeps exactly-grazing points (lN = 0, gap = 0) free */
        if (it->lN[i] + rho * (Nu[i] - p->g[i]) > 1e-12 * L) {
            if (p->friction == CX_FRICTION_NONE) {
                st = CX_PT_CONTACT;
            } else {
                double z[2], nz = 0;
                for (int c = 0; c < dt; c++) {
                    z[c] = it->lT[dt * i + c] + rho * Tu[dt * i + c];
                    nz += z[c] * z[c];
                }
                double sb = cx_problem_slip_bound(p, i, it->lN[i]);
                if (sqrt(nz) <= sb * (1 + 1e-12))
                    st = CX_PT_STICK;
                else
                    st = (dt == 1 && z[0] < 0) ? CX_PT_SLIP_NEG : CX_PT_SLIP_POS;
            }
        }
        it->changed[i] = it->iter > 1 && st != it->status[i];
        it->nchanged += it->changed[i];
        it->status[i] = st;
        it->nfree += st == CX_PT_FREE;
        it->ncontact += st == CX_PT_CONTACT;
        it->nstick += st == CX_PT_STICK;
        it->nslip += st == CX_PT_SLIP_POS || st == CX_PT_SLIP_NEG;
    }
}

/* The kkt error of the iterate: on the condensed system if u is partial. */
static int solver_kkt(cx_session *s, cx_diag *d)
{
    cx_iterate *it = &s->it;
    if (!it->u_partial) {
        it->kkt = cx_kkt_error(s->p, it->u, it->lN, it->lT, s->work, cx_session_counters(s), &it->kkt_parts);
        return CX_OK;
    }
    cx_schur *S;
    const double *fc;
    CX_TRY(cx_session_schur(s, &S, &fc, d));
    it->kkt = cx_kkt_error_condensed(s->p, cx_schur_matrix(S), fc, it->u, it->lN, it->lT, s->work,
                                     &it->kkt_parts);
    return CX_OK;
}

/* Expand a partial iterate's u from its contact dofs; its kkt error is
 * then that of the whole iterate. */
static int solver_expand(cx_session *s, cx_diag *d)
{
    cx_iterate *it = &s->it;
    const cx_problem *p = s->p;
    cx_schur *S;
    CX_TRY(cx_session_schur(s, &S, NULL, d));
    for (int k = 0; k < p->nc; k++)
        s->uc[k] = it->u[p->cdofs[k]];
    int st = cx_schur_expand(S, p->f, s->uc, it->u);
    cx_session_sync_counters_(s);
    if (st != CX_OK)
        return cx_diag_set(d, st, "expanding the iterate from the contact dofs failed");
    it->u_partial = 0;
    return solver_kkt(s, d);
}

/* The outcome after a step, from the kkt error and the limits; time: the
 * run's time including this step. */
static int solver_outcome(const cx_session *s, double time)
{
    const cx_iterate *it = &s->it;
    if (it->kkt <= s->opt.tol)
        return CX_CONVERGED_KKT;
    if (it->own_done && s->opt.own_stop)
        return CX_CONVERGED_OWN;
    if (it->iter >= s->opt.max_iter)
        return CX_DIVERGED_MAXIT;
    if (s->opt.stall_window > 0 && it->iter - s->best_iter >= s->opt.stall_window)
        return CX_DIVERGED_STALL;
    if (s->opt.time_limit > 0 && time >= s->opt.time_limit)
        return CX_DIVERGED_TIME;
    return CX_ITERATING;
}

/* Stall detection: the best kkt so far, and when it last halved (or the
 * method last reported progress of its own). */
static void solver_track_best(cx_session *s)
{
    if (s->it.kkt < 0.5 * s->best_kkt) {
        s->best_kkt = s->it.kkt;
        s->best_iter = s->it.iter;
    } else if (s->it.progress) {
        s->best_iter = s->it.iter;
    }
}

int cx_session_complete_iterate(cx_session *s, cx_diag *d)
{
    cx_iterate *it = &s->it;
    if (!it->u_partial)
        return CX_OK;
    CX_TRY(solver_expand(s, d));
    solver_track_best(s);
    if (it->reason == CX_ITERATING && isfinite(it->kkt))
        it->reason = solver_outcome(s, it->time);
    return CX_OK;
}

int cx_solver_step(cx_session *s, cx_diag *d)
{
    cx_iterate *it = &s->it;
    if (!s->method)
        return cx_diag_set(d, CX_EINVAL, "no method selected");
    if (it->reason != CX_ITERATING)
        return CX_OK;

    it->own = NAN;
    it->own_done = 0;
    it->progress = 0;
    it->inner = 0;
    cx_diag local;
    cx_diag_clear(&local);
    /* the step's time: the method's step and the expansion of a partial
     * iterate, not the kkt error */
    double t0 = cx_clock_now();
    int st = s->method->step(s->state, s, it, &local);
    it->step_time = cx_clock_now() - t0;
    it->iter++;
    it->inner_total += it->inner;
    if (st == CX_OK)
        st = solver_kkt(s, &local);
    double run_time = it->time + it->step_time;
    if (st == CX_OK && isfinite(it->kkt)) {
        solver_track_best(s);
        /* a run that ends here ends on the whole iterate; a nested run's
         * is read by the method that runs it, which may need only the
         * contact dofs (cf-fp) */
        if (it->u_partial && !s->parent && solver_outcome(s, run_time) != CX_ITERATING) {
            double t1 = cx_clock_now();
            st = solver_expand(s, &local);
            it->step_time += cx_clock_now() - t1;
            if (st == CX_OK)
                solver_track_best(s);
        }
    } else if (st != CX_OK && st != CX_ENOMEM && it->u_partial) {
        cx_diag ignored;
        solver_expand(s, &ignored);   /* the last good iterate, whole */
    }
    it->time += it->step_time;
    cx_session_sync_counters_(s);
    if (st == CX_ENOMEM) {
        it->reason = CX_DIVERGED_BREAKDOWN;
        snprintf(s->reason_msg, sizeof s->reason_msg, "out of memory");
        return cx_diag_set(d, CX_ENOMEM, "out of memory in %s", s->method->id);
    }
    if (st != CX_OK) {
        /* a method that cannot go on is an outcome, with its reason */
        it->reason = CX_DIVERGED_BREAKDOWN;
        snprintf(s->reason_msg, sizeof s->reason_msg, "%s", cx_diag_msg(&local, st));
        return CX_OK;
    }
    if (!isfinite(it->kkt)) {
        it->reason = CX_DIVERGED_NAN;
        snprintf(s->reason_msg, sizeof s->reason_msg, "NaN or Inf in the iterate at iteration %d", it->iter);
        return CX_OK;
    }
    solver_classify(s);
    it->reason = solver_outcome(s, it->u_partial ? run_time : it->time);
    return CX_OK;
}

int cx_solver_solve(cx_session *s, cx_observer obs, void *ctx, cx_diag *d)
{
    while (s->it.reason == CX_ITERATING) {
        CX_TRY(cx_solver_step(s, d));
        if (obs && obs(ctx, s, &s->it))
            break;
    }
    return CX_OK;
}
