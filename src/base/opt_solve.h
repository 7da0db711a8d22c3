/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The options of a solve, in one table: 'signorini solve' and 'render'
 * parse them from it, the benchmarks take their rows for the options they
 * share (the CX_OPT_ROW_* macros), and the explorer's value entry checks
 * what is typed against the same rows (cx_opt_find(cx_solve_opts, "tol")).
 * One range per option everywhere: tol in (0, 1), max-iter in [1, 1e8].
 *
 * It lives in base/ because every program layer reads it and it needs
 * nothing above base/: the values are plain numbers and words, turned into
 * a cx_options, a law and a method by the program. */
#ifndef CX_OPT_SOLVE_H
#define CX_OPT_SOLVE_H

#include "base/args.h"

#include <math.h>
#include <stddef.h>

/* The rows more than one table has (type is the struct, field its member). */
#define CX_OPT_ROW_FRICTION(type, field) \
    {"friction", 0, CX_OPT_CHOICE, 0, 0, 0, "none|tresca|coulomb", "LAW", \
     "none | tresca | coulomb (default: the scene's)", offsetof(type, field), NULL}
#define CX_OPT_ROW_F(type, field) \
    {"F", 0, CX_OPT_REAL, 0, INFINITY, CX_OPT_MAX_OPEN, NULL, "VALUE", \
     "Coulomb coefficient (default: the scene's)", offsetof(type, field), NULL}
#define CX_OPT_ROW_SLIP(type, field) \
    {"slip", 0, CX_OPT_REAL, 0, INFINITY, CX_OPT_MAX_OPEN, NULL, "VALUE", \
     "Tresca slip bound, a traction (default: the scene's)", offsetof(type, field), NULL}
#define CX_OPT_LEVEL_MAX (1 << 20)   /* a scene's own level_max is checked when it is built */
#define CX_OPT_ROW_LEVEL_HELP(type, field, help) \
    {"level", 0, CX_OPT_INT, 1, CX_OPT_LEVEL_MAX, 0, NULL, "L", help, offsetof(type, field), NULL}
#define CX_OPT_ROW_LEVEL(type, field) CX_OPT_ROW_LEVEL_HELP(type, field, "mesh level (default: the scene's)")
#define CX_OPT_ROW_TOL(type, field, help) \
    {"tol", 0, CX_OPT_REAL, 0, 1, CX_OPT_MIN_OPEN | CX_OPT_MAX_OPEN, NULL, "T", help, \
     offsetof(type, field), NULL}
#define CX_OPT_ROW_MAX_ITER(type, field, help) \
    {"max-iter", 0, CX_OPT_INT, 1, 1e8, 0, NULL, "N", help, offsetof(type, field), NULL}
#define CX_OPT_ROW_TIME_LIMIT(type, field, help) \
    {"time-limit", 0, CX_OPT_REAL, 0, INFINITY, CX_OPT_MIN_OPEN | CX_OPT_MAX_OPEN, NULL, "S", help, \
     offsetof(type, field), NULL}

/* The values of cx_solve_opts. F and slip are NaN when not given (the
 * scene's), friction -1, level 0, method NULL (auto). */
typedef struct cx_solve_args {
    const char *method;    /* the first of methods (set by the program after parsing) */
    cx_opt_list methods;   /* --method, each use (several: a comparison plot) */
    int friction;
    double F, slip;
    int level;
    double tol;
    int max_iter;
    int own_stop;          /* --stop: 0 kkt, 1 own */
    double time_limit;     /* 0: none */
    cx_opt_list sets;      /* --set KEY=VALUE */
} cx_solve_args;

/* The defaults above with tol, max_iter, own_stop and time_limit as given
 * (the library's cx_options_default, which base/ cannot read). */
void cx_solve_args_default(cx_solve_args *a, double tol, int max_iter, int own_stop, double time_limit);

extern const cx_opt cx_solve_opts[];

#endif
