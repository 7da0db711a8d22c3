/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Private to linalg/: the CHOLMOD set-up shared by fact.c and schur.c
 * (defined in cholmod_util.c). */
#ifndef CX_LINALG_IMPL_H
#define CX_LINALG_IMPL_H

#include "linalg/linalg.h"

#include <cholmod.h>

/* A pivot below this fraction of the largest one (Cholesky: l_jj^2 against
 * the largest diagonal of A; LU: |U_kk| against the largest |U_kk| of the
 * scaled matrix) is taken as singular to working precision: the solves
 * would carry at most two correct digits. */
#define CX_PIVOT_RTOL 1e-14

/* Start c with printing off and errors recorded (not printed), and every
 * factor supernodal LL' (positivity checked at every pivot; the Schur
 * complement reads L22 from the supernodes). */
void cx_cholmod_start(cholmod_common *c);
/* A read-only CHOLMOD view of A (no copy: the fields point at A's arrays,
 * CHOLMOD must never free it). stype 1: use the upper triangle of a
 * full-storage symmetric matrix; 0: unsymmetric. */
cholmod_sparse cx_cholmod_view(const cx_csc *A, int stype);
/* A dense n x 1 view of x (no copy). */
cholmod_dense cx_cholmod_vec(double *x, int n);
/* Turn c->status after a call into a status and a diag line. what names
 * the call; L (may be NULL) gives the failing column for NOT_POSDEF,
 * reported in the original numbering (through L->Perm). */
int cx_cholmod_check(cholmod_common *c, const cholmod_factor *L, const char *what, cx_diag *d);
/* CX_ENUMERIC if a pivot l_jj^2 of the supernodal LL' factor L of A is
 * below CX_PIVOT_RTOL of A's largest diagonal entry (numerically singular: CHOLMOD
 * only refuses pivots <= 0, rounding can leave a tiny positive one). */
int cx_cholmod_check_pivots(const cholmod_factor *L, const cx_csc *A, const char *what, cx_diag *d);
/* The original column of position k of the permuted order of L. */
int cx_cholmod_column(const cholmod_factor *L, int k);

/* schur_numeric.c: with L the supernodal symbolic factor of P A P' (A in
 * full symmetric storage, P = L->Perm) whose columns from nstop on are the
 * dofs condensed onto, factorise the columns before nstop and leave the
 * rest unfactorised: W (nc x nc, nc = n - nstop, column-major, lower
 * triangle written, zero-initialised by the caller) receives
 * S = A22 - L21 L21' in the trailing order, and L's trailing block is set
 * to the identity, so that L y = P f gives y2 = f_c - A_ci A_ii^-1 f_i and
 * L' x = [y1; u_c] gives x_i = A_ii^-1 (f_i - A_ic u_c). CX_ENUMERIC
 * naming a column if A_ii is not (numerically) positive definite. */
int cx_schur_numeric(cholmod_factor *L, const cx_csc *A, int nstop, double *W, cholmod_common *cc, cx_diag *d);

#endif
