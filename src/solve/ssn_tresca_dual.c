/* SPDX-License-Identifier: GPL-3.0-or-later */
/* ssn-tresca-dual — ActiveSetTresca, dual version (paper 000 §5): the
 * semismooth Newton / active-set method on the dual box QP
 *     min q(l) = 1/2 l'A l - l'b,  lN >= 0, |lT| <= s,  A = B K^-1 B',
 * frictionless or Tresca, 2D (several bodies included).
 *
 * Each outer iteration forms the sets of Lemma 2 at the iterate,
 *     A_nu = {lN_i - rho g_i > 0},  I+_t = {lT_i - rho g_i > s_i},
 *     I-_t = {lT_i - rho g_i < -s_i}  (g = A l - b),
 * fixes the others at their bounds (lN = 0, lT = +-s) and minimises q over
 * the free components by CG (Lemma 3), each CG step one product with A,
 * i.e. one solve with the session's Cholesky factor of K (dual_impl.h).
 * Own criterion (000 §5 step 3): ||l^k - l^(k-1)|| / ||l^k|| <= eps.
 *
 * Parameters give the columns of 000's Table 1: rho = 1 in problem units
 * (rho_unit=abs, SNM1/SNM2) or rho = 1/alpha_max (rho_unit=amax, SNM3);
 * inner precision fixed (||g_free|| <= inner_tol ||b||, SNM1) or adaptive
 * (SNM2/3). The default is rho = 1/alpha_max with exact inner solves: it
 * reaches kkt errors near 1e-13, where the adaptive runs, with many more
 * cheap outer iterations, stall a little above 1e-12 on the rounding of
 * the recursively updated gradient. The paper's adaptive rule (its ref. [21]) is lost; ours joins
 * an inexact-Newton forcing term to the proportioning test of MPRGP (000
 * §6 says the rule is adopted from Dostál's work): CG on the face stops
 * when ||g_free|| <= eta ||g^P||, g^P the projected gradient of the outer
 * iterate (so an outer iterate far from the solution is not solved to
 * 1e-12 on a face that will change), or when ||beta|| > Gamma ||g_free||,
 * beta the chopped gradient on the fixed components (the face no longer
 * looks right), and never below inner_tol. The proportioning test alone
 * stops too late (beta is zero right after the sets are chosen), which is
 * why the forcing term is there. Every outer iteration does at least one
 * CG step, so that a small rho cannot stall the sets.
 * By default each face solve starts from the previous iterate and its
 * precision is relative to ||b||. inner_start=cold, inner_ref=face solve
 * each face as Matlab's pcg does with its defaults (paper 000 ran Matlab):
 * from zero free components, to inner_tol relative to the face's
 * right-hand side (the free gradient at that zero start); the paper's
 * SNM1 costs about 60 CG steps per Newton step, as this reading does
 * (on twoblocks-paper's first row 633/10 against the paper's 712/12; warm
 * and relative to ||b||: 543/10). */
#include "solve/dual_impl.h"

#include <math.h>
#include <string.h>

typedef struct {
    cx_dual *D;         /* the session's dual operator (borrowed) */
    int nd;             /* dual order: m (+ nt with friction) */
    int tangential;     /* Tresca rows take part */
    double *lambda;     /* nd: iterate */
    double *lprev;      /* nd: the previous outer iterate */
    double *g;          /* nd: A lambda - b */
    double *p, *Ap;     /* nd: CG direction and its product */
    double *dl;         /* nd: the jump to the bounds of the fixed set */
    double *lo, *hi;    /* nd: the box */
    signed char *set;   /* nd: 0 free, -1 at lo, +1 at hi */
    double *z, *zp;     /* n: K^-1 B' lambda, K^-1 B' p */
    double rho;         /* the sets' parameter (absolute) */
    int adaptive;       /* inner precision: 0 fixed, 1 adaptive */
    double inner_tol;   /* relative to ||b|| */
    double gamma;       /* adaptive rule: proportioning constant */
    double eta;         /* adaptive rule: forcing term */
    double eps;         /* own criterion */
    int max_inner;      /* CG steps per outer iteration */
    int cold;           /* each face solve starts its free components at 0 */
    int inner_face;     /* inner_tol relative to the face's initial gradient */
    double bnorm;       /* ||b|| */
} sdual_state;

static const cx_param sdual_params[] = {
    {"rho", CX_PARAM_REAL, 1.0, 1e-30, 1e30, NULL, "the sets' parameter rho (see rho_unit)", 0},
    {"rho_unit", CX_PARAM_CHOICE, 0, 0, 1, "amax|abs",
     "rho relative to 1/alpha_max (amax, SNM3) or in problem units (abs, SNM1/2)", 0},
    {"inner", CX_PARAM_CHOICE, 0, 0, 1, "fixed|adaptive",
     "inner CG precision: fixed inner_tol (SNM1) or the adaptive MPRGP-like rule (SNM2/3)", 0},
    {"inner_tol", CX_PARAM_REAL, 1e-12, 1e-16, 1, NULL, "inner CG tolerance, relative to ||b||", 0},
    {"gamma", CX_PARAM_REAL, 1.0, 1e-6, 1e6, NULL, "adaptive rule: stop CG when ||beta|| > gamma ||g_free||", 0},
    {"eta", CX_PARAM_REAL, 0.1, 0, 1, NULL,
     "adaptive rule: stop CG when ||g_free|| <= eta ||projected gradient|| of the outer iterate", 0},
    {"eps", CX_PARAM_REAL, 1e-10, 1e-16, 1, NULL,
     "own stop: ||l^k - l^(k-1)|| / ||l^k|| <= eps (000: 1e-6)", 0},
    {"max_inner", CX_PARAM_INT, 10000, 1, 1e8, NULL, "CG steps per outer iteration at most", 0},
    {"inner_start", CX_PARAM_CHOICE, 0, 0, 1, "warm|cold",
     "each face solve starts from the previous iterate (warm) or from zero free components (cold)", 0},
    {"inner_ref", CX_PARAM_CHOICE, 0, 0, 1, "b|face",
     "inner_tol relative to ||b|| (b) or to the free gradient at the start of each face solve (face)", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void sdual_destroy(void *state)
{
    sdual_state *st = state;
    double **v[] = {&st->lambda, &st->lprev, &st->g, &st->p, &st->Ap, &st->dl, &st->lo, &st->hi,
                    &st->z, &st->zp};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        cx_free(*v[k]);
    cx_free(st->set);
    memset(st, 0, sizeof *st);
}

static int sdual_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    sdual_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    if (cx_session_friction(s)->law == CX_FRICTION_COULOMB)
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "method 'ssn-tresca-dual' solves Tresca (or frictionless) problems; for Coulomb "
                           "friction use cf-fp with --set inner=ssn-tresca-dual, or ssn-coulomb");
    st->tangential = cx_session_friction(s)->law == CX_FRICTION_TRESCA;
    CX_TRY(cx_dual_get(s, &st->D, d));
    int nd = st->nd = cx_dual_size(st->D, st->tangential), ok = 1;
    double **v[] = {&st->lambda, &st->lprev, &st->g, &st->p, &st->Ap, &st->dl, &st->lo, &st->hi};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        ok &= (*v[k] = CX_NEW(double, nd > 0 ? nd : 1)) != NULL;
    ok &= (st->set = CX_NEW(signed char, nd > 0 ? nd : 1)) != NULL;
    ok &= (st->z = CX_NEW(double, p->n)) != NULL;
    ok &= (st->zp = CX_NEW(double, p->n)) != NULL;
    if (!ok) {
        sdual_destroy(st);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    st->rho = cx_param_get(params, "rho");
    if ((int)cx_param_get(params, "rho_unit") == 0) {
        double amax;
        int rc = cx_dual_amax(st->D, st->tangential, &amax, d);
        if (rc) {
            sdual_destroy(st);
            return rc;
        }
        st->rho /= amax;
    }
    st->adaptive = (int)cx_param_get(params, "inner") == 1;
    st->inner_tol = cx_param_get(params, "inner_tol");
    st->gamma = cx_param_get(params, "gamma");
    st->eta = cx_param_get(params, "eta");
    st->eps = cx_param_get(params, "eps");
    st->max_inner = (int)cx_param_get(params, "max_inner");
    st->cold = (int)cx_param_get(params, "inner_start") == 1;
    st->inner_face = (int)cx_param_get(params, "inner_ref") == 1;
    const double *b = cx_dual_rhs(st->D);
    for (int i = 0; i < nd; i++)
        st->g[i] = -b[i];          /* lambda = 0 */
    st->bnorm = cx_vec_norm2(nd, b);
    return CX_OK;
}

/* The sets of Lemma 2 at lambda; the jump dl to the bounds; the number of
 * free components. */
static int sdual_sets(sdual_state *st)
{
    int nfree = 0;
    for (int i = 0; i < st->nd; i++) {
        double y = st->lambda[i] - st->rho * st->g[i];
        st->set[i] = y > st->lo[i] ? (y > st->hi[i] ? 1 : 0) : -1;
        st->dl[i] = st->set[i] < 0 ? st->lo[i] - st->lambda[i] : (st->set[i] > 0 ? st->hi[i] - st->lambda[i] : 0);
        nfree += st->set[i] == 0;
    }
    return nfree;
}

/* ||g_free||^2 and ||beta||^2 (the chopped gradient on the fixed set). */
static void sdual_norms(const sdual_state *st, double *f2, double *b2)
{
    *f2 = *b2 = 0;
    for (int i = 0; i < st->nd; i++) {
        double g = st->g[i];
        if (st->set[i] == 0)
            *f2 += g * g;
        else if ((st->set[i] < 0 && g < 0) || (st->set[i] > 0 && g > 0))
            *b2 += g * g;
    }
}

static int sdual_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    sdual_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    int nd = st->nd, n = p->n;
    (void)d;

    cx_dual_bounds(p, cx_session_friction(s)->s, st->tangential, st->lo, st->hi);
    memcpy(st->lprev, st->lambda, sizeof(double) * (size_t)nd);
    /* the outer residual for the forcing term: ||l - P(l - g)||, the
     * projected gradient in its natural-map form */
    double r2 = 0;
    for (int i = 0; i < nd; i++) {
        double y = st->lambda[i] - st->g[i];
        y = y < st->lo[i] ? st->lo[i] : (y > st->hi[i] ? st->hi[i] : y);
        r2 += (st->lambda[i] - y) * (st->lambda[i] - y);
    }
    int nfree = sdual_sets(st);
    /* cold: the free components jump to zero with the fixed ones, in the same product */
    if (st->cold)
        for (int i = 0; i < nd; i++)
            if (st->set[i] == 0)
                st->dl[i] = -st->lambda[i];

    /* fix the inactive components at their bounds (21): one product */
    if (cx_vec_norminf(nd, st->dl) > 0) {
        CX_TRY(cx_dual_apply(st->D, st->tangential, st->dl, st->Ap, st->zp));
        cx_vec_axpy(nd, 1.0, st->dl, st->lambda);
        cx_vec_axpy(nd, 1.0, st->Ap, st->g);
        cx_vec_axpy(n, 1.0, st->zp, st->z);
    }

    /* CG on the free face (Lemma 3) */
    long inner = 0;
    double f2, b2;
    sdual_norms(st, &f2, &b2);
    double tol2 = st->inner_tol * st->inner_tol * (st->inner_face ? f2 : st->bnorm * st->bnorm);
    if (st->adaptive && st->eta * st->eta * r2 > tol2)
        tol2 = st->eta * st->eta * r2;
    for (int i = 0; i < nd; i++)
        st->p[i] = st->set[i] == 0 ? -st->g[i] : 0;
    while (nfree > 0 && inner < st->max_inner && f2 > tol2 &&
           !(st->adaptive && inner > 0 && b2 > st->gamma * st->gamma * f2)) {
        if (inner > 0 && inner % CX_CHECK_INTERVAL == 0 && cx_session_interrupted(s))
            break;   /* cancelled or out of time: the iterate so far stands */
        CX_TRY(cx_dual_apply(st->D, st->tangential, st->p, st->Ap, st->zp));
        double pAp = cx_vec_dot(nd, st->p, st->Ap);
        if (!(pAp > 0))
            break;   /* the face's minimiser is reached to rounding */
        double a = f2 / pAp;
        cx_vec_axpy(nd, a, st->p, st->lambda);
        cx_vec_axpy(nd, a, st->Ap, st->g);
        cx_vec_axpy(n, a, st->zp, st->z);
        double f2old = f2;
        sdual_norms(st, &f2, &b2);
        double beta = f2 / f2old;
        for (int i = 0; i < nd; i++)
            st->p[i] = st->set[i] == 0 ? -st->g[i] + beta * st->p[i] : 0;
        inner++;
    }
    it->inner = inner;

    /* the paper's err = ||l^k - l^(k-1)|| / ||l^k|| */
    cx_vec_axpy(nd, -1.0, st->lambda, st->lprev);
    double nl = cx_vec_norm2(nd, st->lambda);
    it->own = nl > 0 ? cx_vec_norm2(nd, st->lprev) / nl : 0;
    it->own_done = it->own <= st->eps;
    cx_dual_recover(st->D, st->z, it->u);
    cx_dual_split(p, st->tangential, st->lambda, it->lN, it->lT);
    return CX_OK;
}

const cx_method cx_method_ssn_tresca_dual = {
    .id = "ssn-tresca-dual",
    .name = "Semismooth Newton / active set, dual version (Tresca)",
    .source = "000 §5",
    .summary = "active sets of Lemma 2 on the dual box QP, CG on each face (SNM1/2/3 by parameters)",
    .supports = CX_FRICTIONLESS | CX_TRESCA | CX_2D | CX_MULTIBODY,
    .state_size = sizeof(sdual_state),
    .params = sdual_params,
    .init = sdual_init,
    .step = sdual_step,
    .destroy = sdual_destroy,
};
