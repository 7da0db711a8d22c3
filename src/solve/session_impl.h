/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Private to solve/: the session's fields, shared by session.c and
 * solver.c. */
#ifndef CX_SESSION_IMPL_H
#define CX_SESSION_IMPL_H

#include "solve/solve.h"

#include <stdatomic.h>

typedef struct cx_cache_entry {
    char key[CX_CACHE_KEYLEN];
    void *obj;
    cx_cache_destroy_fn destroy;
    int status;                  /* CX_ENUMERIC: the build failed on the matrix itself */
    char *msg;                   /* its message (a failed build is not tried again) */
} cx_cache_entry;

struct cx_session {
    const cx_problem *p;         /* the system: the root's own, a nested session's parent's */
    cx_problem *own;             /* the problem this session owns and frees (NULL when nested) */
    cx_friction_state fr;        /* the friction state; fr.s and fr.Fi point to s and Fi */
    double *s, *Fi;              /* m each: per-point slip bounds and coefficients */
    cx_schur *schur;             /* operator cache: K condensed onto p->cdofs, lazy ... */
    double *schur_load;          /* ... and f condensed with it (nc) */
    double *uc;                  /* nc: scratch to expand a partial iterate */
    cx_schur *schur_n;           /* operator cache: K condensed onto the normal dofs only
                                    (frictionless runs), lazy, beside schur ... */
    double *schur_n_load;        /* ... f condensed with it ... */
    int *ndofs, nn;              /* ... and those dofs (the columns N touches), ascending */
    cx_cache_entry *entries;     /* operator cache: everything else, by key */
    int nentries, centries;
    cx_counters cache;           /* work of building the cache, all runs */
    cx_counters run;             /* work of the current run (linalg writes here) */
    const cx_method *method;     /* current method, or NULL */
    void *state;                 /* its private state (method->state_size bytes) */
    cx_param_values params;
    cx_options opt;
    cx_iterate it;
    double *work;                /* n + m + nt, for the kkt error */
    double best_kkt;             /* stall detection: best kkt so far ... */
    int best_iter;               /* ... and when it last halved */
    char reason_msg[CX_DIAG_LEN];/* why a run broke down */
    atomic_int cancel;           /* cx_session_cancel: set from any thread or a signal handler */
    int has_deadline;            /* the current step has a time limit ... */
    double deadline;             /* ... which passes at this time of the clock */
    cx_clock_fn clock;           /* the time limit's clock (NULL: cx_clock_now) */
    void *clock_ctx;
    /* nested sessions (nested.c) */
    cx_session *parent;          /* the session whose cache and counters this one shares, or NULL */
    cx_counters base;            /* the root's run counters when this run started (nested) */
    double *start;               /* n + m + nt: warm start for the next run (u, lN, lT), or NULL */
};

/* A session over p, which it does not own (nested.c: the parent's
 * system), frictionless until a setter says otherwise. */
int cx_session_create_(cx_session **sp, const cx_problem *p, cx_session *parent, cx_diag *d);

/* The root of a chain of nested sessions (s itself if not nested). */
static inline cx_session *cx_session_root_(cx_session *s)
{
    while (s->parent)
        s = s->parent;
    return s;
}

/* The iterate's counters: the work of this run, counted in the root's run
 * counters since the run started. */
static inline void cx_session_sync_counters_(cx_session *s)
{
    const cx_counters *c = &cx_session_root_(s)->run;
    s->it.counters.factorizations = c->factorizations - s->base.factorizations;
    s->it.counters.solves = c->solves - s->base.solves;
    s->it.counters.matvecs = c->matvecs - s->base.matvecs;
    s->it.counters.dual_products = c->dual_products - s->base.dual_products;
    s->it.counters.dense_factorizations = c->dense_factorizations - s->base.dense_factorizations;
}

/* The time limit's clock. */
static inline double cx_session_clock_(const cx_session *s)
{
    return s->clock ? s->clock(s->clock_ctx) : cx_clock_now();
}

#endif
