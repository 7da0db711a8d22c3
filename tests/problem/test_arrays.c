/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cx_problem_from_data (src/solve/problem_arrays.c): the same problem given
 * as triplets of K's lower triangle or as CSC in full gives the same
 * solution; the solution meets the conditions of solve/problem.h; every
 * bad input is refused with a line naming the array and the entry; every
 * failed allocation is CX_ENOMEM with nothing leaked. */
#include "solve/solve.h"
#include "check.h"

#include <string.h>

enum { M = 8, NU = 2 * M };

typedef struct {
    int Ki[8 * M], Kj[8 * M];   /* 2 springs of 3 entries and 2 anchors per node */
    double Kx[8 * M];
    size_t knz;
    int Ni[M], Nj[M], Ti[M], Tj[M];
    double Nx[M], Tx[M], f[NU], g[M], mu[M];
} chain;

/* The spring chain of examples/arrays.c, K's lower triangle as triplets. */
static void chain_init(chain *c)
{
    memset(c, 0, sizeof *c);
    for (int k = 0; k < M; k++) {
        for (int comp = 0; comp < 2 && k + 1 < M; comp++) {
            int a = 2 * k + comp, b = 2 * k + 2 + comp;
            double s = comp ? 50 : 100;
            c->Ki[c->knz] = a, c->Kj[c->knz] = a, c->Kx[c->knz++] = s;
            c->Ki[c->knz] = b, c->Kj[c->knz] = b, c->Kx[c->knz++] = s;
            c->Ki[c->knz] = b, c->Kj[c->knz] = a, c->Kx[c->knz++] = -s;
        }
        c->Ki[c->knz] = c->Kj[c->knz] = 2 * k, c->Kx[c->knz++] = 1;
        c->Ki[c->knz] = c->Kj[c->knz] = 2 * k + 1, c->Kx[c->knz++] = 1;
        double x = (double)k / (M - 1) - 0.5;
        c->f[2 * k] = 0.25;
        c->f[2 * k + 1] = -1;
        c->g[k] = 0.2 + x * x;
        c->Ni[k] = k, c->Nj[k] = 2 * k + 1, c->Nx[k] = -1;
        c->Ti[k] = k, c->Tj[k] = 2 * k, c->Tx[k] = 1;
        c->mu[k] = k < M / 2 ? 0.3 : 0.6;
    }
}

static cx_problem_data chain_data(chain *c)
{
    cx_problem_data pd = {.dim = 2, .n = NU, .m = M,
                          .K = {CX_SPARSE_TRIPLET, NU, NU, c->knz, NULL, c->Ki, c->Kj, c->Kx}, .K_lower = 1,
                          .f = c->f,
                          .N = {CX_SPARSE_TRIPLET, M, NU, M, NULL, c->Ni, c->Nj, c->Nx},
                          .T = {CX_SPARSE_TRIPLET, M, NU, M, NULL, c->Ti, c->Tj, c->Tx},
                          .g = c->g};
    return pd;
}

/* Solve pd with ssn-coulomb and per-point mu; u (NU) out. */
static int chain_solve(const cx_problem_data *pd, const double *mu, double *u, int *iter)
{
    cx_diag d;
    cx_problem *p = NULL;
    cx_session *s = NULL;
    int st = cx_problem_from_data(&p, pd, &d);
    if (!st)
        st = cx_session_create(&s, &p, &d);
    cx_friction_state fr = {CX_FRICTION_COULOMB, 0, 0, NULL, mu};
    if (!st)
        st = cx_session_set_friction(s, &fr, &d);
    if (!st)
        st = cx_session_set_method(s, cx_method_find("ssn-coulomb"), NULL, NULL, &d);
    if (!st)
        st = cx_solver_solve(s, NULL, NULL, &d);
    if (st)
        fprintf(stderr, "chain_solve: %s\n", d.msg);
    if (!st) {
        const cx_iterate *it = cx_session_iterate(s);
        const cx_problem *cp = cx_session_problem(s);
        memcpy(u, it->u, sizeof(double) * NU);
        *iter = it->iter;
        CX_CHECK(it->reason == CX_CONVERGED_KKT);
        CX_CHECK(cp->mesh == NULL && cp->nc == NU);
        /* the conditions of solve/problem.h */
        double r[NU], Nu[M], Tu[M];
        cx_csc_gemv(&cp->K, 1, it->u, 0, r);
        cx_csc_gemv_t(&cp->N, 1, it->lN, 1, r);
        cx_csc_gemv_t(&cp->T, 1, it->lT, 1, r);
        cx_csc_gemv(&cp->N, 1, it->u, 0, Nu);
        cx_csc_gemv(&cp->T, 1, it->u, 0, Tu);
        double rmax = 0;
        for (int i = 0; i < NU; i++)
            rmax = fmax(rmax, fabs(r[i] - pd->f[i]));
        CX_CHECK_LE(rmax, 1e-9);
        int slipping = 0;
        for (int i = 0; i < M; i++) {
            CX_CHECK(it->lN[i] >= 0);
            CX_CHECK_LE(Nu[i] - pd->g[i], 1e-12);
            CX_CHECK_LE(fabs(it->lT[i]), mu[i] * it->lN[i] + 1e-12);
            if (it->status[i] >= CX_PT_SLIP_POS) {
                slipping++;
                CX_CHECK(Tu[i] * it->lT[i] >= 0);
            }
        }
        CX_CHECK(slipping > 0 && slipping < M);
    }
    cx_session_destroy(&s);
    cx_problem_destroy(&p);
    return st;
}

/* The message of a refused pd holds needle. */
static void refused(const cx_problem_data *pd, const char *needle)
{
    cx_diag d;
    cx_problem *p = NULL;
    int st = cx_problem_from_data(&p, pd, &d);
    CX_CHECK(st == CX_EINVAL && p == NULL);
    if (!strstr(d.msg, needle)) {
        fprintf(stderr, "expected '%s' in '%s'\n", needle, d.msg);
        CX_CHECK(0);
    }
    cx_problem_destroy(&p);
}

int main(void)
{
    chain c;
    chain_init(&c);
    cx_problem_data pd = chain_data(&c);
    double u1[NU], u2[NU];
    int it1 = 0, it2 = 0;
    CX_CHECK_OK(chain_solve(&pd, c.mu, u1, &it1));

    /* the same in CSC, K in full */
    cx_triplet t;
    cx_csc K = {0}, N = {0}, T = {0};
    CX_CHECK_OK(cx_triplet_init(&t, NU, NU, 2 * c.knz));
    for (size_t k = 0; k < c.knz; k++) {
        cx_triplet_add(&t, c.Ki[k], c.Kj[k], c.Kx[k]);
        if (c.Ki[k] != c.Kj[k])
            cx_triplet_add(&t, c.Kj[k], c.Ki[k], c.Kx[k]);
    }
    CX_CHECK_OK(cx_csc_from_triplet(&K, &t));
    cx_triplet_clear(&t);
    CX_CHECK_OK(cx_triplet_init(&t, M, NU, M));
    for (int k = 0; k < M; k++)
        cx_triplet_add(&t, c.Ni[k], c.Nj[k], c.Nx[k]);
    CX_CHECK_OK(cx_csc_from_triplet(&N, &t));
    cx_triplet_clear(&t);
    CX_CHECK_OK(cx_triplet_init(&t, M, NU, M));
    for (int k = 0; k < M; k++)
        cx_triplet_add(&t, c.Ti[k], c.Tj[k], c.Tx[k]);
    CX_CHECK_OK(cx_csc_from_triplet(&T, &t));
    cx_triplet_clear(&t);
    cx_problem_data pc = pd;
    pc.K = (cx_sparse_data){CX_SPARSE_CSC, NU, NU, 0, K.p, K.i, NULL, K.x};
    pc.K_lower = 0;
    pc.N = (cx_sparse_data){CX_SPARSE_CSC, M, NU, 0, N.p, N.i, NULL, N.x};
    pc.T = (cx_sparse_data){CX_SPARSE_CSC, M, NU, 0, T.p, T.i, NULL, T.x};
    CX_CHECK_OK(chain_solve(&pc, c.mu, u2, &it2));
    CX_CHECK(it1 == it2);
    for (int i = 0; i < NU; i++)
        CX_CHECK_NEAR(u2[i], u1[i], 1e-13, 1e-15);

    /* refusals, each naming the array and the entry */
    cx_problem_data bad = pd;
    bad.dim = 4;
    refused(&bad, "dimension 4");
    int Ki = c.Ki[2], Kj = c.Kj[2];   /* (2, 0): the first spring's off-diagonal entry */
    c.Kj[2] = 3;
    refused(&pd, "K: entry 2 (row 2, column 3): above the diagonal (K_lower)");
    c.Kj[2] = Kj;
    c.Ki[2] = NU;
    refused(&pd, "K: entry 2 (row 16, column 0): index out of range");
    c.Ki[2] = Ki;
    c.Kx[0] = NAN;
    refused(&pd, "K: entry 0 (row 0, column 0): not a finite value");
    c.Kx[0] = 101;
    pc.K.x = K.x;
    K.x[1] += 1e-6;           /* K(1, 0) no longer K(0, 1)... */
    refused(&pc, "K: not symmetric at row");
    K.x[1] -= 1e-6;
    c.Kx[0] = 100;
    c.g[3] = -0.1;
    refused(&pd, "g: entry 3 is -0.1, expected a finite value >= 0");
    c.g[3] = 0.1;
    bad = pd;
    bad.T.nrow = 2 * M;
    refused(&bad, "T: 16 x 16, expected 8 x 16");
    bad = pc;
    int p0 = N.p[0];
    N.p[0] = 1;
    refused(&bad, "N: p[0] is 1, expected 0");
    N.p[0] = p0;
    double w[M];
    for (int i = 0; i < M; i++)
        w[i] = 1;
    w[5] = -1;
    bad = pd;
    bad.weight = w;
    refused(&bad, "weight: entry 5 is -1");

    /* the stiffness scale penalty methods use */
    cx_diag d;
    cx_problem *p = NULL;
    bad = pd;
    bad.E = 210e3;
    CX_CHECK_OK(cx_problem_from_data(&p, &bad, &d));
    CX_CHECK(cx_problem_stiffness(p) == 210e3);
    cx_problem_destroy(&p);
    CX_CHECK_OK(cx_problem_from_data(&p, &pd, &d));
    CX_CHECK(cx_problem_stiffness(p) == p->kscale && p->kscale == 201);
    cx_problem_destroy(&p);

    /* every failed allocation: CX_ENOMEM, nothing leaked */
    long live = cx_alloc_live();
    int n, fails = 0;
    for (n = 0; n < 1000; n++) {
        cx_alloc_fail_after(n);
        int st = cx_problem_from_data(&p, &pc, &d);
        cx_alloc_fail_after(-1);
        cx_problem_destroy(&p);
        CX_CHECK(cx_alloc_live() == live);
        if (!st)
            break;
        CX_CHECK(st == CX_ENOMEM);
        fails++;
    }
    CX_CHECK(fails > 8 && n < 1000);
    cx_csc_clear(&K);
    cx_csc_clear(&N);
    cx_csc_clear(&T);
    return check_finish("problem_arrays");
}
