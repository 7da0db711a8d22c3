/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The contact set itself: allocation, lumped weights, clearing, and the
 * removal of clamped points (those whose normal displacement is
 * prescribed: the support holds them, there is nothing to solve for). */
#include "contact/contact_impl.h"
#include "fem/fem.h"

#include <string.h>

void cx_contact_clear(cx_contact_set *cs)
{
    cx_free(cs->node);
    cx_free(cs->x);
    cx_free(cs->weight);
    cx_free(cs->normal);
    cx_free(cs->tangent);
    cx_free(cs->gap);
    cx_triplet_clear(&cs->N);
    cx_triplet_clear(&cs->T);
    cx_free(cs->Fpt);
    cx_free(cs->spt);
    memset(cs, 0, sizeof *cs);
}

int contact_alloc(cx_contact_set *cs, int dim, int m, int nall, size_t capN, size_t capT)
{
    cs->dim = dim;
    cs->m = m;
    cs->nall = nall;
    cs->node = CX_NEW(int, m);
    cs->x = CX_NEW(double, dim * m);
    cs->weight = CX_NEW(double, m);
    cs->normal = CX_NEW(double, dim * m);
    cs->tangent = CX_NEW(double, dim * (dim - 1) * m);
    cs->gap = CX_NEW(double, m);
    if (!cs->node || !cs->x || !cs->weight || !cs->normal || !cs->tangent || !cs->gap)
        return CX_ENOMEM;
    CX_TRY(cx_triplet_init(&cs->N, m, nall, capN));
    return cx_triplet_init(&cs->T, (dim - 1) * m, nall, capT);
}

void contact_weights(double *weight, const cx_mesh *m, const cx_boundary *b, const int *pos)
{
    int dim = m->dim;
    for (int f = 0; f < b->nfacets; f++) {
        double xf[27], w[9];
        const int *fn = b->facets + b->npf * f;
        for (int a = 0; a < b->npf; a++)
            memcpy(xf + dim * a, m->x + dim * fn[a], sizeof(double) * (size_t)dim);
        cx_fem_facet_lumped(dim, b->npf, xf, w);
        for (int a = 0; a < b->npf; a++)
            if (pos[fn[a]] >= 0)
                weight[pos[fn[a]]] += w[a];
    }
}

/* Keep the triplet entries of kept rows, renumbered; rows of a point are
 * per rows apart (N: 1, T: dim - 1). */
static void drop_rows(cx_triplet *R, const int *newpt, int per, int m_new)
{
    size_t o = 0;
    for (size_t q = 0; q < R->nnz; q++) {
        int pt = newpt[R->i[q] / per];
        if (pt < 0)
            continue;
        R->i[o] = per * pt + R->i[q] % per;
        R->j[o] = R->j[q];
        R->x[o] = R->x[q];
        o++;
    }
    R->nnz = o;
    R->nrow = per * m_new;
}

int cx_contact_drop_clamped(cx_contact_set *cs, const cx_dofmap *map)
{
    int m = cs->m, dim = cs->dim, dt = dim - 1, kept = 0;
    int *newpt = CX_NEW(int, m > 0 ? m : 1);
    if (!newpt)
        return CX_ENOMEM;
    for (int i = 0; i < m; i++)
        newpt[i] = -1;
    for (size_t q = 0; q < cs->N.nnz; q++)
        if (map->free_of[cs->N.j[q]] >= 0)
            newpt[cs->N.i[q]] = 0;
    for (int i = 0; i < m; i++) {
        if (newpt[i] < 0)
            continue;
        newpt[i] = kept;
        cs->node[kept] = cs->node[i];
        cs->weight[kept] = cs->weight[i];
        cs->gap[kept] = cs->gap[i];
        if (cs->Fpt)
            cs->Fpt[kept] = cs->Fpt[i];
        if (cs->spt)
            cs->spt[kept] = cs->spt[i];
        memmove(cs->x + dim * kept, cs->x + dim * i, sizeof(double) * (size_t)dim);
        memmove(cs->normal + dim * kept, cs->normal + dim * i, sizeof(double) * (size_t)dim);
        memmove(cs->tangent + dim * dt * kept, cs->tangent + dim * dt * i,
                sizeof(double) * (size_t)(dim * dt));
        kept++;
    }
    drop_rows(&cs->N, newpt, 1, kept);
    drop_rows(&cs->T, newpt, dt, kept);
    cs->nclamped += m - kept;
    cs->m = kept;
    cx_free(newpt);
    return CX_OK;
}
