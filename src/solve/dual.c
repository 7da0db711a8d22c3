/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The dual operator of paper 000 §5 (dual_impl.h): one Cholesky factor of
 * K per session in the operator cache, products A x = B K^-1 B' x, the
 * right-hand side b, alpha_max, and the box helpers of the dual methods. */
#include "solve/dual_impl.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

struct cx_dual {
    const cx_problem *p;   /* the session's problem (borrowed) */
    cx_fact *K;            /* Cholesky of K */
    cx_counters *cnt;      /* the session's run counters (borrowed) */
    double *uf;            /* n: K^-1 f */
    double *b;             /* m + nt: B K^-1 f - c */
    double *w;             /* n: workspace of the products */
    double *v0, *v1;       /* m + nt: power-method vectors */
    double amax[2];        /* lambda_max of A: normal only / with tangential; 0 = not yet */
};

static void dual_destroy(void *obj)
{
    cx_dual *D = obj;
    if (!D)
        return;
    cx_fact_destroy(&D->K);
    cx_free(D->uf);
    cx_free(D->b);
    cx_free(D->w);
    cx_free(D->v0);
    cx_free(D->v1);
    cx_free(D);
}

/* A problem read from a file has no mesh, so dual_rigid_translation
 * cannot see a body held only by contact. Its algebraic stand-in, after a
 * factorisation that passed the pivot check (a floating body's pivot is
 * roundoff, which on a fine mesh can sit above that check's bound): the
 * smallest eigenvalue of K by inverse iteration (three solves from a fixed
 * start), an upper bound of it (a Rayleigh quotient), against K's largest
 * diagonal entry. A rigid motion leaves roundoff, about 1e-16 of that
 * scale; a finite element K, however fine, stays far above 1e-12. Sets
 * *ratio; returns 1 if K is singular to working precision, 0 if not, or
 * a (negative) status. */
#define DUAL_SINGULAR_RATIO 1e-12
static int dual_singular(cx_fact *F, const cx_problem *p, double *ratio, cx_diag *d)
{
    int n = p->n;
    double amax = 0, lam = INFINITY;
    for (int j = 0; j < n; j++)
        for (int q = p->K.p[j]; q < p->K.p[j + 1]; q++)
            if (p->K.i[q] == j)
                amax = fmax(amax, fabs(p->K.x[q]));
    double *x = CX_NEW(double, (size_t)n + 1), *y = CX_NEW(double, (size_t)n + 1);
    int st = x && y ? CX_OK : cx_diag_set(d, CX_ENOMEM, "out of memory");
    uint64_t r = 0x9e3779b97f4a7c15u;   /* a fixed start: the same answer on every run */
    for (int i = 0; !st && i < n; i++) {
        r ^= r << 13, r ^= r >> 7, r ^= r << 17;
        x[i] = (double)(r >> 11) / 9007199254740992.0 - 0.5;
    }
    for (int it = 0; !st && it < 3; it++) {
        double nx = cx_vec_norm2(n, x);
        for (int i = 0; i < n; i++)
            x[i] /= nx;
        if ((st = cx_fact_solve(F, x, y, d)))
            break;
        double xy = cx_vec_dot(n, x, y);   /* x' K^-1 x, |x| = 1 */
        lam = cx_vec_finite(n, y) && xy > 0 ? fmin(lam, 1 / xy) : 0;
        memcpy(x, y, sizeof(double) * (size_t)n);
        if (!(lam > 0))
            break;
    }
    cx_free(x);
    cx_free(y);
    *ratio = amax > 0 ? lam / amax : 0;
    if (st)
        return st;
    return *ratio < DUAL_SINGULAR_RATIO;
}

static int dual_build(void **obj, const cx_problem *p, const void *arg, cx_counters *cnt, cx_diag *d)
{
    (void)arg;
    int nd = p->m + p->nt, st;
    cx_dual *D = CX_NEW(cx_dual, 1);
    if (!D)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    D->p = p;
    D->cnt = cnt;
    D->uf = CX_NEW(double, p->n);
    D->b = CX_NEW(double, nd);
    D->w = CX_NEW(double, p->n);
    D->v0 = CX_NEW(double, nd);
    D->v1 = CX_NEW(double, nd);
    if (!D->uf || !D->b || !D->w || !D->v0 || !D->v1) {
        dual_destroy(D);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    if ((st = cx_fact_create(&D->K, CX_FACT_CHOLESKY, cnt, d)) || (st = cx_fact_analyze(D->K, &p->K, d)) ||
        (st = cx_fact_factorize(D->K, &p->K, d))) {
        dual_destroy(D);
        if (st == CX_ENUMERIC && !p->mesh) {
            /* a problem read from a file has no mesh, so the support check
             * below (dual_rigid_translation) cannot name the body: the
             * factorisation's zero or tiny pivot is its algebraic stand-in,
             * and its column is the one to look at */
            char why[CX_DIAG_LEN];
            snprintf(why, sizeof why, "%s", d && d->msg[0] ? d->msg : "a zero pivot");
            return cx_diag_set(d, CX_EUNSUPPORTED,
                               "the dual methods need K^-1, but K is singular (%s): a body held only by "
                               "contact has a rigid motion K cannot see; use ssn-tresca", why);
        }
        if (st == CX_ENUMERIC)
            return cx_diag_set(d, CX_EUNSUPPORTED,
                               "the dual methods need K^-1, but K is not positive definite "
                               "(a body held only by contact); use ssn-tresca");
        return st;
    }
    double ratio;
    if (!p->mesh && (st = dual_singular(D->K, p, &ratio, d)) != 0) {
        dual_destroy(D);
        if (st != 1)
            return st;
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "the dual methods need K^-1, but K is singular (its smallest eigenvalue, by "
                           "inverse iteration, is %.1e of its largest diagonal entry): a body held only by "
                           "contact has a rigid motion K cannot see; use ssn-tresca", ratio);
    }
    if ((st = cx_fact_solve(D->K, p->f, D->uf, d))) {
        dual_destroy(D);
        return st;
    }
    cx_csc_gemv(&p->N, 1.0, D->uf, 0.0, D->b);
    cx_csc_gemv(&p->T, 1.0, D->uf, 0.0, D->b + p->m);
    for (int i = 0; i < p->m; i++)
        D->b[i] -= p->g[i];
    *obj = D;
    return CX_OK;
}

/* A rigid translation K cannot see: a body none of whose nodes has
 * component c prescribed is held in that direction by contact alone, so K
 * is singular whatever the factorisation would say. Known from the supports
 * at no cost, so that the dual methods refuse such a scene before paying
 * for a failed Cholesky (the explorer greys them up front). Sets *body and
 * *comp of the first such body, returns 1; 0 if every body is supported in
 * every direction (K may still be singular through a rotation: the
 * factorisation then says so, and the cache remembers it). */
static int dual_rigid_translation(const cx_problem *p, int *body, int *comp)
{
    const cx_mesh *me = p->mesh;
    if (!me || !p->map.free_of || p->map.nall != me->dim * me->nnodes)
        return 0;
    int dim = me->dim, nb = me->nbodies > 0 ? me->nbodies : 1;
    unsigned char *held = cx_calloc((size_t)nb * (size_t)dim, 1);
    if (!held)
        return 0;
    for (int e = 0; e < me->nelems; e++) {
        int b = me->body ? me->body[e] : 0;
        for (int k = 0; k < me->npe; k++) {
            int node = me->conn[me->npe * e + k];
            for (int c = 0; c < dim; c++)
                held[dim * b + c] |= p->map.free_of[dim * node + c] < 0;
        }
    }
    int found = 0;
    for (int i = 0; i < nb * dim && !found; i++)
        if (!held[i]) {
            *body = i / dim;
            *comp = i % dim;
            found = 1;
        }
    cx_free(held);
    return found;
}

int cx_dual_get(cx_session *s, cx_dual **D, cx_diag *d)
{
    void *obj = NULL;
    int body, comp;
    const cx_problem *p = cx_session_problem(s);
    if (dual_rigid_translation(p, &body, &comp)) {
        char who[32] = "the body";
        if (p->mesh->nbodies > 1)
            snprintf(who, sizeof who, "body %d", body + 1);
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "the dual methods need K^-1, but K is not positive definite: %s has no "
                           "support in %c (held only by contact); use ssn-tresca",
                           who, "xyz"[comp]);
    }
    CX_TRY(cx_session_cache_get(s, "dual:K", dual_build, NULL, dual_destroy, &obj, d));
    *D = obj;
    return CX_OK;
}

int cx_dual_size(const cx_dual *D, int tangential) { return D->p->m + (tangential ? D->p->nt : 0); }
const double *cx_dual_rhs(const cx_dual *D) { return D->b; }
const double *cx_dual_uf(const cx_dual *D) { return D->uf; }

int cx_dual_apply(cx_dual *D, int tangential, const double *x, double *y, double *z)
{
    const cx_problem *p = D->p;
    cx_csc_gemv_t(&p->N, 1.0, x, 0.0, D->w);
    if (tangential)
        cx_csc_gemv_t(&p->T, 1.0, x + p->m, 1.0, D->w);
    CX_TRY(cx_fact_solve(D->K, D->w, z, NULL));
    cx_csc_gemv(&p->N, 1.0, z, 0.0, y);
    if (tangential)
        cx_csc_gemv(&p->T, 1.0, z, 0.0, y + p->m);
    if (D->cnt)
        D->cnt->dual_products++;
    return CX_OK;
}

int cx_dual_amax(cx_dual *D, int tangential, double *amax, cx_diag *d)
{
    int nd = cx_dual_size(D, tangential);
    double *z;
    if (D->amax[tangential] > 0) {
        *amax = D->amax[tangential];
        return CX_OK;
    }
    /* the products' K^-1 B' x is not needed: borrow a scratch n-vector */
    z = CX_NEW(double, D->p->n);
    if (!z)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    for (int i = 0; i < nd; i++)
        D->v0[i] = 1.0 + (double)(i % 7) / 7.0;   /* not orthogonal to the top eigenvector */
    double nv = cx_vec_norm2(nd, D->v0), est = 0;
    for (int i = 0; i < nd; i++)
        D->v0[i] /= nv;
    for (int k = 0; k < 200 && nd > 0; k++) {
        int st = cx_dual_apply(D, tangential, D->v0, D->v1, z);
        if (st) {
            cx_free(z);
            return cx_diag_set(d, st, "dual operator: a solve with K failed");
        }
        double e = cx_vec_dot(nd, D->v0, D->v1), n1 = cx_vec_norm2(nd, D->v1);
        if (!(n1 > 0))
            break;
        for (int i = 0; i < nd; i++)
            D->v0[i] = D->v1[i] / n1;
        int done = k > 0 && fabs(e - est) <= 1e-4 * e;
        est = e;
        if (done)
            break;
    }
    cx_free(z);
    if (!(est > 0))
        return cx_diag_set(d, CX_ENUMERIC, "dual operator: no positive eigenvalue (no contact rows?)");
    D->amax[tangential] = est;
    *amax = est;
    return CX_OK;
}

void cx_dual_recover(const cx_dual *D, const double *z, double *u)
{
    for (int i = 0; i < D->p->n; i++)
        u[i] = D->uf[i] - z[i];
}

void cx_dual_bounds(const cx_problem *p, const double *s, int tangential, double *lo, double *hi)
{
    for (int i = 0; i < p->m; i++)
        lo[i] = 0, hi[i] = INFINITY;
    for (int i = 0; tangential && i < p->nt; i++)
        lo[p->m + i] = -s[i], hi[p->m + i] = s[i];
}

void cx_dual_project(int nd, const double *lo, const double *hi, double *x)
{
    for (int i = 0; i < nd; i++)
        x[i] = x[i] < lo[i] ? lo[i] : (x[i] > hi[i] ? hi[i] : x[i]);
}

double cx_dual_objective(int nd, const double *lambda, const double *g, const double *b)
{
    double q = 0;
    for (int i = 0; i < nd; i++)
        q += lambda[i] * (g[i] - b[i]);
    return 0.5 * q;
}

void cx_dual_split(const cx_problem *p, int tangential, const double *lambda, double *lN, double *lT)
{
    memcpy(lN, lambda, sizeof(double) * (size_t)p->m);
    if (tangential)
        memcpy(lT, lambda + p->m, sizeof(double) * (size_t)p->nt);
    else
        memset(lT, 0, sizeof(double) * (size_t)p->nt);
}

void cx_dual_gradients(int nd, const double *x, const double *g, const double *lo, const double *hi,
                       double abar, double *phi, double *beta, double *gp2, double *b2, double *rp)
{
    *gp2 = *b2 = *rp = 0;
    for (int i = 0; i < nd; i++) {
        double b = 0, f = 0;
        if (x[i] <= lo[i])
            b = g[i] < 0 ? g[i] : 0;
        else if (x[i] >= hi[i])
            b = g[i] > 0 ? g[i] : 0;
        else {
            f = g[i];
            double r = f > 0 ? fmin((x[i] - lo[i]) / abar, f) : fmax((x[i] - hi[i]) / abar, f);
            *rp += r * f;
        }
        phi[i] = f;
        if (beta)
            beta[i] = b;
        *b2 += b * b;
        *gp2 += (f + b) * (f + b);
    }
}

double cx_dual_max_step(int nd, const double *x, const double *p, const double *lo, const double *hi)
{
    double a = INFINITY;
    for (int i = 0; i < nd; i++) {
        if (p[i] > 0)
            a = fmin(a, (x[i] - lo[i]) / p[i]);
        else if (p[i] < 0)
            a = fmin(a, (x[i] - hi[i]) / p[i]);
    }
    return a;
}
