/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The explorer's program: options, the one loop (a timed getch; while
 * running, one step per tick), scripted keys for tests, and restoring the
 * terminal on every way out (q, Ctrl-C, SIGTERM/SIGHUP, a fatal error). */
#include "tui/tui_impl.h"
#include "base/opt_solve.h"

#include <locale.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char tui_usage[] =
    "usage: signorini [tui [SCENE] [options]]\n"
    "\n"
    "The explorer: pick a scene, a friction law, a method and its parameters;\n"
    "step the solver and watch the contact set and the error. With no\n"
    "argument it opens on 'hertz'. Press ? in the explorer for the keys.\n";

static volatile sig_atomic_t loop_quit;

/* the signal that ends the loop (its exit status is 128 + it) */
static void loop_on_signal(int sig)
{
    loop_quit = sig;
}

/* Out of memory in the explorer (the core's hook, tui_on_oom): restore the
 * terminal, say why, exit 1. */
static void loop_fatal(const char *msg)
{
    tui_term_close();
    fprintf(stderr, "signorini: %s\n", msg);
    exit(1);
}

typedef struct {
    const char *scene, *method, *keys, *export_dir;
    int friction, level, frames, mono, ascii, stats, present;
    int backend;   /* --backend: 0 direct, 1 petsc */
} loop_args;

static const cx_opt loop_opts[] = {
    CX_OPT_ROW_LEVEL(loop_args, level),
    {"method", 0, CX_OPT_STRING, 0, 0, 0, NULL, "ID", "method (default: the scene's first)",
     offsetof(loop_args, method), NULL},
    CX_OPT_ROW_FRICTION(loop_args, friction),
    {"backend", 0, CX_OPT_CHOICE, 0, 0, 0, "direct|petsc", "NAME",
     "the runs' backend: petsc runs ssn-tresca on the PETSc backend, one rank ('b' changes it)",
     offsetof(loop_args, backend), NULL},
    {"mono", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "no colours (also when NO_COLOR is set)",
     offsetof(loop_args, mono), NULL},
    {"ascii", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "ASCII only (automatic when the locale is not UTF-8)",
     offsetof(loop_args, ascii), NULL},
    {"export-dir", 0, CX_OPT_STRING, 0, 0, 0, NULL, "DIR", "where 'e' writes the runs (default: .)",
     offsetof(loop_args, export_dir), NULL},
    {"present", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL,
     "presentation mode: paced runs (about 2 steps/s), high contrast, big plot", offsetof(loop_args, present), NULL},
    {"keys", 0, CX_OPT_STRING, 0, 0, 0, NULL, "KEYS", "type these keys first, one whenever idle (tests)",
     offsetof(loop_args, keys), NULL},
    {"frames", 0, CX_OPT_INT, 1, 1 << 30, 0, NULL, "N", "draw N frames (one per tick) and quit (tests)",
     offsetof(loop_args, frames), NULL},
    {"stats", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL,
     "on exit, print the median redraw and step times (stderr)", offsetof(loop_args, stats), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

/* -1 to go on, else the exit status: 0 after the help, CX_EXIT_USAGE
 * after one line for a malformed command line. */
static int loop_parse(int argc, char **argv, loop_args *a)
{
    memset(a, 0, sizeof *a);
    a->friction = -1;
    cx_opt_group groups[] = {{loop_opts, a}, {NULL, NULL}};
    cx_diag d;
    cx_diag_clear(&d);
    int r = cx_opt_parse(groups, argc, argv, &a->scene, 1, NULL, &d);
    if (r == CX_OPT_HELP) {
        fputs(tui_usage, stdout);
        fputs("\n  -h, --help           this help\n", stdout);
        cx_opt_help(loop_opts, stdout);
        return CX_EXIT_OK;
    }
    /* a method id is a word of the registry: a usage error like a bad law */
    if (!r && a->method && !cx_method_find(a->method))
        r = cx_diag_set(&d, CX_EINVAL, "--method: unknown method '%s' (see 'signorini list')", a->method);
    if (r) {
        fprintf(stderr, "signorini tui: %s%s\n", d.msg, strstr(d.msg, "(see ") ? "" : " (see 'signorini tui --help')");
        return CX_EXIT_USAGE;
    }
    return -1;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    if (n == 0)
        return 0;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

#define LOOP_SAMPLES 4096

int tui_main(int argc, char **argv)
{
    loop_args a;
    int r = loop_parse(argc, argv, &a);
    if (r >= 0)
        return r;
    int law = a.friction;
    /* numbers in the C locale from the start (the scene is read before the
     * terminal opens); tui_term_open takes the user's locale for the
     * characters and keeps LC_NUMERIC at C */
    setlocale(LC_ALL, "");
    setlocale(LC_NUMERIC, "C");
    tui_state *st = NULL;
    cx_diag d;
    cx_diag_clear(&d);
    tui_on_oom(loop_fatal);
    if (tui_state_create(&st, a.scene ? a.scene : "hertz", a.level, a.method, law, 0, &d) != CX_OK) {
        fprintf(stderr, "signorini tui: %s\n", d.msg);
        return 1;
    }
    if (a.export_dir)
        tui_state_set_export_dir(st, a.export_dir);
    if (a.present)
        tui_state_set_present(st, 1);
    if (a.backend) {
        if (!tui_backend_available()) {
            tui_state_destroy(&st);
            fprintf(stderr, "signorini tui: --backend petsc: this build has no PETSc backend "
                            "(meson setup -Dpetsc=enabled)\n");
            return 1;
        }
        st->sel_backend = 1;   /* ssn-tresca, the backend's first method */
    }

    if (tui_term_open(a.mono, a.ascii) != 0) {
        tui_state_destroy(&st);
        fprintf(stderr, "signorini tui: cannot open the terminal\n");
        return 1;
    }
    atexit(tui_term_close);
    signal(SIGINT, loop_on_signal);
    signal(SIGTERM, loop_on_signal);
    signal(SIGHUP, loop_on_signal);

    static double draw_t[LOOP_SAMPLES], step_t[LOOP_SAMPLES];
    int ndraw = 0, nstep = 0, frames = 0;
    const char *keys = a.keys;
    int dirty = 1;
    double last_draw = 0, last_step = 0;
    while (!loop_quit) {
        if (tui_state_poll(st))
            dirty = 1;
        int busy = tui_state_busy(st);
        double now = cx_clock_now();
        /* while a job runs, the progress line moves ten times a second */
        /* with --frames every tick draws, so that N frames end the run */
        if (dirty || a.frames || (busy && now - last_draw > 0.1)) {
            int rows, cols;
            tui_term_size(&rows, &cols);
            double t0 = cx_clock_now();
            tui_draw(st, rows, cols, tui_term_utf8());
            tui_term_show();
            last_draw = cx_clock_now();
            if (ndraw < LOOP_SAMPLES)
                draw_t[ndraw++] = last_draw - t0;
            dirty = 0;
            if (a.frames && ++frames >= a.frames)
                break;
        }
        int key;
        if (keys && *keys && tui_state_idle(st)) {
            key = (unsigned char)*keys++;
            if (key == '\r')
                key = TUI_KEY_ENTER;
        } else {
            /* while a step runs, look often: most take well under a millisecond */
            double age = tui_state_step_age(st, now);
            int stepping = busy && age >= 0 && age < 0.05;
            /* a paced run (presentation) waits for its next step in getch */
            double wait = tui_state_step_interval(st) - (now - last_step);
            int run_ms = wait > 0 ? (int)(1e3 * wait) + 1 : 0;
            key = tui_term_key(stepping ? 1 : tui_state_running(st) && !busy ? run_ms : busy ? 50 : 200);
        }
        if (key == 26) {
            /* Ctrl-Z (a key in raw mode): suspend; fg redraws */
            tui_term_suspend();
            dirty = 1;
            continue;
        }
        if (key == TUI_KEY_MOUSE) {
            /* on what the last frame drew there */
            int y, x, index;
            int what = tui_term_mouse(&y, &x);
            int kind = tui_draw_hit(y, x, &index);
            tui_state_apply(st, kind ? tui_mouse(st, kind, index, what) : 0);
            dirty = 1;
            continue;
        }
        if (key != TUI_KEY_NONE) {
            int react = tui_key(st, key);
            if (react & TUI_QUIT) {
                /* Ctrl-C (a key in raw mode) exits as an interrupt does,
                 * 130, like the other subcommands */
                if (key == TUI_KEY_CTRL_C)
                    loop_quit = SIGINT;
                break;
            }
            tui_state_apply(st, react);
            dirty = 1;
        }
        if (tui_state_running(st) && !tui_state_busy(st) &&
            cx_clock_now() - last_step >= tui_state_step_interval(st)) {
            last_step = cx_clock_now();
            tui_state_step(st);
            dirty = 1;
        }
    }
    tui_term_close();
    int status = loop_quit ? 128 + (int)loop_quit : 0;
    /* the steps' own times (the method's step and the bookkeeping); a
     * job in progress is not read: its step is not in the history yet */
    for (int r = 0; r < tui_state_nruns(st); r++)
        for (int k = 0; k < tui_state_nsteps(st, r) && nstep < LOOP_SAMPLES; k++)
            step_t[nstep++] = tui_state_step_time(st, r, k);
    if (a.stats)
        fprintf(stderr, "explorer: %d redraws, median %.3f ms; %d steps, median %.3f ms\n", ndraw,
               1e3 * median(draw_t, ndraw), nstep, 1e3 * median(step_t, nstep));
    if (tui_state_busy(st) || tui_job_abandoned_any()) {
        /* a build cannot be interrupted: leave it (or one abandoned
         * earlier, whose libraries' exit handlers could wait for it) to
         * the exit, after --stats, which quitting mid-build still prints */
        fflush(stdout);
        fflush(stderr);
        _exit(status);
    }
    tui_state_destroy(&st);
    return status;
}
