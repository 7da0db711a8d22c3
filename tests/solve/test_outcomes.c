/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Honest outcomes (issue 20): converged means kkt <= tol; a method's own
 * criterion above it is "stopped", not converged; a declared breakdown ends
 * the run at once with the method's message; NaN/Inf stop the run with
 * where they are; a cancel or the time limit acts inside long steps within
 * a counted number of inner iterations (counted, not timed); every shipped
 * scene under every law it allows converges with --method auto's choice. */
#include "check.h"
#include "run_fixture.h"
#include "solve_fixture.h"

#include <string.h>

/* ---- a probe method: does nothing, then declares its end --------------- */

static int probe_end_at;         /* the step (1-based) that declares the end */
static int probe_reason;         /* CX_DIVERGED_BREAKDOWN or CX_DIVERGED */
static int probe_status;         /* what that step returns */
static int probe_nan_at;         /* the step that writes a NaN (0: never) */
static double probe_nan_value;   /* NAN or INFINITY */

static int probe_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    (void)state, (void)s, (void)params, (void)d;
    return CX_OK;
}

static int probe_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    (void)state, (void)s;
    int step = it->iter + 1;
    if (step == probe_nan_at)
        it->lN[0] = probe_nan_value;
    if (step == probe_end_at) {
        it->reason = probe_reason;
        return cx_diag_set(d, probe_status, "probe: no solution (row %d)", 7);
    }
    return CX_OK;
}

static const cx_method probe_method = {
    .id = "probe",
    .name = "test probe",
    .source = "test",
    .summary = "declares a breakdown at a chosen step",
    .supports = CX_FRICTIONLESS | CX_TRESCA | CX_COULOMB | CX_2D | CX_3D | CX_MULTIBODY,
    .state_size = 0,
    .params = NULL,
    .init = probe_init,
    .step = probe_step,
    .destroy = NULL,
};

static int refusing_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    (void)state, (void)s, (void)params;
    return cx_diag_set(d, CX_EUNSUPPORTED, "refuser: needs a plate");
}

static const cx_method refusing_method = {
    .id = "refuser",
    .name = "test refuser",
    .source = "test",
    .summary = "refuses every problem at init",
    .supports = CX_FRICTIONLESS | CX_TRESCA | CX_COULOMB | CX_2D | CX_3D | CX_MULTIBODY,
    .init = refusing_init,
    .step = probe_step,
};

static void test_declared_breakdown(void)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("hertz", 8, &sc);
    static const struct { int reason, status; } cases[] = {
        {CX_DIVERGED_BREAKDOWN, CX_OK}, {CX_DIVERGED_BREAKDOWN, CX_ENUMERIC}, {CX_DIVERGED, CX_OK}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        probe_end_at = 3;
        probe_reason = cases[k].reason;
        probe_status = cases[k].status;
        probe_nan_at = 0;
        cx_options o;
        cx_options_default(&o);   /* stall window 50: the old stall came 50 steps later */
        CX_CHECK_OK(cx_session_set_method(s, &probe_method, NULL, &o, &d));
        CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
        const cx_iterate *it = cx_session_iterate(s);
        char buf[512];
        cx_session_outcome(s, buf, sizeof buf);
        fprintf(stderr, "probe %zu: %s (%d iterations): %s\n", k, cx_reason_id(it->reason), it->iter, buf);
        CX_CHECK(it->reason == cases[k].reason);
        CX_CHECK(it->iter == 3);
        CX_CHECK(strcmp(cx_session_reason_msg(s), "probe: no solution (row 7)") == 0);
        CX_CHECK(strstr(buf, "probe: no solution (row 7)") != NULL);
        CX_CHECK(strstr(buf, cases[k].reason == CX_DIVERGED ? "diverged at iteration 3" : "breakdown at iteration 3") != NULL);
        /* a further step does nothing: the run has ended */
        CX_CHECK_OK(cx_solver_step(s, &d));
        CX_CHECK(cx_session_iterate(s)->iter == 3);
    }

    /* NaN and Inf: the run stops with where they are, never as converged */
    for (int k = 0; k < 2; k++) {
        probe_end_at = 0;
        probe_nan_at = 2;
        probe_nan_value = k == 0 ? NAN : INFINITY;
        CX_CHECK_OK(cx_session_set_method(s, &probe_method, NULL, NULL, &d));
        CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
        const cx_iterate *it = cx_session_iterate(s);
        char buf[512];
        cx_session_outcome(s, buf, sizeof buf);
        fprintf(stderr, "probe nonfinite %d: %s\n", k, buf);
        CX_CHECK(it->reason == CX_DIVERGED_NAN && it->iter == 2);
        CX_CHECK(strstr(buf, k == 0 ? "NaN in lN (entry 0) at iteration 2" : "overflow: Inf in lN (entry 0)") != NULL);
        CX_CHECK(strstr(buf, "nan") == NULL && strstr(buf, "inf ") == NULL);
    }
    cx_session_destroy(&s);
}

/* ---- the far obstacle: its own criterion stops it, far from a solution -- */

static void far_obstacle(cx_scene *sc)
{
    sc->obstacle.point[1] = -1e14;
}

static void test_far_obstacle(void)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session_edited("hertz", 8, &sc, far_obstacle);
    static const char *const ids[] = {"ssn-tresca", "graves", "pdas", "lssnn"};
    for (size_t k = 0; k < sizeof ids / sizeof ids[0]; k++) {
        cx_options o;
        cx_options_default(&o);
        CX_CHECK_OK(cx_session_set_method(s, cx_method_find(ids[k]), NULL, &o, &d));
        CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
        const cx_iterate *it = cx_session_iterate(s);
        char buf[512];
        cx_session_outcome(s, buf, sizeof buf);
        fprintf(stderr, "far obstacle, %s: %s\n", ids[k], buf);
        CX_CHECK(it->kkt > o.tol);
        CX_CHECK(it->reason < 0);
        CX_CHECK(it->reason == CX_STOPPED_OWN);
        CX_CHECK(strstr(buf, "stopped by its own criterion at kkt error") != NULL);
        CX_CHECK(strstr(buf, "not converged") != NULL);
    }
    /* --tol is enforced both ways: a tolerance above the kkt error of the
     * stop is converged, the same run under a tighter one is not */
    CX_CHECK_OK(fixture_run(s, "ssn-tresca", "", 1, 1e-10, 500, &d));
    double kkt = cx_session_iterate(s)->kkt;
    CX_CHECK_OK(fixture_run(s, "ssn-tresca", "", 1, 2 * kkt, 500, &d));
    CX_CHECK(cx_session_iterate(s)->reason == CX_CONVERGED_KKT);
    /* new options re-judge a finished run: under a tighter tolerance it
     * is 'stopped' if its own criterion held, else it goes on; with no
     * own stop it goes on; a looser tolerance converges it */
    cx_options o = *cx_session_options(s);
    o.tol = kkt / 2;
    cx_session_set_options(s, &o);
    CX_CHECK(cx_session_iterate(s)->reason ==
             (cx_session_iterate(s)->own_done ? CX_STOPPED_OWN : CX_ITERATING));
    o.own_stop = 0;
    cx_session_set_options(s, &o);
    CX_CHECK(cx_session_iterate(s)->reason == CX_ITERATING);
    o.tol = 2 * kkt;
    o.own_stop = 1;
    cx_session_set_options(s, &o);
    CX_CHECK(cx_session_iterate(s)->reason == CX_ITERATING);
    CX_CHECK_OK(cx_solver_step(s, &d));
    CX_CHECK(cx_session_iterate(s)->reason == CX_CONVERGED_KKT);
    cx_session_destroy(&s);
}

/* ---- the words: one table, ids and sentences --------------------------- */

static void test_words(void)
{
    static const struct { int reason; const char *id, *word; } t[] = {
        {CX_CONVERGED_KKT, "converged", "converged"},
        {CX_STOPPED_OWN, "stopped_own", "stopped by its own criterion"},
        {CX_DIVERGED_STALL, "stalled", "stalled"},
        {CX_DIVERGED_MAXIT, "max_iter", "did not converge"},
        {CX_DIVERGED, "diverged", "diverged"},
        {CX_DIVERGED_BREAKDOWN, "breakdown", "breakdown"},
        {CX_REFUSED, "refused", "refused"},
        {CX_CANCELLED, "cancelled", "cancelled"},
        {CX_DIVERGED_TIME, "time_limit", "time limit"},
        {CX_DIVERGED_NAN, "nonfinite", "overflow or NaN"},
    };
    for (size_t k = 0; k < sizeof t / sizeof t[0]; k++) {
        CX_CHECK(strcmp(cx_reason_id(t[k].reason), t[k].id) == 0);
        CX_CHECK(strcmp(cx_reason_str(t[k].reason), t[k].word) == 0);
        char buf[256];
        cx_reason_format(t[k].reason, 12, t[k].reason > 0 ? 3.5e-12 : 3.5e-4, 1e-10, "the message", buf,
                         sizeof buf);
        fprintf(stderr, "%-12s %s\n", t[k].id, buf);
        CX_CHECK(strncmp(buf, t[k].word, strlen(t[k].word)) == 0);
        CX_CHECK((t[k].reason > 0) == (strstr(buf, "<= tol") != NULL));
        /* never a NaN or Inf in a sentence, whatever the kkt error */
        cx_reason_format(t[k].reason, 12, NAN, 1e-10, NULL, buf, sizeof buf);
        CX_CHECK(strstr(buf, "nan") == NULL && strstr(buf, "inf") == NULL);
    }
    char buf[128];
    cx_reason_format(CX_DIVERGED_MAXIT, 500, 2e-3, 1e-10, NULL, buf, sizeof buf);
    CX_CHECK(strcmp(buf, "did not converge in 500 iterations: kkt error 0.002 > tol 1e-10") == 0);
    cx_reason_format(CX_CONVERGED_KKT, 5, 3e-12, 1e-10, NULL, buf, sizeof buf);
    CX_CHECK(strcmp(buf, "converged in 5 iterations: kkt error 3e-12 <= tol 1e-10") == 0);
    /* a tiny buffer is cut, terminated */
    char small[8];
    cx_reason_format(CX_STOPPED_OWN, 5, 1, 1e-10, NULL, small, sizeof small);
    CX_CHECK(strlen(small) == 7);

    /* refused: init's reason is the outcome, with the method's words */
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("hertz", 4, &sc);
    CX_CHECK(cx_session_set_method(s, &refusing_method, NULL, NULL, &d) == CX_EUNSUPPORTED);
    CX_CHECK(cx_session_iterate(s)->reason == CX_REFUSED);
    cx_session_outcome(s, buf, sizeof buf);
    CX_CHECK(strcmp(buf, "refused: refuser: needs a plate") == 0);
    cx_session_destroy(&s);
}

/* ---- cancel and time limit, counted ------------------------------------ */

/* A clock that reads 0 at its first call (the step's start, when the
 * deadline is set) and far past any limit after: the limit passes as soon
 * as the step has begun. */
static double jump_clock(void *ctx)
{
    int *calls = ctx;
    return (*calls)++ == 0 ? 0 : 1e9;
}

static void test_limits_counted(void)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session("stackbond", 5, &sc);
    char sets[64];
    snprintf(sets, sizeof sets, "sweeps=%d", 50 * CX_CHECK_INTERVAL);
    cx_options o;
    cx_options_default(&o);

    /* no limit: one step is all its sweeps (the count the checks cut) */
    o.max_iter = 1;
    CX_CHECK_OK(fixture_run_opts(s, "psor", sets, &o, &d));
    CX_CHECK(cx_session_iterate(s)->inner == 50 * CX_CHECK_INTERVAL);

    /* the time limit passes once the step has begun (an injected clock):
     * the step stops at its first check */
    int calls = 0;
    cx_session_set_clock(s, jump_clock, &calls);
    o.max_iter = 500;
    o.time_limit = 1000;
    const cx_method *psor = cx_method_find("psor");
    cx_param_values pv;
    cx_param_default(&pv, psor->params);
    CX_CHECK_OK(cx_param_set_pair(&pv, sets, "psor", &d));
    CX_CHECK_OK(cx_session_set_method(s, psor, &pv, &o, &d));
    const cx_iterate *it = cx_session_iterate(s);
    CX_CHECK_OK(cx_solver_step(s, &d));
    fprintf(stderr, "psor after the limit: %ld sweeps, %s\n", it->inner, cx_reason_id(it->reason));
    CX_CHECK(it->inner >= 1 && it->inner <= CX_CHECK_INTERVAL);
    CX_CHECK(it->reason == CX_DIVERGED_TIME);
    cx_session_set_clock(s, NULL, NULL);

    /* the cancel flag (as a signal handler or another thread sets it) */
    o.time_limit = 0;
    CX_CHECK_OK(cx_session_set_method(s, psor, &pv, &o, &d));
    cx_session_cancel(s);
    CX_CHECK_OK(cx_solver_step(s, &d));
    fprintf(stderr, "psor after cancel: %ld sweeps, %s\n", it->inner, cx_reason_id(it->reason));
    CX_CHECK(it->inner >= 1 && it->inner <= CX_CHECK_INTERVAL);
    CX_CHECK(it->reason == CX_CANCELLED);
    /* a new run clears the flag */
    CX_CHECK_OK(cx_session_set_method(s, psor, &pv, &o, &d));
    CX_CHECK_OK(cx_solver_step(s, &d));
    CX_CHECK(it->inner == 50 * CX_CHECK_INTERVAL);

    /* graves: its pivots in chunks of the interval (a Case 2 step is two) */
    cx_param_values gv;
    const cx_method *graves = cx_method_find("graves");
    cx_param_default(&gv, graves->params);
    CX_CHECK_OK(cx_param_set_pair(&gv, "pivots=100000", "graves", &d));
    cx_session_destroy(&s);
    s = fixture_session("halfball", 0, &sc);
    CX_CHECK_OK(cx_session_set_method(s, graves, &gv, &o, &d));
    cx_session_cancel(s);
    CX_CHECK_OK(cx_solver_step(s, &d));
    it = cx_session_iterate(s);
    fprintf(stderr, "graves after cancel: %ld pivots, %s\n", it->inner, cx_reason_id(it->reason));
    CX_CHECK(it->inner <= 2 * CX_CHECK_INTERVAL);
    CX_CHECK(it->reason == CX_CANCELLED);

    /* a nested run (cf-fp over ssn-tresca) ends as cancelled too */
    cx_session_destroy(&s);
    s = fixture_session("hertz", 8, &sc);
    CX_CHECK_OK(cx_session_set_coulomb(s, 0.3, &d));
    CX_CHECK_OK(cx_session_set_method(s, cx_method_find("cf-fp"), NULL, &o, &d));
    cx_session_cancel(s);
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    it = cx_session_iterate(s);
    CX_CHECK(it->reason == CX_CANCELLED && it->iter == 1);
    cx_session_destroy(&s);
}

/* CG under a stop test: stops at the interval (linalg's hook). */
static void apply_lap(void *ctx, const double *x, double *y)
{
    int n = *(const int *)ctx;
    for (int i = 0; i < n; i++)
        y[i] = 2 * x[i] - (i > 0 ? x[i - 1] : 0) - (i + 1 < n ? x[i + 1] : 0);
}

static int stop_after(void *ctx)
{
    return --*(int *)ctx < 0;
}

static void test_pcg_stop(void)
{
    enum { N = 400 };
    static double b[N], x[N], w[4 * N];
    for (int i = 0; i < N; i++)
        b[i] = 1;
    int n = N, iters = 0, allow = 2;   /* two checks pass, the third stops */
    cx_diag d;
    int st = cx_pcg_stop(N, apply_lap, &n, NULL, b, x, 1e-14, 10 * N, stop_after, &allow, &iters, w, &d);
    CX_CHECK(st == CX_ENUMERIC && iters == 3 * CX_PCG_CHECK_INTERVAL);
    CX_CHECK(strstr(d.msg, "interrupted") != NULL);
    memset(x, 0, sizeof x);
    CX_CHECK_OK(cx_pcg_stop(N, apply_lap, &n, NULL, b, x, 1e-10, 10 * N, NULL, NULL, &iters, w, &d));
}

/* ---- every shipped scene, every law it allows: auto converges ---------- */

static void test_auto_converges(void)
{
    char (*ids)[CX_SCENE_NAMELEN] = NULL;
    int count = 0;
    cx_diag d;
    CX_CHECK_OK(cx_scene_list(&ids, &count, &d));
    CX_CHECK(count >= 9);
    for (int k = 0; k < count; k++)
        for (int law = 0; law < 3; law++) {
            cx_scene sc;
            cx_session *s = fixture_session(ids[k], 0, &sc);
            if (!(sc.laws & (1u << law))) {
                cx_session_destroy(&s);
                continue;
            }
            CX_CHECK((sc.laws >> sc.friction) & 1u);
            cx_friction_state fr = {(cx_friction)law, sc.slip_bound, sc.F, NULL, NULL};
            CX_CHECK_OK(cx_session_set_friction(s, &fr, &d));
            const char *sets;
            const char *id = cx_scene_auto_method(&sc, 0, cx_session_problem(s), (cx_friction)law, &sets);
            cx_options o;
            cx_options_default(&o);
            int st = fixture_run_opts(s, id, sets, &o, &d);
            const cx_iterate *it = cx_session_iterate(s);
            char buf[512];
            fprintf(stderr, "%-12s %-8s %-12s %s\n", ids[k], cx_friction_name((cx_friction)law), id,
                    st ? d.msg : cx_session_outcome(s, buf, sizeof buf));
            CX_CHECK_OK(st);
            CX_CHECK(it->reason == CX_CONVERGED_KKT && it->kkt <= o.tol);
            cx_session_destroy(&s);
        }
    cx_free(ids);

    /* the rule for other scenes and levels: masonry's floating bricks take
     * pdas, Coulomb ssn-coulomb in 2D and cf-fp in 3D, the rest ssn-tresca */
    cx_scene sc;
    const char *sets;
    cx_session *s = fixture_session("runningbond", 8, &sc);
    CX_CHECK(strcmp(cx_scene_auto_method(&sc, 8, cx_session_problem(s), CX_FRICTION_NONE, &sets), "pdas") == 0);
    CX_CHECK(strcmp(sets, "start=closed") == 0);   /* the walls: every joint closed first */
    {
        cx_options o;
        cx_options_default(&o);
        CX_CHECK_OK(fixture_run_opts(s, "pdas", sets, &o, &d));
        const cx_iterate *it = cx_session_iterate(s);
        CX_CHECK(it->reason == CX_CONVERGED_KKT && it->kkt <= o.tol);
    }
    cx_session_destroy(&s);
    s = fixture_session("hertz", 8, &sc);
    CX_CHECK(strcmp(cx_scene_auto_method(&sc, 8, cx_session_problem(s), CX_FRICTION_NONE, &sets), "ssn-tresca") == 0);
    CX_CHECK(strcmp(cx_scene_auto_method(&sc, 8, cx_session_problem(s), CX_FRICTION_COULOMB, &sets), "ssn-coulomb") == 0);
    cx_session_destroy(&s);
    s = fixture_session("block3d", 2, &sc);
    CX_CHECK(strcmp(cx_scene_auto_method(&sc, 2, cx_session_problem(s), CX_FRICTION_COULOMB, &sets), "cf-fp") == 0);
    CX_CHECK(strstr(sets, "eps_fp") != NULL);
    cx_session_destroy(&s);
}

int main(void)
{
    test_words();
    test_declared_breakdown();
    test_far_obstacle();
    test_limits_counted();
    test_pcg_stop();
    test_auto_converges();
    return check_finish("solve_outcomes");
}
