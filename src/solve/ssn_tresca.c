/* SPDX-License-Identifier: GPL-3.0-or-later */
/* ssn-tresca — semismooth Newton / primal-dual active set on the saddle-point
 * system, paper 000 §4.2 (Algorithm ActiveSetTresca).
 *
 * Solves frictionless contact and Tresca friction, 2D and 3D.
 * Each iteration predicts the active sets from the natural maps (000 (15),
 * (18), (19)): contact where lN + rho (N u - g) > 0; stick where
 * |lT + rho T u| <= s, slip+/slip- beyond; and solves the mixed problem
 * with u_N = g on the contact set, u_T = 0 on the stick set, lT = +-s on the
 * slip set and lN = 0 elsewhere. Its own criterion: the active sets repeat,
 * which for exact solves means the iterate is the solution.
 *
 * 3D Tresca (disc slip bound, the Euclidean norm): the generalised Newton
 * step for lT = proj_disc(s)(z), z = lT + rho T u. On a slip point
 * (|z| > s) the slip direction q = z/|z| is fixed for the step and the
 * projection linearised at z: with P = I - q q' this gives
 * lT = s q + beta P T u, beta = s rho / (|z| - s), a symmetric positive
 * semi-definite tangential stiffness added to the condensed K. The sets
 * repeating is then not enough (q moves): the run stops on the kkt error,
 * or on the sets repeating with no point slipping.
 *
 * rho matters only for the tangential sets (after an exact solve the normal
 * sets depend on signs alone): a large rho flips a slipping point straight
 * to the opposite slip, and on 'hertz' with Tresca rho = 1 (relative to the
 * stiffness scale) cycles between two sets from level 32 on. A small rho
 * sends such a point to stick first; 1e-3 converged in 5-9 iterations on
 * every hertz level from 16 to 256 and on 'slider'.
 *
 * Linear algebra: the saddle-point system is condensed onto the contact
 * dofs with the session's Schur complement S of K (one sparse Cholesky for
 * the whole session, doc/design.md §5), so each iteration is one dense
 * symmetric-indefinite solve of order nc + |active| (Bunch-Kaufman: S may
 * be singular when only the contact holds the body), or, when every active
 * row pins a dof of its own (a flat obstacle along an axis), a Cholesky of
 * order nc - |active| (ssn_solve_pinned). The step updates u on
 * the contact dofs only (a partial iterate, solve.h): the solve with the
 * sparse factor that expands u is left to the end of the run. The constraint rows are scaled by the
 * stiffness scale so that both blocks have like magnitudes. The first
 * iteration takes every point in contact and sticking (the bonded problem),
 * which holds the body whatever K's null space. */
#include "solve/solve.h"

#include <math.h>
#include <string.h>

typedef struct {
    cx_schur *S;          /* borrowed from the session's operator cache */
    int nc;               /* contact dofs (order of S) */
    const int *dofs;      /* nc: those dofs, the session's: all contact dofs, or for a
                             frictionless run the normal ones only (the tangential ones,
                             free of force, are condensed away with the interior) */
    int normal;           /* S is the normal-only reduction */
    int nrow;             /* constraint rows: m normal, then nt tangential (Tresca) */
    int *rp, *rc;         /* nrow + 1 / nnz: CSR rows over contact-dof positions */
    double *rv;           /* nnz row values */
    const double *fc;     /* nc: load condensed onto the contact dofs (the session's) */
    double *uc;           /* nc: contact-dof displacements of the iterate */
    double *uprev;        /* nc: the previous uc, for the paper's criterion */
    double *Bu;           /* nrow: rows times uc */
    signed char *set;     /* nrow: normal 1 contact / 0 free; tangential 0 stick, +1/-1 slip */
    signed char *prev;    /* nrow: the sets of the previous iteration */
    int *act;             /* nrow: rows in the current system */
    double *M;            /* (nc + nrow)^2: dense saddle-point matrix */
    double *x;            /* nc + nrow: right-hand side, then solution */
    int *ipiv;            /* nc + nrow */
    double *work;         /* lwork */
    int lwork;
    double rho;           /* natural-map parameter (stiffness units) */
    double kappa;         /* row scaling: the stiffness scale */
    int tangential;       /* 1 if Tresca rows take part */
    const double *sb;     /* m: the session's slip bounds (fixed until the next init) */
    int dt;               /* tangential rows per point (dim - 1) */
    double *q;            /* nt: 3D slip direction per point (its two tangential rows) */
    double *beta;         /* m: 3D linearised tangential stiffness of a slip point */
    int warm;             /* 1: the first sets come from the starting iterate */
    int *unit;            /* nrow: the contact-dof position of a row with one entry, else -1 */
    int *pin;             /* nc: the active row pinning a contact dof, or -1 */
    int *fpos;            /* nc: the free contact dofs of the pinned system */
    double *Mf;           /* nc^2: their block of the condensed matrix */
    double *up;           /* nc: the pinned values */
} ssn_state;

static const cx_param ssn_params[] = {
    {"rho", CX_PARAM_REAL, 1e-3, 1e-12, 1e12, NULL,
     "active-set parameter, relative to the largest diagonal entry of K", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

/* Dense systems above this order are refused rather than run for minutes. */
#define SSN_MAX_DENSE 20000

static void ssn_destroy(void *state)
{
    ssn_state *st = state;
    cx_free(st->rp);
    cx_free(st->rc);
    cx_free(st->rv);
    cx_free(st->uc);
    cx_free(st->uprev);
    cx_free(st->Bu);
    cx_free(st->set);
    cx_free(st->prev);
    cx_free(st->act);
    cx_free(st->M);
    cx_free(st->x);
    cx_free(st->ipiv);
    cx_free(st->work);
    cx_free(st->q);
    cx_free(st->beta);
    cx_free(st->unit);
    cx_free(st->pin);
    cx_free(st->fpos);
    cx_free(st->Mf);
    cx_free(st->up);
    memset(st, 0, sizeof *st);
}

/* CSR rows of N (and T) over the positions of the contact dofs. */
static int ssn_build_rows(ssn_state *st, const cx_problem *p)
{
    int *pos = CX_NEW(int, p->n);
    if (!pos)
        return CX_ENOMEM;
    for (int j = 0; j < p->n; j++)
        pos[j] = -1;
    for (int k = 0; k < st->nc; k++)
        pos[st->dofs[k]] = k;
    const cx_csc *B[2] = {&p->N, &p->T};
    int nb = st->tangential ? 2 : 1;
    size_t nnz = 0;
    for (int b = 0; b < nb; b++)
        nnz += cx_csc_nnz(B[b]);
    st->rp = CX_NEW(int, st->nrow + 1);
    st->rc = CX_NEW(int, nnz);
    st->rv = CX_NEW(double, nnz);
    if (!st->rp || !st->rc || !st->rv) {
        cx_free(pos);
        return CX_ENOMEM;
    }
    /* count per row, then fill: the CSC columns are the free dofs */
    int off = 0;
    for (int b = 0; b < nb; b++) {
        for (size_t q = 0; q < cx_csc_nnz(B[b]); q++)
            st->rp[off + B[b]->i[q] + 1]++;
        off += B[b]->nrow;
    }
    for (int r = 0; r < st->nrow; r++)
        st->rp[r + 1] += st->rp[r];
    int *fill = st->act; /* borrowed as a cursor */
    memcpy(fill, st->rp, sizeof(int) * (size_t)st->nrow);
    off = 0;
    for (int b = 0; b < nb; b++) {
        for (int j = 0; j < B[b]->ncol; j++)
            for (int q = B[b]->p[j]; q < B[b]->p[j + 1]; q++) {
                int r = off + B[b]->i[q];
                st->rc[fill[r]] = pos[j];
                st->rv[fill[r]++] = B[b]->x[q];
            }
        off += B[b]->nrow;
    }
    cx_free(pos);
    return CX_OK;
}

/* The bonded start: every point in contact and sticking. */
static void ssn_bonded(ssn_state *st, int m)
{
    for (int r = 0; r < st->nrow; r++)
        st->set[r] = r < m ? 1 : 0;
}

static int ssn_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    ssn_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    st->dt = p->dim - 1;
    st->tangential = cx_session_friction(s)->law == CX_FRICTION_TRESCA;
    st->sb = cx_session_friction(s)->s;
    st->normal = !st->tangential;
    st->nc = p->nc;
    st->dofs = p->cdofs;
    if (st->normal) {   /* which dofs, before anything is factorised */
        int status = cx_session_schur_normal(s, NULL, NULL, &st->dofs, &st->nc, d);
        if (status != CX_OK)
            return status;
    }
    st->nrow = p->m + (st->tangential ? p->nt : 0);
    int ns = st->nc + st->nrow;
    if (ns > SSN_MAX_DENSE)
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "method 'ssn-tresca': the reduced system has %d unknowns (limit %d); "
                           "use a coarser level", ns, SSN_MAX_DENSE);
    st->kappa = p->kscale > 0 ? p->kscale : 1;
    st->rho = cx_param_get(params, "rho") * st->kappa;
    st->lwork = 64 * (ns > 0 ? ns : 1);
    st->uc = CX_NEW(double, st->nc);
    st->uprev = CX_NEW(double, st->nc);
    st->Bu = CX_NEW(double, st->nrow);
    st->set = CX_NEW(signed char, st->nrow);
    st->prev = CX_NEW(signed char, st->nrow);
    st->act = CX_NEW(int, st->nrow);
    st->M = CX_NEW(double, (size_t)ns * (size_t)ns);
    st->x = CX_NEW(double, ns);
    st->ipiv = CX_NEW(int, ns);
    st->work = CX_NEW(double, st->lwork);
    st->q = CX_NEW(double, p->nt);
    st->beta = CX_NEW(double, p->m);
    st->unit = CX_NEW(int, st->nrow);
    st->pin = CX_NEW(int, st->nc);
    st->fpos = CX_NEW(int, st->nc);
    st->Mf = CX_NEW(double, (size_t)st->nc * (size_t)st->nc);
    st->up = CX_NEW(double, st->nc);
    int status = CX_ENOMEM;
    if (!st->unit || !st->pin || !st->fpos || !st->Mf || !st->up ||
        !st->q || !st->beta || !st->uc || !st->uprev || !st->Bu || !st->set || !st->prev || !st->act ||
        !st->M || !st->x || !st->ipiv || !st->work) {
        ssn_destroy(st);
        return cx_diag_set(d, status, "out of memory");
    }
    int nd = p->nc;
    status = st->normal ? cx_session_schur_normal(s, &st->S, &st->fc, &st->dofs, &nd, d)
                        : cx_session_schur(s, &st->S, &st->fc, d);
    if (status == CX_OK && nd != st->nc)   /* the session's choice cannot change in between */
        status = cx_diag_set(d, CX_EINVAL, "ssn-tresca: reduction onto %d dofs, expected %d", nd, st->nc);
    if (status != CX_OK) {
        ssn_destroy(st);
        return status;
    }
    if ((status = ssn_build_rows(st, p)) != CX_OK) {
        ssn_destroy(st);
        return cx_diag_set(d, status, "out of memory");
    }
    for (int r = 0; r < st->nrow; r++)
        st->unit[r] = st->rp[r + 1] - st->rp[r] == 1 ? st->rc[st->rp[r]] : -1;
    /* start from the sets of the session's starting iterate if it has
     * contact forces (cx_session_set_start, e.g. cf-fp's last step), else
     * bonded: every point in contact and sticking */
    const cx_iterate *start = cx_session_iterate(s);
    st->warm = 0;
    for (int i = 0; i < p->m; i++)
        st->warm |= start->lN[i] > 0;
    ssn_bonded(st, p->m);
    memset(st->prev, 0x7f, (size_t)st->nrow);  /* no previous sets */
    return CX_OK;
}

static double ssn_row_dot(const ssn_state *st, int r, const double *v)
{
    double sum = 0;
    for (int q = st->rp[r]; q < st->rp[r + 1]; q++)
        sum += st->rv[q] * v[st->rc[q]];
    return sum;
}

/* Active sets from the iterate, by the natural maps (000 (15), (18), (19)). */
static void ssn_predict(ssn_state *st, const cx_problem *p, const cx_iterate *it)
{
    for (int r = 0; r < st->nrow; r++)
        st->Bu[r] = ssn_row_dot(st, r, st->uc);
    for (int i = 0; i < p->m; i++)
        st->set[i] = it->lN[i] + st->rho * (st->Bu[i] - p->g[i]) > 0;
    for (int i = 0; st->tangential && st->dt == 1 && i < p->m; i++) {
        double z = it->lT[i] + st->rho * st->Bu[p->m + i];
        st->set[p->m + i] = z > st->sb[i] ? 1 : (z < -st->sb[i] ? -1 : 0);
    }
    for (int i = 0; st->tangential && st->dt == 2 && i < p->m; i++) {
        /* the disc: slip along q = z/|z| beyond it, linearised (header) */
        int r = p->m + 2 * i;
        double z0 = it->lT[2 * i] + st->rho * st->Bu[r];
        double z1 = it->lT[2 * i + 1] + st->rho * st->Bu[r + 1];
        double nz = sqrt(z0 * z0 + z1 * z1);
        int slip = nz > st->sb[i];
        st->set[r] = st->set[r + 1] = (signed char)slip;
        st->q[2 * i] = slip ? z0 / nz : 0;
        st->q[2 * i + 1] = slip ? z1 / nz : 0;
        st->beta[i] = slip ? st->sb[i] * st->rho / (nz - st->sb[i]) : 0;
    }
}

/* 3D slip points: the tangential stiffness beta T_i' P T_i into M (order
 * ns) and -s T_i' q into the right-hand side x. */
static void ssn_add_slip3d(ssn_state *st, const cx_problem *p, int ns)
{
    for (int i = 0; i < p->m; i++) {
        int r = p->m + 2 * i;
        if (st->set[r] == 0)
            continue;
        const double *q = st->q + 2 * i;
        double P[2][2] = {{1 - q[0] * q[0], -q[0] * q[1]}, {-q[1] * q[0], 1 - q[1] * q[1]}};
        for (int a = 0; a < 2; a++) {
            for (int qa = st->rp[r + a]; qa < st->rp[r + a + 1]; qa++) {
                st->x[st->rc[qa]] -= st->rv[qa] * st->sb[i] * q[a];
                for (int b = 0; b < 2; b++)
                    for (int qb = st->rp[r + b]; qb < st->rp[r + b + 1]; qb++)
                        st->M[(size_t)ns * st->rc[qb] + st->rc[qa]] +=
                            st->beta[i] * P[a][b] * st->rv[qa] * st->rv[qb];
            }
        }
    }
}

/* 3D slip points after the solve: lT = s q + beta P T u. */
static void ssn_slip3d_multipliers(ssn_state *st, const cx_problem *p, cx_iterate *it)
{
    for (int i = 0; i < p->m; i++) {
        int r = p->m + 2 * i;
        if (st->set[r] == 0)
            continue;
        const double *q = st->q + 2 * i;
        double t0 = ssn_row_dot(st, r, st->uc), t1 = ssn_row_dot(st, r + 1, st->uc);
        double qt = q[0] * t0 + q[1] * t1;
        it->lT[2 * i] = st->sb[i] * q[0] + st->beta[i] * (t0 - qt * q[0]);
        it->lT[2 * i + 1] = st->sb[i] * q[1] + st->beta[i] * (t1 - qt * q[1]);
    }
}

/* Number of 3D slip points in the current sets. */
static int ssn_nslip3d(const ssn_state *st, const cx_problem *p)
{
    int n = 0;
    for (int i = 0; st->tangential && st->dt == 2 && i < p->m; i++)
        n += st->set[p->m + 2 * i] != 0;
    return n;
}

/* The saddle-point system when every active row has one entry, on a dof
 * of its own (a flat obstacle along a coordinate axis): the row pins that
 * dof, u_c = g_r / v_r (0 for a stick row), and what remains is the
 * symmetric positive definite system of the free contact dofs, a Cholesky
 * of order nc - na instead of a Bunch-Kaufman of order nc + na; the
 * multiplier of row r is what its dof's equilibrium row lacks,
 * (x_c - (M u)_c) / v_r. M, x: the top-left nc x nc block (leading
 * dimension ns; S itself, ns = nc, when no 3D slip point adds to it) and
 * the top nc entries of the saddle-point system, as ssn_solve built them.
 * The solution into uc, the multiplier of the a-th active row into
 * lam[a]. CX_EUNSUPPORTED if the rows are not all such, or CX_ENUMERIC if
 * the free block is not definite (the active set does not hold the body):
 * the caller then solves the whole system. */
static int ssn_solve_pinned(ssn_state *st, const cx_problem *p, int na, const double *M, int ns,
                            double *lam)
{
    int nc = st->nc, m = p->m, nf = 0;
    for (int k = 0; k < nc; k++)
        st->pin[k] = -1;
    for (int a = 0; a < na; a++) {
        int r = st->act[a], c = st->unit[r];
        if (c < 0 || st->pin[c] >= 0)
            return CX_EUNSUPPORTED;
        st->pin[c] = r;
        st->up[c] = (r < m ? p->g[r] : 0.0) / st->rv[st->rp[r]];
    }
    for (int k = 0; k < nc; k++)
        if (st->pin[k] < 0)
            st->fpos[nf++] = k;
    const double *x = st->x;
    double *rhs = st->uc;   /* the free right-hand side, then the free solution */
    for (int j = 0; j < nf; j++) {
        const double *col = M + (size_t)ns * st->fpos[j];
        for (int i = 0; i < nf; i++)
            st->Mf[i + (size_t)nf * j] = col[st->fpos[i]];
    }
    for (int i = 0; i < nf; i++) {
        double sum = x[st->fpos[i]];
        for (int a = 0; a < na; a++) {
            int c = st->unit[st->act[a]];
            sum -= M[st->fpos[i] + (size_t)ns * c] * st->up[c];
        }
        rhs[i] = sum;
    }
    CX_TRY(cx_dense_cholesky(nf, st->Mf, NULL));
    cx_dense_cholesky_solve(nf, st->Mf, rhs, 1);
    if (!cx_vec_finite(nf, rhs))
        return CX_ENUMERIC;
    /* scatter in place: fpos[i] >= i, so from the end nothing is overwritten early */
    for (int i = nf - 1; i >= 0; i--)
        st->uc[st->fpos[i]] = rhs[i];
    for (int a = 0; a < na; a++) {
        int c = st->unit[st->act[a]];
        st->uc[c] = st->up[c];
    }
    for (int a = 0; a < na; a++) {
        int r = st->act[a], c = st->unit[r];
        double Mu = 0;
        for (int k = 0; k < nc; k++)
            Mu += M[c + (size_t)ns * k] * st->uc[k];
        lam[a] = (x[c] - Mu) / st->rv[st->rp[r]];
    }
    return CX_OK;
}

/* Solve the condensed saddle-point system of the current sets; the new
 * iterate into uc, it->lN, it->lT. */
static int ssn_solve(ssn_state *st, const cx_problem *p, cx_iterate *it, cx_diag *d)
{
    int nc = st->nc, m = p->m;
    int na = 0;
    /* a row with no free dof (a contact node whose tangential motion is
     * prescribed, e.g. on a symmetry axis) constrains nothing */
    for (int r = 0; r < st->nrow; r++)
        if (st->rp[r + 1] > st->rp[r] && ((r < m && st->set[r] == 1) || (r >= m && st->set[r] == 0)))
            st->act[na++] = r;
    int ns = nc + na;
    const double *S = cx_schur_matrix(st->S);
    memcpy(st->x, st->fc, sizeof(double) * (size_t)nc);
    for (int i = 0; st->tangential && st->dt == 1 && i < m; i++) {
        int r = m + i;
        if (st->set[r] == 0)
            continue;
        double lt = st->set[r] * st->sb[i];
        for (int q = st->rp[r]; q < st->rp[r + 1]; q++)
            st->x[st->rc[q]] -= st->rv[q] * lt;
    }
    double *lam = st->Bu;   /* na <= nrow: the active rows' multipliers */
    /* without 3D slip points the pinned system's block is S's own: read
     * there, the saddle-point matrix (order ns, rebuilt at every
     * iteration) is built only when the pinned solve does not apply */
    int slip3d = ssn_nslip3d(st, p) > 0;
    if (!slip3d && ssn_solve_pinned(st, p, na, S, nc, lam) == CX_OK)
        goto iterate;
    for (int j = 0; j < nc; j++) {
        memcpy(st->M + (size_t)ns * j, S + (size_t)nc * j, sizeof(double) * (size_t)nc);
        memset(st->M + (size_t)ns * j + nc, 0, sizeof(double) * (size_t)na);
    }
    for (int a = 0; a < na; a++) {
        double *col = st->M + (size_t)ns * (nc + a);
        memset(col, 0, sizeof(double) * (size_t)ns);
        int r = st->act[a];
        for (int q = st->rp[r]; q < st->rp[r + 1]; q++) {
            col[st->rc[q]] += st->kappa * st->rv[q];
            st->M[(size_t)ns * st->rc[q] + nc + a] += st->kappa * st->rv[q];
        }
        st->x[nc + a] = r < m ? st->kappa * p->g[r] : 0.0;
    }
    if (slip3d)
        ssn_add_slip3d(st, p, ns);
    if (!slip3d || ssn_solve_pinned(st, p, na, st->M, ns, lam) != CX_OK) {
        int status = cx_dense_sym_solve(ns, st->M, st->x, st->ipiv, st->work, st->lwork, NULL);
        if (status != CX_OK)
            return cx_diag_set(d, status,
                               "ssn-tresca: singular saddle-point system at iteration %d: the active set "
                               "(%d rows) does not hold the body", it->iter + 1, na);
        memcpy(st->uc, st->x, sizeof(double) * (size_t)nc);
        for (int a = 0; a < na; a++)
            lam[a] = st->kappa * st->x[nc + a];
    }

iterate:   /* ---- the new iterate ---- */
    memset(it->lN, 0, sizeof(double) * (size_t)m);
    for (int i = 0; st->tangential && st->dt == 1 && i < m; i++)
        it->lT[i] = st->set[m + i] * st->sb[i];
    if (st->tangential && st->dt == 2) {
        memset(it->lT, 0, sizeof(double) * (size_t)p->nt);
        ssn_slip3d_multipliers(st, p, it);
    }
    for (int a = 0; a < na; a++) {
        int r = st->act[a];
        if (r < m)
            it->lN[r] = lam[a];
        else
            it->lT[r - m] = lam[a];
    }
    return CX_OK;
}

static int ssn_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    ssn_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    int nc = st->nc;

    if (it->iter == 0 && st->warm) {
        /* a warm start: the sets of the starting iterate */
        for (int k = 0; k < nc; k++)
            st->uc[k] = it->u[st->dofs[k]];
        memcpy(st->uprev, st->uc, sizeof(double) * (size_t)nc);
    }
    if (it->iter > 0 || st->warm)
        ssn_predict(st, p, it);
    if (memcmp(st->set, st->prev, (size_t)st->nrow) == 0 && ssn_nslip3d(st, p) == 0) {
        /* the sets repeat: the last iterate solves the problem */
        it->own = 0;
        it->own_done = 1;
        return CX_OK;
    }
    memcpy(st->prev, st->set, (size_t)st->nrow);
    int status = ssn_solve(st, p, it, d);
    if (status == CX_ENUMERIC && it->iter == 0 && st->warm) {
        /* the start's sets do not hold the body: start bonded after all */
        ssn_bonded(st, p->m);
        memcpy(st->prev, st->set, (size_t)st->nrow);
        cx_diag_clear(d);
        status = ssn_solve(st, p, it, d);
    }
    CX_TRY(status);

    /* u on the reduction's dofs only: the solver expands it when the run ends */
    for (int k = 0; k < nc; k++)
        it->u[st->dofs[k]] = st->uc[k];
    it->u_partial = st->normal ? CX_PARTIAL_NORMAL : CX_PARTIAL_CONTACT;

    /* the paper's err = ||u^k - u^(k-1)|| / ||u^k||, over the contact dofs */
    cx_vec_axpy(nc, -1.0, st->uc, st->uprev);
    double nu = cx_vec_norm2(nc, st->uc);
    it->own = nu > 0 ? cx_vec_norm2(nc, st->uprev) / nu : 0;
    memcpy(st->uprev, st->uc, sizeof(double) * (size_t)nc);
    return CX_OK;
}

const cx_method cx_method_ssn_tresca = {
    .id = "ssn-tresca",
    .name = "Semismooth Newton / active set (Tresca)",
    .source = "000 §4.2",
    .summary = "primal-dual active set on the saddle-point system, condensed onto the contact dofs",
    .supports = CX_FRICTIONLESS | CX_TRESCA | CX_2D | CX_3D | CX_MULTIBODY,
    .state_size = sizeof(ssn_state),
    .params = ssn_params,
    .init = ssn_init,
    .step = ssn_step,
    .destroy = ssn_destroy,
};
