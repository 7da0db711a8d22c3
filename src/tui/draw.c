/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The screen, drawn from the state only (through term.c): the layout, the
 * header, the pickers, the status line and the help overlay, and the
 * drawing helpers the panels (panels.c) share. */
#include "tui/tui_impl.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DRAW_MIN_COLS 60
#define DRAW_MIN_ROWS 16

static int draw_utf8;

const char *tui_sym(const char *utf8, const char *ascii)
{
    return draw_utf8 ? utf8 : ascii;
}

void tui_put(int y, int x, int role, int maxw, const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    tui_term_put(y, x, role, buf, maxw);
}

/* A section title: "─ name ───" across w columns. */
void tui_rule(int y, int x, int w, const char *name)
{
    char buf[512];
    const char *dash = tui_sym("─", "-");
    size_t at = 0;
    at += (size_t)snprintf(buf, sizeof buf, "%s %s ", dash, name);
    for (int k = (int)strlen(name) + 3; k < w && at + 4 < sizeof buf; k++)
        at += (size_t)snprintf(buf + at, sizeof buf - at, "%s", dash);
    tui_term_put(y, x, TUI_C_LABEL, buf, w);
}

void tui_put_canvas(const tui_canvas *c, int y, int x)
{
    char g[8];
    for (int j = 0; j < c->h; j++)
        for (int i = 0; i < c->w; i++) {
            tui_canvas_glyph(c, i, j, draw_utf8, g);
            if (g[0] != ' ')
                tui_term_put(y + j, x + i, c->role[j * c->w + i], g, 1);
        }
}

/* ---- header and status line ------------------------------------------------- */

/* Columns of UTF-8 text (one per code point: the header's symbols are
 * single-width). */
static int draw_columns(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += ((unsigned char)*s & 0xC0) != 0x80;
    return n;
}

static void draw_header(const tui_state *st, int cols)
{
    char left[512], right[64], pad[1024];
    const tui_run *run = tui_state_run(st);
    const char *bar = tui_sym("│", "|");
    /* the counter that shows nothing was refactorised stays visible */
    int rw = snprintf(right, sizeof right, " %s factorised: %ld ", bar, st->cache.factorizations);
    /* the program's name gives way first when the method and law would
     * meet the counter (ssn-coulomb coulomb at 80 columns) */
    for (int named = 1; named >= 0; named--) {
        const char *me = named ? " signorini " : "";
        const char *sep = named ? bar : "";
        if (!st->have_info)
            snprintf(left, sizeof left, "%s%s %s %s building level %d", me, sep, st->scene.id, bar, st->sel_level);
        else if (st->sel_backend)   /* what s and r run: the PETSc backend's method */
            snprintf(left, sizeof left, "%s%s %s L%d %dD %d dofs %d pts %s petsc %s %s", me, sep, st->scene.id,
                     st->level, st->info->dim, st->info->n, st->info->m, bar, tui_backend_method(st->sel_backend - 1),
                     cx_friction_name(st->cur_law));
        else
            snprintf(left, sizeof left, "%s%s %s L%d %dD %d dofs %d pts %s %s %s", me, sep, st->scene.id, st->level,
                     st->info->dim, st->info->n, st->info->m, bar, run ? run->method : "-",
                     cx_friction_name(st->cur_law));
        if (draw_columns(left) + draw_columns(right) <= cols)
            break;
    }
    snprintf(pad, sizeof pad, "%-*s", cols, left);
    tui_term_put(0, 0, TUI_C_TITLE, pad, cols);
    tui_term_put(0, cols - rw + (draw_utf8 ? 2 : 0), TUI_C_TITLE, right, cols);
    if (st->present) {
        /* what the class is looking at, and where the method comes from */
        const cx_method *me = tui_state_sel_method(st);
        /* the source and the pace first: a long title is what gets cut */
        char line[512];
        int n = 0;
        if (me && me->source && me->source[0])
            n += snprintf(line + n, sizeof line - (size_t)n, " paper %s %s", me->source, bar);
        if (st->running)
            n += snprintf(line + n, sizeof line - (size_t)n, " %.3g steps/s %s", st->pace, bar);
        snprintf(line + n, sizeof line - (size_t)n, " %s", st->scene.title[0] ? st->scene.title : st->scene.id);
        /* too long: the title cut at a word, with an ellipsis */
        if (draw_columns(line) > cols) {
            const char *ell = tui_sym("…", "~");
            char *sp;
            while (draw_columns(line) + 1 > cols && (sp = strrchr(line + n, ' ')) && sp > line + n)
                *sp = '\0';
            size_t l = strlen(line);
            snprintf(line + l, sizeof line - l, "%s", ell);
        }
        tui_put(1, 0, TUI_C_LABEL, cols, "%s", line);
    }
}

static const char spinner_ascii[] = "|/-\\";
static const char *const spinner_utf8[] = {"⠋", "⠙", "⠹", "⠸", "⠼", "⠴", "⠦", "⠧", "⠇", "⠏"};

/* Split text into lines of at most w columns at spaces (a word longer
 * than w is cut, the only case): the start and length of each line into
 * at[], len[] (up to max); the number of lines. ASCII widths: messages
 * and diagnostics are ASCII. */
static int draw_wrap(const char *text, int w, const char **at, int *len, int max)
{
    int n = 0;
    while (*text == ' ')
        text++;
    while (*text && n < max) {
        int l = (int)strlen(text);
        if (l > w) {
            l = w;
            while (l > 0 && text[l] != ' ')
                l--;
            if (l == 0)
                l = w;
        }
        at[n] = text;
        len[n++] = l;
        text += l;
        while (*text == ' ')
            text++;
    }
    return n;
}

/* The key bar, always on the bottom row: the keys a class needs first
 * (m f n v e p among them), as many as fit, whole. */
static void draw_keybar(const tui_state *st, int y, int cols)
{
    static const char *const usual[] = {"s step", "r run", "m method", "f friction", "n scene", "v view",
                                        "e export", "p png", "? help", "q quit", "x reset", "b backend", NULL};
    /* presentation: the pace keys in the bar, the file keys go */
    static const char *const present[] = {"s step", "r run", "m method", "f friction", "n scene", "{ } pace",
                                          "x reset", "? help", "P leave", "q quit", "v view", NULL};
    const char *const *items = st->present ? present : usual;
    char bar[256] = "";
    size_t at = 0;
    for (int k = 0; items[k]; k++) {
        size_t l = strlen(items[k]) + 2;
        if ((int)(at + l) > cols || at + l >= sizeof bar)
            continue;   /* a later, shorter item may still fit */
        at += (size_t)snprintf(bar + at, sizeof bar - at, " %s ", items[k]);
    }
    tui_term_put(y, 0, TUI_C_LABEL, bar, cols);
}

static void draw_status(const tui_state *st, int rows, int cols)
{
    draw_keybar(st, rows - 1, cols);
    int y = rows - 2;
    double t = cx_clock_now() - st->job.t0;
    /* a step shows progress only when it is slow */
    if (tui_state_busy(st) && (st->job.kind != TUI_JOB_STEP || t > 0.25)) {
        int ph = tui_job_phase(st);
        const char *what = ph == TUI_PHASE_ASSEMBLE ? "assembling K and the contact rows"
                           : ph == TUI_PHASE_FACTORISE ? "factorising (method setup)"
                           : ph == TUI_PHASE_STEP      ? "one iteration"
                                                       : "starting";
        const char *spin = draw_utf8 ? spinner_utf8[(int)(t * 10) % 10]
                                     : (char[]){spinner_ascii[(int)(t * 10) % 4], 0};
        /* typed-ahead steps are shown as queued; a step says Esc stops it */
        char q[64] = "";
        if (st->queued_steps)
            snprintf(q, sizeof q, " %d step%s queued", st->queued_steps, st->queued_steps > 1 ? "s" : "");
        if (st->job.kind == TUI_JOB_PETSC) {   /* a whole run, its steps drawn as they come */
            const tui_run *run = tui_state_run(st);
            tui_put(y, 0, TUI_C_WARN, cols, "%s petsc %s level %d: iteration %d... %.1f s (keys still work), Esc stops it",
                spin, run ? run->method : "-", st->level, run && run->nsteps ? run->steps[run->nsteps - 1].iter : 0, t);
            return;
        }
        tui_put(y, 0, TUI_C_WARN, cols, "%s %s level %d: %s... %.1f s (keys still work)%s%s", spin,
            st->job.kind == TUI_JOB_BUILD ? st->scene.id : st->job.kind == TUI_JOB_STEP ? "stepping" : "switching",
            st->job.kind == TUI_JOB_STEP ? st->level : st->job.level, what, t, q,
            st->job.kind == TUI_JOB_STEP || st->job.box ? ", Esc cancels" : "");
        return;
    }
    if (st->editing) {
        tui_put(y, 0, TUI_C_SELECT, cols, " %s: %.*s_   (Enter sets, Esc cancels) ", tui_field_label(st, st->field),
            st->edit_len, st->edit);
        return;
    }
    if (st->msg[0]) {
        /* whole words: a message longer than the line wraps upwards (over
         * the panel above), never cut mid-word */
        const char *at[4];
        int len[4];
        int n = draw_wrap(st->msg, cols - 2, at, len, 4);
        int role = st->msg_error == 1 ? TUI_C_ERROR : st->msg_error == 2 ? TUI_C_WARN : TUI_C_OK;
        for (int k = 0; k < n; k++)
            tui_put(y - (n - 1) + k, 0, role, cols, " %.*s%*s", len[k], at[k], cols - 1 - len[k], "");
        return;
    }
    tui_put(y, 0, TUI_C_FAINT, cols, " %s %s rows, %s %s change, Enter types a value",
        tui_sym("↑↓", "up/dn"), "choose", tui_sym("←→", "<-/->"), "");
}

/* ---- pickers ---------------------------------------------------------------- */

static void draw_pickers(const tui_state *st, tui_box b)
{
    int nf = tui_state_nfields(st);
    int y = b.y;
    const int lw = 11;   /* labels up to 10 characters (abar_scale, max_sweeps) */
    tui_rule(y++, b.x, b.w, "setup");
    /* the rows above the session block; scrolled to keep the cursor in view
     * when a method has many parameters */
    int room = b.h - 6, first = 0;
    if (room < 1)
        room = 1;
    if (st->field >= room)
        first = st->field - room + 1;
    for (int f = first; f < nf && y < b.y + 1 + room; f++, y++) {
        char val[64];
        tui_field_value(st, f, val, sizeof val);
        int sel = f == st->field, i;
        int role = sel ? TUI_C_SELECT : TUI_C_NORMAL;
        const tui_row *row = tui_row_at(st, f, &i);
        char reason[CX_DIAG_LEN];
        if (row->greyed && row->greyed(st, i, reason, sizeof reason)[0])
            role = sel ? TUI_C_SELECT : TUI_C_GREY;
        if (sel && st->editing)
            snprintf(val, sizeof val, "%.*s_", st->edit_len, st->edit);
        char line[128], label[32];
        const char *full = tui_field_label(st, f);
        if ((int)strlen(full) > lw - 1)   /* the full name is in the detail below when selected */
            snprintf(label, sizeof label, "%.*s%s", lw - 2, full, tui_sym("…", "~"));
        else
            snprintf(label, sizeof label, "%s", full);
        int pad = lw - (int)strlen(full) > 0 ? lw - (int)strlen(full) : 1;
        snprintf(line, sizeof line, "%s%*s%s%-*s", label, pad, "", sel ? tui_sym("◂", "<") : " ", b.w, val);
        tui_term_put(y, b.x, role, line, b.w);
        tui_hit_add(y, b.x, b.x + b.w, TUI_HIT_FIELD, f);
    }
    y++;
    if (y >= b.y + b.h)
        return;
    /* detail of the row under the cursor */
    int bottom = b.y + b.h - 5, i;
    const tui_row *row = tui_row_at(st, st->field, &i);
    char detail[1024] = "", reason[CX_DIAG_LEN];
    if (row->describe)
        row->describe(st, i, detail, sizeof detail);
    if (row->kind == TUI_ROW_LIST) {
        int n = row->count(st);
        int cur = row->current(st);
        int first = cur - (bottom - y - 2) / 2;
        if (first + (bottom - y - 2) > n)
            first = n - (bottom - y - 2);
        if (first < 0)
            first = 0;
        for (int k = first; k < n && y < bottom - 1; k++, y++) {
            const char *id = row->item(st, k, reason, sizeof reason);
            int grey = reason[0] != '\0';
            tui_put(y, b.x, k == cur ? (grey ? TUI_C_GREY : TUI_C_STICK) : grey ? TUI_C_GREY : TUI_C_NORMAL, b.w,
                "%s%s", k == cur ? tui_sym("▸ ", "> ") : "  ", id);
        }
        /* the reason it is grey, or its description, wrapped at words */
        int grey = row->greyed && row->greyed(st, i, reason, sizeof reason)[0];
        const char *text = grey ? reason + (strncmp(reason, "method ", 7) == 0 ? 7 : 0) : detail;
        const char *at[6];
        int len[6];
        int nl = draw_wrap(text, b.w, at, len, 6);
        for (int k = 0; k < nl && (y < bottom || (grey && k == 0)); k++)
            tui_put(y++, b.x, grey ? TUI_C_WARN : TUI_C_FAINT, b.w, "%.*s", len[k], at[k]);
    } else if (detail[0]) {
        /* the first line as it is, the rest wrapped */
        size_t first = strcspn(detail, "\n");
        tui_put(y++, b.x, TUI_C_FAINT, b.w, "%.*s", (int)first, detail);
        const char *h = detail[first] ? detail + first + 1 : "";
        while (*h && y < bottom) {
            int len = (int)strlen(h);
            int cut = len <= b.w ? len : b.w;
            if (cut < len)
                while (cut > 0 && h[cut] != ' ')
                    cut--;
            if (cut == 0)
                cut = b.w < len ? b.w : len;
            tui_put(y++, b.x, TUI_C_FAINT, b.w, "%.*s", cut, h);
            h += cut;
            while (*h == ' ')
                h++;
        }
    }
    /* the session */
    y = b.y + b.h - 5;
    if (y <= b.y)
        return;
    tui_rule(y++, b.x, b.w, "session");
    tui_put(y++, b.x, TUI_C_NORMAL, b.w, "%dD %s, %d bod%s", st->info->dim,
        st->info->mesh ? cx_elem_name(st->info->mesh->etype) : "-", st->info->mesh ? st->info->mesh->nbodies : 0,
        st->info->mesh && st->info->mesh->nbodies > 1 ? "ies" : "y");
    tui_put(y++, b.x, TUI_C_NORMAL, b.w, "%d dofs, %d points", st->info->n, st->info->m);
    tui_put(y++, b.x, st->cache.factorizations == 1 ? TUI_C_OK : TUI_C_WARN, b.w, "cache %d op%s, %ld fact.",
        st->cache_size, st->cache_size == 1 ? "" : "s", st->cache.factorizations);
    /* the run's setup apart from its iterations; the explorer's own work
     * for drawing apart from the run's */
    const tui_run *run = tui_state_run(st);
    if (run && tui_run_cached(run))
        tui_put(y++, b.x, TUI_C_OK, b.w, "cached: 0 fact., %.1fms", 1e3 * run->setup);
    else if (run)
        tui_put(y++, b.x, TUI_C_NORMAL, b.w, "setup %.1fms draw %ldK", 1e3 * run->setup,
            run->draw.solves);
}

/* ---- help overlay -------------------------------------------------------------------- */

/* What the help explains besides the keys: the step table's columns, the
 * contact strip's symbols and the colours (name, UTF-8 symbol or NULL,
 * the role it is drawn in, the words). */
static const struct {
    const char *name, *utf8;
    int role;
    const char *help;
} draw_legend[] = {
    {"kkt", NULL, TUI_C_LABEL, "contact conditions' error"},
    {"own", NULL, TUI_C_LABEL, "the method's own criterion"},
    {"fr ct", NULL, TUI_C_LABEL, "points free, in contact"},
    {"st sl", NULL, TUI_C_LABEL, "points sticking, slipping"},
    {"ch", NULL, TUI_C_LABEL, "points changed this step"},
    {"inn nK", NULL, TUI_C_LABEL, "inner iterations, K solves"},
    {"free", NULL, TUI_C_FREE, "strip: no contact (grey)"},
    {"contact", NULL, TUI_C_CONTACT, "strip: contact, no friction"},
    {"stick", NULL, TUI_C_STICK, "strip: sticking"},
    {"slip", NULL, TUI_C_SLIP, "strip: slipping, arrow: way"},
    {"changed", NULL, TUI_C_CHANGED, "strip: changed this step"},
    {"Hertz", NULL, TUI_C_REF, "exact pressure; bars: solved"},
    {"run", "━━ run", TUI_C_SERIES0, "a run's colour: plot, table"},
    {"tol", NULL, TUI_C_LABEL, "dotted line: the tolerance"},
    {"grey", NULL, TUI_C_GREY, "cannot run (reason beside)"},
};
#define DRAW_NLEGEND ((int)(sizeof draw_legend / sizeof draw_legend[0]))

static void draw_help(int rows, int cols)
{
    const tui_binding *bd = tui_bindings();
    int n = 0;
    while (bd[n].key)
        n++;
    int nkeys = 0;
    for (int k = 0; k < n; k++)
        nkeys += bd[k].help != NULL;
    int ncol = (nkeys + 4 + DRAW_NLEGEND > rows - 2) ? 2 : 1;
    int per = (nkeys + DRAW_NLEGEND + ncol - 1) / ncol;
    int cw = (cols - 2) / ncol < 44 ? (cols - 2) / ncol : 44;
    int w = ncol * cw + 2, h = per + 4;
    if (w > cols)
        w = cols;
    if (h > rows)
        h = rows;
    int y0 = (rows - h) / 2, x0 = (cols - w) / 2;
    char blank[512];
    snprintf(blank, sizeof blank, "%*s", w, "");
    for (int y = 0; y < h; y++)
        tui_term_put(y0 + y, x0, TUI_C_NORMAL, blank, w);
    tui_put(y0, x0, TUI_C_TITLE, w, " help: keys of the explorer, columns, colours%*s", w - 45, "");
    int at = 0;
    for (int k = 0; k < n; k++) {
        if (!bd[k].help)
            continue;   /* an alias: named with its key */
        int col = at / per, row = at % per;
        at++;
        tui_put(y0 + 2 + row, x0 + 1 + col * cw, TUI_C_LABEL, 9, "%s", bd[k].keyname);
        tui_put(y0 + 2 + row, x0 + 10 + col * cw, TUI_C_NORMAL, cw - 10, "%s", bd[k].help);
    }
    for (int k = 0; k < DRAW_NLEGEND; k++, at++) {
        int col = at / per, row = at % per;
        int role = draw_legend[k].role;
        const char *name = draw_legend[k].utf8 ? tui_sym(draw_legend[k].utf8, draw_legend[k].name) : draw_legend[k].name;
        tui_put(y0 + 2 + row, x0 + 1 + col * cw, role, 9, "%s", name);
        tui_put(y0 + 2 + row, x0 + 10 + col * cw, TUI_C_NORMAL, cw - 10, "%s", draw_legend[k].help);
    }
    tui_put(y0 + h - 1, x0, TUI_C_FAINT, w, " any key closes this help");
}

/* ---- the screen --------------------------------------------------------------------- */

/* ---- what is where, for the mouse ---------------------------------------- */

typedef struct draw_hit {
    int y, x0, x1, kind, index;
} draw_hit;
static draw_hit draw_hits[128];
static int draw_nhits;

void tui_hit_add(int y, int x0, int x1, int kind, int index)
{
    if (draw_nhits < (int)(sizeof draw_hits / sizeof draw_hits[0]))
        draw_hits[draw_nhits++] = (draw_hit){y, x0, x1, kind, index};
}

int tui_draw_hit(int y, int x, int *index)
{
    for (int k = 0; k < draw_nhits; k++)
        if (draw_hits[k].y == y && x >= draw_hits[k].x0 && x < draw_hits[k].x1) {
            *index = draw_hits[k].index;
            return draw_hits[k].kind;
        }
    return 0;
}

void tui_draw(const tui_state *st, int rows, int cols, int utf8)
{
    draw_utf8 = utf8;
    draw_nhits = 0;
    tui_term_scheme(st->present);
    tui_term_clear();
    if (cols < DRAW_MIN_COLS || rows < DRAW_MIN_ROWS) {
        /* whole words at any size, centred (30x10 shows it all) */
        char msg[96];
        snprintf(msg, sizeof msg, "terminal too small: %dx%d, needs %dx%d; q quits", cols, rows, DRAW_MIN_COLS,
                 DRAW_MIN_ROWS);
        const char *at[8];
        int len[8];
        int n = draw_wrap(msg, cols, at, len, rows < 8 ? rows : 8);
        for (int k = 0; k < n; k++) {
            char line[96];
            snprintf(line, sizeof line, "%.*s", len[k], at[k]);
            tui_term_put((rows - n) / 2 + k, (cols - len[k]) / 2, TUI_C_WARN, line, cols);
        }
        return;
    }
    draw_header(st, cols);
    int lw = cols >= 120 ? 30 : 23;
    int top = st->present ? 2 : 1;
    draw_pickers(st, (tui_box){top, 0, rows - 2 - top, lw});

    /* the header, then the panels, the status line and the key bar */
    int x = lw + 1, w = cols - x, y = 1, h = rows - 3;
    if (st->present) {
        /* the header's second line: the scene and the method's source */
        y = 2;
        h--;
    }
    /* a second column for the mesh on wide terminals */
    int mesh_w = cols >= 140 ? (w * 2) / 5 : 0;
    w -= mesh_w ? mesh_w + 1 : 0;
    int big = h >= 34;
    int steps_h = big ? 12 : 6;
    int contact_h = st->info->dim == 3 ? (big ? 10 : 5) : (big ? 6 : 4);
    int runs_h = mesh_w ? 0 : big ? 8 : 4;
    if (st->present) {
        /* the plot and the contact strip enlarged, the tables shorter */
        steps_h = big ? 7 : 4;
        contact_h = st->info->dim == 3 ? (big ? 14 : 6) : (big ? 10 : 5);
        runs_h = mesh_w ? 0 : big ? 6 : 0;
    }
    int plot_h = h - steps_h - contact_h - runs_h;
    if (plot_h < 5) {
        runs_h = 0;
        plot_h = h - steps_h - contact_h;
    }
    tui_panel_steps(st, (tui_box){y, x, steps_h, w});
    y += steps_h;
    tui_panel_contact(st, (tui_box){y, x, contact_h, w});
    y += contact_h;
    if (st->view == 1 && !mesh_w)
        tui_panel_mesh(st, (tui_box){y, x, plot_h, w});
    else
        tui_panel_plot(st, (tui_box){y, x, plot_h, w});
    y += plot_h;
    if (runs_h)
        tui_panel_runs(st, (tui_box){y, x, runs_h, w});
    if (mesh_w) {
        int mx = x + w + 1, rh = big ? 10 : 5;
        tui_panel_mesh(st, (tui_box){top, mx, h - rh, mesh_w});
        tui_panel_runs(st, (tui_box){top + h - rh, mx, rh, mesh_w});
    }
    /* last: a long message wraps upwards over the panels */
    draw_status(st, rows, cols);
    if (st->help)
        draw_help(rows, cols);
}
