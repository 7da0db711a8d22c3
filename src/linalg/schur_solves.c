/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The Schur complement the way paper 001 §3 computes it, for comparison
 * with cx_schur_create (the bench times both): factorise A_ii alone
 * (CHOLMOD's default ordering) and solve once per contact dof,
 *     S(:, k) = A_cc(:, k) - A_ci A_ii^-1 A_ic(:, k),
 * the right-hand sides taken SCHUR_BLOCK at a time per CHOLMOD call (each
 * column is still its own forward and backward solve). The constrained
 * ordering of schur.c gets the same S from the factor's trailing block at
 * about the cost of one factorisation. */
#include "linalg/linalg_impl.h"

#include <string.h>

#define SCHUR_BLOCK 32

/* A_ii: the rows and columns of A with imap[j] >= 0, renumbered by imap. */
static int schur_interior(const cx_csc *A, const int *imap, int ni, cx_csc *Aii)
{
    size_t nnz = 0;
    for (int j = 0; j < A->ncol; j++)
        if (imap[j] >= 0)
            for (int q = A->p[j]; q < A->p[j + 1]; q++)
                nnz += imap[A->i[q]] >= 0;
    Aii->nrow = Aii->ncol = ni;
    Aii->p = CX_NEW(int, ni + 1);
    Aii->i = CX_NEW(int, nnz ? nnz : 1);
    Aii->x = CX_NEW(double, nnz ? nnz : 1);
    if (!Aii->p || !Aii->i || !Aii->x)
        return CX_ENOMEM;
    int col = 0;
    size_t at = 0;
    Aii->p[0] = 0;
    for (int j = 0; j < A->ncol; j++) {
        if (imap[j] < 0)
            continue;
        for (int q = A->p[j]; q < A->p[j + 1]; q++)
            if (imap[A->i[q]] >= 0) {   /* imap is increasing: rows stay sorted */
                Aii->i[at] = imap[A->i[q]];
                Aii->x[at++] = A->x[q];
            }
        Aii->p[++col] = (int)at;
    }
    return CX_OK;
}

int cx_schur_by_solves(const cx_csc *A, const int *c, int nc, double *S, cx_counters *cnt, cx_diag *d)
{
    int n = A->nrow, ni = n - nc, st = CX_ENOMEM;
    int *imap = CX_NEW(int, n), *cpos = CX_NEW(int, n);
    cx_csc Aii = {0};
    cholmod_common cc;
    cholmod_factor *L = NULL;
    cholmod_dense *B = NULL, *X = NULL;
    cx_cholmod_start(&cc);
    if (!imap || !cpos)
        goto done;
    for (int j = 0; j < n; j++)
        cpos[j] = -1;
    for (int k = 0; k < nc; k++) {
        if (c[k] < 0 || c[k] >= n || cpos[c[k]] >= 0) {
            st = cx_diag_set(d, CX_EINVAL, "schur: dof %d out of range or repeated", c[k]);
            goto done;
        }
        cpos[c[k]] = k;
    }
    for (int j = 0, t = 0; j < n; j++)
        imap[j] = cpos[j] < 0 ? t++ : -1;
    if ((st = schur_interior(A, imap, ni, &Aii)))
        goto done;

    cholmod_sparse view = cx_cholmod_view(&Aii, 1);
    L = cholmod_analyze(&view, &cc);
    if ((st = cx_cholmod_check(&cc, L, "schur by solves: analysis", d)))
        goto done;
    cholmod_factorize(&view, L, &cc);
    if (cnt)
        cnt->factorizations++;
    if ((st = cx_cholmod_check(&cc, L, "schur by solves: Cholesky factorisation of A_ii", d)) ||
        (st = cx_cholmod_check_pivots(L, &Aii, "schur by solves: Cholesky factorisation of A_ii", d)))
        goto done;

    B = cholmod_zeros((size_t)ni, SCHUR_BLOCK, CHOLMOD_REAL, &cc);
    if (!B) {
        st = CX_ENOMEM;
        goto done;
    }
    for (int k0 = 0; k0 < nc; k0 += SCHUR_BLOCK) {
        int nb = nc - k0 < SCHUR_BLOCK ? nc - k0 : SCHUR_BLOCK;
        double *b = B->x;
        B->ncol = (size_t)nb;
        memset(b, 0, sizeof(double) * (size_t)ni * SCHUR_BLOCK);
        /* B = A_ic(:, k0 .. k0 + nb), S(:, k) = A_cc(:, k) */
        for (int k = k0; k < k0 + nb; k++) {
            int j = c[k];
            memset(S + (size_t)nc * k, 0, sizeof(double) * (size_t)nc);
            for (int q = A->p[j]; q < A->p[j + 1]; q++) {
                int r = A->i[q];
                if (imap[r] >= 0)
                    b[(size_t)ni * (k - k0) + imap[r]] = A->x[q];
                else
                    S[(size_t)nc * k + cpos[r]] = A->x[q];
            }
        }
        cholmod_free_dense(&X, &cc);
        X = cholmod_solve(CHOLMOD_A, L, B, &cc);
        if (cnt)
            cnt->solves += nb;
        if ((st = cx_cholmod_check(&cc, L, "schur by solves: solve", d)))
            goto done;
        if (!X) {
            st = cx_diag_set(d, CX_EEXTERNAL, "schur by solves: solve failed");
            goto done;
        }
        /* S(:, k) -= A_ci X(:, k), column by column of A_ci' = A_ic */
        const double *x = X->x;
        for (int i = 0; i < n; i++) {
            if (imap[i] < 0)
                continue;
            for (int q = A->p[i]; q < A->p[i + 1]; q++) {
                int a = cpos[A->i[q]];
                if (a < 0)
                    continue;
                for (int k = 0; k < nb; k++)
                    S[(size_t)nc * (k0 + k) + a] -= A->x[q] * x[(size_t)ni * k + imap[i]];
            }
        }
    }
    st = CX_OK;
done:
    if (st == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "schur by solves: out of memory");
    if (B)
        B->ncol = SCHUR_BLOCK;
    cholmod_free_dense(&B, &cc);
    cholmod_free_dense(&X, &cc);
    cholmod_free_factor(&L, &cc);
    cholmod_finish(&cc);
    cx_csc_clear(&Aii);
    cx_free(imap);
    cx_free(cpos);
    return st;
}
