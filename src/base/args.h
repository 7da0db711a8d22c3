/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Command-line arguments: the exit statuses of the programs and the option
 * tables. A command declares its options once, as a table of cx_opt rows
 * (name, value type, range, help, where the value goes); cx_opt_parse reads
 * argv from the tables and cx_opt_help writes the help from the same rows,
 * so the help and the parser cannot disagree. The ranges are cx_param's
 * (base/param.h): one range check, one way of writing a range.
 *
 * Nothing here prints except cx_opt_help, to the FILE the program passes:
 * errors go into a cx_diag (one line), and the program reports them with
 * the exit status CX_EXIT_USAGE. */
#ifndef CX_ARGS_H
#define CX_ARGS_H

#include "base/diag.h"
#include "base/param.h"
#include "base/status.h"

#include <stddef.h>
#include <stdio.h>

/* The process exit statuses (doc/design.md §6). */
enum {
    CX_EXIT_OK = 0,             /* success (converged) */
    CX_EXIT_ERROR = 1,          /* an error of the run: one line on stderr */
    CX_EXIT_USAGE = 2,          /* a malformed command line */
    CX_EXIT_NOT_CONVERGED = 3,  /* a result: the solve did not converge */
    CX_EXIT_INTERRUPTED = 130   /* Ctrl-C */
};

typedef enum cx_opt_type {
    CX_OPT_FLAG,    /* no value; target int, set to 1 */
    CX_OPT_INT,     /* target int, an integer in [min, max] */
    CX_OPT_REAL,    /* target double, a finite number in the range */
    CX_OPT_STRING,  /* target const char * (points into argv) */
    CX_OPT_CHOICE,  /* target int: the index of the word in choices "a|b|c" */
    CX_OPT_LIST     /* repeatable text; target cx_opt_list, one entry per use */
} cx_opt_type;

/* Range ends of INT/REAL rows: closed unless one of these says. */
#define CX_OPT_MIN_OPEN CX_PARAM_MIN_OPEN
#define CX_OPT_MAX_OPEN CX_PARAM_MAX_OPEN

#define CX_OPT_LIST_MAX 32
typedef struct cx_opt_list {
    const char *v[CX_OPT_LIST_MAX];   /* point into argv */
    int n;
} cx_opt_list;

/* One option. Tables end with a row whose name is NULL. */
typedef struct cx_opt {
    const char *name;      /* long name without the dashes: "max-iter" */
    char short_name;       /* 0, or the letter of "-x" */
    cx_opt_type type;
    double min, max;       /* INT/REAL: the range */
    unsigned flags;        /* CX_OPT_MIN_OPEN, CX_OPT_MAX_OPEN */
    const char *choices;   /* CHOICE: "a|b|c" */
    const char *arg;       /* the value's name in the help ("T", "FILE") */
    const char *help;      /* lines separated by '\n' */
    size_t offset;         /* offsetof the target in the struct the group names */
    /* STRING/LIST: a check of the text beyond its type (may be NULL):
     * CX_OK, or an error naming the option in d. */
    int (*check)(const char *text, cx_diag *d);
} cx_opt;

/* The tables one command reads and the structs their values go to; an
 * array of groups ends with a group whose opts is NULL. */
typedef struct cx_opt_group {
    const cx_opt *opts;
    void *args;
} cx_opt_group;

/* What cx_opt_parse returns when -h or --help is anywhere on the line. */
#define CX_OPT_HELP 1

/* Read argv[1..argc-1]: "--name value", "--name=value", "-x value", flags,
 * and up to maxpos positional arguments into pos (their count in *npos;
 * after "--" every argument is positional). CX_OK; CX_OPT_HELP if help
 * was asked (nothing else is checked); CX_EINVAL with one line in d for
 * an unknown option, a missing, malformed or out-of-range value or a
 * positional argument too many. Values not given keep what the caller put
 * in the structs. */
int cx_opt_parse(const cx_opt_group *groups, int argc, char **argv, const char **pos, int maxpos,
                 int *npos, cx_diag *d);

/* The row called name in table, or NULL. */
const cx_opt *cx_opt_find(const cx_opt *table, const char *name);

/* Parse text as the value of the INT/REAL/CHOICE row o (its range
 * checked): CX_OK and *x, or CX_EINVAL with "--name 'text': expected ..."
 * in d. The check the command line and the explorer's value entry share. */
int cx_opt_value(const cx_opt *o, const char *text, double *x, cx_diag *d);

/* 1 if x is inside the range of the INT/REAL row o. */
int cx_opt_in_range(const cx_opt *o, double x);

/* The allowed values of o as text: "a number in (0, 1)", "an integer in
 * [1, 100000000]", "none, tresca or coulomb"; "" for the others. */
void cx_opt_range(const cx_opt *o, char *buf, size_t len);

/* Write one line per row of table ("  --name ARG   help; range"). */
void cx_opt_help(const cx_opt *table, FILE *out);

/* The one line of a failed command: "signorini CMD: MSG" on out (the
 * program's stderr), MSG escaped; a usage error (CX_EXIT_USAGE) adds a
 * pointer to the command's help. Returns status. */
int cx_arg_report(FILE *out, const char *cmd, const char *msg, int status);

#endif
