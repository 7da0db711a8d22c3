/* The explorer's program: options, the one loop (a timed getch; while
 * running, one step per tick), scripted keys for tests, and restoring the
 * terminal on every way out (q, Ctrl-C, SIGTERM/SIGHUP, a fatal error). */
#include "tui/tui_impl.h"

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
    "argument it opens on 'hertz'. Press ? in the explorer for the keys.\n"
    "\n"
    "  --level L            mesh level (default: the scene's)\n"
    "  --method ID          method (default: the scene's first)\n"
    "  --friction LAW       none | tresca | coulomb (default: the scene's)\n"
    "  --mono               no colours (also when NO_COLOR is set)\n"
    "  --ascii              ASCII only (automatic when the locale is not UTF-8)\n"
    "  --export-dir DIR     where 'e' writes the runs (default: .)\n"
    "  --keys KEYS          type these keys first, one whenever idle (tests)\n"
    "  --frames N           draw N frames (one per tick) and quit (tests)\n"
    "  --stats              on exit, print the median redraw and step times (stderr)\n";

static volatile sig_atomic_t loop_quit;

static void loop_on_signal(int sig)
{
    (void)sig;
    loop_quit = 1;
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
    const char *scene, *method, *friction, *keys, *export_dir;
    int level, frames, mono, ascii, stats;
} loop_args;

static int loop_parse(int argc, char **argv, loop_args *a)
{
    memset(a, 0, sizeof *a);
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        long n;
        if (strcmp(o, "--help") == 0 || strcmp(o, "-h") == 0) {
            fputs(tui_usage, stdout);
            return 0;
        } else if (strcmp(o, "--mono") == 0) {
            a->mono = 1;
        } else if (strcmp(o, "--ascii") == 0) {
            a->ascii = 1;
        } else if (strcmp(o, "--stats") == 0) {
            a->stats = 1;
        } else if (!v && (strcmp(o, "--level") == 0 || strcmp(o, "--frames") == 0 || strcmp(o, "--method") == 0 ||
                          strcmp(o, "--friction") == 0 || strcmp(o, "--keys") == 0 ||
                          strcmp(o, "--export-dir") == 0)) {
            fprintf(stderr, "signorini tui: option '%s' needs a value\n", o);
            return 1;
        } else if (strcmp(o, "--level") == 0 || strcmp(o, "--frames") == 0) {
            if (cx_parse_int(v, 1, 1 << 30, &n)) {
                fprintf(stderr, "signorini tui: %s '%s': expected a positive integer\n", o, v);
                return 1;
            }
            *(strcmp(o, "--level") == 0 ? &a->level : &a->frames) = (int)n;
            i++;
        } else if (strcmp(o, "--method") == 0) {
            a->method = argv[++i];
        } else if (strcmp(o, "--friction") == 0) {
            a->friction = argv[++i];
        } else if (strcmp(o, "--keys") == 0) {
            a->keys = argv[++i];
        } else if (strcmp(o, "--export-dir") == 0) {
            a->export_dir = argv[++i];
        } else if (o[0] == '-') {
            fprintf(stderr, "signorini tui: unknown option '%s' (see 'signorini tui --help')\n", o);
            return 1;
        } else if (a->scene) {
            fprintf(stderr, "signorini tui: unexpected argument '%s': one scene only\n", o);
            return 1;
        } else {
            a->scene = o;
        }
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
    int law = -1;
    if (a.friction && (law = cx_friction_from_name(a.friction)) < 0) {
        fprintf(stderr, "signorini tui: --friction '%s': expected none, tresca or coulomb\n", a.friction);
        return 1;
    }
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
    double last_draw = 0;
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
            key = tui_term_key(stepping ? 1 : tui_state_running(st) && !busy ? 0 : busy ? 50 : 200);
        }
        if (key != TUI_KEY_NONE) {
            int react = tui_key(st, key);
            if (react & TUI_QUIT)
                break;
            tui_state_apply(st, react);
            dirty = 1;
        }
        if (tui_state_running(st) && !tui_state_busy(st)) {
            tui_state_step(st);
            dirty = 1;
        }
    }
    tui_term_close();
    if (tui_state_busy(st)) {
        /* a build cannot be interrupted: leave it to the exit */
        fflush(stdout);
        _exit(0);
    }
    /* the steps' own times (the method's step and the bookkeeping) */
    for (int r = 0; r < tui_state_nruns(st); r++)
        for (int k = 0; k < tui_state_nsteps(st, r) && nstep < LOOP_SAMPLES; k++)
            step_t[nstep++] = tui_state_step_time(st, r, k);
    if (a.stats)
        fprintf(stderr, "explorer: %d redraws, median %.3f ms; %d steps, median %.3f ms\n", ndraw,
               1e3 * median(draw_t, ndraw), nstep, 1e3 * median(step_t, nstep));
    tui_state_destroy(&st);
    return 0;
}
