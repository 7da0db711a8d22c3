/* SPDX-License-Identifier: GPL-3.0-or-later */
/* ssn-coulomb (paper 000 §4.1, ActiveSetCoulomb) on the condensed system:
 * one sparse factorisation per run (the session's Schur complement; none
 * when the session already holds it), a dense factorisation per Newton
 * step, counted apart; 2 solves (condense f, expand u); the iteration
 * counts the method had on the whole system (hertz 32/64: 7/8, slider 4:
 * 4, twoblocks 10: 3, all F = 0.3); the answer of another method on the
 * same problem: cf-fp (Coulomb by successive Tresca problems) on hertz,
 * where the active rows pin dofs (the eliminated system), and on
 * twoblocks (node-to-segment rows: the whole condensed system), the
 * fixed point, ssn-tresca with the slip bounds s = F lN of the answer. */
#include "run_fixture.h"

typedef struct {
    const char *scene;
    int level;
    int iters;        /* on the whole system, before the condensation */
} coul_case;

/* ssn-coulomb at F = 0.3 to kkt 1e-11 on a fresh session; its checks. */
static cx_session *coul_run(const coul_case *c)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session(c->scene, c->level, &sc);
    CX_CHECK_OK(cx_session_set_coulomb(s, 0.3, &d));
    CX_CHECK_OK(fixture_run(s, "ssn-coulomb", "", 1, 1e-11, 50, &d));
    const cx_iterate *it = cx_session_iterate(s);
    fprintf(stderr, "%s %d coulomb 0.3: ssn-coulomb %d iterations (before: %d), kkt %.2e, %ld sparse and %ld "
            "dense factorisations, %ld solves, %d stick %d slip\n", c->scene, c->level, it->iter, c->iters,
            it->kkt, it->counters.factorizations, it->counters.dense_factorizations, it->counters.solves,
            it->nstick, it->nslip);
    CX_CHECK(it->reason == CX_CONVERGED_KKT);
    CX_CHECK_LE(it->kkt, 1e-11);
    CX_CHECK(it->u_partial == 0);
    CX_CHECK(abs(it->iter - c->iters) <= 1);
    CX_CHECK(it->counters.factorizations == 1);
    CX_CHECK(it->counters.dense_factorizations >= 1 && it->counters.dense_factorizations <= it->iter);
    CX_CHECK(it->counters.solves == 2);
    CX_CHECK(it->nslip > 0);
    /* a second run: the Schur complement is the session's already */
    CX_CHECK_OK(fixture_run(s, "ssn-coulomb", "", 1, 1e-11, 50, &d));
    CX_CHECK(it->counters.factorizations == 0);
    CX_CHECK_LE(it->kkt, 1e-11);
    return s;
}

/* hertz: against cf-fp to kkt 1e-12 */
static void check_against_cffp(const coul_case *c)
{
    cx_diag d;
    cx_session *s = coul_run(c);
    const cx_problem *p = cx_session_problem(s);
    const cx_iterate *it = cx_session_iterate(s);
    double *u = fixture_copy_u(s);
    CX_CHECK_OK(fixture_run(s, "cf-fp", "inner=ssn-tresca eps_min=1e-14 eps_fp=1e-14", 0, 1e-12, 100, &d));
    double e = fixture_energy_diff(p, u, it->u);
    fprintf(stderr, "  cf-fp: %d steps, kkt %.2e; energy-norm difference %.2e\n", it->iter, it->kkt, e);
    CX_CHECK(it->reason == CX_CONVERGED_KKT);
    CX_CHECK_LE(e, 1e-8);
    free(u);
    cx_session_destroy(&s);
}

/* twoblocks: the Tresca problem with s = F lN of the answer has the same
 * answer (ssn-tresca, another code path through the same Schur complement) */
static void check_fixed_point(const coul_case *c)
{
    cx_diag d;
    cx_session *s = coul_run(c);
    const cx_problem *p = cx_session_problem(s);
    const cx_iterate *it = cx_session_iterate(s);
    double *u = fixture_copy_u(s), *sb = malloc(sizeof(double) * (size_t)p->m);
    for (int i = 0; i < p->m; i++)
        sb[i] = cx_session_friction(s)->Fi[i] * it->lN[i];
    cx_session_clear_method(s);
    CX_CHECK_OK(cx_session_set_slip_bounds(s, sb, &d));
    CX_CHECK_OK(fixture_run(s, "ssn-tresca", "", 1, 1e-11, 50, &d));
    double e = fixture_energy_diff(p, u, it->u);
    fprintf(stderr, "  ssn-tresca with s = F lN: %d iterations, kkt %.2e; energy-norm difference %.2e\n", it->iter,
            it->kkt, e);
    CX_CHECK(it->reason > 0);
    CX_CHECK_LE(e, 1e-8);
    free(sb);
    free(u);
    cx_session_destroy(&s);
}

int main(void)
{
    static const coul_case hertz[] = {{"hertz", 32, 7}, {"hertz", 64, 8}};
    static const coul_case slider = {"slider", 4, 4}, blocks = {"twoblocks", 10, 3};
    for (size_t k = 0; k < sizeof hertz / sizeof hertz[0]; k++)
        check_against_cffp(&hertz[k]);
    cx_session *s = coul_run(&slider);
    cx_session_destroy(&s);
    check_fixed_point(&blocks);
    return check_finish("solve_ssn_coulomb");
}
