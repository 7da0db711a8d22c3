/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Dirichlet conditions by elimination: a map of the prescribed dofs, the
 * reduced system over the free dofs, and the expansion back. */
#include "fem/fem.h"

#include <string.h>

int cx_dofmap_init(cx_dofmap *map, int nall)
{
    memset(map, 0, sizeof *map);
    if (nall < 0)
        return CX_EINVAL;
    map->nall = map->nfree = nall;
    map->free_of = CX_NEW(int, nall);
    map->all_of = CX_NEW(int, nall);
    map->value = CX_NEW(double, nall);
    if (!map->free_of || !map->all_of || !map->value) {
        cx_dofmap_clear(map);
        return CX_ENOMEM;
    }
    for (int k = 0; k < nall; k++)
        map->free_of[k] = map->all_of[k] = k;
    return CX_OK;
}

void cx_dofmap_clear(cx_dofmap *map)
{
    cx_free(map->free_of);
    cx_free(map->all_of);
    cx_free(map->value);
    memset(map, 0, sizeof *map);
}

int cx_dofmap_fix(cx_dofmap *map, const cx_mesh *m, const cx_boundary *b, int c, double value)
{
    if (c < 0 || c >= m->dim || map->nall != m->dim * m->nnodes)
        return CX_EINVAL;
    for (int k = 0; k < b->nfacets * b->npf; k++) {
        int dof = m->dim * b->facets[k] + c;
        map->free_of[dof] = -1;
        map->value[dof] = value;
    }
    /* the free numbering is stale until finish: reduce refuses it */
    map->nfree = -1;
    return CX_OK;
}

int cx_dofmap_finish(cx_dofmap *map)
{
    int n = 0;
    for (int k = 0; k < map->nall; k++)
        if (map->free_of[k] >= 0) {
            map->free_of[k] = n;
            map->all_of[n++] = k;
        }
    map->nfree = n;
    return CX_OK;
}

int cx_fem_reduce(const cx_csc *Kall, const double *fall, const cx_dofmap *map,
                  cx_csc *K, double *f)
{
    int n = map->nfree;
    memset(K, 0, sizeof *K);
    if (n < 0 || Kall->nrow != map->nall || Kall->ncol != map->nall)
        return CX_EINVAL;
    /* nnz(Kall) bounds nnz(K); shrunk at the end */
    size_t cap = cx_csc_nnz(Kall);
    K->nrow = K->ncol = n;
    K->p = CX_NEW(int, n + 1);
    K->i = CX_NEW(int, cap);
    K->x = CX_NEW(double, cap);
    if (!K->p || !K->i || !K->x) {
        cx_csc_clear(K);
        return CX_ENOMEM;
    }
    for (int r = 0; r < n; r++)
        f[r] = fall[map->all_of[r]];
    /* one pass over the columns of Kall: free indices ascend with the
     * all-dofs, so the free columns come in order and their rows stay
     * sorted; a prescribed column moves its free part times the value to
     * the right-hand side */
    int nz = 0;
    for (int j = 0; j < map->nall; j++) {
        int fj = map->free_of[j];
        if (fj >= 0) {
            K->p[fj] = nz;
            for (int q = Kall->p[j]; q < Kall->p[j + 1]; q++) {
                int r = map->free_of[Kall->i[q]];
                if (r >= 0) {
                    K->i[nz] = r;
                    K->x[nz++] = Kall->x[q];
                }
            }
        } else if (map->value[j] != 0) {
            double v = map->value[j];
            for (int q = Kall->p[j]; q < Kall->p[j + 1]; q++) {
                int r = map->free_of[Kall->i[q]];
                if (r >= 0)
                    f[r] -= Kall->x[q] * v;
            }
        }
    }
    K->p[n] = nz;
    if ((size_t)nz < cap) {
        /* a failed shrink keeps the larger arrays, which are still valid */
        int *ni = cx_realloc(K->i, sizeof(int) * (size_t)(nz ? nz : 1));
        if (ni)
            K->i = ni;
        double *nx = cx_realloc(K->x, sizeof(double) * (size_t)(nz ? nz : 1));
        if (nx)
            K->x = nx;
    }
    return CX_OK;
}

int cx_fem_reduce_move(cx_csc *Kall, const double *fall, const cx_dofmap *map, cx_csc *K, double *f)
{
    int n = map->nfree;
    if (n < 0 || Kall->nrow != n || Kall->ncol != n)
        return cx_fem_reduce(Kall, fall, map, K, f);
    /* over the free dofs already (or no dof prescribed): nothing to drop */
    *K = *Kall;
    memset(Kall, 0, sizeof *Kall);
    for (int r = 0; r < n; r++)
        f[r] = fall[map->all_of[r]];
    return CX_OK;
}

void cx_fem_expand(const cx_dofmap *map, const double *u, double *uall)
{
    for (int k = 0; k < map->nall; k++) {
        int r = map->free_of[k];
        uall[k] = r >= 0 ? u[r] : map->value[k];
    }
}
