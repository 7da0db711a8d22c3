/* Private to tui/: colour roles, the braille canvas, the terminal wrapper
 * (term.c, the only file that includes curses) and the panels (draw.c). */
#ifndef TUI_IMPL_H
#define TUI_IMPL_H

#include "tui/tui.h"

#include <stddef.h>

/* Colour roles (STYLE.md C12), mapped to a scheme in term.c with a
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
    TUI_C_COUNT
};

/* ---- program helpers ------------------------------------------------------ */

/* realloc or end the program (the terminal restored first). */
void *tui_xalloc(void *p, size_t size);
/* Restore the terminal, print "signorini: msg" and exit 1 (loop.c; a test
 * that links the state without loop.c gives its own). */
void tui_fatal(const char *msg);

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
/* Restore the terminal; safe to call twice and from atexit. */
void tui_term_close(void);
int tui_term_utf8(void);
void tui_term_size(int *rows, int *cols);
/* A key within timeout_ms (< 0: wait), TUI_KEY_NONE if none. */
int tui_term_key(int timeout_ms);
void tui_term_clear(void);
/* Text at (y, x) in a role, at most maxw columns (< 0: to the edge). */
void tui_term_put(int y, int x, int role, const char *s, int maxw);
void tui_term_show(void);

/* ---- drawing (draw.c) --------------------------------------------------------- */

/* (state.c) The mesh view's automatic displacement scale: the largest displacement
 * drawn as a tenth of the body. */
double tui_mesh_auto_scale(const tui_state *st);

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

/* The panels (panels.c), each within its box. */
void tui_panel_steps(const tui_state *st, tui_box b);
void tui_panel_contact(const tui_state *st, tui_box b);
void tui_panel_plot(const tui_state *st, tui_box b);
void tui_panel_mesh(const tui_state *st, tui_box b);
void tui_panel_runs(const tui_state *st, tui_box b);

#endif
