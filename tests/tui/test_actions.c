/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The explorer's state and actions without a terminal: keys give the
 * reactions of doc/style.md C12 (only scene and level changes reassemble),
 * stepping fills the history, switching method / parameter / friction /
 * tolerance keeps the one factorisation, refused switches keep the
 * session, export writes every step, and the braille canvas and the strip
 * buckets give the expected cells. */
#include "check.h"
#include "tui/tui_impl.h"
#include "cx_config.h"

#if CX_HAVE_RENDER
#include "render/pngread.h"
#include "render/render.h"
#endif

#include <sys/stat.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static int count_status(const tui_state *st, int a, int b)
{
    int n = 0;
    for (int i = 0; i < st->m; i++)
        n += st->status[i] == a || st->status[i] == b;
    return n;
}

static int type(tui_state *st, const char *text)
{
    int r = 0;
    for (; *text; text++)
        r |= tui_key(st, *text);
    return r;
}

static int run_to_end(tui_state *st, int max)
{
    for (int k = 0; k < max && tui_state_run(st)->reason == CX_ITERATING; k++)
        tui_key(st, 's');
    return tui_state_run(st)->nsteps;
}

static void test_hertz(void)
{
    static tui_state st;
    cx_diag d;
    cx_diag_clear(&d);
    CX_CHECK_OK(tui_state_init(&st, "hertz", 8, NULL, -1, 1, &d));
    CX_CHECK(st.session != NULL);
    CX_CHECK(!tui_state_busy(&st));
    CX_CHECK(st.cur_method && strcmp(st.cur_method->id, "ssn-tresca") == 0);
    CX_CHECK(st.cache.factorizations == 1);
    CX_CHECK(tui_state_nruns(&st) == 1 && tui_state_run(&st)->nsteps == 0);
    CX_CHECK(st.m == st.info->m && st.m > 0);
    /* Hertz's pressure is there for the profile, zero beyond b ~ 2.72 */
    CX_CHECK_NEAR(st.hertz[0], cx_scene_hertz_pressure(&st.scene, st.info->contact.x[0]), 1e-12, 0);
    CX_CHECK(st.hertz[st.m - 1] == 0);

    /* three step keys: three iterations */
    CX_CHECK(tui_key(&st, 's') == TUI_REDRAW);
    tui_key(&st, ' ');
    tui_key(&st, 's');
    const tui_run *run = tui_state_run(&st);
    CX_CHECK(run->nsteps == 3 && run->steps[2].iter == 3);
    CX_CHECK(cx_session_iterate(st.session)->iter == 3);
    int n = run_to_end(&st, 60);
    run = tui_state_run(&st);
    CX_CHECK(run->reason > 0);
    CX_CHECK_LE(run->steps[n - 1].kkt, 1e-10);
    CX_CHECK_LE(run->steps[n - 1].kkt, run->steps[0].kkt);
    /* the run's solves are solve's (one with the factor of K, one for the
     * expansion at the end); the explorer's expansions for drawing after
     * each single step are counted apart */
    CX_CHECK(run->steps[n - 1].solves < n && run->steps[n - 1].solves >= 1);
    CX_CHECK(run->draw.solves >= n - 1);
    CX_CHECK(run->setup > 0 && run->steps[n - 1].time >= 0);
    /* the pressure snapshot is lN / weight of the session's iterate */
    const cx_iterate *it = cx_session_iterate(st.session);
    CX_CHECK_NEAR(st.pressure[0], it->lN[0] / st.info->contact.weight[0], 1e-14, 0);
    CX_CHECK(count_status(&st, CX_PT_CONTACT, CX_PT_CONTACT) == it->ncontact && it->ncontact > 0);
    /* a step after the end does nothing but say so */
    tui_key(&st, 's');
    CX_CHECK(tui_state_run(&st)->nsteps == n);
    CX_CHECK(strstr(st.msg, "run ended") != NULL);

    /* a parameter: RESOLVE, never REASSEMBLE; the factorisation is kept */
    st.field = TUI_F_PARAM0;
    int r = tui_key(&st, TUI_KEY_RIGHT);
    CX_CHECK(r == (TUI_REDRAW | TUI_RESOLVE));
    CX_CHECK_NEAR(st.sel_params.num[0], 2e-3, 1e-12, 0);
    tui_state_apply(&st, r);
    CX_CHECK_NEAR(st.cur_params.num[0], 2e-3, 1e-12, 0);
    CX_CHECK(tui_state_nruns(&st) == 2 && tui_state_run(&st)->nsteps == 0);
    CX_CHECK(strstr(tui_state_run_at(&st, 1)->params, "rho=0.002") != NULL);
    CX_CHECK(st.cache.factorizations == 1);

    /* a bad typed value names the key and its range; nothing changes */
    tui_key(&st, TUI_KEY_ENTER);
    CX_CHECK(st.editing);
    for (int k = 0; k < 10; k++)
        tui_key(&st, TUI_KEY_BACKSPACE);
    r = type(&st, "-5\n");
    CX_CHECK(r == TUI_REDRAW && !st.editing && st.msg_error);
    CX_CHECK(strstr(st.msg, "rho") != NULL);
    CX_CHECK_NEAR(st.sel_params.num[0], 2e-3, 1e-12, 0);

    /* Tresca: RESOLVE; the frictionless reduction (onto the normal dofs)
     * is kept, and the one onto every contact dof that Tresca needs is
     * built beside it, once: two factorisations from here on, whatever
     * the law */
    r = tui_key(&st, 'f');
    CX_CHECK(r == (TUI_REDRAW | TUI_RESOLVE) && st.sel_law == CX_FRICTION_TRESCA);
    tui_state_apply(&st, r);
    CX_CHECK(st.cur_law == CX_FRICTION_TRESCA && cx_session_friction(st.session)->law == CX_FRICTION_TRESCA);
    CX_CHECK_NEAR(st.cur_coef, st.scene.slip_bound, 1e-15, 0);
    CX_CHECK(st.cache.factorizations == 2);
    n = run_to_end(&st, 60);
    CX_CHECK(tui_state_run(&st)->reason > 0 && n > 1);
    CX_CHECK(count_status(&st, CX_PT_STICK, CX_PT_STICK) + count_status(&st, CX_PT_SLIP_POS, CX_PT_SLIP_NEG) > 0);

    /* the slip bound: RESOLVE, scaled by 1.25 */
    r = tui_key(&st, '+');
    CX_CHECK(r == (TUI_REDRAW | TUI_RESOLVE));
    tui_state_apply(&st, r);
    CX_CHECK_NEAR(st.cur_coef, 1.25 * st.scene.slip_bound, 1e-14, 0);
    CX_CHECK(st.cache.factorizations == 2);

    char reason[CX_DIAG_LEN];
    /* 'f' cycles the scene's laws and never dead-ends: Coulomb, which
     * ssn-tresca does not support, brings --method auto's Coulomb method;
     * four presses visit the three laws and come back to Tresca, each
     * converging */
    CX_CHECK(st.scene.laws == CX_SCENE_ALL_LAWS);
    cx_friction seen[4];
    for (int k = 0; k < 4; k++) {
        r = tui_key(&st, 'f');
        CX_CHECK(r & TUI_RESOLVE);
        tui_state_apply(&st, r);
        seen[k] = st.cur_law;
        CX_CHECK(st.cur_law == st.sel_law && st.cur_method == tui_state_sel_method(&st));
        CX_CHECK_OK(cx_method_check(st.cur_method, st.info, st.cur_law, &d));
        n = run_to_end(&st, 300);
        CX_CHECK(tui_state_run(&st)->reason > 0);
    }
    CX_CHECK(seen[0] == CX_FRICTION_COULOMB && seen[1] == CX_FRICTION_NONE && seen[2] == CX_FRICTION_TRESCA &&
             seen[3] == CX_FRICTION_COULOMB);
    CX_CHECK(strcmp(tui_state_run_at(&st, tui_state_nruns(&st) - 4)->method, "ssn-coulomb") == 0);
    tui_state_apply(&st, tui_key(&st, 'f'));
    tui_state_apply(&st, tui_key(&st, 'f'));
    CX_CHECK(st.cur_law == CX_FRICTION_TRESCA && strcmp(st.cur_method->id, "ssn-tresca") == 0);
    n = run_to_end(&st, 60);
    CX_CHECK(st.cache.factorizations == 2);

    /* a switch refused (the dual methods need K positive definite;
     * hertz's body is held by contact only, which the supports tell
     * before anything is factorised) changes nothing: not the iterate, not
     * the run and its steps, not the snapshot; the status line says why.
     * The method is greyed from the build on, before anyone tried it, and
     * the screening factorised nothing (two factorisations: ssn-tresca's
     * two reductions) */
    {
        const cx_iterate *it0 = cx_session_iterate(st.session);
        int iter0 = it0->iter, nruns0 = tui_state_nruns(&st), nsteps0 = tui_state_run(&st)->nsteps;
        double kkt0 = it0->kkt, p0 = st.pressure[st.m / 2];
        long fact0 = tui_state_run(&st)->factorizations, solves0 = it0->counters.solves;
        unsigned char status0[4096];
        memcpy(status0, st.status, (size_t)st.m);
        int mi = tui_method_index("mprgp");
        CX_CHECK(mi >= 0 && strstr(tui_state_method_reason(&st, mi, reason, sizeof reason),
                                    "no support in y (held only by contact)") != NULL);
        CX_CHECK(st.cache.factorizations == 2);
        st.field = TUI_F_METHOD;
        tui_key(&st, TUI_KEY_ENTER);
        for (int k = 0; k < 20; k++)
            tui_key(&st, TUI_KEY_BACKSPACE);
        r = type(&st, "mprgp\n");
        CX_CHECK(!(r & TUI_RESOLVE));
        tui_state_apply(&st, r);
        CX_CHECK(st.cache.factorizations == 2);
        CX_CHECK(st.msg_error && strstr(st.msg, "positive definite") != NULL);
        CX_CHECK(strcmp(st.cur_method->id, "ssn-tresca") == 0 && st.sel_method == tui_method_index("ssn-tresca"));
        const cx_iterate *it1 = cx_session_iterate(st.session);
        CX_CHECK(it1->iter == iter0 && it1->kkt == kkt0 && it1->reason > 0);
        CX_CHECK(it1->counters.solves == solves0);
        CX_CHECK(tui_state_nruns(&st) == nruns0 && tui_state_run(&st)->nsteps == nsteps0);
        CX_CHECK(tui_state_run(&st)->factorizations == fact0);
        CX_CHECK(memcmp(status0, st.status, (size_t)st.m) == 0 && st.pressure[st.m / 2] == p0);
        CX_CHECK(strstr(tui_state_method_reason(&st, mi, reason, sizeof reason), "positive definite") != NULL);
        /* 's' after it: the run has ended, nothing appended */
        tui_key(&st, 's');
        CX_CHECK(tui_state_run(&st)->nsteps == nsteps0 && cx_session_iterate(st.session)->iter == iter0);
        /* greyed now: typing it is refused at once, with no job */
        tui_key(&st, TUI_KEY_ENTER);
        for (int k = 0; k < 20; k++)
            tui_key(&st, TUI_KEY_BACKSPACE);
        r = type(&st, "mprgp\n");
        CX_CHECK(!(r & TUI_RESOLVE) && st.msg_error && strstr(st.msg, "positive definite") != NULL);
        CX_CHECK(st.sel_method == tui_method_index("ssn-tresca"));
    }

    /* the method row: 'm' goes to the next method that fits. A method may
     * add the one operator of its own to the cache the first time (ubr-*:
     * K + rM); nothing is ever factorised twice, so a second round through
     * every method adds no factorisation at all */
    long before = st.cache.factorizations;
    for (int k = 0; k < cx_method_count() + 1; k++) {
        long f0 = st.cache.factorizations;
        r = tui_key(&st, 'm');
        CX_CHECK(!(r & TUI_REASSEMBLE));
        tui_state_apply(&st, r);
        CX_CHECK(st.cur_method != NULL);
        CX_CHECK(st.cache.factorizations - f0 <= 1);
    }
    CX_CHECK(st.cache.factorizations - before <= cx_method_count());
    long after_round = st.cache.factorizations;
    for (int k = 0; k < cx_method_count() + 1; k++) {
        tui_state_apply(&st, tui_key(&st, 'm'));
        CX_CHECK(st.cur_method != NULL);
    }
    CX_CHECK(st.cache.factorizations == after_round);

    /* the tolerance: options only, the run goes on */
    tui_key(&st, 's');
    int runs_before = tui_state_nruns(&st);
    int steps_before = tui_state_run(&st)->nsteps;
    st.field = TUI_F_TOL;
    r = tui_key(&st, TUI_KEY_LEFT);
    CX_CHECK(r == (TUI_REDRAW | TUI_RESOLVE));
    tui_state_apply(&st, r);
    CX_CHECK_NEAR(st.cur_opt.tol, 1e-11, 1e-12, 0);
    CX_CHECK(tui_state_nruns(&st) == runs_before && tui_state_run(&st)->nsteps == steps_before);

    /* export: every step of every run, CSV and JSON, no NaN */
    char dir[] = "/tmp/tui_export_XXXXXX", csv[512], json[512];
    CX_CHECK(mkdtemp(dir) != NULL);
    CX_CHECK_OK(tui_export(&st, dir, csv, json, sizeof csv, &d));
    int total = 0;
    for (int k = 0; k < tui_state_nruns(&st); k++)
        total += tui_state_run_at(&st, k)->nsteps;
    FILE *f = fopen(csv, "r");
    int lines = 0, ch;
    while (f && (ch = fgetc(f)) != EOF)
        lines += ch == '\n';
    if (f)
        fclose(f);
    CX_CHECK(lines == total + 1);
    f = fopen(json, "r");
    char buf[1 << 16];
    size_t len = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
    buf[len] = '\0';
    if (f)
        fclose(f);
    CX_CHECK(strstr(buf, "\"scene\": \"hertz\"") != NULL && strstr(buf, "\"runs\"") != NULL);
    CX_CHECK(strstr(buf, "nan") == NULL && strstr(buf, "inf") == NULL);
    remove(csv);
    remove(json);
    rmdir(dir);

    /* rendering: a PNG of the current state in the export directory, or a
     * plain message in a build without the renderer */
#if CX_HAVE_RENDER
    snprintf(st.export_dir, sizeof st.export_dir, "%s", dir);
    CX_CHECK(mkdir(dir, 0700) == 0);
    CX_CHECK_OK(tui_render_png(&st, buf, sizeof buf, &d));
    f = fopen(buf, "rb");
    unsigned char sig[8] = {0};
    CX_CHECK(f && fread(sig, 1, 8, f) == 8 && memcmp(sig, "\x89PNG\r\n\x1a\n", 8) == 0);
    if (f)
        fclose(f);
    CX_CHECK(strstr(buf, "/signorini-hertz-L") != NULL);
    fprintf(stderr, "rendered %s\n", buf);
    remove(buf);
    tui_key(&st, 'p');
    CX_CHECK(!st.msg_error && strstr(st.msg, ".png") != NULL);
    char *png = strstr(st.msg, dir);
    if (png) {
        char name[512];
        snprintf(name, sizeof name, "%s", png);
        name[strcspn(name, " ")] = '\0';
        CX_CHECK(remove(name) == 0);
    }
    rmdir(dir);
#else
    CX_CHECK(tui_render_png(&st, buf, sizeof buf, &d) == CX_EUNSUPPORTED);
    tui_key(&st, 'p');
    CX_CHECK(st.msg_error && strstr(st.msg, "rendering not available") != NULL);
#endif

    /* the level: the only kind of change (with the scene) that reassembles */
    int dofs = st.info->n;
    r = tui_key(&st, ']');
    CX_CHECK(r == (TUI_REDRAW | TUI_REASSEMBLE));
    tui_state_apply(&st, r);
    CX_CHECK(st.level == 16 && st.info->n > dofs);
    CX_CHECK(tui_state_nruns(&st) == 1 && st.cache.factorizations == 1);

    /* help, quit */
    CX_CHECK(tui_key(&st, '?') == TUI_REDRAW && st.help);
    CX_CHECK(tui_key(&st, 's') == TUI_REDRAW && !st.help);
    CX_CHECK(tui_key(&st, 'q') == TUI_QUIT);
    CX_CHECK(tui_key(&st, TUI_KEY_CTRL_C) == TUI_QUIT);
    tui_state_clear(&st);
}

static void test_slider(void)
{
    static tui_state st;
    cx_diag d;
    cx_diag_clear(&d);
    CX_CHECK_OK(tui_state_init(&st, "hertz", 4, NULL, -1, 1, &d));
    /* typing a scene id reassembles on that scene with its friction */
    st.field = TUI_F_SCENE;
    tui_key(&st, TUI_KEY_ENTER);
    for (int k = 0; k < 10; k++)
        tui_key(&st, TUI_KEY_BACKSPACE);
    int r = type(&st, "slider\n");
    CX_CHECK(r == (TUI_REDRAW | TUI_REASSEMBLE));
    tui_state_apply(&st, r);
    CX_CHECK(strcmp(st.scene.id, "slider") == 0 && st.level == st.scene.level);
    CX_CHECK(st.cur_law == CX_FRICTION_TRESCA);
    /* the mesh view's outline of the 32 x 8 quad grid: its 2 (32 + 8) boundary edges */
    int noutline;
    tui_state_outline(&st, &noutline);
    CX_CHECK(noutline == 2 * (32 + 8));
    run_to_end(&st, 60);
    CX_CHECK(tui_state_run(&st)->reason > 0);
    /* the slider sticks in the middle and slips at the edges */
    CX_CHECK(count_status(&st, CX_PT_STICK, CX_PT_STICK) > 0);
    CX_CHECK(count_status(&st, CX_PT_SLIP_POS, CX_PT_SLIP_NEG) > 0);
    CX_CHECK(tui_state_nruns(&st) == 1);
    /* reset: a new run, nothing rebuilt */
    tui_key(&st, 'x');
    CX_CHECK(tui_state_nruns(&st) == 2 && tui_state_run(&st)->nsteps == 0 && st.cache.factorizations == 1);
    tui_state_clear(&st);

    /* an unknown scene or method at start is an error with the reason */
    CX_CHECK(tui_state_init(&st, "nope", 0, NULL, -1, 1, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "nope") != NULL);
    CX_CHECK(tui_state_init(&st, "hertz", 0, "nope", -1, 1, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "unknown method 'nope'") != NULL);
}

/* ssn-tresca with rho = 1 on hertz with Tresca alternates between two
 * iterates from iteration 6 on (kkt 2.482e-2, 2.544e-2: see the comment
 * in solve/ssn_tresca.c): the explorer says so and pauses. */
static void test_cycle(void)
{
    static tui_state st;
    cx_diag d;
    cx_diag_clear(&d);
    CX_CHECK_OK(tui_state_init(&st, "hertz", 32, NULL, CX_FRICTION_TRESCA, 1, &d));
    st.field = TUI_F_PARAM0;
    tui_key(&st, TUI_KEY_ENTER);
    for (int k = 0; k < 10; k++)
        tui_key(&st, TUI_KEY_BACKSPACE);
    tui_state_apply(&st, type(&st, "1\n"));
    CX_CHECK_NEAR(st.cur_params.num[0], 1, 0, 0);
    st.running = 1;
    for (int k = 0; k < 12 && st.running; k++)
        tui_state_step(&st);
    const tui_run *run = tui_state_run(&st);
    /* iteration 8 has 6's kkt but not its own criterion; 9 repeats 7 in
     * both (and in the set): a true 2-cycle */
    CX_CHECK(st.cycle_iter == 9 && run->nsteps == 9);
    CX_CHECK(!st.running && st.msg_error == 2 && strstr(st.msg, "cycling: iteration 9 repeats iteration 7"));
    CX_CHECK_NEAR(run->steps[8].kkt, run->steps[6].kkt, 1e-10, 0);
    CX_CHECK(run->reason == CX_ITERATING);
    /* a new run forgets it */
    tui_key(&st, 'x');
    CX_CHECK(st.cycle_iter == 0);
    tui_state_clear(&st);

    /* a plateau is no cycle: lssnn on halfball sits at kkt 1 for its first
     * steps (its own criterion moving) and converges in 85 as solve does;
     * 'r' runs it through without a pause */
    CX_CHECK_OK(tui_state_init(&st, "halfball", 0, "lssnn", -1, 1, &d));
    tui_key(&st, 'r');
    while (st.running)
        tui_state_step(&st);
    run = tui_state_run(&st);
    CX_CHECK(st.cycle_iter == 0 && run->reason == CX_CONVERGED_KKT && run->nsteps == 85);
    CX_CHECK(run->factorizations == 2 && run->steps[84].solves == 85);
    tui_state_clear(&st);
}

/* The loop's part without a terminal: poll the job, step while running. */
static void drive(tui_state *st, double seconds)
{
    double end = cx_clock_now() + seconds;
    while (cx_clock_now() < end) {
        tui_state_poll(st);
        if (tui_state_running(st) && !tui_state_busy(st))
            tui_state_step(st);
        if (!tui_state_busy(st) && !tui_state_running(st) && !st->queued_steps)
            return;
        nanosleep(&(struct timespec){0, 1000000}, NULL);
    }
}

/* With the jobs on their thread, as in the terminal: 'r' typed while a
 * friction switch runs asks for the run that switch opens (it said "run
 * ended" of the converged run on screen before). */
static void test_run_during_switch(void)
{
    static tui_state st;
    cx_diag d;
    cx_diag_clear(&d);
    CX_CHECK_OK(tui_state_init(&st, "hertz", 16, "ssn-tresca", CX_FRICTION_NONE, 0, &d));
    drive(&st, 120);
    CX_CHECK(st.session && st.cur_law == CX_FRICTION_NONE);
    tui_key(&st, 'r');
    drive(&st, 120);
    CX_CHECK(tui_state_run(&st)->reason == CX_CONVERGED_KKT);
    int nruns = tui_state_nruns(&st);
    tui_state_apply(&st, tui_key(&st, 'f'));
    int busy = tui_state_busy(&st);
    CX_CHECK(tui_key(&st, 'r') == TUI_REDRAW && st.running);
    CX_CHECK(busy && strstr(st.msg, "runs when the switch ends") != NULL);   /* the switch runs on its thread */
    drive(&st, 120);
    const tui_run *run = tui_state_run(&st);
    CX_CHECK(st.cur_law == CX_FRICTION_TRESCA && tui_state_nruns(&st) == nruns + 1);
    CX_CHECK(run->law == CX_FRICTION_TRESCA && run->reason == CX_CONVERGED_KKT && run->nsteps > 0);
    CX_CHECK(strstr(st.msg, "converged in ") != NULL);
    if (!strstr(st.msg, "converged in "))
        fprintf(stderr, "after f r: %s\n", st.msg);
    tui_state_clear(&st);
}

#if CX_HAVE_RENDER
/* 'p' in the explorer draws what solve --png draws: on the running bond
 * wall (rollers on its sides and the right half of its base) the
 * explorer's picture equals, pixel for pixel, the renderer's with the
 * scene's supports, and differs from the one without them. */
static void test_png_supports(void)
{
    static tui_state st;
    cx_diag d;
    cx_diag_clear(&d);
    CX_CHECK_OK(tui_state_init(&st, "runningbond", 0, "graves", -1, 1, &d));
    tui_key(&st, 'r');
    while (st.running)
        tui_state_step(&st);
    char dir[] = "/tmp/tui_png_XXXXXX", file[512], with[600], without[600];
    CX_CHECK(mkdtemp(dir) != NULL);
    snprintf(st.export_dir, sizeof st.export_dir, "%s", dir);
    CX_CHECK_OK(tui_render_png(&st, file, sizeof file, &d));
    snprintf(with, sizeof with, "%s/with.png", dir);
    snprintf(without, sizeof without, "%s/without.png", dir);
    cx_result *res = NULL;
    CX_CHECK_OK(cx_result_from_session(&res, st.session, &st.scene, st.level, &d));
    cx_render_opts o;
    cx_render_opts_default(&o);
    o.scale = st.disp_scale;
    o.scene = &st.scene;
    CX_CHECK_OK(cx_render_png(res, &o, with, NULL, &d));
    o.scene = NULL;
    CX_CHECK_OK(cx_render_png(res, &o, without, NULL, &d));
    cx_result_destroy(&res);
    test_png a, b, c;
    CX_CHECK(test_png_read(&a, file) == 0 && test_png_read(&b, with) == 0 && test_png_read(&c, without) == 0);
    size_t bytes = (size_t)a.w * a.h * 3;
    CX_CHECK(a.w == b.w && a.h == b.h && a.rgb && b.rgb && memcmp(a.rgb, b.rgb, bytes) == 0);
    CX_CHECK(a.w == c.w && a.h == c.h && c.rgb && memcmp(a.rgb, c.rgb, bytes) != 0);
    free(a.rgb), free(b.rgb), free(c.rgb);
    remove(file), remove(with), remove(without);
    rmdir(dir);
    tui_state_clear(&st);
}
#endif

/* A scene that fails to build (the block starts inside the plane): the
 * message says why and the explorer stays on the scene it had. */
static void test_failed_build(void)
{
    char dir[] = "/tmp/tui_scenes_XXXXXX", path[600], scenes[1200];
    CX_CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/sunk.ini", dir);
    FILE *f = fopen(path, "w");
    CX_CHECK(f != NULL);
    if (!f)
        return;
    fputs("[scene]\nid = sunk\ntitle = a block below the plane\ndim = 2\n"
          "[mesh]\ngenerator = rectangle\nelement = quad4\nlo = -2 0\nhi = 2 1\ncells = 8 2\nlevel = 1\n"
          "level_max = 4\n[material]\nmodel = plane_strain\nE = 1000\nnu = 0.3\n"
          "[support punch]\nboundary = top\nfix = xy\nvalue = 0 -0.01\n"
          "[contact]\nboundary = bottom\nobstacle = plane\npoint = 0 0.5\nnormal = 0 1\nfriction = none\n"
          "[methods]\nlist = ssn-tresca\n", f);
    fclose(f);
    const char *old = getenv("SIGNORINI_SCENES");
    snprintf(scenes, sizeof scenes, "%s:%s", old ? old : "", dir);
    setenv("SIGNORINI_SCENES", scenes, 1);

    static tui_state st;
    cx_diag d;
    cx_diag_clear(&d);
    CX_CHECK_OK(tui_state_init(&st, "hertz", 4, NULL, -1, 1, &d));
    int dofs = st.info->n;
    st.field = TUI_F_SCENE;
    tui_key(&st, TUI_KEY_ENTER);
    for (int k = 0; k < 10; k++)
        tui_key(&st, TUI_KEY_BACKSPACE);
    int r = type(&st, "sunk\n");
    CX_CHECK(r == (TUI_REDRAW | TUI_REASSEMBLE));
    tui_state_apply(&st, r);
    CX_CHECK(st.msg_error == 1 && strstr(st.msg, "penetrates the plane obstacle by 0.5") != NULL);
    CX_CHECK(strcmp(st.scene.id, "hertz") == 0 && strcmp(st.scene_ids[st.sel_scene], "hertz") == 0);
    CX_CHECK(st.info->n == dofs && st.level == 4 && st.sel_level == 4);
    /* and it still steps */
    tui_key(&st, 's');
    CX_CHECK(tui_state_run(&st)->nsteps == 1);
    tui_state_clear(&st);
    if (old)
        setenv("SIGNORINI_SCENES", old, 1);
    remove(path);
    rmdir(dir);
}

static void test_pieces(void)
{
    /* strip buckets: slip beats stick beats contact beats free */
    unsigned char s[6] = {CX_PT_FREE, CX_PT_STICK, CX_PT_CONTACT, CX_PT_SLIP_NEG, CX_PT_FREE, CX_PT_FREE};
    unsigned char c[6] = {0, 0, 0, 0, 1, 0};
    int ch;
    CX_CHECK(tui_bucket_status(s, c, 0, 3, &ch) == CX_PT_STICK && !ch);
    CX_CHECK(tui_bucket_status(s, c, 1, 4, &ch) == CX_PT_SLIP_NEG && !ch);
    CX_CHECK(tui_bucket_status(s, c, 4, 6, &ch) == CX_PT_FREE && ch);

    /* braille: dot (0,0) is U+2801, dot (1,3) U+2880; ASCII by halves */
    tui_canvas cv;
    tui_canvas_init(&cv, 3, 2);
    char g[8];
    tui_canvas_dot(&cv, 0, 0, TUI_C_BAR);
    tui_canvas_dot(&cv, 3, 3, TUI_C_REF);
    tui_canvas_dot(&cv, 2, 0, TUI_C_BAR);
    tui_canvas_dot(&cv, 99, 99, TUI_C_BAR); /* clipped */
    tui_canvas_glyph(&cv, 0, 0, 1, g);
    CX_CHECK(strcmp(g, "\xE2\xA0\x81") == 0);
    tui_canvas_glyph(&cv, 1, 0, 1, g);
    CX_CHECK(strcmp(g, "\xE2\xA2\x81") == 0);     /* 0x01 | 0x80 */
    CX_CHECK(cv.role[1] == TUI_C_REF);             /* the higher role wins */
    tui_canvas_glyph(&cv, 1, 0, 0, g);
    CX_CHECK(strcmp(g, ":") == 0);
    tui_canvas_glyph(&cv, 0, 0, 0, g);
    CX_CHECK(strcmp(g, "'") == 0);
    tui_canvas_glyph(&cv, 2, 1, 1, g);
    CX_CHECK(strcmp(g, " ") == 0);
    /* a horizontal line across the lower row lights its bottom dots */
    tui_canvas_line(&cv, 0, 7, 5, 7, TUI_C_BAR);
    for (int i = 0; i < 3; i++) {
        tui_canvas_glyph(&cv, i, 1, 1, g);
        CX_CHECK(strcmp(g, "\xE2\xA3\x80") == 0); /* 0x40 | 0x80 */
    }
    tui_canvas_free(&cv);

    /* the help lists every named key */
    int named = 0;
    for (const tui_binding *b = tui_bindings(); b->key; b++)
        named += b->keyname && b->help;
    CX_CHECK(named >= 20);
}

/* Every scene opens on --method auto's choice for its default law, and
 * that method converges on it ('r'); the run keeps the outcome sentence
 * the runs table shows. */
static void test_scenes_open_converging(void)
{
    static tui_state st;
    cx_diag d;
    cx_diag_clear(&d);
    char (*ids)[CX_SCENE_NAMELEN] = NULL;
    int n = 0;
    CX_CHECK_OK(cx_scene_list(&ids, &n, &d));
    CX_CHECK(n >= 9);
    for (int k = 0; k < n; k++) {
        CX_CHECK_OK(tui_state_init(&st, ids[k], 0, NULL, -1, 1, &d));
        const char *sets;
        const char *want = cx_scene_auto_method(&st.scene, st.scene.level, NULL, st.scene.friction, &sets);
        CX_CHECK(st.cur_method && strcmp(st.cur_method->id, want) == 0);
        CX_CHECK(st.cur_law == st.scene.friction);
        tui_key(&st, 'r');
        while (st.running)
            tui_state_step(&st);
        const tui_run *run = tui_state_run(&st);
        CX_CHECK(run->reason > 0);
        CX_CHECK(strncmp(run->outcome, "converged in ", 13) == 0);
        if (run->reason <= 0)
            fprintf(stderr, "%s: %s does not converge: %s\n", ids[k], st.cur_method->id, st.msg);
        tui_state_clear(&st);
    }
    cx_free(ids);
}

/* Issue 21: each run its colour (the shared series palette, kept when the
 * table drops older runs), the legend, the palette's terminal mapping and
 * the presentation pace the loop waits by. */
static void test_colours_and_pace(void)
{
    /* the nearest terminal colours of the palette's entries */
    const unsigned char blue[3] = {0, 114, 178}, orange[3] = {230, 159, 0}, grey[3] = {153, 153, 153};
    CX_CHECK(tui_palette_xterm256(blue) == 16 + 0 * 36 + 1 * 6 + 3);    /* (0, 95, 175) */
    CX_CHECK(tui_palette_xterm256(orange) == 16 + 4 * 36 + 3 * 6 + 0);  /* (215, 175, 0) */
    CX_CHECK(tui_palette_xterm256(grey) == 246);                          /* grey 148 */
    CX_CHECK(tui_palette_basic8(blue) == 4 || tui_palette_basic8(blue) == 6);
    CX_CHECK(tui_palette_basic8(orange) == 3 || tui_palette_basic8(orange) == 1);
    CX_CHECK(tui_palette_basic8(cx_palette_series[2]) == 2 || tui_palette_basic8(cx_palette_series[2]) == 6);
    CX_CHECK(tui_palette_basic8(cx_palette_series[3]) == 1);
    for (int k = 0; k < CX_PALETTE_NSERIES; k++) {
        /* never black or white: a run stays visible on both backgrounds */
        int b = tui_palette_basic8(cx_palette_series[k]);
        CX_CHECK(b != 0 && b != 7);
        for (int j = 0; j < k; j++)
            CX_CHECK(tui_palette_xterm256(cx_palette_series[j]) != tui_palette_xterm256(cx_palette_series[k]));
    }

    static tui_state st;
    cx_diag d;
    cx_diag_clear(&d);
    CX_CHECK_OK(tui_state_init(&st, "hertz", 8, NULL, -1, 1, &d));
    tui_state_apply(&st, tui_key(&st, 's'));
    CX_CHECK(tui_state_nruns(&st) == 1 && tui_run_colour(tui_state_run(&st)) == 0);
    /* a changed parameter opens a second run: the next colour, and the
     * legend names the method and the changed parameter */
    st.field = TUI_F_PARAM0;
    tui_state_apply(&st, tui_key(&st, TUI_KEY_RIGHT));
    tui_state_apply(&st, tui_key(&st, 's'));
    CX_CHECK(tui_state_nruns(&st) == 2);
    const tui_run *r1 = tui_state_run_at(&st, 1);
    CX_CHECK(tui_run_colour(r1) == 1);
    char leg[64];
    tui_run_legend(r1, leg, sizeof leg);
    CX_CHECK(strncmp(leg, "ssn-tresca rho=", 15) == 0);
    tui_run_legend(tui_state_run_at(&st, 0), leg, sizeof leg);
    CX_CHECK(strcmp(leg, "ssn-tresca") == 0);
    /* 'c' keeps the current run, and its colour */
    tui_state_apply(&st, tui_key(&st, 'c'));
    CX_CHECK(tui_state_nruns(&st) == 1 && tui_run_colour(tui_state_run(&st)) == 1);

    /* the pace: no wait outside presentation mode; 'P' gives 2 steps a
     * second; '}' doubles, '{' halves, within the bounds */
    CX_CHECK(tui_state_step_interval(&st) == 0);
    CX_CHECK(tui_key(&st, 'P') == TUI_REDRAW && st.present);
    CX_CHECK(fabs(tui_state_step_interval(&st) - 0.5) < 1e-12);
    tui_key(&st, '}');
    CX_CHECK(fabs(tui_state_step_interval(&st) - 0.25) < 1e-12);
    tui_key(&st, '{');
    tui_key(&st, '{');
    CX_CHECK(fabs(tui_state_step_interval(&st) - 1.0) < 1e-12);
    for (int k = 0; k < 10; k++)
        tui_key(&st, '{');
    CX_CHECK(fabs(tui_state_step_interval(&st) - 1 / TUI_PACE_MIN) < 1e-12);
    for (int k = 0; k < 20; k++)
        tui_key(&st, '}');
    CX_CHECK(fabs(tui_state_step_interval(&st) - 1 / TUI_PACE_MAX) < 1e-12);
    /* the pace keys change nothing of the run */
    CX_CHECK(tui_state_nruns(&st) == 1 && tui_state_run(&st)->nsteps == 1);
    CX_CHECK(tui_key(&st, 'P') == TUI_REDRAW && !st.present && tui_state_step_interval(&st) == 0);
    /* Esc pauses a run and changes nothing of it */
    tui_state_apply(&st, tui_key(&st, 'r'));
    CX_CHECK(st.running);
    CX_CHECK(tui_key(&st, TUI_KEY_ESC) == TUI_REDRAW && !st.running && strstr(st.msg, "paused"));
    CX_CHECK(tui_state_nruns(&st) == 1 && tui_state_run(&st)->nsteps == 1 && tui_state_run(&st)->reason == 0);
    tui_state_clear(&st);
}

/* The level row's estimate: the dofs of the next level within 20% of the
 * build's, memory and time positive and growing with the level; a level
 * whose memory estimate exceeds what is available is refused with the
 * figures, and nothing is built (the selection stays). */
static void test_level_estimate(void)
{
    static tui_state st;
    cx_diag d;
    const char *scenes[] = {"hertz", "block3d"};
    const int levels[] = {16, 4};
    for (int k = 0; k < 2; k++) {
        CX_CHECK_OK(tui_state_init(&st, scenes[k], levels[k], NULL, -1, 1, &d));
        double n, b, t, n2, b2, t2;
        CX_CHECK(tui_state_level_estimate(&st, levels[k], &n, &b, &t) && n == st.info->n);
        CX_CHECK(tui_state_level_estimate(&st, 2 * levels[k], &n2, &b2, &t2));
        CX_CHECK(b > 0 && t > 0 && b2 > b && t2 > t);
        char msg[CX_DIAG_LEN];
        CX_CHECK(!tui_state_level_refused(&st, 2 * levels[k], 1e12, msg, sizeof msg));
        CX_CHECK(tui_state_level_refused(&st, 2 * levels[k], b2 / 2, msg, sizeof msg));
        CX_CHECK(strstr(msg, "refused") != NULL && strstr(msg, "available") != NULL);
        /* the level row: its dofs; ']' builds the next level (sync) */
        st.field = TUI_F_LEVEL;
        char val[64];
        tui_field_value(&st, TUI_F_LEVEL, val, sizeof val);
        CX_CHECK(strstr(val, "dofs") != NULL || strchr(val, 'k') != NULL);
        tui_state_apply(&st, tui_key(&st, ']'));
        CX_CHECK(st.level == 2 * levels[k]);
        CX_CHECK(fabs(n2 - st.info->n) <= 0.25 * st.info->n);
        printf("%s level %d: %d dofs, estimated %.0f\n", scenes[k], st.level, st.info->n, n2);
        tui_state_clear(&st);
    }
}

/* The level asked for at start, above the scene's default: the default
 * level is built first and measures it. Refused with the estimate and the
 * memory available when it does not fit (the measured level open and
 * stepping); built when it fits, its dofs within 10% of the estimate.
 * $SIGNORINI_MEMAVAILABLE stands in for MemAvailable (malformed: ignored). */
static void test_first_level(void)
{
    static tui_state st;
    cx_diag d;
    setenv("SIGNORINI_MEMAVAILABLE", "100e6", 1);
    CX_CHECK(tui_mem_available() == 100e6 && strcmp(tui_mem_source(), "SIGNORINI_MEMAVAILABLE") == 0);
    CX_CHECK_OK(tui_state_init(&st, "block3d", 16, NULL, -1, 1, &d));
    CX_CHECK(st.session && st.level == st.scene.level && st.level < 16 && st.sel_level == st.level);
    CX_CHECK(st.msg_error == 1 && strstr(st.msg, "level 16 refused: about ") &&
             strstr(st.msg, "100 MB of memory is available (SIGNORINI_MEMAVAILABLE)") &&
             strstr(st.msg, "block3d level 4, built to measure it, is open"));
    double n, b, t;
    CX_CHECK(tui_state_level_estimate(&st, 16, &n, &b, &t) && b > 100e6 && t > 0);
    /* block3d 16: 33 x 33 x 17 nodes, 54 417 dofs */
    CX_CHECK(fabs(n - 54417) < 0.1 * 54417);
    tui_key(&st, 's');
    CX_CHECK(tui_state_nruns(&st) == 1 && tui_state_run(&st)->nsteps == 1);
    tui_state_clear(&st);

    setenv("SIGNORINI_MEMAVAILABLE", "100e9", 1);
    CX_CHECK_OK(tui_state_init(&st, "block3d", 8, NULL, -1, 1, &d));
    CX_CHECK(st.level == 8 && st.sel_level == 8 && st.target_level == 0);
    CX_CHECK(st.msg_error == 0 && strstr(st.msg, "block3d level 8:") && strstr(st.msg, "built in"));
    tui_state_clear(&st);
    /* the default level itself: built at once, nothing measured first */
    CX_CHECK_OK(tui_state_init(&st, "block3d", 4, NULL, -1, 1, &d));
    CX_CHECK(st.level == 4 && st.msg_error == 0 && strstr(st.msg, "block3d level 4:"));
    tui_state_clear(&st);

    setenv("SIGNORINI_MEMAVAILABLE", "lots", 1);
    CX_CHECK(strcmp(tui_mem_source(), "/proc/meminfo MemAvailable") == 0);
    unsetenv("SIGNORINI_MEMAVAILABLE");
}

/* The mesh view in 3D draws the surface's folds, not every surface edge:
 * block3d at level 4 is an 8 x 8 x 4 brick, whose 12 box edges are 4 x 8 +
 * 4 x 8 + 4 x 4 = 80 mesh edges; its plane obstacle is drawn, twoblocks'
 * second body is no obstacle. */
static void test_mesh_view(void)
{
    static tui_state st;
    cx_diag d;
    CX_CHECK_OK(tui_state_init(&st, "block3d", 4, NULL, -1, 1, &d));
    int nout;
    tui_state_outline(&st, &nout);
    CX_CHECK(st.mesh_view.nfeatures == 80 && nout > 3 * st.mesh_view.nfeatures);
    CX_CHECK(st.mesh_view.has_obstacle && st.mesh_view.obstacle.kind == CX_OBST_PLANE);
    tui_state_clear(&st);
    CX_CHECK_OK(tui_state_init(&st, "twoblocks", 0, NULL, -1, 1, &d));
    CX_CHECK(!st.mesh_view.has_obstacle && st.mesh_view.nfeatures == 0);
    tui_state_clear(&st);
}

int main(void)
{
    test_level_estimate();
    test_first_level();
    test_mesh_view();
    test_pieces();
    test_hertz();
    test_colours_and_pace();
    test_slider();
    test_cycle();
    test_run_during_switch();
#if CX_HAVE_RENDER
    test_png_supports();
#endif
    test_failed_build();
    test_scenes_open_converging();
    return check_finish("tui_actions");
}
