/* The conformance harness (STYLE.md C14): every registered method that
 * supports a case must reach the case's kkt tolerance within its iteration
 * band, agree with the reference solution, balance the load, and keep its
 * counters consistent; a method that does not support a case must refuse it
 * at init with a reason. A new method is tested the moment it is
 * registered. The reference is ssn-tresca run to kkt < 1e-13, or the
 * case's own (pdas for the floating bodies of paper 003). */
#include "solve_fixture.h"
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
    const char *ref;   /* reference method (NULL: ssn-tresca) */
} method_case;

static const method_case cases[] = {
    {"hertz", 8, CX_FRICTION_NONE, 0, 1e-12, 2, 12, 1e-8, NULL},
    {"hertz", 16, CX_FRICTION_NONE, 0, 1e-12, 2, 12, 1e-8, NULL},
    {"hertz", 16, CX_FRICTION_TRESCA, 20, 1e-12, 2, 15, 1e-8, NULL},
    {"slider", 2, CX_FRICTION_TRESCA, 1.5, 1e-12, 2, 15, 1e-8, NULL},
    {"slider", 2, CX_FRICTION_NONE, 0, 1e-12, 1, 12, 1e-8, NULL},
    {"block3d", 2, CX_FRICTION_NONE, 0, 1e-12, 1, 12, 1e-8, NULL},
    /* paper 003: floating bodies, ssn-tresca refuses them; pdas is the reference */
    {"stackbond", 5, CX_FRICTION_NONE, 0, 1e-10, 2, 30, 1e-8, "pdas"},
    {"runningbond", 5, CX_FRICTION_NONE, 0, 1e-10, 2, 30, 1e-8, "pdas"},
    {"laminae", 5, CX_FRICTION_NONE, 0, 1e-10, 2, 30, 1e-8, "pdas"},
};

/* ||u - v||_K / ||v||_K */
static double energy_diff(const cx_problem *p, const double *u, const double *v)
{
    int n = p->n;
    double *e = malloc(sizeof(double) * (size_t)n), *Ke = malloc(sizeof(double) * (size_t)n);
    double *Kv = malloc(sizeof(double) * (size_t)n);
    for (int k = 0; k < n; k++)
        e[k] = u[k] - v[k];
    cx_csc_gemv(&p->K, 1.0, e, 0.0, Ke);
    cx_csc_gemv(&p->K, 1.0, v, 0.0, Kv);
    double num = sqrt(fabs(cx_vec_dot(n, e, Ke))), den = sqrt(fabs(cx_vec_dot(n, v, Kv)));
    free(e);
    free(Ke);
    free(Kv);
    return den > 0 ? num / den : num;
}

static void run_case(const method_case *c)
{
    cx_scene sc;
    cx_diag d;
    cx_session *s = fixture_session(c->scene, c->level, &sc);
    CX_CHECK_OK(cx_session_set_friction(s, c->law, c->value, &d));
    const cx_problem *p = cx_session_problem(s);

    /* the reference */
    cx_options o;
    cx_options_default(&o);
    o.tol = 1e-13;
    const char *ref = c->ref ? c->ref : "ssn-tresca";
    CX_CHECK_OK(cx_session_set_method(s, cx_method_find(ref), NULL, &o, &d));
    CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
    const cx_iterate *it = cx_session_iterate(s);
    CX_CHECK(it->reason > 0);
    double *uref = malloc(sizeof(double) * (size_t)p->n);
    memcpy(uref, it->u, sizeof(double) * (size_t)p->n);

    for (int k = 0; k < cx_method_count(); k++) {
        const cx_method *m = cx_method_at(k);
        o.tol = c->tol;
        int st = cx_session_set_method(s, m, NULL, &o, &d);
        if (cx_method_check(m, p, NULL) != CX_OK) {
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
        CX_CHECK(it->reason > 0);
        CX_CHECK_LE(it->kkt, c->tol);
        CX_CHECK_LE(energy_diff(p, it->u, uref), c->agree);
        if (strcmp(m->id, ref) == 0) {
            CX_CHECK(it->iter >= c->min_it && it->iter <= c->max_it);
            /* ssn-tresca: one factorisation for the session (cached, so 0
             * here), one expansion solve per iteration that changed the sets */
            if (!c->ref) {
                CX_CHECK(it->counters.factorizations == 0);
                CX_CHECK(it->counters.solves <= it->iter + 1);  /* + the condensation of f */
            }
        }
        CX_CHECK(it->nfree + it->ncontact + it->nstick + it->nslip == p->m);
        /* at most one factorisation per cached operator */
        CX_CHECK(cx_session_cache_counters(s)->factorizations <= cx_session_cache_size(s));
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
