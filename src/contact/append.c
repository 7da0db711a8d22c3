/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Several contacts in one set: a scene's [contact NAME] sections are
 * built one by one (each an obstacle or a two-body pair) and appended,
 * points and rows, in the order of the sections; each keeps its own
 * friction values, per point. */
#include "contact/contact_impl.h"

#include <string.h>

static int append_grow(void **p, size_t old, size_t add)
{
    void *q = cx_realloc(*p, old + add > 0 ? old + add : 1);
    if (!q)
        return CX_ENOMEM;
    *p = q;
    return CX_OK;
}

static int append_rows(cx_triplet *dst, const cx_triplet *src, int row0)
{
    for (size_t q = 0; q < src->nnz; q++)
        CX_TRY(cx_triplet_add(dst, src->i[q] + row0, src->j[q], src->x[q]));
    return CX_OK;
}

int cx_contact_append(cx_contact_set *dst, cx_contact_set *src)
{
    if (dst->m == 0 && !dst->node) {   /* the first: move */
        *dst = *src;
        memset(src, 0, sizeof *src);
        return CX_OK;
    }
    if (dst->dim != src->dim || dst->nall != src->nall || dst->Fpt || dst->spt)
        return CX_EINVAL;
    int dim = dst->dim, dt = dim - 1, m0 = dst->m, m1 = src->m;
    size_t mi = sizeof(int), md = sizeof(double);
    cx_triplet N = {0}, T = {0};
    int st;
    if ((st = cx_triplet_init(&N, m0 + m1, dst->nall, dst->N.nnz + src->N.nnz)) ||
        (st = cx_triplet_init(&T, dt * (m0 + m1), dst->nall, dst->T.nnz + src->T.nnz)) ||
        (st = append_rows(&N, &dst->N, 0)) || (st = append_rows(&N, &src->N, m0)) ||
        (st = append_rows(&T, &dst->T, 0)) || (st = append_rows(&T, &src->T, dt * m0)) ||
        (st = append_grow((void **)&dst->node, mi * m0, mi * m1)) ||
        (st = append_grow((void **)&dst->x, md * dim * m0, md * dim * m1)) ||
        (st = append_grow((void **)&dst->weight, md * m0, md * m1)) ||
        (st = append_grow((void **)&dst->normal, md * dim * m0, md * dim * m1)) ||
        (st = append_grow((void **)&dst->tangent, md * dim * dt * m0, md * dim * dt * m1)) ||
        (st = append_grow((void **)&dst->gap, md * m0, md * m1))) {
        cx_triplet_clear(&N);
        cx_triplet_clear(&T);
        return st;
    }
    memcpy(dst->node + m0, src->node, mi * m1);
    memcpy(dst->x + dim * m0, src->x, md * dim * m1);
    memcpy(dst->weight + m0, src->weight, md * m1);
    memcpy(dst->normal + dim * m0, src->normal, md * dim * m1);
    memcpy(dst->tangent + dim * dt * m0, src->tangent, md * dim * dt * m1);
    memcpy(dst->gap + m0, src->gap, md * m1);
    cx_triplet_clear(&dst->N);
    cx_triplet_clear(&dst->T);
    dst->N = N;
    dst->T = T;
    dst->m = m0 + m1;
    dst->nclamped += src->nclamped;
    cx_contact_clear(src);
    return CX_OK;
}

int cx_contact_set_friction(cx_contact_set *cs, int start, int end, double F, double slip_bound)
{
    if (!cs->Fpt)
        cs->Fpt = CX_NEW(double, cs->m > 0 ? cs->m : 1);
    if (!cs->spt)
        cs->spt = CX_NEW(double, cs->m > 0 ? cs->m : 1);
    if (!cs->Fpt || !cs->spt)
        return CX_ENOMEM;
    for (int i = start; i < end && i < cs->m; i++) {
        cs->Fpt[i] = F;
        cs->spt[i] = slip_bound * cs->weight[i];
    }
    return CX_OK;
}
