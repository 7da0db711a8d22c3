/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Private to tui/: the state's fields, the picker rows (actions.c), colour
 * roles, the braille canvas, the terminal wrapper (term.c, the only file
 * that includes curses) and the panels (draw.c, panels.c). */
#ifndef TUI_IMPL_H
#define TUI_IMPL_H

#include "tui/tui.h"
#include "tui/history.h"
#include "tui/job.h"
#include "tui/meshview.h"

#include "out/palette.h"

#include <stddef.h>

/* ---- the picker rows (actions.c) ------------------------------------------ */

/* Row indices: the fixed rows, then one per parameter of the selected
 * method (all described by the TUI_F_PARAM0 row). */
enum {
    TUI_F_SCENE,
    TUI_F_LEVEL,
    TUI_F_FRICTION,
    TUI_F_COEF,        /* Tresca slip bound or Coulomb F */
    TUI_F_METHOD,
    TUI_F_TOL,
    TUI_F_MAXIT,
    TUI_F_PARAM0
};

enum {
    TUI_ROW_LIST,      /* a choice among items listed under the pickers (scene, method) */
    TUI_ROW_CHOICE,    /* a choice cycled with left/right (friction law) */
    TUI_ROW_NUMBER     /* a number (level, coefficient, tol, max iter, parameters) */
};

/* One row of the pickers: drawing, keys and value entry all read it. i is
 * the parameter index for the parameter row, else 0. */
typedef struct tui_row {
    const char *label;     /* NULL: label_of */
    int kind;              /* TUI_ROW_* */
    const char *(*label_of)(const tui_state *st, int i);
    void (*format)(const tui_state *st, int i, char *buf, size_t len);
    int (*step)(tui_state *st, int i, int dir);               /* left -1, right +1: reactions */
    int (*enter)(tui_state *st, int i, const char *text);     /* Enter on typed text: reactions */
    /* why the row's value cannot be used now ("" if it can): drawn grey */
    const char *(*greyed)(const tui_state *st, int i, char *why, size_t len);
    /* the detail shown under the pickers: one line, then text wrapped ("" none) */
    void (*describe)(const tui_state *st, int i, char *buf, size_t len);
    /* TUI_ROW_LIST: the items, the selected one, item k's id and why it is greyed */
    int (*count)(const tui_state *st);
    int (*current)(const tui_state *st);
    const char *(*item)(const tui_state *st, int k, char *why, size_t len);
} tui_row;

/* The descriptor of picker row f (*i: its parameter index). */
const tui_row *tui_row_at(const tui_state *st, int f, int *i);
/* Rows of the picker: TUI_F_PARAM0 + parameters of the selected method. */
int tui_state_nfields(const tui_state *st);
/* The label and the value of row f as text ("32", "tresca", "1e-10"). */
const char *tui_field_label(const tui_state *st, int f);
void tui_field_value(const tui_state *st, int f, char *buf, size_t len);

/* ---- the state ------------------------------------------------------------ */

struct tui_state {
    /* scenes */
    char (*scene_ids)[CX_SCENE_NAMELEN];
    int nscenes;
    cx_scene scene;           /* the scene of the session (or being built) */
    cx_scene prev_scene;      /* the scene before a build, kept if it fails */
    int level;                /* of the session */
    /* the level asked for at start, when above the scene's default: that
     * level is built first and measures it (0: none, or done) */
    int target_level;

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
     * dual method), per registry entry and friction law: greyed with the
     * reason, skipped by 'm', so that a refusal (and its failed
     * factorisation) is not repeated; cx_method_count() rows */
    char (*refused)[3][CX_DIAG_LEN];
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

    /* the backend the runs use: 0 the direct path (the session's method),
     * k + 1 the PETSc backend's method k on one rank (backend.c) */
    int sel_backend;
    tui_backend *backend;     /* its thread, once a PETSc run was asked for */

    /* running */
    int running;              /* run to convergence, one step per tick */
    int sync;                 /* run jobs inline (tests) */
    tui_job job;
    int pending;              /* reactions that arrived during a job */
    int queued_steps;         /* step keys that arrived during a job */

    /* what panels draw (copies, safe while a job runs) */
    int m;                    /* contact points of the snapshot */
    unsigned char *status, *changed;   /* m */
    double *pressure;         /* m: lN / weight */
    double *hertz;            /* m: analytical pressure (NaN if none) */
    double *slip_dir;         /* 2m: tangential force direction in 3D (x, y) */
    double *uall;             /* dim * nnodes displacement of every node */
    int *flips;               /* m: status changes of each point in this run */
    unsigned long long status_hash[3];  /* of the last three steps, newest first */
    int cycle_iter;           /* iteration at which a 2-cycle was seen, 0 if none */
    cx_counters cache;        /* the session's cache counters */
    int cache_size;
    double build_time;        /* seconds of the last build */

    /* runs on this scene and level (history.c) */
    tui_history *history;
    /* the mesh view's geometry (meshview.c) */
    tui_meshview mesh_view;

    /* view */
    int view;                 /* 0 convergence plot, 1 mesh (small terminals) */
    double disp_scale;        /* mesh view displacement scale, 0 = auto */
    int help;                 /* help overlay shown */
    int present;              /* presentation mode: paced runs, high contrast, big plot */
    int highlight;            /* serial + 1 of the run clicked in the runs table, 0 none */
    double pace;              /* presentation: steps per second */
    int editing;              /* text entry for the field under the cursor */
    char edit[64];
    int edit_len;
    char export_dir[256];     /* where exports are written ("." by default) */

    /* status line */
    char msg[CX_DIAG_LEN];
    int msg_error;            /* 0 information, 1 error, 2 warning */
};

const cx_method *tui_state_sel_method(const tui_state *st);
/* Why method index cannot run this scene ("" if it can), for greying out. */
const char *tui_state_method_reason(const tui_state *st, int index, char *buf, size_t len);
/* Select the method (and parameters) --method auto chooses for the
 * selected scene, level and law. */
void tui_state_select_auto(tui_state *st);
/* The registry index of method id, -1 if none. */
int tui_method_index(const char *id);

/* Status line. */
void tui_msg(tui_state *st, int error, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* What a build at level would take, scaled from the level built (state.c):
 * dofs, bytes and seconds, each within about a factor of 2. 0 if not known
 * (nothing built yet, or a job in progress). */
int tui_state_level_estimate(const tui_state *st, int level, double *dofs, double *bytes, double *secs);
/* 1, with the message, if level's memory estimate exceeds avail bytes. */
int tui_state_level_refused(const tui_state *st, int level, double avail, char *msg, size_t len);
/* /proc/meminfo's MemAvailable in bytes (or $SIGNORINI_MEMAVAILABLE's, for
 * the tests), -1 if unknown; and which of the two it is. */
double tui_mem_available(void);
const char *tui_mem_source(void);
/* "1.2 GB", "48 MB", "300 kB". */
void tui_size_text(double bytes, char *buf, size_t len);

/* Esc during a build on a worker: abandon it (job.c) and go back to the
 * session's scene and level at once, saying so. */
void tui_state_abandon_build(tui_state *st);

/* 1 if the current run has ended and is the one s and r would go on
 * with (x starts it again); a run of the other backend, or of another
 * PETSc method, has ended for them only. */
int tui_state_run_ended(const tui_state *st);

/* After a step ends (state.c, called by tui_state_poll). */
void tui_state_after_step(tui_state *st, int status, const cx_diag *d);

/* The outline the mesh view draws (2 *n node pairs). */
const int *tui_state_outline(const tui_state *st, int *n);
/* The mesh view's automatic displacement scale: the largest displacement
 * drawn as a tenth of the body (meshview.c). */
double tui_mesh_auto_scale(const tui_state *st);

/* ---- actions (actions.c) ---------------------------------------------------- */

typedef int (*tui_action)(tui_state *st);

typedef struct tui_binding {
    int key;
    const char *keyname;   /* as shown in the help */
    tui_action action;
    const char *help;
} tui_binding;

/* A mouse event on what the screen shows there (kind TUI_HIT_*, index,
 * what TUI_MOUSE_*): a click selects a setup row or highlights a run
 * (again: no highlight), the wheel steps the row under it as the arrow
 * keys do. Returns reactions. */
int tui_mouse(tui_state *st, int kind, int index, int what);

/* The key table (terminated by key 0), for the help overlay. */
const tui_binding *tui_bindings(void);

/* ---- export (export.c) -------------------------------------------------- */

/* Write every run's steps as CSV and JSON to dir/signorini-SCENE-LlEVEL
 * .csv/.json (each through a temporary file renamed into place). The
 * names written go to csv/json. CX_EIO with the file name. */
int tui_export(const tui_state *st, const char *dir, char *csv, char *json, size_t len, cx_diag *d);

/* ---- rendering hook (actions.c) ----------------------------------------- */

/* Render the current state to a PNG; the one place the explorer calls the
 * renderer. Returns CX_EUNSUPPORTED while rendering is not in this build. */
int tui_render_png(const tui_state *st, char *file, size_t len, cx_diag *d);

/* Colour roles (doc/style.md C12), mapped to a scheme in term.c with a
 * monochrome fallback. On a canvas a higher role wins a shared cell. */
enum {
    TUI_C_NORMAL,
    TUI_C_FAINT,      /* earlier runs, axes */
    TUI_C_LABEL,
    TUI_C_TITLE,
    TUI_C_SELECT,     /* the picker row under the cursor */
    TUI_C_GREY,       /* a method that cannot run this scene */
    TUI_C_BAR,        /* computed bars and profiles */
    TUI_C_REF,        /* the analytical reference (Hertz), drawn over bars */
    TUI_C_CURRENT,    /* the current run's curve */
    TUI_C_FREE,
    TUI_C_CONTACT,
    TUI_C_STICK,
    TUI_C_SLIP,
    TUI_C_CHANGED,    /* a contact point whose status changed this step */
    TUI_C_OK,
    TUI_C_WARN,
    TUI_C_ERROR,
    TUI_C_SERIES0,    /* the runs' colours: cx_palette_series, one role each */
    TUI_C_COUNT = TUI_C_SERIES0 + CX_PALETTE_NSERIES
};

/* ---- the runs' colours and presentation pace (canvas.c, state.c) --------- */

/* The xterm 256-colour index nearest an rgb colour (the 6x6x6 cube and
 * the grey ramp), and the nearest of the 8 basic curses colours (0 black,
 * 1 red, 2 green, 3 yellow, 4 blue, 5 magenta, 6 cyan, 7 white). */
int tui_palette_xterm256(const unsigned char rgb[3]);
int tui_palette_basic8(const unsigned char rgb[3]);
/* Run r's entry in cx_palette_series (its number in the session modulo
 * the palette: a run keeps its colour when older runs are dropped). */
int tui_run_colour(const tui_run *r);
/* The legend of a run: the method and the parameters that differ from
 * their defaults ("pdas rho=0.01"). */
void tui_run_legend(const tui_run *r, char *buf, size_t len);
/* 1 if the run has stepped without a factorisation of its own: the
 * operator cache served it (every method factorises at least once on a
 * fresh session, as solve shows). */
int tui_run_cached(const tui_run *r);
/* Seconds the loop waits between the steps of a run: 0 (as fast as the
 * steps go) outside presentation mode, 1 / pace in it. */
double tui_state_step_interval(const tui_state *st);
/* Presentation pace: steps per second, between these, doubled or halved
 * by '}' and '{'. */
#define TUI_PACE_DEFAULT 2.0
#define TUI_PACE_MIN 0.25
#define TUI_PACE_MAX 32.0

/* ---- program helpers ------------------------------------------------------ */

/* realloc, or out of memory: the hook of tui_on_oom (the program restores
 * the terminal first), else abort(). */
void *tui_xalloc(void *p, size_t size);
/* Out of memory: the hook, else abort(); does not return. */
_Noreturn void tui_oom(const char *msg);

/* ---- braille canvas (canvas.c) --------------------------------------------- */

typedef struct tui_canvas {
    int w, h;              /* cells; dots are 2w x 4h, y down */
    unsigned char *bits;   /* w h: braille dot masks */
    unsigned char *role;   /* w h: colour role of each cell */
} tui_canvas;

void tui_canvas_init(tui_canvas *c, int w, int h);
void tui_canvas_free(tui_canvas *c);
void tui_canvas_dot(tui_canvas *c, int x, int y, int role);
/* A line between dot positions (rounded, clipped to the canvas). */
void tui_canvas_line(tui_canvas *c, double x0, double y0, double x1, double y1, int role);
/* The text of cell (i, j): a braille character (UTF-8) or, without UTF-8,
 * an ASCII stand-in (' . : ' by where the dots are). */
void tui_canvas_glyph(const tui_canvas *c, int i, int j, int utf8, char out[8]);

/* ---- contact strip buckets (canvas.c) ------------------------------------- */

/* The status shown for points [lo, hi) in one cell: a changed point
 * first, then slip, stick, contact, free (the most telling wins). */
/* How telling a status is: free 0, contact 1, stick 2, slip 3. */
int tui_status_rank(int s);
int tui_bucket_status(const unsigned char *status, const unsigned char *changed, int lo, int hi,
                      int *changed_out);

/* ---- terminal (term.c) ------------------------------------------------------ */

/* Start curses (locale, colours, keypad); mono forces no colours, ascii
 * forces the ASCII fallback. 0 on success. */
int tui_term_open(int mono, int ascii);
/* Ctrl-Z: restore the terminal, stop the process; on fg redraw whole. */
void tui_term_suspend(void);
/* Restore the terminal; safe to call twice and from atexit. */
void tui_term_close(void);
int tui_term_utf8(void);
void tui_term_size(int *rows, int *cols);
/* A key within timeout_ms (< 0: wait), TUI_KEY_NONE if none. */
int tui_term_key(int timeout_ms);
void tui_term_clear(void);
/* The mouse event behind the last TUI_KEY_MOUSE: its cell (0-based) and
 * what it was (TUI_MOUSE_*). */
enum { TUI_MOUSE_CLICK = 1, TUI_MOUSE_WHEEL_UP, TUI_MOUSE_WHEEL_DOWN };
int tui_term_mouse(int *y, int *x);
/* Text at (y, x) in a role, at most maxw columns (< 0: to the edge). */
void tui_term_put(int y, int x, int role, const char *s, int maxw);
void tui_term_show(void);
/* The colours: 0 the usual scheme, 1 presentation's high contrast (no
 * dark blue, no bold black, no yellow text: reads on white and on black).
 * Cheap when unchanged. */
void tui_term_scheme(int present);

/* ---- drawing (draw.c) --------------------------------------------------------- */

/* Draw every panel from the state (through term.c). */
void tui_draw(const tui_state *st, int rows, int cols, int utf8);

/* Drawing helpers (draw.c), valid during tui_draw: the UTF-8 or the ASCII
 * text by the terminal; formatted text; a section rule "- name ---"; a
 * canvas at (y, x). */
typedef struct tui_box {
    int y, x, h, w;
} tui_box;
const char *tui_sym(const char *utf8, const char *ascii);
void tui_put(int y, int x, int role, int maxw, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
void tui_rule(int y, int x, int w, const char *name);
void tui_put_canvas(const tui_canvas *c, int y, int x);

/* What the last frame drew where, for the mouse: a setup row (index: the
 * row) or a run of the runs table (index: the run). Registered while
 * drawing; tui_draw_hit finds the thing under a cell (0 if none). */
enum { TUI_HIT_FIELD = 1, TUI_HIT_RUN };
void tui_hit_add(int y, int x0, int x1, int kind, int index);
int tui_draw_hit(int y, int x, int *index);

/* The panels (panels.c), each within its box. */
void tui_panel_steps(const tui_state *st, tui_box b);
void tui_panel_contact(const tui_state *st, tui_box b);
void tui_panel_plot(const tui_state *st, tui_box b);
void tui_panel_mesh(const tui_state *st, tui_box b);
void tui_panel_runs(const tui_state *st, tui_box b);

#endif
