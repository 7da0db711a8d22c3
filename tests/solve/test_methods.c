/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The conformance harness (doc/style.md C14): every registered method that
 * supports a case must reach the case's kkt tolerance within its iteration
 * band, agree with the reference solution, balance the load, and keep its
 * counters consistent; a method that does not support a case must refuse it
 * at init with a reason. A new method is tested the moment it is
 * registered. The reference is ssn-tresca run to kkt < 1e-13 (ssn-coulomb
 * for Coulomb cases, or the case's own: pdas for the floating bodies of
 * paper 003). Methods run until the kkt tolerance (own_stop off:
 * the harness asserts the kkt error, whatever a method's own criterion).
 * A method may also refuse a case at init with CX_EUNSUPPORTED and a reason
 * the flags cannot express (the dual methods when K is singular). */
#include "run_fixture.h"
#include "check.h"

#include <math.h>
#include <string.h>

typedef struct {
    const char *scene;
    int level;
    cx_friction law;
    double value;      /* slip bound (Tresca) or F (Coulomb) */
    double tol;        /* kkt tolerance every method must reach */
    int min_it, max_it;/* iteration band for ssn-tresca */
    double agree;      /* energy-norm agreement with the reference */
    const char *ref;   /* reference method (NULL: ssn-tresca, ssn-coulomb for Coulomb) */
    const char *fails; /* a method known not to converge here: it must say so
                          (a negative reason), never crash or claim success */
    double gap_h;      /* masonry: the settlement gap as a fraction of H (0: the scene's) */
} method_case;

static double case_gap;
static void set_case_gap(cx_scene *sc) { sc->gap_h = case_gap; }

static const method_case cases[] = {
    {"hertz", 8, CX_FRICTION_NONE, 0, 1e-12, 2, 12, 1e-8, NULL, NULL, 0},
    {"hertz", 16, CX_FRICTION_NONE, 0, 1e-12, 2, 12, 1e-8, NULL, NULL, 0},
    {"hertz", 16, CX_FRICTION_TRESCA, 20, 1e-12, 2, 15, 1e-8, NULL, NULL, 0},
    {"slider", 2, CX_FRICTION_TRESCA, 1.5, 1e-12, 2, 15, 1e-8, NULL, NULL, 0},
    {"slider", 2, CX_FRICTION_NONE, 0, 1e-12, 1, 12, 1e-8, NULL, NULL, 0},
    {"block3d", 2, CX_FRICTION_NONE, 0, 1e-12, 1, 12, 1e-8, NULL, NULL, 0},
    {"twoblocks", 2, CX_FRICTION_TRESCA, 1.7e7, 1e-12, 2, 15, 1e-8, NULL, NULL, 0},
    {"twoblocks", 4, CX_FRICTION_TRESCA, 5e7, 1e-12, 2, 15, 1e-8, NULL, NULL, 0},
    {"twoblocks", 2, CX_FRICTION_NONE, 0, 1e-12, 1, 12, 1e-8, NULL, NULL, 0},
    {"twoblocks", 3, CX_FRICTION_COULOMB, 0.3, 1e-12, 1, 12, 1e-8, NULL, NULL, 0},
    {"halfball", 4, CX_FRICTION_NONE, 0, 1e-10, 1, 12, 1e-8, NULL, NULL, 0},
    {"prism", 1, CX_FRICTION_TRESCA, 1.5e8, 1e-12, 2, 15, 1e-8, NULL, NULL, 0},
    {"prism", 2, CX_FRICTION_TRESCA, 1.5e8, 1e-12, 2, 15, 1e-8, NULL, NULL, 0},
    {"prism", 2, CX_FRICTION_NONE, 0, 1e-12, 1, 12, 1e-8, NULL, NULL, 0},
    /* paper 003: floating bodies; pdas is the reference. On running bond
     * with the stress gap g = H/2 the solution is degenerate (bricks free to
     * slide on frictionless joints) and ssn-tresca's active sets cycle: it
     * must stop with a failure reason. */
    {"stackbond", 5, CX_FRICTION_NONE, 0, 1e-10, 2, 30, 1e-8, "pdas", NULL, 0},
    {"runningbond", 5, CX_FRICTION_NONE, 0, 1e-10, 2, 30, 1e-8, "pdas", NULL, 0},
    {"runningbond", 5, CX_FRICTION_NONE, 0, 1e-10, 2, 30, 1e-8, "pdas", "ssn-tresca", 0.5},
    {"laminae", 5, CX_FRICTION_NONE, 0, 1e-10, 2, 30, 1e-8, "pdas", NULL, 0},
};

/* Methods that cannot meet a case's tolerance as it stands: linearly
 * convergent ones (ubr-*: run past their own criterion, at the r that
 * converges fastest asymptotically) and ssn-c, whose answer is that of the
 * regularised problem (penetration O(lam / r): kkt ~ 1e-7 at r = 1e9 E). */
typedef struct {
    const char *id;
    const char *set;   /* parameters, "key=value" */
    double tol;        /* kkt tolerance instead of the case's (if larger) */
    int own_stop;      /* stop on the method's own criterion */
    int max_iter;
    double agree;      /* energy-norm agreement instead of the case's (if larger) */
} method_setting;

static const method_setting settings[] = {
    {"ubr-c", "r=1", 1e-10, 0, 20000, 1e-8},
    {"ubr-tf", "r=1", 1e-10, 0, 20000, 1e-8},
    {"ssn-c", "r=1e9", 2e-6, 1, 50, 1e-6},
};

static const method_setting *setting_of(const cx_method *m)
{
    for (size_t k = 0; k < sizeof settings / sizeof settings[0]; k++)
        if (strcmp(settings[k].id, m->id) == 0)
            return &settings[k];
    return NULL;
}

static void run_case(const method_case *c)
{
    cx_scene sc;
    cx_diag d;
    case_gap = c->gap_h;
    cx_session *s = fixture_session_edited(c->scene, c->level, &sc, c->gap_h > 0 ? set_case_gap : NULL);
    CX_CHECK_OK(c->law == CX_FRICTION_TRESCA    ? cx_session_set_tresca(s, c->value, &d)
                : c->law == CX_FRICTION_COULOMB ? cx_session_set_coulomb(s, c->value, &d)
                                                : cx_session_set_frictionless(s, &d));
    const cx_problem *p = cx_session_problem(s);

    /* the reference */
    cx_options o;
    cx_options_default(&o);
    o.tol = 1e-13;
    o.own_stop = c->ref != NULL;  /* pdas stops on its own exact criterion */
    const char *ref = c->ref ? c->ref : c->law == CX_FRICTION_COULOMB ? "ssn-coulomb" : "ssn-tresca";
    CX_CHECK_OK(cx_session_set_method(s, cx_method_find(ref), NULL, &o, &d));
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    const cx_iterate *it = cx_session_iterate(s);
    CX_CHECK(cx_reason_criterion_met(it->reason));
    double *uref = malloc(sizeof(double) * (size_t)p->n);
    memcpy(uref, it->u, sizeof(double) * (size_t)p->n);

    for (int k = 0; k < cx_method_count(); k++) {
        const cx_method *m = cx_method_at(k);
        const method_setting *ms = setting_of(m);
        cx_param_values pv;
        cx_param_default(&pv, m->params);
        cx_options om = o;
        om.tol = c->tol;
        double agree = c->agree;
        if (ms) {
            CX_CHECK_OK(cx_param_set_pair(&pv, ms->set, m->id, &d));
            om.tol = fmax(om.tol, ms->tol);
            om.own_stop = ms->own_stop;
            om.max_iter = ms->max_iter;
            om.stall_window = 0;
            agree = fmax(agree, ms->agree);
        }
        double cache_before = (double)cx_session_cache_counters(s)->factorizations;
        int st = cx_session_set_method(s, m, &pv, &om, &d);
        if (cx_method_check(m, p, cx_session_friction(s)->law, NULL) != CX_OK || st == CX_EUNSUPPORTED) {
            if (st == CX_EUNSUPPORTED)
                fprintf(stderr, "%s level %d %s: %s refused: %s\n", c->scene, c->level,
                        cx_friction_name(c->law), m->id, d.msg);
            CX_CHECK(st == CX_EUNSUPPORTED && d.msg[0] != '\0');
            continue;
        }
        CX_CHECK_OK(st);
        if (st)
            continue;
        CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
        it = cx_session_iterate(s);
        fprintf(stderr, "%s level %d %s: %s %d iterations, kkt %.2e, %ld solves\n", c->scene, c->level,
                cx_friction_name(c->law), m->id, it->iter, it->kkt, it->counters.solves);
        if (c->fails && strcmp(m->id, c->fails) == 0) {
            CX_CHECK(it->reason < 0);
            continue;
        }
        CX_CHECK(it->reason > 0);
        CX_CHECK_LE(it->kkt, om.tol);
        CX_CHECK_LE(fixture_energy_diff(p, it->u, uref), agree);
        if (strcmp(m->id, ref) == 0) {
            CX_CHECK(it->iter >= c->min_it && it->iter <= c->max_it);
            /* ssn-tresca: one factorisation for the session (cached, so 0
             * here), one expansion solve per iteration that changed the sets */
            if (strcmp(m->id, "ssn-tresca") == 0) {
                CX_CHECK(it->counters.factorizations == 0);
                CX_CHECK(it->counters.solves <= it->iter + 1);  /* + the condensation of f */
            }
        }
        CX_CHECK(it->nfree + it->ncontact + it->nstick + it->nslip == p->m);
        /* the reference's Schur complement, plus at most one cached
         * operator per method (ubr-*: K + rM, keyed by r) */
        CX_CHECK(cx_session_cache_counters(s)->factorizations - cache_before <= 1);
    }
    free(uref);
    cx_session_destroy(&s);
}

int main(void)
{
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++)
        run_case(&cases[k]);
    return check_finish("solve_methods");
}
