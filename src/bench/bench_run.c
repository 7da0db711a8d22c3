/* SPDX-License-Identifier: GPL-3.0-or-later */
/* One benchmark case: build the problem, run a method under a time limit,
 * measure its errors against the reference. A failure is described in the
 * result, never returned as an error of the benchmark. */
#include "bench/bench.h"

#include <malloc.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void bench_friction(const bench_problem_spec *spec, cx_friction_state *fr)
{
    /* spec->value is the value of spec->law; the other scalar stays the
     * scene's */
    const cx_scene *sc = spec->scene;
    *fr = (cx_friction_state){spec->law, sc->slip_bound, sc->F, NULL, NULL};
    if (spec->law == CX_FRICTION_COULOMB)
        fr->F = spec->value;
    else if (spec->law == CX_FRICTION_TRESCA)
        fr->slip_bound = spec->value;
}

int bench_build(const bench_problem_spec *spec, cx_problem **p, double *t_assemble, cx_diag *d)
{
    double t0 = cx_clock_now();
    CX_TRY(cx_scene_build(spec->scene, spec->level, p, NULL, d));
    cx_friction_state fr;
    bench_friction(spec, &fr);
    int st = cx_friction_check(&fr, 0, d);
    if (st == CX_OK && spec->perturb)
        st = spec->perturb(*p, spec->perturb_arg, d);
    if (st != CX_OK) {
        cx_problem_destroy(p);
        return st;
    }
    if (t_assemble)
        *t_assemble = cx_clock_now() - t0;
    return CX_OK;
}

int bench_session(const bench_problem_spec *spec, cx_session **s, double *t_assemble, cx_diag *d)
{
    cx_problem *p = NULL;
    *s = NULL;
    CX_TRY(bench_build(spec, &p, t_assemble, d));
    int st = cx_session_create(s, &p, d);
    cx_problem_destroy(&p);
    if (st != CX_OK)
        return st;
    /* the friction state goes to the session; per point it is expanded
     * from the scalars over the problem's contact points, a point
     * duplicated by a perturbation included */
    cx_friction_state fr;
    bench_friction(spec, &fr);
    if ((st = cx_session_set_friction(*s, &fr, d)) != CX_OK)
        cx_session_destroy(s);
    return st;
}

/* sqrt(e' K e) */
static double run_energy(const cx_problem *p, const double *e, double *work)
{
    cx_csc_gemv(&p->K, 1.0, e, 0.0, work);
    double q = cx_vec_dot(p->n, e, work);
    return sqrt(q > 0 ? q : 0);
}

void bench_errors(const cx_problem *p, cx_friction law, const bench_ref *ref, const double *u,
                  const double *lN, const double *lT, double *err_u, double *err_l)
{
    *err_u = *err_l = NAN;
    if (!ref || ref->n != p->n || ref->m != p->m)
        return;
    double *e = malloc(sizeof(double) * 2 * (size_t)p->n);
    if (!e)
        return;
    for (int k = 0; k < p->n; k++)
        e[k] = u[k] - ref->u[k];
    double eu = run_energy(p, e, e + p->n);
    free(e);
    double el = 0;
    for (int i = 0; i < p->m; i++)
        el += (lN[i] - ref->lN[i]) * (lN[i] - ref->lN[i]);
    for (int i = 0; law != CX_FRICTION_NONE && i < p->nt; i++)
        el += (lT[i] - ref->lT[i]) * (lT[i] - ref->lT[i]);
    el = sqrt(el);
    *err_u = ref->uK > 0 ? eu / ref->uK : eu;
    *err_l = ref->lnorm > 0 ? el / ref->lnorm : el;
}

/* Bytes of heap in use (glibc): small blocks plus mmapped ones. The
 * factorisations (CHOLMOD, LAPACK workspaces) allocate here too. */
static double run_heap_mb(void)
{
    struct mallinfo2 mi = mallinfo2();
    return (double)(mi.uordblks + mi.hblkhd) / 1048576.0;
}

typedef struct {
    double base, peak;
} run_watch;

static int run_observe(void *ctx, const cx_session *s, const cx_iterate *it)
{
    run_watch *w = ctx;
    w->peak = fmax(w->peak, run_heap_mb() - w->base);
    return bench_observer(NULL, s, it);
}

void bench_run(cx_session *s, const cx_method *m, const cx_param_values *pv,
               const cx_options *opt, const bench_ref *ref, bench_result *r)
{
    memset(r, 0, sizeof *r);
    r->kkt = r->err_u = r->err_l = r->t_setup = r->t_solve = NAN;
    cx_diag d;
    cx_diag_clear(&d);
    const cx_counters before = *cx_session_cache_counters(s);
    run_watch w = {run_heap_mb(), 0};
    int st = cx_session_set_method(s, m, pv, opt, &d);
    w.peak = fmax(w.peak, run_heap_mb() - w.base);
    if (st == CX_OK)
        st = bench_solve_watched(s, run_observe, &w, &d);
    r->heap_mb = w.peak;
    const cx_iterate *it = cx_session_iterate(s);
    if (st != CX_OK) {
        r->failed = 1;
        snprintf(r->msg, sizeof r->msg, "%s", cx_diag_msg(&d, st));
        r->work = *cx_session_cache_counters(s);
        r->work.factorizations -= before.factorizations;
        return;
    }
    const cx_problem *p = cx_session_problem(s);
    r->interrupted = it->reason == CX_ITERATING;
    r->reason = it->reason;
    r->iterations = it->iter;
    r->active = it->ncontact + it->nstick + it->nslip;
    r->kkt = it->kkt;
    r->t_setup = it->init_time;
    r->t_solve = it->time - it->init_time;
    r->work = it->counters;
    r->nonfinite = it->reason == CX_DIVERGED_NAN || !cx_vec_finite(p->n, it->u) ||
                   !cx_vec_finite(p->m, it->lN) || !cx_vec_finite(p->nt, it->lT);
    /* the outcome's sentence (solve/'s one table of words) for every run
     * that did not converge */
    if (it->reason != CX_CONVERGED_KKT)
        cx_session_outcome(s, r->msg, sizeof r->msg);
    else
        r->msg[0] = '\0';
    if (!r->nonfinite && it->iter > 0)
        bench_errors(p, cx_session_friction(s)->law, ref, it->u, it->lN, it->lT, &r->err_u,
                     &r->err_l);
}

void bench_set_result(bench_table *t, int r, const bench_result *res)
{
    if (res->failed) {
        bench_set_str(t, r, "converged", "n/a");
        bench_set_str(t, r, "reason", "%s", cx_reason_id(CX_REFUSED));
        bench_set_str(t, r, "message", "%s", res->msg);
        return;
    }
    bench_set_str(t, r, "converged", "%s", res->reason > 0 ? "yes" : "no");
    bench_set_str(t, r, "reason", "%s", cx_reason_id(res->reason));
    bench_set_int(t, r, "iterations", res->iterations);
    bench_set_int(t, r, "active", res->active);
    bench_set_num(t, r, "kkt", res->kkt);
    bench_set_num(t, r, "err_u", res->err_u);
    bench_set_num(t, r, "err_l", res->err_l);
    bench_set_str(t, r, "nonfinite", "%s", res->nonfinite ? "yes" : "no");
    if (res->msg[0])
        bench_set_str(t, r, "message", "%s", res->msg);
}

int bench_methods(const char *list, const cx_problem *p, cx_friction law, const cx_method **out,
                  int max, int *count, cx_diag *d)
{
    *count = 0;
    if (!list) {
        for (int k = 0; k < cx_method_count() && *count < max; k++)
            if (cx_method_check(cx_method_at(k), p, law, NULL) == CX_OK)
                out[(*count)++] = cx_method_at(k);
        if (*count == 0)
            return cx_diag_set(d, CX_EUNSUPPORTED,
                               "no registered method supports %s friction in %dD%s (see 'signorini list')",
                               cx_friction_name(law), p->dim,
                               p->mesh && p->mesh->nbodies > 1 ? " with several bodies" : "");
        return CX_OK;
    }
    char buf[512];
    snprintf(buf, sizeof buf, "%s", list);
    for (char *save = NULL, *id = strtok_r(buf, ",", &save); id; id = strtok_r(NULL, ",", &save)) {
        const cx_method *m = cx_method_find(id);
        if (!m)
            return cx_diag_set(d, CX_EINVAL, "--methods: unknown method '%s' (see 'signorini list')", id);
        if (*count < max)
            out[(*count)++] = m;
    }
    return CX_OK;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_median(double *v, int n)
{
    if (n <= 0)
        return NAN;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int bench_baseline(const cx_problem *p, int n, double *seconds, cx_diag *d)
{
    double t[BENCH_MAX_REPEAT];
    n = n < 1 ? 1 : n > BENCH_MAX_REPEAT ? BENCH_MAX_REPEAT : n;
    for (int k = 0; k < n; k++)
        CX_TRY(cx_problem_baseline(p, &t[k], d));
    *seconds = bench_median(t, n);
    return CX_OK;
}

void bench_run_paired(const bench_problem_spec *spec, const cx_method *m, const cx_param_values *pv,
                      const cx_options *opt, const bench_ref *ref, int repeat, bench_result *res,
                      bench_paired *out)
{
    double time[BENCH_MAX_REPEAT], ratio[BENCH_MAX_REPEAT], setup[BENCH_MAX_REPEAT],
        solve[BENCH_MAX_REPEAT], base[BENCH_MAX_REPEAT], assembly[BENCH_MAX_REPEAT],
        aratio[BENCH_MAX_REPEAT], sratio[BENCH_MAX_REPEAT], eratio[BENCH_MAX_REPEAT];
    int n = 0;
    memset(res, 0, sizeof *res);
    memset(out, 0, sizeof *out);
    for (int rep = 0; rep < repeat && rep < BENCH_MAX_REPEAT && !bench_interrupted(); rep++) {
        cx_session *s = NULL;
        cx_diag d;
        cx_diag_clear(&d);
        double ta = NAN, tb = NAN;
        if (bench_session(spec, &s, &ta, &d)) {
            memset(res, 0, sizeof *res);
            res->failed = 1;
            snprintf(res->msg, sizeof res->msg, "%s", d.msg);
            break;
        }
        /* the baseline of this very problem, just before the run: the
         * ratio is robust to the load of a shared machine drifting during
         * the benchmark */
        cx_problem_baseline(cx_session_problem(s), &tb, NULL);
        bench_run(s, m, pv, opt, ref, res);
        cx_session_destroy(&s);
        out->peak_mb = fmax(out->peak_mb, res->heap_mb);
        if (res->failed || res->interrupted)
            break;
        setup[n] = res->t_setup;
        solve[n] = res->t_solve;
        time[n] = res->t_setup + res->t_solve;
        ratio[n] = time[n] / tb;
        base[n] = tb;
        assembly[n] = ta;
        aratio[n] = ta / tb;
        sratio[n] = setup[n] / tb;
        eratio[n] = (ta + time[n]) / tb;
        n++;
    }
    /* stopped by Ctrl-C before the first run: not a result either */
    if (!res->failed && n == 0)
        res->interrupted = 1;
    out->runs = n;
    out->time = bench_median(time, n);
    out->ratio = bench_median(ratio, n);
    out->setup = bench_median(setup, n);
    out->solve = bench_median(solve, n);
    out->baseline = bench_median(base, n);
    out->assembly = bench_median(assembly, n);
    out->assembly_ratio = bench_median(aratio, n);
    out->setup_ratio = bench_median(sratio, n);
    out->end_ratio = bench_median(eratio, n);
}
