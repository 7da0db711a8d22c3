/* The command line: subcommands and their shared option handling. Each
 * subcommand returns the process exit status: 0 success, 1 an error (one
 * line on stderr), 3 a solve that did not converge (a result, not an
 * error). */
#ifndef CLI_H
#define CLI_H

#include "base/args.h"
#include "out/result.h"

int cli_list(int argc, char **argv);
int cli_solve(int argc, char **argv);

int cli_render(int argc, char **argv);  /* cli/render.c */
/* 'solve' under another command name (render: the same options and more). */
int cli_solve_as(const char *cmd, int argc, char **argv);

/* The rendering options shared by solve and render (cli/render.c). */
typedef struct cli_render_args {
    const char *png, *vtu, *field_name;
    int plot;            /* 0 none, 1 pressure, 2 convergence, 3 work */
    double scale;        /* 0: auto */
    int w, h, view, edges, vtu_ascii, timing;
} cli_render_args;
void cli_render_args_init(cli_render_args *r);
/* 1 if argv[*i] was a rendering option (consumed), 0 if not, -1 on error. */
int cli_render_option(int argc, char **argv, int *i, cli_render_args *r, cx_diag *d);
/* Check the options against the problem's dimension before solving. */
int cli_render_check(const cli_render_args *r, int dim, cx_diag *d);
/* Write what was asked (VTU, PNG image or plot) for the solution res of
 * session s (the convergence plots run the scene's other methods on s). */
int cli_render_outputs(const cli_render_args *r, const cx_scene *sc, cx_session *s, cx_result *res,
                       int quiet, cx_diag *d);
/* How many of --png and --vtu are '-' (standard output). */
int cli_render_stdout_users(const cli_render_args *r);

/* Print "signorini CMD: message" on stderr and return CX_EXIT_ERROR. */
int cli_fail(const char *cmd, const char *msg);


#endif
