/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Two sessions on two threads (issue 19): scenes loaded, built and solved
 * concurrently give the same numbers, bit for bit, as the same runs done
 * alone; scene loading from several threads at once; the allocation
 * counters and the failure injection under concurrency. Run under
 * ThreadSanitizer in CI (meson setup -Db_sanitize=thread; suite 'threads').
 *
 * The jobs cover every place that held global state: the contact-row sorts
 * of rigid 3D (block3d), node-to-segment (twoblocks) and masonry
 * (stackbond) scenes, cf-fp's inner_set parsing (slider), the scene reader,
 * and the allocator. check.h's counters are not thread-safe: the threads
 * only record, the main thread checks. */
#include "scene/scene.h"
#include "check.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#if CX_TEST_RENDER
#include "out/result.h"
#include "render/render.h"
#endif

/* ---- one run: load, build, solve, keep the numbers --------------------------- */

typedef struct {
    const char *scene;
    int level;
    cx_friction law;
    double value;             /* slip bound or F (the scene's if < 0) */
    const char *method;
    const char *sets[6];      /* "key=value", NULL-terminated */
} job;

typedef struct {
    int status;               /* CX_OK or the first failure */
    char msg[CX_DIAG_LEN];
    int n, m, nt;
    double *u, *lN, *lT;      /* malloc'ed copies */
    int iter, reason;
    double kkt;
    cx_counters counters;
    long live_thread;         /* cx_alloc_live_thread() after minus before */
} outcome;

static const job jobs[] = {
    {"hertz", 16, CX_FRICTION_TRESCA, -1, "ssn-tresca", {NULL}},
    {"twoblocks", 6, CX_FRICTION_COULOMB, 0.3, "ssn-coulomb", {NULL}},
    {"slider", 4, CX_FRICTION_COULOMB, 0.3, "cf-fp", {"inner=ssn-tresca-dual", "inner_set=rho=0.5,eps=1e-12", "eps_fp=1e-12", "eps_min=1e-12", NULL}},
    {"stackbond", 4, CX_FRICTION_NONE, 0, "pdas", {NULL}},
    {"block3d", 2, CX_FRICTION_NONE, 0, "ssn-tresca", {NULL}},
    {"twoblocks", 5, CX_FRICTION_TRESCA, -1, "mprgp", {"eps=1e-12", NULL}},
};
#define NJOBS ((int)(sizeof jobs / sizeof jobs[0]))

static double *copy_of(const double *x, int n)
{
    double *c = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
    if (c && n > 0)
        memcpy(c, x, sizeof(double) * (size_t)n);
    return c;
}

static void outcome_clear(outcome *o)
{
    free(o->u);
    free(o->lN);
    free(o->lT);
    memset(o, 0, sizeof *o);
}

/* Thread-safe: no strtok (fixture_run's parsing uses it), no check.h. */
static void run_job(const job *j, outcome *o)
{
    cx_diag d = {0};
    cx_scene sc;
    cx_problem *p = NULL;
    cx_session *s = NULL;
    char path[512];
    memset(o, 0, sizeof *o);
    long live = cx_alloc_live_thread();
    int st = cx_scene_resolve(j->scene, path, sizeof path, &d);
    if (!st)
        st = cx_scene_load(&sc, path, &d);
    if (!st)
        st = cx_scene_build(&sc, j->level, &p, NULL, &d);
    if (!st)
        st = cx_session_create(&s, &p, &d);
    if (!st) {
        cx_friction_state fr = {j->law, sc.slip_bound, sc.F, NULL, NULL};
        if (j->value >= 0 && j->law == CX_FRICTION_COULOMB)
            fr.F = j->value;
        else if (j->value >= 0)
            fr.slip_bound = j->value;
        st = cx_session_set_friction(s, &fr, &d);
    }
    const cx_method *m = cx_method_find(j->method);
    cx_param_values pv;
    if (!st && !m)
        st = cx_diag_set(&d, CX_EINVAL, "no method %s", j->method);
    if (!st) {
        cx_param_default(&pv, m->params);
        for (int k = 0; !st && j->sets[k]; k++)
            st = cx_param_set_pair(&pv, j->sets[k], j->method, &d);
    }
    if (!st) {
        cx_options opt;
        cx_options_default(&opt);
        opt.tol = 1e-10;
        opt.max_iter = 500;
        st = cx_session_set_method(s, m, &pv, &opt, &d);
    }
    if (!st)
        st = cx_solver_solve(s, NULL, NULL, &d);
    if (!st) {
        const cx_problem *pp = cx_session_problem(s);
        const cx_iterate *it = cx_session_iterate(s);
        o->n = pp->n;
        o->m = pp->m;
        o->nt = pp->nt;
        o->u = copy_of(it->u, pp->n);
        o->lN = copy_of(it->lN, pp->m);
        o->lT = copy_of(it->lT, pp->nt);
        o->iter = it->iter;
        o->reason = it->reason;
        o->kkt = it->kkt;
        o->counters = it->counters;
    }
    o->status = st;
    if (st)
        snprintf(o->msg, sizeof o->msg, "%s", d.msg);
    cx_session_destroy(&s);
    cx_problem_destroy(&p);
    o->live_thread = cx_alloc_live_thread() - live;
}

static int same_array(const double *a, const double *b, int n)
{
    return n == 0 || memcmp(a, b, sizeof(double) * (size_t)n) == 0;
}

/* The concurrent run equals the run alone, bit for bit: each session owns
 * all it computes with, and BLAS runs single-threaded (the test's
 * environment), so nothing may differ. */
static void check_same(const job *j, const outcome *got, const outcome *ref, const char *when)
{
    if (got->status)
        fprintf(stderr, "%s %s (%s): %s\n", j->scene, j->method, when, got->msg);
    CX_CHECK(got->status == CX_OK);
    CX_CHECK(got->live_thread == 0);
    if (got->status)
        return;
    int same = got->n == ref->n && got->m == ref->m && got->nt == ref->nt && got->iter == ref->iter &&
               got->reason == ref->reason && memcmp(&got->kkt, &ref->kkt, sizeof got->kkt) == 0 &&
               memcmp(&got->counters, &ref->counters, sizeof got->counters) == 0 &&
               same_array(got->u, ref->u, ref->n) && same_array(got->lN, ref->lN, ref->m) &&
               same_array(got->lT, ref->lT, ref->nt);
    if (!same)
        fprintf(stderr, "%s %s (%s): differs from the run alone (iter %d/%d, kkt %.17g/%.17g)\n",
                j->scene, j->method, when, got->iter, ref->iter, got->kkt, ref->kkt);
    CX_CHECK(same);
}

/* ---- two runs at once ----------------------------------------------------- */

typedef struct {
    const job *j;
    outcome o;
    pthread_barrier_t *start;   /* both threads start together */
} task;

static void *task_main(void *arg)
{
    task *t = arg;
    pthread_barrier_wait(t->start);
    run_job(t->j, &t->o);
    return NULL;
}

static void run_pair(int a, int b, const outcome *ref, int round)
{
    pthread_barrier_t start;
    pthread_t th[2];
    task t[2] = {{&jobs[a], {0}, &start}, {&jobs[b], {0}, &start}};
    CX_CHECK(pthread_barrier_init(&start, NULL, 2) == 0);
    for (int k = 0; k < 2; k++)
        CX_CHECK(pthread_create(&th[k], NULL, task_main, &t[k]) == 0);
    for (int k = 0; k < 2; k++)
        pthread_join(th[k], NULL);
    pthread_barrier_destroy(&start);
    char when[64];
    snprintf(when, sizeof when, "round %d, beside job %d", round, b);
    check_same(&jobs[a], &t[0].o, &ref[a], when);
    snprintf(when, sizeof when, "round %d, beside job %d", round, a);
    check_same(&jobs[b], &t[1].o, &ref[b], when);
    outcome_clear(&t[0].o);
    outcome_clear(&t[1].o);
}

static void test_sessions(void)
{
    outcome ref[NJOBS];
    long live = cx_alloc_live();
    for (int k = 0; k < NJOBS; k++) {
        run_job(&jobs[k], &ref[k]);
        if (ref[k].status)
            fprintf(stderr, "%s %s alone: %s\n", jobs[k].scene, jobs[k].method, ref[k].msg);
        CX_CHECK(ref[k].status == CX_OK && ref[k].reason > 0);
        CX_CHECK(ref[k].live_thread == 0);
    }
    /* different jobs side by side, and each job beside itself or another
     * of the same contact kind (the sorts of contact/ used statics) */
    static const int pairs[][2] = {{0, 1}, {2, 3}, {4, 5}, {1, 5}, {3, 4}, {5, 0}, {1, 2},
                                   {0, 0}, {2, 2}, {3, 3}, {4, 4}};
    int npairs = (int)(sizeof pairs / sizeof pairs[0]);
    for (int round = 0; round < 3; round++)
        for (int q = 0; q < npairs; q++)
            run_pair(pairs[q][0], pairs[q][1], ref, round);
    for (int k = 0; k < NJOBS; k++)
        outcome_clear(&ref[k]);
    CX_CHECK(cx_alloc_live() == live);
}

/* ---- scene loading from several threads --------------------------------------- */

#define LOADERS 4
#define LOAD_ROUNDS 5

typedef struct {
    char (*ids)[CX_SCENE_NAMELEN];
    int nids;
    const cx_scene *ref;
    pthread_barrier_t *start;
    int loads, mismatches, failures;
} loader;

static void *loader_main(void *arg)
{
    loader *l = arg;
    pthread_barrier_wait(l->start);
    for (int r = 0; r < LOAD_ROUNDS; r++)
        for (int k = 0; k < l->nids; k++) {
            cx_scene sc;
            char path[512];
            cx_diag d;
            if (cx_scene_resolve(l->ids[k], path, sizeof path, &d) || cx_scene_load(&sc, path, &d)) {
                l->failures++;
                continue;
            }
            l->loads++;
            /* cx_scene is plain data, zeroed before it is filled */
            if (memcmp(&sc, &l->ref[k], sizeof sc) != 0)
                l->mismatches++;
        }
    return NULL;
}

static void test_loading(void)
{
    char (*ids)[CX_SCENE_NAMELEN] = NULL;
    int nids = 0;
    cx_diag d;
    CX_CHECK_OK(cx_scene_list(&ids, &nids, &d));
    CX_CHECK(nids >= 9);
    cx_scene *ref = calloc((size_t)nids, sizeof *ref);
    for (int k = 0; k < nids; k++) {
        char path[512];
        CX_CHECK_OK(cx_scene_resolve(ids[k], path, sizeof path, &d));
        CX_CHECK_OK(cx_scene_load(&ref[k], path, &d));
    }
    pthread_barrier_t start;
    pthread_barrier_init(&start, NULL, LOADERS);
    pthread_t th[LOADERS];
    loader l[LOADERS];
    for (int t = 0; t < LOADERS; t++) {
        l[t] = (loader){ids, nids, ref, &start, 0, 0, 0};
        CX_CHECK(pthread_create(&th[t], NULL, loader_main, &l[t]) == 0);
    }
    for (int t = 0; t < LOADERS; t++) {
        pthread_join(th[t], NULL);
        CX_CHECK(l[t].failures == 0);
        CX_CHECK(l[t].mismatches == 0);
        CX_CHECK(l[t].loads == LOAD_ROUNDS * nids);
    }
    pthread_barrier_destroy(&start);
    free(ref);
    cx_free(ids);
}

/* ---- the allocator under concurrency ----------------------------------------- */

/* Allocate and free many blocks; keep every 4th for the main thread to
 * free (a block freed by another thread than its maker). */
#define HAMMER_N 20000

typedef struct {
    void **kept;
    int nkept;
    long live_thread;
    pthread_barrier_t *start;
} hammer;

static void *hammer_main(void *arg)
{
    hammer *h = arg;
    long live = cx_alloc_live_thread();
    pthread_barrier_wait(h->start);
    for (int k = 0; k < HAMMER_N; k++) {
        void *p = (k & 1) ? cx_malloc(16) : cx_calloc(2, 8);
        if (p && k % 4 == 0)
            h->kept[h->nkept++] = p;
        else
            cx_free(p);
    }
    h->live_thread = cx_alloc_live_thread() - live;
    return NULL;
}

/* Thread 0 forces failures on its own allocations (every allocation point
 * of building a scene, each must come back CX_ENOMEM with nothing of its
 * own leaked); meanwhile thread 1 solves, and none of its allocations may
 * fail. */
typedef struct {
    pthread_barrier_t *start;
    int points, bad_status, leaks, converged;
    outcome o;
} injector;

static void *inject_main(void *arg)
{
    injector *in = arg;
    cx_scene sc;
    char path[512];
    cx_diag d;
    pthread_barrier_wait(in->start);
    if (cx_scene_resolve("twoblocks", path, sizeof path, &d) || cx_scene_load(&sc, path, &d))
        return NULL;
    for (long n = 0; n < 100000; n++) {
        cx_problem *p = NULL;
        cx_session *s = NULL;
        long live = cx_alloc_live_thread();
        cx_alloc_fail_after(n);
        int st = cx_scene_build(&sc, 3, &p, NULL, &d);
        if (!st)
            st = cx_session_create(&s, &p, &d);
        cx_alloc_fail_after(-1);
        cx_session_destroy(&s);
        cx_problem_destroy(&p);
        if (cx_alloc_live_thread() != live)
            in->leaks++;
        if (!st) {
            in->converged = 1;   /* every allocation point passed */
            break;
        }
        in->points++;
        if (st != CX_ENOMEM)
            in->bad_status++;
    }
    return NULL;
}

static void *solve_main(void *arg)
{
    injector *in = arg;
    pthread_barrier_wait(in->start);
    for (int r = 0; r < 3; r++) {
        outcome_clear(&in->o);
        run_job(&jobs[0], &in->o);
        if (in->o.status)
            break;
    }
    return NULL;
}

static void test_alloc(void)
{
    long live = cx_alloc_live();

    /* counts from two threads, blocks freed by a third */
    pthread_barrier_t start;
    pthread_barrier_init(&start, NULL, 2);
    hammer h[2];
    pthread_t th[2];
    for (int t = 0; t < 2; t++) {
        h[t] = (hammer){malloc(sizeof(void *) * HAMMER_N), 0, 0, &start};
        CX_CHECK(pthread_create(&th[t], NULL, hammer_main, &h[t]) == 0);
    }
    for (int t = 0; t < 2; t++)
        pthread_join(th[t], NULL);
    pthread_barrier_destroy(&start);
    long kept = h[0].nkept + h[1].nkept;
    CX_CHECK(h[0].nkept == HAMMER_N / 4 && h[1].nkept == HAMMER_N / 4);
    CX_CHECK(h[0].live_thread == HAMMER_N / 4 && h[1].live_thread == HAMMER_N / 4);
    CX_CHECK(cx_alloc_live() == live + kept);   /* no update lost */
    long mine = cx_alloc_live_thread();
    for (int t = 0; t < 2; t++) {
        for (int k = 0; k < h[t].nkept; k++)
            cx_free(h[t].kept[k]);
        free(h[t].kept);
    }
    CX_CHECK(cx_alloc_live() == live);
    CX_CHECK(cx_alloc_live_thread() == mine - kept);   /* freed here, made there */

    /* failure injection is per thread */
    outcome ref;
    run_job(&jobs[0], &ref);
    CX_CHECK(ref.status == CX_OK);
    injector in;
    memset(&in, 0, sizeof in);
    pthread_barrier_init(&start, NULL, 2);
    in.start = &start;
    CX_CHECK(pthread_create(&th[0], NULL, inject_main, &in) == 0);
    CX_CHECK(pthread_create(&th[1], NULL, solve_main, &in) == 0);
    pthread_join(th[0], NULL);
    pthread_join(th[1], NULL);
    pthread_barrier_destroy(&start);
    fprintf(stderr, "alloc: %d failing allocation points on one thread beside a solve on another\n",
            in.points);
    CX_CHECK(in.converged && in.points > 20);
    CX_CHECK(in.bad_status == 0 && in.leaks == 0);
    check_same(&jobs[0], &in.o, &ref, "beside failure injection");
    outcome_clear(&in.o);
    outcome_clear(&ref);
    CX_CHECK(cx_alloc_live() == live);
}

/* ---- two images at once (built with the renderer) ----------------------------- */

#if CX_TEST_RENDER
/* OSMesa is not made for two threads drawing at once: render/glctx.c lets
 * one context exist at a time. Two threads render the same solution at
 * once, twice each; every file equals the one rendered alone. */
typedef struct {
    cx_result *r;                 /* its own: a result's stress cache is not shared */
    const cx_render_opts *o;
    char path[2][600];
    int status[2];
    pthread_barrier_t *start;
} painter;

static void *paint_main(void *arg)
{
    painter *pt = arg;
    pthread_barrier_wait(pt->start);
    for (int r = 0; r < 2; r++) {
        cx_diag d;
        pt->status[r] = cx_render_png(pt->r, pt->o, pt->path[r], NULL, &d);
        if (pt->status[r])
            fprintf(stderr, "render %s: %s\n", pt->path[r], d.msg);
    }
    return NULL;
}

static int same_file(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    int same = fa && fb, ca, cb;
    while (same && ((ca = fgetc(fa)) != EOF) + ((cb = fgetc(fb)) != EOF) > 0)
        same = ca == cb;
    if (fa)
        fclose(fa);
    if (fb)
        fclose(fb);
    return same;
}

static void test_render(void)
{
    char dir[] = "/tmp/cx-threads-XXXXXX", path[600];
    cx_diag d;
    cx_scene sc;
    cx_problem *p = NULL;
    cx_session *s = NULL;
    if (!mkdtemp(dir)) {
        CX_CHECK(0);
        return;
    }
    CX_CHECK_OK(cx_scene_resolve("hertz", path, sizeof path, &d));
    CX_CHECK_OK(cx_scene_load(&sc, path, &d));
    cx_friction_state fr;
    CX_CHECK_OK(cx_scene_build(&sc, 16, &p, &fr, &d));
    CX_CHECK_OK(cx_session_create(&s, &p, &d));
    CX_CHECK_OK(cx_session_set_friction(s, &fr, &d));
    CX_CHECK_OK(cx_session_set_method(s, cx_method_find("ssn-tresca"), NULL, NULL, &d));
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    cx_result *res[3] = {NULL, NULL, NULL};   /* alone, thread 0, thread 1 */
    for (int k = 0; k < 3; k++)
        CX_CHECK_OK(cx_result_from_session(&res[k], s, &sc, 16, &d));
    cx_render_opts o;
    cx_render_opts_default(&o);
    o.width = 320, o.height = 240;
    snprintf(path, sizeof path, "%s/alone.png", dir);
    int alone = cx_render_png(res[0], &o, path, NULL, &d);
    if (alone)
        fprintf(stderr, "render alone: %s\n", d.msg);
    CX_CHECK(alone == CX_OK);

    pthread_barrier_t start;
    pthread_barrier_init(&start, NULL, 2);
    painter pt[2];
    pthread_t th[2];
    for (int t = 0; t < 2; t++) {
        pt[t] = (painter){res[t + 1], &o, {"", ""}, {0, 0}, &start};
        for (int r = 0; r < 2; r++)
            snprintf(pt[t].path[r], sizeof pt[t].path[r], "%s/t%d-%d.png", dir, t, r);
        CX_CHECK(pthread_create(&th[t], NULL, paint_main, &pt[t]) == 0);
    }
    for (int t = 0; t < 2; t++)
        pthread_join(th[t], NULL);
    pthread_barrier_destroy(&start);
    for (int t = 0; t < 2; t++)
        for (int r = 0; r < 2; r++) {
            CX_CHECK(pt[t].status[r] == CX_OK);
            CX_CHECK(same_file(pt[t].path[r], path));
            remove(pt[t].path[r]);
        }
    remove(path);
    rmdir(dir);
    for (int k = 0; k < 3; k++)
        cx_result_destroy(&res[k]);
    cx_session_destroy(&s);
}
#endif

int main(void)
{
    test_loading();
    test_alloc();
    test_sessions();
#if CX_TEST_RENDER
    test_render();
#endif
    return check_finish("threads");
}
