/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cf-fp (paper 002 CF-FP) and the nested sessions under it: Coulomb
 * F = 0.6 on hertz converges with stick and slip points, one factorisation
 * for all fixed-point steps, all inner work counted in the run, the same
 * answer over two different inner methods (ubr-tf, ssn-tresca), the fixed
 * point satisfied (s = F lN reproduces the solution), and bad inner
 * methods refused. */
#include "run_fixture.h"

static void check_hertz_coulomb(void)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("hertz", 20, &sc);
    const cx_problem *p = cx_session_problem(s);
    CX_CHECK_OK(cx_session_set_coulomb(s, 0.6, &d));

    /* the paper's run: inner ubr-tf at r = 0.29E, its criteria */
    CX_CHECK_OK(fixture_run(s, "cf-fp", "inner=ubr-tf inner_set=r=0.29", 1, 0, 100, &d));
    const cx_iterate *it = cx_session_iterate(s);
    fprintf(stderr, "hertz 20 coulomb: cf-fp %d fixed-point steps, %ld Tresca iterations, kkt %.2e, "
            "%d stick %d slip, %ld factorisations, %ld solves\n", it->iter, it->inner_total, it->kkt,
            it->nstick, it->nslip, it->counters.factorizations, it->counters.solves);
    CX_CHECK(it->reason == CX_STOPPED_OWN);
    CX_CHECK(it->iter >= 5 && it->iter <= 13);   /* the paper: 9 on 442 nodes */
    CX_CHECK(it->nstick > 0 && it->nslip > 0);
    CX_CHECK(it->counters.factorizations == 1);
    /* every inner UBR iteration is one solve, counted in the outer run */
    CX_CHECK(it->counters.solves == it->inner_total);
    CX_CHECK_LE(it->kkt, 1e-3);

    /* to kkt 1e-8 over ubr-tf (tight inner tolerance), then over ssn-tresca:
     * the same solution */
    CX_CHECK_OK(fixture_run(s, "cf-fp", "inner=ubr-tf inner_set=r=1,eps=1e-12 eps_min=1e-12 eps_fp=1e-12", 0, 1e-8,
                            100, &d));
    fprintf(stderr, "  over ubr-tf to kkt: %d steps, kkt %.2e, %ld factorisations\n", it->iter, it->kkt,
            it->counters.factorizations);
    CX_CHECK(it->reason == CX_CONVERGED_KKT);
    CX_CHECK(it->counters.factorizations == 1);
    double *u1 = fixture_copy_u(s);
    CX_CHECK_OK(fixture_run(s, "cf-fp", "inner=ssn-tresca eps_min=1e-13 eps_fp=1e-12", 0, 1e-10, 100, &d));
    fprintf(stderr, "  over ssn-tresca: %d steps, kkt %.2e\n", it->iter, it->kkt);
    CX_CHECK(it->reason == CX_CONVERGED_KKT);
    CX_CHECK_LE(fixture_energy_diff(p, u1, it->u), 1e-6);

    /* the fixed point: Tresca with s = F lN of the solution gives it back */
    double *sb = malloc(sizeof(double) * (size_t)p->m);
    for (int i = 0; i < p->m; i++)
        sb[i] = 0.6 * it->lN[i];
    double *u2 = fixture_copy_u(s);
    cx_session_clear_method(s);
    CX_CHECK_OK(cx_session_set_slip_bounds(s, sb, &d));
    CX_CHECK_OK(fixture_run(s, "ssn-tresca", "", 1, 1e-13, 50, &d));
    CX_CHECK_LE(fixture_energy_diff(p, it->u, u2), 1e-8);
    free(sb);
    free(u1);
    free(u2);
    cx_session_destroy(&s);
}

/* 3D (the disc): halfball level 4, F = 0.6, to kkt 1e-8 with one
 * factorisation; ubr-tf with s = F lN of the answer gives it back. */
static void check_halfball_coulomb(void)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("halfball", 4, &sc);
    const cx_problem *p = cx_session_problem(s);
    CX_CHECK_OK(cx_session_set_coulomb(s, 0.6, &d));
    CX_CHECK_OK(fixture_run(s, "cf-fp", "inner=ubr-tf inner_set=r=4,eps=1e-12 eps_min=1e-12 eps_fp=1e-12", 0, 1e-8, 100, &d));
    const cx_iterate *it = cx_session_iterate(s);
    fprintf(stderr, "halfball 4 coulomb: cf-fp %d steps, %ld Tresca iterations, kkt %.2e, %d stick %d slip\n",
            it->iter, it->inner_total, it->kkt, it->nstick, it->nslip);
    CX_CHECK(it->reason == CX_CONVERGED_KKT);
    CX_CHECK(it->counters.factorizations == 1);
    CX_CHECK(it->nstick + it->nslip > 0);
    double *sb = malloc(sizeof(double) * (size_t)p->m);
    for (int i = 0; i < p->m; i++)
        sb[i] = 0.6 * it->lN[i];
    double *u = fixture_copy_u(s);
    cx_session_clear_method(s);
    CX_CHECK_OK(cx_session_set_slip_bounds(s, sb, &d));
    CX_CHECK_OK(fixture_run(s, "ubr-tf", "r=4", 0, 1e-11, 5000, &d));
    CX_CHECK_LE(fixture_energy_diff(p, it->u, u), 1e-6);
    free(sb);
    free(u);
    cx_session_destroy(&s);
}

static void check_refusals(void)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("hertz", 8, &sc);
    CX_CHECK_OK(cx_session_set_coulomb(s, 0.6, &d));
    const char *bad[] = {"inner=ubr-c", "inner=nosuch", "inner=cf-fp", "inner_set=rr=1"};
    for (int k = 0; k < 4; k++) {
        int st = fixture_run(s, "cf-fp", bad[k], 1, 0, 10, &d);
        fprintf(stderr, "%s: %s\n", bad[k], d.msg);
        CX_CHECK(st != CX_OK && d.msg[0]);
    }
    /* frictionless: cf-fp refuses */
    CX_CHECK_OK(cx_session_set_frictionless(s, &d));
    CX_CHECK(fixture_run(s, "cf-fp", "", 1, 0, 10, &d) == CX_EUNSUPPORTED);
    cx_session_destroy(&s);
}

/* The nested session on its own: a child shares the cache and counts its
 * work in the parent's run. */
static void check_nested(void)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("hertz", 16, &sc);
    const cx_problem *p = cx_session_problem(s);
    CX_CHECK_OK(fixture_run(s, "ubr-c", "r=1", 1, 0, 500, &d));  /* caches K + r N'WN */
    int cached = cx_session_cache_size(s);
    cx_session *child = NULL;
    CX_CHECK_OK(cx_session_nested_create(&child, s, &d));
    CX_CHECK(cx_session_friction(child)->law == CX_FRICTION_TRESCA);
    CX_CHECK(cx_session_problem(child)->K.x == p->K.x);   /* a view, not a copy */
    double *sb = malloc(sizeof(double) * (size_t)p->m);
    for (int i = 0; i < p->m; i++)
        sb[i] = 20 * p->contact.weight[i];
    CX_CHECK_OK(cx_session_set_slip_bounds(child, sb, &d));
    long solves_before = cx_session_counters(s)->solves;
    CX_CHECK_OK(fixture_run(child, "ubr-tf", "r=1", 0, 1e-9, 5000, &d));
    const cx_iterate *in = cx_session_iterate(child);
    CX_CHECK(in->reason == CX_CONVERGED_KKT);
    CX_CHECK(in->counters.factorizations == 1);           /* K + r(N'WN + T'WT): new key */
    CX_CHECK(cx_session_cache_size(s) == cached + 1);      /* built in the parent's cache */
    CX_CHECK(cx_session_counters(s)->solves - solves_before == in->counters.solves);
    /* the same Tresca problem on the parent: the same answer */
    double *uc = fixture_copy_u(child);
    /* ubr-c refuses Tresca: select no method first */
    CX_CHECK(cx_session_set_tresca(s, 20, &d) == CX_EUNSUPPORTED);
    cx_session_clear_method(s);
    CX_CHECK_OK(cx_session_set_tresca(s, 20, &d));
    CX_CHECK_OK(fixture_run(s, "ssn-tresca", "", 1, 1e-13, 50, &d));
    CX_CHECK_LE(fixture_energy_diff(p, uc, cx_session_iterate(s)->u), 1e-6);
    cx_session_destroy(&child);
    free(sb);
    free(uc);
    cx_session_destroy(&s);
}

int main(void)
{
    check_hertz_coulomb();
    check_halfball_coulomb();
    check_refusals();
    check_nested();
    return check_finish("solve_cffp");
}
