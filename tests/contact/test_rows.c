/* SPDX-License-Identifier: GPL-3.0-or-later */
/* contact/: N and T rows, gaps, weights and normals against hand values
 * for each obstacle, the refusal of an initial penetration, and the
 * removal of clamped points (cx_contact_drop_clamped). */
#include "contact/contact.h"
#include "check.h"

#include <math.h>
#include <string.h>

static double row_get(const cx_triplet *t, int i, int j)
{
    double s = 0;
    for (size_t k = 0; k < t->nnz; k++)
        if (t->i[k] == i && t->j[k] == j)
            s += t->x[k];
    return s;
}

static void test_plane_2d(void)
{
    cx_mesh *m = NULL;
    cx_diag d;
    CX_CHECK_OK(cx_mesh_rectangle(&m, 0, 0.1, 1, 1, 2, 2, CX_EL_QUAD4, &d));
    cx_obstacle ob = {.kind = CX_OBST_PLANE, .normal = {0, 1}};
    cx_contact_set cs = {0};
    CX_CHECK_OK(cx_contact_from_obstacle(&cs, m, cx_mesh_boundary(m, "bottom"), &ob, &d));
    CX_CHECK(cs.m == 3);
    for (int i = 0; i < cs.m; i++) {
        int k = cs.node[i];
        CX_CHECK_NEAR(cs.x[2 * i], 0.5 * i, 0, 1e-15);          /* ordered along x */
        CX_CHECK_NEAR(cs.gap[i], 0.1, 1e-14, 0);
        CX_CHECK_NEAR(row_get(&cs.N, i, 2 * k), 0, 0, 0);
        CX_CHECK_NEAR(row_get(&cs.N, i, 2 * k + 1), -1, 0, 0);   /* towards the plane */
        CX_CHECK_NEAR(row_get(&cs.T, i, 2 * k), 1, 0, 0);        /* normal turned +90 deg */
        CX_CHECK_NEAR(row_get(&cs.T, i, 2 * k + 1), 0, 0, 0);
    }
    CX_CHECK_NEAR(cs.weight[0], 0.25, 1e-14, 0);
    CX_CHECK_NEAR(cs.weight[1], 0.5, 1e-14, 0);
    CX_CHECK_NEAR(cs.weight[2], 0.25, 1e-14, 0);
    CX_CHECK(cs.N.nnz == 3 && cs.T.nnz == 3);   /* no explicit zeros */
    cx_contact_clear(&cs);

    /* the plane raised to y = 0.2 cuts the body: reported, not clipped */
    ob.point[1] = 0.2;
    CX_CHECK(cx_contact_from_obstacle(&cs, m, cx_mesh_boundary(m, "bottom"), &ob, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "penetrates the plane obstacle by 0.1") != NULL);
    CX_CHECK(cs.m == 0 && cs.node == NULL);
    cx_mesh_destroy(&m);
}

static void test_disc_2d(void)
{
    cx_mesh *m = NULL;
    cx_diag d;
    CX_CHECK_OK(cx_mesh_rectangle(&m, 0, 0.1, 1, 1, 2, 2, CX_EL_TRI3, &d));
    cx_obstacle ob = {.kind = CX_OBST_DISC, .point = {0.5, -1}, .radius = 1};
    cx_contact_set cs = {0};
    CX_CHECK_OK(cx_contact_from_obstacle(&cs, m, cx_mesh_boundary(m, "bottom"), &ob, &d));
    CX_CHECK(cs.m == 3);
    /* middle point (0.5, 0.1): straight above the centre */
    CX_CHECK_NEAR(cs.gap[1], 0.1, 1e-14, 0);
    CX_CHECK_NEAR(row_get(&cs.N, 1, 2 * cs.node[1] + 1), -1, 1e-15, 0);
    /* corner (0, 0.1): w = (-0.5, 1.1), |w| = sqrt(1.46) */
    double len = sqrt(1.46);
    CX_CHECK_NEAR(cs.gap[0], len - 1, 1e-14, 0);
    int k = cs.node[0];
    CX_CHECK_NEAR(row_get(&cs.N, 0, 2 * k), 0.5 / len, 1e-14, 0);
    CX_CHECK_NEAR(row_get(&cs.N, 0, 2 * k + 1), -1.1 / len, 1e-14, 0);
    CX_CHECK_NEAR(row_get(&cs.T, 0, 2 * k), 1.1 / len, 1e-14, 0);
    CX_CHECK_NEAR(row_get(&cs.T, 0, 2 * k + 1), 0.5 / len, 1e-14, 0);
    cx_contact_clear(&cs);
    cx_mesh_destroy(&m);
}

static void test_sphere_3d(void)
{
    cx_mesh *m = NULL;
    cx_diag d;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    CX_CHECK_OK(cx_mesh_brick(&m, lo, hi, 1, 1, 1, CX_EL_HEX8, &d));
    cx_obstacle ob = {.kind = CX_OBST_SPHERE, .point = {0.5, 0.5, -1}, .radius = 1};
    cx_contact_set cs = {0};
    CX_CHECK_OK(cx_contact_from_obstacle(&cs, m, cx_mesh_boundary(m, "zmin"), &ob, &d));
    CX_CHECK(cs.m == 4);
    double wsum = 0;
    for (int i = 0; i < cs.m; i++) {
        const double *x = cs.x + 3 * i, *n = cs.normal + 3 * i, *t = cs.tangent + 6 * i;
        double w[3] = {x[0] - 0.5, x[1] - 0.5, x[2] + 1};
        double len = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        CX_CHECK_NEAR(cs.gap[i], sqrt(1.5) - 1, 1e-14, 0);
        for (int c = 0; c < 3; c++) {
            CX_CHECK_NEAR(n[c], -w[c] / len, 1e-14, 1e-15);
            CX_CHECK_NEAR(row_get(&cs.N, i, 3 * cs.node[i] + c), n[c], 0, 0);
        }
        /* orthonormal tangents with t1 x t2 = n */
        double d1 = 0, d2 = 0, d12 = 0, n1 = 0, n2 = 0;
        for (int c = 0; c < 3; c++) {
            d1 += t[c] * n[c];
            d2 += t[3 + c] * n[c];
            d12 += t[c] * t[3 + c];
            n1 += t[c] * t[c];
            n2 += t[3 + c] * t[3 + c];
        }
        CX_CHECK_NEAR(d1, 0, 0, 1e-15);
        CX_CHECK_NEAR(d2, 0, 0, 1e-15);
        CX_CHECK_NEAR(d12, 0, 0, 1e-15);
        CX_CHECK_NEAR(n1, 1, 1e-15, 0);
        CX_CHECK_NEAR(n2, 1, 1e-15, 0);
        CX_CHECK_NEAR(t[1] * t[5] - t[2] * t[4], n[0], 0, 1e-15);
        CX_CHECK_NEAR(t[2] * t[3] - t[0] * t[5], n[1], 0, 1e-15);
        CX_CHECK_NEAR(t[0] * t[4] - t[1] * t[3], n[2], 0, 1e-15);
        wsum += cs.weight[i];
    }
    CX_CHECK_NEAR(wsum, 1.0, 1e-14, 0);
    cx_contact_clear(&cs);

    /* gap measured along -z (paper 002's half-ball): (z+1)^2 = 1 - 0.5 */
    ob.direction[2] = -1;
    CX_CHECK_OK(cx_contact_from_obstacle(&cs, m, cx_mesh_boundary(m, "zmin"), &ob, &d));
    for (int i = 0; i < cs.m; i++) {
        CX_CHECK_NEAR(cs.gap[i], 1 - sqrt(0.5), 1e-14, 0);
        CX_CHECK_NEAR(cs.normal[3 * i + 2], -1, 0, 0);
    }
    cx_contact_clear(&cs);

    /* a cylinder along y under the block: gap from the axis distance */
    cx_obstacle cyl = {.kind = CX_OBST_CYLINDER, .point = {0.5, 0, -1}, .normal = {0, 1, 0}, .radius = 1};
    CX_CHECK_OK(cx_contact_from_obstacle(&cs, m, cx_mesh_boundary(m, "zmin"), &cyl, &d));
    for (int i = 0; i < cs.m; i++) {
        CX_CHECK_NEAR(cs.gap[i], sqrt(1.25) - 1, 1e-14, 0);
        CX_CHECK_NEAR(cs.normal[3 * i + 1], 0, 0, 1e-15);
    }
    cx_contact_clear(&cs);
    cx_mesh_destroy(&m);
}

/* Clamped points leave the set: the left edge fixed in x and y drops the
 * point at x = 0 and renumbers the rows; fixing y only (the normal) on the
 * right edge drops that one too; x only keeps it (its normal is free). */
static void test_drop_clamped(void)
{
    cx_mesh *m = NULL;
    cx_diag d;
    cx_dofmap map = {0};
    CX_CHECK_OK(cx_mesh_rectangle(&m, 0, 0.1, 1, 1, 2, 2, CX_EL_QUAD4, &d));
    cx_obstacle ob = {.kind = CX_OBST_PLANE, .normal = {0, 1}};
    const cx_boundary *left = cx_mesh_boundary(m, "left"), *right = cx_mesh_boundary(m, "right");
    for (int fix_right = 0; fix_right < 3; fix_right++) {   /* none, y, x */
        cx_contact_set cs = {0};
        CX_CHECK_OK(cx_dofmap_init(&map, 2 * m->nnodes));
        CX_CHECK_OK(cx_dofmap_fix(&map, m, left, 0, 0));
        CX_CHECK_OK(cx_dofmap_fix(&map, m, left, 1, 0));
        if (fix_right)
            CX_CHECK_OK(cx_dofmap_fix(&map, m, right, fix_right == 1 ? 1 : 0, 0));
        CX_CHECK_OK(cx_dofmap_finish(&map));
        CX_CHECK_OK(cx_contact_from_obstacle(&cs, m, cx_mesh_boundary(m, "bottom"), &ob, &d));
        CX_CHECK(cs.m == 3 && cs.nclamped == 0);
        CX_CHECK_OK(cx_contact_drop_clamped(&cs, &map));
        int want = fix_right == 1 ? 1 : 2;
        CX_CHECK(cs.m == want && cs.nclamped == 3 - want);
        CX_CHECK(cs.N.nrow == want && cs.T.nrow == want && cs.N.nnz == (size_t)want);
        for (int i = 0; i < cs.m; i++) {
            int k = cs.node[i];
            CX_CHECK_NEAR(cs.x[2 * i], 0.5 * (i + 1), 0, 1e-15);   /* order kept */
            CX_CHECK_NEAR(cs.weight[i], i == 0 ? 0.5 : 0.25, 1e-14, 0);
            CX_CHECK_NEAR(row_get(&cs.N, i, 2 * k + 1), -1, 0, 0);
            CX_CHECK_NEAR(row_get(&cs.T, i, 2 * k), 1, 0, 0);
            CX_CHECK_NEAR(cs.gap[i], 0.1, 1e-14, 0);
        }
        cx_contact_clear(&cs);
        cx_dofmap_clear(&map);
    }
    cx_mesh_destroy(&m);
}

int main(void)
{
    test_plane_2d();
    test_disc_2d();
    test_sphere_3d();
    test_drop_clamped();
    return check_finish("contact_rows");
}
