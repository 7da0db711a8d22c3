/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Shared by the solve tests: a scene's problem at a level, in a session. */
#ifndef CX_TEST_SOLVE_FIXTURE_H
#define CX_TEST_SOLVE_FIXTURE_H

#include "scene/scene.h"

#include <stdio.h>
#include <stdlib.h>

/* Load scene id, let edit change it (NULL: as it is) and build it at level
 * into a new session (aborts the test program on failure: nothing else can
 * be checked then). */
static inline cx_session *fixture_session_edited(const char *id, int level, cx_scene *sc,
                                                 void (*edit)(cx_scene *))
{
    char path[512];
    cx_diag d;
    cx_problem *p = NULL;
    cx_session *s = NULL;
    if (cx_scene_resolve(id, path, sizeof path, &d) || cx_scene_load(sc, path, &d)) {
        fprintf(stderr, "fixture %s: %s\n", id, d.msg);
        exit(2);
    }
    if (edit)
        edit(sc);
    cx_friction_state fr;
    if (cx_scene_build(sc, level, &p, &fr, &d) || cx_session_create(&s, &p, &d) ||
        cx_session_set_friction(s, &fr, &d)) {
        fprintf(stderr, "fixture %s level %d: %s\n", id, level, d.msg);
        exit(2);
    }
    return s;
}

static inline cx_session *fixture_session(const char *id, int level, cx_scene *sc)
{
    return fixture_session_edited(id, level, sc, NULL);
}

#endif
