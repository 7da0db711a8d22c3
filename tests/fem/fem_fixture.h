/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Shared by the fem tests: distorted meshes of every element type, a
 * deterministic random number, dense views of a CSC matrix. */
#ifndef CX_TEST_FEM_FIXTURE_H
#define CX_TEST_FEM_FIXTURE_H

#include "fem/fem.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* uniform in [-1, 1], a fixed sequence (xorshift64) */
static unsigned long long fx_state_ = 0x9E3779B97F4A7C15ull;
static inline double fx_rand(void)
{
    fx_state_ ^= fx_state_ << 13;
    fx_state_ ^= fx_state_ >> 7;
    fx_state_ ^= fx_state_ << 17;
    return 2.0 * (double)(fx_state_ >> 11) / 9007199254740992.0 - 1.0;
}

/* Move every node that is on no boundary by up to frac * h per coordinate.
 * straight (TRI6): only vertices move and mid-edge nodes are put back at
 * the middle of their edges; otherwise mid-edge nodes move too and the P2
 * edges become curved. */
static inline void fx_distort(cx_mesh *m, double h, double frac, int straight)
{
    char *fixed = calloc((size_t)m->nnodes, 1), *mid = calloc((size_t)m->nnodes, 1);
    for (int b = 0; b < m->nbounds; b++)
        for (int k = 0; k < m->bounds[b].nfacets * m->bounds[b].npf; k++)
            fixed[m->bounds[b].facets[k]] = 1;
    if (m->etype == CX_EL_TRI6 && straight)
        for (int e = 0; e < m->nelems; e++)
            for (int a = 3; a < 6; a++)
                mid[m->conn[6 * e + a]] = 1;
    for (int k = 0; k < m->nnodes; k++)
        if (!fixed[k] && !mid[k])
            for (int c = 0; c < m->dim; c++)
                m->x[m->dim * k + c] += frac * h * fx_rand();
    if (m->etype == CX_EL_TRI6 && straight)
        for (int e = 0; e < m->nelems; e++)
            for (int a = 0; a < 3; a++) {
                const int *c = m->conn + 6 * e;
                for (int k = 0; k < 2; k++)
                    m->x[2 * c[3 + a] + k] = 0.5 * (m->x[2 * c[a] + k] + m->x[2 * c[(a + 1) % 3] + k]);
            }
    free(fixed);
    free(mid);
}

/* A distorted mesh of type t: the rectangle [0,2] x [0,1.5] with 3 x 3 cells
 * or the brick [0,1] x [0,2] x [0,1.5] with 3 x 3 x 3 cells, interior nodes
 * moved by up to 20 % of the smallest cell size (TRI6: of the node spacing,
 * half a cell). NULL on failure. */
static inline cx_mesh *fx_mesh(cx_elem_type t, int straight)
{
    cx_mesh *m = NULL;
    if (cx_elem_dim(t) == 2) {
        if (cx_mesh_rectangle(&m, 0, 0, 2, 1.5, 3, 3, t, NULL))
            return NULL;
        fx_distort(m, t == CX_EL_TRI6 && !straight ? 0.25 : 0.5, 0.2, straight);
    } else {
        double lo[3] = {0, 0, 0}, hi[3] = {1, 2, 1.5};
        if (cx_mesh_brick(&m, lo, hi, 3, 3, 3, t, NULL))
            return NULL;
        fx_distort(m, 1.0 / 3, 0.2, 1);
    }
    return m;
}

static inline cx_material fx_material(cx_model model)
{
    cx_material mat = {.E = 210.0, .nu = 0.3, .model = model};
    return mat;
}

/* max |A(i, j)| */
static inline double fx_maxabs(const cx_csc *A)
{
    double s = 0;
    for (size_t k = 0; k < cx_csc_nnz(A); k++)
        s = fmax(s, fabs(A->x[k]));
    return s;
}

/* Frobenius norm */
static inline double fx_frob(const cx_csc *A)
{
    double s = 0;
    for (size_t k = 0; k < cx_csc_nnz(A); k++)
        s += A->x[k] * A->x[k];
    return sqrt(s);
}

static inline double fx_norm(int n, const double *x)
{
    double s = 0;
    for (int k = 0; k < n; k++)
        s += x[k] * x[k];
    return sqrt(s);
}

/* y = A x for a CSC A (the test's own product, independent of linalg) */
static inline void fx_matvec(const cx_csc *A, const double *x, double *y)
{
    memset(y, 0, sizeof(double) * (size_t)A->nrow);
    for (int j = 0; j < A->ncol; j++)
        for (int q = A->p[j]; q < A->p[j + 1]; q++)
            y[A->i[q]] += A->x[q] * x[j];
}

#endif
