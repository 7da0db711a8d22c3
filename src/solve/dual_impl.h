/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Private to solve/: the dual operator of paper 000 §5 and the box helpers
 * shared by the dual methods (mprgp, ssn-tresca-dual, ssn-tresca-glob).
 *
 * With B = [N; T] (frictionless: B = N), c = [g; 0] and K SPD,
 *     A = B K^-1 B',   b = B K^-1 f - c,   q(lambda) = 1/2 l'A l - l'b,
 * and u = K^-1 (f - B' lambda). The Cholesky factor of K, K^-1 f and b are
 * built once per session in the operator cache (key "dual:K"); every
 * product with A is one solve with the factor (counted in solves by
 * linalg/) and one dual product (counted here), so that the papers' nK is
 * the solves of a run. The estimate of alpha_max = lambda_max(A) is kept in
 * the same object, computed the first time a run asks for it.
 * Dual vectors hold the m normal entries, then (Tresca) the m(dim-1)
 * tangential ones. */
#ifndef CX_DUAL_IMPL_H
#define CX_DUAL_IMPL_H

#include "solve/solve.h"

typedef struct cx_dual cx_dual;

/* The session's dual operator (built on first use). CX_EUNSUPPORTED with a
 * reason when K is not positive definite (a body held only by contact:
 * these methods need K^-1). */
int cx_dual_get(cx_session *s, cx_dual **D, cx_diag *d);

/* Order of the dual problem: m, or m + nt with the tangential rows. */
int cx_dual_size(const cx_dual *D, int tangential);
/* b = B K^-1 f - c (m + nt entries; the first m are the normal part). */
const double *cx_dual_rhs(const cx_dual *D);
/* K^-1 f (n entries). */
const double *cx_dual_uf(const cx_dual *D);

/* y = A x and z = K^-1 B' x (n entries; the caller's, so that it can keep
 * K^-1 B' lambda and recover u without another solve). One solve, one
 * dual product. */
int cx_dual_apply(cx_dual *D, int tangential, const double *x, double *y, double *z);

/* alpha_max = lambda_max(A) by the power method (relative change < 1e-4,
 * at most 200 steps), computed once per operator and kept. */
int cx_dual_amax(cx_dual *D, int tangential, double *amax, cx_diag *d);

/* u = K^-1 f - z with z = K^-1 B' lambda. */
void cx_dual_recover(const cx_dual *D, const double *z, double *u);

/* The box Lambda of paper 000: lN >= 0 and, with the tangential rows,
 * -s <= lT <= s, s the session's per-point slip bounds (m; read now,
 * so that an outer fixed point may change them between runs). */
void cx_dual_bounds(const cx_problem *p, const double *s, int tangential, double *lo, double *hi);

/* x := P_[lo,hi](x). */
void cx_dual_project(int nd, const double *lo, const double *hi, double *x);

/* q(lambda) = 1/2 l'(g - b) with g = A l - b. */
double cx_dual_objective(int nd, const double *lambda, const double *g, const double *b);

/* MPRGP's gradients at x in the box (Dostál; doc/papers.md
 * §2.3): the free gradient phi (nd), the chopped gradient beta (nd, may be
 * NULL), and *gp2 = ||g^P||^2, *b2 = ||beta||^2, *rp = phi~'phi with phi~
 * the free gradient reduced for the steplength abar. */
void cx_dual_gradients(int nd, const double *x, const double *g, const double *lo, const double *hi,
                       double abar, double *phi, double *beta, double *gp2, double *b2, double *rp);

/* The largest a >= 0 with lo <= x - a p <= hi (x feasible). */
double cx_dual_max_step(int nd, const double *x, const double *p, const double *lo, const double *hi);

/* Split the iterate into lN, lT for the cx_iterate (lT zero when the dual
 * has no tangential part). */
void cx_dual_split(const cx_problem *p, int tangential, const double *lambda, double *lN, double *lT);

#endif
