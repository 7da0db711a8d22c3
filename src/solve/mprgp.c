/* SPDX-License-Identifier: GPL-3.0-or-later */
/* mprgp — Dostál's MPRGP (modified proportioning with reduced gradient
 * projections) on the dual of paper 000 §5: the baseline column of its
 * Tables 1 and 2.
 *
 * Minimises q(l) = 1/2 l'A l - l'b over the box lN >= 0, |lT| <= s with
 * A = B K^-1 B' (the session's dual operator: each product is one solve
 * with the Cholesky factor of K). Frictionless contact and Tresca friction
 * in 2D. Coulomb is refused: its slip bound F lN is not a box; run it as
 * successive Tresca problems with the fixed-point wrapper cf-fp
 * (--set inner=mprgp).
 *
 * One step is one MPRGP iteration (doc/papers.md §2.3):
 * a conjugate gradient step on the free set while the iterate is
 * proportional (||beta||^2 <= Gamma^2 phi~'phi, phi~ the reduced free
 * gradient), an expansion step (to the boundary, then the fixed step
 * abar = abar_scale / alpha_max along the free gradient, projected) when
 * CG would leave the box, and a proportioning step along the chopped
 * gradient beta otherwise. Products: CG 1, proportioning 1, expansion 2.
 * Own criterion: ||g^P|| <= eps ||b||. u = K^-1 f - K^-1 B' l is kept up to
 * date from the products, without extra solves. */
#include "solve/dual_impl.h"

#include <math.h>
#include <string.h>

typedef struct {
    cx_dual *D;        /* the session's dual operator (borrowed) */
    int nd;            /* dual order: m (+ nt with friction) */
    int tangential;    /* Tresca rows take part */
    double *lambda;    /* nd: iterate, feasible */
    double *g;         /* nd: A lambda - b */
    double *p;         /* nd: CG direction */
    double *Ap;        /* nd: A p */
    double *phi;       /* nd: free gradient */
    double *beta;      /* nd: chopped gradient */
    double *lo, *hi;   /* nd: the box */
    double *z;         /* n: K^-1 B' lambda */
    double *zp;        /* n: K^-1 B' p */
    double *tmp;       /* nd */
    double abar;       /* fixed steplength abar_scale / alpha_max */
    double gamma;      /* proportioning constant */
    double eps;        /* own criterion */
    double bnorm;      /* ||b|| */
} mprgp_state;

static const cx_param mprgp_params[] = {
    {"abar_scale", CX_PARAM_REAL, 2.0, 1e-6, 2.0, NULL,
     "expansion steplength abar = abar_scale / alpha_max (000: 2)", 0},
    {"gamma", CX_PARAM_REAL, 1.0, 1e-6, 1e6, NULL, "proportioning constant Gamma", 0},
    {"eps", CX_PARAM_REAL, 1e-10, 1e-16, 1, NULL,
     "own stop: ||projected gradient|| <= eps ||b|| (000: 1e-6)", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void mprgp_destroy(void *state)
{
    mprgp_state *st = state;
    double **v[] = {&st->lambda, &st->g, &st->p, &st->Ap, &st->phi, &st->beta, &st->lo, &st->hi,
                    &st->z, &st->zp, &st->tmp};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        cx_free(*v[k]);
    memset(st, 0, sizeof *st);
}

/* phi, beta, ||g^P||^2, ||beta||^2 and phi~'phi at the iterate. */
static void mprgp_gradients(mprgp_state *st, double *gp2, double *b2, double *rp)
{
    cx_dual_gradients(st->nd, st->lambda, st->g, st->lo, st->hi, st->abar, st->phi, st->beta, gp2, b2, rp);
}

static int mprgp_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    mprgp_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    if (cx_session_friction(s)->law == CX_FRICTION_COULOMB)
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "method 'mprgp' solves a bound-constrained dual (Tresca or frictionless); "
                           "for Coulomb friction use the fixed-point wrapper cf-fp with --set inner=mprgp");
    st->tangential = cx_session_friction(s)->law == CX_FRICTION_TRESCA;
    CX_TRY(cx_dual_get(s, &st->D, d));
    st->nd = cx_dual_size(st->D, st->tangential);
    int nd = st->nd;
    double **v[] = {&st->lambda, &st->g, &st->p, &st->Ap, &st->phi, &st->beta, &st->lo, &st->hi, &st->tmp};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        *v[k] = CX_NEW(double, nd > 0 ? nd : 1);
    st->z = CX_NEW(double, p->n);
    st->zp = CX_NEW(double, p->n);
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        if (!*v[k]) {
            mprgp_destroy(st);
            return cx_diag_set(d, CX_ENOMEM, "out of memory");
        }
    if (!st->z || !st->zp) {
        mprgp_destroy(st);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    double amax;
    int rc = cx_dual_amax(st->D, st->tangential, &amax, d);
    if (rc) {
        mprgp_destroy(st);
        return rc;
    }
    st->abar = cx_param_get(params, "abar_scale") / amax;
    st->gamma = cx_param_get(params, "gamma");
    st->eps = cx_param_get(params, "eps");
    /* lambda = 0 is feasible; g = -b without a product */
    const double *b = cx_dual_rhs(st->D);
    for (int i = 0; i < nd; i++)
        st->g[i] = -b[i];
    st->bnorm = cx_vec_norm2(nd, b);
    cx_dual_bounds(p, cx_session_friction(s)->s, st->tangential, st->lo, st->hi);
    double gp2, b2, rp;
    mprgp_gradients(st, &gp2, &b2, &rp);
    memcpy(st->p, st->phi, sizeof(double) * (size_t)nd);
    return CX_OK;
}

/* lambda -= a p; g -= a Ap; z -= a zp */
static void mprgp_move(mprgp_state *st, int n, double a)
{
    cx_vec_axpy(st->nd, -a, st->p, st->lambda);
    cx_vec_axpy(st->nd, -a, st->Ap, st->g);
    cx_vec_axpy(n, -a, st->zp, st->z);
}

static int mprgp_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    mprgp_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    int nd = st->nd, n = p->n;
    double gp2, b2, rp;
    (void)d;

    mprgp_gradients(st, &gp2, &b2, &rp);
    if (gp2 == 0) {
        it->own = 0;
        it->own_done = 1;
        goto out;
    }
    if (b2 <= st->gamma * st->gamma * rp) {
        /* proportional: CG step, or expansion if it leaves the box */
        CX_TRY(cx_dual_apply(st->D, st->tangential, st->p, st->Ap, st->zp));
        double pAp = cx_vec_dot(nd, st->p, st->Ap);
        if (!(pAp > 0))
            return cx_diag_set(d, CX_ENUMERIC, "mprgp: p'Ap = %g is not positive", pAp);
        double acg = cx_vec_dot(nd, st->g, st->p) / pAp;
        double af = cx_dual_max_step(nd, st->lambda, st->p, st->lo, st->hi);
        if (acg <= af) {
            mprgp_move(st, n, acg);
            mprgp_gradients(st, &gp2, &b2, &rp);
            double gam = cx_vec_dot(nd, st->phi, st->Ap) / pAp;
            for (int i = 0; i < nd; i++)
                st->p[i] = st->phi[i] - gam * st->p[i];
        } else {
            mprgp_move(st, n, af);
            mprgp_gradients(st, &gp2, &b2, &rp);
            /* the fixed-step projection along the free gradient: the step
             * is p = (lambda - P(lambda - abar phi)), then one product */
            memcpy(st->tmp, st->lambda, sizeof(double) * (size_t)nd);
            cx_vec_axpy(nd, -st->abar, st->phi, st->tmp);
            cx_dual_project(nd, st->lo, st->hi, st->tmp);
            for (int i = 0; i < nd; i++)
                st->p[i] = st->lambda[i] - st->tmp[i];
            CX_TRY(cx_dual_apply(st->D, st->tangential, st->p, st->Ap, st->zp));
            mprgp_move(st, n, 1.0);
            memcpy(st->lambda, st->tmp, sizeof(double) * (size_t)nd);   /* exact bounds */
            mprgp_gradients(st, &gp2, &b2, &rp);
            memcpy(st->p, st->phi, sizeof(double) * (size_t)nd);
            it->inner = 1;   /* an expansion */
        }
    } else {
        /* proportioning: exact line search along the chopped gradient */
        memcpy(st->p, st->beta, sizeof(double) * (size_t)nd);
        CX_TRY(cx_dual_apply(st->D, st->tangential, st->p, st->Ap, st->zp));
        double pAp = cx_vec_dot(nd, st->p, st->Ap);
        if (!(pAp > 0))
            return cx_diag_set(d, CX_ENUMERIC, "mprgp: beta'A beta = %g is not positive", pAp);
        mprgp_move(st, n, cx_vec_dot(nd, st->g, st->p) / pAp);
        mprgp_gradients(st, &gp2, &b2, &rp);
        memcpy(st->p, st->phi, sizeof(double) * (size_t)nd);
    }
    it->own = st->bnorm > 0 ? sqrt(gp2) / st->bnorm : 0;
    it->own_done = sqrt(gp2) <= st->eps * st->bnorm;
out:
    cx_dual_recover(st->D, st->z, it->u);
    cx_dual_split(p, st->tangential, st->lambda, it->lN, it->lT);
    return CX_OK;
}

const cx_method cx_method_mprgp = {
    .id = "mprgp",
    .name = "MPRGP on the dual (Dostál)",
    .source = "000 §7 (Dostál 2005)",
    .summary = "bound-constrained CG with proportioning and projections on the dual box QP",
    .supports = CX_FRICTIONLESS | CX_TRESCA | CX_2D | CX_MULTIBODY,
    .state_size = sizeof(mprgp_state),
    .params = mprgp_params,
    .init = mprgp_init,
    .step = mprgp_step,
    .destroy = mprgp_destroy,
};
