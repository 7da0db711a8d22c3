/* The session's keyed operator cache: built once per key, counted in the
 * cache counters, freed with the session, failures not cached. */
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

    char longkey[CX_CACHE_KEYLEN + 1];
    memset(longkey, 'k', sizeof longkey - 1);
    longkey[CX_CACHE_KEYLEN] = '\0';
    CX_CHECK(cx_session_cache_get(s, longkey, build_vector, &two, destroy_vector, &e, &d) == CX_EINVAL);

    cx_session_destroy(&s);
    CX_CHECK(destroys == 2);
    return check_finish("solve_cache");
}
