/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The Uzawa block relaxation core (paper 002 §4.3, §5), shared by ubr-c and
 * ubr-tf. The augmented Lagrangian
 *     1/2 u'Ku - f'u + (lam, Bu - phi)_W + r/2 |Bu - phi|_W^2 + j(phi)
 * (B = N, or [N; T] with Tresca; W the lumped contact-boundary measure, so
 * that (., .)_W is the boundary integral of (4.5) and r has the paper's
 * units) is minimised in u, then in phi (closed form: the projection (4.15)
 * onto phi_N <= g, the disc shrinkage (5.5) for the slip), then lam takes
 * the step rho = r. The u-problem has the constant matrix K + r B'WB:
 * factorised once per (session, r) through the session's operator cache,
 * so that a run costs one factorisation and one solve per iteration, and
 * a second run (another method, tolerance or friction value) none.
 * Multipliers are kept as tractions (lam) and reported as nodal forces
 * lN = W lam, lT = W lam_T.
 *
 * r = auto (beyond the paper, which names the choice of r as open): an
 * a-priori rule, one factorisation. For a fixed contact set UBR is ADMM on
 * the constraint Bu = phi; its error contracts like 1/(1 + r mu) on the
 * contact set and like r mu/(1 + r mu) off it, mu the eigenvalues of the
 * contact-boundary compliance W^1/2 B K^-1 B' W^1/2 (per unit measure), so
 * the best r balances the extremes: r* = 1/sqrt(mu_min mu_max). For an
 * elastic body mu_max ~ L/E (the smoothest boundary mode over the contact
 * boundary of size L) and mu_min ~ h/E (the mesh-scale mode, h the
 * boundary mesh size), hence
 *     r = c E / sqrt(h L),  L = |Gc'|^(1/(d-1)),  h = (|Gc'|/m')^(1/(d-1)),
 * over the m' candidate points Gc' (those the obstacle can reach: initial
 * gap below the size of the contact boundary; a half-ball leaves most of a
 * face out of reach), one factorisation. Measured (iterations to kkt 1e-8,
 * Table A of 'signorini bench paper 002'): the best hand-tuned r grows
 * with the level as the rule says (0.7E to 2E on hertz at levels 20 to
 * 192, 2.8E to 8E on halfball at levels 4 to 20), with c = 1.0 on hertz
 * and about 1.4 on halfball; c = 1.2 splits the difference. The paper's
 * 0.11E is tuned to its own relative-change criterion, which stops earlier
 * (a small r moves phi in small steps); the rule aims at the kkt error. E
 * is the largest Young modulus of the bodies. Tried and dropped: residual
 * balancing (adaptive r, refactorising): on hertz the early transient of
 * the rigid mode drove r down 16-fold and the run stalled.
 */
#include "solve/ubr.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define UBR_AUTO_C 1.2

typedef struct {
    double r;
    int tangential;
} ubr_factor_arg;

typedef struct {
    cx_fact *F;
} ubr_factor_obj;

static void ubr_factor_destroy(void *obj)
{
    ubr_factor_obj *o = obj;
    if (o)
        cx_fact_destroy(&o->F);
    cx_free(o);
}

/* K + r (N'WN + T'WT): the weights of the rows are r w_i, a point's
 * weight on each of its tangential rows. */
static int ubr_factor_build(void **obj, const cx_problem *p, const void *argp, cx_counters *cnt,
                            cx_diag *d)
{
    const ubr_factor_arg *arg = argp;
    int dt = p->dim - 1, nb = arg->tangential && p->nt > 0 ? 2 : 1, nrow = p->m + (nb > 1 ? p->nt : 0);
    const cx_csc *rows[2] = {&p->N, &p->T};
    cx_csc_aug A = {0};
    ubr_factor_obj *o = CX_NEW(ubr_factor_obj, 1);
    double *w = CX_NEW(double, nrow + 1);
    int st = o && w ? CX_OK : CX_ENOMEM;
    if (!st)
        st = cx_csc_aug_build(&A, &p->K, rows, nb);
    if (!st) {
        for (int r = 0; r < nrow; r++)
            w[r] = arg->r * p->contact.weight[r < p->m ? r : (r - p->m) / dt];
        cx_csc_aug_fill(&A, &p->K, w);
    }
    cx_free(w);
    if (st)
        cx_diag_set(d, st, st == CX_ENOMEM ? "out of memory" : "ubr: the sizes of K, N and T do not fit");
    if (!st && !(st = cx_fact_create(&o->F, CX_FACT_CHOLESKY, cnt, d)) &&
        !(st = cx_fact_analyze(o->F, &A.A, d)))
        st = cx_fact_factorize(o->F, &A.A, d);
    cx_csc_aug_clear(&A);
    if (st) {
        ubr_factor_destroy(o);
        return st;
    }
    *obj = o;
    return CX_OK;
}

int ubr_factor(cx_session *s, double r, int tangential, cx_fact **F, cx_diag *d)
{
    char key[CX_CACHE_KEYLEN];
    snprintf(key, sizeof key, "ubr:K+r(N'WN%s) r=%.17g", tangential ? "+T'WT" : "", r);
    ubr_factor_arg arg = {r, tangential};
    void *obj;
    CX_TRY(cx_session_cache_get(s, key, ubr_factor_build, &arg, ubr_factor_destroy, &obj, d));
    *F = ((ubr_factor_obj *)obj)->F;
    return CX_OK;
}

void ubr_core_clear(ubr_core *c)
{
    cx_free(c->sb);
    cx_free(c->phiN);
    cx_free(c->lamN);
    cx_free(c->phiT);
    cx_free(c->lamT);
    cx_free(c->phiN0);
    cx_free(c->phiT0);
    cx_free(c->un);
    cx_free(c->ut);
    cx_free(c->rhs);
    cx_free(c->uprev);
    cx_free(c->tmp);
    memset(c, 0, sizeof *c);
}

/* The a-priori r of the auto rule (see the header), over the candidate
 * points: those whose initial gap is below the size of the contact
 * boundary (a point the obstacle cannot reach has a far gap). */
double cx_ubr_auto_r(const cx_problem *p, double E)
{
    int d = p->dim;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, size = 0;
    for (int i = 0; i < p->m; i++)
        for (int k = 0; k < d; k++) {
            lo[k] = fmin(lo[k], p->contact.x[d * i + k]);
            hi[k] = fmax(hi[k], p->contact.x[d * i + k]);
        }
    for (int k = 0; k < d && p->m > 0; k++)
        size += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    size = sqrt(size);
    double area = 0;
    int mc = 0;
    for (int i = 0; i < p->m; i++)
        if (p->g[i] < size) {
            area += p->contact.weight[i];
            mc++;
        }
    if (!(area > 0) || mc == 0)
        return E;
    double e = 1.0 / (d - 1);
    double L = pow(area, e), h = pow(area / mc, e);
    return UBR_AUTO_C * E / sqrt(h * L);
}

int ubr_core_init(ubr_core *c, cx_session *s, const cx_param_values *params, int tangential,
                  const char *id, cx_diag *d)
{
    const cx_problem *p = cx_session_problem(s);
    const cx_iterate *it = cx_session_iterate(s);
    c->n = p->n;
    c->m = p->m;
    c->dt = tangential ? p->dim - 1 : 0;
    c->w = p->contact.weight;
    c->E = cx_problem_stiffness(p);
    for (int i = 0; i < p->m; i++)
        if (!(c->w[i] > 0))
            return cx_diag_set(d, CX_EUNSUPPORTED,
                               "method '%s' needs a positive contact-boundary measure at every "
                               "contact point (point %d has %g)", id, i, c->w[i]);
    double r = cx_param_get(params, "r");
    c->auto_r = isnan(r);
    c->r = c->auto_r ? cx_ubr_auto_r(p, c->E) : r * c->E;
    c->eps = cx_param_get(params, "eps");
    int mt = c->m * c->dt, mx = mt > c->m ? mt : c->m;
    c->sb = CX_NEW(double, c->m);
    c->phiN = CX_NEW(double, c->m);
    c->lamN = CX_NEW(double, c->m);
    c->phiN0 = CX_NEW(double, c->m);
    c->un = CX_NEW(double, c->m);
    c->phiT = CX_NEW(double, mt);
    c->lamT = CX_NEW(double, mt);
    c->phiT0 = CX_NEW(double, mt);
    c->ut = CX_NEW(double, mt);
    c->rhs = CX_NEW(double, c->n);
    c->uprev = CX_NEW(double, c->n);
    c->tmp = CX_NEW(double, mx);
    if (!c->sb || !c->phiN || !c->lamN || !c->phiN0 || !c->un || (mt && (!c->phiT || !c->lamT ||
        !c->phiT0 || !c->ut)) || !c->rhs || !c->uprev || !c->tmp) {
        ubr_core_clear(c);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    int st = ubr_factor(s, c->r, tangential, &c->F, d);
    if (st) {
        ubr_core_clear(c);
        return st;
    }
    /* start: lam from the iterate's multipliers, phi = B u (both zero
     * unless the session was given a warm start) */
    cx_csc_gemv(&p->N, 1.0, it->u, 0.0, c->phiN);
    for (int i = 0; i < c->m; i++) {
        c->lamN[i] = it->lN[i] / c->w[i];
        c->phiN[i] = fmin(c->phiN[i], p->g[i]);
        c->sb[i] = tangential ? cx_session_friction(s)->s[i] / c->w[i] : 0;
    }
    if (mt) {
        cx_csc_gemv(&p->T, 1.0, it->u, 0.0, c->phiT);
        for (int k = 0; k < mt; k++)
            c->lamT[k] = it->lT[k] / c->w[k / c->dt];
    }
    memcpy(c->uprev, it->u, sizeof(double) * (size_t)c->n);
    return CX_OK;
}

/* phi_T = (|z| - s)+ / (r |z|) z, z = lam_T + r u_T, at point i (5.5);
 * in 3D the shrinkage acts on the vector z in R^2 (the disc). */
static void ubr_shrink(const ubr_core *c, int i)
{
    int dt = c->dt;
    double z[2], nz = 0;
    for (int k = 0; k < dt; k++) {
        z[k] = c->lamT[dt * i + k] + c->r * c->ut[dt * i + k];
        nz += z[k] * z[k];
    }
    nz = sqrt(nz);
    double scale = nz > c->sb[i] ? (nz - c->sb[i]) / (c->r * nz) : 0;
    for (int k = 0; k < dt; k++)
        c->phiT[dt * i + k] = scale * z[k];
}

int ubr_core_step(ubr_core *c, cx_session *s, cx_iterate *it, cx_diag *d)
{
    const cx_problem *p = cx_session_problem(s);
    int m = c->m, dt = c->dt, mt = m * dt;
    double r = c->r;

    /* (4.13)/(5.3): (K + r B'WB) u = f + B'W (r phi - lam) */
    memcpy(c->rhs, p->f, sizeof(double) * (size_t)c->n);
    for (int i = 0; i < m; i++)
        c->tmp[i] = c->w[i] * (r * c->phiN[i] - c->lamN[i]);
    cx_csc_gemv_t(&p->N, 1.0, c->tmp, 1.0, c->rhs);
    if (mt) {
        for (int k = 0; k < mt; k++)
            c->tmp[k] = c->w[k / dt] * (r * c->phiT[k] - c->lamT[k]);
        cx_csc_gemv_t(&p->T, 1.0, c->tmp, 1.0, c->rhs);
    }
    memcpy(c->uprev, it->u, sizeof(double) * (size_t)c->n);
    CX_TRY(cx_fact_solve(c->F, c->rhs, it->u, d));
    cx_csc_gemv(&p->N, 1.0, it->u, 0.0, c->un);
    if (mt)
        cx_csc_gemv(&p->T, 1.0, it->u, 0.0, c->ut);

    /* (4.15): phi_N = u_N + [lam - (lam + r(u_N - g))+] / r; (5.5) for phi_T */
    memcpy(c->phiN0, c->phiN, sizeof(double) * (size_t)m);
    if (mt)
        memcpy(c->phiT0, c->phiT, sizeof(double) * (size_t)mt);
    for (int i = 0; i < m; i++) {
        double z = c->lamN[i] + r * (c->un[i] - p->g[i]);
        c->phiN[i] = c->un[i] + (c->lamN[i] - (z > 0 ? z : 0)) / r;
    }
    for (int i = 0; mt && i < m; i++)
        ubr_shrink(c, i);

    /* multiplier step rho = r */
    for (int i = 0; i < m; i++) {
        c->lamN[i] += r * (c->un[i] - c->phiN[i]);
        it->lN[i] = c->w[i] * c->lamN[i];
    }
    for (int k = 0; k < mt; k++) {
        c->lamT[k] += r * (c->ut[k] - c->phiT[k]);
        it->lT[k] = c->w[k / dt] * c->lamT[k];
    }

    /* (4.16)/(5.6): relative change of (u, phi) */
    double du = 0, nu = 0;
    for (int j = 0; j < c->n; j++) {
        double e = it->u[j] - c->uprev[j];
        du += e * e;
        nu += it->u[j] * it->u[j];
    }
    for (int i = 0; i < m; i++) {
        double e = c->phiN[i] - c->phiN0[i];
        du += e * e;
        nu += c->phiN[i] * c->phiN[i];
    }
    for (int k = 0; k < mt; k++) {
        double e = c->phiT[k] - c->phiT0[k];
        du += e * e;
        nu += c->phiT[k] * c->phiT[k];
    }
    it->own = nu > 0 ? sqrt(du / nu) : 0;
    it->own_done = it->iter > 0 && it->own < c->eps;
    return CX_OK;
}
