/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Shared by the render tests in C (test_image.c, test_figures.c): a scene
 * solved by its first method, and an image drawn to a file and read back. */
#ifndef CX_TEST_RENDER_FIXTURE_H
#define CX_TEST_RENDER_FIXTURE_H

#include <stdio.h>
#include <stdlib.h>

#include "pngread.h"
#include "render/render.h"
#include "scene/scene.h"

/* Scene id loaded into sc, built at level and solved on a new session *s
 * by the scene's first method (max_iter > 0: that limit). Any error ends
 * the test (exit 2): what follows needs the solution. */
static inline void fixture_solve_scene(cx_scene *sc, cx_session **s, const char *id, int level, int max_iter)
{
    char path[512];
    cx_diag d;
    cx_problem *p = NULL;
    cx_friction_state fr;
    *s = NULL;
    int rc = cx_scene_resolve(id, path, sizeof path, &d) || cx_scene_load(sc, path, &d) ||
             cx_scene_build(sc, level, &p, &fr, &d) || cx_session_create(s, &p, &d) ||
             cx_session_set_friction(*s, &fr, &d) ||
             cx_session_set_method(*s, cx_method_find(sc->methods[0]), NULL, NULL, &d);
    if (!rc && max_iter > 0) {
        cx_options opt = *cx_session_options(*s);
        opt.max_iter = max_iter;
        cx_session_set_options(*s, &opt);
    }
    if (rc || cx_solver_solve(*s, NULL, NULL, &d)) {
        fprintf(stderr, "%s level %d: %s\n", id, level, d.msg);
        exit(2);
    }
}

/* r drawn with o into the PNG at path (its timing in t, which may be
 * NULL) and read back into img: 0, else non-zero with the error on
 * stderr. */
static inline int fixture_render_read(cx_result *r, const cx_render_opts *o, const char *path, test_png *img,
                                      cx_render_timing *t)
{
    cx_diag d;
    cx_diag_clear(&d);
    if (cx_render_png(r, o, path, t, &d) != CX_OK) {
        fprintf(stderr, "render %s: %s\n", cx_field_name(o->field), d.msg);
        return -1;
    }
    return test_png_read(img, path);
}

#endif
