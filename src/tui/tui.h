/* SPDX-License-Identifier: GPL-3.0-or-later */
/* tui/: the explorer, an ncurses program layer beside cli/ (doc/style.md C12).
 *
 * The core (state.c, actions.c, job.c, history.c, meshview.c, export.c,
 * canvas.c: no curses, linked alone into tests/tui) holds the scene, the
 * session (the problem, its operator cache and the current method), the
 * selections of the pickers and the history of runs. Keys map through one
 * table to actions that change the state and return reaction flags; the
 * loop (loop.c) decides what to recompute (tui_state_apply) and redraws.
 *
 * Building a level (assembly and the first factorisation), switching
 * method and each step run as a job, on a worker thread in the program and
 * inline in the tests (job.h). Errors never end the program: they go to
 * the status line. The core never calls into the program: out of memory,
 * it calls the hook the program installs (tui_on_oom).
 *
 * This header is what the program's loop needs; the state's fields, the
 * picker rows and the drawing are in tui_impl.h, the jobs, the runs and
 * the mesh view's geometry in job.h, history.h and meshview.h. */
#ifndef TUI_H
#define TUI_H

#include "scene/scene.h"

#include <stddef.h>

/* ---- reactions (what an action asks the loop to do) ------------------ */

enum {
    TUI_REDRAW = 1,      /* draw again */
    TUI_RESOLVE = 2,     /* method, parameters, friction or options changed */
    TUI_REASSEMBLE = 4,  /* scene or mesh level changed: build a new problem */
    TUI_QUIT = 8
};

/* ---- keys (printable ASCII keys are themselves) ------------------------ */

enum {
    TUI_KEY_NONE = -1,
    TUI_KEY_ENTER = '\n',
    TUI_KEY_ESC = 27,
    TUI_KEY_CTRL_C = 3,
    TUI_KEY_UP = 0x101,
    TUI_KEY_DOWN,
    TUI_KEY_LEFT,
    TUI_KEY_RIGHT,
    TUI_KEY_BACKSPACE,
    TUI_KEY_PGUP,
    TUI_KEY_PGDN,
    TUI_KEY_RESIZE,
    TUI_KEY_MOUSE        /* a click or a wheel turn: tui_term_mouse says where */
};

typedef struct tui_state tui_state;   /* tui_impl.h */
typedef struct tui_run tui_run;       /* history.h */

/* ---- life ---------------------------------------------------------------- */

/* Create the state on scene id at level (<= 0: the scene's default) with
 * method id (NULL: the scene's first) and friction law (-1: the scene's);
 * starts the first build (inline when sync). CX_EINVAL with the reason for
 * an unknown scene or method. tui_state_create allocates it (the program),
 * tui_state_init fills one the caller owns (the tests). */
int tui_state_create(tui_state **st, const char *scene, int level, const char *method, int law,
                     int sync, cx_diag *d);
void tui_state_destroy(tui_state **st);
int tui_state_init(tui_state *st, const char *scene, int level, const char *method,
                   int law, int sync, cx_diag *d);
void tui_state_clear(tui_state *st);

/* Out of memory in the explorer is fatal (doc/style.md C5): the core calls
 * hook (the loop restores the terminal, prints, exits); without a hook, or
 * if it returns, abort(). */
void tui_on_oom(void (*hook)(const char *msg));

/* Where 'e' and 'p' write ("." by default). */
void tui_state_set_export_dir(tui_state *st, const char *dir);
/* Presentation mode (--present, 'P'): runs paced at a few steps a second,
 * high-contrast colours, the plot and the contact strip enlarged. */
void tui_state_set_present(tui_state *st, int on);

/* ---- the loop ------------------------------------------------------------ */

/* Handle one key: the text entry when editing, else the key table.
 * Returns the reactions. */
int tui_key(tui_state *st, int key);

/* Do what the reactions ask: start a build for TUI_REASSEMBLE, switch
 * method / parameters / friction / options for TUI_RESOLVE (through the
 * session: nothing is reassembled). Messages go to the status line. */
void tui_state_apply(tui_state *st, int reactions);

/* If a job has ended, take its result (swap in a built session). Returns 1
 * if something changed. Called by the loop on every tick. */
int tui_state_poll(tui_state *st);
int tui_state_busy(const tui_state *st);
/* Running to convergence (one step per tick). */
int tui_state_running(const tui_state *st);
/* Idle: no job, not running, no change waiting (a scripted key may come). */
int tui_state_idle(const tui_state *st);
/* Seconds a step job has run, or -1 when no step runs (the loop polls
 * keys often while a step is young). */
double tui_state_step_age(const tui_state *st, double now);

/* One step of the current method (nothing if busy or the run ended), as
 * a job; when it ends, tui_state_poll appends it to the history and
 * refreshes the snapshot (at once when sync). */
void tui_state_step(tui_state *st);

/* Start the current method again (a new run; nothing rebuilt). */
void tui_state_reset(tui_state *st);

/* ---- the runs -------------------------------------------------------------- */

/* The current run (NULL before the first build), the number of runs and
 * run i (0 the oldest). */
const tui_run *tui_state_run(const tui_state *st);
int tui_state_nruns(const tui_state *st);
const tui_run *tui_state_run_at(const tui_state *st, int i);
/* Seconds of step k of run i (for --stats). */
double tui_state_step_time(const tui_state *st, int i, int k);
int tui_state_nsteps(const tui_state *st, int i);

/* ---- the program (loop.c): tui_main, declared in its own header ---------- */

#include "tui/tui_main.h"

#endif
