/* SPDX-License-Identifier: GPL-3.0-or-later */
/* ssn-c (paper 002 §7): the paper's iteration counts on hertz (Table 1:
 * 7, 8, 9 on 442, 1692, 6619 nodes; 5-12 in the issue), one symbolic
 * analysis and one factorisation per Newton step, the regularised answer
 * approaching the reference as r grows (error O(1/r)), and the answer of
 * the regularised problem exactly (its residual) at the stop. */
#include "run_fixture.h"

int main(void)
{
    static const int levels[] = {20, 40, 80};
    static const int paper[] = {7, 8, 9};
    for (int k = 0; k < 3; k++) {
        cx_scene sc;
        cx_diag d;
        cx_session *s = fixture_session("hertz", levels[k], &sc);
        CX_CHECK_OK(fixture_run(s, "ssn-c", "r=1e3", 1, 0, 50, &d));
        const cx_iterate *it = cx_session_iterate(s);
        fprintf(stderr, "hertz %d: ssn-c %d iterations (paper %d), kkt %.2e, %ld factorisations\n", levels[k],
                it->iter, paper[k], it->kkt, it->counters.factorizations);
        CX_CHECK(it->reason == CX_STOPPED_OWN);
        CX_CHECK(it->iter >= 5 && it->iter <= 12);
        CX_CHECK(abs(it->iter - paper[k]) <= 1);
        /* the last step only finds the set repeated: no factorisation */
        CX_CHECK(it->counters.factorizations == it->iter - 1);
        CX_CHECK(it->counters.solves == it->iter - 1);
        cx_session_destroy(&s);
    }

    /* against the reference: the penalty error falls like 1/r */
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("hertz", 16, &sc);
    const cx_problem *p = cx_session_problem(s);
    CX_CHECK_OK(fixture_run(s, "ssn-tresca", "", 1, 1e-13, 50, &d));
    double *uref = fixture_copy_u(s);
    double e3, e6, e9;
    CX_CHECK_OK(fixture_run(s, "ssn-c", "r=1e3", 1, 0, 50, &d));
    e3 = fixture_energy_diff(p, cx_session_iterate(s)->u, uref);
    CX_CHECK_OK(fixture_run(s, "ssn-c", "r=1e6", 1, 0, 50, &d));
    e6 = fixture_energy_diff(p, cx_session_iterate(s)->u, uref);
    CX_CHECK_OK(fixture_run(s, "ssn-c", "r=1e9", 1, 0, 50, &d));
    e9 = fixture_energy_diff(p, cx_session_iterate(s)->u, uref);
    fprintf(stderr, "hertz 16: energy error at r = 1e3, 1e6, 1e9 E: %.2e %.2e %.2e; kkt at 1e9 %.2e\n", e3, e6,
            e9, cx_session_iterate(s)->kkt);
    CX_CHECK_NEAR(e3 / e6, 1e3, 0.2, 0);
    CX_CHECK_LE(e9, 1e-6);
    CX_CHECK_LE(cx_session_iterate(s)->kkt, 1e-6);

    /* 3D: halfball, against the reference */
    cx_session *b = fixture_session("halfball", 4, &sc);
    CX_CHECK_OK(fixture_run(b, "ssn-tresca", "", 1, 1e-13, 50, &d));
    double *bref = fixture_copy_u(b);
    CX_CHECK_OK(fixture_run(b, "ssn-c", "r=1e9", 1, 0, 50, &d));
    fprintf(stderr, "halfball 4: ssn-c %d iterations, kkt %.2e\n", cx_session_iterate(b)->iter,
            cx_session_iterate(b)->kkt);
    CX_CHECK_LE(fixture_energy_diff(cx_session_problem(b), cx_session_iterate(b)->u, bref), 1e-6);
    CX_CHECK(cx_session_iterate(b)->iter <= 12);
    free(bref);
    free(uref);
    cx_session_destroy(&b);
    cx_session_destroy(&s);
    return check_finish("solve_ssnc");
}
