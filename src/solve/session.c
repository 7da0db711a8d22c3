/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The session: a problem, its friction state, its cache of shared
 * operators, the current method with its private state, and the iterate.
 * Switching method, parameters or friction keeps the cache (doc/design.md §5:
 * assemble and factorise once). */
#include "solve/session_impl.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void cx_options_default(cx_options *o)
{
    o->tol = 1e-10;
    o->max_iter = 500;
    o->own_stop = 1;
    o->stall_window = 50;
    o->time_limit = 0;
}

static void session_free_iterate(cx_iterate *it)
{
    cx_free(it->u);
    cx_free(it->lN);
    cx_free(it->lT);
    cx_free(it->status);
    cx_free(it->changed);
}

int cx_session_create_(cx_session **sp, const cx_problem *p, cx_session *parent, cx_diag *d)
{
    cx_session *s = CX_NEW(cx_session, 1);
    if (!s)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    s->p = p;
    s->parent = parent;
    atomic_init(&s->cancel, 0);
    cx_options_default(&s->opt);
    s->it.u = CX_NEW(double, p->n);
    s->it.lN = CX_NEW(double, p->m);
    s->it.lT = CX_NEW(double, p->nt);
    s->it.status = CX_NEW(unsigned char, p->m);
    s->it.changed = CX_NEW(unsigned char, p->m);
    s->work = CX_NEW(double, p->n + p->m + p->nt);
    s->uc = CX_NEW(double, p->nc);
    s->s = CX_NEW(double, p->m);
    s->Fi = CX_NEW(double, p->m);
    if (!s->it.u || !s->it.lN || !s->it.lT || !s->it.status || !s->it.changed || !s->work ||
        !s->uc || !s->s || !s->Fi) {
        cx_session_destroy(&s);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    s->fr = (cx_friction_state){CX_FRICTION_NONE, 0, 0, s->s, s->Fi};
    *sp = s;
    return CX_OK;
}

static void session_drop_method(cx_session *s)
{
    if (s->method && s->state && s->method->destroy)
        s->method->destroy(s->state);
    cx_free(s->state);
    s->state = NULL;
    s->method = NULL;
}

int cx_session_create(cx_session **sp, cx_problem **pp, cx_diag *d)
{
    CX_TRY(cx_session_create_(sp, *pp, NULL, d));
    (*sp)->own = *pp;
    *pp = NULL;
    return CX_OK;
}

void cx_session_destroy(cx_session **sp)
{
    if (!sp || !*sp)
        return;
    cx_session *s = *sp;
    session_drop_method(s);
    cx_schur_destroy(&s->schur);
    cx_free(s->schur_load);
    cx_schur_destroy(&s->schur_n);
    cx_free(s->schur_n_load);
    cx_free(s->ndofs);
    cx_free(s->uc);
    for (int i = 0; i < s->nentries; i++) {
        if (s->entries[i].destroy && s->entries[i].obj)
            s->entries[i].destroy(s->entries[i].obj);
        cx_free(s->entries[i].msg);
    }
    cx_free(s->entries);
    session_free_iterate(&s->it);
    cx_free(s->work);
    cx_free(s->start);
    cx_free(s->s);
    cx_free(s->Fi);
    cx_problem_destroy(&s->own);   /* NULL in a nested session: the parent owns the system */
    cx_free(s);
    *sp = NULL;
}

const cx_problem *cx_session_problem(const cx_session *s) { return s->p; }
const cx_friction_state *cx_session_friction(const cx_session *s) { return &s->fr; }
const cx_counters *cx_session_cache_counters(const cx_session *s)
{
    while (s->parent)   /* a nested session shares its root's cache */
        s = s->parent;
    return &s->cache;
}
cx_counters *cx_session_counters(cx_session *s) { return &cx_session_root_(s)->run; }
const cx_method *cx_session_method(const cx_session *s) { return s->method; }
const cx_param_values *cx_session_params(const cx_session *s) { return &s->params; }
const cx_options *cx_session_options(const cx_session *s) { return &s->opt; }
const cx_iterate *cx_session_iterate(const cx_session *s) { return &s->it; }
const char *cx_session_reason_msg(const cx_session *s) { return s->reason_msg; }

void cx_session_set_options(cx_session *s, const cx_options *opt)
{
    s->opt = *opt;
    cx_iterate *it = &s->it;
    /* a run ended by a limit, a stall, a cancel or its own criterion may go
     * on under new options; a breakdown, NaN, divergence or refusal may not */
    switch (it->reason) {
    case CX_CONVERGED_KKT:
        if (it->kkt > s->opt.tol)
            it->reason = s->opt.own_stop && it->own_done ? CX_STOPPED_OWN : CX_ITERATING;
        break;
    case CX_STOPPED_OWN:
        if (it->kkt <= s->opt.tol)
            it->reason = CX_CONVERGED_KKT;
        else if (!s->opt.own_stop)
            it->reason = CX_ITERATING;
        break;
    case CX_DIVERGED_MAXIT:
    case CX_DIVERGED_STALL:
    case CX_DIVERGED_TIME:
    case CX_CANCELLED:
        atomic_store(&s->cancel, 0);
        it->reason = CX_ITERATING;
        break;
    default:
        break;
    }
}

void cx_session_cancel(cx_session *s)
{
    atomic_store(&s->cancel, 1);
}

int cx_session_stop(void *session)
{
    return cx_session_interrupted(session);
}

void cx_session_set_clock(cx_session *s, cx_clock_fn now, void *ctx)
{
    s->clock = now;
    s->clock_ctx = ctx;
}

int cx_session_interrupted(cx_session *s)
{
    for (; s; s = s->parent) {
        if (atomic_load(&s->cancel))
            return 1;
        if (s->has_deadline && cx_session_clock_(s) >= s->deadline)
            return 1;
    }
    return 0;
}

/* Add the work done since 'before' to the cache counters. */
static void session_count_cache(cx_session *s, const cx_counters *before)
{
    s->cache.factorizations += s->run.factorizations - before->factorizations;
    s->cache.solves += s->run.solves - before->solves;
    s->cache.matvecs += s->run.matvecs - before->matvecs;
    s->cache.dual_products += s->run.dual_products - before->dual_products;
}

int cx_session_schur(cx_session *s, cx_schur **S, const double **fc, cx_diag *d)
{
    if (s->parent)   /* a nested session has its parent's K and f */
        return cx_session_schur(s->parent, S, fc, d);
    if (!s->schur) {
        /* as in cx_session_cache_get: a cancel or the time limit stops a
         * factorisation before it starts (it cannot once it has) */
        if (cx_session_interrupted(s))
            return cx_diag_set(d, CX_ENUMERIC, "interrupted before building the Schur complement");
        cx_counters before = s->run;
        int st = CX_ENOMEM;
        if ((s->schur_load = CX_NEW(double, s->p->nc)))
            st = cx_schur_create(&s->schur, &s->p->K, s->p->cdofs, s->p->nc, &s->run, d);
        if (st == CX_OK)
            st = cx_schur_condense(s->schur, s->p->f, s->schur_load);
        session_count_cache(s, &before);
        if (st != CX_OK) {
            cx_schur_destroy(&s->schur);
            cx_free(s->schur_load);
            s->schur_load = NULL;
            return st == CX_ENOMEM ? cx_diag_set(d, st, "out of memory") : st;
        }
    }
    *S = s->schur;
    if (fc)
        *fc = s->schur_load;
    return CX_OK;
}

/* The dofs the rows of N touch, ascending (a subset of p->cdofs). */
static int session_normal_dofs(cx_session *s)
{
    const cx_csc *N = &s->p->N;
    int nn = 0;
    for (int j = 0; j < N->ncol; j++)
        nn += N->p[j + 1] > N->p[j];
    if (!(s->ndofs = CX_NEW(int, nn > 0 ? nn : 1)))
        return CX_ENOMEM;
    s->nn = 0;
    for (int j = 0; j < N->ncol; j++)
        if (N->p[j + 1] > N->p[j])
            s->ndofs[s->nn++] = j;
    return CX_OK;
}

int cx_session_schur_normal(cx_session *s, cx_schur **S, const double **fc, const int **dofs, int *nd,
                            cx_diag *d)
{
    if (s->parent)
        return cx_session_schur_normal(s->parent, S, fc, dofs, nd, d);
    if (!s->ndofs && session_normal_dofs(s))
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    /* the full reduction serves when N touches every contact dof, and when
     * it is built and this one is not: a frictionless run after a run with
     * friction then factorises nothing (its dense system is larger). Else
     * the normal dofs alone, in 2D as in 3D: with fewer dofs held last the
     * factor fills less (hertz 256: 257 of 513 contact dofs, and an
     * ordering that keeps only those last beats CAMD on all 513 by 15 % in
     * flops), and a later change of law builds the full reduction beside
     * this one once; neither is ever factorised twice */
    if (s->nn == s->p->nc || (s->schur && !s->schur_n)) {
        if (S)
            CX_TRY(cx_session_schur(s, S, fc, d));
        if (dofs)
            *dofs = s->p->cdofs;
        *nd = s->p->nc;
        return CX_OK;
    }
    if (dofs)
        *dofs = s->ndofs;
    *nd = s->nn;
    if (!S)
        return CX_OK;
    if (!s->schur_n) {
        if (cx_session_interrupted(s))
            return cx_diag_set(d, CX_ENUMERIC, "interrupted before building the Schur complement");
        cx_counters before = s->run;
        int st = CX_ENOMEM;
        if ((s->schur_n_load = CX_NEW(double, s->nn > 0 ? s->nn : 1)))
            st = cx_schur_create(&s->schur_n, &s->p->K, s->ndofs, s->nn, &s->run, d);
        if (st == CX_OK)
            st = cx_schur_condense(s->schur_n, s->p->f, s->schur_n_load);
        session_count_cache(s, &before);
        if (st != CX_OK) {
            cx_schur_destroy(&s->schur_n);
            cx_free(s->schur_n_load);
            s->schur_n_load = NULL;
            return st == CX_ENOMEM ? cx_diag_set(d, st, "out of memory") : st;
        }
    }
    *S = s->schur_n;
    if (fc)
        *fc = s->schur_n_load;
    return CX_OK;
}

const cx_schur *cx_session_schur_built(const cx_session *s)
{
    while (s->parent)
        s = s->parent;
    return s->schur ? s->schur : s->schur_n;
}

int cx_session_cache_get(cx_session *s, const char *key, cx_cache_build_fn build,
                         const void *arg, cx_cache_destroy_fn destroy, void **obj, cx_diag *d)
{
    if (strlen(key) >= CX_CACHE_KEYLEN)
        return cx_diag_set(d, CX_EINVAL, "operator cache key too long: '%s'", key);
    if (s->parent)
        return cx_session_cache_get(s->parent, key, build, arg, destroy, obj, d);
    for (int i = 0; i < s->nentries; i++)
        if (strcmp(s->entries[i].key, key) == 0) {
            *obj = s->entries[i].obj;
            return s->entries[i].status == CX_OK
                       ? CX_OK
                       : cx_diag_set(d, s->entries[i].status, "%s", s->entries[i].msg);
        }
    /* a factorisation cannot be interrupted: the cancel flag and the time
     * limit are checked before it (after it, by the generic step); not a
     * failure of the matrix, so nothing is remembered */
    if (cx_session_interrupted(s))
        return cx_diag_set(d, CX_ENUMERIC, "interrupted before building '%s'", key);
    if (s->nentries == s->centries) {
        int cap = s->centries ? 2 * s->centries : 4;
        cx_cache_entry *e = cx_realloc(s->entries, sizeof *e * (size_t)cap);
        if (!e)
            return cx_diag_set(d, CX_ENOMEM, "out of memory");
        s->entries = e;
        s->centries = cap;
    }
    cx_counters before = s->run;
    void *made = NULL;
    cx_diag bd;
    cx_diag_clear(&bd);
    int st = build(&made, s->p, arg, &s->run, &bd);
    session_count_cache(s, &before);
    if (d && st != CX_OK)
        *d = bd;
    /* a matrix that cannot be factorised stays so: remember the failure
     * (and a refusal the build turned it into, as dual.c does), so that no
     * method switch pays for the same failed factorisation again */
    char *msg = st == CX_ENUMERIC || st == CX_EUNSUPPORTED ? cx_malloc(strlen(bd.msg) + 1) : NULL;
    if (st != CX_OK && !msg)
        return st;
    cx_cache_entry *e = &s->entries[s->nentries++];
    snprintf(e->key, sizeof e->key, "%s", key);
    e->obj = made;
    e->destroy = destroy;
    e->status = st;
    e->msg = msg;
    if (msg)
        memcpy(msg, bd.msg, strlen(bd.msg) + 1);
    *obj = made;
    return st;
}

int cx_session_cache_size(const cx_session *s)
{
    if (s->parent)
        return cx_session_cache_size(s->parent);
    return s->nentries + (s->schur != NULL) + (s->schur_n != NULL);
}

/* Zero the iterate and the run counters for a new run. */
static void session_clear_run(cx_session *s)
{
    cx_iterate *it = &s->it;
    const cx_problem *p = s->p;
    memset(it->u, 0, sizeof(double) * (size_t)p->n);
    memset(it->lN, 0, sizeof(double) * (size_t)p->m);
    memset(it->lT, 0, sizeof(double) * (size_t)p->nt);
    memset(it->status, 0, (size_t)p->m);
    memset(it->changed, 0, (size_t)p->m);
    it->iter = 0;
    it->u_partial = 0;
    it->reason = CX_ITERATING;
    it->kkt = INFINITY;
    it->kkt_parts = (cx_kkt){INFINITY, INFINITY, INFINITY, INFINITY};
    it->own = NAN;
    it->own_done = 0;
    it->progress = 0;
    it->nfree = p->m;
    it->ncontact = it->nstick = it->nslip = it->nchanged = 0;
    it->inner = it->inner_total = 0;
    it->step_time = it->time = it->init_time = 0;
    if (s->start) {
        memcpy(it->u, s->start, sizeof(double) * (size_t)p->n);
        memcpy(it->lN, s->start + p->n, sizeof(double) * (size_t)p->m);
        memcpy(it->lT, s->start + p->n + p->m, sizeof(double) * (size_t)p->nt);
    }
    if (s->parent)
        s->base = cx_session_root_(s)->run;
    else
        memset(&s->run, 0, sizeof s->run);
    memset(&it->counters, 0, sizeof it->counters);
    s->best_kkt = INFINITY;
    s->best_iter = 0;
    s->reason_msg[0] = '\0';
    s->has_deadline = 0;
    atomic_store(&s->cancel, 0);
}

int cx_session_set_method(cx_session *s, const cx_method *m, const cx_param_values *params,
                          const cx_options *opt, cx_diag *d)
{
    CX_TRY(cx_method_check(m, s->p, s->fr.law, d));
    cx_param_values values;
    if (params)
        values = *params;
    else
        cx_param_default(&values, m->params);
    session_drop_method(s);
    session_clear_run(s);
    if (opt)
        s->opt = *opt;
    s->state = cx_calloc(1, m->state_size ? m->state_size : 1);
    if (!s->state)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    s->method = m;
    s->params = values;
    double t0 = cx_clock_now();
    int st = m->init(s->state, s, &s->params, d);
    s->it.init_time = cx_clock_now() - t0;
    s->it.time = s->it.init_time;
    cx_session_sync_counters_(s);
    if (st != CX_OK) {
        /* init frees what it built on failure; drop the shell */
        cx_free(s->state);
        s->state = NULL;
        s->method = NULL;
        if (st == CX_EUNSUPPORTED) {
            s->it.reason = CX_REFUSED;
            snprintf(s->reason_msg, sizeof s->reason_msg, "%s", d ? d->msg : m->id);
        }
        return st;
    }
    return CX_OK;
}

void cx_session_clear_method(cx_session *s)
{
    session_drop_method(s);
    session_clear_run(s);
}

int cx_session_reset(cx_session *s, cx_diag *d)
{
    if (!s->method)
        return cx_diag_set(d, CX_EINVAL, "no method selected");
    cx_param_values params = s->params;
    return cx_session_set_method(s, s->method, &params, NULL, d);
}

/* Make fr the session's friction state (checked): the scalars, and the
 * per-point values given or expanded from them (slip bounds are nodal
 * forces: the traction bound times the lumped measure of the contact
 * boundary at the point). */
static void session_put_friction(cx_session *s, const cx_friction_state *fr)
{
    const cx_problem *p = s->p;
    for (int i = 0; i < p->m; i++) {
        s->s[i] = fr->s ? fr->s[i] : fr->slip_bound * p->contact.weight[i];
        s->Fi[i] = fr->Fi ? fr->Fi[i] : fr->F;
    }
    s->fr = (cx_friction_state){fr->law, fr->slip_bound, fr->F, s->s, s->Fi};
}

/* Re-init the current method (a new run) after a friction change; if it
 * refuses the new state and old is given (the state before, with its
 * per-point values), restore old and the method. */
static int session_refriction(cx_session *s, const cx_friction_state *old, cx_diag *d)
{
    const cx_method *m = s->method;
    if (!m)
        return CX_OK;
    cx_param_values params = s->params;
    int st = cx_session_set_method(s, m, &params, NULL, d);
    if (st != CX_OK && old) {
        session_put_friction(s, old);
        cx_session_set_method(s, m, &params, NULL, NULL);
    }
    return st;
}

int cx_session_set_friction(cx_session *s, const cx_friction_state *fr, cx_diag *d)
{
    const cx_problem *p = s->p;
    CX_TRY(cx_friction_check(fr, p->m, d));
    /* the old state, to restore if the method refuses the new law */
    double *keep = s->method ? CX_NEW(double, 2 * (size_t)p->m + 1) : NULL;
    if (s->method && !keep)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    cx_friction_state old = s->fr;
    if (keep) {
        memcpy(keep, s->s, sizeof(double) * (size_t)p->m);
        memcpy(keep + p->m, s->Fi, sizeof(double) * (size_t)p->m);
        old.s = keep;
        old.Fi = keep + p->m;
    }
    session_put_friction(s, fr);
    int st = session_refriction(s, &old, d);
    cx_free(keep);
    return st;
}

int cx_session_set_tresca(cx_session *s, double slip_bound, cx_diag *d)
{
    cx_friction_state fr = {CX_FRICTION_TRESCA, slip_bound, s->fr.F, NULL, NULL};
    return cx_session_set_friction(s, &fr, d);
}

int cx_session_set_coulomb(cx_session *s, double F, cx_diag *d)
{
    cx_friction_state fr = {CX_FRICTION_COULOMB, s->fr.slip_bound, F, NULL, NULL};
    return cx_session_set_friction(s, &fr, d);
}

int cx_session_set_frictionless(cx_session *s, cx_diag *d)
{
    cx_friction_state fr = {CX_FRICTION_NONE, s->fr.slip_bound, s->fr.F, NULL, NULL};
    return cx_session_set_friction(s, &fr, d);
}

int cx_session_set_slip_bounds(cx_session *s, const double *sb, cx_diag *d)
{
    cx_friction_state fr = {CX_FRICTION_TRESCA, s->fr.slip_bound, s->fr.F, sb, s->Fi};
    CX_TRY(cx_friction_check(&fr, s->p->m, d));
    session_put_friction(s, &fr);
    return session_refriction(s, NULL, d);
}
