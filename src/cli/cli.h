/* The command line: subcommands and their shared option handling. Each
 * subcommand returns the process exit status: 0 success, 1 an error (one
 * line on stderr), 3 a solve that did not converge (a result, not an
 * error). */
#ifndef CLI_H
#define CLI_H

#include "scene/scene.h"

enum { CLI_EXIT_OK = 0, CLI_EXIT_ERROR = 1, CLI_EXIT_NOT_CONVERGED = 3 };

int cli_list(int argc, char **argv);
int cli_solve(int argc, char **argv);
int cli_bench(int argc, char **argv);   /* cli/bench.c */
int cli_bench_paper_003(int argc, char **argv);   /* cli/paper_003.c */

/* Print "signorini CMD: message" on stderr and return CLI_EXIT_ERROR. */
int cli_fail(const char *cmd, const char *msg);

/* If argv[*i] is option name ("--name value" or "--name=value"), set
 * *value, advance *i past it and return 1; a missing value is an error
 * (-1, message in d). Otherwise 0. */
int cli_option(int argc, char **argv, int *i, const char *name, const char **value, cx_diag *d);

/* Load a scene by id or path. */
int cli_load_scene(const char *id, cx_scene *s, cx_diag *d);

#endif
