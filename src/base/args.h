/* Command-line arguments: the exit statuses of the programs and the small
 * helpers that read "--name value" / "--name=value". Nothing here prints:
 * errors go into a cx_diag, and the program reports them. */
#ifndef CX_ARGS_H
#define CX_ARGS_H

#include "base/diag.h"
#include "base/status.h"

/* The process exit statuses (DESIGN.md §6). */
enum {
    CX_EXIT_OK = 0,             /* success (converged) */
    CX_EXIT_ERROR = 1,          /* an error of the run: one line on stderr */
    CX_EXIT_USAGE = 2,          /* a malformed command line */
    CX_EXIT_NOT_CONVERGED = 3,  /* a result: the solve did not converge */
    CX_EXIT_INTERRUPTED = 130   /* Ctrl-C */
};

/* If argv[*i] is option name ("--name value" or "--name=value"), set
 * *value, advance *i past it and return 1; a missing value is an error
 * (-1, message in d). Otherwise 0. */
int cx_arg_option(int argc, char **argv, int *i, const char *name, const char **value, cx_diag *d);

/* The value of --level: a positive integer, or a one-line error. */
int cx_arg_level(const char *v, int *level, cx_diag *d);

#endif
