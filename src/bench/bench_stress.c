/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini bench stress: every scene and method under a catalogue of
 * perturbations (bench_perturb.c). For each: converged or the reason,
 * iterations, kkt, the errors against the reference solution of the
 * perturbed problem, NaN/Inf. A failure is a row, never a crash or a hang:
 * every run has a time limit and the iteration limit. */
#include "bench/bench_perturb.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char stress_usage[] =
    "usage: signorini bench stress [SCENE...] [--level L] [--cases a,b,...] [options]\n"
    "\n"
    "Stability: each scene (default: all) and method under the perturbations\n"
    "below; a failure is a row with its reason. --cases keeps the cases whose id\n"
    "starts with one of the given prefixes.\n";

typedef enum {
    S_NOMINAL, S_UNITS, S_CONTRAST, S_NU, S_FRICTION, S_LOAD, S_GAP, S_DUP, S_JITTER, S_PARAM
} stress_kind;

static const struct {
    const char *id;
    stress_kind kind;
    double v;
    const char *what;
} stress_cases[] = {
    {"nominal", S_NOMINAL, 0, "the scene as it is"},
    {"units", S_UNITS, 0, "SI -> mm-MPa: kkt and iterations unchanged, results scale exactly"},
    {"contrast", S_CONTRAST, 1e6, "E ratio 1e6 between bodies (needs several bodies)"},
    {"nu-0.49", S_NU, 0.49, "nearly incompressible"},
    {"nu-0.4999", S_NU, 0.4999, "nearly incompressible"},
    {"F-1e-8", S_FRICTION, 1e-8, "Coulomb F (and the Tresca bound s F / F_scene)"},
    {"F-10", S_FRICTION, 10, "Coulomb F (and the Tresca bound s F / F_scene)"},
    {"load-1e-8", S_LOAD, 1e-8, "loads and prescribed displacements x 1e-8"},
    {"load-1e4", S_LOAD, 1e4, "loads and prescribed displacements x 1e4"},
    {"gap-1e-12", S_GAP, 1e-12, "initial gap + 1e-12 x body size"},
    {"gap-1e-8", S_GAP, 1e-8, "initial gap + 1e-8 x body size"},
    {"gap-1e-4", S_GAP, 1e-4, "initial gap + 1e-4 x body size"},
    {"gap-1", S_GAP, 1, "initial gap + the body size"},
    {"coincident", S_DUP, 0, "a contact point duplicated"},
    {"near-coincident", S_DUP, 1e-10, "a contact point duplicated, its gap + 1e-10 x body size"},
    {"jitter", S_JITTER, 0.05, "interior nodes moved by up to 5 % of h (fixed seed)"},
    {"param", S_PARAM, 1e5, "each real method parameter at default x 1e-5 and x 1e5 (in range)"},
};
#define STRESS_NCASES ((int)(sizeof stress_cases / sizeof stress_cases[0]))

static const char *const stress_cols[] = {
    "scene", "level", "case", "friction", "method", "converged", "reason", "iterations",
    "nominal_iterations", "active", "kkt", "err_u", "err_l", "nonfinite", "dkkt", "scale_err", "check",
    "message", NULL};

#define STRESS_MAX_METHODS 64

typedef struct {
    bench_common c;
    const char *scenes[32];
    int nscenes;
    int level;
    const char *cases;
} stress_args;

/* The nominal run of one method on one scene, for comparisons. */
typedef struct {
    int ran, iterations;
    double kkt;
    double *u, *lN, *lT;
} stress_nominal;

static const cx_opt stress_opts[] = {
    CX_OPT_ROW_LEVEL_HELP(stress_args, level, "mesh level of every scene (default: each scene's)"),
    {"cases", 0, CX_OPT_STRING, 0, 0, 0, NULL, "LIST", "case id prefixes (see the cases below)",
     offsetof(stress_args, cases), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

/* CX_OK, CX_OPT_HELP, CX_EINVAL (a malformed line) or the status of
 * bench_common_finish. */
static int stress_parse(int argc, char **argv, stress_args *a, cx_diag *d)
{
    memset(a, 0, sizeof *a);
    bench_common_default(&a->c, 1);
    int r = bench_parse(argc, argv, stress_opts, a, &a->c, a->scenes, 32, &a->nscenes, d);
    if (r)
        return r;
    return bench_common_finish(&a->c, d);
}

static int stress_selected(const stress_args *a, const char *id)
{
    if (!a->cases)
        return 1;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", a->cases);
    for (char *save = NULL, *p = strtok_r(buf, ",", &save); p; p = strtok_r(NULL, ",", &save))
        if (strncmp(id, p, strlen(p)) == 0)
            return 1;
    return 0;
}

/* What one row needs to say where it comes from. */
typedef struct {
    bench_table *t;
    const cx_scene *sc;
    int level;
    const char *case_id;
    cx_friction law;
} stress_row_ctx;

static int stress_row(const stress_row_ctx *x, const char *method)
{
    int r = bench_table_row(x->t);
    bench_set_str(x->t, r, "scene", "%s", x->sc->id);
    bench_set_int(x->t, r, "level", x->level);
    bench_set_str(x->t, r, "case", "%s", x->case_id);
    bench_set_str(x->t, r, "friction", "%s", cx_friction_name(x->law));
    bench_set_str(x->t, r, "method", "%s", method);
    return r;
}

static void stress_fill(bench_table *t, int r, const bench_result *res, const stress_nominal *nom)
{
    bench_set_result(t, r, res);
    if (!res->failed && nom && nom->ran)
        bench_set_int(t, r, "nominal_iterations", nom->iterations);
}

static double stress_maxabs(int n, const double *v, double scale)
{
    double m = 0;
    for (int k = 0; k < n; k++)
        m = fmax(m, fabs(scale * v[k]));
    return m;
}

/* The unit-scaling checks of one method: the same iterations, the same kkt
 * (it has no units) within 1e-12, and u, l scaled exactly (relative). */
static void stress_units_check(bench_table *t, int r, const cx_session *s, const stress_nominal *nom,
                               double L, double P)
{
    const cx_problem *p = cx_session_problem(s);
    cx_friction law = cx_session_friction(s)->law;
    const cx_iterate *it = cx_session_iterate(s);
    if (!nom->ran || it->iter == 0)
        return;
    double fs = P * pow(L, p->dim - 1);
    double du = 0, dl = 0;
    for (int k = 0; k < p->n; k++)
        du = fmax(du, fabs(it->u[k] - L * nom->u[k]));
    for (int k = 0; k < p->m; k++)
        dl = fmax(dl, fabs(it->lN[k] - fs * nom->lN[k]));
    for (int k = 0; law != CX_FRICTION_NONE && k < p->nt; k++)
        dl = fmax(dl, fabs(it->lT[k] - fs * nom->lT[k]));
    double nu = stress_maxabs(p->n, nom->u, L);
    double nl = fmax(stress_maxabs(p->m, nom->lN, fs),
                     law != CX_FRICTION_NONE ? stress_maxabs(p->nt, nom->lT, fs) : 0);
    double err = fmax(nu > 0 ? du / nu : du, nl > 0 ? dl / nl : dl);
    double dkkt = fabs(it->kkt - nom->kkt);
    bench_set_num(t, r, "dkkt", dkkt);
    bench_set_num(t, r, "scale_err", err);
    int ok = it->iter == nom->iterations && dkkt <= 1e-12 * fmax(1, nom->kkt) && err <= 1e-8;
    bench_set_str(t, r, "check", "%s", ok ? "ok" : "FAIL");
}

static void stress_nominal_keep(stress_nominal *nom, const cx_session *s)
{
    const cx_problem *p = cx_session_problem(s);
    const cx_iterate *it = cx_session_iterate(s);
    nom->ran = 1;
    nom->iterations = it->iter;
    nom->kkt = it->kkt;
    nom->u = malloc(sizeof(double) * ((size_t)p->n + 1));
    nom->lN = malloc(sizeof(double) * ((size_t)p->m + 1));
    nom->lT = malloc(sizeof(double) * ((size_t)p->nt + 1));
    if (!nom->u || !nom->lN || !nom->lT) {
        fputs("signorini bench stress: out of memory\n", stderr);
        exit(CX_EXIT_ERROR);
    }
    memcpy(nom->u, it->u, sizeof(double) * (size_t)p->n);
    memcpy(nom->lN, it->lN, sizeof(double) * (size_t)p->m);
    memcpy(nom->lT, it->lT, sizeof(double) * (size_t)p->nt);
}

static void stress_nominal_clear(stress_nominal *nom)
{
    free(nom->u);
    free(nom->lN);
    free(nom->lT);
    memset(nom, 0, sizeof *nom);
}

/* One case on one problem: build it, its reference, then every method.
 * methods[k] is run when it supports the problem, else a row says why. */
static void stress_case(stress_args *a, const stress_row_ctx *x, const bench_problem_spec *spec,
                        const cx_method *const *methods, int nm, stress_nominal *nominal,
                        int case_kind, int *done, int total)
{
    cx_diag d;
    cx_diag_clear(&d);
    cx_session *s = NULL;
    if (bench_session(spec, &s, NULL, &d)) {
        int r = stress_row(x, "-");
        bench_set_str(x->t, r, "converged", "n/a");
        bench_set_str(x->t, r, "reason", "%s", d.status == CX_EUNSUPPORTED ? "n/a" : "build failed");
        bench_set_str(x->t, r, "message", "%s", d.msg);
        *done += nm;
        return;
    }
    const cx_problem *cp = cx_session_problem(s);
    bench_ref ref;
    cx_diag rd;
    cx_diag_clear(&rd);
    int ref_ok = bench_ref_get(&a->c.refs, spec, cp, 10 * a->c.time_limit, &ref, &rd) == CX_OK;
    int rows = 0;
    for (int k = 0; k < nm && !bench_interrupted(); k++) {
        char label[128];
        snprintf(label, sizeof label, "%s %s %s", x->sc->id, x->case_id, methods[k]->id);
        bench_progress_case((*done)++, label);
        if (cx_method_check(methods[k], cp, spec->law, NULL) != CX_OK && case_kind != S_NOMINAL &&
            !a->c.methods)
            continue;   /* not asked for, and cannot: no row */
        cx_options opt;
        bench_common_options(&a->c, &opt);
        bench_result res;
        bench_run(s, methods[k], NULL, &opt, ref_ok ? &ref : NULL, &res);
        if (res.interrupted)
            break;
        int r = stress_row(x, methods[k]->id);
        /* methods[] is the nominal list except under the friction extremes */
        int same = case_kind != S_NOMINAL && case_kind != S_FRICTION;
        stress_fill(x->t, r, &res, same ? &nominal[k] : NULL);
        if (!ref_ok && !res.failed)
            bench_set_str(x->t, r, "message", "%s%sno reference: %s", res.msg, res.msg[0] ? "; " : "", rd.msg);
        rows++;
        if (case_kind == S_NOMINAL && !res.failed)
            stress_nominal_keep(&nominal[k], s);
        if (case_kind == S_UNITS && !res.failed)
            stress_units_check(x->t, r, s, &nominal[k], 1e3, 1e-6);
    }
    (void)total;
    if (rows == 0 && !bench_interrupted()) {
        int r = stress_row(x, "-");
        bench_set_str(x->t, r, "converged", "n/a");
        bench_set_str(x->t, r, "reason", "n/a");
        bench_set_str(x->t, r, "message", "no registered method supports %s friction in %dD",
                      cx_friction_name(spec->law), cp->dim);
    }
    bench_ref_clear(&ref);
    cx_session_destroy(&s);
}

/* Each real parameter of each method at default x 1e-5 and x 1e5 (clipped
 * to its range): ten decades. */
static void stress_params(stress_args *a, const stress_row_ctx *x, const bench_problem_spec *spec,
                          const cx_method *const *methods, int nm, stress_nominal *nominal)
{
    cx_diag d;
    cx_diag_clear(&d);
    cx_session *s = NULL;
    if (bench_session(spec, &s, NULL, &d))
        return;
    bench_ref ref;
    int ref_ok = bench_ref_get(&a->c.refs, spec, cx_session_problem(s), 10 * a->c.time_limit, &ref, &d) == CX_OK;
    for (int k = 0; k < nm && !bench_interrupted(); k++) {
        const cx_method *m = methods[k];
        for (int j = 0; m->params && m->params[j].key; j++) {
            const cx_param *q = &m->params[j];
            if (q->type != CX_PARAM_REAL || !(q->def != 0))
                continue;
            for (int side = -1; side <= 1; side += 2) {
                double v = q->def * pow(10.0, side * 5.0);
                v = fmin(fmax(v, q->min), q->max);
                cx_param_values pv;
                cx_param_default(&pv, m->params);
                char text[32];
                snprintf(text, sizeof text, "%g", v);
                if (cx_param_set(&pv, q->key, text, m->id, NULL))
                    continue;
                cx_options opt;
                bench_common_options(&a->c, &opt);
                bench_result res;
                bench_run(s, m, &pv, &opt, ref_ok ? &ref : NULL, &res);
                if (res.interrupted)
                    break;
                char cid[64];
                snprintf(cid, sizeof cid, "param %s=%s", q->key, text);
                stress_row_ctx y = *x;
                y.case_id = cid;
                int r = stress_row(&y, m->id);
                stress_fill(x->t, r, &res, &nominal[k]);
            }
        }
    }
    if (ref_ok)
        bench_ref_clear(&ref);
    cx_session_destroy(&s);
}

/* All the selected cases on one scene. */
static int stress_scene(stress_args *a, const char *id, bench_table *t, int *done, int total)
{
    cx_diag d;
    cx_diag_clear(&d);
    cx_scene sc;
    bench_problem_spec nominal_spec;
    if (bench_open(&a->c, id, a->level, &sc, &nominal_spec, &d))
        return bench_fail("bench stress", d.msg);
    cx_problem *p0 = NULL;
    const cx_method *methods[STRESS_MAX_METHODS];
    int nm = 0;
    int st = bench_build(&nominal_spec, &p0, NULL, &d);
    if (st == CX_OK)
        st = bench_methods(a->c.methods, p0, nominal_spec.law, methods, STRESS_MAX_METHODS, &nm,
                           &d);
    cx_problem_destroy(&p0);
    if (st != CX_OK && st != CX_EUNSUPPORTED)
        return bench_fail("bench stress", d.msg);
    if (st == CX_EUNSUPPORTED) {
        /* a scene no method can solve is a row, and the others go on */
        stress_row_ctx x = {t, &sc, a->level > 0 ? a->level : sc.level, "nominal", nominal_spec.law};
        int r = stress_row(&x, "-");
        bench_set_str(t, r, "converged", "n/a");
        bench_set_str(t, r, "reason", "n/a");
        bench_set_str(t, r, "message", "%s", d.msg);
        return CX_OK;
    }
    /* under Coulomb or Tresca extremes the methods of another law join */
    const cx_method *all[STRESS_MAX_METHODS];
    int nall = 0;
    for (int k = 0; k < cx_method_count() && nall < STRESS_MAX_METHODS; k++)
        all[nall++] = cx_method_at(k);
    stress_nominal nominal[STRESS_MAX_METHODS];
    memset(nominal, 0, sizeof nominal);
    stress_row_ctx x = {t, &sc, a->level > 0 ? a->level : sc.level, "", nominal_spec.law};

    for (int c = 0; c < STRESS_NCASES && !bench_interrupted(); c++) {
        if (!stress_selected(a, stress_cases[c].id) && stress_cases[c].kind != S_NOMINAL)
            continue;
        x.case_id = stress_cases[c].id;
        x.law = nominal_spec.law;
        cx_scene changed = sc;
        bench_problem_spec spec = nominal_spec;
        spec.scene = &changed;
        spec.variant = stress_cases[c].id;
        double v = stress_cases[c].v;
        perturb_jitter_arg jit = {&changed, v, 20261125};
        perturb_contrast_arg con = {&changed, v};
        switch (stress_cases[c].kind) {
        case S_NOMINAL:
            spec.variant = "";
            break;
        case S_UNITS:
            perturb_scene_units(&changed, 1e3, 1e-6);
            spec.value *= spec.law == CX_FRICTION_TRESCA ? 1e-6 : 1;
            break;
        case S_CONTRAST:
            spec.perturb = perturb_contrast;
            spec.perturb_arg = &con;
            break;
        case S_NU:
            changed.mat.nu = v;
            break;
        case S_LOAD:
            perturb_scene_loads(&changed, v);
            break;
        case S_GAP:
            spec.perturb = perturb_gap;
            spec.perturb_arg = &stress_cases[c].v;
            break;
        case S_DUP:
            spec.perturb = perturb_duplicate_contact;
            spec.perturb_arg = &stress_cases[c].v;
            break;
        case S_JITTER:
            spec.perturb = perturb_jitter;
            spec.perturb_arg = &jit;
            break;
        case S_PARAM:
            stress_params(a, &x, &nominal_spec, methods, nm, nominal);
            *done += nm;
            continue;
        case S_FRICTION: {
            /* Coulomb with F, then Tresca with the bound the scene's
             * (slip_bound, F) pair gives that F */
            bench_problem_spec sub = spec;
            char variant[64];
            sub.law = x.law = CX_FRICTION_COULOMB;
            sub.value = v;
            snprintf(variant, sizeof variant, "%s coulomb", stress_cases[c].id);
            sub.variant = variant;
            stress_case(a, &x, &sub, all, nall, nominal, S_FRICTION, done, total);
            sub.law = x.law = CX_FRICTION_TRESCA;
            sub.value = sc.F > 0 ? sc.slip_bound * v / sc.F : v;
            snprintf(variant, sizeof variant, "%s tresca", stress_cases[c].id);
            stress_case(a, &x, &sub, all, nall, nominal, S_FRICTION, done, total);
            continue;
        }
        }
        stress_case(a, &x, &spec, methods, nm, nominal, stress_cases[c].kind, done, total);
    }
    for (int k = 0; k < STRESS_MAX_METHODS; k++)
        stress_nominal_clear(&nominal[k]);
    return CX_OK;
}

int bench_stress(int argc, char **argv)
{
    cx_diag d;
    cx_diag_clear(&d);
    stress_args a;
    int parsed = stress_parse(argc, argv, &a, &d);
    if (parsed == CX_OPT_HELP) {
        bench_help(stress_usage, stress_opts, stdout);
        printf("\ncases:\n");
        for (int c = 0; c < STRESS_NCASES; c++)
            printf("  %-18s %s\n", stress_cases[c].id, stress_cases[c].what);
        return CX_EXIT_OK;
    }
    if (parsed)
        return bench_parse_fail("bench stress", parsed, d.msg);
    char (*ids)[CX_SCENE_NAMELEN] = NULL;
    if (a.nscenes == 0) {
        int count;
        if (cx_scene_list(&ids, &count, &d))
            return bench_fail("bench stress", d.msg);
        for (int k = 0; k < count && k < 32; k++)
            a.scenes[a.nscenes++] = ids[k];
    }
    bench_table t;
    bench_table_init(&t, stress_cols);
    bench_meta_machine(&t);
    bench_meta(&t, "benchmark", "stress; time limit %g s per run; iteration limit %d", a.c.time_limit,
               a.c.max_iter > 0 ? a.c.max_iter : 500);
    int ncases = 0;
    for (int c = 0; c < STRESS_NCASES; c++)
        ncases += stress_selected(&a, stress_cases[c].id) || stress_cases[c].kind == S_NOMINAL;
    int total = a.nscenes * ncases * cx_method_count(), done = 0, code = CX_EXIT_OK;
    bench_progress_start(total);
    for (int k = 0; k < a.nscenes && !bench_interrupted() && code == CX_EXIT_OK; k++) {
        cx_scene sc;
        if (cx_scene_open(a.scenes[k], &sc, &d) == CX_OK)
            bench_meta(&t, sc.id, "hash %016llx (%s)", (unsigned long long)bench_scene_hash(&sc), sc.path);
        code = stress_scene(&a, a.scenes[k], &t, &done, total);
    }
    bench_progress_end();
    cx_free(ids);
    int yes = 0, no = 0, na = 0, fails = 0, nonfinite = 0;
    for (int r = 0; r < t.nrows; r++) {
        const char *c = bench_get_str(&t, r, "converged");
        yes += strcmp(c, "yes") == 0;
        no += strcmp(c, "no") == 0;
        na += strcmp(c, "n/a") == 0;
        fails += strcmp(bench_get_str(&t, r, "check"), "FAIL") == 0;
        nonfinite += strcmp(bench_get_str(&t, r, "nonfinite"), "yes") == 0;
    }
    bench_meta(&t, "summary", "%d rows: %d converged, %d not converged (%d with NaN/Inf), %d n/a; "
               "%d failed unit-scaling checks", t.nrows, yes, no, nonfinite, na, fails);
    if (bench_interrupted())
        bench_meta(&t, "interrupted", "yes: %d rows done", t.nrows);
    if (code == CX_EXIT_OK && bench_output(&a.c, &t, &d))
        code = bench_fail("bench stress", d.msg);
    bench_table_clear(&t);
    return bench_interrupted() ? CX_EXIT_INTERRUPTED : code;
}
