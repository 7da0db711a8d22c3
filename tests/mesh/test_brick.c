/* SPDX-License-Identifier: GPL-3.0-or-later */
/* mesh/brick.c: counts; positive HEX8 corners and TET4 volumes; total
 * volume; the TET4 split is conforming (every tetrahedron face is shared by
 * two tetrahedra or is one boundary facet, and every boundary facet is a
 * tetrahedron face); outward boundary facets; validation; allocation
 * failures. */
#include "mesh/mesh.h"
#include "mesh_check.h"
#include "check.h"

#include <string.h>

typedef struct face {
    int v[3];
} face;

static int cmp_face(const void *a, const void *b)
{
    const face *x = a, *y = b;
    for (int k = 0; k < 3; k++)
        if (x->v[k] != y->v[k])
            return x->v[k] < y->v[k] ? -1 : 1;
    return 0;
}

static face sorted_face(int a, int b, int c)
{
    face f = {{a, b, c}};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2 - i; j++)
            if (f.v[j] > f.v[j + 1]) {
                int t = f.v[j];
                f.v[j] = f.v[j + 1];
                f.v[j + 1] = t;
            }
    return f;
}

/* Faces of all tetrahedra, sorted: counts of faces seen once and of faces
 * seen more than twice; and how many boundary facets are not a face seen
 * exactly once. */
static void tet_faces(const cx_mesh *m, int *once, int *over, int *stray)
{
    static const int fv[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    int n = 4 * m->nelems;
    face *f = malloc(sizeof(face) * (size_t)n);
    for (int e = 0; e < m->nelems; e++)
        for (int k = 0; k < 4; k++) {
            const int *c = m->conn + 4 * e;
            f[4 * e + k] = sorted_face(c[fv[k][0]], c[fv[k][1]], c[fv[k][2]]);
        }
    qsort(f, (size_t)n, sizeof(face), cmp_face);
    *once = *over = 0;
    for (int i = 0; i < n;) {
        int j = i;
        while (j < n && cmp_face(&f[i], &f[j]) == 0)
            j++;
        *once += j - i == 1;
        *over += j - i > 2;
        i = j;
    }
    *stray = 0;
    for (int b = 0; b < m->nbounds; b++)
        for (int k = 0; k < m->bounds[b].nfacets; k++) {
            const int *v = m->bounds[b].facets + 3 * k;
            face key = sorted_face(v[0], v[1], v[2]);
            face *hit = bsearch(&key, f, (size_t)n, sizeof(face), cmp_face);
            int count = 0;
            for (int i = 0; i < n; i++)
                count += cmp_face(&f[i], &key) == 0;
            *stray += !hit || count != 1;
        }
    free(f);
}

static void test_brick(cx_elem_type t, int nx, int ny, int nz)
{
    double lo[3] = {-1, 0, 0.5}, hi[3] = {2, 1, 2.5};
    cx_mesh *m = NULL;
    cx_diag d;
    CX_CHECK_OK(cx_mesh_brick(&m, lo, hi, nx, ny, nz, t, &d));
    if (!m)
        return;
    int tets = t == CX_EL_TET4;
    CX_CHECK(m->dim == 3 && m->npe == (tets ? 4 : 8));
    CX_CHECK(m->nnodes == (nx + 1) * (ny + 1) * (nz + 1));
    CX_CHECK(m->nelems == (tets ? 6 : 1) * nx * ny * nz);
    CX_CHECK(m->nbounds == 6 && m->body == NULL && m->nbodies == 1);
    CX_CHECK(mc_all_nodes_used(m));
    int bad = 0;
    for (int e = 0; e < m->nelems; e++)
        bad += !(mc_min_corner(m, e) > 0);
    CX_CHECK(bad == 0);
    CX_CHECK_NEAR(mc_measure(m), 3.0 * 1.0 * 2.0, 1e-14, 0);

    static const char *names[] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
    int n[3] = {nx, ny, nz}, total = 0;
    for (int s = 0; s < 6; s++) {
        const cx_boundary *b = cx_mesh_boundary(m, names[s]);
        CX_CHECK(b != NULL);
        if (!b)
            continue;
        int a = s / 2;
        CX_CHECK(b->npf == (tets ? 3 : 4));
        CX_CHECK(b->nfacets == (tets ? 2 : 1) * n[(a + 1) % 3] * n[(a + 2) % 3]);
        CX_CHECK(mc_bad_facets(m, b) == 0);
        double want = s % 2 ? hi[a] : lo[a];
        for (int k = 0; k < b->nfacets * b->npf; k++)
            CX_CHECK(m->x[3 * b->facets[k] + a] == want);
        total += b->nfacets;
    }
    if (tets) {
        int once, over, stray;
        tet_faces(m, &once, &over, &stray);
        CX_CHECK(over == 0);
        CX_CHECK(once == total);
        CX_CHECK(stray == 0);
    }
    cx_mesh_destroy(&m);
}

static void test_invalid(void)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, flat[3] = {1, 0, 1};
    cx_mesh *m = NULL;
    cx_diag d;
    CX_CHECK(cx_mesh_brick(&m, lo, hi, 1, 0, 1, CX_EL_HEX8, &d) == CX_EINVAL && m == NULL);
    CX_CHECK(strstr(d.msg, "at least") != NULL);
    CX_CHECK(cx_mesh_brick(&m, lo, flat, 1, 1, 1, CX_EL_HEX8, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "axis y") != NULL);
    CX_CHECK(cx_mesh_brick(&m, lo, hi, 1, 1, 1, CX_EL_QUAD4, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "quad4") != NULL);
    CX_CHECK(cx_mesh_brick(&m, lo, hi, 2000, 2000, 2000, CX_EL_TET4, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "too large") != NULL && m == NULL);
}

static void test_alloc(void)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    int points;
    MC_ALLOC_LOOP(points, cx_mesh_brick(&am_, lo, hi, 2, 1, 2, CX_EL_TET4, NULL));
    CX_CHECK(points > 5);
    MC_ALLOC_LOOP(points, cx_mesh_brick(&am_, lo, hi, 1, 2, 1, CX_EL_HEX8, NULL));
    CX_CHECK(points > 5);
}

int main(void)
{
    long live = cx_alloc_live();
    test_brick(CX_EL_HEX8, 1, 1, 1);
    test_brick(CX_EL_HEX8, 3, 2, 4);
    test_brick(CX_EL_TET4, 1, 1, 1);
    test_brick(CX_EL_TET4, 3, 2, 4);
    test_invalid();
    test_alloc();
    CX_CHECK(cx_alloc_live() == live);
    return check_finish("mesh_brick");
}
