/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The LCP form of paper 003 (lcp.h): the change of variables, the cached
 * full and reduced LCPs, masked solves, the PDAS step and the two-stage
 * driver of the regularised methods. */
#include "solve/lcp.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- the change of variables u = u0 + T v (cached) ------------------------ */

static void lcp_clear(cx_lcp *L)
{
    cx_free(L->S);
    cx_csc_clear(&L->A);
    cx_free(L->Ad);
    cx_free(L->b);
    memset(L, 0, sizeof *L);
}

static void lcp_map_destroy(void *obj)
{
    cx_lcp_map *m = obj;
    if (!m)
        return;
    lcp_clear(&m->full);
    lcp_clear(&m->red);
    cx_csc_clear(&m->T);
    cx_free(m->u0);
    cx_free(m->piv);
    cx_free(m->sidx);
    cx_schur_destroy(&m->schur);
    cx_free(m);
}

/* Pivots: per row the dof of largest |coefficient| that no other row touches. */
static int lcp_pivots(const cx_problem *p, const cx_csc *Nt, int *piv, cx_diag *d)
{
    for (int r = 0; r < p->m; r++) {
        double best = 0;
        piv[r] = -1;
        for (int q = Nt->p[r]; q < Nt->p[r + 1]; q++) {
            int j = Nt->i[q];
            if (p->N.p[j + 1] - p->N.p[j] == 1 && fabs(Nt->x[q]) > best)
                best = fabs(Nt->x[q]), piv[r] = j;
        }
        if (piv[r] < 0)
            return cx_diag_set(d, CX_EUNSUPPORTED,
                               "contact row %d has no dof of its own (rows must be node-to-node or "
                               "node-to-obstacle with distinct nodes)", r);
    }
    return CX_OK;
}

static int lcp_build_map(void **obj, const cx_problem *p, const void *arg, cx_counters *cnt,
                         cx_diag *d)
{
    (void)arg, (void)cnt;
    int n = p->n, m = p->m, st = CX_ENOMEM;
    cx_csc Nt = {0};
    cx_triplet tr = {0};
    double *r = NULL;
    cx_lcp_map *map = CX_NEW(cx_lcp_map, 1);
    *obj = NULL;
    if (!map)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    map->u0 = CX_NEW(double, n);
    map->piv = CX_NEW(int, m);
    map->sidx = CX_NEW(int, m);
    map->full.S = CX_NEW(unsigned char, n);
    map->full.b = CX_NEW(double, n);
    r = CX_NEW(double, n);
    if (!map->u0 || !map->piv || !map->sidx || !map->full.S || !map->full.b || !r ||
        cx_csc_transpose(&Nt, &p->N))
        goto fail;
    if ((st = lcp_pivots(p, &Nt, map->piv, d)))
        goto fail;
    st = CX_ENOMEM;
    if (cx_triplet_init(&tr, n, n, (size_t)n + 2 * cx_csc_nnz(&p->N)))
        goto fail;
    for (int k = 0; k < m; k++)
        map->full.S[map->piv[k]] = 1;
    for (int j = 0; j < n; j++)
        if (!map->full.S[j] && cx_triplet_add(&tr, j, j, 1.0))
            goto fail;
    for (int k = 0; k < m; k++) {
        int pv = map->piv[k];
        double npv = cx_csc_get(&p->N, k, pv);
        map->u0[pv] = p->g[k] / npv;
        if (cx_triplet_add(&tr, pv, pv, -1.0 / npv))
            goto fail;
        for (int q = Nt.p[k]; q < Nt.p[k + 1]; q++)
            if (Nt.i[q] != pv && cx_triplet_add(&tr, pv, Nt.i[q], -Nt.x[q] / npv))
                goto fail;
    }
    /* A = T' K T in one pass (cx_csc_congruence): K T is never stored */
    if (cx_csc_from_triplet(&map->T, &tr) || cx_csc_congruence(&map->full.A, &p->K, &map->T))
        goto fail;
    /* b = T' (f - K u0) */
    cx_csc_gemv(&p->K, -1.0, map->u0, 0.0, r);
    cx_vec_axpy(n, 1.0, p->f, r);
    cx_csc_gemv_t(&map->T, 1.0, r, 0.0, map->full.b);
    map->full.n = n;
    map->full.nc = m;
    for (int j = 0, k = 0; j < n; j++) {
        if (map->full.S[j])
            map->sidx[k++] = j;
        double a = cx_csc_get(&map->full.A, j, j);
        if (a > map->full.amax)
            map->full.amax = a;
    }
    cx_csc_clear(&Nt), cx_triplet_clear(&tr), cx_free(r);
    *obj = map;
    return CX_OK;
fail:
    cx_csc_clear(&Nt), cx_triplet_clear(&tr), cx_free(r);
    lcp_map_destroy(map);
    return st == CX_ENOMEM ? cx_diag_set(d, CX_ENOMEM, "out of memory building the LCP") : st;
}

int cx_lcp_get(cx_session *s, cx_lcp_map **map, cx_diag *d)
{
    if (cx_session_friction(s)->law != CX_FRICTION_NONE)
        return cx_diag_set(d, CX_EUNSUPPORTED, "the LCP methods of paper 003 are frictionless");
    void *obj = NULL;
    CX_TRY(cx_session_cache_get(s, "lcp003:full", lcp_build_map, NULL, lcp_map_destroy, &obj, d));
    *map = obj;
    return CX_OK;
}

/* The reduced LCP lives inside the map; the cache entry only counts and
 * keys its construction (destroyed with the map). */
static int lcp_build_reduced(void **obj, const cx_problem *p, const void *arg, cx_counters *cnt,
                             cx_diag *d)
{
    (void)p;
    cx_lcp_map *map = (cx_lcp_map *)arg;
    cx_lcp *R = &map->red;
    int nc = map->full.nc;
    CX_TRY(cx_schur_create(&map->schur, &map->full.A, map->sidx, nc, cnt, d));
    R->n = R->nc = nc;
    R->dense = 1;
    R->S = CX_NEW(unsigned char, nc);
    R->Ad = CX_NEW(double, (size_t)nc * nc);
    R->b = CX_NEW(double, nc);
    if (!R->S || !R->Ad || !R->b) {
        lcp_clear(R);
        cx_schur_destroy(&map->schur);
        return cx_diag_set(d, CX_ENOMEM, "out of memory (reduced LCP of order %d)", nc);
    }
    memcpy(R->Ad, cx_schur_matrix(map->schur), sizeof(double) * (size_t)nc * nc);
    CX_TRY(cx_schur_condense(map->schur, map->full.b, R->b));
    for (int k = 0; k < nc; k++) {
        R->S[k] = 1;
        if (R->Ad[(size_t)nc * k + k] > R->amax)
            R->amax = R->Ad[(size_t)nc * k + k];
    }
    *obj = map;   /* a marker: the data is in the map */
    return CX_OK;
}

static void lcp_reduced_nothing(void *obj) { (void)obj; }

int cx_lcp_get_reduced(cx_session *s, cx_lcp_map **map, cx_diag *d)
{
    CX_TRY(cx_lcp_get(s, map, d));
    void *obj = NULL;
    return cx_session_cache_get(s, "lcp003:schur", lcp_build_reduced, *map, lcp_reduced_nothing,
                                &obj, d);
}

void cx_lcp_apply(const cx_lcp *L, const double *v, double *y)
{
    if (L->dense)
        cx_dense_gemv(L->n, L->n, 1.0, L->Ad, v, 0.0, y);
    else
        cx_csc_gemv(&L->A, 1.0, v, 0.0, y);
}

/* cx_lcp_result with A v given (Av, NULL: computed row by row): the
 * multipliers are then read from it instead of one row of A each. */
static int lcp_result(cx_lcp_map *map, int reduced, const double *v, const double *Av, double *work,
                      const cx_problem *p, double *u, double *lN);

int cx_lcp_result(cx_lcp_map *map, int reduced, const double *v, double *work,
                  const cx_problem *p, double *u, double *lN)
{
    return lcp_result(map, reduced, v, NULL, work, p, u, lN);
}

static int lcp_result(cx_lcp_map *map, int reduced, const double *v, const double *Av, double *work,
                      const cx_problem *p, double *u, double *lN)
{
    const double *vf = v;
    int n = map->full.n;
    if (reduced) {
        CX_TRY(cx_schur_expand(map->schur, map->full.b, v, work));
        vf = work;
    }
    memcpy(u, map->u0, sizeof(double) * (size_t)n);
    cx_csc_gemv(&map->T, 1.0, vf, 1.0, u);
    /* lN_r = (A v - b)_p(r): one row of A per contact row */
    if (Av && !reduced) {
        for (int k = 0; k < p->m; k++)
            lN[k] = Av[map->piv[k]] - map->full.b[map->piv[k]];
        return CX_OK;
    }
    for (int k = 0; k < p->m; k++) {
        int j = map->piv[k];
        double s = -map->full.b[j];
        for (int q = map->full.A.p[j]; q < map->full.A.p[j + 1]; q++)   /* A symmetric */
            s += map->full.A.x[q] * vf[map->full.A.i[q]];
        lN[k] = s;
    }
    return CX_OK;
}

/* ---- masked solves ---------------------------------------------------------- */

int cx_lcp_solver_init(cx_lcp_solver *s, const cx_lcp *L, cx_counters *cnt, cx_diag *d)
{
    memset(s, 0, sizeof *s);
    s->L = L;
    s->cnt = cnt;
    if (L->dense) {
        s->Md = CX_NEW(double, (size_t)L->n * L->n);
        return s->Md ? CX_OK : cx_diag_set(d, CX_ENOMEM, "out of memory (dense %d x %d)", L->n, L->n);
    }
    /* the masked matrix has A's pattern: borrowed, only the values are its own */
    s->M.nrow = L->A.nrow, s->M.ncol = L->A.ncol;
    s->M.p = L->A.p, s->M.i = L->A.i;
    if (!(s->M.x = CX_NEW(double, cx_csc_nnz(&L->A) + 1)))
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    /* analysed on its first use: a solver whose factors are all ldlmod's
     * (updates) never needs it */
    return cx_fact_create(&s->F, CX_FACT_CHOLESKY, cnt, d);
}

int cx_lcp_solver_updates(cx_lcp_solver *s, int update_max, cx_diag *d)
{
    if (s->L->dense || update_max <= 0)
        return CX_OK;
    s->update_max = update_max;
    if (!s->fkeep && !(s->fkeep = CX_NEW(unsigned char, s->L->n)))
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    return CX_OK;
}

void cx_lcp_solver_clear(cx_lcp_solver *s)
{
    cx_free(s->pmask);
    cx_free(s->pwork);
    cx_ldlmod_destroy(&s->ldl);
    cx_free(s->fkeep);
    cx_fact_destroy(&s->F);
    cx_free(s->M.x);   /* M.p, M.i are A's */
    cx_free(s->Md);
    memset(s, 0, sizeof *s);
}

static int lcp_refactor(cx_lcp_solver *s, double eps, const unsigned char *zero, cx_diag *d);

/* Whether the masked system (eps, zero) can be solved by CG with like's
 * factor (cx_lcp_solver.pre): like's factor is valid, of the same LCP,
 * its mask differs in few unknowns, and it has no pivot near its eps (a
 * pivot of order eps is a motion the mask leaves free: the unregularised
 * system is singular there, and the factorisation's fallback decides). */
static int lcp_pcg_ok(cx_lcp_solver *s, double eps, const unsigned char *zero)
{
    const cx_lcp_solver *o = s->like;
    if (!o || o->L != s->L || !o->ldl || !o->fvalid || o->feps < eps)
        return 0;
    int n = s->L->n, k = 0;
    for (int i = 0; i < n && k <= CX_LCP_PCG_ROWS; i++)
        k += o->fkeep[i] != !(zero && zero[i]);
    if (k > CX_LCP_PCG_ROWS)
        return 0;
    if (cx_ldlmod_min_pivot(o->ldl) <= 1e3 * o->feps)
        return 0;
    if (!s->pmask && !(s->pmask = CX_NEW(unsigned char, n)))
        return 0;
    if (!s->pwork && !(s->pwork = CX_NEW(double, 5 * (size_t)n)))
        return 0;
    for (int i = 0; i < n; i++)
        s->pmask[i] = zero && zero[i];
    return 1;
}

/* y = M x for the masked M of (s->peps, s->pmask); t: n doubles */
static void lcp_pcg_apply(const cx_lcp_solver *s, const double *x, double *y, double *t)
{
    const cx_lcp *L = s->L;
    for (int i = 0; i < L->n; i++)
        t[i] = s->pmask[i] ? 0 : x[i];
    cx_csc_gemv(&L->A, 1.0, t, 0.0, y);
    for (int i = 0; i < L->n; i++)
        y[i] = s->pmask[i] ? x[i] : y[i] + s->peps * x[i];
}

/* x = M^-1 b by CG preconditioned with like's factor, to roundoff:
 * ||b - M x|| <= 1e-14 (||b|| + amax ||x||), the accuracy of a direct
 * solve. CX_ENUMERIC if not reached in CX_LCP_PCG_MAXIT steps. */
static int lcp_pcg_solve(cx_lcp_solver *s, const double *b, double *x, cx_diag *d)
{
    int n = s->L->n;
    double *r = s->pwork, *z = r + n, *p = z + n, *q = p + n, *t = q + n;
    double amax = s->L->amax + s->peps, nb = cx_vec_norminf(n, b);
    memset(x, 0, sizeof(double) * (size_t)n);
    memcpy(r, b, sizeof(double) * (size_t)n);
    if (nb == 0)
        return CX_OK;
    CX_TRY(cx_ldlmod_solve(s->like->ldl, r, z, d));
    memcpy(p, z, sizeof(double) * (size_t)n);
    double rz = cx_vec_dot(n, r, z);
    s->pcg_solves++;
    for (int k = 0; k < CX_LCP_PCG_MAXIT; k++) {
        lcp_pcg_apply(s, p, q, t);
        double pq = cx_vec_dot(n, p, q);
        if (!(pq > 0))
            break;
        double a = rz / pq;
        cx_vec_axpy(n, a, p, x);
        cx_vec_axpy(n, -a, q, r);
        s->pcg_iters++;
        /* the true residual at the end: the recursion's drifts below roundoff */
        if (cx_vec_norminf(n, r) <= 1e-14 * (nb + amax * cx_vec_norminf(n, x))) {
            lcp_pcg_apply(s, x, q, t);
            for (int i = 0; i < n; i++)
                r[i] = b[i] - q[i];
            if (cx_vec_norminf(n, r) <= 1e-14 * (nb + amax * cx_vec_norminf(n, x)))
                return CX_OK;
        }
        CX_TRY(cx_ldlmod_solve(s->like->ldl, r, z, d));
        double rz1 = cx_vec_dot(n, r, z);
        for (int i = 0; i < n; i++)
            p[i] = z[i] + rz1 / rz * p[i];
        rz = rz1;
    }
    return cx_diag_set(d, CX_ENUMERIC, "CG with the previous factor did not reach roundoff");
}

/* The masked factor by row changes from the last one, or anew (update_max). */
static int lcp_factor_mod(cx_lcp_solver *s, double eps, const unsigned char *zero, cx_diag *d)
{
    const cx_lcp *L = s->L;
    int n = L->n;
    double amax = fmax(1.0, L->amax + eps);
    s->pre = 0;
    if (s->ldl && s->fvalid && s->feps == eps) {
        int nch = 0;
        for (int i = 0; i < n; i++)
            nch += s->fkeep[i] != !(zero && zero[i]);
        int update = nch <= s->update_max;
        if (update && s->model && nch > 0) {
            /* the rows' work against a new factor's (CX_LCP_UPDATE_RATIO) */
            double budget = CX_LCP_UPDATE_RATIO * cx_ldlmod_factor_nnz(s->ldl), cost = 0;
            for (int i = 0; i < n && cost <= budget; i++)
                if (s->fkeep[i] != !(zero && zero[i]))
                    cost += cx_ldlmod_row_cost(s->ldl, i, &L->A, s->fkeep);
            update = cost <= budget;
        }
        if (update) {
            int st = CX_OK;
            /* deletes first: each add then sees only the rows that stay */
            for (int i = 0; i < n && st == CX_OK; i++)
                if (s->fkeep[i] && zero && zero[i]) {
                    st = cx_ldlmod_delete_row(s->ldl, i, &L->A, s->fkeep, d);
                    s->fkeep[i] = 0;
                }
            for (int i = 0; i < n && st == CX_OK; i++)
                if (!s->fkeep[i] && !(zero && zero[i])) {
                    st = cx_ldlmod_add(s->ldl, i, &L->A, s->fkeep, eps, d);
                    s->fkeep[i] = 1;
                }
            if (st == CX_OK)
                st = cx_ldlmod_check_updated(s->ldl, amax, d);
            if (st == CX_OK)
                return CX_OK;
            if (st != CX_ENUMERIC)
                return st;
            /* no longer definite to working precision after the updates: a
             * new factorisation decides (it reports the same singularity or
             * recovers from the rounding of the updates) */
        }
    }
    if (lcp_pcg_ok(s, eps, zero)) {
        s->pre = 1;
        s->peps = eps;
        return CX_OK;
    }
    return lcp_refactor(s, eps, zero, d);
}

/* A new masked factor (ldlmod), the analysis kept or like's copied. */
static int lcp_refactor(cx_lcp_solver *s, double eps, const unsigned char *zero, cx_diag *d)
{
    const cx_lcp *L = s->L;
    int n = L->n;
    double amax = fmax(1.0, L->amax + eps);
    s->pre = 0;
    s->fvalid = 0;
    /* the mask as fkeep (1: A's row) goes to ldlmod, which gathers the
     * masked values itself: s->M is not formed on this path */
    for (int i = 0; i < n; i++)
        s->fkeep[i] = !(zero && zero[i]);
    if (!s->ldl) {
        const cx_ldlmod *like = s->like && s->like->L == s->L ? s->like->ldl : NULL;
        CX_TRY(cx_ldlmod_create_masked(&s->ldl, &L->A, s->fkeep, eps, like, s->cnt, d));
        CX_TRY(cx_ldlmod_check(s->ldl, amax, d));
    } else {
        CX_TRY(cx_ldlmod_refactor_masked(s->ldl, &L->A, s->fkeep, eps, d));
    }
    s->feps = eps;
    s->fvalid = 1;
    return CX_OK;
}

int cx_lcp_factor(cx_lcp_solver *s, double eps, const unsigned char *zero, const double *dadd,
                  cx_diag *d)
{
    const cx_lcp *L = s->L;
    int n = L->n;
    if (L->dense) {
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                size_t q = (size_t)n * j + i;
                int z = zero && (zero[i] || zero[j]);
                s->Md[q] = z ? (i == j) : L->Ad[q] + (i == j ? eps + (dadd ? dadd[j] : 0) : 0);
            }
        if (cx_dense_cholesky(n, s->Md, s->cnt) != CX_OK)
            return cx_diag_set(d, CX_ENUMERIC, "the (masked) LCP matrix of order %d is singular", n);
        return CX_OK;
    }
    if (s->update_max > 0 && !dadd)
        return lcp_factor_mod(s, eps, zero, d);
    s->fvalid = 0;
    cx_lcp_factor_values(s, eps, zero, dadd);
    if (!s->analysed) {
        CX_TRY(cx_fact_analyze(s->F, &s->M, d));
        s->analysed = 1;
    }
    return cx_fact_factorize(s->F, &s->M, d);
}

void cx_lcp_factor_values(cx_lcp_solver *s, double eps, const unsigned char *zero, const double *dadd)
{
    const cx_lcp *L = s->L;
    for (int j = 0; j < L->n; j++)
        for (int q = L->A.p[j]; q < L->A.p[j + 1]; q++) {
            int i = L->A.i[q];
            int z = zero && (zero[i] || zero[j]);
            s->M.x[q] = z ? (i == j) : L->A.x[q] + (i == j ? eps + (dadd ? dadd[j] : 0) : 0);
        }
}

int cx_lcp_solve(cx_lcp_solver *s, const unsigned char *zero, const double *rhs, double *x,
                 double *work, cx_diag *d)
{
    int n = s->L->n;
    for (int i = 0; i < n; i++)
        work[i] = zero && zero[i] ? 0 : rhs[i];
    if (s->L->dense) {
        cx_dense_cholesky_solve(n, s->Md, work, 1);
        if (s->cnt)
            s->cnt->solves++;
        memcpy(x, work, sizeof(double) * (size_t)n);
    } else if (s->update_max > 0 && s->pre) {
        int st = lcp_pcg_solve(s, work, x, d);
        if (st == CX_ENUMERIC) {
            /* CG did not converge: factorise after all (the masked rhs in
             * work is intact: CG reads it only) */
            CX_TRY(lcp_refactor(s, s->peps, s->pmask, d));
            st = cx_ldlmod_solve(s->ldl, work, x, d);
        }
        CX_TRY(st);
    } else if (s->update_max > 0 && s->fvalid) {
        CX_TRY(cx_ldlmod_solve(s->ldl, work, x, d));
    } else {
        CX_TRY(cx_fact_solve(s->F, work, x, d));
    }
    for (int i = 0; zero && i < n; i++)
        if (zero[i])
            x[i] = 0;
    return CX_OK;
}

/* Factorise on the set act and move v to the solution of the masked system
 * (lam from it); shared by the plain and the damped step. */
/* Av (n, or NULL): A v on entry, A v at the new v on exit. Given, the
 * step takes one product with A (the new v's) instead of two: the entry's
 * is corrected by the columns of the unknowns the set zeroes. */
static int pdas_solve_set(cx_lcp_solver *s, double eps, double *v, double *lam,
                          const unsigned char *act, cx_pdas_guard *g, double *work, double *Av,
                          cx_diag *d)
{
    const cx_lcp *L = s->L;
    int n = L->n;
    double *r = work + n;
    for (int i = 0; i < n; i++)
        if (act[i] && v[i] != 0) {
            if (Av && !L->dense)
                for (int q = L->A.p[i]; q < L->A.p[i + 1]; q++)
                    Av[L->A.i[q]] -= L->A.x[q] * v[i];
            v[i] = 0;
        }
    if (Av && L->dense)
        cx_lcp_apply(L, v, Av);
    for (int fallback = 0;; fallback = 1) {
        int st = cx_lcp_factor(s, eps, act, NULL, d);
        /* the correction from the current v (v = 0 on the active set):
         * where the system is singular the free motion keeps its value */
        if (st == CX_OK) {
            if (Av)
                memcpy(r, Av, sizeof(double) * (size_t)n);
            else
                cx_lcp_apply(L, v, r);
            for (int i = 0; i < n; i++)
                r[i] = L->b[i] - r[i] - eps * v[i];
            st = cx_lcp_solve(s, act, r, r, work, d);   /* CG's fallback can find it singular */
        }
        if (st == CX_ENUMERIC && !fallback && eps == 0 && g->eps_fallback > 0) {
            /* a motion the set leaves free (a brick between open head
             * joints slides): the consistent singular system, nearly its
             * minimum-norm solution */
            eps = g->eps_fallback;
            g->fallbacks++;
            continue;
        }
        CX_TRY(st);
        break;
    }
    cx_vec_axpy(n, 1.0, r, v);
    double *Avn = Av ? Av : work;
    cx_lcp_apply(L, v, Avn);
    for (int i = 0; i < n; i++)
        lam[i] = act[i] ? Avn[i] + eps * v[i] - L->b[i] : 0;
    return CX_OK;
}

/* ---- PDAS step -------------------------------------------------------------- */

/* The first set {i in S : lam_i - c v_i > 0} from a start (v, lam). With
 * g->ties_to_v (the projection's start) an index within roundoff of the
 * switch takes the start's side (active where v_i = 0): the degenerate
 * joints (closed, without force) keep the regularised solution's side,
 * which the rounding of lam would otherwise decide. */
static void pdas_first_set(const cx_lcp *L, double c, const double *v, const double *lam,
                           const cx_pdas_guard *g, unsigned char *act)
{
    double tol = g->ties_to_v
                     ? CX_PDAS_ROUNDOFF * (cx_vec_norminf(L->n, lam) + c * cx_vec_norminf(L->n, v))
                     : 0;
    for (int i = 0; i < L->n; i++) {
        double t = lam[i] - c * v[i];
        act[i] = L->S[i] && (t > tol || (g->ties_to_v && t >= -tol && v[i] == 0));
    }
}

int cx_lcp_pdas_step(cx_lcp_solver *s, double eps, double c, double *v, double *lam,
                     unsigned char *act, cx_pdas_guard *g, int *same, double *work, cx_diag *d)
{
    const cx_lcp *L = s->L;
    int n = L->n;
    *same = 0;
    if (act[0] == 2) {
        pdas_first_set(L, c, v, lam, g, act);
        g->best = n + 1, g->tries = CX_PDAS_TRIES;
        g->Av_valid = 0;
    } else {
        /* infeasible: active with lam < 0, inactive with v < 0 (to roundoff) */
        double vs = cx_vec_norminf(n, v), ls = cx_vec_norminf(n, lam), tol = CX_PDAS_ROUNDOFF;
        int ninf = 0, last = -1;
        for (int i = 0; i < n; i++)
            if (L->S[i] && (act[i] ? lam[i] < -tol * ls : v[i] < -tol * vs))
                ninf++, last = i;
        if (ninf == 0) {
            *same = 1;
            return CX_OK;
        }
        /* Judice & Pires: block pivots while the infeasibilities fall (or for
         * a few tries), else Murty's single pivot on the last one, which
         * terminates for a P-matrix */
        int block = 1;
        if (ninf < g->best)
            g->best = ninf, g->tries = CX_PDAS_TRIES;
        else if (g->tries > 0)
            g->tries--;
        else
            block = 0, g->single++;
        for (int i = 0; i < n; i++)
            if (L->S[i] && (block ? (act[i] ? lam[i] < -tol * ls : v[i] < -tol * vs) : i == last))
                act[i] = !act[i];
    }
    if (g->Av && !g->Av_valid) {
        cx_lcp_apply(L, v, g->Av);
        g->Av_valid = 1;
    }
    int st = pdas_solve_set(s, eps, v, lam, act, g, work, g->Av, d);
    if (st != CX_OK)
        g->Av_valid = 0;
    return st;
}

/* ---- damped PDAS step ------------------------------------------------------- */

/* ||F(v + alpha (vn - v))||^2 (lcp.h) from A v and A (vn - v). */
static double pdas_merit(const cx_lcp *L, double eps, double c, const double *v, const double *vn,
                         const double *Av, const double *Ad, double alpha)
{
    double th = 0;
    for (int i = 0; i < L->n; i++) {
        double vi = v[i] + alpha * (vn[i] - v[i]);
        double li = Av[i] + alpha * Ad[i] + eps * vi - L->b[i];
        double f = L->S[i] ? fmin(vi, li / c) : li / c;
        th += f * f;
    }
    return th;
}

/* F(v) = 0 to roundoff: v solves the LCP. Shortened steps can end there,
 * at a kink of F (a degenerate joint), where the kept Newton point lies
 * beyond the kink (running bond 1/225: stuck at the regularised solution,
 * kkt 2.5e-8, until the stall rule). lam: on S at v; Av = A v. */
static int pdas_solved(const cx_lcp *L, double eps, double c, const double *v, const double *lam,
                       const double *Av)
{
    double f = 0;
    for (int i = 0; i < L->n; i++)
        f = fmax(f, fabs(L->S[i] ? fmin(v[i], lam[i] / c) : (Av[i] + eps * v[i] - L->b[i]) / c));
    return f <= CX_PDAS_ROUNDOFF * (cx_vec_norminf(L->n, v) + cx_vec_norminf(L->n, lam) / c);
}

int cx_lcp_pdas_search_step(cx_lcp_solver *s, double eps, double c, double *v, double *lam,
                            unsigned char *act, cx_pdas_search *ls, cx_pdas_guard *g, int *same,
                            double *work, cx_diag *d)
{
    const cx_lcp *L = s->L;
    int n = L->n, first = ls->alpha == 0, changed = 0;
    *same = 0;
    /* the set at v (A v kept from the last step while valid) */
    if (first || !ls->Av_valid)
        cx_lcp_apply(L, v, ls->Av);
    ls->Av_valid = 0;
    for (int i = 0; i < n; i++)
        lam[i] = L->S[i] ? ls->Av[i] + eps * v[i] - L->b[i] : 0;
    if (first) {
        pdas_first_set(L, c, v, lam, g, act);
    } else {
        double tol = CX_PDAS_ROUNDOFF * (cx_vec_norminf(n, lam) + c * cx_vec_norminf(n, v));
        for (int i = 0; i < n; i++) {
            if (!L->S[i])
                continue;
            double t = lam[i] - c * v[i];
            unsigned char a = t > tol ? 1 : t < -tol ? 0 : act[i];
            changed += a != act[i];
            act[i] = a;
        }
    }
    if (!first && changed == 0 && (ls->alpha == 1 || pdas_solved(L, eps, c, v, lam, ls->Av))) {
        *same = 1;
        for (int i = 0; i < n; i++)
            lam[i] = act[i] ? lam[i] : 0;
        return CX_OK;
    }
    /* the Newton point on the set (kept while the set is) */
    if (first || changed) {
        memcpy(ls->vn, v, sizeof(double) * (size_t)n);
        memcpy(ls->Avn, ls->Av, sizeof(double) * (size_t)n);
        CX_TRY(pdas_solve_set(s, eps, ls->vn, work + 2 * n, act, g, work, ls->Avn, d));
    }
    for (int i = 0; i < n; i++)
        ls->Ad[i] = ls->Avn[i] - ls->Av[i];
    /* Armijo on ||F||^2 */
    double th0 = pdas_merit(L, eps, c, v, ls->vn, ls->Av, ls->Ad, 0), alpha = 1, th = th0;
    double ref = th0;
    for (int k = 0; k < ls->memory && k < ls->steps; k++)
        ref = fmax(ref, ls->hist[(ls->steps - 1 - k) % CX_PDAS_MEMORY]);
    ls->hist[ls->steps++ % CX_PDAS_MEMORY] = th0;
    int k = 0;
    for (; !first && k < CX_PDAS_HALVINGS; k++, alpha *= 0.5)
        if ((th = pdas_merit(L, eps, c, v, ls->vn, ls->Av, ls->Ad, alpha)) <= ref - 1e-4 * alpha * th0)
            break;
    if (k == CX_PDAS_HALVINGS) {
        /* no descent along the Newton direction: v sits on a kink of F (an
         * index with v_i = lam_i / c), where the set's derivative is not
         * F's; the full step (plain PDAS) leaves it (laminae 1/20, reduced:
         * stuck at a wrong set with kkt 3e-3 without it) */
        alpha = 1;
        th = pdas_merit(L, eps, c, v, ls->vn, ls->Av, ls->Ad, alpha);
    }
    if (alpha < 1)
        ls->short_steps++;
    for (int i = 0; i < n; i++) {
        v[i] += alpha * (ls->vn[i] - v[i]);
        ls->Av[i] += alpha * ls->Ad[i];
        lam[i] = L->S[i] ? ls->Av[i] + eps * v[i] - L->b[i] : 0;
    }
    ls->alpha = alpha;
    ls->merit = sqrt(th);
    ls->Av_valid = 1;
    return CX_OK;
}

int cx_lcp_pdas_resolve(cx_lcp_solver *s, double eps, double *v, double *lam,
                        const unsigned char *act, double *work, cx_diag *d)
{
    const cx_lcp *L = s->L;
    CX_TRY(cx_lcp_factor(s, eps, act, NULL, d));
    CX_TRY(cx_lcp_solve(s, act, L->b, v, work, d));
    cx_lcp_apply(L, v, work);
    for (int i = 0; i < L->n; i++)
        lam[i] = act[i] ? work[i] + eps * v[i] - L->b[i] : 0;
    return CX_OK;
}

/* ---- the two-stage driver ----------------------------------------------------- */

int cx_lcp_run_init(cx_lcp_run *r, cx_session *s, const cx_param_values *params, int reduced,
                    cx_diag *d)
{
    memset(r, 0, sizeof *r);
    if (reduced)
        CX_TRY(cx_lcp_get_reduced(s, &r->map, d));
    else
        CX_TRY(cx_lcp_get(s, &r->map, d));
    r->reduced = reduced;
    r->L = reduced ? &r->map->red : &r->map->full;
    double scale = r->L->amax > 0 ? r->L->amax : 1;
    /* the regularised methods' eps (pdpc has none) */
    int k = cx_param_find(params, reduced ? "schur_eps" : "eps");
    r->eps = k >= 0 ? params->num[k] * scale : 0;
    r->c = cx_param_get(params, "tau") * scale;
    r->project = cx_param_get(params, "project") != 0;
    r->search = cx_param_get(params, "search") != 0;
    r->guard.eps_fallback = CX_PDAS_EPS_FALLBACK * scale;
    /* a reduced run's projection works on the full LCP (stage_done) */
    int nmax = r->map->full.n;
    r->v = CX_NEW(double, nmax);
    r->lam = CX_NEW(double, nmax);
    r->work = CX_NEW(double, 4 * (size_t)nmax);
    r->act = CX_NEW(unsigned char, nmax);
    r->ls.Av = CX_NEW(double, nmax);
    r->ls.Ad = CX_NEW(double, nmax);
    r->ls.vn = CX_NEW(double, nmax);
    r->ls.Avn = CX_NEW(double, nmax);
    r->guard.Av = CX_NEW(double, nmax);
    if (!r->v || !r->lam || !r->work || !r->act || !r->ls.Av || !r->ls.Ad || !r->ls.vn || !r->ls.Avn ||
        !r->guard.Av) {
        cx_lcp_run_clear(r);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    if (r->project) {
        int st = cx_lcp_solver_init(&r->proj, &r->map->full, cx_session_counters(s), d);
        if (st) {
            cx_lcp_run_clear(r);
            return st;
        }
    }
    return CX_OK;
}

void cx_lcp_run_clear(cx_lcp_run *r)
{
    cx_lcp_solver_clear(&r->proj);
    cx_free(r->v);
    cx_free(r->lam);
    cx_free(r->work);
    cx_free(r->act);
    cx_free(r->ls.Av), cx_free(r->ls.Ad), cx_free(r->ls.vn), cx_free(r->ls.Avn);
    cx_free(r->guard.Av);
    memset(r, 0, sizeof *r);
}

int cx_lcp_run_stage_done(cx_lcp_run *r, cx_iterate *it, cx_diag *d)
{
    if (!r->project) {
        r->stage = 2;
        it->own_done = 1;
        return CX_OK;
    }
    r->stage = 1;
    if (r->reduced) {
        /* the projection of a reduced run works on the full LCP: the same
         * equations, a sparse factorisation in place of a dense one of
         * order n_c, and no rounding of the dense condensation */
        const cx_lcp *F = &r->map->full;
        int st = cx_schur_expand(r->map->schur, F->b, r->v, r->work);
        if (st != CX_OK)
            return cx_diag_set(d, st, "expanding the reduced solution for the projection failed");
        memcpy(r->v, r->work, sizeof(double) * (size_t)F->n);
        double scale = (F->amax > 0 ? F->amax : 1) / (r->L->amax > 0 ? r->L->amax : 1);
        r->c *= scale;
        r->guard.eps_fallback *= scale;
        r->L = F;
        r->reduced = 0;
    }
    /* lam from the current v on the constrained unknowns: the PDAS start of
     * the projection (003 §4) */
    cx_lcp_apply(r->L, r->v, r->work);
    for (int i = 0; i < r->L->n; i++) {
        r->lam[i] = r->L->S[i] ? r->work[i] - r->L->b[i] : 0;
        r->act[i] = 2;   /* no previous set */
    }
    r->ls.alpha = 0;
    r->ls.steps = 0;
    r->ls.Av_valid = 0;
    r->guard.Av_valid = 0;
    r->guard.ties_to_v = 1;
    /* nonmonotone: near the solution the full PDAS steps of the projection
     * may raise the residual for a step or two */
    r->ls.memory = CX_PDAS_PROJ_MEMORY;
    return CX_OK;
}

int cx_lcp_run_pdas_step(cx_lcp_run *r, cx_lcp_solver *solver, double eps, int *same, cx_diag *d)
{
    if (r->search)
        return cx_lcp_pdas_search_step(solver, eps, r->c, r->v, r->lam, r->act, &r->ls, &r->guard,
                                       same, r->work, d);
    return cx_lcp_pdas_step(solver, eps, r->c, r->v, r->lam, r->act, &r->guard, same, r->work, d);
}

int cx_lcp_run_project(cx_lcp_run *r, cx_session *s, cx_iterate *it, cx_diag *d)
{
    int same = 0;
    CX_TRY(cx_lcp_run_pdas_step(r, &r->proj, 0.0, &same, d));
    if (same) {
        r->stage = 2;
        it->own_done = 1;
        it->own = r->proj_iters;
        return CX_OK;
    }
    r->proj_iters++;
    it->inner = 1;
    it->own = r->proj_iters;
    return cx_lcp_run_publish(r, s, it);
}

int cx_lcp_run_publish(cx_lcp_run *r, cx_session *s, cx_iterate *it)
{
    const cx_problem *p = cx_session_problem(s);
    /* A v of the last PDAS step when it is of this v (one product fewer
     * per published iterate) */
    const double *Av = r->ls.Av_valid ? r->ls.Av : r->guard.Av_valid ? r->guard.Av : NULL;
    return lcp_result(r->map, r->reduced, r->v, Av, r->work + 2 * r->L->n, p, it->u, it->lN);
}
