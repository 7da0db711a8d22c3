/* Nested sessions (solve.h): a child session over a view of its parent's
 * problem, sharing the parent's operator cache and counters, so that a
 * wrapper method (cf-fp) runs any registered inner method through the
 * ordinary stepping with all its bookkeeping. Also per-point slip bounds
 * and warm starts, which the wrapper needs and which work on any session. */
#include "solve/session_impl.h"

#include <math.h>
#include <string.h>

void cx_session_view_free_(cx_problem *p)
{
    if (!p)
        return;
    cx_free(p->s);
    cx_free(p->Fi);
    cx_free(p);
}

int cx_session_nested_create(cx_session **child, cx_session *parent, cx_diag *d)
{
    const cx_problem *pp = parent->p;
    cx_problem *view = CX_NEW(cx_problem, 1);
    if (!view)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    *view = *pp;   /* shares K, f, N, T, g, mesh, contact: the parent owns them */
    view->s = CX_NEW(double, pp->m);
    view->Fi = CX_NEW(double, pp->m);
    if (!view->s || !view->Fi) {
        cx_session_view_free_(view);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    view->friction = CX_FRICTION_TRESCA;
    view->slip_bound = 0;
    view->F = 0;
    cx_session *s = NULL;
    int st = cx_session_create_(&s, &view, parent, d);
    if (st != CX_OK) {
        cx_session_view_free_(view);   /* NULL once the session took it: destroy freed it */
        return st;
    }
    *child = s;
    return CX_OK;
}

int cx_session_set_slip_bounds(cx_session *s, const double *sb, cx_diag *d)
{
    cx_problem *p = s->p;
    for (int i = 0; i < p->m; i++)
        if (!(sb[i] >= 0) || !isfinite(sb[i]))
            return cx_diag_set(d, CX_EINVAL, "slip bound of contact point %d: expected a finite "
                               "value >= 0, got %g", i, sb[i]);
    memcpy(p->s, sb, sizeof(double) * (size_t)p->m);
    p->friction = CX_FRICTION_TRESCA;
    if (!s->method)
        return CX_OK;
    cx_param_values params = s->params;
    return cx_session_set_method(s, s->method, &params, NULL, d);
}

int cx_session_set_start(cx_session *s, const double *u, const double *lN, const double *lT,
                         cx_diag *d)
{
    const cx_problem *p = s->p;
    if (!u) {
        cx_free(s->start);
        s->start = NULL;
        return CX_OK;
    }
    if (!s->start && !(s->start = CX_NEW(double, p->n + p->m + p->nt)))
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    memcpy(s->start, u, sizeof(double) * (size_t)p->n);
    if (lN)
        memcpy(s->start + p->n, lN, sizeof(double) * (size_t)p->m);
    else
        memset(s->start + p->n, 0, sizeof(double) * (size_t)p->m);
    if (lT)
        memcpy(s->start + p->n + p->m, lT, sizeof(double) * (size_t)p->nt);
    else
        memset(s->start + p->n + p->m, 0, sizeof(double) * (size_t)p->nt);
    return CX_OK;
}
