/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The session's keyed operator cache: built once per key, counted in the
 * cache counters, freed with the session; a bad argument is not cached, a
 * matrix that cannot be factorised is (the failure, tried once). */
#include "check.h"
#include "solve_fixture.h"

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

int main(void)
{
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
