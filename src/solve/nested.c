/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Nested sessions (solve.h): a child session over its parent's system,
 * with its own friction state, sharing the parent's operator cache and
 * counters, so that a wrapper method (cf-fp) runs any registered inner
 * method through the ordinary stepping with all its bookkeeping. Also warm
 * starts, which the wrapper needs and which work on any session. Depends
 * on session.c (cx_session_create_), never the other way. */
#include "solve/session_impl.h"

#include <string.h>

int cx_session_nested_create(cx_session **child, cx_session *parent, cx_diag *d)
{
    /* the parent's system itself, not a copy: the parent owns it and
     * outlives the child; the child has its own friction state (Tresca,
     * zero bounds until the wrapper sets them) */
    cx_session *s = NULL;
    CX_TRY(cx_session_create_(&s, parent->p, parent, d));
    s->fr.law = CX_FRICTION_TRESCA;
    *child = s;
    return CX_OK;
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
