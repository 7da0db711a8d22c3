/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cx_scene_build_flags with CX_SCENE_BUILD_NO_K against cx_scene_build:
 * the same problem but K, bitwise. The load (with the prescribed
 * displacements' part, which the build without K sums from the element
 * matrices: slider, halfball and coated prescribe non-zero values), the
 * stiffness scale (K's largest diagonal entry, from the elements too),
 * the gaps, contact rows, dof map, mesh and friction defaults; and K
 * itself empty in the one, whole in the other. Scenes of every generator
 * and element: hertz (triangles), slider (quadrilaterals), prism (tets),
 * halfball and block3d (hexahedra), twoblocks (two bodies), stackbond
 * (masonry's joints), coated (a Gmsh file with a material per region,
 * where this build has Gmsh). */
#include "scene/scene.h"
#include "check.h"

#include <stdio.h>
#include <string.h>

static int same(const void *a, const void *b, size_t n)
{
    return n == 0 || (a && b && memcmp(a, b, n) == 0);
}

#define SAME(x, y, n) CX_CHECK(same((x), (y), sizeof *(x) * (size_t)(n)))

static void check_csc(const cx_csc *a, const cx_csc *b)
{
    CX_CHECK(a->nrow == b->nrow && a->ncol == b->ncol);
    SAME(a->p, b->p, a->ncol + 1);
    SAME(a->i, b->i, cx_csc_nnz(a));
    SAME(a->x, b->x, cx_csc_nnz(a));
}

static void check_scene(const char *id, int level)
{
    cx_scene s;
    cx_diag d;
    cx_diag_clear(&d);
    cx_problem *pk = NULL, *p0 = NULL;
    cx_friction_state fk, f0;
    if (cx_scene_open(id, &s, &d) != CX_OK) {
        fprintf(stderr, "%s: %s\n", id, d.msg);
        CX_CHECK(0);
        return;
    }
    int st = cx_scene_build(&s, level, &pk, &fk, &d);
    if (st == CX_EUNSUPPORTED && s.generator == CX_GEN_FILE) {   /* no Gmsh in this build */
        fprintf(stderr, "%s: skipped: %s\n", id, d.msg);
        return;
    }
    CX_CHECK_OK(st);
    CX_CHECK_OK(cx_scene_build_flags(&s, level, CX_SCENE_BUILD_NO_K, &p0, &f0, &d));
    if (!pk || !p0) {
        cx_problem_destroy(&pk);
        cx_problem_destroy(&p0);
        return;
    }
    fprintf(stderr, "%s level %d: %d dofs, %d contact points, kscale %.17g / %.17g\n", id, level, pk->n, pk->m,
            pk->kscale, p0->kscale);
    /* K: whole in the one, empty in the other */
    CX_CHECK(pk->K.nrow == pk->n && cx_csc_nnz(&pk->K) > 0);
    CX_CHECK(p0->K.nrow == 0 && p0->K.ncol == 0 && cx_csc_nnz(&p0->K) == 0);
    /* the rest bitwise */
    CX_CHECK(pk->dim == p0->dim && pk->n == p0->n && pk->m == p0->m && pk->nt == p0->nt && pk->nc == p0->nc);
    CX_CHECK(pk->kscale == p0->kscale && pk->kscale > 0);
    CX_CHECK(pk->E == p0->E);
    SAME(pk->f, p0->f, pk->n);
    SAME(pk->g, p0->g, pk->m);
    SAME(pk->cdofs, p0->cdofs, pk->nc);
    SAME(pk->f_applied, p0->f_applied, 3);
    check_csc(&pk->N, &p0->N);
    check_csc(&pk->T, &p0->T);
    const cx_dofmap *mk = &pk->map, *m0 = &p0->map;
    CX_CHECK(mk->nall == m0->nall && mk->nfree == m0->nfree);
    SAME(mk->free_of, m0->free_of, mk->nall);
    SAME(mk->all_of, m0->all_of, mk->nfree);
    SAME(mk->value, m0->value, mk->nall);
    const cx_mesh *a = pk->mesh, *b = p0->mesh;
    CX_CHECK(a->nnodes == b->nnodes && a->nelems == b->nelems && a->npe == b->npe);
    SAME(a->x, b->x, (size_t)a->dim * a->nnodes);
    SAME(a->conn, b->conn, (size_t)a->npe * a->nelems);
    SAME(pk->mats, p0->mats, cx_mesh_nmats(a));
    const cx_contact_set *ck = &pk->contact, *c0 = &p0->contact;
    SAME(ck->node, c0->node, ck->m);
    SAME(ck->gap, c0->gap, ck->m);
    SAME(ck->weight, c0->weight, ck->m);
    CX_CHECK(!ck->spt == !c0->spt);
    if (ck->spt && c0->spt)
        SAME(ck->spt, c0->spt, ck->m);
    CX_CHECK(fk.law == f0.law && fk.slip_bound == f0.slip_bound && fk.F == f0.F);
    /* a prescribed value reaches f: it differs from the applied loads alone */
    int prescribed = 0;
    for (int k = 0; k < mk->nall; k++)
        prescribed |= mk->free_of[k] < 0 && mk->value[k] != 0;
    if (prescribed)
        fprintf(stderr, "  non-zero prescribed displacements folded into f\n");
    cx_problem_destroy(&pk);
    cx_problem_destroy(&p0);
}

int main(void)
{
    check_scene("hertz", 16);
    check_scene("slider", 0);
    check_scene("prism", 3);
    check_scene("halfball", 4);
    check_scene("block3d", 4);
    check_scene("twoblocks", 0);
    check_scene("stackbond", 0);
    check_scene("coated", 0);
    return check_finish("scene_build_no_k");
}
