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
 *     (T u)_i = 0 on A_t,          lT_i = +-F_i lN_i on I+-_t,
 * with UMFPACK (cx_fact CX_FACT_LU): the pattern holds every entry any set
 * can need, so it is analysed once in init and only refactorised. The
 * multipliers are scaled by the stiffness scale kappa (unknowns lambda /
 * kappa, constraint rows times kappa) so that all blocks have like sizes.
 * The first iteration takes every point in contact and sticking (the
 * bonded start, which holds a body whatever K's null space); rho matters
 * only for the next sets (000 §4.1). Own criterion (step 3):
 * ||u^k - u^(k-1)|| / ||u^k|| <= eps, or sets that repeat (then the last
 * iterate solves G(y) = 0 exactly). A row with no free dof (a contact
 * point whose motion is all prescribed) constrains nothing: its multiplier
 * is 0. */
#include "solve/solve.h"

#include <math.h>
#include <string.h>

typedef struct {
    cx_fact *F;          /* UMFPACK LU of the Newton matrix */
    cx_csc J;            /* (n + 2m)^2 Newton matrix, fixed pattern */
    int nsys;            /* n + m + nt */
    int *role;           /* nnz(J): what each entry is (see coul_fill) */
    int *rowi;           /* nnz(J): the contact point of a constraint entry */
    double *base;        /* nnz(J): the entry's value when present */
    double *rhs, *x;     /* nsys */
    double *uprev;       /* n */
    double *Nu, *Tu;     /* m, nt */
    signed char *setN;   /* m: 1 contact, 0 not */
    signed char *setT;   /* nt: 0 stick, +1 / -1 slip */
    signed char *prevN, *prevT;
    unsigned char *emptyN, *emptyT;  /* m, nt: rows with no free dof */
    double rho;          /* natural-map parameter (stiffness units) */
    double kappa;        /* multiplier scaling */
    double eps;
    int first;           /* the bonded start is still to be done */
} coul_state;

enum { R_FIXED, R_NROW, R_NDIAG, R_TROW, R_TCOUPLE, R_TDIAG };

static const cx_param coul_params[] = {
    {"rho", CX_PARAM_REAL, 1e-3, 1e-12, 1e12, NULL,
     "active-set parameter, relative to the largest diagonal entry of K", 0},
    {"eps", CX_PARAM_REAL, 1e-12, 0, 1, NULL, "own stop: ||u^k - u^(k-1)|| / ||u^k|| <= eps", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void coul_destroy(void *state)
{
    coul_state *st = state;
    cx_fact_destroy(&st->F);
    cx_csc_clear(&st->J);
    cx_free(st->role);
    cx_free(st->rowi);
    cx_free(st->base);
    cx_free(st->rhs);
    cx_free(st->x);
    cx_free(st->uprev);
    cx_free(st->Nu);
    cx_free(st->Tu);
    cx_free(st->setN);
    cx_free(st->setT);
    cx_free(st->prevN);
    cx_free(st->prevT);
    cx_free(st->emptyN);
    cx_free(st->emptyT);
    memset(st, 0, sizeof *st);
}

/* Position of (i, j) in J (present by construction). */
static int coul_find(const cx_csc *J, int i, int j)
{
    int lo = J->p[j], hi = J->p[j + 1] - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        if (J->i[mid] == i)
            return mid;
        if (J->i[mid] < i)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

/* The pattern of every Newton matrix, the role of each entry and its value
 * when present. */
static int coul_pattern(coul_state *st, const cx_problem *p)
{
    int n = p->n, m = p->m, nt = p->nt;
    double k = st->kappa;
    size_t cap = cx_csc_nnz(&p->K) + 2 * (cx_csc_nnz(&p->N) + cx_csc_nnz(&p->T)) + (size_t)(m + 2 * nt);
    cx_triplet t;
    CX_TRY(cx_triplet_init(&t, st->nsys, st->nsys, cap));
    int rc = CX_OK;
    for (int j = 0; j < n && !rc; j++)
        for (int q = p->K.p[j]; q < p->K.p[j + 1] && !rc; q++)
            rc = cx_triplet_add(&t, p->K.i[q], j, p->K.x[q]);
    const cx_csc *B[2] = {&p->N, &p->T};
    for (int b = 0; b < 2; b++)
        for (int j = 0; j < n && !rc; j++)
            for (int q = B[b]->p[j]; q < B[b]->p[j + 1] && !rc; q++) {
                int r = n + b * m + B[b]->i[q];
                if (!(rc = cx_triplet_add(&t, j, r, k * B[b]->x[q])))
                    rc = cx_triplet_add(&t, r, j, k * B[b]->x[q]);
            }
    for (int i = 0; i < m && !rc; i++)
        rc = cx_triplet_add(&t, n + i, n + i, 1.0);
    for (int i = 0; i < nt && !rc; i++)
        if (!(rc = cx_triplet_add(&t, n + m + i, n + i, 0.0)))
            rc = cx_triplet_add(&t, n + m + i, n + m + i, 1.0);
    if (!rc)
        rc = cx_csc_from_triplet(&st->J, &t);
    if (rc) {
        cx_triplet_clear(&t);
        return rc;
    }
    size_t nnz = cx_csc_nnz(&st->J);
    st->role = CX_NEW(int, nnz);
    st->rowi = CX_NEW(int, nnz);
    st->base = CX_NEW(double, nnz);
    if (!st->role || !st->rowi || !st->base) {
        cx_triplet_clear(&t);
        return CX_ENOMEM;
    }
    for (size_t e = 0; e < t.nnz; e++) {
        int i = t.i[e], j = t.j[e], pos = coul_find(&st->J, i, j), role = R_FIXED, pt = 0;
        if (i >= n + m) {
            pt = i - n - m;
            role = j < n ? R_TROW : (j == i ? R_TDIAG : R_TCOUPLE);
        } else if (i >= n) {
            pt = i - n;
            role = j < n ? R_NROW : R_NDIAG;
        }
        st->role[pos] = role;
        st->rowi[pos] = pt;
        st->base[pos] = t.x[e];
    }
    cx_triplet_clear(&t);
    return CX_OK;
}

/* The values of J for the current sets (000 §4.1, step (2)). */
static void coul_fill(coul_state *st, const cx_problem *p)
{
    size_t nnz = cx_csc_nnz(&st->J);
    for (size_t e = 0; e < nnz; e++) {
        int i = st->rowi[e];
        double v = st->base[e];
        switch (st->role[e]) {
        case R_NROW: v = st->setN[i] == 1 && !st->emptyN[i] ? v : 0; break;
        case R_NDIAG: v = st->setN[i] == 1 && !st->emptyN[i] ? 0 : 1; break;
        case R_TROW: v = st->setT[i] == 0 && !st->emptyT[i] ? v : 0; break;
        case R_TDIAG: v = st->setT[i] == 0 && !st->emptyT[i] ? 0 : 1; break;
        case R_TCOUPLE: v = st->emptyT[i] ? 0 : -st->setT[i] * p->Fi[i]; break;
        default: break;
        }
        st->J.x[e] = v;
    }
}

static int coul_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    coul_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    if (p->friction != CX_FRICTION_COULOMB)
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "method 'ssn-coulomb' solves Coulomb friction only (use ssn-tresca for %s)",
                           p->friction == CX_FRICTION_TRESCA ? "Tresca" : "frictionless contact");
    int n = p->n, m = p->m, nt = p->nt, rc;
    st->nsys = n + m + nt;
    st->kappa = p->kscale > 0 ? p->kscale : 1;
    st->rho = cx_param_get(params, "rho") * st->kappa;
    st->eps = cx_param_get(params, "eps");
    st->rhs = CX_NEW(double, st->nsys);
    st->x = CX_NEW(double, st->nsys);
    st->uprev = CX_NEW(double, n);
    st->Nu = CX_NEW(double, m + 1);
    st->Tu = CX_NEW(double, nt + 1);
    st->setN = CX_NEW(signed char, m + 1);
    st->setT = CX_NEW(signed char, nt + 1);
    st->prevN = CX_NEW(signed char, m + 1);
    st->prevT = CX_NEW(signed char, nt + 1);
    st->emptyN = CX_NEW(unsigned char, m + 1);
    st->emptyT = CX_NEW(unsigned char, nt + 1);
    if (!st->rhs || !st->x || !st->uprev || !st->Nu || !st->Tu || !st->setN || !st->setT || !st->prevN ||
        !st->prevT || !st->emptyN || !st->emptyT || (rc = coul_pattern(st, p)) == CX_ENOMEM) {
        coul_destroy(st);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    if (rc) {
        coul_destroy(st);
        return cx_diag_set(d, rc, "ssn-coulomb: cannot build the Newton matrix");
    }
    for (int i = 0; i < m; i++)
        st->emptyN[i] = 1;
    for (int i = 0; i < nt; i++)
        st->emptyT[i] = 1;
    for (int j = 0; j < n; j++) {
        for (int q = p->N.p[j]; q < p->N.p[j + 1]; q++)
            st->emptyN[p->N.i[q]] = 0;
        for (int q = p->T.p[j]; q < p->T.p[j + 1]; q++)
            st->emptyT[p->T.i[q]] = 0;
    }
    /* the bonded start: all in contact, sticking; analyse that pattern */
    memset(st->setN, 1, (size_t)m);
    memset(st->setT, 0, (size_t)nt);
    coul_fill(st, p);
    if ((rc = cx_fact_create(&st->F, CX_FACT_LU, cx_session_counters(s), d)) ||
        (rc = cx_fact_analyze(st->F, &st->J, d))) {
        coul_destroy(st);
        return rc;
    }
    st->first = 1;
    return CX_OK;
}

/* Sets (15)-(17) at the iterate. */
static void coul_sets(coul_state *st, const cx_problem *p, const cx_iterate *it)
{
    cx_csc_gemv(&p->N, 1.0, it->u, 0.0, st->Nu);
    cx_csc_gemv(&p->T, 1.0, it->u, 0.0, st->Tu);
    for (int i = 0; i < p->m; i++)
        st->setN[i] = it->lN[i] + st->rho * (st->Nu[i] - p->g[i]) > 0;
    for (int i = 0; i < p->nt; i++) {
        double z = it->lT[i] + st->rho * st->Tu[i], b = p->Fi[i] * it->lN[i];
        st->setT[i] = z > b ? 1 : (z < -b ? -1 : 0);
    }
}

static int coul_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    coul_state *st = state;
    const cx_problem *p = cx_session_problem(s);
    int n = p->n, m = p->m, nt = p->nt;

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

    coul_fill(st, p);
    memset(st->rhs, 0, sizeof(double) * (size_t)st->nsys);
    memcpy(st->rhs, p->f, sizeof(double) * (size_t)n);
    for (int i = 0; i < m; i++)
        if (st->setN[i] == 1 && !st->emptyN[i])
            st->rhs[n + i] = st->kappa * p->g[i];
    int rc = cx_fact_factorize(st->F, &st->J, d);
    if (rc == CX_OK)
        rc = cx_fact_solve(st->F, st->rhs, st->x, d);
    if (rc != CX_OK)
        return cx_diag_set(d, rc, "ssn-coulomb: the Newton system at iteration %d cannot be solved (%s)",
                           it->iter + 1, d ? d->msg : "");
    memcpy(st->uprev, it->u, sizeof(double) * (size_t)n);
    memcpy(it->u, st->x, sizeof(double) * (size_t)n);
    for (int i = 0; i < m; i++)
        it->lN[i] = st->kappa * st->x[n + i];
    for (int i = 0; i < nt; i++)
        it->lT[i] = st->kappa * st->x[n + m + i];

    cx_vec_axpy(n, -1.0, it->u, st->uprev);
    double nu = cx_vec_norm2(n, it->u);
    it->own = nu > 0 ? cx_vec_norm2(n, st->uprev) / nu : 0;
    it->own_done = it->own <= st->eps;
    return CX_OK;
}

const cx_method cx_method_ssn_coulomb = {
    .id = "ssn-coulomb",
    .name = "Semismooth Newton / active set (Coulomb)",
    .source = "000 §4.1",
    .summary = "non-symmetric active-set Newton on (u, lN, lT), UMFPACK LU analysed once",
    .supports = CX_COULOMB | CX_2D | CX_MULTIBODY,
    .state_size = sizeof(coul_state),
    .params = coul_params,
    .init = coul_init,
    .step = coul_step,
    .destroy = coul_destroy,
};
