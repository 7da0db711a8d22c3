/* Allocation failures (STYLE.md C5): make the N-th allocation fail for
 * N = 0, 1, 2, ... through scene building, session creation, method
 * selection and a solve; every failure must come back as CX_ENOMEM (or an
 * outcome) with nothing of ours leaked, and the run without failures must
 * succeed. */
#include "solve_fixture.h"
#include "check.h"

static int attempt(const cx_scene *sc, long budget, int *status)
{
    cx_diag d;
    cx_problem *p = NULL;
    cx_session *s = NULL;
    long live = cx_alloc_live();
    cx_alloc_fail_after(budget);
    int st = cx_scene_build(sc, 2, &p, &d);
    if (!st)
        st = cx_session_create(&s, &p, &d);
    if (!st)
        st = cx_session_set_method(s, cx_method_find("ssn-tresca"), NULL, NULL, &d);
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

int main(void)
{
    cx_scene sc;
    cx_session *s0 = fixture_session("hertz", 2, &sc);
    cx_session_destroy(&s0);
    int st = 0, failures = 0;
    long n;
    for (n = 0; n < 100000; n++) {
        if (attempt(&sc, n, &st))
            break;
        failures++;
        if (st != CX_OK && st != CX_ENOMEM) {
            fprintf(stderr, "allocation %ld: status %d instead of CX_ENOMEM\n", n, st);
            CX_CHECK(st == CX_ENOMEM);
        }
    }
    fprintf(stderr, "alloc: %d failing allocation points checked\n", failures);
    CX_CHECK(failures > 20);
    CX_CHECK(n < 100000);
    return check_finish("solve_alloc");
}
