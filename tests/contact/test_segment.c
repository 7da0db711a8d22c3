/* SPDX-License-Identifier: GPL-3.0-or-later */
/* contact/segment.c and mesh/twoblocks.c: the two-block mesh, and the
 * node-to-segment rows against hand values on a non-matching 2x2 over 3x3
 * pair, with and without an initial gap, and a penetration refused. */
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

/* Upper block [0,1] x [1,2] with 2 x 2 cells (nodes 0..8, node (i, j) =
 * 3 j + i), lower block [0,1] x [0,1] with 3 x 3 cells (nodes 9..24, node
 * (i, j) = 9 + 4 j + i). */
static cx_mesh *pair(void)
{
    cx_mesh *m = NULL;
    cx_diag d;
    const int up[2] = {2, 2}, lo[2] = {3, 3};
    CX_CHECK_OK(cx_mesh_twoblocks(&m, 0, 0, 1, 1, 2, up, lo, CX_EL_QUAD4, &d));
    return m;
}

static void test_mesh(void)
{
    cx_mesh *m = pair();
    CX_CHECK(m->nnodes == 9 + 16 && m->nelems == 4 + 9 && m->nbodies == 2);
    int nb0 = 0;
    for (int e = 0; e < m->nelems; e++)
        nb0 += m->body[e] == 0;
    CX_CHECK(nb0 == 4);
    const char *names[] = {"left1", "right1", "bottom1", "top1", "left2", "right2", "bottom2", "top2"};
    for (int k = 0; k < 8; k++)
        CX_CHECK(cx_mesh_boundary(m, names[k]) != NULL);
    CX_CHECK(cx_mesh_boundary(m, "top2")->nfacets == 3 && cx_mesh_boundary(m, "bottom1")->nfacets == 2);
    CX_CHECK_NEAR(m->x[2 * 4 + 1], 1.5, 0, 1e-15);       /* upper centre node */
    CX_CHECK_NEAR(m->x[2 * (9 + 13) + 0], 1.0 / 3, 0, 1e-15);
    CX_CHECK_NEAR(m->x[2 * (9 + 13) + 1], 1.0, 0, 0);    /* lower top row at y = 1 exactly */
    cx_diag d;
    cx_mesh *bad = NULL;
    const int c[2] = {1, 1};
    CX_CHECK(cx_mesh_twoblocks(&bad, 0, 0, 2, 1, 2, c, c, CX_EL_QUAD4, &d) == CX_EINVAL && !bad);
    cx_mesh_destroy(&m);
}

/* Matching geometry (gap 0): nu = n^1 = (0, -1), t = (1, 0). Slave node x
 * meets the master segment [x_p, x_q] (top2 is walked from x = 1 to 0). */
static void test_rows(void)
{
    cx_mesh *m = pair();
    cx_diag d;
    cx_contact_set cs = {0};
    CX_CHECK_OK(cx_contact_node_to_segment(&cs, m, cx_mesh_boundary(m, "bottom1"),
                                           cx_mesh_boundary(m, "top2"), NULL, &d));
    CX_CHECK(cs.m == 3 && cs.dim == 2 && cs.nall == 50);
    const int top2 = 9 + 12;    /* lower node (0, 3) */
    /* slave node, master p and q with weights -(1 - delta), -delta */
    const int slave[3] = {0, 1, 2};
    const int p[3] = {top2 + 1, top2 + 2, top2 + 3}, q[3] = {top2 + 0, top2 + 1, top2 + 2};
    const double delta[3] = {1, 0.5, 0};
    for (int i = 0; i < 3; i++) {
        CX_CHECK(cs.node[i] == slave[i]);
        CX_CHECK_NEAR(cs.x[2 * i], 0.5 * i, 0, 1e-15);
        CX_CHECK_NEAR(cs.gap[i], 0, 0, 0);
        CX_CHECK_NEAR(cs.normal[2 * i], 0, 0, 1e-15);
        CX_CHECK_NEAR(cs.normal[2 * i + 1], -1, 0, 1e-15);
        CX_CHECK_NEAR(cs.tangent[2 * i], 1, 0, 1e-15);
        CX_CHECK_NEAR(row_get(&cs.N, i, 2 * slave[i] + 1), -1, 0, 1e-15);
        CX_CHECK_NEAR(row_get(&cs.N, i, 2 * p[i] + 1), 1 - delta[i], 0, 1e-15);
        CX_CHECK_NEAR(row_get(&cs.N, i, 2 * q[i] + 1), delta[i], 0, 1e-15);
        CX_CHECK_NEAR(row_get(&cs.T, i, 2 * slave[i]), 1, 0, 1e-15);
        CX_CHECK_NEAR(row_get(&cs.T, i, 2 * p[i]), -(1 - delta[i]), 0, 1e-15);
        CX_CHECK_NEAR(row_get(&cs.T, i, 2 * q[i]), -delta[i], 0, 1e-15);
    }
    CX_CHECK_NEAR(cs.weight[0], 0.25, 1e-14, 0);
    CX_CHECK_NEAR(cs.weight[1], 0.5, 1e-14, 0);
    CX_CHECK_NEAR(cs.weight[2], 0.25, 1e-14, 0);
    /* nu and t have one non-zero component each, and delta = 0 or 1 drops
     * a master node: 2 + 3 + 2 entries, no explicit zeros */
    CX_CHECK(cs.N.nnz == 7 && cs.T.nnz == 7);
    cx_contact_clear(&cs);

    /* the other way round: 4 slave nodes of the 3 x 3 block on 2 segments */
    CX_CHECK_OK(cx_contact_node_to_segment(&cs, m, cx_mesh_boundary(m, "top2"),
                                           cx_mesh_boundary(m, "bottom1"), NULL, &d));
    CX_CHECK(cs.m == 4);
    /* x = 1/3 on bottom1's segment from node 0 (x = 0) to node 1 (x = 0.5):
     * delta = 2/3, nu = outward normal of top2 = (0, 1), t = (-1, 0) */
    CX_CHECK(cs.node[1] == top2 + 1);
    CX_CHECK_NEAR(row_get(&cs.N, 1, 2 * (top2 + 1) + 1), 1, 0, 1e-15);
    CX_CHECK_NEAR(row_get(&cs.N, 1, 2 * 0 + 1), -1.0 / 3, 0, 1e-15);
    CX_CHECK_NEAR(row_get(&cs.N, 1, 2 * 1 + 1), -2.0 / 3, 0, 1e-15);
    CX_CHECK_NEAR(row_get(&cs.T, 1, 2 * (top2 + 1)), -1, 0, 1e-15);
    CX_CHECK_NEAR(row_get(&cs.T, 1, 2 * 1), 2.0 / 3, 0, 1e-15);
    CX_CHECK_NEAR(cs.weight[1], 1.0 / 3, 1e-14, 0);
    cx_contact_clear(&cs);
    cx_mesh_destroy(&m);
}

/* Dirichlet nodes are not contact nodes (000 §3); an initial gap gives
 * nu = (chi - x)/d; a penetration is refused. */
static void test_gap_and_map(void)
{
    cx_mesh *m = pair();
    cx_diag d;
    cx_contact_set cs = {0};
    cx_dofmap map = {0};
    CX_CHECK_OK(cx_dofmap_init(&map, 2 * m->nnodes));
    for (int c = 0; c < 2; c++)
        CX_CHECK_OK(cx_dofmap_fix(&map, m, cx_mesh_boundary(m, "left1"), c, 0));
    CX_CHECK_OK(cx_dofmap_finish(&map));
    for (int k = 0; k < 9; k++)
        m->x[2 * k + 1] += 0.1;    /* lift the upper block */
    CX_CHECK_OK(cx_contact_node_to_segment(&cs, m, cx_mesh_boundary(m, "bottom1"),
                                           cx_mesh_boundary(m, "top2"), &map, &d));
    CX_CHECK(cs.m == 2 && cs.node[0] == 1 && cs.node[1] == 2);
    for (int i = 0; i < 2; i++) {
        CX_CHECK_NEAR(cs.gap[i], 0.1, 1e-12, 0);
        CX_CHECK_NEAR(cs.normal[2 * i + 1], -1, 0, 1e-15);
    }
    CX_CHECK_NEAR(cs.weight[0], 0.5, 1e-14, 0);   /* node 1 keeps its share */
    cx_contact_clear(&cs);
    for (int k = 0; k < 9; k++)
        m->x[2 * k + 1] -= 0.2;    /* now 0.1 into the lower block */
    CX_CHECK(cx_contact_node_to_segment(&cs, m, cx_mesh_boundary(m, "bottom1"),
                                        cx_mesh_boundary(m, "top2"), &map, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "penetrates") != NULL && cs.m == 0);
    cx_dofmap_clear(&map);
    cx_mesh_destroy(&m);
}

int main(void)
{
    test_mesh();
    test_rows();
    test_gap_and_map();
    return check_finish("contact_segment");
}
