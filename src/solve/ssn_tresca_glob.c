/* SPDX-License-Identifier: GPL-3.0-or-later */
/* ssn-tresca-glob — the globalised inexact ActiveSetTresca of paper 000 §6
 * (SNM4 of its Table 2): frictionless or Tresca, 2D, on the dual box QP
 *     min q(l) = 1/2 l'A l - l'b,  lN >= 0, |lT| <= s,  A = B K^-1 B'.
 *
 * §6 reads the dual active-set method as a restarted CG whose iterates
 * decrease q, with MPRGP's adaptive precision, the sets of (15), (18),
 * (19) in place of MPRGP's and rho in the role of its steplength; it then
 * converges from any feasible start. The text gives no more, so this is our
 * concrete rule (doc/papers.md §2.4):
 *  1. an outer iteration starts with the projection l <- P(l - rho g),
 *     rho = rho_scale / alpha_max (000: 20): its clipped components are
 *     the SSN sets I, the rest the face A. If that step raised q (rho may
 *     exceed 2/alpha_max), it is replaced by P(l - abar g), abar =
 *     2/alpha_max, which cannot (Dostál), so q decreases monotonically;
 *  2. CG on the face, kept feasible, while the iterate is proportional
 *     (||beta||^2 <= Gamma^2 phi~'phi, MPRGP's adaptive precision test);
 *     a step that would leave the box stops at the boundary and ends the
 *     outer iteration, as does a failed proportioning test.
 * Products: one for the projection (two if it falls back), one per CG step.
 * Own criterion (000 §5): ||l^k - l^(k-1)|| / ||l^k|| <= eps, or a zero
 * projected gradient. */
#include "solve/dual_impl.h"

#include <math.h>
#include <string.h>

typedef struct {
    cx_dual *D;         /* the session's dual operator (borrowed) */
    int nd;             /* dual order */
    int tangential;     /* Tresca rows take part */
    double *lambda;     /* nd: feasible iterate */
    double *lprev;      /* nd: previous outer iterate */
    double *g;          /* nd: A lambda - b */
    double *p, *Ap;     /* nd: CG direction, its product */
    double *phi;        /* nd: free gradient */
    double *trial;      /* nd: projected point */
    double *lo, *hi;    /* nd: the box */
    double *z, *zp;     /* n: K^-1 B' lambda, K^-1 B' p */
    double rho, abar;   /* projection steps */
    double gamma, eps;
    int max_inner;
    double bnorm;
} glob_state;

static const cx_param glob_params[] = {
    {"rho_scale", CX_PARAM_REAL, 20.0, 1e-6, 1e6, NULL, "rho = rho_scale / alpha_max (000 SNM4: 20)", 0},
    {"gamma", CX_PARAM_REAL, 1.0, 1e-6, 1e6, NULL, "proportioning constant Gamma", 0},
    {"eps", CX_PARAM_REAL, 1e-10, 1e-16, 1, NULL,
     "own stop: ||l^k - l^(k-1)|| / ||l^k|| <= eps (000: 1e-6)", 0},
    {"max_inner", CX_PARAM_INT, 10000, 1, 1e8, NULL, "CG steps per outer iteration at most", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void glob_destroy(void *state)
{
    glob_state *st = state;
    double **v[] = {&st->lambda, &st->lprev, &st->g, &st->p, &st->Ap, &st->phi, &st->trial,
                    &st->lo, &st->hi, &st->z, &st->zp};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        cx_free(*v[k]);
    memset(st, 0, sizeof *st);
}

static int glob_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    glob_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    if (cx_session_friction(s)->law == CX_FRICTION_COULOMB)
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "method 'ssn-tresca-glob' solves Tresca (or frictionless) problems; for Coulomb "
                           "friction use cf-fp with --set inner=ssn-tresca-glob, or ssn-coulomb");
    st->tangential = cx_session_friction(s)->law == CX_FRICTION_TRESCA;
    CX_TRY(cx_dual_get(s, &st->D, d));
    int nd = st->nd = cx_dual_size(st->D, st->tangential), ok = 1;
    double **v[] = {&st->lambda, &st->lprev, &st->g, &st->p, &st->Ap, &st->phi, &st->trial, &st->lo, &st->hi};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        ok &= (*v[k] = CX_NEW(double, nd > 0 ? nd : 1)) != NULL;
    ok &= (st->z = CX_NEW(double, p->n)) != NULL;
    ok &= (st->zp = CX_NEW(double, p->n)) != NULL;
    if (!ok) {
        glob_destroy(st);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    double amax;
    int rc = cx_dual_amax(st->D, st->tangential, &amax, d);
    if (rc) {
        glob_destroy(st);
        return rc;
    }
    st->rho = cx_param_get(params, "rho_scale") / amax;
    st->abar = 2.0 / amax;
    st->gamma = cx_param_get(params, "gamma");
    st->eps = cx_param_get(params, "eps");
    st->max_inner = (int)cx_param_get(params, "max_inner");
    const double *b = cx_dual_rhs(st->D);
    for (int i = 0; i < nd; i++)
        st->g[i] = -b[i];          /* lambda = 0, feasible */
    st->bnorm = cx_vec_norm2(nd, b);
    return CX_OK;
}

/* Move to trial = P(lambda - step g): one product; returns the change of q. */
static int glob_project(glob_state *st, int n, double step, double *dq)
{
    int nd = st->nd;
    memcpy(st->trial, st->lambda, sizeof(double) * (size_t)nd);
    cx_vec_axpy(nd, -step, st->g, st->trial);
    cx_dual_project(nd, st->lo, st->hi, st->trial);
    for (int i = 0; i < nd; i++)
        st->p[i] = st->trial[i] - st->lambda[i];
    *dq = 0;
    if (cx_vec_norminf(nd, st->p) == 0)
        return CX_OK;
    CX_TRY(cx_dual_apply(st->D, st->tangential, st->p, st->Ap, st->zp));
    /* q(l + p) - q(l) = p'g + 1/2 p'Ap */
    *dq = cx_vec_dot(nd, st->p, st->g) + 0.5 * cx_vec_dot(nd, st->p, st->Ap);
    (void)n;
    return CX_OK;
}

static void glob_accept(glob_state *st, int n)
{
    memcpy(st->lambda, st->trial, sizeof(double) * (size_t)st->nd);
    cx_vec_axpy(st->nd, 1.0, st->Ap, st->g);
    cx_vec_axpy(n, 1.0, st->zp, st->z);
}

/* Free gradient phi; ||g^P||^2, ||beta||^2 and phi~'phi. */
static void glob_gradients(glob_state *st, double *gp2, double *b2, double *rp)
{
    cx_dual_gradients(st->nd, st->lambda, st->g, st->lo, st->hi, st->abar, st->phi, NULL, gp2, b2, rp);
}

static int glob_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    glob_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    int nd = st->nd, n = p->n;
    double dq, gp2, b2, rp;

    cx_dual_bounds(p, cx_session_friction(s)->s, st->tangential, st->lo, st->hi);
    memcpy(st->lprev, st->lambda, sizeof(double) * (size_t)nd);

    /* 1. the SSN sets by the projection with rho; monotone safeguard */
    CX_TRY(glob_project(st, n, st->rho, &dq));
    if (dq > 0)
        CX_TRY(glob_project(st, n, st->abar, &dq));
    if (dq <= 0)
        glob_accept(st, n);

    /* 2. feasible CG on the face while proportional */
    long inner = 0;
    glob_gradients(st, &gp2, &b2, &rp);
    memcpy(st->p, st->phi, sizeof(double) * (size_t)nd);
    while (inner < st->max_inner && gp2 > 0 && b2 <= st->gamma * st->gamma * rp &&
           sqrt(gp2) > st->eps * 1e-3 * st->bnorm) {
        if (inner > 0 && inner % CX_CHECK_INTERVAL == 0 && cx_session_interrupted(s))
            break;   /* cancelled or out of time: the iterate so far is feasible */
        CX_TRY(cx_dual_apply(st->D, st->tangential, st->p, st->Ap, st->zp));
        inner++;
        double pAp = cx_vec_dot(nd, st->p, st->Ap);
        if (!(pAp > 0))
            return cx_diag_set(d, CX_ENUMERIC, "ssn-tresca-glob: p'Ap = %g is not positive", pAp);
        double acg = cx_vec_dot(nd, st->g, st->p) / pAp;
        double af = cx_dual_max_step(nd, st->lambda, st->p, st->lo, st->hi);
        double a = acg <= af ? acg : af;
        cx_vec_axpy(nd, -a, st->p, st->lambda);
        cx_vec_axpy(nd, -a, st->Ap, st->g);
        cx_vec_axpy(n, -a, st->zp, st->z);
        glob_gradients(st, &gp2, &b2, &rp);
        if (acg > af)
            break;   /* at the boundary: the next projection picks new sets */
        double gam = cx_vec_dot(nd, st->phi, st->Ap) / pAp;
        for (int i = 0; i < nd; i++)
            st->p[i] = st->phi[i] - gam * st->p[i];
    }
    it->inner = inner;

    cx_vec_axpy(nd, -1.0, st->lambda, st->lprev);
    double nl = cx_vec_norm2(nd, st->lambda);
    it->own = nl > 0 ? cx_vec_norm2(nd, st->lprev) / nl : 0;
    it->own_done = it->own <= st->eps || gp2 == 0;
    cx_dual_recover(st->D, st->z, it->u);
    cx_dual_split(p, st->tangential, st->lambda, it->lN, it->lT);
    return CX_OK;
}

const cx_method cx_method_ssn_tresca_glob = {
    .id = "ssn-tresca-glob",
    .name = "Globalised inexact active set, dual (Tresca)",
    .source = "000 §6",
    .summary = "SSN sets by projection with rho = 20/alpha_max, feasible CG while proportional; q decreases",
    .supports = CX_FRICTIONLESS | CX_TRESCA | CX_2D | CX_MULTIBODY,
    .state_size = sizeof(glob_state),
    .params = glob_params,
    .init = glob_init,
    .step = glob_step,
    .destroy = glob_destroy,
};
