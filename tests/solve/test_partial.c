/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Partial iterates (solve.h): a method on the condensed system updates u on
 * the contact dofs only, the kkt error is evaluated on the condensed
 * system, and u is expanded once, when the run ends.
 *
 * 1. The condensed kkt error equals the full one, part by part, for any
 *    u_c and multipliers once the other dofs are their exact expansion
 *    (hertz, frictionless and Tresca).
 * 2. ssn-tresca: the run ends whole, with 2 solves (condense f, expand u)
 *    and 1 product with K, and the same u and kkt as a run completed after
 *    every step; mid-run the iterate is partial, and completing it gives
 *    the full kkt error.
 * 3. A warm start from the solution: ssn-tresca repeats its sets at once.
 * 4. cf-fp (inner=auto: ssn-tresca) on Coulomb: one factorisation, 2 solves
 *    for the whole run, kkt 1e-9. */
#include "run_fixture.h"

static double rnd(unsigned *x)
{
    *x = *x * 1664525u + 1013904223u;
    return (double)(*x >> 8) / (double)(1u << 24) - 0.5;
}

static void check_condensed_kkt(cx_friction law)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("hertz", 12, &sc);
    const cx_problem *p = cx_session_problem(s);
    if (law != CX_FRICTION_NONE)
        CX_CHECK_OK(cx_session_set_friction(s, &(cx_friction_state){law, 20, 20, NULL, NULL}, &d));
    cx_schur *S;
    const double *fc;
    CX_CHECK_OK(cx_session_schur(s, &S, &fc, &d));
    int n = p->n, m = p->m, nc = p->nc;
    double *u = calloc((size_t)n, sizeof(double)), *uc = calloc((size_t)nc, sizeof(double));
    double *lN = calloc((size_t)m, sizeof(double)), *lT = calloc((size_t)m, sizeof(double));
    double *work = calloc((size_t)(n + m + p->nt), sizeof(double));
    unsigned seed = 7;
    for (int trial = 0; trial < 3; trial++) {
        /* displacements of a few percent of the radius, forces of the load's size */
        for (int k = 0; k < nc; k++)
            uc[k] = 0.05 * rnd(&seed);
        for (int i = 0; i < m; i++) {
            lN[i] = 40 * rnd(&seed);
            lT[i] = 10 * rnd(&seed);
        }
        CX_CHECK_OK(cx_schur_expand(S, p->f, uc, u));
        cx_kkt full, cond;
        cx_kkt_error(p, cx_session_friction(s), u, lN, lT, work, NULL, &full);
        cx_kkt_error_condensed(p, cx_session_friction(s), cx_schur_matrix(S), fc, u, lN, lT, work, &cond);
        fprintf(stderr, "hertz 12 %s: kkt full %.6e (%.3e %.3e %.3e) condensed %.6e (%.3e)\n",
                cx_friction_name(law), full.total, full.equilibrium, full.contact, full.friction, cond.total,
                cond.equilibrium);
        CX_CHECK(full.equilibrium > 1e-3);   /* a point far from equilibrium */
        CX_CHECK_NEAR(cond.equilibrium, full.equilibrium, 1e-9, 0);
        CX_CHECK_NEAR(cond.contact, full.contact, 1e-12, 0);
        CX_CHECK_NEAR(cond.friction, full.friction, 1e-12, 0);
        CX_CHECK_NEAR(cond.total, full.total, 1e-9, 0);
    }
    free(u);
    free(uc);
    free(lN);
    free(lT);
    free(work);
    cx_session_destroy(&s);
}

static void check_ssn_run(void)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("hertz", 32, &sc);
    const cx_problem *p = cx_session_problem(s);
    CX_CHECK_OK(cx_session_set_tresca(s, 20, &d));
    const cx_iterate *it = cx_session_iterate(s);

    /* the run as a library user makes it */
    CX_CHECK_OK(fixture_run(s, "ssn-tresca", "", 1, 1e-10, 50, &d));
    CX_CHECK(it->reason > 0 && it->u_partial == 0);
    CX_CHECK(it->counters.factorizations == 1);
    CX_CHECK(it->counters.solves == 2);
    CX_CHECK(it->counters.matvecs == 1);
    double kkt1 = it->kkt;
    int iter1 = it->iter;
    double *u1 = fixture_copy_u(s);
    cx_kkt check;
    double *work = calloc((size_t)(p->n + p->m + p->nt), sizeof(double));
    CX_CHECK_NEAR(cx_kkt_error(p, cx_session_friction(s), it->u, it->lN, it->lT, work, NULL, &check), kkt1, 1e-12, 0);
    CX_CHECK_LE(kkt1, 1e-10);

    /* step by step, completing each iterate as the explorer does */
    CX_CHECK_OK(cx_session_reset(s, &d));
    int partial_seen = 0;
    while (it->reason == CX_ITERATING) {
        CX_CHECK_OK(cx_solver_step(s, &d));
        partial_seen += it->u_partial;
        double kkt_cond = it->kkt;
        int was_partial = it->u_partial;
        CX_CHECK_OK(cx_session_complete_iterate(s, &d));
        CX_CHECK(it->u_partial == 0);
        double kkt_full = cx_kkt_error(p, cx_session_friction(s), it->u, it->lN, it->lT, work, NULL, &check);
        CX_CHECK_NEAR(it->kkt, kkt_full, 1e-12, 1e-15);
        /* the equilibrium part is exact on the condensed system; the rest
         * differs only through the displacement scale */
        if (was_partial && kkt_full > 1e-6)
            CX_CHECK_NEAR(kkt_cond, kkt_full, 0.5, 0);
    }
    fprintf(stderr, "hertz 32 tresca: ssn-tresca %d iterations (stepped: %d, %d partial), kkt %.2e\n", iter1,
            it->iter, partial_seen, it->kkt);
    CX_CHECK(partial_seen > 0);
    CX_CHECK(it->iter == iter1);
    CX_CHECK_LE(fixture_energy_diff(p, it->u, u1), 1e-13);

    /* a warm start from the solution: the sets repeat at the first check */
    double *lN = malloc(sizeof(double) * (size_t)p->m), *lT = malloc(sizeof(double) * (size_t)p->nt);
    memcpy(lN, it->lN, sizeof(double) * (size_t)p->m);
    memcpy(lT, it->lT, sizeof(double) * (size_t)p->nt);
    CX_CHECK_OK(cx_session_set_start(s, u1, lN, lT, &d));
    CX_CHECK_OK(fixture_run(s, "ssn-tresca", "", 1, 1e-10, 50, &d));
    fprintf(stderr, "  warm started: %d iterations, kkt %.2e\n", it->iter, it->kkt);
    CX_CHECK(it->reason > 0 && it->iter <= 2);
    CX_CHECK_LE(fixture_energy_diff(p, it->u, u1), 1e-12);
    CX_CHECK_OK(cx_session_set_start(s, NULL, NULL, NULL, &d));
    free(lN);
    free(lT);
    free(u1);
    free(work);
    cx_session_destroy(&s);
}

static void check_cffp_coulomb(void)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("hertz", 32, &sc);
    CX_CHECK_OK(cx_session_set_coulomb(s, 0.3, &d));
    const cx_iterate *it = cx_session_iterate(s);
    CX_CHECK_OK(fixture_run(s, "cf-fp", "", 0, 1e-9, 40, &d));
    fprintf(stderr, "hertz 32 coulomb: cf-fp %d steps, %ld inner iterations, kkt %.2e, %ld factorisations, "
            "%ld solves, %d stick %d slip\n", it->iter, it->inner_total, it->kkt, it->counters.factorizations,
            it->counters.solves, it->nstick, it->nslip);
    CX_CHECK(it->reason == CX_CONVERGED_KKT && it->u_partial == 0);
    CX_CHECK(it->iter >= 4 && it->iter <= 15);
    CX_CHECK(it->nstick > 0 && it->nslip > 0);
    CX_CHECK(it->counters.factorizations == 1);
    CX_CHECK(it->counters.solves == 2);
    /* warm-started inner runs: after the first steps, one solve and a check */
    CX_CHECK_LE(it->inner_total, 20 + 2 * it->iter);
    cx_session_destroy(&s);
}

int main(void)
{
    check_condensed_kkt(CX_FRICTION_NONE);
    check_condensed_kkt(CX_FRICTION_TRESCA);
    check_ssn_run();
    check_cffp_coulomb();
    return check_finish("solve_partial");
}
