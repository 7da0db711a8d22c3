/* SPDX-License-Identifier: GPL-3.0-or-later */
/* From a scene to a problem at a mesh level: mesh, assembly, supports,
 * loads and contact rows, then the problem over the free dofs. */
#include "scene/scene.h"

#include <stdarg.h>
#include <stdio.h>
#include <math.h>
#include <string.h>

/* ---- finite numbers: a NaN or Inf is refused where it appears, naming the
 * section that put it there (the loader's ranges make this a backstop) ---- */

static int build_finite(const double *x, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (!isfinite(x[k]))
            return 0;
    return 1;
}

#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static int build_overflow(const cx_scene *s, int line, cx_diag *d, const char *fmt, ...)
{
    char what[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    return cx_diag_set(d, CX_EINVAL, "%s:%d: %s (overflow: Inf or NaN; rescale the units)",
                       s->path, line, what);
}

static int build_mesh(const cx_scene *s, int level, cx_mesh **m, cx_diag *d)
{
    int cells[3];
    cx_scene_cells(s, level, cells);
    switch (s->generator) {
    case CX_GEN_RECTANGLE:
        return cx_mesh_rectangle(m, s->lo[0], s->lo[1], s->hi[0], s->hi[1], cells[0], cells[1],
                                 s->element, d);
    case CX_GEN_HERTZ:
        return cx_mesh_hertz(m, s->radius, cells[0], s->element, d);
    case CX_GEN_BRICK:
        return cx_mesh_brick(m, s->lo, s->hi, cells[0], cells[1], cells[2], s->element, d);
    case CX_GEN_TWOBLOCKS: {
        int lower[3];
        cx_scene_cells_lower(s, level, lower);
        return cx_mesh_twoblocks(m, s->lo[0], s->lo[1], s->interface, s->hi[0], s->hi[1], cells,
                                 lower, s->element, d);
    }
    case CX_GEN_MASONRY:
        return cx_mesh_masonry(m, s->bond, cells[0], d);
    }
    return cx_diag_set(d, CX_EINVAL, "%s: unknown generator", s->path);
}

static int build_boundary(const cx_scene *s, const cx_mesh *m, const char *name,
                          const cx_boundary **b, cx_diag *d)
{
    *b = cx_mesh_boundary(m, name);
    if (!*b)
        return cx_diag_set(d, CX_EINVAL, "%s: the mesh has no boundary '%s'", s->path, name);
    return CX_OK;
}

/* Masonry (paper 003): Signorini on the contact boundary against the
 * obstacle lowered by the settlement gap g = gap_h H (H = 1 / courses),
 * except where boundary "base" fixes the node, and the joint rows. */
static int build_masonry_contact(const cx_scene *s, int level, const cx_mesh *m,
                                 cx_contact_set *cs, cx_diag *d)
{
    const cx_boundary *settle, *base, *joints;
    CX_TRY(build_boundary(s, m, s->contact_boundary, &settle, d));
    CX_TRY(build_boundary(s, m, "base", &base, d));
    CX_TRY(build_boundary(s, m, "joints", &joints, d));
    cx_obstacle ob;
    cx_scene_obstacle(s, level, &ob);
    return cx_contact_masonry(cs, m, settle, base, joints, &ob, d);
}

void cx_scene_obstacle(const cx_scene *s, int level, cx_obstacle *ob)
{
    *ob = s->obstacle;
    if (s->generator != CX_GEN_MASONRY)
        return;
    int cells[3];
    cx_scene_cells(s, level > 0 ? level : s->level, cells);
    for (int k = 0; k < 2; k++)
        ob->point[k] -= s->gap_h / cells[0] * ob->normal[k];
}

int cx_scene_build(const cx_scene *s, int level, cx_problem **pp, cx_friction_state *fr,
                   cx_diag *d)
{
    cx_mesh *m = NULL;
    cx_material *mats = NULL;
    cx_dofmap map = {0};
    cx_contact_set cs = {0};
    cx_csc K = {0};
    double *f = NULL;
    const cx_boundary *b;
    int st;

    if (level <= 0)
        level = s->level;
    if (level > s->level_max)
        return cx_diag_set(d, CX_EINVAL, "level %d: scene '%s' allows levels 1 to %d",
                           level, s->id, s->level_max);
    if ((st = build_mesh(s, level, &m, d)))
        goto fail;
    cx_progress_step("assembling", (double)m->dim * m->nnodes);   /* the progress line of cli/ */
    if (!build_finite(m->x, (size_t)m->dim * (size_t)m->nnodes)) {
        st = build_overflow(s, s->line_mesh, d, "section [mesh]: the node coordinates");
        goto fail;
    }
    mats = CX_NEW(cx_material, m->nbodies);
    f = CX_NEW(double, m->dim * m->nnodes);
    if (!mats || !f) {
        st = cx_diag_set(d, CX_ENOMEM, "out of memory");
        goto fail;
    }
    for (int k = 0; k < m->nbodies; k++)
        mats[k] = s->mat;
    if ((st = cx_fem_assemble_stiffness(m, mats, &K, d)))
        goto fail;
    if (!build_finite(K.x, cx_csc_nnz(&K))) {
        st = build_overflow(s, s->line_material, d, "section [material]: E = %g gives a stiffness "
                            "matrix", s->mat.E);
        goto fail;
    }

    size_t nall = (size_t)m->dim * (size_t)m->nnodes;
    for (int k = 0; k < s->ntractions; k++) {
        if ((st = build_boundary(s, m, s->tractions[k].boundary, &b, d)) ||
            (st = cx_fem_add_traction(m, b, &s->tractions[k].t, f)))
            goto fail;
        if (!build_finite(f, nall)) {
            st = build_overflow(s, s->tractions[k].line, d, "section [traction %s]: the loads",
                                s->tractions[k].name);
            goto fail;
        }
    }
    if (s->body_force[0] != 0 || s->body_force[1] != 0 || s->body_force[2] != 0) {
        if ((st = cx_fem_add_body_force(m, s->body_force, f)))
            goto fail;
        if (!build_finite(f, nall)) {
            st = build_overflow(s, s->line_material, d, "section [material]: key 'body_force': "
                                "the loads");
            goto fail;
        }
    }

    if ((st = cx_dofmap_init(&map, m->dim * m->nnodes)))
        goto fail;
    for (int k = 0; k < s->nsupports; k++) {
        if ((st = build_boundary(s, m, s->supports[k].boundary, &b, d)))
            goto fail;
        for (int c = 0; c < m->dim; c++)
            if ((s->supports[k].comps >> c) & 1u)
                if ((st = cx_dofmap_fix(&map, m, b, c, s->supports[k].value[c])))
                    goto fail;
    }
    if ((st = cx_dofmap_finish(&map)))
        goto fail;

    if (s->generator == CX_GEN_MASONRY) {
        if ((st = build_masonry_contact(s, level, m, &cs, d)))
            goto fail;
    } else if ((st = build_boundary(s, m, s->contact_boundary, &b, d))) {
        goto fail;
    } else if (s->contact_master[0]) {
        const cx_boundary *master;
        if ((st = build_boundary(s, m, s->contact_master, &master, d)) ||
            (st = cx_contact_node_to_segment(&cs, m, b, master, &map, d)))
            goto fail;
    } else if ((st = cx_contact_from_obstacle(&cs, m, b, &s->obstacle, d))) {
        goto fail;
    }
    if (!build_finite(cs.gap, (size_t)cs.m) || !build_finite(cs.N.x, cs.N.nnz) ||
        !build_finite(cs.T.x, cs.T.nnz)) {
        st = build_overflow(s, s->line_contact, d, "section [contact]: the gaps or normals");
        goto fail;
    }
    /* contact points are the points with a free dof (doc/design.md §2: Dirichlet
     * dofs are eliminated; a clamped point's row would be empty) */
    if ((st = cx_contact_drop_clamped(&cs, &map)))
        goto fail;

    /* the scene's friction defaults (both values; the law) go beside the
     * problem, not into it: the session that solves it owns them */
    cx_friction_state defaults = {s->friction, s->slip_bound, s->F, NULL, NULL};
    if ((st = cx_problem_create(pp, &m, &mats, &map, &cs, &K, f, d)))
        goto fail;
    cx_problem *p = *pp;
    /* the prescribed displacements fold into f and g */
    if (!build_finite(p->f, (size_t)p->n) || !build_finite(p->g, (size_t)p->m)) {
        st = build_overflow(s, s->nsupports ? s->supports[0].line : s->line_contact, d,
                            "section [support %s]: the prescribed displacements against K",
                            s->nsupports ? s->supports[0].name : "");
        cx_problem_destroy(pp);
        goto fail;
    }
    if ((st = cx_friction_check(&defaults, 0, d))) {
        cx_problem_destroy(pp);
        goto fail;
    }
    if (fr)
        *fr = defaults;
    cx_csc_clear(&K);
    cx_free(f);
    return CX_OK;

fail:
    if (st == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "out of memory building scene '%s' at level %d", s->id, level);
    cx_mesh_destroy(&m);
    cx_free(mats);
    cx_dofmap_clear(&map);
    cx_contact_clear(&cs);
    cx_csc_clear(&K);
    cx_free(f);
    return st;
}
