/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Shared by the allocation-failure tests (doc/style.md C5): make the N-th
 * allocation fail for N = 0, 1, 2, ... through scene building, session
 * creation, the friction law, method selection and a solve; every failure
 * must come back as CX_ENOMEM (or an outcome) with nothing of ours leaked,
 * and the run without failures must converge. */
#ifndef CX_TEST_ALLOC_FIXTURE_H
#define CX_TEST_ALLOC_FIXTURE_H

#include "solve_fixture.h"
#include "check.h"

/* One run with the budget; 1 if it converged, the status in *status. */
static int alloc_attempt(const cx_scene *sc, const char *method, cx_friction law, double value, long budget,
                         int *status)
{
    cx_diag d;
    cx_problem *p = NULL;
    cx_session *s = NULL;
    long live = cx_alloc_live();
    cx_alloc_fail_after(budget);
    cx_friction_state fr;
    int st = cx_scene_build(sc, 2, &p, &fr, &d);
    if (!st)
        st = cx_session_create(&s, &p, &d);
    if (!st) {
        fr.law = law;   /* value is the law's: the slip bound or F */
        if (law == CX_FRICTION_COULOMB)
            fr.F = value;
        else if (law == CX_FRICTION_TRESCA)
            fr.slip_bound = value;
        st = cx_session_set_friction(s, &fr, &d);
    }
    if (!st)
        st = cx_session_set_method(s, cx_method_find(method), NULL, NULL, &d);
    if (!st)
        st = cx_solver_solve(s, NULL, NULL, &d);
    int done = !st && cx_session_iterate(s)->reason > 0;
    cx_alloc_fail_after(-1);
    cx_problem_destroy(&p);
    cx_session_destroy(&s);
    CX_CHECK(cx_alloc_live() == live);
    *status = st;
    return done;
}

/* Every failing allocation point of a run of method on sc at level 2:
 * more than 20 of them, each CX_ENOMEM, then a run that converges. */
static void alloc_check_all(const cx_scene *sc, const char *method, cx_friction law, double value)
{
    int st = 0, failures = 0;
    long n;
    for (n = 0; n < 100000; n++) {
        if (alloc_attempt(sc, method, law, value, n, &st))
            break;
        failures++;
        if (st != CX_OK && st != CX_ENOMEM) {
            fprintf(stderr, "%s: allocation %ld: status %d instead of CX_ENOMEM\n", method, n, st);
            CX_CHECK(st == CX_ENOMEM);
        }
    }
    fprintf(stderr, "alloc %s: %d failing allocation points checked\n", method, failures);
    CX_CHECK(failures > 20);
    CX_CHECK(n < 100000);
}

#endif
