/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Paper 001's prism and its mesh rule (level_rule = sqrt2): the cell
 * counts, nodes and contact nodes of every level against Table 1 (levels
 * 2-8 exactly; level 1 by the rule, 112 / 24), the built problems of levels
 * 1-5 (nodes, contact points, contact dofs; the clamped points counted
 * apart), pdas and pdpc on the frictionless prism (they need every contact
 * row to have a free dof of its own), and a bad level_rule value. */
#include "scene/scene.h"
#include "check.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Table 1 of paper 001, level 1 replaced by the rule's value */
static const int table_nodes[9] = {0, 112, 225, 637, 1377, 4056, 9537, 27072, 70785};
static const int table_contact[9] = {0, 24, 40, 84, 144, 299, 544, 1104, 2112};

static void check_counts(const cx_scene *s)
{
    static const int table_nx[9] = {0, 6, 8, 12, 16, 23, 32, 46, 64};
    for (int L = 1; L <= 8; L++) {
        int c[3];
        cx_scene_cells(s, L, c);
        CX_CHECK(c[0] == table_nx[L]);
        CX_CHECK(c[1] == c[2] && 2 * c[1] == c[0] + (L % 2 ? c[0] % 2 : 0));
        CX_CHECK((c[0] + 1) * (c[1] + 1) * (c[2] + 1) == table_nodes[L]);
        CX_CHECK(c[0] * (c[1] + 1) == table_contact[L]);
    }
}

static void check_built(const cx_scene *s)
{
    for (int L = 1; L <= 5; L++) {
        cx_problem *p = NULL;
        cx_diag d;
        cx_friction_state fr;
        CX_CHECK_OK(cx_scene_build(s, L, &p, &fr, &d));
        if (!p)
            continue;
        int c[3], active = 0;
        cx_scene_cells(s, L, c);
        /* contact points are the points with a free dof: every row of N
         * is non-empty, the clamped edge (x = 0) is counted apart */
        int *hit = calloc((size_t)p->m, sizeof(int));
        for (size_t q = 0; q < cx_csc_nnz(&p->N); q++)
            hit[p->N.i[q]] = 1;
        for (int i = 0; i < p->m; i++)
            active += hit[i];
        free(hit);
        CX_CHECK(p->mesh->nnodes == table_nodes[L]);
        CX_CHECK(p->m == table_contact[L]);            /* off the clamped face */
        CX_CHECK(active == p->m);
        CX_CHECK(p->contact.nclamped == c[1] + 1);     /* the bottom face's edge x = 0 */
        CX_CHECK(p->m + p->contact.nclamped == (c[0] + 1) * (c[1] + 1));
        for (int i = 0; i < p->m; i++)
            CX_CHECK(p->contact.x[3 * i] > 0);
        CX_CHECK(p->nc == 3 * table_contact[L]);
        CX_CHECK(p->n == 3 * (table_nodes[L] - (c[1] + 1) * (c[2] + 1)));
        CX_CHECK(fr.law == CX_FRICTION_TRESCA);
        cx_problem_destroy(&p);
    }
}

/* pdas and pdpc refused the prism while its clamped points were contact
 * rows ("contact row 0 has no dof of its own"). */
static void check_active_set_methods(const cx_scene *s)
{
    const char *ids[] = {"pdas", "pdpc"};
    for (int k = 0; k < 2; k++) {
        cx_problem *p = NULL;
        cx_session *ss = NULL;
        cx_diag d;
        cx_options o;
        CX_CHECK_OK(cx_scene_build(s, 2, &p, NULL, &d));
        CX_CHECK_OK(cx_session_create(&ss, &p, &d));
        if (!ss)
            continue;
        CX_CHECK_OK(cx_session_set_frictionless(ss, &d));
        cx_options_default(&o);
        int st = cx_session_set_method(ss, cx_method_find(ids[k]), NULL, &o, &d);
        CX_CHECK_OK(st);
        if (st == CX_OK)
            CX_CHECK_OK(cx_solver_solve(ss, NULL, NULL, &d));
        if (st != CX_OK)
            fprintf(stderr, "  %s: %s\n", ids[k], d.msg);
        const cx_iterate *it = cx_session_iterate(ss);
        CX_CHECK(cx_session_problem(ss)->m == 40);
        CX_CHECK(it->reason > 0);
        CX_CHECK_LE(it->kkt, o.tol);
        CX_CHECK(it->iter <= 20 && it->ncontact + it->nstick + it->nslip > 0);
        cx_session_destroy(&ss);
    }
}

static void check_bad_rule(void)
{
    char dir[] = "/tmp/signorini_prism_XXXXXX", path[64];
    CX_CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/bad.ini", dir);
    FILE *fp = fopen(path, "w");
    CX_CHECK(fp != NULL);
    if (!fp)
        return;
    const char *text = "[scene]\nid = x\ndim = 3\n[mesh]\ngenerator = brick\nlo = 0 0 0\n"
                       "hi = 1 1 1\nlevel_rule = cubic\n[material]\nE = 1\nnu = 0.3\n"
                       "[contact]\nboundary = zmin\nobstacle = plane\nnormal = 0 0 1\n";
    CX_CHECK(fputs(text, fp) >= 0);
    fclose(fp);
    cx_scene s;
    cx_diag d;
    CX_CHECK(cx_scene_load(&s, path, &d) == CX_EINVAL);
    char expect[600];
    snprintf(expect, sizeof expect, "%s:8: key 'level_rule'", path);
    CX_CHECK(strstr(d.msg, expect) != NULL);
    if (!strstr(d.msg, expect))
        fprintf(stderr, "  got: %s\n", d.msg);
    unlink(path);
    rmdir(dir);
}

int main(void)
{
    char path[1024];
    cx_scene s;
    cx_diag d;
    CX_CHECK_OK(cx_scene_resolve("prism", path, sizeof path, &d));
    CX_CHECK_OK(cx_scene_load(&s, path, &d));
    CX_CHECK(s.level_rule == CX_LEVEL_SQRT2);
    check_counts(&s);
    check_built(&s);
    check_active_set_methods(&s);
    check_bad_rule();
    return check_finish("scene_prism");
}
