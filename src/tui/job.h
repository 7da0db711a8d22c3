/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The explorer's jobs (job.c): building a level, switching method or
 * friction, and one step run off the UI thread on a worker (inline in the
 * tests). While a job runs the main thread leaves the session alone and
 * draws from the state's copies. */
#ifndef TUI_JOB_H
#define TUI_JOB_H

#include "tui/tui.h"

#include <stdatomic.h>

enum { TUI_JOB_NONE, TUI_JOB_BUILD, TUI_JOB_RESOLVE, TUI_JOB_STEP, TUI_JOB_PETSC };
enum { TUI_PHASE_IDLE, TUI_PHASE_ASSEMBLE, TUI_PHASE_FACTORISE, TUI_PHASE_STEP, TUI_PHASE_DONE };

typedef struct tui_job {
    int kind;
    atomic_int phase;      /* TUI_PHASE_*, written by the worker */
    double t0;             /* when it started */
    int status;
    cx_diag diag;
    /* inputs */
    int level;
    const cx_method *method;
    cx_param_values params;
    cx_options opt;
    cx_friction law;
    double coef;
    /* output of a resolve: the probe's work (charged to the new run), 1 if
     * the probe refused (the session was not touched) */
    cx_counters probe;
    int probed;
    /* a step: expand a partial iterate afterwards (for drawing) */
    int expand;
    /* output of a step: the kkt error and counters as the step left them
     * (solve's), and the work of the expansion for drawing */
    double kkt;
    cx_counters counters, draw;
    /* output of a build */
    cx_session *session;
    /* ... and the methods its problem refuses before any factorisation
     * (per registry entry and law, "" if not known to refuse): the
     * state's refused table for the new level */
    char (*refused)[3][CX_DIAG_LEN];
    void *worker;          /* pthread_t *, when a worker thread runs */
    void *box;             /* a build on a worker: its own copy (job.c), so that it can be abandoned */
} tui_job;

/* The phase of the job in progress (TUI_PHASE_*), for the progress line. */
int tui_job_phase(const tui_state *st);
/* Esc on a build: drop it at once. The worker finishes on its own (a
 * factorisation cannot be interrupted) and frees what it built when it
 * ends; the state's job is none. 0 if there was no such build (inline,
 * or not a build). */
int tui_job_abandon(tui_state *st);
/* 1 once a build has been abandoned in this process (the program then
 * ends with _exit: see job.c). */
int tui_job_abandoned_any(void);

/* Start a job of kind on the selections (a worker thread, or inline when
 * the state is sync or no thread can start; inline, the result is taken
 * at once through tui_state_poll). */
void tui_job_start(tui_state *st, int kind);
/* If the job has ended: join its worker and return 1 (the result is in
 * st->job). */
int tui_job_ended(tui_state *st);
/* Abandon a build, wait for a step's or a switch's worker, and drop a
 * built session nobody took. */
void tui_job_clear(tui_state *st);

/* ---- the PETSc backend (backend.c) ---------------------------------------- */

/* One rank of the PETSc backend on a thread of its own, started at the
 * first PETSc run and ended by tui_backend_stop: PETSc's start, every
 * PETSc call and its end happen on that thread (PETSc is not
 * thread-safe). A run (TUI_JOB_PETSC) goes to its end as one job; the
 * main thread takes its steps as they come. */
typedef struct tui_backend tui_backend;

/* What a finished PETSc run gives the main thread; u, lN, lT are the
 * backend's (valid until the next run). */
typedef struct tui_backend_outcome {
    int reason, iterations, nranks, pc_setups;
    long krylov;
    double kkt, t_setup, t_solve, mem_peak;
    char message[CX_DIAG_LEN];
    char solver[96];   /* the inner solves' Krylov method and preconditioner ("CG + BoomerAMG") */
    const double *u, *lN, *lT;
} tui_backend_outcome;

/* 1 if this build has the backend. */
int tui_backend_available(void);
/* The backend's method k (NULL past the end), its one-line summary, and
 * why it does not take law ("" if it does). */
const char *tui_backend_method(int k);
const char *tui_backend_summary(int k);
const char *tui_backend_refusal(int k, cx_friction law);
/* Start a run of method on p under fr (the thread started if need be);
 * waits for its end when the state is sync (tests). */
int tui_backend_start(tui_state *st, const cx_problem *p, const cx_friction_state *fr, const char *method,
                      const cx_options *opt, cx_diag *d);
/* Append the steps that came since the last call to run (m contact
 * points); the number appended. */
int tui_backend_take(tui_state *st, tui_run *run, int m);
/* 1 once the run has ended (or there is none). */
int tui_backend_done(const tui_state *st);
/* The ended run: its status (an error: the message in d) and outcome. */
int tui_backend_result(tui_state *st, tui_backend_outcome *out, cx_diag *d);
/* The points' statuses of a solution's forces (cx_petsc_point_status). */
void tui_backend_point_status(const cx_problem *p, const cx_friction_state *fr, const double *lN,
                              const double *lT, unsigned char *status);
/* Ask the run in progress to stop at its next step. */
void tui_backend_cancel(tui_state *st);
/* Stop a run in progress, end PETSc on its thread, join it. */
void tui_backend_stop(tui_state *st);

#endif
