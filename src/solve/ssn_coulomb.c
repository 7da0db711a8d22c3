/* SPDX-License-Identifier: GPL-3.0-or-later */
/* ssn-coulomb — ActiveSetCoulomb (paper 000 §4.1): the semismooth Newton
 * method on G(y) = 0, y = (u, lN, lT), for Coulomb friction in 2D
 * (several bodies included), solved directly, without a fixed point.
 *
 * Each iteration forms the sets at the previous iterate, by (15)-(17):
 *     A_nu = {lN_i + rho (N u - g)_i > 0},
 *     I+_t = {lT_i + rho (T u)_i > F_i lN_i},  I-_t = {... < -F_i lN_i},
 * A_t (stick) the rest, and solves the non-symmetric system of step (2):
 *     K u + N'lN + T'lT = f,
 *     (N u)_i = g_i on A_nu,       lN_i = 0 elsewhere,
 *     (T u)_i = 0 on A_t,          lT_i = +-F_i lN_i on I+-_t.
 * The first iteration takes every point in contact and sticking (the
 * bonded start, which holds a body whatever K's null space); rho matters
 * only for the next sets (000 §4.1). Own criterion (step 3):
 * ||u^k - u^(k-1)|| / ||u^k|| <= eps over the contact dofs, or sets that
 * repeat (then the last iterate solves G(y) = 0 exactly). A row with no
 * free dof (a contact point whose motion is all prescribed) constrains
 * nothing: its multiplier is 0.
 *
 * Linear algebra: the Newton matrix differs from K only in the contact
 * rows, so the system is condensed onto the contact dofs with the
 * session's Schur complement S of K (one sparse Cholesky for the whole
 * session, doc/design.md §5): S u_c + N'lN + T'lT = f_c. Slip rows are
 * substituted (lT_i = +-F_i lN_i puts F_i T_i' into lN_i's column), and
 * each step is one dense LU (non-symmetric by that column) of order
 * nc + |active rows|, the multipliers scaled by the stiffness scale kappa
 * so that both blocks have like sizes. When every active row pins a dof of
 * its own (a flat obstacle along an axis, ssn-tresca's case) and the slip
 * rows touch only the other dofs, the pinned dofs and their multipliers
 * are eliminated as well: the multiplier of a pinned dof is what its
 * equilibrium row lacks, so a slip row adds -(+-F_i t / v) times the
 * pinned normal dof's row of S to the rows of its dofs, and what remains
 * is an LU of the free contact dofs alone. The step updates u on the
 * contact dofs only (a partial iterate, solve.h); u is expanded with the
 * sparse factor when the run ends. */
#include "solve/solve.h"

#include <math.h>
#include <string.h>

typedef struct {
    cx_schur *S;          /* borrowed from the session's operator cache */
    const double *fc;     /* nc: the condensed load (the session's) */
    int nc;               /* contact dofs (order of S) */
    cx_csc Nr, Tr;        /* N', T' (nc x m, nc x nt): column i is row i, over contact-dof positions */
    double *uc, *uprev;   /* nc: contact-dof displacements of the iterate, of the previous one */
    double *Nu, *Tu;      /* m, nt */
    signed char *setN;    /* m: 1 contact, 0 not */
    signed char *setT;    /* nt: 0 stick, +1 / -1 slip */
    signed char *prevN, *prevT;   /* m, nt: the sets of the previous iteration */
    int *act;             /* m + nt: the active rows (normal i as i, tangential i as m + i) */
    int *aidx;            /* m + nt: a row's place in act, or -1 */
    int *pin;             /* nc: the active row pinning a contact dof, or -1 */
    int *fpos;            /* nc: a free contact dof's place in the pinned system, or -1 */
    int *fdof;            /* nc: the free contact dofs of the pinned system */
    double *up;           /* nc: the pinned values */
    double *lam;          /* m + nt: the active rows' multipliers */
    double *M;            /* ns^2, ns = nc + m + nt: the dense Newton matrix of either form */
    double *x;            /* ns: right-hand side, then solution */
    int *ipiv;            /* ns */
    double rho;           /* natural-map parameter (stiffness units) */
    double kappa;         /* multiplier scaling */
    double eps;
    int first;            /* the bonded start is still to be done */
    const double *Fi;     /* m: the session's coefficients (fixed until the next init) */
} coul_state;

static const cx_param coul_params[] = {
    {"rho", CX_PARAM_REAL, 1e-3, 1e-12, 1e12, NULL,
     "active-set parameter, relative to the largest diagonal entry of K", 0},
    {"eps", CX_PARAM_REAL, 1e-12, 0, 1, NULL, "own stop: ||u^k - u^(k-1)|| / ||u^k|| <= eps", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

/* Dense systems above this order are refused rather than run for minutes. */
#define COUL_MAX_DENSE 20000

static void coul_destroy(void *state)
{
    coul_state *st = state;
    cx_csc_clear(&st->Nr);
    cx_csc_clear(&st->Tr);
    void *owned[] = {st->uc, st->uprev, st->Nu, st->Tu, st->setN, st->setT, st->prevN, st->prevT,
                     st->act, st->aidx, st->lam, st->pin, st->fpos, st->fdof, st->up, st->M, st->x, st->ipiv};
    for (size_t k = 0; k < sizeof owned / sizeof owned[0]; k++)
        cx_free(owned[k]);
    memset(st, 0, sizeof *st);
}

/* Bt = B' with its row indices (free dofs) turned into contact-dof
 * positions: column i is row i of B over the contact dofs. */
static int coul_rows(cx_csc *Bt, const cx_csc *B, const int *pos)
{
    CX_TRY(cx_csc_transpose(Bt, B));
    for (size_t q = 0; q < cx_csc_nnz(Bt); q++)
        Bt->i[q] = pos[Bt->i[q]];   /* cdofs ascending: the order stays sorted */
    return CX_OK;
}

/* Row r (normal r < m, tangential m + i) as a column of Nr or Tr. */
static const cx_csc *coul_row(const coul_state *st, int m, int r, int *col)
{
    *col = r < m ? r : r - m;
    return r < m ? &st->Nr : &st->Tr;
}

static int coul_empty(const cx_csc *R, int i) { return R->p[i + 1] == R->p[i]; }

static int coul_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    coul_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    const cx_friction_state *fr = cx_session_friction(s);
    if (fr->law != CX_FRICTION_COULOMB)
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "method 'ssn-coulomb' solves Coulomb friction only (use ssn-tresca for %s)",
                           fr->law == CX_FRICTION_TRESCA ? "Tresca" : "frictionless contact");
    int n = p->n, m = p->m, nt = p->nt, nc = p->nc, ns = nc + m + nt, status = CX_ENOMEM;
    if (ns > COUL_MAX_DENSE)
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "method 'ssn-coulomb': the reduced system has %d unknowns (limit %d); "
                           "use a coarser level", ns, COUL_MAX_DENSE);
    st->nc = nc;
    st->kappa = p->kscale > 0 ? p->kscale : 1;
    st->rho = cx_param_get(params, "rho") * st->kappa;
    st->Fi = fr->Fi;
    st->eps = cx_param_get(params, "eps");
    st->uc = CX_NEW(double, nc + 1);
    st->uprev = CX_NEW(double, nc + 1);
    st->Nu = CX_NEW(double, m + 1);
    st->Tu = CX_NEW(double, nt + 1);
    st->setN = CX_NEW(signed char, m + 1);
    st->setT = CX_NEW(signed char, nt + 1);
    st->prevN = CX_NEW(signed char, m + 1);
    st->prevT = CX_NEW(signed char, nt + 1);
    st->act = CX_NEW(int, m + nt + 1);
    st->aidx = CX_NEW(int, m + nt + 1);
    st->lam = CX_NEW(double, m + nt + 1);
    st->pin = CX_NEW(int, nc + 1);
    st->fpos = CX_NEW(int, nc + 1);
    st->fdof = CX_NEW(int, nc + 1);
    st->up = CX_NEW(double, nc + 1);
    st->M = CX_NEW(double, (size_t)ns * (size_t)ns + 1);
    st->x = CX_NEW(double, ns + 1);
    st->ipiv = CX_NEW(int, ns + 1);
    int *pos = CX_NEW(int, n + 1);
    if (pos && st->uc && st->uprev && st->Nu && st->Tu && st->setN && st->setT && st->prevN && st->prevT &&
        st->act && st->aidx && st->lam && st->pin && st->fpos && st->fdof && st->up && st->M && st->x && st->ipiv) {
        for (int k = 0; k < nc; k++)
            pos[p->cdofs[k]] = k;
        if (!(status = coul_rows(&st->Nr, &p->N, pos)))
            status = coul_rows(&st->Tr, &p->T, pos);
    }
    cx_free(pos);
    if (status) {
        coul_destroy(st);
        return cx_diag_set(d, status, "out of memory");
    }
    if ((status = cx_session_schur(s, &st->S, &st->fc, d)) != CX_OK) {
        coul_destroy(st);
        return status;
    }
    /* the bonded start: all in contact, sticking */
    memset(st->setN, 1, (size_t)m);
    memset(st->setT, 0, (size_t)nt);
    st->first = 1;
    return CX_OK;
}

/* Sets (15)-(17) at the iterate (N and T touch the contact dofs only, so a
 * partial u serves). */
static void coul_sets(coul_state *st, const cx_problem *p, const cx_iterate *it)
{
    cx_csc_gemv(&p->N, 1.0, it->u, 0.0, st->Nu);
    cx_csc_gemv(&p->T, 1.0, it->u, 0.0, st->Tu);
    for (int i = 0; i < p->m; i++)
        st->setN[i] = it->lN[i] + st->rho * (st->Nu[i] - p->g[i]) > 0;
    for (int i = 0; i < p->nt; i++) {
        double z = it->lT[i] + st->rho * st->Tu[i], b = st->Fi[i] * it->lN[i];
        st->setT[i] = z > b ? 1 : (z < -b ? -1 : 0);
    }
}

/* The active rows (act, aidx); returns their number. */
static int coul_active(coul_state *st, const cx_problem *p)
{
    int m = p->m, na = 0;
    for (int r = 0; r < m + p->nt; r++) {
        int on = r < m ? st->setN[r] == 1 && !coul_empty(&st->Nr, r)
                       : st->setT[r - m] == 0 && !coul_empty(&st->Tr, r - m);
        st->aidx[r] = on ? na : -1;
        if (on)
            st->act[na++] = r;
    }
    return na;
}

/* The factor c_i of lT_i = c_i lN_i on a slip row whose normal row is
 * active (the substituted coupling), else 0. */
static double coul_slip(const coul_state *st, int i)
{
    if (st->setT[i] == 0 || coul_empty(&st->Tr, i) || st->aidx[i] < 0)
        return 0;
    return st->setT[i] * st->Fi[i];
}

/* The condensed Newton system with the active rows' multipliers (scaled by
 * kappa) as unknowns: order nc + na, one dense LU. */
static int coul_solve_full(coul_state *st, const cx_problem *p, int na, cx_counters *cnt, double *lam)
{
    int nc = st->nc, m = p->m, ns = nc + na;
    const double *S = cx_schur_matrix(st->S);
    double k = st->kappa, *M = st->M;
    memset(M, 0, sizeof(double) * (size_t)ns * (size_t)ns);
    for (int j = 0; j < nc; j++)
        memcpy(M + (size_t)ns * j, S + (size_t)nc * j, sizeof(double) * (size_t)nc);
    memcpy(st->x, st->fc, sizeof(double) * (size_t)nc);
    for (int a = 0; a < na; a++) {
        int r = st->act[a], col;
        const cx_csc *R = coul_row(st, m, r, &col);
        for (int q = R->p[col]; q < R->p[col + 1]; q++) {
            M[(size_t)ns * (nc + a) + R->i[q]] += k * R->x[q];
            M[(size_t)ns * R->i[q] + nc + a] += k * R->x[q];
        }
        st->x[nc + a] = r < m ? k * p->g[r] : 0.0;
    }
    for (int i = 0; i < p->nt; i++) {
        double c = coul_slip(st, i);
        for (int q = st->Tr.p[i]; c != 0 && q < st->Tr.p[i + 1]; q++)
            M[(size_t)ns * (nc + st->aidx[i]) + st->Tr.i[q]] += k * c * st->Tr.x[q];
    }
    CX_TRY(cx_dense_lu_solve(ns, M, st->x, st->ipiv, cnt));
    memcpy(st->uc, st->x, sizeof(double) * (size_t)nc);
    for (int a = 0; a < na; a++)
        lam[a] = k * st->x[nc + a];
    return CX_OK;
}

/* Pin the contact dofs of the active rows: CX_EUNSUPPORTED unless every
 * active row has one entry, on a dof of its own, and every substituted
 * slip row touches only unpinned dofs. */
static int coul_pin(coul_state *st, const cx_problem *p, int na)
{
    int nc = st->nc, m = p->m;
    for (int k = 0; k < nc; k++)
        st->pin[k] = -1;
    for (int a = 0; a < na; a++) {
        int r = st->act[a], col;
        const cx_csc *R = coul_row(st, m, r, &col);
        int q = R->p[col];
        if (R->p[col + 1] - q != 1 || st->pin[R->i[q]] >= 0 || R->x[q] == 0)
            return CX_EUNSUPPORTED;
        st->pin[R->i[q]] = r;
        st->up[R->i[q]] = (r < m ? p->g[r] : 0.0) / R->x[q];
    }
    for (int i = 0; i < p->nt; i++)
        for (int q = st->Tr.p[i]; coul_slip(st, i) != 0 && q < st->Tr.p[i + 1]; q++)
            if (st->pin[st->Tr.i[q]] >= 0)
                return CX_EUNSUPPORTED;
    return CX_OK;
}

/* f_c - S u_p in row k, u_p the pinned values (0 on the free dofs): the
 * right-hand side of row k of the free system. */
static double coul_pinned_rhs(const coul_state *st, const double *S, int k, int nf)
{
    int nc = st->nc;
    double sum = st->fc[k];
    if (nf < nc)
        for (int j = 0; j < nc; j++)
            if (st->pin[j] >= 0)
                sum -= S[k + (size_t)nc * j] * st->up[j];
    return sum;
}

/* The system of the free contact dofs when the active rows pin dofs (see
 * the header): a slip row i whose normal row pins dof c with value v adds
 * -(c_i t / v) times row c to the row of each of its dofs (entry t). One
 * dense LU of order nc - na. */
static int coul_solve_pinned(coul_state *st, const cx_problem *p, cx_counters *cnt, double *lam)
{
    int nc = st->nc, m = p->m, nf = 0;
    const double *S = cx_schur_matrix(st->S);
    double *M = st->M, *rhs = st->x;
    for (int k = 0; k < nc; k++) {
        st->fpos[k] = st->pin[k] < 0 ? nf : -1;
        if (st->pin[k] < 0)
            st->fdof[nf++] = k;
    }
    for (int b = 0; b < nf; b++)
        for (int a = 0; a < nf; a++)
            M[a + (size_t)nf * b] = S[st->fdof[a] + (size_t)nc * st->fdof[b]];
    for (int a = 0; a < nf; a++)
        rhs[a] = coul_pinned_rhs(st, S, st->fdof[a], nf);
    for (int i = 0; i < p->nt; i++) {
        double c = coul_slip(st, i);
        if (c == 0)
            continue;
        int qn = st->Nr.p[i], cn = st->Nr.i[qn];
        double rn = coul_pinned_rhs(st, S, cn, nf);
        for (int q = st->Tr.p[i]; q < st->Tr.p[i + 1]; q++) {
            int a = st->fpos[st->Tr.i[q]];
            double alpha = c * st->Tr.x[q] / st->Nr.x[qn];
            for (int b = 0; b < nf; b++)
                M[a + (size_t)nf * b] -= alpha * S[cn + (size_t)nc * st->fdof[b]];
            rhs[a] -= alpha * rn;
        }
    }
    CX_TRY(cx_dense_lu_solve(nf, M, rhs, st->ipiv, cnt));
    for (int k = 0; k < nc; k++)
        st->uc[k] = st->pin[k] < 0 ? rhs[st->fpos[k]] : st->up[k];
    /* a pinned dof's equilibrium row holds its multiplier alone */
    for (int k = 0; k < nc; k++) {
        int r = st->pin[k], col;
        if (r < 0)
            continue;
        const cx_csc *R = coul_row(st, m, r, &col);
        double Su = 0;
        for (int j = 0; j < nc; j++)
            Su += S[k + (size_t)nc * j] * st->uc[j];
        lam[st->aidx[r]] = (st->fc[k] - Su) / R->x[R->p[col]];
    }
    return CX_OK;
}

/* Solve the Newton system of the current sets: uc, it->lN, it->lT. */
static int coul_solve(coul_state *st, const cx_problem *p, cx_iterate *it, cx_counters *cnt, cx_diag *d)
{
    int m = p->m, na = coul_active(st, p);
    int status = coul_pin(st, p, na);
    if (status == CX_OK)
        status = coul_solve_pinned(st, p, cnt, st->lam);
    else
        status = coul_solve_full(st, p, na, cnt, st->lam);
    if (status != CX_OK)
        return cx_diag_set(d, status, "ssn-coulomb: the Newton system at iteration %d is singular: its %d "
                           "active rows do not hold the bodies, or repeat a constraint", it->iter + 1, na);
    memset(it->lN, 0, sizeof(double) * (size_t)m);
    memset(it->lT, 0, sizeof(double) * (size_t)p->nt);
    for (int a = 0; a < na; a++) {
        int r = st->act[a];
        if (r < m)
            it->lN[r] = st->lam[a];
        else
            it->lT[r - m] = st->lam[a];
    }
    for (int i = 0; i < p->nt; i++) {
        double c = coul_slip(st, i);
        if (c != 0)
            it->lT[i] = c * it->lN[i];
    }
    return CX_OK;
}

static int coul_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    coul_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    int m = p->m, nt = p->nt, nc = st->nc;

    int from_start = st->first;
    if (!st->first) {
        coul_sets(st, p, it);
        if (memcmp(st->setN, st->prevN, (size_t)m) == 0 && memcmp(st->setT, st->prevT, (size_t)nt) == 0) {
            it->own = 0;
            it->own_done = 1;
            return CX_OK;
        }
    }
    st->first = 0;
    memcpy(st->prevN, st->setN, (size_t)m);
    memcpy(st->prevT, st->setT, (size_t)nt);
    for (int k = 0; k < nc; k++)
        st->uprev[k] = it->u[p->cdofs[k]];
    CX_TRY(coul_solve(st, p, it, cx_session_counters(s), d));

    /* u on the contact dofs only: the solver expands it when the run ends */
    for (int k = 0; k < nc; k++)
        it->u[p->cdofs[k]] = st->uc[k];
    it->u_partial = 1;
    cx_vec_axpy(nc, -1.0, st->uc, st->uprev);
    double nu = cx_vec_norm2(nc, st->uc);
    double du = cx_vec_norm2(nc, st->uprev);
    it->own = nu > 0 ? du / nu : (du > 0 ? 1 : 0);
    /* the start's other dofs are not the expansion of its contact dofs
     * (later iterates' are): an unchanged u_c says nothing there */
    it->own_done = !from_start && it->own <= st->eps;
    return CX_OK;
}

const cx_method cx_method_ssn_coulomb = {
    .id = "ssn-coulomb",
    .name = "Semismooth Newton / active set (Coulomb)",
    .source = "000 §4.1",
    .summary = "non-symmetric active-set Newton on (u, lN, lT), condensed onto the contact dofs: dense LU per step",
    .supports = CX_COULOMB | CX_2D | CX_MULTIBODY,
    .state_size = sizeof(coul_state),
    .params = coul_params,
    .init = coul_init,
    .step = coul_step,
    .destroy = coul_destroy,
};
