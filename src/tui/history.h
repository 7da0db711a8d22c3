/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The history of runs on the current scene and level (history.c): one run
 * per method switch or reset, each with its steps, so the convergence plot
 * draws the earlier runs' curves under the current one. */
#ifndef TUI_HISTORY_H
#define TUI_HISTORY_H

#include "tui/tui.h"

typedef struct tui_step {
    int iter;
    double kkt, own;
    int nfree, ncontact, nstick, nslip, nchanged;
    long inner;
    long solves;           /* solves with K in the run so far */
    double time;           /* seconds of the run's iterations so far (its setup apart) */
    double step_time;      /* seconds of this step */
} tui_step;

struct tui_run {
    int serial;            /* the run's number in the session (its colour) */
    char method[32];
    char params[160];      /* "rho=0.001 ..." */
    char changed[160];     /* the parameters that differ from their defaults */
    char outcome[CX_DIAG_LEN];   /* cx_reason_format's sentence when it ended */
    cx_friction law;
    double coef;
    double tol;
    int nsteps, cap;
    tui_step *steps;
    int reason;            /* cx_reason of the last step */
    char reason_msg[160];  /* breakdown message, if any */
    long factorizations;   /* of the run, the cache build included */
    double setup;          /* seconds of the method's setup (init) */
    cx_counters draw;      /* the explorer's own work for drawing (expanding
                              a partial iterate for the mesh view), not the
                              run's: its counters are solve's */
    cx_counters probe;     /* work of the check before the switch that
                              opened the run (an operator it cached): the
                              run's own, added to its counters */
};

#define TUI_MAX_RUNS 32

typedef struct tui_history {
    tui_run runs[TUI_MAX_RUNS];   /* the last one is the current run */
    int nruns;
    int next_serial;              /* numbers the runs: their colours */
} tui_history;

tui_history *tui_history_create(void);
void tui_history_destroy(tui_history **h);
/* Forget every run (a new scene or level). */
void tui_history_clear(tui_history *h);
/* Forget the earlier runs, keep the current one. */
void tui_history_keep_current(tui_history *h);
/* A new, empty current run: an empty current run is replaced, the oldest
 * run dropped when the table is full. */
tui_run *tui_history_new_run(tui_history *h);
/* Append the step the iterate describes to run r. */
void tui_history_append(tui_run *r, const cx_iterate *it);

#endif
