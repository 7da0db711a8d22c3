/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini bench: the benchmarks. Each kind is a row of the table below;
 * the papers' tables are rows of bench_papers[]. A benchmark prints its
 * tables on stdout; timings live here, never in the test suite.
 *
 * Ctrl-C belongs to the bench (the library installs no signal handler):
 * bench_main catches SIGINT for every kind and paper, the runs stop through
 * bench_observer, what finished is printed, and the exit status is
 * CX_EXIT_INTERRUPTED (130). */
#include "bench/bench.h"

#include <stdio.h>
#include <string.h>

static const char bench_main_usage[] =
    "usage: signorini bench <kind> [options]\n"
    "\n"
    "kinds:\n"
    "  wp SCENE [options]     work-precision: time against error for every method\n"
    "  scaling SCENE --levels a..b [options]\n"
    "                         mesh scaling: assembly, baseline and methods per level\n"
    "  stress [SCENE...]      numerical stability under a catalogue of perturbations\n"
    "  paper NNN [options]    reproduce the tables of paper NNN (see below)\n"
    "\n"
    "'signorini bench KIND --help' and 'signorini bench paper NNN --help' give\n"
    "their options.\n"
    "\n"
    "papers:\n";

typedef struct bench_paper {
    const char *id;                      /* "002" */
    const char *what;                    /* one line */
    int (*run)(int argc, char **argv);   /* argv[0] is the paper id */
} bench_paper;

/* One line per paper: the id, what it reproduces, its entry point
 * (bench/paper_NNN.c). */
static const bench_paper bench_papers[] = {
    {"000", "Tables 1-2: MPRGP and SNM1-4 (nK/kmax) on two blocks", bench_paper_000},
    {"001", "Table 1: semismooth* Newton, 3D Tresca on the prism, reduction to the contact face", bench_paper_001},
    {"002", "Koko: Uzawa block relaxation, Tables 1-6 (hertz, halfball), r = auto", bench_paper_002},
    {"003", "masonry walls: Tables 1-7 (sizes; PSOR, LSSNN, PDAS, PDPC, Graves, Schur variants)", bench_paper_003},
    {NULL, NULL, NULL}
};

/* The benchmarks of bench/bench_*.c. */
static const struct {
    const char *id;
    int (*run)(int argc, char **argv);
} bench_kinds[] = {
    {"wp", bench_wp},
    {"scaling", bench_scaling},
    {"stress", bench_stress},
    {NULL, NULL}
};

static void bench_print_usage(FILE *out)
{
    fputs(bench_main_usage, out);
    for (int k = 0; bench_papers[k].id; k++)
        fprintf(out, "  %s  %s\n", bench_papers[k].id, bench_papers[k].what);
    if (!bench_papers[0].id)
        fputs("  (none yet)\n", out);
}

static int bench_paper_run(int argc, char **argv)
{
    if (argc < 2)
        return bench_usage("bench paper", "which paper? (see 'signorini bench --help')");
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        fputs("usage: signorini bench paper NNN [options]\n\nReproduce the tables of paper NNN"
              " ('signorini bench paper NNN --help' for its options):\n", stdout);
        for (int k = 0; bench_papers[k].id; k++)
            printf("  %s  %s\n", bench_papers[k].id, bench_papers[k].what);
        return CX_EXIT_OK;
    }
    for (int k = 0; bench_papers[k].id; k++)
        if (strcmp(bench_papers[k].id, argv[1]) == 0) {
            bench_catch_sigint();
            int code = bench_papers[k].run(argc - 1, argv + 1);
            fflush(stdout);
            if (!bench_interrupted())
                return code;
            fprintf(stderr, "signorini bench paper %s: interrupted: the lines above finished\n",
                    bench_papers[k].id);
            return CX_EXIT_INTERRUPTED;
        }
    char msg[128];
    snprintf(msg, sizeof msg, "unknown paper '%s'", argv[1]);
    return bench_usage("bench paper", msg);
}

int bench_main(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        /* no kind is a malformed line: the usage goes to stderr, status 2 */
        bench_print_usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? CX_EXIT_USAGE : CX_EXIT_OK;
    }
    if (strcmp(argv[1], "paper") == 0)
        return bench_paper_run(argc - 1, argv + 1);
    for (int k = 0; bench_kinds[k].id; k++)
        if (strcmp(bench_kinds[k].id, argv[1]) == 0) {
            bench_catch_sigint();
            return bench_kinds[k].run(argc - 1, argv + 1);
        }
    char msg[128];
    snprintf(msg, sizeof msg, "unknown kind '%s'", argv[1]);
    return bench_usage("bench", msg);
}
