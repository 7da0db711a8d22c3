/* SPDX-License-Identifier: GPL-3.0-or-later */
/* mesh/gmsh.c through the helper: a 2D square meshed as TRI3, TRI6 (second
 * order) and QUAD4 (recombined), its area, boundaries and groups; the
 * shipped sphere.geo as TET4 at two levels (more nodes at the finer,
 * positive volumes, the eighth ball's volume); a clockwise surface turned
 * over; bad files refused with a message. The .geo files are written to a
 * temporary directory. */
#include "check.h"
#include "mesh/mesh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char dir[] = "/tmp/cx_gmsh_XXXXXX";

static void put(const char *name, const char *text)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    fputs(text, f);
    fclose(f);
}

static const char *at(const char *name)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return path;
}

/* the signed area of element e (corners) */
static double area(const cx_mesh *m, int e)
{
    int nc = m->etype == CX_EL_QUAD4 ? 4 : 3;
    double a = 0;
    for (int k = 0; k < nc; k++) {
        const double *p = m->x + 2 * m->conn[m->npe * e + k];
        const double *q = m->x + 2 * m->conn[m->npe * e + (k + 1) % nc];
        a += 0.5 * (p[0] * q[1] - q[0] * p[1]);
    }
    return a;
}

static double tet_volume(const cx_mesh *m, int e)
{
    const int *c = m->conn + 4 * e;
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) {
        u[k] = m->x[3 * c[1] + k] - m->x[3 * c[0] + k];
        v[k] = m->x[3 * c[2] + k] - m->x[3 * c[0] + k];
        w[k] = m->x[3 * c[3] + k] - m->x[3 * c[0] + k];
    }
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
            u[2] * (v[0] * w[1] - v[1] * w[0])) / 6;
}

static const char square[] =
    "Point(1) = {0, 0, 0, 0.25}; Point(2) = {2, 0, 0, 0.25}; Point(3) = {2, 1, 0, 0.25};\n"
    "Point(4) = {0, 1, 0, 0.25};\n"
    "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
    "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
    "Physical Curve(\"bottom\") = {1}; Physical Curve(\"top\") = {3};\n"
    "Physical Surface(\"body\") = {1}; Physical Point(\"corner\") = {3};\n";

/* the same square with its loop turned clockwise: Gmsh's elements turn too */
static const char square_cw[] =
    "Point(1) = {0, 0, 0, 0.25}; Point(2) = {2, 0, 0, 0.25}; Point(3) = {2, 1, 0, 0.25};\n"
    "Point(4) = {0, 1, 0, 0.25};\n"
    "Line(1) = {1, 4}; Line(2) = {4, 3}; Line(3) = {3, 2}; Line(4) = {2, 1};\n"
    "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
    "Physical Curve(\"bottom\") = {4}; Physical Surface(\"body\") = {1};\n";

static void test_square(const char *file, int element, cx_elem_type want)
{
    cx_mesh *m = NULL;
    cx_mesh_groups g;
    cx_diag d = {0};
    cx_gmsh_options opt = {1, 0, element};
    int st = cx_mesh_read_gmsh(&m, &g, at(file), &opt, &d);
    CX_CHECK(st == CX_OK);
    if (st) {
        fprintf(stderr, "%s\n", d.msg);
        return;
    }
    CX_CHECK(m->dim == 2 && m->etype == want && m->nbodies == 1);
    double total = 0, amin = 1;
    for (int e = 0; e < m->nelems; e++) {
        total += area(m, e);
        amin = fmin(amin, area(m, e));
    }
    CX_CHECK_NEAR(total, 2.0, 1e-12, 0);
    CX_CHECK(amin > 0);
    const cx_boundary *b = cx_mesh_boundary(m, "bottom");
    CX_CHECK(b != NULL);
    if (b) {
        CX_CHECK(b->npf == (want == CX_EL_TRI6 ? 3 : 2));
        double len = 0;
        for (int f = 0; f < b->nfacets; f++) {
            const double *p = m->x + 2 * b->facets[b->npf * f], *q = m->x + 2 * b->facets[b->npf * f + 1];
            CX_CHECK(p[1] == 0 && q[1] == 0);
            len += q[0] - p[0];   /* the body on the left: the bottom runs in +x */
        }
        CX_CHECK_NEAR(len, 2.0, 1e-12, 0);
    }
    const cx_mesh_group *r = cx_mesh_group_find(&g, "body");
    CX_CHECK(r && r->dim == 2 && r->count == m->nelems);
    const cx_mesh_group *c = cx_mesh_group_find(&g, "corner");
    if (strcmp(file, "square.geo") == 0) {
        CX_CHECK(c && c->dim == 0 && c->count == 1);
        if (c && c->count == 1)
            CX_CHECK(m->x[2 * c->items[0]] == 2 && m->x[2 * c->items[0] + 1] == 1);
    }
    cx_mesh_destroy(&m);
    cx_mesh_groups_clear(&g);
}

static void test_sphere(void)
{
    int nn[2] = {0, 0};
    for (int level = 1; level <= 2; level++) {
        cx_mesh *m = NULL;
        cx_mesh_groups g;
        cx_diag d = {0};
        cx_gmsh_options opt = {level, 0, -1};
        int st = cx_mesh_read_gmsh(&m, &g, CX_SOURCE_SCENES "/sphere.geo", &opt, &d);
        CX_CHECK(st == CX_OK);
        if (st) {
            fprintf(stderr, "%s\n", d.msg);
            return;
        }
        CX_CHECK(m->dim == 3 && m->etype == CX_EL_TET4);
        double vol = 0, vmin = 1;
        for (int e = 0; e < m->nelems; e++) {
            vol += tet_volume(m, e);
            vmin = fmin(vmin, tet_volume(m, e));
        }
        CX_CHECK(vmin > 0);
        /* an eighth of a ball of radius 8: pi 8^3 / 6, less the chords' share */
        CX_CHECK_NEAR(vol, 3.14159265358979 * 512 / 6, 0.03 / level, 0);
        CX_CHECK(cx_mesh_boundary(m, "surface") && cx_mesh_boundary(m, "top"));
        CX_CHECK(cx_mesh_boundary(m, "surface")->npf == 3);
        nn[level - 1] = m->nnodes;
        cx_mesh_destroy(&m);
        cx_mesh_groups_clear(&g);
    }
    CX_CHECK(nn[1] > 4 * nn[0]);   /* size h/2: about 8 times the nodes */
}

/* the size: the file's h = 0.25 divided by the level, capped by size / level */
static void test_size(void)
{
    int ne[3];
    const cx_gmsh_options opts[3] = {{1, 0, -1}, {2, 0, -1}, {1, 0.125, -1}};
    for (int k = 0; k < 3; k++) {
        cx_mesh *m = NULL;
        cx_mesh_groups g;
        cx_diag d = {0};
        ne[k] = 0;
        CX_CHECK(cx_mesh_read_gmsh(&m, &g, at("square.geo"), &opts[k], &d) == CX_OK);
        if (m)
            ne[k] = m->nelems;
        cx_mesh_destroy(&m);
        cx_mesh_groups_clear(&g);
    }
    /* h / 2 either way: about 4 times the triangles, the same count twice */
    CX_CHECK(ne[1] > 3 * ne[0] && ne[1] < 5 * ne[0]);
    CX_CHECK(ne[2] > 3 * ne[0] && ne[2] < 5 * ne[0]);
}

static void test_bad(void)
{
    cx_mesh *m = NULL;
    cx_mesh_groups g;
    cx_diag d = {0};
    cx_gmsh_options opt = {1, 0, -1};
    CX_CHECK(cx_mesh_read_gmsh(&m, &g, at("nothere.geo"), &opt, &d) == CX_EIO);
    CX_CHECK(strstr(d.msg, "nothere.geo") != NULL);
    CX_CHECK(m == NULL);
    put("bad.geo", "Point(1) = {0, 0, 0;\n");
    CX_CHECK(cx_mesh_read_gmsh(&m, &g, at("bad.geo"), &opt, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "syntax error") != NULL);
    /* the scene asks for another type than the file makes (its own option
     * read after ours: no recombination) */
    opt.element = CX_EL_QUAD4;
    put("one.geo", "Mesh.RecombineAll = 0;\nPoint(1) = {0, 0, 0, 1}; Point(2) = {1, 0, 0, 1}; Point(3) = {0, 1, 0, 1};\n"
                   "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};\n"
                   "Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};\n");
    CX_CHECK(cx_mesh_read_gmsh(&m, &g, at("one.geo"), &opt, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "TRI3") != NULL && strstr(d.msg, "quad4") != NULL);
    CX_CHECK(m == NULL);
}

int main(void)
{
    if (!cx_mesh_have_gmsh()) {
        printf("gmsh: not in this build\n");
        return 77;
    }
    if (!mkdtemp(dir))
        return 1;
    put("square.geo", square);
    put("square_cw.geo", square_cw);
    test_square("square.geo", -1, CX_EL_TRI3);
    test_square("square.geo", CX_EL_TRI6, CX_EL_TRI6);
    test_square("square.geo", CX_EL_QUAD4, CX_EL_QUAD4);
    test_square("square_cw.geo", -1, CX_EL_TRI3);
    test_sphere();
    test_size();
    test_bad();
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", dir);
    return check_finish("mesh_gmsh");
}
