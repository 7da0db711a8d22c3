/* SPDX-License-Identifier: GPL-3.0-or-later */
/* ssn-tresca on the foundation's scenes: the Hertz contact zone and load
 * balance, stick and slip on 'slider', the 3D block, refusals, and that
 * switching method or friction keeps the one factorisation. */
#include "solve_fixture.h"
#include "check.h"

#include <math.h>
#include <string.h>

static const cx_method *ssn(void) { return cx_method_find("ssn-tresca"); }

static void test_hertz(int level)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("hertz", level, &sc);
    CX_CHECK_OK(cx_session_set_method(s, ssn(), NULL, NULL, &d));
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    const cx_iterate *it = cx_session_iterate(s);
    const cx_problem *p = cx_session_problem(s);
    CX_CHECK(it->reason > 0);
    CX_CHECK_LE(it->kkt, 1e-12);

    /* the contact carries the load: sum lN = 800 (the quarter's share) */
    double sum = 0;
    for (int i = 0; i < p->m; i++)
        sum += it->lN[i];
    CX_CHECK_NEAR(sum, 800.0, 1e-9, 0);
    CX_CHECK_NEAR(p->f_applied[1], -800.0, 1e-12, 0);

    /* the contact zone is x < b to within two node spacings */
    double b = cx_scene_hertz_halfwidth(&sc);
    for (int i = 0; i < p->m; i++) {
        double x = p->contact.x[2 * i];
        double h = i + 1 < p->m ? p->contact.x[2 * (i + 1)] - x : x - p->contact.x[2 * (i - 1)];
        if (x < b - 2 * h)
            CX_CHECK(it->status[i] == CX_PT_CONTACT);
        if (x > b + 2 * h)
            CX_CHECK(it->status[i] == CX_PT_FREE);
    }
    double pa, pr;
    CX_CHECK_OK(cx_scene_pressure_error(&sc, p, it->lN, &pa, &pr));
    fprintf(stderr, "hertz level %d: %d iterations, kkt %.2e, pressure error %.3g (%.2f %%)\n", level,
            it->iter, it->kkt, pa, 100 * pr);
    CX_CHECK_LE(pr, level >= 32 ? 0.05 : 0.15);
    cx_session_destroy(&s);
}

static void test_slider(void)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("slider", 0, &sc);
    CX_CHECK(cx_session_friction(s)->law == CX_FRICTION_TRESCA);
    CX_CHECK_OK(cx_session_set_method(s, ssn(), NULL, NULL, &d));
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    const cx_iterate *it = cx_session_iterate(s);
    CX_CHECK(it->reason > 0);
    CX_CHECK_LE(it->kkt, 1e-12);
    fprintf(stderr, "slider: %d stick, %d slip, %d free\n", it->nstick, it->nslip, it->nfree);
    CX_CHECK(it->nstick > 0);
    CX_CHECK(it->nslip > 0);

    /* slipping points carry exactly the slip bound */
    const cx_problem *p = cx_session_problem(s);
    for (int i = 0; i < p->m; i++)
        if (it->status[i] == CX_PT_SLIP_POS || it->status[i] == CX_PT_SLIP_NEG)
            CX_CHECK_NEAR(fabs(it->lT[i]), cx_session_friction(s)->s[i], 1e-10, 0);

    /* Coulomb is refused with the reason, the session keeps its law */
    CX_CHECK(cx_session_set_coulomb(s, 0.3, &d) == CX_EUNSUPPORTED);
    CX_CHECK(strstr(d.msg, "does not support Coulomb friction") != NULL);
    CX_CHECK(cx_session_friction(s)->law == CX_FRICTION_TRESCA);

    /* friction off and on again, method re-selected: still one factorisation */
    CX_CHECK_OK(cx_session_set_frictionless(s, &d));
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    CX_CHECK(cx_session_iterate(s)->nstick == 0);
    CX_CHECK_OK(cx_session_set_tresca(s, 1e9, &d));
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    it = cx_session_iterate(s);
    CX_CHECK(it->nslip == 0 && it->nstick > 0);   /* a huge bound sticks everywhere in contact */
    CX_CHECK_OK(cx_session_set_method(s, ssn(), NULL, NULL, &d));
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    CX_CHECK(cx_session_cache_counters(s)->factorizations == 1);
    cx_session_destroy(&s);
}

static void test_block3d(void)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("block3d", 2, &sc);
    CX_CHECK_OK(cx_session_set_method(s, ssn(), NULL, NULL, &d));
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    const cx_iterate *it = cx_session_iterate(s);
    const cx_problem *p = cx_session_problem(s);
    CX_CHECK(it->reason > 0);
    CX_CHECK_LE(it->kkt, 1e-12);
    double sum = 0;
    for (int i = 0; i < p->m; i++)
        sum += it->lN[i];
    CX_CHECK_NEAR(sum, -p->f_applied[2], 1e-9, 0);
    /* 3D Tresca (disc slip bound): converges, and the tangential
     * multipliers stay in the disc */
    CX_CHECK_OK(cx_session_set_tresca(s, 1, &d));
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    CX_CHECK(it->reason > 0);
    CX_CHECK_LE(it->kkt, 1e-10);
    for (int i = 0; i < p->m; i++)
        CX_CHECK_LE(hypot(it->lT[2 * i], it->lT[2 * i + 1]), cx_session_friction(s)->s[i] * (1 + 1e-9));
    cx_session_destroy(&s);
}

static void test_limits(void)
{
    /* an iteration limit is an outcome, not an error */
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("hertz", 16, &sc);
    cx_options o;
    cx_options_default(&o);
    o.max_iter = 1;
    CX_CHECK_OK(cx_session_set_method(s, ssn(), NULL, &o, &d));
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    CX_CHECK(cx_session_iterate(s)->reason == CX_DIVERGED_MAXIT);
    CX_CHECK(cx_session_iterate(s)->iter == 1);
    /* more iterations allowed: the run goes on from where it stopped */
    o.max_iter = 50;
    cx_session_set_options(s, &o);
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    CX_CHECK(cx_session_iterate(s)->reason > 0);
    /* an unknown parameter value is refused with the range */
    cx_param_values pv;
    cx_param_default(&pv, ssn()->params);
    CX_CHECK(cx_param_set(&pv, "rho", "-1", "method 'ssn-tresca'", &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "rho") != NULL);
    cx_session_destroy(&s);
}

int main(void)
{
    test_hertz(16);
    test_hertz(32);
    test_slider();
    test_block3d();
    test_limits();
    return check_finish("solve_ssn");
}
