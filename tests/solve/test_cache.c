/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The session's keyed operator cache: built once per key, counted in the
 * cache counters, freed with the session; a bad argument is not cached, a
 * matrix that cannot be factorised is (the failure, tried once). */
#include "check.h"
#include "solve_fixture.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int builds, destroys;

static int build_vector(void **obj, const cx_problem *p, const void *arg, cx_counters *cnt,
                        cx_diag *d)
{
    const double *scale = arg;
    if (*scale < 0)
        return cx_diag_set(d, CX_EINVAL, "negative scale");
    double *v = CX_NEW(double, p->n);
    if (!v)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    for (int i = 0; i < p->n; i++)
        v[i] = *scale;
    cnt->factorizations++;   /* pretend it was a factorisation */
    builds++;
    *obj = v;
    return CX_OK;
}

static int singular_builds;

/* A factorisation that fails on the matrix itself (CX_ENUMERIC). */
static int build_singular(void **obj, const cx_problem *p, const void *arg, cx_counters *cnt,
                          cx_diag *d)
{
    (void)obj;
    (void)p;
    (void)arg;
    cnt->factorizations++;
    singular_builds++;
    return cx_diag_set(d, CX_ENUMERIC, "not positive definite at column 7");
}

static void destroy_vector(void *obj)
{
    destroys++;
    cx_free(obj);
}

/* sqrt(e' K e) for e = u - v, and sqrt(u' K u). */
static double energy_diff(const cx_problem *p, const double *u, const double *v, double *unorm)
{
    double *e = malloc(sizeof(double) * (size_t)p->n), *Ke = malloc(sizeof(double) * (size_t)p->n);
    for (int i = 0; i < p->n; i++)
        e[i] = u[i] - v[i];
    cx_csc_gemv(&p->K, 1.0, e, 0.0, Ke);
    double de = 0, du = 0;
    for (int i = 0; i < p->n; i++)
        de += e[i] * Ke[i];
    cx_csc_gemv(&p->K, 1.0, u, 0.0, Ke);
    for (int i = 0; i < p->n; i++)
        du += u[i] * Ke[i];
    free(e);
    free(Ke);
    *unorm = sqrt(du);
    return sqrt(fmax(de, 0));
}

/* The two reductions of a problem (session.c), in 3D and in 2D alike: a
 * frictionless run condenses onto the normal dofs only (a third of the
 * contact dofs on block3d's flat obstacle, half on hertz's), a run with
 * friction onto all of them, each
 * built once and kept beside the other, so that switching the law back
 * and forth factorises nothing already factorised; a frictionless run
 * after one with friction takes the full reduction that is there. Both
 * give the same solution to 1e-10 in the energy norm. */
static void test_normal_reduction(const char *scene, int level, int dim)
{
    cx_scene sc;
    cx_diag d;
    const cx_method *ssn = cx_method_find("ssn-tresca");
    cx_session *a = fixture_session(scene, level, &sc);
    const cx_problem *p = cx_session_problem(a);
    CX_CHECK(p->dim == dim && cx_session_friction(a)->law == CX_FRICTION_NONE);
    const int *dofs = NULL;
    int nd = 0;
    cx_schur *S = NULL;
    CX_CHECK_OK(cx_session_schur_normal(a, NULL, NULL, &dofs, &nd, &d));   /* which dofs only */
    /* one per point; fewer than the contact dofs (some tangential ones
     * are held by the supports) */
    CX_CHECK(nd == p->m && nd < p->nc && cx_session_cache_counters(a)->factorizations == 0);
    CX_CHECK(cx_session_schur_built(a) == NULL);

    /* frictionless first: the normal reduction, one factorisation */
    CX_CHECK_OK(cx_session_set_method(a, ssn, NULL, NULL, &d));
    CX_CHECK_OK(cx_solver_solve(a, NULL, NULL, &d));
    const cx_iterate *it = cx_session_iterate(a);
    CX_CHECK(it->reason > 0 && !it->u_partial);
    CX_CHECK_LE(it->kkt, 1e-10);
    CX_CHECK(cx_session_cache_counters(a)->factorizations == 1);
    CX_CHECK_OK(cx_session_schur_normal(a, &S, NULL, &dofs, &nd, &d));
    CX_CHECK(cx_schur_size(S) == nd && nd == p->m);
    double *u_normal = malloc(sizeof(double) * (size_t)p->n);
    memcpy(u_normal, it->u, sizeof(double) * (size_t)p->n);

    /* Tresca: the full reduction, built once beside it */
    CX_CHECK_OK(cx_session_set_tresca(a, 1e-3, &d));
    CX_CHECK_OK(cx_solver_solve(a, NULL, NULL, &d));
    CX_CHECK(cx_session_iterate(a)->reason > 0);
    CX_CHECK(cx_session_cache_counters(a)->factorizations == 2);
    CX_CHECK(cx_session_cache_size(a) == 2);
    /* back and forth: nothing more is factorised */
    CX_CHECK_OK(cx_session_set_frictionless(a, &d));
    CX_CHECK_OK(cx_solver_solve(a, NULL, NULL, &d));
    CX_CHECK(cx_session_iterate(a)->reason > 0);
    double un = 0;
    CX_CHECK_LE(energy_diff(p, cx_session_iterate(a)->u, u_normal, &un), 1e-12 * un);
    CX_CHECK_OK(cx_session_set_tresca(a, 2e-3, &d));
    CX_CHECK_OK(cx_solver_solve(a, NULL, NULL, &d));
    CX_CHECK(cx_session_cache_counters(a)->factorizations == 2);
    /* ssstar (3D only; pdas in 2D), frictionless, on the same normal
     * reduction: the same solution */
    CX_CHECK_OK(cx_session_set_frictionless(a, &d));
    CX_CHECK_OK(cx_session_set_method(a, cx_method_find(dim == 3 ? "ssstar" : "pdas"), NULL, NULL, &d));
    CX_CHECK_OK(cx_solver_solve(a, NULL, NULL, &d));
    CX_CHECK(cx_session_iterate(a)->reason > 0 && !cx_session_iterate(a)->u_partial);
    CX_CHECK(cx_session_cache_counters(a)->factorizations == 2);
    CX_CHECK_LE(energy_diff(p, cx_session_iterate(a)->u, u_normal, &un), 1e-10 * un);

    /* friction first, then frictionless: the full reduction serves, and
     * gives the normal one's solution */
    cx_scene sc2;
    cx_session *b = fixture_session(scene, level, &sc2);
    CX_CHECK_OK(cx_session_set_tresca(b, 1e-3, &d));   /* before the method: its init builds */
    CX_CHECK_OK(cx_session_set_method(b, ssn, NULL, NULL, &d));
    CX_CHECK_OK(cx_solver_solve(b, NULL, NULL, &d));
    CX_CHECK_OK(cx_session_set_frictionless(b, &d));
    CX_CHECK_OK(cx_session_schur_normal(b, NULL, NULL, &dofs, &nd, &d));
    CX_CHECK(nd == p->nc);   /* the full one is there: it serves */
    CX_CHECK_OK(cx_solver_solve(b, NULL, NULL, &d));
    it = cx_session_iterate(b);
    CX_CHECK(it->reason > 0 && !it->u_partial);
    CX_CHECK(cx_session_cache_counters(b)->factorizations == 1);
    double e = energy_diff(p, u_normal, it->u, &un);
    fprintf(stderr, "%s %d: normal-only against full reduction, energy norm %.3g of %.3g\n", scene, level, e, un);
    CX_CHECK(un > 0);
    CX_CHECK_LE(e, 1e-10 * un);

    free(u_normal);
    cx_session_destroy(&a);
    cx_session_destroy(&b);
}

int main(void)
{
    test_normal_reduction("block3d", 3, 3);
    test_normal_reduction("hertz", 16, 2);
    cx_scene sc;
    cx_session *s = fixture_session("hertz", 4, &sc);
    cx_diag d;
    void *a = NULL, *b = NULL, *c = NULL;
    double two = 2, three = 3, bad = -1;

    CX_CHECK(cx_session_cache_size(s) == 0);
    CX_CHECK_OK(cx_session_cache_get(s, "vec scale=2", build_vector, &two, destroy_vector, &a, &d));
    CX_CHECK_OK(cx_session_cache_get(s, "vec scale=2", build_vector, &two, destroy_vector, &b, &d));
    CX_CHECK(a == b);
    CX_CHECK(builds == 1);
    CX_CHECK(((double *)a)[0] == 2);
    CX_CHECK_OK(cx_session_cache_get(s, "vec scale=3", build_vector, &three, destroy_vector, &c, &d));
    CX_CHECK(c != a && builds == 2);
    CX_CHECK(cx_session_cache_size(s) == 2);
    CX_CHECK(cx_session_cache_counters(s)->factorizations == 2);

    /* a failed build is reported and not cached */
    void *e = NULL;
    CX_CHECK(cx_session_cache_get(s, "vec scale=-1", build_vector, &bad, destroy_vector, &e, &d) == CX_EINVAL);
    CX_CHECK(strcmp(d.msg, "negative scale") == 0);
    CX_CHECK(cx_session_cache_size(s) == 2);

    /* a matrix that cannot be factorised: tried once, the failure kept */
    long f0 = cx_session_cache_counters(s)->factorizations;
    for (int k = 0; k < 3; k++) {
        cx_diag_clear(&d);
        CX_CHECK(cx_session_cache_get(s, "singular", build_singular, NULL, NULL, &e, &d) == CX_ENUMERIC);
        CX_CHECK(strcmp(d.msg, "not positive definite at column 7") == 0);
    }
    CX_CHECK(singular_builds == 1);
    CX_CHECK(cx_session_cache_counters(s)->factorizations == f0 + 1);
    CX_CHECK(cx_session_cache_get(s, "singular", build_singular, NULL, NULL, &e, NULL) == CX_ENUMERIC);

    char longkey[CX_CACHE_KEYLEN + 1];
    memset(longkey, 'k', sizeof longkey - 1);
    longkey[CX_CACHE_KEYLEN] = '\0';
    CX_CHECK(cx_session_cache_get(s, longkey, build_vector, &two, destroy_vector, &e, &d) == CX_EINVAL);

    cx_session_destroy(&s);
    CX_CHECK(destroys == 2);
    return check_finish("solve_cache");
}
