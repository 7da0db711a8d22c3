/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The options of a solve (see opt_solve.h). */
#include "base/opt_solve.h"

#include <string.h>

/* --set KEY=VALUE: the shape here, the key and the value against the
 * method's parameter table once the method is known. */
static int solve_check_set(const char *text, cx_diag *d)
{
    const char *eq = strchr(text, '=');
    if (!eq || eq == text)
        return cx_diag_set(d, CX_EINVAL, "--set '%s': expected key=value", text);
    return CX_OK;
}

const cx_opt cx_solve_opts[] = {
    {"method", 0, CX_OPT_LIST, 0, 0, 0, NULL, "ID|auto",
     "solver (default auto: the fastest measured for the scene\n"
     "and law, or a rule from the problem; see the README);\n"
     "repeatable with --plot convergence|work (one series each)", offsetof(cx_solve_args, methods), NULL},
    CX_OPT_ROW_FRICTION(cx_solve_args, friction),
    CX_OPT_ROW_F(cx_solve_args, F),
    CX_OPT_ROW_SLIP(cx_solve_args, slip),
    CX_OPT_ROW_LEVEL(cx_solve_args, level),
    CX_OPT_ROW_TOL(cx_solve_args, tol, "stop when the kkt error is below T (default 1e-10)"),
    CX_OPT_ROW_MAX_ITER(cx_solve_args, max_iter, "iteration limit (default 500)"),
    {"stop", 0, CX_OPT_CHOICE, 0, 0, 0, "kkt|own", "kkt|own",
     "stop on the kkt error only, or also on the method's\n"
     "own criterion (default own; a run it stops above the\n"
     "tolerance has not converged)", offsetof(cx_solve_args, own_stop), NULL},
    CX_OPT_ROW_TIME_LIMIT(cx_solve_args, time_limit,
                          "stop the run after S seconds (checked inside long steps)"),
    {"set", 0, CX_OPT_LIST, 0, 0, 0, NULL, "KEY=VALUE",
     "a method parameter (repeatable; see 'signorini list')", offsetof(cx_solve_args, sets),
     solve_check_set},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

void cx_solve_args_default(cx_solve_args *a, double tol, int max_iter, int own_stop, double time_limit)
{
    memset(a, 0, sizeof *a);
    a->friction = -1;
    a->F = NAN;
    a->slip = NAN;
    a->tol = tol;
    a->max_iter = max_iter;
    a->own_stop = own_stop;
    a->time_limit = time_limit;
}
