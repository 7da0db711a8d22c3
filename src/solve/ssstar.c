/* SPDX-License-Identifier: GPL-3.0-or-later */
/* ssstar — the semismooth* Newton method of Gfrerer and Outrata for Tresca
 * friction, paper 001 §2–§4 (reconstruction: doc/papers.md §1.3–1.5).
 *
 * Solves Tresca friction and frictionless contact (slip bound 0) in 3D, one
 * body on a rigid obstacle (the code is written for 2D too, but a body held
 * only by the contact makes the first Newton step from zero singular, so
 * 2D, where the scenes are such bodies, is not offered). The problem is reduced to the contact dofs
 * with the session's Schur complement (A = S, b = f condensed; one sparse
 * Cholesky with the contact dofs ordered last, doc/design.md §5) and rotated into
 * each point's frame (tangential, normal), so that the generalized equation
 * (7) 0 in A u - b + (lT, lN) with lT in s d|u_T|, lN in N_{R+}-complement
 * splits into per-point convex parts. One step is:
 *  - the approximation step: one forward-backward step per point, in closed
 *    form (block soft-thresholding of u_T, the projection of lN onto R+),
 *    giving a point (y^, y*^) of the graph of the multifunction;
 *  - the stopping rule: the residual |F(y^) + y*^| (force rows over the load
 *    scale, the gap row times the stiffness scale) <= eps stops with y^;
 *  - the Newton step (9) with the case rules: stick (u^_T = 0) fixes u_T = 0,
 *    slide linearises s u/|u| at u^_T; contact (lN^ > 0) fixes u_N = g, no
 *    or weak contact fixes lN = 0. What remains is one dense SPD system
 *    (Cholesky) on the free components.
 * [M] The step of the approximation step is lost. Here it is gamma / kappa_j
 * on the displacement rows and gamma_n kappa_j on the multiplier row, with
 * kappa_j the largest diagonal entry of A at point j. gamma = 12, chosen on
 * the prism: gamma <= 1 cycles between two active sets from level 4 on, 3-5
 * from level 5 on; Newton steps on levels 1-8 from zero were
 *     gamma 10: 8 8 9 9 9 9 12 19   gamma 12: 8 8 9 9 9 9 11 13
 *     gamma 15: 8 8 10 9 9 10 10 12 gamma 20: 9 8 10 9 10 10 10 11
 * (20 is the flattest; 12 keeps levels 1-5 within 9). gamma_n does not
 * change the iterates (only the sign of the contact indicator matters). eps is lost too: 1e-12, relative. The
 * "enhanced system" (8) is not used: the reconstruction works on (7)
 * directly. Start from zero, as the paper. */
#include "solve/solve.h"

#include <math.h>
#include <string.h>

typedef struct {
    cx_schur *S;          /* borrowed from the session's operator cache */
    const int *dofs;      /* nc: the dofs S is over, the session's: all contact dofs, or
                             for a frictionless run in 3D the normal ones only */
    int nc;
    int normal;           /* frictionless: the session's normal reduction */
    int normal_only;      /* ... which leaves out the tangential dofs (and T's rows) */
    int nv;               /* reduced unknowns: local components = contact dofs */
    int np;               /* points with at least one free component */
    int dt;               /* tangential components per point (dim - 1) */
    int *pt;              /* np: problem point of each reduced point */
    int *tv;              /* dt np: variable of each tangential component, or -1 */
    int *nvar;            /* np: variable of the normal component, or -1 */
    int *rp, *rc;         /* nv + 1 / nnz: rows of the rotation R over contact-dof positions */
    double *rv;           /* nnz */
    double *A;            /* nv^2: R S R' (column-major) */
    double *b;            /* nv: R f_c */
    double *gap;          /* np: initial gap */
    double *sb;           /* np: slip bound (nodal force) */
    double *kp;           /* np: largest diagonal entry of A at the point (step scale) */
    double *xi;           /* nv: reduced displacements of the iterate */
    double *lam;          /* np: contact pressures of the iterate */
    double *r;            /* nv: A xi - b */
    double *uh;           /* nv: the approximation step's displacements */
    double *lh;           /* np: ... and pressures */
    double *ys;           /* nv: y*^ on the displacement rows (tangential part) */
    double *ysl;          /* np: y*^ on the multiplier rows */
    int *free_;           /* nv: free variables of the Newton system */
    double *M;            /* nv^2: the Newton matrix on the free variables */
    double *x;            /* nv: its right-hand side, then solution */
    double *uc;           /* nc: contact-dof displacements */
    double kappa;         /* largest diagonal entry of A */
    double gamma;         /* approximation step (relative), tangential rows */
    double gamma_n;       /* ... multiplier rows */
    int compliance;       /* step: kp holds 1 / max (A^-1)_vv at the point, not max A_vv */
    int seidel;           /* sweep: each point's step sees the points before it moved */
    double eps;           /* stopping tolerance */
    double fscale;        /* load scale for the residual */
} ssstar_state;

static const cx_param ssstar_params[] = {
    {"gamma", CX_PARAM_REAL, 12.0, 1e-6, 1e6, NULL,
     "[M, chosen] approximation step, relative to 1/kappa (a point's largest diagonal entry of A)", 0},
    {"step", CX_PARAM_CHOICE, 0, 0, 1, "diag|compliance",
     "the approximation step's scale per point: gamma / kappa (diag) or gamma x the largest "
     "diagonal entry of A^-1 at the point (compliance: the point's own flexibility)", 0},
    {"sweep", CX_PARAM_CHOICE, 0, 0, 1, "jacobi|seidel",
     "the approximation step over the points: all from the same iterate (jacobi) or one after "
     "another, each from the residual the points before it left (seidel; the paper's "
     "'consecutively' read as a Gauss-Seidel sweep)", 0},
    {"gamma_n", CX_PARAM_REAL, 1.0, 1e-6, 1e6, NULL,
     "[M, chosen] approximation step of the contact multiplier, relative to kappa", 0},
    {"eps", CX_PARAM_REAL, 1e-12, 0, 1, NULL,
     "[M, chosen] stopping rule: relative residual after the approximation step", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

#define SSSTAR_MAX_DENSE 20000

static void ssstar_destroy(void *state)
{
    ssstar_state *st = state;
    void *ptrs[] = {st->pt, st->tv, st->nvar, st->rp, st->rc, st->rv, st->A, st->b, st->gap, st->sb, st->kp,
                    st->xi, st->lam, st->r, st->uh, st->lh, st->ys, st->ysl, st->free_, st->M, st->x,
                    st->uc};
    for (size_t k = 0; k < sizeof ptrs / sizeof ptrs[0]; k++)
        cx_free(ptrs[k]);
    memset(st, 0, sizeof *st);
}

/* The rotation R: one row per non-empty row of N and T, over the positions
 * of the contact dofs. Refuses unless the rows of each point touch only its
 * own dofs, as many as it has rows, orthonormally (a node on a rigid
 * obstacle), so that R is orthogonal and xi = R u_c. */
static int ssstar_rotation(ssstar_state *st, const cx_problem *p, cx_diag *d)
{
    int m = p->m, dt = st->dt, nc = st->nc, status = CX_ENOMEM;
    int *pos = CX_NEW(int, p->n), *owner = CX_NEW(int, nc), *rowvar = CX_NEW(int, m + p->nt);
    int *cnt = CX_NEW(int, m + p->nt), *ptof = CX_NEW(int, m);
    cx_csc Nt = {0}, Tt = {0};
    if (!pos || !owner || !rowvar || !cnt || !ptof || cx_csc_transpose(&Nt, &p->N) ||
        cx_csc_transpose(&Tt, &p->T))
        goto done;
    for (int j = 0; j < p->n; j++)
        pos[j] = -1;
    for (int k = 0; k < nc; k++)
        pos[st->dofs[k]] = k, owner[k] = -1;
    /* rows (normal i -> i, tangential r -> m + r) and their point */
    int nv = 0, np = 0;
    for (int i = 0; i < m; i++) {
        int any = 0;
        for (int a = -1; a < dt; a++) {
            const cx_csc *R = a < 0 ? &Nt : &Tt;
            int row = a < 0 ? i : dt * i + a;
            /* the normal-only reduction: no tangential rows (no force there) */
            cnt[a < 0 ? i : m + row] = a >= 0 && st->normal_only ? 0 : R->p[row + 1] - R->p[row];
            any |= R->p[row + 1] > R->p[row];
        }
        ptof[i] = any ? np++ : -1;
        for (int a = -1; a < dt; a++) {
            int key = a < 0 ? i : m + dt * i + a;
            rowvar[key] = cnt[key] > 0 ? nv++ : -1;
        }
    }
    if (nv != nc) {
        status = cx_diag_set(d, CX_EUNSUPPORTED,
                             "method 'ssstar' needs one contact row per contact dof (%d rows, %d dofs): "
                             "node-on-rigid-obstacle contact only", nv, nc);
        goto done;
    }
    st->nv = nv;
    st->np = np;
    st->pt = CX_NEW(int, np);
    st->tv = CX_NEW(int, dt * np);
    st->nvar = CX_NEW(int, np);
    st->rp = CX_NEW(int, nv + 1);
    size_t nnz = cx_csc_nnz(&p->N) + cx_csc_nnz(&p->T);
    st->rc = CX_NEW(int, nnz);
    st->rv = CX_NEW(double, nnz);
    if (!st->pt || !st->tv || !st->nvar || !st->rp || !st->rc || !st->rv)
        goto done;
    st->rp[0] = 0;
    for (int i = 0; i < m; i++) {
        int k = ptof[i];
        if (k < 0)
            continue;
        st->pt[k] = i;
        for (int a = -1; a < dt; a++) {
            const cx_csc *R = a < 0 ? &Nt : &Tt;
            int row = a < 0 ? i : dt * i + a, v = rowvar[a < 0 ? i : m + row];
            if (a < 0)
                st->nvar[k] = v;
            else
                st->tv[dt * k + a] = v;
            if (v < 0)
                continue;
            int q0 = st->rp[v];
            for (int q = R->p[row]; q < R->p[row + 1]; q++) {
                int c = pos[R->i[q]];
                if (owner[c] >= 0 && owner[c] != k) {
                    status = cx_diag_set(d, CX_EUNSUPPORTED,
                                         "method 'ssstar': contact points %d and %d share a dof "
                                         "(node-on-rigid-obstacle contact only)", st->pt[owner[c]], i);
                    goto done;
                }
                owner[c] = k;
                st->rc[q0 + q - R->p[row]] = c;
                st->rv[q0 + q - R->p[row]] = R->x[q];
            }
            st->rp[v + 1] = q0 + R->p[row + 1] - R->p[row];
        }
    }
    /* orthonormal rows (rows of different points touch disjoint dofs) */
    for (int k = 0; k < np; k++) {
        int vars[3], nvk = 0;
        for (int a = 0; a < dt; a++)
            if (st->tv[dt * k + a] >= 0)
                vars[nvk++] = st->tv[dt * k + a];
        if (st->nvar[k] >= 0)
            vars[nvk++] = st->nvar[k];
        for (int x = 0; x < nvk; x++)
            for (int y = 0; y < nvk; y++) {
                double dot = 0;
                for (int q = st->rp[vars[x]]; q < st->rp[vars[x] + 1]; q++)
                    for (int t = st->rp[vars[y]]; t < st->rp[vars[y] + 1]; t++)
                        if (st->rc[q] == st->rc[t])
                            dot += st->rv[q] * st->rv[t];
                if (fabs(dot - (x == y)) > 1e-10) {
                    status = cx_diag_set(d, CX_EUNSUPPORTED,
                                         "method 'ssstar': the contact rows of point %d are not "
                                         "orthonormal", st->pt[k]);
                    goto done;
                }
            }
    }
    status = CX_OK;
done:
    if (status == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "out of memory");
    cx_free(pos);
    cx_free(owner);
    cx_free(rowvar);
    cx_free(cnt);
    cx_free(ptof);
    cx_csc_clear(&Nt);
    cx_csc_clear(&Tt);
    return status;
}

/* A = R S R', b = R f_c, column by column (x, uc as scratch). */
static void ssstar_reduce(ssstar_state *st, const double *S, const double *fc, int nc)
{
    int nv = st->nv;
    for (int v = 0; v < nv; v++) {
        /* uc = S R' e_v */
        memset(st->uc, 0, sizeof(double) * (size_t)nc);
        for (int q = st->rp[v]; q < st->rp[v + 1]; q++)
            cx_vec_axpy(nc, st->rv[q], S + (size_t)nc * st->rc[q], st->uc);
        for (int w = 0; w < nv; w++) {
            double sum = 0;
            for (int q = st->rp[w]; q < st->rp[w + 1]; q++)
                sum += st->rv[q] * st->uc[st->rc[q]];
            st->A[(size_t)nv * v + w] = sum;
        }
    }
    for (int w = 0; w < nv; w++) {
        double sum = 0;
        for (int q = st->rp[w]; q < st->rp[w + 1]; q++)
            sum += st->rv[q] * fc[st->rc[q]];
        st->b[w] = sum;
    }
}

static int ssstar_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    ssstar_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    const cx_friction_state *fr = cx_session_friction(s);
    st->normal = fr->law == CX_FRICTION_NONE;
    st->dofs = p->cdofs;
    st->nc = p->nc;
    if (st->normal) {   /* which dofs, before anything is factorised */
        int status = cx_session_schur_normal(s, NULL, NULL, &st->dofs, &st->nc, d);
        if (status != CX_OK)
            return status;
    }
    st->normal_only = st->nc != p->nc;
    if (st->nc > SSSTAR_MAX_DENSE)
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "method 'ssstar': %d contact dofs (limit %d); use a coarser level",
                           st->nc, SSSTAR_MAX_DENSE);
    st->dt = p->dim - 1;
    st->gamma = cx_param_get(params, "gamma");
    st->gamma_n = cx_param_get(params, "gamma_n");
    st->compliance = (int)cx_param_get(params, "step") == 1;
    st->seidel = (int)cx_param_get(params, "sweep") == 1;
    st->eps = cx_param_get(params, "eps");
    int status = ssstar_rotation(st, p, d);
    if (status != CX_OK) {
        ssstar_destroy(st);
        return status;
    }
    int nv = st->nv, np = st->np, nc = st->nc;
    size_t nv2 = (size_t)nv * (size_t)nv;
    st->A = CX_NEW(double, nv2 ? nv2 : 1);
    st->M = CX_NEW(double, nv2 ? nv2 : 1);
    st->b = CX_NEW(double, nv);
    st->gap = CX_NEW(double, np);
    st->sb = CX_NEW(double, np);
    st->kp = CX_NEW(double, np);
    st->xi = CX_NEW(double, nv);
    st->lam = CX_NEW(double, np);
    st->r = CX_NEW(double, nv);
    st->uh = CX_NEW(double, nv);
    st->lh = CX_NEW(double, np);
    st->ys = CX_NEW(double, nv);
    st->ysl = CX_NEW(double, np);
    st->free_ = CX_NEW(int, nv);
    st->x = CX_NEW(double, nv);
    st->uc = CX_NEW(double, nc);
    if (!st->A || !st->M || !st->b || !st->gap || !st->sb || !st->kp || !st->xi || !st->lam || !st->r ||
        !st->uh || !st->lh || !st->ys || !st->ysl || !st->free_ || !st->x || !st->uc) {
        ssstar_destroy(st);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    const double *fc;
    int nd = p->nc;
    status = st->normal ? cx_session_schur_normal(s, &st->S, &fc, &st->dofs, &nd, d)
                        : cx_session_schur(s, &st->S, &fc, d);
    if (status == CX_OK && nd != nc)   /* the session's choice cannot change in between */
        status = cx_diag_set(d, CX_EINVAL, "ssstar: reduction onto %d dofs, expected %d", nd, nc);
    if (status != CX_OK) {
        ssstar_destroy(st);
        return status;
    }
    ssstar_reduce(st, cx_schur_matrix(st->S), fc, nc);
    st->kappa = 0;
    for (int v = 0; v < nv; v++)
        st->kappa = fmax(st->kappa, st->A[(size_t)nv * v + v]);
    if (!(st->kappa > 0))
        st->kappa = 1;
    st->fscale = cx_vec_norminf(nv, st->b);
    for (int k = 0; k < np; k++) {
        st->gap[k] = p->g[st->pt[k]];
        st->sb[k] = fr->law == CX_FRICTION_TRESCA ? fr->s[st->pt[k]] : 0.0;
        st->fscale = fmax(st->fscale, st->sb[k]);
        st->kp[k] = 0;
        for (int a = -1; a < st->dt; a++) {
            int v = a < 0 ? st->nvar[k] : st->tv[st->dt * k + a];
            if (v >= 0)
                st->kp[k] = fmax(st->kp[k], st->A[(size_t)nv * v + v]);
        }
        if (!(st->kp[k] > 0))
            st->kp[k] = st->kappa;
    }
    if (st->compliance && nv > 0) {
        /* the local flexibility: the diagonal of A^-1 (one dense Cholesky
         * and a solve with the identity, a few Newton steps' price), so that
         * gamma / kp is gamma times the displacement of the point under a
         * unit force at it with every other contact point free */
        size_t nv2c = (size_t)nv * (size_t)nv;
        double *inv = CX_NEW(double, nv2c);
        if (!inv) {
            ssstar_destroy(st);
            return cx_diag_set(d, CX_ENOMEM, "out of memory");
        }
        memcpy(st->M, st->A, sizeof(double) * nv2c);
        for (int v = 0; v < nv; v++)
            inv[(size_t)nv * v + v] = 1;
        if (cx_dense_cholesky(nv, st->M, NULL) == CX_OK) {
            cx_dense_cholesky_solve(nv, st->M, inv, nv);
            for (int k = 0; k < np; k++) {
                double c = 0;
                for (int a = -1; a < st->dt; a++) {
                    int v = a < 0 ? st->nvar[k] : st->tv[st->dt * k + a];
                    if (v >= 0)
                        c = fmax(c, inv[(size_t)nv * v + v]);
                }
                if (c > 0)
                    st->kp[k] = 1 / c;
            }
        }
        cx_free(inv);
    }
    if (!(st->fscale > 0))
        st->fscale = 1;
    memset(st->xi, 0, sizeof(double) * (size_t)nv);
    memset(st->lam, 0, sizeof(double) * (size_t)np);
    return CX_OK;
}

/* sweep=seidel: r = A x - b with x point k's new displacements (uh) and
 * the later points' old ones (xi), where the next point's step starts. */
static void ssstar_seidel(ssstar_state *st, int k)
{
    for (int a = -1; a < st->dt; a++) {
        int q = a < 0 ? st->nvar[k] : st->tv[st->dt * k + a];
        if (q >= 0 && st->uh[q] != st->xi[q])
            cx_vec_axpy(st->nv, st->uh[q] - st->xi[q], st->A + (size_t)st->nv * q, st->r);
    }
}

/* The approximation step (001 §4, doc/papers.md §1.3) from (xi, lam):
 * uh, lh and y*^ (ys, ysl). r = A xi - b on entry. */
static void ssstar_approximate(ssstar_state *st)
{
    memset(st->ys, 0, sizeof(double) * (size_t)st->nv);
    for (int k = 0; k < st->np; k++) {
        double gt = st->gamma / st->kp[k], gl = st->gamma_n * st->kp[k];
        /* tangential: block soft-thresholding of w = u_T - gt (A u - b)_T */
        double w[2] = {0, 0}, nw = 0;
        for (int a = 0; a < st->dt; a++) {
            int v = st->tv[st->dt * k + a];
            if (v >= 0)
                w[a] = st->xi[v] - gt * st->r[v];
            nw += w[a] * w[a];
        }
        nw = sqrt(nw);
        double shrink = nw > gt * st->sb[k] ? 1 - gt * st->sb[k] / nw : 0;
        for (int a = 0; a < st->dt; a++) {
            int v = st->tv[st->dt * k + a];
            if (v < 0)
                continue;
            st->uh[v] = shrink * w[a];
            st->ys[v] = (w[a] - st->uh[v]) / gt;
        }
        /* normal: a plain gradient step; multiplier: projection onto R+ */
        int v = st->nvar[k];
        if (v < 0) {
            st->lh[k] = st->ysl[k] = 0;
            if (st->seidel)
                ssstar_seidel(st, k);
            continue;
        }
        st->uh[v] = st->xi[v] - gt * (st->r[v] + st->lam[k]);
        double wl = st->lam[k] + gl * (st->xi[v] - st->gap[k]);
        st->lh[k] = wl > 0 ? wl : 0;
        st->ysl[k] = wl < 0 ? wl / gl : 0;
        if (st->seidel)
            ssstar_seidel(st, k);
    }
}

/* |F(y^) + y*^|, dimensionless (the stopping rule). r = A uh - b on entry. */
static double ssstar_residual(const ssstar_state *st)
{
    double L = fmax(st->fscale, cx_vec_norminf(st->np, st->lh)), res = 0;
    for (int k = 0; k < st->np; k++) {
        for (int a = 0; a < st->dt; a++) {
            int v = st->tv[st->dt * k + a];
            if (v >= 0)
                res = fmax(res, fabs(st->r[v] + st->ys[v]) / L);
        }
        int v = st->nvar[k];
        if (v < 0)
            continue;
        res = fmax(res, fabs(st->r[v] + st->lh[k]) / L);
        res = fmax(res, fabs(-(st->uh[v] - st->gap[k]) + st->ysl[k]) * st->kappa / L);
    }
    return res;
}

/* The Newton step (9) with the case rules, from (uh, lh): the new xi, lam. */
static int ssstar_newton(ssstar_state *st, cx_counters *cnt, int iter, cx_diag *d)
{
    int nv = st->nv, dt = st->dt, nf = 0;
    /* fixed values: stick u_T = 0, contact u_N = gap; the rest is free */
    for (int k = 0; k < st->np; k++) {
        double nu = 0;
        for (int a = 0; a < dt; a++) {
            int v = st->tv[dt * k + a];
            if (v >= 0)
                nu += st->uh[v] * st->uh[v];
        }
        for (int a = 0; a < dt; a++) {
            int v = st->tv[dt * k + a];
            if (v < 0)
                continue;
            st->xi[v] = 0;
            if (nu > 0)
                st->free_[nf++] = v;
        }
        int v = st->nvar[k];
        if (v < 0)
            continue;
        st->xi[v] = st->lh[k] > 0 ? st->gap[k] : 0;
        if (!(st->lh[k] > 0))
            st->free_[nf++] = v;
    }
    for (int a = 0; a < nf; a++)
        st->xi[st->free_[a]] = 0;
    /* rhs = b_F - A_FX xi_X - s n (slide);  M = A_FF + G (slide) */
    cx_dense_gemv(nv, nv, 1.0, st->A, st->xi, 0.0, st->r);
    for (int a = 0; a < nf; a++) {
        int v = st->free_[a];
        st->x[a] = st->b[v] - st->r[v];
        for (int c = 0; c < nf; c++)
            st->M[(size_t)nf * c + a] = st->A[(size_t)nv * st->free_[c] + v];
    }
    int a0 = 0;
    for (int k = 0; k < st->np; k++) {
        /* the tangential variables of point k among the free ones come first
         * in its stretch of free_ (same order as above) */
        int ni = 0;
        double u[2], nu = 0;
        for (int a = 0; a < dt; a++) {
            int v = st->tv[dt * k + a];
            if (v < 0)
                continue;
            u[ni] = st->uh[v];
            nu += u[ni] * u[ni];
            ni++;
        }
        nu = sqrt(nu);
        if (nu > 0) {
            double g = st->sb[k] / nu;
            for (int x = 0; x < ni; x++) {
                st->x[a0 + x] -= st->sb[k] * u[x] / nu;
                for (int y = 0; y < ni; y++)
                    st->M[(size_t)nf * (a0 + y) + a0 + x] += g * ((x == y) - u[x] * u[y] / (nu * nu));
            }
            a0 += ni;
        }
        if (st->nvar[k] >= 0 && !(st->lh[k] > 0))
            a0++;
    }
    if (nf > 0) {
        int status = cx_dense_cholesky(nf, st->M, cnt);
        if (status != CX_OK)
            return cx_diag_set(d, status,
                               "ssstar: the Newton matrix (order %d) is not positive definite at "
                               "iteration %d (a body held only by the contact?)", nf, iter);
        cx_dense_cholesky_solve(nf, st->M, st->x, 1);
    }
    for (int a = 0; a < nf; a++)
        st->xi[st->free_[a]] = st->x[a];
    /* pressures: lN = b_N - (A xi)_N on contact points, 0 elsewhere */
    cx_dense_gemv(nv, nv, 1.0, st->A, st->xi, 0.0, st->r);
    for (int k = 0; k < st->np; k++) {
        int v = st->nvar[k];
        st->lam[k] = v >= 0 && st->lh[k] > 0 ? st->b[v] - st->r[v] : 0;
    }
    return CX_OK;
}

/* The iterate from (xi, lam): u_c = R' xi on the contact dofs (a partial
 * iterate: the solver expands u when the run ends), lN = lam,
 * lT = -(A xi - b)_T (the tangential rows of the reduced equilibrium). */
static int ssstar_write(ssstar_state *st, const cx_problem *p, cx_iterate *it)
{
    int dt = st->dt;
    memset(st->uc, 0, sizeof(double) * (size_t)st->nc);
    for (int v = 0; v < st->nv; v++)
        for (int q = st->rp[v]; q < st->rp[v + 1]; q++)
            st->uc[st->rc[q]] += st->rv[q] * st->xi[v];
    cx_dense_gemv(st->nv, st->nv, 1.0, st->A, st->xi, 0.0, st->r);
    cx_vec_axpy(st->nv, -1.0, st->b, st->r);
    memset(it->lN, 0, sizeof(double) * (size_t)p->m);
    memset(it->lT, 0, sizeof(double) * (size_t)p->nt);
    for (int k = 0; k < st->np; k++) {
        int i = st->pt[k];
        it->lN[i] = st->lam[k];
        for (int a = 0; a < dt; a++) {
            int v = st->tv[dt * k + a];
            if (v >= 0)
                it->lT[dt * i + a] = -st->r[v];
        }
    }
    for (int k = 0; k < st->nc; k++)
        it->u[st->dofs[k]] = st->uc[k];
    it->u_partial = st->normal ? CX_PARTIAL_NORMAL : CX_PARTIAL_CONTACT;
    return CX_OK;
}

static int ssstar_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    ssstar_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    int nv = st->nv;

    cx_dense_gemv(nv, nv, 1.0, st->A, st->xi, 0.0, st->r);
    cx_vec_axpy(nv, -1.0, st->b, st->r);
    ssstar_approximate(st);
    cx_dense_gemv(nv, nv, 1.0, st->A, st->uh, 0.0, st->r);
    cx_vec_axpy(nv, -1.0, st->b, st->r);
    it->own = ssstar_residual(st);
    it->inner = 0;
    if (it->own <= st->eps) {
        /* the stopping rule holds: y^ is the answer */
        memcpy(st->xi, st->uh, sizeof(double) * (size_t)nv);
        memcpy(st->lam, st->lh, sizeof(double) * (size_t)st->np);
        it->own_done = 1;
    } else {
        CX_TRY(ssstar_newton(st, cx_session_counters(s), it->iter + 1, d));
        it->inner = 1;   /* Newton steps: the paper's iteration count */
    }
    return ssstar_write(st, p, it);
}

const cx_method cx_method_ssstar = {
    .id = "ssstar",
    .name = "Semismooth* Newton (Tresca, reduced to the contact face)",
    .source = "001 §4",
    .summary = "approximation step (per-point proximal maps) + Newton step on the dense Schur "
               "complement of the contact dofs; gamma and eps chosen (lost in the paper)",
    .supports = CX_FRICTIONLESS | CX_TRESCA | CX_3D,
    .state_size = sizeof(ssstar_state),
    .params = ssstar_params,
    .init = ssstar_init,
    .step = ssstar_step,
    .destroy = ssstar_destroy,
};
