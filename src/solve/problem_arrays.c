/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A problem from plain arrays (problem.h, cx_problem_from_data): checked
 * entry by entry, so that a bad input is one line naming the array and the
 * entry, never a NaN found by a method later; then copied into the same
 * cx_problem a scene builds, without its mesh. */
#include "solve/problem.h"

#include <math.h>
#include <string.h>

/* data's matrix named name (nrow x ncol expected) into a triplet; lower:
 * K's lower triangle (upper entries refused, off-diagonal ones mirrored). */
static int data_triplet(const cx_sparse_data *a, const char *name, int nrow, int ncol, int lower,
                        cx_triplet *t, cx_diag *d)
{
    if (a->nrow != nrow || a->ncol != ncol)
        return cx_diag_set(d, CX_EINVAL, "%s: %d x %d, expected %d x %d", name, a->nrow, a->ncol, nrow,
                           ncol);
    if (a->form != CX_SPARSE_CSC && a->form != CX_SPARSE_TRIPLET)
        return cx_diag_set(d, CX_EINVAL, "%s: unknown form %d (CX_SPARSE_CSC or CX_SPARSE_TRIPLET)", name,
                           (int)a->form);
    size_t nnz = a->nnz;
    if (a->form == CX_SPARSE_CSC) {
        if (!a->p)
            return cx_diag_set(d, CX_EINVAL, "%s: no column starts p", name);
        if (a->p[0] != 0)
            return cx_diag_set(d, CX_EINVAL, "%s: p[0] is %d, expected 0", name, a->p[0]);
        for (int j = 0; j < ncol; j++)
            if (a->p[j + 1] < a->p[j])
                return cx_diag_set(d, CX_EINVAL, "%s: column starts decrease at column %d", name, j);
        nnz = (size_t)a->p[ncol];
    } else if (nnz > 0 && !a->j) {
        return cx_diag_set(d, CX_EINVAL, "%s: no column indices j", name);
    }
    if (nnz > 0 && (!a->i || !a->x))
        return cx_diag_set(d, CX_EINVAL, "%s: no row indices or values", name);
    CX_TRY(cx_triplet_init(t, nrow, ncol, lower ? 2 * nnz : nnz));
    int col = 0;
    for (size_t k = 0; k < nnz; k++) {
        int i = a->i[k], j;
        if (a->form == CX_SPARSE_CSC) {
            while (a->p[col + 1] <= (int)k)
                col++;
            j = col;
        } else {
            j = a->j[k];
        }
        double x = a->x[k];
        const char *bad = i < 0 || i >= nrow || j < 0 || j >= ncol ? "index out of range"
                          : !isfinite(x)                          ? "not a finite value"
                          : lower && i < j                        ? "above the diagonal (K_lower)"
                                                                  : NULL;
        if (bad) {
            cx_triplet_clear(t);
            return cx_diag_set(d, CX_EINVAL, "%s: entry %zu (row %d, column %d): %s", name, k, i, j, bad);
        }
        int st = cx_triplet_add(t, i, j, x);
        if (!st && lower && i != j)
            st = cx_triplet_add(t, j, i, x);
        if (st) {
            cx_triplet_clear(t);
            return cx_diag_set(d, st, "out of memory");
        }
    }
    return CX_OK;
}

static int data_csc(const cx_sparse_data *a, const char *name, int nrow, int ncol, int lower, cx_csc *A,
                    cx_diag *d)
{
    cx_triplet t;
    CX_TRY(data_triplet(a, name, nrow, ncol, lower, &t, d));
    int st = cx_csc_from_triplet(A, &t);
    cx_triplet_clear(&t);
    return st ? cx_diag_set(d, st, "out of memory") : CX_OK;
}

/* name[0..n-1] finite (and >= 0 with nonneg); NULL is an error if needed. */
static int data_vec(const double *v, int n, const char *name, int nonneg, cx_diag *d)
{
    if (!v && n > 0)
        return cx_diag_set(d, CX_EINVAL, "%s: no values", name);
    for (int k = 0; k < n; k++)
        if (!isfinite(v[k]) || (nonneg && v[k] < 0))
            return cx_diag_set(d, CX_EINVAL, "%s: entry %d is %g, expected a finite value%s", name, k, v[k],
                               nonneg ? " >= 0" : "");
    return CX_OK;
}

/* Both triangles given: K_ij = K_ji to 1e-12 of the largest entry. */
static int data_symmetric(const cx_csc *K, cx_diag *d)
{
    double amax = 0;
    for (size_t q = 0; q < cx_csc_nnz(K); q++)
        amax = fmax(amax, fabs(K->x[q]));
    for (int j = 0; j < K->ncol; j++)
        for (int q = K->p[j]; q < K->p[j + 1]; q++) {
            int i = K->i[q];
            double kt = cx_csc_get(K, j, i);
            if (fabs(K->x[q] - kt) > 1e-12 * amax)
                return cx_diag_set(d, CX_EINVAL,
                                   "K: not symmetric at row %d, column %d: %.17g against %.17g at (%d, %d)", i, j,
                                   K->x[q], kt, j, i);
        }
    return CX_OK;
}

static double *data_copy(const double *v, int n, double fill)
{
    double *c = CX_NEW(double, n > 0 ? n : 1);
    for (int k = 0; c && k < n; k++)
        c[k] = v ? v[k] : fill;
    return c;
}

int cx_problem_from_data(cx_problem **pp, const cx_problem_data *a, cx_diag *d)
{
    *pp = NULL;
    if (a->dim != 2 && a->dim != 3)
        return cx_diag_set(d, CX_EINVAL, "dimension %d, expected 2 or 3", a->dim);
    if (a->n < 1 || a->m < 0)
        return cx_diag_set(d, CX_EINVAL, "%d unknowns and %d contact points: expected n >= 1, m >= 0", a->n,
                           a->m);
    if (!isfinite(a->E) || a->E < 0)
        return cx_diag_set(d, CX_EINVAL, "E: %g, expected a finite value >= 0", a->E);
    int n = a->n, m = a->m, nt = (a->dim - 1) * m;
    CX_TRY(data_vec(a->f, n, "f", 0, d));
    CX_TRY(data_vec(a->g, m, "g", 1, d));
    if (a->weight)
        CX_TRY(data_vec(a->weight, m, "weight", 1, d));
    if (a->x)
        CX_TRY(data_vec(a->x, a->dim * m, "x", 0, d));

    int status;
    unsigned char *touched = NULL;
    cx_problem *p = CX_NEW(cx_problem, 1);
    if (!p)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    p->dim = a->dim;
    p->n = n;
    p->m = m;
    p->nt = nt;
    p->E = a->E;
    if ((status = data_csc(&a->K, "K", n, n, a->K_lower, &p->K, d)) ||
        (!a->K_lower && (status = data_symmetric(&p->K, d))) ||
        (status = data_csc(&a->N, "N", m, n, 0, &p->N, d)) ||
        (status = data_csc(&a->T, "T", nt, n, 0, &p->T, d)))
        goto fail;

    cx_contact_set *c = &p->contact;
    c->dim = a->dim;
    c->m = m;
    c->nall = n;
    p->f = data_copy(a->f, n, 0);
    p->g = data_copy(a->g, m, 0);
    c->gap = data_copy(a->g, m, 0);
    c->weight = data_copy(a->weight, m, 1);
    c->x = data_copy(a->x, a->dim * m, 0);
    c->node = CX_NEW(int, m > 0 ? m : 1);
    touched = CX_NEW(unsigned char, n);
    if (!p->f || !p->g || !c->gap || !c->weight || !c->x || !c->node || !touched) {
        status = cx_diag_set(d, CX_ENOMEM, "out of memory");
        goto fail;
    }
    for (int i = 0; i < m; i++)
        c->node[i] = -1;   /* no mesh node */

    /* the contact dofs and the stiffness scale, as cx_problem_create */
    for (int j = 0; j < n; j++) {
        touched[j] = p->N.p[j + 1] > p->N.p[j] || p->T.p[j + 1] > p->T.p[j];
        p->nc += touched[j];
    }
    p->cdofs = CX_NEW(int, p->nc > 0 ? p->nc : 1);
    if (!p->cdofs) {
        status = cx_diag_set(d, CX_ENOMEM, "out of memory");
        goto fail;
    }
    for (int j = 0, k = 0; j < n; j++)
        if (touched[j])
            p->cdofs[k++] = j;
    for (int j = 0; j < n; j++)
        for (int q = p->K.p[j]; q < p->K.p[j + 1]; q++)
            if (p->K.i[q] == j && p->K.x[q] > p->kscale)
                p->kscale = p->K.x[q];
    cx_free(touched);
    *pp = p;
    return CX_OK;

fail:
    cx_free(touched);
    cx_problem_destroy(&p);
    return status;
}

double cx_problem_stiffness(const cx_problem *p)
{
    double E = p->E;
    for (int b = 0; p->mesh && p->mats && b < cx_mesh_nmats(p->mesh); b++)
        E = fmax(E, p->mats[b].E);
    return E > 0 ? E : p->kscale > 0 ? p->kscale : 1;
}
