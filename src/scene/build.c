/* SPDX-License-Identifier: GPL-3.0-or-later */
/* From a scene to a problem at a mesh level: mesh, assembly, supports,
 * loads and contact rows, then the problem over the free dofs. */
#include "scene/scene.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <math.h>
#include <string.h>

/* ---- finite numbers: a NaN or Inf is refused where it appears, naming the
 * section that put it there (the loader's ranges make this a backstop) ---- */

static int build_finite(const double *x, size_t n)
{
    /* x - x is +0 (all bits clear) for a finite x and NaN otherwise: the
     * bits or'ed over blocks of a fixed length, without a branch per entry,
     * which the compiler vectorises (K has millions of entries) */
    enum { BLOCK = 256 };
    size_t k = 0;
    for (; k + BLOCK <= n; k += BLOCK) {
        uint64_t bad = 0;
        for (int q = 0; q < BLOCK; q++) {
            double z = x[k + q] - x[k + q];
            uint64_t u;
            memcpy(&u, &z, sizeof u);
            bad |= u;
        }
        if (bad)
            return 0;
    }
    for (; k < n; k++)
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

/* ---- Gmsh meshes: the groups the scene names, materials per region,
 * pressure, point forces and body force per region ---- */

static const char *build_ref_what(cx_scene_ref_kind k)
{
    return k == CX_REF_BOUNDARY ? "a boundary" : k == CX_REF_REGION ? "a region" : "a point";
}

static int build_ref_dim(const cx_scene *s, cx_scene_ref_kind k)
{
    return k == CX_REF_BOUNDARY ? s->dim - 1 : k == CX_REF_REGION ? s->dim : 0;
}

/* Every group the scene names exists in the file with the right dimension. */
static int build_file_refs(const cx_scene *s, const cx_mesh *m, const cx_mesh_groups *g,
                           cx_diag *d)
{
    for (int r = 0; r < s->nrefs; r++) {
        const cx_scene_ref *ref = &s->refs[r];
        const cx_mesh_group *grp = cx_mesh_group_find(g, ref->name);
        int want = build_ref_dim(s, ref->kind);
        if (!grp) {
            char have[256] = "";
            for (int k = 0; k < g->n && strlen(have) < 200; k++)
                snprintf(have + strlen(have), sizeof have - strlen(have), "%s%s (%dD)",
                         k ? ", " : "", g->g[k].name, g->g[k].dim);
            return cx_diag_set(d, CX_EINVAL, "%s:%d: key '%s': no physical group '%s' in %s "
                               "(it has: %s)", s->path, ref->line, ref->key, ref->name,
                               s->mesh_file_key, have[0] ? have : "no named groups");
        }
        if (grp->dim != want)
            return cx_diag_set(d, CX_EINVAL, "%s:%d: key '%s': physical group '%s' of %s has "
                               "dimension %d; %s needs dimension %d", s->path, ref->line,
                               ref->key, ref->name, s->mesh_file_key, grp->dim,
                               build_ref_what(ref->kind), want);
        if (ref->kind == CX_REF_BOUNDARY && !cx_mesh_boundary(m, ref->name))
            return cx_diag_set(d, CX_EINVAL, "%s:%d: key '%s': physical group '%s' of %s holds "
                               "no facets of the mesh", s->path, ref->line, ref->key, ref->name,
                               s->mesh_file_key);
    }
    return CX_OK;
}

/* The material of each element: a region's [material NAME] where the
 * region holds the element, else [material]. A body may be split between
 * materials (a bimaterial block, a layered ring): the mesh gets a
 * material id per element, section k of [material NAME] id k and
 * [material] id nmaterials; mats has nmaterials + 1 entries. An element
 * in no region takes [material], or where there is none the first
 * [material NAME] (load.c takes it as the default); one in two regions of
 * different materials is refused. */
static int build_file_materials(const cx_scene *s, cx_mesh *m, const cx_mesh_groups *g,
                                cx_material **mats, cx_diag *d)
{
    int nm = s->nmaterials, *id = CX_NEW(int, (size_t)m->nelems + 1);
    cx_material *tab = CX_NEW(cx_material, (size_t)nm + 1);
    if (!id || !tab) {
        cx_free(id);
        cx_free(tab);
        return CX_ENOMEM;
    }
    for (int e = 0; e < m->nelems; e++)
        id[e] = -1;
    for (int k = 0; k < nm; k++)
        tab[k] = s->materials[k].mat;
    tab[nm] = s->mat;
    int st = CX_OK;
    for (int k = 0; k < nm && st == CX_OK; k++) {
        const cx_mesh_group *grp = cx_mesh_group_find(g, s->materials[k].region);
        for (int q = 0; grp && q < grp->count; q++) {
            int e = grp->items[q], o = id[e];
            if (o >= 0 && o != k) {
                st = cx_diag_set(d, CX_EINVAL, "%s:%d: section [material %s]: region '%s' and "
                                 "region '%s' ([material %s]) overlap (element %d is in both)",
                                 s->path, s->materials[k].line, s->materials[k].name,
                                 s->materials[k].region, s->materials[o].region,
                                 s->materials[o].name, e + 1);
                break;
            }
            id[e] = k;
        }
    }
    /* no unnamed [material]: the loader took the first region's line for it */
    int rest = nm > 0 && s->line_material == s->materials[0].line ? 0 : nm;
    for (int e = 0; e < m->nelems; e++)
        if (id[e] < 0)
            id[e] = rest;
    if (st != CX_OK) {
        cx_free(id);
        cx_free(tab);
        return st;
    }
    cx_free(m->mat);
    m->mat = id;
    m->nmats = nm + 1;
    cx_free(*mats);
    *mats = tab;
    return CX_OK;
}

static int build_file_loads(const cx_scene *s, const cx_mesh *m, const cx_mesh_groups *g,
                            double *f, cx_diag *d)
{
    int dim = m->dim;
    for (int k = 0; k < s->npressures; k++) {
        const cx_boundary *b = cx_mesh_boundary(m, s->pressures[k].boundary);
        if (!b)
            return cx_diag_set(d, CX_EINVAL, "%s:%d: section [pressure %s]: the mesh has no "
                               "boundary '%s'", s->path, s->pressures[k].line,
                               s->pressures[k].name, s->pressures[k].boundary);
        if (cx_fem_add_pressure(m, b, s->pressures[k].p, f))
            return cx_diag_set(d, CX_EINVAL, "%s:%d: section [pressure %s]: a facet of '%s' has "
                               "no length or area", s->path, s->pressures[k].line,
                               s->pressures[k].name, s->pressures[k].boundary);
    }
    for (int k = 0; k < s->nforces; k++) {
        const cx_mesh_group *grp = g ? cx_mesh_group_find(g, s->forces[k].point) : NULL;
        if (!grp || grp->count < 1)
            return cx_diag_set(d, CX_EINVAL, "%s:%d: section [force %s]: no nodes in point '%s'",
                               s->path, s->forces[k].line, s->forces[k].name, s->forces[k].point);
        for (int q = 0; q < grp->count; q++)
            for (int c = 0; c < dim; c++)
                f[dim * grp->items[q] + c] += s->forces[k].F[c] / grp->count;
    }
    for (int k = 0; g && k < s->nmaterials; k++) {
        const double *bf = s->materials[k].body_force;
        const cx_mesh_group *grp = g ? cx_mesh_group_find(g, s->materials[k].region) : NULL;
        if (!grp || (bf[0] == 0 && bf[1] == 0 && bf[2] == 0))
            continue;
        if (cx_fem_add_body_force_on(m, grp->items, grp->count, bf, f))
            return cx_diag_set(d, CX_EINVAL, "%s:%d: section [material %s]: key 'body_force': a "
                               "degenerate element", s->path, s->materials[k].line,
                               s->materials[k].name);
    }
    return CX_OK;
}

/* A node is a point of one contact only: two rows on one node (the end
 * of two boundaries meeting at a corner) leave the methods that pair
 * rows with nodes nothing to stand on. */
static int build_contacts_distinct(const cx_scene *s, const cx_mesh *m, const cx_contact_set *cs,
                                   const int *start, cx_diag *d)
{
    if (s->ncontacts < 2)
        return CX_OK;
    int *owner = CX_NEW(int, m->nnodes);
    if (!owner)
        return CX_ENOMEM;
    for (int k = 0; k < m->nnodes; k++)
        owner[k] = -1;
    int st = CX_OK;
    for (int k = 0; k < s->ncontacts && st == CX_OK; k++)
        for (int i = start[k]; i < start[k + 1]; i++) {
            int node = cs->node[i];
            if (owner[node] >= 0 && owner[node] != k) {
                const cx_scene_contact *a = &s->contacts[owner[node]], *b = &s->contacts[k];
                char at[96];
                const double *x = m->x + m->dim * node;
                if (m->dim == 3)
                    snprintf(at, sizeof at, "(%g, %g, %g)", x[0], x[1], x[2]);
                else
                    snprintf(at, sizeof at, "(%g, %g)", x[0], x[1]);
                st = cx_diag_set(d, CX_EINVAL, "%s:%d: [contact %s]: node %d at %s is also a point "
                                 "of [contact %s] (boundaries '%s' and '%s' meet): a node may be "
                                 "a point of one contact only", s->path, b->line, b->name,
                                 node + 1, at, a->name, a->boundary, b->boundary);
                break;
            }
            owner[node] = k;
        }
    cx_free(owner);
    return st;
}

/* The scene's contacts one by one, appended in their order, each with its
 * friction values when they differ. */
static int build_contacts(const cx_scene *s, const cx_mesh *m, const cx_dofmap *map,
                          cx_contact_set *cs, cx_diag *d)
{
    int start[CX_SCENE_MAX_LOADS + 1], differ = 0, st;
    memset(cs, 0, sizeof *cs);
    int ncontacts = s->ncontacts > 0 ? s->ncontacts : 1;
    for (int k = 0; k < ncontacts; k++) {
        /* the first contact from the scalars, which a caller may have edited */
        cx_scene_contact first = {0};
        if (k == 0) {
            if (s->ncontacts > 0)
                first = s->contacts[0];
            memcpy(first.boundary, s->contact_boundary, sizeof first.boundary);
            memcpy(first.master, s->contact_master, sizeof first.master);
            first.obstacle = s->obstacle;
            first.F = s->F;
            first.slip_bound = s->slip_bound;
            first.line = s->line_contact;
        }
        const cx_scene_contact *c = k == 0 ? &first : &s->contacts[k];
        const cx_boundary *b, *master;
        cx_contact_set one = {0};
        start[k] = cs->m;
        differ |= c->F != s->F || c->slip_bound != s->slip_bound;
        b = cx_mesh_boundary(m, c->boundary);
        master = c->master[0] ? cx_mesh_boundary(m, c->master) : NULL;
        if (!b || (c->master[0] && !master))
            return cx_diag_set(d, CX_EINVAL, "%s:%d: the mesh has no boundary '%s'", s->path,
                               c->line, !b ? c->boundary : c->master);
        st = master ? cx_contact_node_to_segment(&one, m, b, master, map, d)
                    : cx_contact_from_obstacle(&one, m, b, &c->obstacle, d);
        if (st == CX_OK && (st = cx_contact_append(cs, &one)) == CX_EINVAL)
            st = cx_diag_set(d, CX_EINVAL, "%s:%d: contact sets of different sizes", s->path,
                             c->line);
        cx_contact_clear(&one);
        if (st) {
            if (st != CX_ENOMEM && s->ncontacts > 1)
                cx_diag_prefix(d, "%s:%d: [contact%s%s]", s->path, c->line, c->name[0] ? " " : "",
                               c->name);
            return st;
        }
    }
    start[ncontacts] = cs->m;
    CX_TRY(build_contacts_distinct(s, m, cs, start, d));
    for (int k = 0; differ && k < ncontacts; k++)
        CX_TRY(cx_contact_set_friction(cs, start[k], start[k + 1], k ? s->contacts[k].F : s->F,
                                       k ? s->contacts[k].slip_bound : s->slip_bound));
    return CX_OK;
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
    case CX_GEN_FILE:
        break;   /* build_file_mesh */
    }
    return cx_diag_set(d, CX_EINVAL, "%s: unknown generator", s->path);
}

/* A Gmsh mesh at a level (size h0 / level) and its groups, checked
 * against the names the scene gives. */
static int build_file_mesh(const cx_scene *s, int level, cx_mesh **m, cx_mesh_groups *g,
                           cx_diag *d)
{
    cx_gmsh_options opt = {level, s->mesh_size, s->file_element};
    int st = cx_mesh_read_gmsh(m, g, s->mesh_file, &opt, d);
    if (st == CX_ENOMEM)
        return st;
    if (st)
        return cx_diag_prefix(d, "%s:%d: key 'file'", s->path, s->line_file);
    if ((*m)->dim != s->dim) {
        st = cx_diag_set(d, CX_EINVAL, "%s:%d: key 'file': %s is a %dD mesh (the scene has dim %d)",
                         s->path, s->line_file, s->mesh_file_key, (*m)->dim, s->dim);
    } else {
        st = build_file_refs(s, *m, g, d);
    }
    if (st) {
        cx_mesh_destroy(m);
        cx_mesh_groups_clear(g);
    }
    return st;
}

/* Without the serial K (CX_SCENE_BUILD_NO_K), what the problem takes from
 * it, element by element: the prescribed values' part of the load, fd -=
 * K(free, prescribed) value, and K's diagonal over the free dofs (diag,
 * nfree), whose largest entry is the stiffness scale. Each entry is summed
 * over the elements in their order, with the same element matrices, as
 * cx_fem_assemble_free sums it, so both are K's bitwise. */
static int build_load_diag(const cx_mesh *m, const cx_material *mats, const cx_dofmap *map, double *fd,
                           double *diag, cx_diag *d)
{
    int dim = m->dim, npe = m->npe, nd = dim * npe, ns = cx_fem_nstress(dim), nmat = cx_mesh_nmats(m);
    double *D = CX_NEW(double, (size_t)ns * ns * (size_t)(nmat > 0 ? nmat : 1));
    double *Ke = CX_NEW(double, (size_t)nd * nd), *xe = CX_NEW(double, nd);
    int st = CX_OK;
    if (!D || !Ke || !xe) {
        st = CX_ENOMEM;
        goto done;
    }
    for (int k = 0; k < nmat; k++)
        cx_fem_elasticity(&mats[k], D + (size_t)ns * ns * k);
    for (int e = 0; e < m->nelems; e++) {
        const int *c = m->conn + (size_t)npe * e;
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++)
                xe[dim * a + i] = m->x[(size_t)dim * c[a] + i];
        if (cx_fem_element_stiffness(m->etype, xe, D + (size_t)ns * ns * cx_mesh_elem_mat(m, e), Ke)) {
            st = cx_diag_set(d, CX_ENUMERIC, "element %d (%s) is degenerate or inverted", e,
                             cx_elem_name(m->etype));
            goto done;
        }
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++) {
                int r = map->free_of[dim * c[a] + i];
                if (r >= 0)
                    diag[r] += Ke[(size_t)nd * (dim * a + i) + dim * a + i];
            }
        /* column (b j) prescribed to v: -v times it into the free rows,
         * (b, j) outer as the assembly's scatter has them */
        for (int b = 0; b < npe; b++)
            for (int j = 0; j < dim; j++) {
                int col = dim * c[b] + j;
                double v = map->value[col];
                if (map->free_of[col] >= 0 || v == 0)
                    continue;
                for (int a = 0; a < npe; a++)
                    for (int i = 0; i < dim; i++) {
                        int r = map->free_of[dim * c[a] + i];
                        if (r >= 0)
                            fd[r] -= Ke[(size_t)nd * (dim * b + j) + dim * a + i] * v;
                    }
            }
    }
done:
    cx_free(D);
    cx_free(Ke);
    cx_free(xe);
    return st;
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

/* masonry's plane lowered by the settlement gap g = gap_h H */
static void scene_obstacle_settle(const cx_scene *s, int level, cx_obstacle *ob)
{
    if (s->generator != CX_GEN_MASONRY)
        return;
    int cells[3];
    cx_scene_cells(s, level > 0 ? level : s->level, cells);
    for (int k = 0; k < 2; k++)
        ob->point[k] -= s->gap_h / cells[0] * ob->normal[k];
}

void cx_scene_obstacle(const cx_scene *s, int level, cx_obstacle *ob)
{
    *ob = s->obstacle;
    scene_obstacle_settle(s, level, ob);
}

int cx_scene_obstacles(const cx_scene *s, int level, cx_obstacle *ob, int max)
{
    int n = 0;
    for (int i = 0; i < s->ncontacts && n < max; i++)
        if (!s->contacts[i].master[0]) {
            ob[n] = s->contacts[i].obstacle;
            scene_obstacle_settle(s, level, &ob[n]);
            n++;
        }
    return n;
}

int cx_scene_build(const cx_scene *s, int level, cx_problem **pp, cx_friction_state *fr,
                   cx_diag *d)
{
    return cx_scene_build_flags(s, level, 0, pp, fr, d);
}

int cx_scene_build_flags(const cx_scene *s, int level, unsigned flags, cx_problem **pp,
                         cx_friction_state *fr, cx_diag *d)
{
    int no_k = (flags & CX_SCENE_BUILD_NO_K) != 0;
    double *diag = NULL;   /* no_k: K's diagonal over the free dofs */
    cx_mesh *m = NULL;
    cx_mesh_groups groups = {0};
    cx_material *mats = NULL;
    cx_dofmap map = {0};
    cx_contact_set cs = {0};
    cx_csc K = {0};
    double *f = NULL, *fd = NULL;
    const cx_boundary *b;
    int st;

    if (level <= 0)
        level = s->level;
    if (level > s->level_max)
        return cx_diag_set(d, CX_EINVAL, "level %d: scene '%s' allows levels 1 to %d",
                           level, s->id, s->level_max);
    if ((st = s->generator == CX_GEN_FILE ? build_file_mesh(s, level, &m, &groups, d)
                                          : build_mesh(s, level, &m, d)))
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
    if (s->generator == CX_GEN_FILE && s->nmaterials > 0 &&
        (st = build_file_materials(s, m, &groups, &mats, d)))
        goto fail;
    /* the supports first: K is assembled over the free dofs only, the
     * prescribed values' part of the load into fd (cx_fem_assemble_free) */
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
    if (!(fd = CX_NEW(double, map.nfree > 0 ? map.nfree : 1))) {
        st = cx_diag_set(d, CX_ENOMEM, "out of memory");
        goto fail;
    }
    if (no_k) {
        /* an empty K over the free dofs for cx_problem_create to take;
         * the load's prescribed part and the stiffness scale from the
         * elements */
        K.nrow = K.ncol = map.nfree;
        K.p = CX_NEW(int, (size_t)map.nfree + 1);
        diag = CX_NEW(double, map.nfree > 0 ? map.nfree : 1);
        if (!K.p || !diag) {
            st = cx_diag_set(d, CX_ENOMEM, "out of memory");
            goto fail;
        }
        if ((st = build_load_diag(m, mats, &map, fd, diag, d)))
            goto fail;
    } else if ((st = cx_fem_assemble_free(m, mats, &map, &K, fd, d))) {
        goto fail;
    }
    if (no_k ? !build_finite(diag, (size_t)map.nfree) || !build_finite(fd, (size_t)map.nfree)
             : !build_finite(K.x, cx_csc_nnz(&K))) {
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
    if (s->generator == CX_GEN_FILE || s->npressures > 0) {
        if ((st = build_file_loads(s, m, s->generator == CX_GEN_FILE ? &groups : NULL, f, d)))
            goto fail;
        if (!build_finite(f, nall)) {
            st = build_overflow(s, s->line_mesh, d, "the pressures, forces or body forces");
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

    if (s->generator == CX_GEN_MASONRY) {
        if ((st = build_masonry_contact(s, level, m, &cs, d)))
            goto fail;
    } else if ((st = build_contacts(s, m, &map, &cs, d))) {
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
    for (int r = 0; r < p->n; r++)
        p->f[r] += fd[r];
    if (no_k) {   /* cx_problem_create's scale, from the diagonal it had not */
        for (int r = 0; r < p->n; r++)
            if (diag[r] > p->kscale)
                p->kscale = diag[r];
        cx_csc_clear(&p->K);
    }
    defaults.Fi = p->contact.Fpt;   /* several contacts: their own values */
    defaults.s = p->contact.spt;
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
    cx_free(fd);
    cx_free(diag);
    cx_mesh_groups_clear(&groups);
    return CX_OK;

fail:
    if (st == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "out of memory building scene '%s' at level %d", s->id, level);
    cx_mesh_groups_clear(&groups);
    cx_mesh_destroy(&m);
    cx_free(mats);
    cx_dofmap_clear(&map);
    cx_contact_clear(&cs);
    cx_csc_clear(&K);
    cx_free(f);
    cx_free(fd);
    cx_free(diag);
    return st;
}
