/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini: elastic contact problems with and without friction. The
 * program above its three parts, which never call one another: the
 * command line (cli/), the benchmarks (bench/) and the explorer (tui/). */
#include "bench/bench.h"
#include "cli/cli.h"
#include "tui/tui_main.h"
#include "cx_config.h"
#if CX_HAVE_PETSC
#include "petsc/petsc.h"
#endif

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char usage[] =
    "usage: signorini [<command> [options]]\n"
    "\n"
    "With no command, in a terminal: the explorer on the scene 'hertz'.\n"
    "\n"
    "commands:\n"
    "  tui [SCENE] [options]    the explorer (an ncurses UI; tui --help)\n"
    "  list [--json]            scenes and methods, with what each supports and its parameters\n"
    "  solve SCENE [options]    solve a scene (or --problem DIR|FILE) and print a summary (or --json)\n"
    "  bench KIND [options]     benchmarks and the papers' tables (bench --help)\n"
    "  render SCENE --png FILE  solve and draw a field, a plot or a VTU file (render --help)\n"
    "  export SCENE OUT         the discrete problem for other solvers (export --help)\n"
    "  version                  print the version\n"
    "\n"
    "  -h, --help               this help\n"
    "  -V, --version            print the version\n"
    "\n"
    "'signorini <command> --help' describes a command's options. Exit status:\n"
    "0 success, 1 an error of the run, 2 a malformed command line (unknown\n"
    "option, missing or bad value, a value out of range), 3 a solve that did\n"
    "not converge, 130 interrupted.\n";

static const char version_usage[] = "usage: signorini version\n\nPrints the version.\n";

/* 'signorini version' has no options but -h. */
static int main_version(int argc, char **argv)
{
    static const cx_opt none[] = {{NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}};
    cx_opt_group groups[] = {{none, NULL}, {NULL, NULL}};
    cx_diag d;
    int parsed = argc > 1 ? cx_opt_parse(groups, argc, argv, NULL, 0, NULL, &d) : CX_OK;
    if (parsed == CX_OPT_HELP) {
        const cx_opt *const tables[] = {NULL};
        cli_help(version_usage, tables, stdout);
        return CX_EXIT_OK;
    }
    if (parsed)
        return cli_usage("version", d.msg);
    printf("signorini %s\n", CX_VERSION);
    return CX_EXIT_OK;
}

static int main_command(int argc, char **argv);

/* MPI and PETSc start when a command first asks for the PETSc backend
 * (solve --backend petsc), not here: a run of the direct path, the tests
 * and the sanitizer builds then never start MPI (OpenMPI's start costs
 * 0.1-0.3 s and keeps allocations a leak checker reports). They end here,
 * once, after the command, whichever command started them. */
int main(int argc, char **argv)
{
    /* Debian's CHOLMOD opens 4 OpenMP threads beside OpenBLAS's: serial
     * loops unless the user set OMP_THREAD_LIMIT (measured in the README's
     * performance section) */
    if (!getenv("OMP_THREAD_LIMIT"))
        cx_linalg_cholmod_serial(1);
    int code = main_command(argc, argv);
#if CX_HAVE_PETSC
    cx_petsc_finalize();
#endif
    return code;
}

static int main_command(int argc, char **argv)
{
    /* no argument: the explorer, when there is a terminal to draw on */
    if (argc < 2 && isatty(STDIN_FILENO) && isatty(STDOUT_FILENO))
        return tui_main(argc, argv);
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
        strcmp(argv[1], "help") == 0) {
        fputs(usage, stdout);
        return CX_EXIT_OK;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "list") == 0)
        return cli_list(argc - 1, argv + 1);
    if (strcmp(cmd, "solve") == 0)
        return cli_solve(argc - 1, argv + 1);
    if (strcmp(cmd, "tui") == 0)
        return tui_main(argc - 1, argv + 1);
    if (strcmp(cmd, "render") == 0)
        return cli_render(argc - 1, argv + 1);
    if (strcmp(cmd, "export") == 0)
        return cli_export(argc - 1, argv + 1);
    if (strcmp(cmd, "bench") == 0)
        return bench_main(argc - 1, argv + 1);
    if (strcmp(cmd, "version") == 0)
        return main_version(argc - 1, argv + 1);
    if (strcmp(cmd, "help-man") == 0)   /* hidden: the man pages, made at build time */
        return cli_man(argc - 1, argv + 1, main_command);
    if (strcmp(cmd, "help-completion") == 0)   /* hidden: shell completions, made at build time */
        return cli_completion(argc - 1, argv + 1, main_command);
    if (strcmp(cmd, "--version") == 0 || strcmp(cmd, "-V") == 0)
        return main_version(1, argv + 1);
    char safe[256];
    fprintf(stderr, "signorini: unknown %s '%s' (see 'signorini --help')\n", cmd[0] == '-' ? "option" : "command",
            cx_escape(safe, sizeof safe, cmd, strlen(cmd)));
    return CX_EXIT_USAGE;
}
