/* tui/: the explorer, an ncurses program layer beside cli/ (STYLE.md C12).
 *
 * tui_state holds everything the screen shows: the scene, the session (the
 * problem, its operator cache and the current method), the selections of
 * the pickers and the history of runs. Keys map through one table to
 * actions that change the state and return reaction flags; the loop
 * (loop.c) decides what to recompute (tui_state_apply) and redraws. Only
 * term.c includes curses, so the state and the actions are tested without
 * a terminal (tests/tui/test_actions.c).
 *
 * Building a level (assembly and the first factorisation), switching
 * method and each step run as a job, on a worker thread in the program and inline in the
 * tests; while a job runs, the main thread does not touch the session and
 * draws from the state's own copies (snapshot and history). Errors never
 * end the program: they go to the status line (st->msg). */
#ifndef TUI_H
#define TUI_H

#include "scene/scene.h"

#include <stdatomic.h>

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
    TUI_KEY_RESIZE
};

/* ---- the picker rows --------------------------------------------------- */

enum {
    TUI_F_SCENE,
    TUI_F_LEVEL,
    TUI_F_FRICTION,
    TUI_F_COEF,        /* Tresca slip bound or Coulomb F */
    TUI_F_METHOD,
    TUI_F_TOL,
    TUI_F_MAXIT,
    TUI_F_PARAM0       /* then one row per parameter of the selected method */
};

/* ---- history ------------------------------------------------------------ */

typedef struct tui_step {
    int iter;
    double kkt, own;
    int nfree, ncontact, nstick, nslip, nchanged;
    long inner;
    long solves;           /* solves with K in the run so far */
    double time;           /* seconds of the run so far (init included) */
    double step_time;      /* seconds of this step */
} tui_step;

typedef struct tui_run {
    char method[32];
    char params[160];      /* "rho=0.001 ..." */
    cx_friction law;
    double coef;
    double tol;
    int nsteps, cap;
    tui_step *steps;
    int reason;            /* cx_reason of the last step */
    char reason_msg[160];  /* breakdown message, if any */
    long factorizations;   /* of the run, the cache build included */
} tui_run;

#define TUI_MAX_RUNS 32

/* ---- jobs ---------------------------------------------------------------- */

enum { TUI_JOB_NONE, TUI_JOB_BUILD, TUI_JOB_RESOLVE, TUI_JOB_STEP };
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
    /* output of a build */
    cx_session *session;
} tui_job;

/* ---- the state ----------------------------------------------------------- */

#define TUI_MAX_METHODS 64       /* registry entries the explorer tracks */

typedef struct tui_state {
    /* scenes */
    char (*scene_ids)[CX_SCENE_NAMELEN];
    int nscenes;
    cx_scene scene;           /* the scene of the session (or being built) */
    cx_scene prev_scene;      /* the scene before a build, kept if it fails */
    int level;                /* of the session */

    /* the session (NULL until the first build ends) */
    cx_session *session;

    /* selections (what the pickers show; applied by tui_state_apply) */
    int field;                /* TUI_F_* row with the cursor */
    int sel_scene;            /* index in scene_ids */
    int sel_level;
    cx_friction sel_law;
    double sel_slip, sel_F;   /* Tresca bound (traction) and Coulomb F */
    int sel_method;           /* index in the registry */
    /* methods the session's problem refused at init (e.g. K singular for a
     * dual method), per friction law: greyed with the reason, skipped by 'm',
     * so that a refusal (and its failed factorisation) is not repeated */
    char refused[TUI_MAX_METHODS][3][CX_DIAG_LEN];
    cx_param_values sel_params;
    cx_options sel_opt;

    /* what the session now runs (copied after each job) */
    const cx_problem *info;   /* the session's system (sizes, geometry): read, never copied */
    int have_info;
    const cx_method *cur_method;
    cx_param_values cur_params;
    cx_options cur_opt;
    cx_friction cur_law;
    double cur_coef;

    /* running */
    int running;              /* run to convergence, one step per tick */
    int sync;                 /* run jobs inline (tests) */
    tui_job job;
    void *worker;             /* pthread_t *, when a worker thread runs */
    int pending;              /* reactions that arrived during a job */
    int queued_steps;         /* step keys that arrived during a job */

    /* what panels draw (copies, safe while a job runs) */
    int m;                    /* contact points of the snapshot */
    unsigned char *status, *changed;   /* m */
    double *pressure;         /* m: lN / weight */
    double *hertz;            /* m: analytical pressure (NaN if none) */
    double *slip_dir;         /* 2m: tangential force direction in 3D (x, y) */
    double *uall;             /* dim * nnodes displacement of every node */
    int *outline;             /* 2 noutline: node pairs of the edges on the body's surface */
    int noutline;
    int *flips;               /* m: status changes of each point in this run */
    unsigned long long status_hash[3];  /* of the last three steps, newest first */
    int cycle_iter;           /* iteration at which a 2-cycle was seen, 0 if none */
    cx_counters cache;        /* the session's cache counters */
    int cache_size;
    double build_time;        /* seconds of the last build */

    /* runs on this scene and level; the last one is the current run */
    tui_run runs[TUI_MAX_RUNS];
    int nruns;

    /* view */
    int view;                 /* 0 convergence plot, 1 mesh (small terminals) */
    double disp_scale;        /* mesh view displacement scale, 0 = auto */
    int help;                 /* help overlay shown */
    int editing;              /* text entry for the field under the cursor */
    char edit[64];
    int edit_len;
    char export_dir[256];     /* where exports are written ("." by default) */

    /* status line */
    char msg[CX_DIAG_LEN];
    int msg_error;            /* 0 information, 1 error, 2 warning */
} tui_state;

/* Create the state on scene id at level (<= 0: the scene's default) with
 * method id (NULL: the scene's first) and friction law (-1: the scene's);
 * starts the first build (inline when sync). CX_EINVAL with the reason for
 * an unknown scene or method. */
int tui_state_init(tui_state *st, const char *scene, int level, const char *method,
                   int law, int sync, cx_diag *d);
void tui_state_clear(tui_state *st);

/* Do what the reactions ask: start a build for TUI_REASSEMBLE, switch
 * method / parameters / friction / options for TUI_RESOLVE (through the
 * session: nothing is reassembled). Messages go to st->msg. */
void tui_state_apply(tui_state *st, int reactions);

/* If a job has ended, take its result (swap in a built session). Returns 1
 * if something changed. Called by the loop on every tick. */
int tui_state_poll(tui_state *st);
int tui_state_busy(const tui_state *st);

/* One step of the current method (nothing if busy or the run ended), as
 * a job; when it ends, tui_state_poll appends it to the history and
 * refreshes the snapshot (at once when sync). */
void tui_state_step(tui_state *st);

/* Start the current method again (a new run; nothing rebuilt). */
void tui_state_reset(tui_state *st);

/* The current run (NULL before the first build). */
const tui_run *tui_state_run(const tui_state *st);
/* Rows of the picker: TUI_F_PARAM0 + parameters of the selected method. */
int tui_state_nfields(const tui_state *st);
const cx_method *tui_state_sel_method(const tui_state *st);
/* Why the selected method cannot run this scene (""), for greying out. */
const char *tui_state_method_reason(const tui_state *st, int index, char *buf, size_t len);

/* Status line. */
void tui_msg(tui_state *st, int error, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* ---- actions ------------------------------------------------------------ */

typedef int (*tui_action)(tui_state *st);

typedef struct tui_binding {
    int key;
    const char *keyname;   /* as shown in the help */
    tui_action action;
    const char *help;
} tui_binding;

/* The key table (terminated by key 0), for the help overlay. */
const tui_binding *tui_bindings(void);
/* Handle one key: the text entry when editing, else the key table.
 * Returns the reactions. */
int tui_key(tui_state *st, int key);
/* The value of picker row f as text ("32", "tresca", "1e-10"). */
void tui_field_value(const tui_state *st, int f, char *buf, size_t len);
const char *tui_field_label(const tui_state *st, int f);

/* ---- export (export.c) -------------------------------------------------- */

/* Write every run's steps as CSV and JSON to dir/signorini-SCENE-LlEVEL
 * .csv/.json (each through a temporary file renamed into place). The
 * names written go to csv/json. CX_EIO with the file name. */
int tui_export(const tui_state *st, const char *dir, char *csv, char *json, size_t len, cx_diag *d);

/* ---- rendering hook (actions.c) ----------------------------------------- */

/* Render the current state to a PNG; the one place the explorer calls the
 * renderer. Returns CX_EUNSUPPORTED while rendering is not in this build. */
int tui_render_png(const tui_state *st, char *file, size_t len, cx_diag *d);

/* ---- the program (loop.c): tui_main, declared in its own header ---------- */

#include "tui/tui_main.h"

#endif
