/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Allocation failures (doc/style.md C5) through scene building, session
 * creation, method selection and a solve on hertz (alloc_fixture.h). */
#include "alloc_fixture.h"

int main(void)
{
    cx_scene sc;
    cx_session *s0 = fixture_session("hertz", 2, &sc);
    cx_session_destroy(&s0);
    alloc_check_all(&sc, "ssn-tresca", CX_FRICTION_NONE, 0);
    return check_finish("solve_alloc");
}
