/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The command line: subcommands and their shared option handling. Each
 * subcommand declares its options as cx_opt tables (base/args.h) and
 * returns the process exit status: 0 success, 1 an error of the run (one
 * line on stderr), 2 a malformed command line (one line), 3 a solve that
 * did not converge (a result, not an error). */
#ifndef CLI_H
#define CLI_H

#include "base/args.h"
#include "base/opt_solve.h"
#include "out/out.h"

int cli_list(int argc, char **argv);
int cli_solve(int argc, char **argv);

int cli_render(int argc, char **argv);  /* cli/render.c */
int cli_export(int argc, char **argv);  /* cli/export.c */
/* solve --problem PATH (cli/solve_problem.c): the exported problem at
 * path with a's method, friction and --set, opt's stopping rules. */
int cli_solve_problem(const char *cmd, const char *path, const cx_solve_args *a, const cx_options *opt, int json,
                      int quiet);
/* The summary of a result (solve's text output). */
void cli_solve_write_text(const cx_result *r, FILE *out);

/* What 'solve SCENE' and 'solve --problem' share (cli/solve.c). */
/* The method's parameters: its defaults, then auto_sets ("key=value ...",
 * --method auto's choice), then a's --set. */
int cli_method_params(const cx_method *m, const char *auto_sets, const cx_solve_args *a, cx_param_values *pv,
                      cx_diag *d);
/* A run's observer: a line per iterate on out unless quiet, every
 * iterate in history (--json; NULL: none), with series every iterate as
 * series/iter_NNNN.vtu (completed on s, sc at level; the first error in
 * d stops the run). */
typedef struct cli_watch {
    int quiet;
    FILE *out;
    cx_history *history;
    const char *series;
    cx_session *s;
    const cx_scene *sc;
    int level, nseries;
    cx_diag *d;
} cli_watch;
/* Run session s (its friction and method set) observed by w: unless
 * w->quiet, first the header "TITLE: 2D, N dofs, M contact points; METHOD
 * [(auto)], friction LAW" and the column heads. Ctrl-C cancels the run:
 * it ends at the next check, as cancelled. The solver's status. */
int cli_solve_run(cx_session *s, const char *title, int is_auto, cli_watch *w, cx_diag *d);
/* The exit status of a run that ended for reason: 0 converged, 130
 * cancelled, else 3. */
int cli_exit_status(int reason);
/* solve --backend petsc (cli/solve_petsc.c): the problem built on every
 * rank solved by the PETSc backend; rank 0 prints and writes. */
typedef struct cli_petsc_args {
    const char *method;   /* NULL or "auto": ssn-tresca */
    int level, json, quiet, baseline;
    const char *vtu;      /* --vtu FILE (NULL: none) */
    double t_assemble;
} cli_petsc_args;
int cli_solve_petsc(const char *cmd, const cx_scene *sc, const cx_problem *p, const cx_friction_state *fr,
                    const cx_options *opt, const cli_petsc_args *a, FILE *summary);
/* 'solve' under another command name and usage (render: the same options,
 * and --png required). */
int cli_solve_as(const char *cmd, const char *usage, int argc, char **argv);

/* The rendering options shared by solve and render (cli/render.c). */
typedef struct cli_render_args {
    const char *png, *vtu, *field_name, *size;
    int plot;            /* -1 none, 0 pressure, 1 convergence, 2 work */
    double scale;        /* 0: auto */
    double font_scale;   /* text size factor (1) */
    int cmap, no_title;  /* --cmap index (0 auto, then cx_cmap + 1), --no-title */
    const char *range, *title;   /* --range MIN:MAX, --title TEXT */
    int w, h, view, edges, vtu_ascii, timing;
    /* 3D camera and framing: --camera AZ,EL, --crop contact, --mirror */
    const char *camera;
    int crop, mirror;
    /* the solve's --method and --set (borrowed): a convergence or work
     * plot runs each method named */
    const cx_opt_list *methods, *sets;
    /* vector files, the animation, the log colour scale (issue 22) */
    const char *svg, *pdf, *frames, *gif;
    int log, every;      /* --log; --every K: the animation draws every K-th iterate */
} cli_render_args;
/* --set KEY=VALUE into pv; with several --method (nmethods > 1) a key pv's
 * method has not is skipped (it is another method's). */
int cli_param_set_for(cx_param_values *pv, const char *pair, int nmethods, const char *owner, cx_diag *d);
/* With several --method: each --set key is some named method's. */
int cli_sets_check(const cx_opt_list *methods, const cx_opt_list *sets, cx_diag *d);
void cli_render_args_init(cli_render_args *r);
/* Their table (values into a cli_render_args). */
extern const cx_opt cli_render_opts[];
/* After parsing: the image size from --size. */
void cli_render_finish(cli_render_args *r);
/* Check the options against the problem's dimension before solving. */
int cli_render_check(const cli_render_args *r, int dim, cx_diag *d);
/* Write what was asked (VTU, PNG image or plot) for the solution res of
 * session s (the convergence plots run the scene's other methods on s). */
int cli_render_outputs(const cli_render_args *r, const cx_scene *sc, cx_session *s, cx_result *res,
                       int quiet, cx_diag *d);
/* Non-zero if a drawing was asked for (--png, --svg, --pdf, --gif, --frames). */
int cli_render_wanted(const cli_render_args *r);
/* How many of --png, --vtu, --svg, --pdf and --gif are '-' (standard output). */
int cli_render_stdout_users(const cli_render_args *r);

/* Print "signorini CMD: message" on stderr and return CX_EXIT_ERROR. */
int cli_fail(const char *cmd, const char *msg);
/* A malformed command line: print "signorini CMD: message (see 'signorini
 * CMD --help')" on stderr and return CX_EXIT_USAGE. */
int cli_usage(const char *cmd, const char *msg);
/* The help of a command: usage (its first lines), then each table. */
void cli_help(const char *usage, const cx_opt *const *tables, FILE *out);
/* signorini help-man [COMMAND] (hidden): the man page of the program or of
 * COMMAND in roff, from the --help that run(argc, argv) prints (cli/man.c). */
int cli_man(int argc, char **argv, int (*run)(int, char **));
/* What run(n, args) prints on stdout, NUL-terminated (free), or NULL. */
char *cli_capture(int (*run)(int, char **), int n, char **args);
/* signorini help-completion bash|zsh|scenes (hidden): the shell completion
 * scripts from the commands' --help, and the scene ids they ask for at
 * completion time (cli/complete.c). */
int cli_completion(int argc, char **argv, int (*run)(int, char **));


#endif
