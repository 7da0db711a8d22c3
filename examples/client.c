/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A client of libsignorini: load a scene, build its problem, open a
 * session, solve with a method and print the kkt error and the number of
 * iterations. Build it against an installed signorini with
 *   cc client.c $(pkg-config --cflags --libs signorini)
 * usage: client [SCENE [METHOD [LEVEL]]]   (default: hertz ssn-tresca 0) */
#include <signorini.h>

#include <stdio.h>
#include <stdlib.h>

static int fail(const char *what, const cx_diag *d, int status)
{
    fprintf(stderr, "client: %s: %s\n", what, cx_diag_msg(d, status));
    return 1;
}

int main(int argc, char **argv)
{
    const char *scene = argc > 1 ? argv[1] : "hertz";
    const char *method = argc > 2 ? argv[2] : "ssn-tresca";
    int level = argc > 3 ? atoi(argv[3]) : 0;
    cx_diag d;
    cx_scene sc;
    int st;

    if ((st = cx_scene_open(scene, &sc, &d)))
        return fail("scene", &d, st);
    /* the problem at the level, and the scene's friction law and values */
    cx_problem *p = NULL;
    cx_friction_state fr;
    if ((st = cx_scene_build(&sc, level, &p, &fr, &d)))
        return fail("build", &d, st);

    const cx_method *m = cx_method_find(method);
    if (!m) {
        fprintf(stderr, "client: unknown method '%s'\n", method);
        cx_problem_destroy(&p);
        return 1;
    }
    cx_param_values pv;
    cx_param_default(&pv, m->params);
    cx_options opt;
    cx_options_default(&opt);

    /* the session takes the problem (p is NULL afterwards) */
    cx_session *s = NULL;
    if ((st = cx_session_create(&s, &p, &d))) {
        cx_problem_destroy(&p);
        return fail("session", &d, st);
    }
    int code = 1;
    if ((st = cx_session_set_friction(s, &fr, &d)) || (st = cx_session_set_method(s, m, &pv, &opt, &d))) {
        fail("method", &d, st);
        goto done;
    }
    if ((st = cx_solver_solve(s, NULL, NULL, &d))) {
        fail("solve", &d, st);
        goto done;
    }
    const cx_iterate *it = cx_session_iterate(s);
    const cx_problem *cp = cx_session_problem(s);
    printf("scene %s method %s: %d dofs, %d contact points\n", sc.id, m->id, cp->n, cp->m);
    printf("kkt %.3e iterations %d reason %s\n", it->kkt, it->iter, cx_reason_id(it->reason));
    code = cx_reason_criterion_met(it->reason) ? 0 : 3;
done:
    cx_session_destroy(&s);
    return code;
}
