/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The mesh view's geometry (meshview.c): the outline of the body (the
 * edges of its surface, from mesh/surface.c), the edges of one element,
 * and the automatic displacement scale. Drawing is in panels.c. */
#ifndef TUI_MESHVIEW_H
#define TUI_MESHVIEW_H

#include "tui/tui.h"

typedef struct tui_meshview {
    int *outline;          /* 2 noutline node pairs */
    int noutline;
    /* 3D: the feature edges of the surface (where it folds by more than
     * 30 degrees, or ends): the box of a brick, the rim of a half-ball;
     * what a dense wireframe of every surface edge hides */
    int *features;         /* 2 nfeatures node pairs */
    int nfeatures;
    int has_obstacle;      /* a rigid obstacle (not a second body) ... */
    cx_obstacle obstacle;  /* ... as the solver has it at the level */
} tui_meshview;

/* The outline and features of mesh (NULL: none) and the scene's obstacle
 * at the level (scene NULL: none). */
void tui_meshview_update(tui_meshview *v, const cx_mesh *mesh, const cx_scene *scene, int level);
void tui_meshview_clear(tui_meshview *v);
/* The segments of a 2D element's edges as node pairs (TRI6 edges split at
 * their mid nodes); returns their count (at most 6; 0 in 3D). */
int tui_meshview_elem_edges(const cx_mesh *mesh, int e, int seg[6][2]);

#endif
