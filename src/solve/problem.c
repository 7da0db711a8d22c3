/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The discrete problem: the assembled system reduced to the free dofs, the
 * contact rows mapped to them; and the check of a friction state. */
#include "solve/problem.h"

#include <math.h>
#include <string.h>

static const char *const friction_names[] = {"none", "tresca", "coulomb"};

const char *cx_friction_name(cx_friction f)
{
    return (unsigned)f < 3 ? friction_names[f] : "?";
}

int cx_friction_from_name(const char *name)
{
    for (int k = 0; k < 3; k++)
        if (strcmp(name, friction_names[k]) == 0)
            return k;
    return -1;
}

void cx_problem_destroy(cx_problem **pp)
{
    if (!pp || !*pp)
        return;
    cx_problem *p = *pp;
    cx_csc_clear(&p->K);
    cx_csc_clear(&p->N);
    cx_csc_clear(&p->T);
    cx_free(p->f);
    cx_free(p->g);
    cx_free(p->cdofs);
    cx_mesh_destroy(&p->mesh);
    cx_free(p->mats);
    cx_dofmap_clear(&p->map);
    cx_contact_clear(&p->contact);
    cx_free(p);
    *pp = NULL;
}

/* Rows of an all-dof triplet mapped to free dofs; the prescribed part of
 * each row times the prescribed value goes to shift (may be NULL, then a
 * non-zero prescribed part is an error the caller reports). */
static int map_rows(const cx_triplet *R, const cx_dofmap *map, cx_csc *out, double *shift)
{
    cx_triplet t;
    CX_TRY(cx_triplet_init(&t, R->nrow, map->nfree, R->nnz));
    for (size_t k = 0; k < R->nnz; k++) {
        int fj = map->free_of[R->j[k]];
        if (fj >= 0) {
            int st = cx_triplet_add(&t, R->i[k], fj, R->x[k]);
            if (st) {
                cx_triplet_clear(&t);
                return st;
            }
        } else if (shift) {
            shift[R->i[k]] += R->x[k] * map->value[R->j[k]];
        }
    }
    int st = cx_csc_from_triplet(out, &t);
    cx_triplet_clear(&t);
    return st;
}

int cx_problem_create(cx_problem **pp, cx_mesh **mesh, cx_material **mats, cx_dofmap *map,
                      cx_contact_set *cs, cx_csc *Kall, const double *fall, cx_diag *d)
{
    int status;
    double *shift = NULL;
    unsigned char *touched = NULL;
    cx_problem *p = CX_NEW(cx_problem, 1);
    if (!p)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    /* take ownership first, so that fail: frees everything */
    p->mesh = *mesh;
    *mesh = NULL;
    p->mats = *mats;
    *mats = NULL;
    p->map = *map;
    memset(map, 0, sizeof *map);
    p->contact = *cs;
    memset(cs, 0, sizeof *cs);

    p->dim = p->mesh->dim;
    p->n = p->map.nfree;
    p->m = p->contact.m;
    p->nt = (p->dim - 1) * p->m;
    p->f = CX_NEW(double, p->n);
    p->g = CX_NEW(double, p->m);
    shift = CX_NEW(double, p->nt > p->m ? p->nt : p->m);
    touched = CX_NEW(unsigned char, p->n);
    if (!p->f || !p->g || !shift || !touched) {
        status = CX_ENOMEM;
        goto fail;
    }
    if ((status = cx_fem_reduce_move(Kall, fall, &p->map, &p->K, p->f)))
        goto fail;

    /* N u_all - g <= 0 with u_all = u on free dofs, prescribed values
     * elsewhere: the prescribed part moves into the gap. */
    if ((status = map_rows(&p->contact.N, &p->map, &p->N, shift)))
        goto fail;
    for (int i = 0; i < p->m; i++)
        p->g[i] = p->contact.gap[i] - shift[i];
    for (int i = 0; i < p->m; i++)
        if (p->g[i] < 0) {
            status = cx_diag_set(d, CX_EINVAL,
                                 "contact point %d (node %d): the prescribed displacement pushes it %g into the obstacle",
                                 i, p->contact.node[i], -p->g[i]);
            goto fail;
        }
    memset(shift, 0, sizeof(double) * (size_t)(p->nt > p->m ? p->nt : p->m));
    if ((status = map_rows(&p->contact.T, &p->map, &p->T, shift)))
        goto fail;
    for (int i = 0; i < p->nt; i++)
        if (shift[i] != 0) {
            status = cx_diag_set(d, CX_EUNSUPPORTED,
                                 "contact point %d: a prescribed non-zero tangential displacement is not supported",
                                 i / (p->dim - 1));
            goto fail;
        }

    /* the contact dofs: columns of N and T */
    for (int j = 0; j < p->n; j++) {
        if (p->N.p[j + 1] > p->N.p[j] || p->T.p[j + 1] > p->T.p[j])
            touched[j] = 1;
        p->nc += touched[j];
    }
    p->cdofs = CX_NEW(int, p->nc);
    if (!p->cdofs) {
        status = CX_ENOMEM;
        goto fail;
    }
    for (int j = 0, k = 0; j < p->n; j++)
        if (touched[j])
            p->cdofs[k++] = j;

    for (int j = 0; j < p->n; j++) {
        int q = cx_csc_find(&p->K, j, j);   /* bisection, not a pass over K */
        if (q >= 0 && p->K.x[q] > p->kscale)
            p->kscale = p->K.x[q];
    }

    /* resultant of the applied loads */
    for (int k = 0; k < p->map.nall; k++)
        p->f_applied[k % p->dim] += fall[k];

    cx_free(shift);
    cx_free(touched);
    *pp = p;
    return CX_OK;

fail:
    cx_free(shift);
    cx_free(touched);
    cx_problem_destroy(&p);
    if (status == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "out of memory building the problem");
    return status;
}

int cx_friction_check(const cx_friction_state *fr, int m, cx_diag *d)
{
    if ((unsigned)fr->law > CX_FRICTION_COULOMB)
        return cx_diag_set(d, CX_EINVAL, "unknown friction law %d", (int)fr->law);
    if (!(fr->slip_bound >= 0) || !isfinite(fr->slip_bound))
        return cx_diag_set(d, CX_EINVAL, "tresca: expected a non-negative slip bound, got %g",
                           fr->slip_bound);
    if (!(fr->F >= 0) || !isfinite(fr->F))
        return cx_diag_set(d, CX_EINVAL, "coulomb: expected a non-negative coefficient F, got %g",
                           fr->F);
    for (int i = 0; fr->s && i < m; i++)
        if (!(fr->s[i] >= 0) || !isfinite(fr->s[i]))
            return cx_diag_set(d, CX_EINVAL, "slip bound of contact point %d: expected a finite "
                               "value >= 0, got %g", i, fr->s[i]);
    for (int i = 0; fr->Fi && i < m; i++)
        if (!(fr->Fi[i] >= 0) || !isfinite(fr->Fi[i]))
            return cx_diag_set(d, CX_EINVAL, "friction coefficient of contact point %d: expected "
                               "a finite value >= 0, got %g", i, fr->Fi[i]);
    return CX_OK;
}
