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

int cx_solver_step(cx_session *s, cx_diag *d)
{
    cx_iterate *it = &s->it;
    if (!s->method)
        return cx_diag_set(d, CX_EINVAL, "no method selected");
    if (it->reason != CX_ITERATING)
        return CX_OK;

    it->own = NAN;
    it->own_done = 0;
    it->inner = 0;
    cx_diag local;
    cx_diag_clear(&local);
    double t0 = cx_clock_now();
    int st = s->method->step(s->state, s, it, &local);
    it->step_time = cx_clock_now() - t0;
    it->time += it->step_time;
    it->iter++;
    it->inner_total += it->inner;
    if (st == CX_ENOMEM) {
        it->reason = CX_DIVERGED_BREAKDOWN;
        snprintf(s->reason_msg, sizeof s->reason_msg, "out of memory");
        return cx_diag_set(d, CX_ENOMEM, "out of memory in %s", s->method->id);
    }
    if (st != CX_OK) {
        /* a method that cannot go on is an outcome, with its reason */
        it->reason = CX_DIVERGED_BREAKDOWN;
        snprintf(s->reason_msg, sizeof s->reason_msg, "%s", cx_diag_msg(&local, st));
        cx_session_sync_counters_(s);
        return CX_OK;
    }

    it->kkt = cx_kkt_error(s->p, it->u, it->lN, it->lT, s->work, cx_session_counters(s),
                           &it->kkt_parts);
    cx_session_sync_counters_(s);
    if (!isfinite(it->kkt)) {
        it->reason = CX_DIVERGED_NAN;
        snprintf(s->reason_msg, sizeof s->reason_msg, "NaN or Inf in the iterate at iteration %d", it->iter);
        return CX_OK;
    }
    solver_classify(s);

    if (it->kkt < 0.5 * s->best_kkt) {
        s->best_kkt = it->kkt;
        s->best_iter = it->iter;
    }
    if (it->kkt <= s->opt.tol)
        it->reason = CX_CONVERGED_KKT;
    else if (it->own_done && s->opt.own_stop)
        it->reason = CX_CONVERGED_OWN;
    else if (it->iter >= s->opt.max_iter)
        it->reason = CX_DIVERGED_MAXIT;
    else if (s->opt.stall_window > 0 && it->iter - s->best_iter >= s->opt.stall_window)
        it->reason = CX_DIVERGED_STALL;
    else if (s->opt.time_limit > 0 && it->time >= s->opt.time_limit)
        it->reason = CX_DIVERGED_TIME;
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
