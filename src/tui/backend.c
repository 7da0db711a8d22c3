/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The explorer's PETSc backend (one rank): a thread of its own that starts
 * PETSc, runs every PETSc solve the explorer asks for and ends PETSc when
 * the explorer closes. PETSc is not thread-safe and MPI wants its start and
 * end on one thread, so no other thread of the explorer ever calls the
 * backend (the job threads of job.c are new for each job: they could not
 * be that thread). A solve runs to its end as one job; its steps reach the
 * main thread through a buffer under a mutex as the observer sees them.
 * No curses here. */
#include "tui/tui_impl.h"
#include "cx_config.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#if CX_HAVE_PETSC
#include "petsc/petsc.h"

#include <pthread.h>
#include <stdatomic.h>

enum { BK_IDLE, BK_RUN, BK_QUIT };

struct tui_backend {
    pthread_t thread;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    int request;                 /* BK_*: set by the main thread, taken by the backend's */
    /* the run asked for (read by the backend's thread while it runs; the
     * explorer leaves the session alone while the job is busy) */
    const cx_problem *p;
    cx_friction_state fr;
    char method[32];
    cx_options opt;
    /* what comes back, under mu */
    cx_petsc_step *steps;
    int nsteps, cap, taken;
    int running, done;
    int status;
    cx_diag diag;
    cx_petsc_result res;
    atomic_int cancel;
};

static int bk_observe(void *ctx, const cx_petsc_step *s)
{
    tui_backend *b = ctx;
    pthread_mutex_lock(&b->mu);
    if (b->nsteps == b->cap) {
        int cap = b->cap ? 2 * b->cap : 64;
        cx_petsc_step *n = realloc(b->steps, sizeof *n * (size_t)cap);
        if (!n) {
            pthread_mutex_unlock(&b->mu);
            return 1;   /* out of memory: the run stops (cancelled) */
        }
        b->steps = n;
        b->cap = cap;
    }
    b->steps[b->nsteps++] = *s;
    pthread_mutex_unlock(&b->mu);
    return atomic_load(&b->cancel);
}

static void *bk_thread(void *arg)
{
    tui_backend *b = arg;
    cx_diag init;
    cx_diag_clear(&init);
    /* PETSc's own signal handlers would take the terminal's signals
     * (the explorer restores the terminal on SIGTERM itself) */
    const char *old = getenv("PETSC_OPTIONS");
    char opts[512];
    snprintf(opts, sizeof opts, "%s%s-no_signal_handler", old ? old : "", old ? " " : "");
    setenv("PETSC_OPTIONS", opts, 1);
    int init_status = cx_petsc_initialize(&init);
    pthread_mutex_lock(&b->mu);
    for (;;) {
        while (b->request == BK_IDLE)
            pthread_cond_wait(&b->cv, &b->mu);
        if (b->request == BK_QUIT)
            break;
        b->request = BK_IDLE;
        pthread_mutex_unlock(&b->mu);
        cx_diag d;
        cx_diag_clear(&d);
        cx_petsc_result r = {0};
        int status = init_status;
        if (status == CX_OK)
            status = cx_petsc_solve(b->p, &b->fr, b->method, &b->opt, bk_observe, b, &r, &d);
        else
            d = init;
        pthread_mutex_lock(&b->mu);
        cx_petsc_result_clear(&b->res);
        b->res = r;
        b->status = status;
        b->diag = d;
        b->running = 0;
        b->done = 1;
        pthread_cond_broadcast(&b->cv);
    }
    pthread_mutex_unlock(&b->mu);
    cx_petsc_result_clear(&b->res);
    cx_petsc_finalize();
    return NULL;
}

int tui_backend_available(void)
{
    return 1;
}

const char *tui_backend_method(int k)
{
    const cx_petsc_method *m = cx_petsc_method_at(k);
    return m ? m->id : NULL;
}

const char *tui_backend_summary(int k)
{
    const cx_petsc_method *m = cx_petsc_method_at(k);
    return m ? m->summary : "";
}

const char *tui_backend_refusal(int k, cx_friction law)
{
    const cx_petsc_method *m = cx_petsc_method_at(k);
    if (!m || (m->supports & (1u << law)))
        return "";
    return law == CX_FRICTION_TRESCA ? "frictionless only (Tresca is not a bound on u)"
                                     : "frictionless or Tresca only";
}

int tui_backend_start(tui_state *st, const cx_problem *p, const cx_friction_state *fr, const char *method,
                      const cx_options *opt, cx_diag *d)
{
    tui_backend *b = st->backend;
    if (!b) {
        b = calloc(1, sizeof *b);
        if (!b)
            tui_oom("out of memory");
        pthread_mutex_init(&b->mu, NULL);
        pthread_cond_init(&b->cv, NULL);
        if (pthread_create(&b->thread, NULL, bk_thread, b) != 0) {
            pthread_mutex_destroy(&b->mu);
            pthread_cond_destroy(&b->cv);
            free(b);
            return cx_diag_set(d, CX_EEXTERNAL, "the PETSc backend's thread could not start");
        }
        st->backend = b;
    }
    pthread_mutex_lock(&b->mu);
    b->p = p;
    b->fr = *fr;
    b->fr.s = b->fr.Fi = NULL;   /* the session's rule: bound x weight (cx_petsc_solve) */
    snprintf(b->method, sizeof b->method, "%s", method);
    b->opt = *opt;
    b->nsteps = b->taken = 0;
    b->done = 0;
    b->running = 1;
    atomic_store(&b->cancel, 0);
    b->request = BK_RUN;
    pthread_cond_broadcast(&b->cv);
    if (st->sync)   /* the tests: the run ends before the job returns */
        while (!b->done)
            pthread_cond_wait(&b->cv, &b->mu);
    pthread_mutex_unlock(&b->mu);
    return CX_OK;
}

int tui_backend_take(tui_state *st, tui_run *run, int m)
{
    tui_backend *b = st->backend;
    if (!b)
        return 0;
    pthread_mutex_lock(&b->mu);
    int n = 0;
    for (; b->taken < b->nsteps; b->taken++, n++) {
        const cx_petsc_step *s = &b->steps[b->taken];
        if (run->nsteps == run->cap) {
            run->cap = run->cap ? 2 * run->cap : 64;
            run->steps = tui_xalloc(run->steps, sizeof *run->steps * (size_t)run->cap);
        }
        tui_step *t = &run->steps[run->nsteps++];
        double before = run->nsteps > 1 ? t[-1].time : 0;
        t->iter = s->iter;
        t->kkt = s->kkt;
        t->own = NAN;
        t->ncontact = s->ncontact;
        t->nstick = s->nstick;
        t->nslip = s->nslip;
        t->nfree = m - s->ncontact - s->nstick - s->nslip;
        t->nchanged = s->nchanged;
        t->inner = s->krylov;
        t->solves = 0;   /* no factorisation, no solve with K: Krylov iterations instead */
        t->time = s->time;
        t->step_time = s->time - before;
    }
    pthread_mutex_unlock(&b->mu);
    return n;
}

int tui_backend_done(const tui_state *st)
{
    tui_backend *b = st->backend;
    if (!b)
        return 1;
    pthread_mutex_lock(&b->mu);
    int done = b->done;
    pthread_mutex_unlock(&b->mu);
    return done;
}

int tui_backend_result(tui_state *st, tui_backend_outcome *out, cx_diag *d)
{
    tui_backend *b = st->backend;
    memset(out, 0, sizeof *out);
    if (!b)
        return CX_OK;
    pthread_mutex_lock(&b->mu);
    int status = b->status;
    if (status != CX_OK)
        *d = b->diag;
    else {
        out->reason = b->res.reason;
        out->iterations = b->res.iterations;
        out->kkt = b->res.kkt;
        out->krylov = b->res.krylov;
        out->pc_setups = b->res.pc_setups;
        out->nranks = b->res.nranks;
        out->t_setup = b->res.t_setup;
        out->t_solve = b->res.t_solve;
        out->mem_peak = b->res.nranks > 0 ? b->res.mem_peak[0] : 0;
        snprintf(out->message, sizeof out->message, "%s", b->res.message);
        snprintf(out->solver, sizeof out->solver, "%s", b->res.solver);
        out->u = b->res.u;
        out->lN = b->res.lN;
        out->lT = b->res.lT;
    }
    pthread_mutex_unlock(&b->mu);
    return status;
}

void tui_backend_point_status(const cx_problem *p, const cx_friction_state *fr, const double *lN,
                              const double *lT, unsigned char *status)
{
    cx_petsc_point_status(p, fr, lN, lT, status);
}

void tui_backend_cancel(tui_state *st)
{
    tui_backend *b = st->backend;
    if (b)
        atomic_store(&b->cancel, 1);
}

void tui_backend_stop(tui_state *st)
{
    tui_backend *b = st->backend;
    if (!b)
        return;
    pthread_mutex_lock(&b->mu);
    atomic_store(&b->cancel, 1);
    while (b->running)   /* a run in progress stops at its next step */
        pthread_cond_wait(&b->cv, &b->mu);
    b->request = BK_QUIT;
    pthread_cond_broadcast(&b->cv);
    pthread_mutex_unlock(&b->mu);
    pthread_join(b->thread, NULL);   /* PETSc and MPI end on their thread */
    pthread_mutex_destroy(&b->mu);
    pthread_cond_destroy(&b->cv);
    free(b->steps);
    free(b);
    st->backend = NULL;
}

#else

int tui_backend_available(void)
{
    return 0;
}

const char *tui_backend_method(int k)
{
    (void)k;
    return NULL;
}

const char *tui_backend_summary(int k)
{
    (void)k;
    return "";
}

const char *tui_backend_refusal(int k, cx_friction law)
{
    (void)k, (void)law;
    return "";
}

int tui_backend_start(tui_state *st, const cx_problem *p, const cx_friction_state *fr, const char *method,
                      const cx_options *opt, cx_diag *d)
{
    (void)st, (void)p, (void)fr, (void)method, (void)opt;
    return cx_diag_set(d, CX_EUNSUPPORTED, "this build has no PETSc backend (meson setup -Dpetsc=enabled)");
}

int tui_backend_take(tui_state *st, tui_run *run, int m)
{
    (void)st, (void)run, (void)m;
    return 0;
}

int tui_backend_done(const tui_state *st)
{
    (void)st;
    return 1;
}

int tui_backend_result(tui_state *st, tui_backend_outcome *out, cx_diag *d)
{
    (void)st;
    memset(out, 0, sizeof *out);
    return cx_diag_set(d, CX_EUNSUPPORTED, "this build has no PETSc backend");
}

void tui_backend_point_status(const cx_problem *p, const cx_friction_state *fr, const double *lN,
                              const double *lT, unsigned char *status)
{
    (void)fr, (void)lN, (void)lT;
    memset(status, CX_PT_FREE, (size_t)p->m);
}

void tui_backend_cancel(tui_state *st)
{
    (void)st;
}

void tui_backend_stop(tui_state *st)
{
    (void)st;
}

#endif
