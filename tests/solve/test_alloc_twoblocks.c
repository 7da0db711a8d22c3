/* Allocation failures (STYLE.md C5) through the paper-000 path: the
 * two-block mesh, node-to-segment rows, the session, the dual operator in
 * the cache and each paper-000 method's init and solve. The N-th
 * allocation fails for N = 0, 1, ...; every failure must come back as
 * CX_ENOMEM with nothing of ours leaked, and the run without failures must
 * converge. */
#include "solve_fixture.h"
#include "check.h"

static int attempt(const cx_scene *sc, const char *method, cx_friction law, double value, long budget,
                   int *status)
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
        st = cx_session_set_friction(s, law, value, &d);
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

int main(void)
{
    cx_scene sc;
    cx_session *s0 = fixture_session("twoblocks", 2, &sc);
    cx_session_destroy(&s0);
    const struct {
        const char *id;
        cx_friction law;
        double value;
    } runs[] = {{"mprgp", CX_FRICTION_TRESCA, 1.7e7},
                {"ssn-tresca-dual", CX_FRICTION_TRESCA, 1.7e7},
                {"ssn-tresca-glob", CX_FRICTION_NONE, 0},
                {"ssn-coulomb", CX_FRICTION_COULOMB, 0.3}};
    for (size_t r = 0; r < sizeof runs / sizeof runs[0]; r++) {
        int st = 0, failures = 0;
        long n;
        for (n = 0; n < 100000; n++) {
            if (attempt(&sc, runs[r].id, runs[r].law, runs[r].value, n, &st))
                break;
            failures++;
            if (st != CX_OK && st != CX_ENOMEM) {
                fprintf(stderr, "%s: allocation %ld: status %d instead of CX_ENOMEM\n", runs[r].id, n, st);
                CX_CHECK(st == CX_ENOMEM);
            }
        }
        fprintf(stderr, "alloc %s: %d failing allocation points checked\n", runs[r].id, failures);
        CX_CHECK(failures > 20);
        CX_CHECK(n < 100000);
    }
    return check_finish("solve_alloc_twoblocks");
}
