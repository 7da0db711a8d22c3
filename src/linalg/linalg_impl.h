/* Private to linalg/: the CHOLMOD set-up shared by fact.c and schur.c. */
#ifndef CX_LINALG_IMPL_H
#define CX_LINALG_IMPL_H

#include "linalg/linalg.h"

#include <cholmod.h>

/* Start c with printing off and errors recorded (not printed). */
void cx_cholmod_start(cholmod_common *c);
/* A read-only CHOLMOD view of A (no copy). stype 1: use the upper
 * triangle of a full-storage symmetric matrix; 0: unsymmetric. */
cholmod_sparse cx_cholmod_view(const cx_csc *A, int stype);
/* A dense n x 1 view of x. */
cholmod_dense cx_cholmod_vec(double *x, int n);
/* Turn c->status after a call into a status and a diag line. what names
 * the call; L (may be NULL) gives the failing column for NOT_POSDEF. */
int cx_cholmod_check(cholmod_common *c, const cholmod_factor *L, const char *what, cx_diag *d);

/* CX_ENUMERIC if a pivot of the supernodal LL' factor L of A is below
 * 1e-14 of A's largest diagonal entry (numerically singular). */
int cx_cholmod_check_pivots(const cholmod_factor *L, const cx_csc *A, const char *what, cx_diag *d);

#endif
