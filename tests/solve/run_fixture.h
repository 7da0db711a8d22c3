/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Shared by the solve tests: run a method with "key=value ..."
 * parameters and options, and the energy-norm distance of two solutions. */
#ifndef CX_TEST_RUN_FIXTURE_H
#define CX_TEST_RUN_FIXTURE_H

#include "solve_fixture.h"
#include "check.h"

#include <string.h>

/* Run method id on s with "key=value ..." parameters and options o.
 * Returns the status of set_method (the iterate is cx_session_iterate(s)). */
static inline int fixture_run_opts(cx_session *s, const char *id, const char *sets,
                                   const cx_options *o, cx_diag *d)
{
    const cx_method *m = cx_method_find(id);
    if (!m)
        return cx_diag_set(d, CX_EINVAL, "no method %s", id);
    cx_param_values pv;
    cx_param_default(&pv, m->params);
    char buf[256];
    snprintf(buf, sizeof buf, "%s", sets);
    for (char *tok = strtok(buf, " "); tok; tok = strtok(NULL, " "))
        CX_TRY(cx_param_set_pair(&pv, tok, id, d));
    CX_TRY(cx_session_set_method(s, m, &pv, o, d));
    return cx_solver_solve(s, NULL, NULL, d);
}

/* The same with the default options but tol, max_iter, own (also stop on
 * the method's own criterion) and no stall rule. */
static inline int fixture_run(cx_session *s, const char *id, const char *sets, int own, double tol,
                              int max_iter, cx_diag *d)
{
    cx_options o;
    cx_options_default(&o);
    o.tol = tol;
    o.own_stop = own;
    o.max_iter = max_iter;
    o.stall_window = 0;
    return fixture_run_opts(s, id, sets, &o, d);
}

/* ||u - v||_K / ||v||_K */
static inline double fixture_energy_diff(const cx_problem *p, const double *u, const double *v)
{
    int n = p->n;
    double *e = malloc(sizeof(double) * (size_t)n), *Ke = malloc(sizeof(double) * (size_t)n);
    double *Kv = malloc(sizeof(double) * (size_t)n);
    for (int k = 0; k < n; k++)
        e[k] = u[k] - v[k];
    cx_csc_gemv(&p->K, 1.0, e, 0.0, Ke);
    cx_csc_gemv(&p->K, 1.0, v, 0.0, Kv);
    double num = sqrt(fabs(cx_vec_dot(n, e, Ke))), den = sqrt(fabs(cx_vec_dot(n, v, Kv)));
    free(e);
    free(Ke);
    free(Kv);
    return den > 0 ? num / den : num;
}

/* A copy of the current u (malloc). */
static inline double *fixture_copy_u(const cx_session *s)
{
    const cx_problem *p = cx_session_problem(s);
    double *u = malloc(sizeof(double) * (size_t)p->n);
    memcpy(u, cx_session_iterate(s)->u, sizeof(double) * (size_t)p->n);
    return u;
}

#endif
