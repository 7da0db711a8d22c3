/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The generic step: the method's step, then in one place the kkt error,
 * the contact status and its changes, the timing, and the outcome. */
#include "solve/session_impl.h"

#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>

static const struct {
    int value;
    const char *id, *word;
} reason_table[] = {
#define CX_REASON_ROW_(name, value, id, word) {value, id, word},
    CX_REASON_LIST(CX_REASON_ROW_)
#undef CX_REASON_ROW_
};

#define REASON_COUNT (sizeof reason_table / sizeof reason_table[0])

const char *cx_reason_str(int reason)
{
    for (size_t k = 0; k < REASON_COUNT; k++)
        if (reason_table[k].value == reason)
            return reason_table[k].word;
    return "unknown";
}

const char *cx_reason_id(int reason)
{
    for (size_t k = 0; k < REASON_COUNT; k++)
        if (reason_table[k].value == reason)
            return reason_table[k].id;
    return "unknown";
}

char *cx_reason_format(int reason, int iter, double kkt, double tol, const char *msg, char *buf,
                       size_t len)
{
    if (!buf || len == 0)
        return buf;
    const char *w = cx_reason_str(reason);
    int has_msg = msg && msg[0];
    char at[96] = "";
    /* the kkt error and the tolerance, never a NaN or Inf */
    if (isfinite(kkt))
        snprintf(at, sizeof at, "kkt error %.3g %s tol %.3g", kkt, kkt <= tol ? "<=" : ">", tol);
    else
        snprintf(at, sizeof at, "no finite kkt error (tol %.3g)", tol);
    switch (reason) {
    case CX_CONVERGED_KKT:
        snprintf(buf, len, "%s in %d iterations: %s", w, iter, at);
        break;
    case CX_STOPPED_OWN:
        snprintf(buf, len, "%s at %s after %d iterations: not converged", w, at, iter);
        break;
    case CX_DIVERGED_MAXIT:
        snprintf(buf, len, "%s in %d iterations: %s", w, iter, at);
        break;
    case CX_DIVERGED_STALL:
        snprintf(buf, len, "%s: the kkt error no longer decreases (%s after %d iterations)", w, at,
                 iter);
        break;
    case CX_REFUSED:
        snprintf(buf, len, "%s: %s", w, has_msg ? msg : "the method does not take this problem");
        break;
    case CX_DIVERGED:
    case CX_DIVERGED_BREAKDOWN:
        snprintf(buf, len, "%s at iteration %d: %s%s%s%s", w, iter,
                 has_msg ? msg : "the method cannot continue", isfinite(kkt) ? " (" : "",
                 isfinite(kkt) ? at : "", isfinite(kkt) ? ")" : "");
        break;
    case CX_DIVERGED_NAN:
        snprintf(buf, len, "%s: %s", w, has_msg ? msg : "a NaN or Inf in the iterate");
        break;
    case CX_CANCELLED:
    case CX_DIVERGED_TIME:
        snprintf(buf, len, "%s%s after %d iterations: %s%s%s", w, reason == CX_DIVERGED_TIME ? " reached" : "",
                 iter, at, has_msg ? "; " : "", has_msg ? msg : "");
        break;
    default:
        snprintf(buf, len, "%s after %d iterations: %s", w, iter, at);
        break;
    }
    return buf;
}

char *cx_session_outcome(const cx_session *s, char *buf, size_t len)
{
    const cx_iterate *it = &s->it;
    return cx_reason_format(it->reason, it->iter, it->kkt, s->opt.tol, s->reason_msg, buf, len);
}

/* Status of every contact point from the iterate, by the same natural maps
 * as the kkt error: in contact if lN + rho (N u - g) > 0; sticking if
 * |lT + rho T u| <= s. Every method is classified the same way. */
static void solver_classify(cx_session *s)
{
    const cx_problem *p = s->p;
    const cx_friction_state *fr = &s->fr;
    cx_iterate *it = &s->it;
    int m = p->m, dt = p->dim - 1;
    double *Nu = s->work, *Tu = s->work + m;
    double L, U;
    cx_kkt_scales(p, fr->law, it->u, it->lN, it->lT, &L, &U);
    double rho = L / U;
    cx_csc_gemv(&p->N, 1.0, it->u, 0.0, Nu);
    if (fr->law != CX_FRICTION_NONE)
        cx_csc_gemv(&p->T, 1.0, it->u, 0.0, Tu);
    it->nfree = it->ncontact = it->nstick = it->nslip = it->nchanged = 0;
    for (int i = 0; i < m; i++) {
        unsigned char st = CX_PT_FREE;
        /* a relative margin keeps exactly-grazing points (lN = 0, gap = 0) free */
        if (it->lN[i] + rho * (Nu[i] - p->g[i]) > 1e-12 * L) {
            if (fr->law == CX_FRICTION_NONE) {
                st = CX_PT_CONTACT;
            } else {
                double z[2], nz = 0;
                for (int c = 0; c < dt; c++) {
                    z[c] = it->lT[dt * i + c] + rho * Tu[dt * i + c];
                    nz += z[c] * z[c];
                }
                double sb = cx_friction_slip_bound(fr, i, it->lN[i]);
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
        it->kkt = cx_kkt_error(s->p, &s->fr, it->u, it->lN, it->lT, s->work, cx_session_counters(s),
                               &it->kkt_parts);
        return CX_OK;
    }
    cx_schur *S;
    const double *fc;
    cx_problem q = *s->p;   /* the condensed rows are those of the reduction the iterate came from */
    if (it->u_partial == CX_PARTIAL_NORMAL) {
        const int *dofs;
        CX_TRY(cx_session_schur_normal(s, &S, &fc, &dofs, &q.nc, d));
        q.cdofs = (int *)dofs;   /* read only */
    } else
        CX_TRY(cx_session_schur(s, &S, &fc, d));
    it->kkt = cx_kkt_error_condensed(&q, &s->fr, cx_schur_matrix(S), fc, it->u, it->lN, it->lT, s->work,
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
    const int *dofs = p->cdofs;
    int nd = p->nc;
    if (it->u_partial == CX_PARTIAL_NORMAL)
        CX_TRY(cx_session_schur_normal(s, &S, NULL, &dofs, &nd, d));
    else
        CX_TRY(cx_session_schur(s, &S, NULL, d));
    for (int k = 0; k < nd; k++)
        s->uc[k] = it->u[dofs[k]];
    int st = cx_schur_expand(S, p->f, s->uc, it->u);
    cx_session_sync_counters_(s);
    if (st != CX_OK)
        return cx_diag_set(d, st, "expanding the iterate from the contact dofs failed");
    it->u_partial = 0;
    return solver_kkt(s, d);
}

/* Whether this session (not one above it) is cancelled or past its time
 * limit: the deadline of the step, or the run's measured time. */
static int solver_cancelled(const cx_session *s)
{
    return atomic_load(&s->cancel) != 0;
}

static int solver_timed_out(const cx_session *s, double time)
{
    if (s->opt.time_limit > 0 && time >= s->opt.time_limit)
        return 1;
    return s->has_deadline && cx_session_clock_(s) >= s->deadline;
}

/* The outcome after a step, from the kkt error, the flags and the limits;
 * time: the run's time including this step. Converged means the kkt error
 * is at or below the tolerance, and nothing else does. */
static int solver_outcome(cx_session *s, double time)
{
    const cx_iterate *it = &s->it;
    if (it->kkt <= s->opt.tol)
        return CX_CONVERGED_KKT;
    if (solver_cancelled(s))
        return CX_CANCELLED;
    if (solver_timed_out(s, time))
        return CX_DIVERGED_TIME;
    if (s->parent && cx_session_interrupted(s->parent))
        return CX_CANCELLED;   /* the run above it is ending */
    if (it->own_done && s->opt.own_stop)
        return CX_STOPPED_OWN;
    if (it->iter >= s->opt.max_iter)
        return CX_DIVERGED_MAXIT;
    if (s->opt.stall_window > 0 && it->iter - s->best_iter >= s->opt.stall_window)
        return CX_DIVERGED_STALL;
    return CX_ITERATING;
}

/* The first non-finite value of the iterate, as a message: "NaN in u
 * (entry 12) at iteration 3", "overflow: Inf in lN ...", or the kkt
 * error's own overflow. Returns 0 if all is finite. */
static int solver_nonfinite(const cx_session *s, char *msg, size_t len)
{
    const cx_iterate *it = &s->it;
    const cx_problem *p = s->p;
    const struct { const char *name; const double *x; int n; } vecs[] = {
        {"u", it->u, p->n}, {"lN", it->lN, p->m}, {"lT", it->lT, p->nt}};
    for (size_t v = 0; v < sizeof vecs / sizeof vecs[0]; v++)
        for (int i = 0; i < vecs[v].n; i++)
            if (!isfinite(vecs[v].x[i])) {
                if (isnan(vecs[v].x[i]))
                    snprintf(msg, len, "NaN in %s (entry %d) at iteration %d", vecs[v].name, i, it->iter);
                else
                    snprintf(msg, len, "overflow: Inf in %s (entry %d) at iteration %d", vecs[v].name, i,
                             it->iter);
                return 1;
            }
    if (!isfinite(it->kkt)) {
        snprintf(msg, len, "%s in the kkt error at iteration %d (the iterate is finite)",
                 isnan(it->kkt) ? "NaN" : "overflow: Inf", it->iter);
        return 1;
    }
    return 0;
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

static int solver_step(cx_session *s, cx_diag *d)
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
    /* the time limit as a deadline on the clock, for the checks inside
     * the step (cx_session_interrupted) */
    s->has_deadline = s->opt.time_limit > 0;
    if (s->has_deadline)
        s->deadline = cx_session_clock_(s) + (s->opt.time_limit - it->time);
    /* the step's time: the method's step and the expansion of a partial
     * iterate, not the kkt error */
    double t0 = cx_clock_now();
    int st = s->method->step(s->state, s, it, &local);
    it->step_time = cx_clock_now() - t0;
    it->iter++;
    it->inner_total += it->inner;
    /* a method that declares its end (breakdown, divergence) ends the run
     * now, with its message: no later test may overwrite it */
    int declared = it->reason == CX_DIVERGED_BREAKDOWN || it->reason == CX_DIVERGED ? it->reason : 0;
    if (declared) {
        snprintf(s->reason_msg, sizeof s->reason_msg, "%s",
                 local.msg[0] ? local.msg : "the method cannot continue");
        it->reason = CX_ITERATING;   /* set again below, once the bookkeeping is done */
        if (st != CX_OK && st != CX_ENOMEM)
            st = CX_OK;              /* the message is the outcome's, not an error of the run */
    }
    if (st == CX_OK)
        st = solver_kkt(s, &local);
    double run_time = it->time + it->step_time;
    if (st == CX_OK && isfinite(it->kkt)) {
        solver_track_best(s);
        /* a run that ends here ends on the whole iterate; a nested run's
         * is read by the method that runs it, which may need only the
         * contact dofs (cf-fp) */
        if (it->u_partial && !s->parent && (declared || solver_outcome(s, run_time) != CX_ITERATING)) {
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
        /* a step cut short by a cancel or the time limit may fail on the
         * way out (an inner run cancelled): the outcome is the cancel */
        int cut = solver_cancelled(s) ? CX_CANCELLED
                  : solver_timed_out(s, it->time) ? CX_DIVERGED_TIME
                  : s->parent && cx_session_interrupted(s->parent) ? CX_CANCELLED
                  : CX_ITERATING;
        /* a method that cannot go on is an outcome, with its reason (a
         * declared end keeps the method's words) */
        it->reason = cut != CX_ITERATING ? cut : declared ? declared : CX_DIVERGED_BREAKDOWN;
        if (!declared)
            snprintf(s->reason_msg, sizeof s->reason_msg, "%s", cx_diag_msg(&local, st));
        return CX_OK;
    }
    if (declared) {
        if (isfinite(it->kkt))
            solver_classify(s);
        it->reason = declared;
        return CX_OK;
    }
    char msg[CX_DIAG_LEN];
    if (solver_nonfinite(s, msg, sizeof msg)) {
        it->reason = CX_DIVERGED_NAN;
        snprintf(s->reason_msg, sizeof s->reason_msg, "%s", msg);
        return CX_OK;
    }
    solver_classify(s);
    it->reason = solver_outcome(s, it->u_partial ? run_time : it->time);
    return CX_OK;
}

int cx_solver_step(cx_session *s, cx_diag *d)
{
    int st = solver_step(s, d);
    /* the deadline holds during a step only: the time between steps (the
     * explorer paused) is not the run's */
    s->has_deadline = 0;
    return st;
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
