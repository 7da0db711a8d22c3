/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The explorer's jobs: a build, a switch of method or friction, or one
 * step, on a worker thread (inline in the tests). No curses here. */
#include "tui/tui_impl.h"

#include <pthread.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Runs on the worker (or inline): touches only the job, the scene (read)
 * and, for a resolve, the session, which the main thread leaves alone. */
/* The pickers' law and its one value (the slip bound or F, by the law)
 * over base's other scalar, as a friction state. */
static cx_friction_state state_friction(cx_friction law, double coef, const cx_friction_state *base)
{
    cx_friction_state fr = {law, base->slip_bound, base->F, NULL, NULL};
    if (law == CX_FRICTION_TRESCA)
        fr.slip_bound = coef;
    else if (law == CX_FRICTION_COULOMB)
        fr.F = coef;
    return fr;
}

/* Try the switch on a nested session over the same system (its own
 * friction state, the shared operator cache) before touching the session:
 * a method that refuses at init (a dual method when K is singular) then
 * leaves the session's iterate, run and counters exactly as they were.
 * The probe's work (an operator it put in the cache) is returned in *work
 * so that the run it opens is charged with it. */
static int job_probe(cx_session *s, const cx_friction_state *fr, tui_job *j, cx_counters *work)
{
    cx_counters *run = cx_session_counters(s), saved = *run;
    cx_session *child = NULL;
    int status = cx_session_nested_create(&child, s, &j->diag);
    if (status == CX_OK)
        status = cx_session_set_friction(child, fr, &j->diag);
    if (status == CX_OK)
        status = cx_session_set_method(child, j->method, &j->params, &j->opt, &j->diag);
    cx_session_destroy(&child);
    work->factorizations = run->factorizations - saved.factorizations;
    work->solves = run->solves - saved.solves;
    work->matvecs = run->matvecs - saved.matvecs;
    work->dual_products = run->dual_products - saved.dual_products;
    work->updates = run->updates - saved.updates;
    work->dense_factorizations = run->dense_factorizations - saved.dense_factorizations;
    *run = saved;   /* the current run did not do it */
    j->probed = status != CX_OK;
    return status;
}

/* Which methods refuse this problem outright, before anyone tries them:
 * each method (under each law it supports) is set on a nested session
 * while the session's cancel flag is up, so that every operator a method
 * would build (a factorisation, the Schur complement) is refused as
 * interrupted before it starts, and only what a method knows for free
 * comes through: the dual methods' "K is not positive definite" when the
 * supports leave a body held by contact alone (solve/dual.c), or a refusal
 * the operator cache remembers. Nothing is built, nothing counted; the
 * session's own set_method clears the flag after. */
static void job_screen_methods(cx_session *s, const cx_friction_state *base, tui_job *j)
{
    const cx_problem *p = cx_session_problem(s);
    cx_counters *run = cx_session_counters(s), saved = *run;
    cx_session_cancel(s);
    for (int i = 0; i < cx_method_count(); i++)
        for (int law = 0; law < 3; law++) {
            const cx_method *m = cx_method_at(i);
            j->refused[i][law][0] = '\0';
            if (cx_method_check(m, p, (cx_friction)law, NULL) != CX_OK)
                continue;   /* greyed by its flags already */
            cx_friction_state fr = *base;
            fr.law = (cx_friction)law;
            fr.s = fr.Fi = NULL;
            cx_session *child = NULL;
            cx_diag d;
            cx_diag_clear(&d);
            int status = cx_session_nested_create(&child, s, &d);
            if (status == CX_OK)
                status = cx_session_set_friction(child, &fr, &d);
            if (status == CX_OK)
                status = cx_session_set_method(child, m, NULL, NULL, &d);
            cx_session_destroy(&child);
            if (status == CX_EUNSUPPORTED)
                snprintf(j->refused[i][law], CX_DIAG_LEN, "%s", d.msg);
        }
    *run = saved;
}

/* A build: the scene's problem at the level, its session under the law,
 * the methods screened, the method set. Touches only j and the scene it
 * is given (a copy of its own when on a worker: an abandoned build runs on
 * after the explorer has moved on). */
static void job_build(tui_job *j, const cx_scene *scene)
{
    cx_problem *p = NULL;
    cx_friction_state fr;
    atomic_store(&j->phase, TUI_PHASE_ASSEMBLE);
    j->status = cx_scene_build(scene, j->level, &p, &fr, &j->diag);
    if (j->status == CX_OK)
        j->status = cx_session_create(&j->session, &p, &j->diag);
    cx_problem_destroy(&p);
    if (j->status == CX_OK) {
        fr = state_friction(j->law, j->coef, &fr);
        j->status = cx_session_set_friction(j->session, &fr, &j->diag);
    }
    if (j->status == CX_OK && j->refused)
        job_screen_methods(j->session, &fr, j);
    if (j->status == CX_OK) {
        atomic_store(&j->phase, TUI_PHASE_FACTORISE);
        j->status = cx_session_set_method(j->session, j->method, &j->params, &j->opt, &j->diag);
    }
}

/* A build on a worker owns its inputs and outputs here, so that Esc can
 * abandon it: the explorer drops the box and goes on at once; the worker
 * finishes (a factorisation cannot be interrupted), sees that nobody
 * waits, and frees the session it built and the box. */
enum { BOX_RUNNING, BOX_DONE, BOX_ABANDONED };
typedef struct job_box {
    tui_job job;           /* the worker's copy of the job */
    cx_scene scene;        /* the scene it builds */
    pthread_t thread;
    atomic_int state;      /* BOX_* */
} job_box;

static void box_free(job_box *b)
{
    cx_session_destroy(&b->job.session);
    free(b->job.refused);
    free(b);
}

static void *box_thread(void *arg)
{
    job_box *b = arg;
    cx_diag_clear(&b->job.diag);
    b->job.status = CX_OK;
    job_build(&b->job, &b->scene);
    atomic_store(&b->job.phase, TUI_PHASE_DONE);
    if (atomic_exchange(&b->state, BOX_DONE) == BOX_ABANDONED) {
        box_free(b);   /* detached: nobody will join or read it */
#ifdef __GLIBC__
        malloc_trim(0);   /* and give the pages back, not only to malloc */
#endif
    }
    return NULL;
}

static void job_run(tui_state *st)
{
    tui_job *j = &st->job;
    cx_diag_clear(&j->diag);
    j->status = CX_OK;
    if (j->kind == TUI_JOB_BUILD) {
        job_build(j, &st->scene);
    } else if (j->kind == TUI_JOB_STEP) {
        atomic_store(&j->phase, TUI_PHASE_STEP);
        cx_session *s = st->session;
        j->status = cx_solver_step(s, &j->diag);
        const cx_iterate *it = cx_session_iterate(s);
        j->kkt = it->kkt;
        j->counters = it->counters;
        memset(&j->draw, 0, sizeof j->draw);
        if (j->status == CX_OK && j->expand && it->u_partial) {
            /* the mesh view draws the whole u: expanding it is the
             * explorer's work, not the run's (solve does not do it), so it
             * is counted apart and the run's counters are put back. Only
             * on single steps: a run ('r') is stepped as solve steps it */
            cx_counters *run = cx_session_counters(s), saved = *run;
            j->status = cx_session_complete_iterate(s, &j->diag);
            j->draw.solves = run->solves - saved.solves;
            j->draw.factorizations = run->factorizations - saved.factorizations;
            j->draw.matvecs = run->matvecs - saved.matvecs;
            *run = saved;
        }
    } else if (j->kind == TUI_JOB_RESOLVE) {
        cx_session *s = st->session;
        cx_friction_state old = *cx_session_friction(s), fr = state_friction(j->law, j->coef, &old);
        double coef = old.law == CX_FRICTION_COULOMB ? old.F : old.slip_bound;
        int law_changes = j->law != old.law || j->coef != coef;
        atomic_store(&j->phase, TUI_PHASE_FACTORISE);
        memset(&j->probe, 0, sizeof j->probe);
        if (cx_session_method(s))
            j->status = job_probe(s, &fr, j, &j->probe);
        if (j->status == CX_OK && law_changes) {
            /* the old method may not support the new law: it goes first */
            if (j->method != cx_session_method(s))
                cx_session_clear_method(s);
            j->status = cx_session_set_friction(s, &fr, &j->diag);
        }
        if (j->status == CX_OK)
            j->status = cx_session_set_method(s, j->method, &j->params, &j->opt, &j->diag);
        if (j->status != CX_OK && st->cur_method && !j->probed) {
            /* refused where the probe passed (or no probe): back to the
             * old method, so the explorer always has a method to step */
            old.s = old.Fi = NULL;   /* restored from the scalars, as they were set */
            cx_session_set_friction(s, &old, NULL);
            cx_session_set_method(s, st->cur_method, &st->cur_params, &st->cur_opt, NULL);
        }
    }
    atomic_store(&j->phase, TUI_PHASE_DONE);
}

static void *job_thread(void *arg)
{
    job_run(arg);
    return NULL;
}

void tui_job_start(tui_state *st, int kind)
{
    tui_job *j = &st->job;
    j->kind = kind;
    j->t0 = cx_clock_now();
    j->level = st->sel_level;
    j->method = tui_state_sel_method(st);
    j->params = st->sel_params;
    j->opt = st->sel_opt;
    j->law = st->sel_law;
    j->coef = st->sel_law == CX_FRICTION_COULOMB ? st->sel_F : st->sel_slip;
    j->session = NULL;
    j->probed = 0;
    j->expand = !st->running;
    memset(&j->probe, 0, sizeof j->probe);
    if (kind == TUI_JOB_BUILD && !j->refused)
        j->refused = tui_xalloc(NULL, sizeof j->refused[0] * (size_t)(cx_method_count() + 1));
    atomic_store(&j->phase, TUI_PHASE_IDLE);
    if (kind == TUI_JOB_PETSC) {
        /* on the backend's own thread, never on a job thread (backend.c) */
        const char *id = tui_backend_method(st->sel_backend - 1);
        atomic_store(&j->phase, TUI_PHASE_STEP);
        cx_diag_clear(&j->diag);
        j->status = tui_backend_start(st, cx_session_problem(st->session), cx_session_friction(st->session),
                                      id ? id : "ssn-tresca", &st->sel_opt, &j->diag);
        if (j->status != CX_OK || st->sync)
            tui_state_poll(st);
        return;
    }
    /* 'running' is kept: a run asked for during the job starts after it */
    if (!st->sync && kind == TUI_JOB_BUILD) {
        job_box *b = calloc(1, sizeof *b);
        if (b) {
            b->job = *j;
            b->job.worker = NULL;
            b->job.box = NULL;
            b->job.session = NULL;
            b->job.refused = calloc((size_t)cx_method_count() + 1, sizeof j->refused[0]);
            b->scene = st->scene;
            atomic_init(&b->state, BOX_RUNNING);
            atomic_init(&b->job.phase, TUI_PHASE_IDLE);
            if (b->job.refused && pthread_create(&b->thread, NULL, box_thread, b) == 0) {
                j->box = b;
                return;
            }
            free(b->job.refused);
            free(b);
        }
    }
    if (!st->sync) {
        pthread_t *t = malloc(sizeof *t);
        if (t && pthread_create(t, NULL, job_thread, st) == 0) {
            j->worker = t;
            return;
        }
        free(t);
    }
    job_run(st);
    tui_state_poll(st);
}

int tui_job_phase(const tui_state *st)
{
    const tui_job *j = &st->job;
    if (j->box)
        return atomic_load(&((job_box *)j->box)->job.phase);
    return atomic_load(&((tui_job *)j)->phase);
}

/* A boxed build has ended: its results into the state's job. */
static void job_unbox(tui_job *j)
{
    job_box *b = j->box;
    pthread_join(b->thread, NULL);
    j->status = b->job.status;
    j->diag = b->job.diag;
    cx_session_destroy(&j->session);
    j->session = b->job.session;
    b->job.session = NULL;
    if (j->refused && b->job.refused)
        memcpy(j->refused, b->job.refused, sizeof j->refused[0] * (size_t)cx_method_count());
    box_free(b);
    j->box = NULL;
    atomic_store(&j->phase, TUI_PHASE_DONE);
}

/* Set once a build was abandoned in this process: the program then leaves
 * through _exit, since a library's exit handlers may wait for threads the
 * abandoned build used (OpenBLAS's shutdown joins its pool, and can hang). */
static atomic_int job_abandoned;

int tui_job_abandoned_any(void)
{
    return atomic_load(&job_abandoned);
}

int tui_job_abandon(tui_state *st)
{
    tui_job *j = &st->job;
    job_box *b = j->box;
    if (!b)
        return 0;
    if (atomic_exchange(&b->state, BOX_ABANDONED) == BOX_DONE) {
        /* it ended meanwhile: nobody else will free it */
        pthread_join(b->thread, NULL);
        box_free(b);
    } else {
        pthread_detach(b->thread);
        atomic_store(&job_abandoned, 1);
    }
    j->box = NULL;
    j->kind = TUI_JOB_NONE;
    return 1;
}

int tui_job_ended(tui_state *st)
{
    tui_job *j = &st->job;
    if (j->kind == TUI_JOB_NONE)
        return 0;
    if (j->box) {
        if (atomic_load(&((job_box *)j->box)->state) != BOX_DONE)
            return 0;
        job_unbox(j);
        return 1;
    }
    if (j->kind == TUI_JOB_PETSC) {
        if (j->status == CX_OK && !tui_backend_done(st))
            return 0;
        atomic_store(&j->phase, TUI_PHASE_DONE);
        return 1;
    }
    if (atomic_load(&j->phase) != TUI_PHASE_DONE)
        return 0;
    if (j->worker) {
        pthread_join(*(pthread_t *)j->worker, NULL);
        free(j->worker);
        j->worker = NULL;
    }
    return 1;
}

void tui_job_clear(tui_state *st)
{
    tui_job *j = &st->job;
    /* a build on its worker is left to finish on its own */
    tui_job_abandon(st);
    if (j->kind == TUI_JOB_PETSC)   /* a PETSc run stops at its next step */
        tui_backend_cancel(st);
    if (j->worker) {
        /* a step or a switch uses the session: wait for it */
        pthread_join(*(pthread_t *)j->worker, NULL);
        free(j->worker);
        j->worker = NULL;
    }
    cx_session_destroy(&j->session);
    free(j->refused);
    j->refused = NULL;
}
