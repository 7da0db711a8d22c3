/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Allocation failures (doc/style.md C5) through the paper-000 path: the
 * two-block mesh, node-to-segment rows, the session, the dual operator in
 * the cache and each paper-000 method's init and solve. The N-th
 * allocation fails for N = 0, 1, ...; every failure must come back as
 * CX_ENOMEM with nothing of ours leaked, and the run without failures must
 * converge (alloc_fixture.h). */
#include "alloc_fixture.h"

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
    for (size_t r = 0; r < sizeof runs / sizeof runs[0]; r++)
        alloc_check_all(&sc, runs[r].id, runs[r].law, runs[r].value);
    return check_finish("solve_alloc_twoblocks");
}
