/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The terminal: the only file that includes curses (doc/style.md C12). Keys
 * become TUI_KEY_* codes, colour roles become colour pairs or, without
 * colours, attributes (bold, dim, reverse, underline). */
#include "tui/tui_impl.h"

#include <curses.h>
#include <langinfo.h>
#include <locale.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int term_on;
static int term_mouse_y, term_mouse_x, term_mouse_what;
static int term_utf8;
static attr_t term_attr[TUI_C_COUNT];

/* role: foreground, background (-1 default), extra attribute with colours,
 * attribute without colours */
static const struct {
    short fg, bg;
    attr_t color_attr, mono_attr;
} term_scheme[TUI_C_COUNT] = {
    [TUI_C_NORMAL] = {-1, -1, 0, 0},
    [TUI_C_FAINT] = {COLOR_BLUE, -1, 0, 0},
    [TUI_C_LABEL] = {COLOR_CYAN, -1, 0, 0},
    [TUI_C_TITLE] = {COLOR_WHITE, COLOR_BLUE, A_BOLD, A_REVERSE},
    [TUI_C_SELECT] = {COLOR_BLACK, COLOR_CYAN, 0, A_REVERSE},
    [TUI_C_GREY] = {-1, -1, A_DIM, A_DIM},   /* not bold black: invisible on dark themes */
    [TUI_C_REF] = {COLOR_MAGENTA, -1, 0, 0},
    [TUI_C_BAR] = {COLOR_YELLOW, -1, 0, A_BOLD},
    [TUI_C_CURRENT] = {COLOR_GREEN, -1, A_BOLD, A_BOLD},
    [TUI_C_FREE] = {-1, -1, A_DIM, 0},
    [TUI_C_CONTACT] = {COLOR_CYAN, -1, A_BOLD, A_BOLD},
    [TUI_C_STICK] = {COLOR_GREEN, -1, A_BOLD, A_BOLD},
    [TUI_C_SLIP] = {COLOR_RED, -1, A_BOLD, A_BOLD},
    [TUI_C_CHANGED] = {COLOR_BLACK, COLOR_YELLOW, 0, A_REVERSE},
    [TUI_C_OK] = {COLOR_GREEN, -1, 0, 0},
    [TUI_C_WARN] = {COLOR_YELLOW, -1, A_BOLD, A_BOLD},
    [TUI_C_ERROR] = {COLOR_WHITE, COLOR_RED, A_BOLD, A_REVERSE | A_BOLD},
};

/* Presentation: high contrast on white and on black alike; no dark blue,
 * no bold black, no yellow text; labels in the default colour, emphasis
 * by reverse video and bold. */
static const struct {
    short fg, bg;
    attr_t color_attr;
} term_present[TUI_C_COUNT] = {
    [TUI_C_NORMAL] = {-1, -1, 0},
    [TUI_C_FAINT] = {-1, -1, 0},
    [TUI_C_LABEL] = {-1, -1, A_BOLD},
    [TUI_C_TITLE] = {-1, -1, A_REVERSE | A_BOLD},
    [TUI_C_SELECT] = {-1, -1, A_REVERSE},
    [TUI_C_GREY] = {-1, -1, A_DIM},
    [TUI_C_REF] = {COLOR_MAGENTA, -1, A_BOLD},
    [TUI_C_BAR] = {-1, -1, A_BOLD},
    [TUI_C_CURRENT] = {-1, -1, A_BOLD},   /* the current run: its series colour below */
    [TUI_C_FREE] = {-1, -1, 0},
    [TUI_C_CONTACT] = {COLOR_BLUE, -1, A_BOLD},
    [TUI_C_STICK] = {COLOR_GREEN, -1, A_BOLD},
    [TUI_C_SLIP] = {COLOR_RED, -1, A_BOLD},
    [TUI_C_CHANGED] = {-1, -1, A_REVERSE | A_BOLD},
    [TUI_C_OK] = {COLOR_GREEN, -1, A_BOLD},
    [TUI_C_WARN] = {COLOR_RED, -1, A_BOLD},
    [TUI_C_ERROR] = {COLOR_WHITE, COLOR_RED, A_BOLD},
};

static int term_color, term_cur_scheme = -1;

void tui_term_scheme(int present)
{
    if (!term_on || present == term_cur_scheme)
        return;
    term_cur_scheme = present;
    for (int r = 1; r < TUI_C_COUNT; r++) {
        short fg, bg;
        attr_t extra;
        if (r >= TUI_C_SERIES0) {
            /* the runs: the shared palette, nearest colour the terminal has */
            const unsigned char *rgb = cx_palette_series[r - TUI_C_SERIES0];
            fg = (short)(COLORS >= 256 ? tui_palette_xterm256(rgb) : tui_palette_basic8(rgb));
            bg = -1;
            extra = COLORS >= 256 ? 0 : A_BOLD;
        } else if (present) {
            fg = term_present[r].fg;
            bg = term_present[r].bg;
            extra = term_present[r].color_attr;
        } else {
            fg = term_scheme[r].fg;
            bg = term_scheme[r].bg;
            extra = term_scheme[r].color_attr;
        }
        if (term_color && init_pair((short)r, fg, bg) == OK)
            term_attr[r] = COLOR_PAIR(r) | extra;
        else
            term_attr[r] = r >= TUI_C_SERIES0 ? (r == TUI_C_SERIES0 ? A_BOLD : 0) : term_scheme[r].mono_attr;
    }
}

int tui_term_open(int mono, int ascii)
{
    /* the user's locale for the characters (UTF-8 drawing), the C locale
     * for numbers: scene files are read and exports written with '.'
     * whatever LC_ALL or LC_NUMERIC say */
    setlocale(LC_ALL, "");
    setlocale(LC_NUMERIC, "C");
    const char *cs = nl_langinfo(CODESET);
    term_utf8 = !ascii && cs && (strcmp(cs, "UTF-8") == 0 || strcmp(cs, "utf8") == 0);
    if (!initscr())
        return -1;
    term_on = 1;
    raw();          /* Ctrl-C arrives as a key: the loop quits cleanly */
    noecho();
    keypad(stdscr, TRUE);
    curs_set(0);
    set_escdelay(25);
    /* the mouse: curses turns the terminal's reports on (button events);
     * SGR reports (1006) are asked for as well, which read the same at any
     * width, and are decoded here when the terminfo entry does not know
     * them (tmux's and screen's kmous is the old \E[M) */
    mousemask(BUTTON1_PRESSED | BUTTON4_PRESSED | BUTTON5_PRESSED, NULL);
    mouseinterval(0);
    fputs("\033[?1000h\033[?1006h", stdout);
    fflush(stdout);
    if (getenv("NO_COLOR") && getenv("NO_COLOR")[0])
        mono = 1;
    term_color = !mono && has_colors() && start_color() == OK;
    if (term_color)
        use_default_colors();
    term_cur_scheme = -1;
    tui_term_scheme(0);
    return 0;
}

void tui_term_suspend(void)
{
    if (!term_on)
        return;
    /* raw mode: Ctrl-Z arrives as a key, not as SIGTSTP; leave the screen,
     * stop as the tty's suspend would, and on SIGCONT (fg) take the screen
     * back whole */
    endwin();
    fflush(stdout);
    void (*old)(int) = signal(SIGTSTP, SIG_DFL);
    raise(SIGTSTP);
    signal(SIGTSTP, old);
    reset_prog_mode();
    fputs("\033[?1000h\033[?1006h", stdout);
    fflush(stdout);
    clearok(curscr, TRUE);
    refresh();
}

void tui_term_close(void)
{
    if (!term_on)
        return;
    term_on = 0;
    curs_set(1);
    fputs("\033[?1006l\033[?1000l", stdout);
    fflush(stdout);
    endwin();
}

int tui_term_utf8(void)
{
    return term_utf8;
}

void tui_term_size(int *rows, int *cols)
{
    getmaxyx(stdscr, *rows, *cols);
}

int tui_term_mouse(int *y, int *x)
{
    *y = term_mouse_y;
    *x = term_mouse_x;
    return term_mouse_what;
}

/* An SGR mouse report after its ESC [ <: "b;x;y" then M (press) or m
 * (release). Button 0 is the left one, 64 and 65 the wheel; the bits 4,
 * 8, 16 (shift, alt, ctrl) are ignored, motion (32) and releases too. */
static int term_sgr_mouse(void)
{
    int v[3] = {0, 0, 0}, n = 0, c;
    timeout(50);
    while ((c = getch()) != ERR) {
        if (c >= '0' && c <= '9' && v[n] < 100000)
            v[n] = 10 * v[n] + (c - '0');
        else if (c == ';' && n < 2)
            n++;
        else
            break;
    }
    if ((c != 'M' && c != 'm') || n != 2 || c == 'm' || (v[0] & 32))
        return TUI_KEY_NONE;
    int b = v[0] & ~(4 | 8 | 16);
    term_mouse_what = b == 0 ? TUI_MOUSE_CLICK : b == 64 ? TUI_MOUSE_WHEEL_UP : b == 65 ? TUI_MOUSE_WHEEL_DOWN : 0;
    term_mouse_x = v[1] - 1;
    term_mouse_y = v[2] - 1;
    return term_mouse_what ? TUI_KEY_MOUSE : TUI_KEY_NONE;
}

int tui_term_key(int timeout_ms)
{
    timeout(timeout_ms);
    int k = getch();
    if (k == 27) {
        /* Esc, or the start of a report curses did not decode */
        timeout(5);
        int c1 = getch();
        if (c1 == '[') {
            int c2 = getch();
            if (c2 == '<')
                return term_sgr_mouse();
            if (c2 != ERR)
                ungetch(c2);
        }
        if (c1 != ERR)
            ungetch(c1);
        return TUI_KEY_ESC;
    }
    if (k == KEY_MOUSE) {
        MEVENT ev;
        if (getmouse(&ev) != OK)
            return TUI_KEY_NONE;
        term_mouse_y = ev.y;
        term_mouse_x = ev.x;
        term_mouse_what = ev.bstate & BUTTON1_PRESSED ? TUI_MOUSE_CLICK
                          : ev.bstate & BUTTON4_PRESSED ? TUI_MOUSE_WHEEL_UP
                          : ev.bstate & BUTTON5_PRESSED ? TUI_MOUSE_WHEEL_DOWN
                                                        : 0;
        return term_mouse_what ? TUI_KEY_MOUSE : TUI_KEY_NONE;
    }
    switch (k) {
    case ERR: return TUI_KEY_NONE;
    case KEY_UP: return TUI_KEY_UP;
    case KEY_DOWN: return TUI_KEY_DOWN;
    case KEY_LEFT: return TUI_KEY_LEFT;
    case KEY_RIGHT: return TUI_KEY_RIGHT;
    case KEY_PPAGE: return TUI_KEY_PGUP;
    case KEY_NPAGE: return TUI_KEY_PGDN;
    case KEY_BACKSPACE: case 127: case 8: return TUI_KEY_BACKSPACE;
    case KEY_ENTER: case '\r': case '\n': return TUI_KEY_ENTER;
    case KEY_RESIZE: return TUI_KEY_RESIZE;
    default: return k >= 0 && k < 256 ? k : TUI_KEY_NONE;
    }
}

void tui_term_clear(void)
{
    erase();
}

void tui_term_put(int y, int x, int role, const char *s, int maxw)
{
    int rows, cols;
    getmaxyx(stdscr, rows, cols);
    if (y < 0 || y >= rows || x >= cols)
        return;
    int room = cols - x;
    if (maxw < 0 || maxw > room)
        maxw = room;
    /* count columns by code points: every glyph the explorer uses is one
     * column wide */
    int n = 0;
    size_t bytes = 0;
    while (s[bytes] && n < maxw) {
        unsigned char c = (unsigned char)s[bytes];
        size_t len = c < 0x80 ? 1 : c < 0xE0 ? 2 : c < 0xF0 ? 3 : 4;
        for (size_t k = 1; k < len; k++)
            if (!s[bytes + k])
                len = k;
        if (x + n < 0) {
            bytes += len;
            n++;
            continue;
        }
        bytes += len;
        n++;
    }
    int skip = x < 0 ? -x : 0;
    const char *p = s;
    for (int k = 0; k < skip && *p; k++) {
        p++;
        while ((*p & 0xC0) == 0x80)
            p++;
    }
    attrset(term_attr[role]);
    mvaddnstr(y, x + skip, p, (int)(bytes - (size_t)(p - s)));
    attrset(A_NORMAL);
}

void tui_term_show(void)
{
    refresh();
}
