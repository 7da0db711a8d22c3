/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The stall rule: a run whose kkt error has not halved for stall_window
 * iterations is stopped as stalled, unless the method reports progress of
 * its own (a regularised first stage resting at its O(eps) kkt floor). */
#include "check.h"
#include "solve_fixture.h"

/* A method that never moves the iterate (the kkt error stays put) and
 * reports progress in its first `quiet` steps. */
static int quiet;

static int idle_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    (void)state, (void)s, (void)d;
    it->progress = it->iter < quiet;   /* it->iter: the steps done before this one */
    return CX_OK;
}

static int idle_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    (void)state, (void)s, (void)params, (void)d;
    return CX_OK;
}

static const cx_method idle = {
    .id = "idle",
    .name = "does nothing",
    .source = "test",
    .summary = "keeps the start",
    .supports = CX_FRICTIONLESS | CX_2D,
    .init = idle_init,
    .step = idle_step,
};

static const cx_iterate *run(cx_session *s, int progress_steps)
{
    cx_diag d;
    cx_options o;
    cx_options_default(&o);
    o.stall_window = 10;
    o.max_iter = 1000;
    quiet = progress_steps;
    CX_CHECK_OK(cx_session_set_method(s, &idle, NULL, &o, &d));
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    return cx_session_iterate(s);
}

int main(void)
{
    cx_scene sc;
    cx_session *s = fixture_session("hertz", 4, &sc);
    /* no progress: the first iterate sets the best kkt, 10 more end it */
    const cx_iterate *it = run(s, 0);
    CX_CHECK(it->reason == CX_DIVERGED_STALL);
    CX_CHECK(it->iter == 11);
    /* progress in the first 25 steps: stalled 10 after the last of them */
    it = run(s, 25);
    CX_CHECK(it->reason == CX_DIVERGED_STALL);
    CX_CHECK(it->iter == 35);
    cx_session_destroy(&s);
    return check_finish("solve_stall");
}
