/* SPDX-License-Identifier: GPL-3.0-or-later */
/* solve/: the friction state belongs to the session (issue 19, the
 * cx_problem split). The build gives the scene's defaults beside the
 * problem; a new session is frictionless; each setter changes one meaning
 * (a slip bound is never read as F); per-point values go in through the
 * setter and are copied; bad values change nothing; a refused law leaves
 * the state (per-point values included) as it was; a nested session shares
 * the parent's system, not a copy, and has a friction state of its own. */
#include "run_fixture.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static cx_session *slider_session(int level, cx_friction_state *fr)
{
    char path[512];
    cx_scene sc;
    cx_diag d;
    cx_problem *p = NULL;
    cx_session *s = NULL;
    CX_CHECK_OK(cx_scene_resolve("slider", path, sizeof path, &d));
    CX_CHECK_OK(cx_scene_load(&sc, path, &d));
    CX_CHECK_OK(cx_scene_build(&sc, level, &p, fr, &d));
    /* the scene file's values: Tresca, slip bound 1.5, F from the defaults */
    CX_CHECK(fr->law == CX_FRICTION_TRESCA && fr->slip_bound == sc.slip_bound && fr->F == sc.F);
    CX_CHECK(fr->s == NULL && fr->Fi == NULL);
    CX_CHECK_OK(cx_session_create(&s, &p, &d));
    CX_CHECK(p == NULL);
    return s;
}

static void check_setters(void)
{
    cx_diag d;
    cx_friction_state def;
    cx_session *s = slider_session(3, &def);
    const cx_problem *p = cx_session_problem(s);
    int m = p->m;
    CX_CHECK(m > 2);

    /* a new session is frictionless, with per-point values to read */
    const cx_friction_state *fr = cx_session_friction(s);
    CX_CHECK(fr->law == CX_FRICTION_NONE && fr->s && fr->Fi);

    /* the scene's defaults: s_i = bound x lumped weight, F_i = F */
    CX_CHECK_OK(cx_session_set_friction(s, &def, &d));
    fr = cx_session_friction(s);
    CX_CHECK(fr->law == CX_FRICTION_TRESCA && fr->slip_bound == def.slip_bound && fr->F == def.F);
    for (int i = 0; i < m; i++) {
        CX_CHECK_NEAR(fr->s[i], def.slip_bound * p->contact.weight[i], 1e-15, 0);
        CX_CHECK(fr->Fi[i] == def.F);
    }

    /* one value, one meaning: Coulomb's F leaves the slip bound alone */
    CX_CHECK_OK(cx_session_set_coulomb(s, 0.45, &d));
    CX_CHECK(fr->law == CX_FRICTION_COULOMB && fr->F == 0.45 && fr->slip_bound == def.slip_bound);
    CX_CHECK(fr->Fi[m - 1] == 0.45);
    CX_CHECK_OK(cx_session_set_tresca(s, 2.5, &d));
    CX_CHECK(fr->law == CX_FRICTION_TRESCA && fr->slip_bound == 2.5 && fr->F == 0.45);
    CX_CHECK_NEAR(fr->s[1], 2.5 * p->contact.weight[1], 1e-15, 0);

    /* bad values: CX_EINVAL, nothing changed */
    CX_CHECK(cx_session_set_coulomb(s, -1, &d) == CX_EINVAL);
    CX_CHECK(cx_session_set_tresca(s, NAN, &d) == CX_EINVAL);
    double *Fi = malloc(sizeof(double) * (size_t)m);
    for (int i = 0; i < m; i++)
        Fi[i] = 0.3 + 0.01 * i;
    Fi[m / 2] = -0.1;
    cx_friction_state bad = {CX_FRICTION_COULOMB, 1, 0.3, NULL, Fi};
    CX_CHECK(cx_session_set_friction(s, &bad, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "contact point") != NULL);
    CX_CHECK(fr->law == CX_FRICTION_TRESCA && fr->slip_bound == 2.5 && fr->F == 0.45);

    /* per-point F through the setter: copied, and read by the kkt error */
    Fi[m / 2] = 0.3;
    cx_friction_state per = {CX_FRICTION_COULOMB, def.slip_bound, 0.3, NULL, Fi};
    CX_CHECK_OK(cx_session_set_friction(s, &per, &d));
    CX_CHECK(fr->Fi != Fi && fr->Fi[m - 1] == Fi[m - 1]);
    Fi[0] = 99;   /* the caller's array is not the session's */
    CX_CHECK(fr->Fi[0] == 0.3);
    CX_CHECK_OK(fixture_run(s, "ssn-coulomb", "", 0, 1e-10, 200, &d));
    const cx_iterate *it = cx_session_iterate(s);
    CX_CHECK(it->reason == CX_CONVERGED_KKT);
    /* the same iterate under a uniform F = 0.3 is off the per-point solution
     * (some point slips with F_i != 0.3) unless no point slips */
    cx_friction_state uni = {CX_FRICTION_COULOMB, def.slip_bound, 0.3, NULL, NULL};
    double *work = calloc((size_t)(p->n + p->m + p->nt), sizeof(double));
    double *tmp = malloc(sizeof(double) * (size_t)m);
    for (int i = 0; i < m; i++)
        tmp[i] = 0.3;
    uni.Fi = tmp;
    double e_own = cx_kkt_error(p, cx_session_friction(s), it->u, it->lN, it->lT, work, NULL, NULL);
    double e_uni = cx_kkt_error(p, &uni, it->u, it->lN, it->lT, work, NULL, NULL);
    fprintf(stderr, "slider 3, per-point F: kkt %.2e under its own F_i, %.2e under F = 0.3; %d slip\n",
            e_own, e_uni, it->nslip);
    CX_CHECK_LE(e_own, 1e-10);
    if (it->nslip > 0)
        CX_CHECK(e_uni > 1e-6);

    /* a refused law keeps the old state, per-point values included */
    double *sb = malloc(sizeof(double) * (size_t)m);
    for (int i = 0; i < m; i++)
        sb[i] = 0.1 * (i + 1);
    cx_session_clear_method(s);   /* ssn-coulomb would refuse Tresca */
    CX_CHECK_OK(cx_session_set_slip_bounds(s, sb, &d));
    CX_CHECK_OK(fixture_run(s, "ssn-tresca-dual", "", 0, 1e-10, 500, &d));
    CX_CHECK(cx_session_set_coulomb(s, 0.3, &d) == CX_EUNSUPPORTED);
    CX_CHECK(fr->law == CX_FRICTION_TRESCA && cx_session_method(s) == cx_method_find("ssn-tresca-dual"));
    for (int i = 0; i < m; i++)
        CX_CHECK(fr->s[i] == sb[i]);

    free(sb);
    free(tmp);
    free(work);
    free(Fi);
    cx_session_destroy(&s);
}

static void check_nested(void)
{
    cx_diag d;
    cx_friction_state def;
    cx_session *s = slider_session(3, &def);
    CX_CHECK_OK(cx_session_set_friction(s, &def, &d));
    CX_CHECK_OK(cx_session_set_coulomb(s, 0.3, &d));
    cx_session *child = NULL;
    CX_CHECK_OK(cx_session_nested_create(&child, s, &d));
    /* the parent's system itself */
    CX_CHECK(cx_session_problem(child) == cx_session_problem(s));
    const cx_friction_state *cf = cx_session_friction(child), *pf = cx_session_friction(s);
    CX_CHECK(cf->law == CX_FRICTION_TRESCA && pf->law == CX_FRICTION_COULOMB);
    int m = cx_session_problem(s)->m;
    double *sb = malloc(sizeof(double) * (size_t)m);
    for (int i = 0; i < m; i++)
        sb[i] = 0.5;
    CX_CHECK_OK(cx_session_set_slip_bounds(child, sb, &d));
    CX_CHECK(cf->s[0] == 0.5 && cf->s != pf->s);
    CX_CHECK(pf->law == CX_FRICTION_COULOMB && pf->Fi[0] == 0.3);
    CX_CHECK_NEAR(pf->s[0], def.slip_bound * cx_session_problem(s)->contact.weight[0], 1e-15, 0);
    free(sb);
    cx_session_destroy(&child);
    /* the parent and its system outlive the child */
    CX_CHECK_OK(fixture_run(s, "ssn-coulomb", "", 0, 1e-10, 200, &d));
    CX_CHECK(cx_session_iterate(s)->reason == CX_CONVERGED_KKT);
    cx_session_destroy(&s);
}

int main(void)
{
    check_setters();
    check_nested();
    return check_finish("solve_friction");
}
