/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Element stiffness and its assembly: a hand-computed TRI3 matrix; for each
 * element type on a distorted mesh, K over all dofs is symmetric
 * (asymmetry < 1e-12 max |K|), has the rigid motions in its null space
 * (||K r|| <= 1e-10 ||K||_F ||r||: 3 in 2D, 6 in 3D) and is positive on a
 * non-rigid displacement; per-body materials against a dense assembly of
 * the element matrices; CX_ENUMERIC for degenerate or inverted elements;
 * CX_EINVAL for bad materials and body ids; allocation failures. */
#include "fem/fem.h"
#include "fem_fixture.h"
#include "check.h"

#include <stdio.h>

/* TRI3 (0,0), (1,0), (0,1), plane strain, E = 1, nu = 0: lambda = 0,
 * mu = 1/2, D = diag(1, 1, 1/2), area 1/2. N = (1-x-y, x, y), so
 * dN/dx = (-1, 1, 0), dN/dy = (-1, 0, 1) and, in dof order u0 v0 u1 v1 u2 v2,
 *   B_xx = (-1, 0, 1, 0, 0, 0), B_yy = (0, -1, 0, 0, 0, 1),
 *   B_xy = (-1, -1, 0, 1, 1, 0).
 * Ke = 1/2 (B_xx' B_xx + B_yy' B_yy + 1/2 B_xy' B_xy): */
static const double hand_ke[6][6] = {
    {0.75, 0.25, -0.5, -0.25, -0.25, 0},
    {0.25, 0.75, 0, -0.25, -0.25, -0.5},
    {-0.5, 0, 0.5, 0, 0, 0},
    {-0.25, -0.25, 0, 0.25, 0.25, 0},
    {-0.25, -0.25, 0, 0.25, 0.25, 0},
    {0, -0.5, 0, 0, 0, 0.5},
};

static void test_hand_tri3(void)
{
    double xe[6] = {0, 0, 1, 0, 0, 1}, D[9], Ke[36];
    cx_material mat = {.E = 1, .nu = 0, .model = CX_PLANE_STRAIN};
    cx_fem_elasticity(&mat, D);
    CX_CHECK_OK(cx_fem_element_stiffness(CX_EL_TRI3, xe, D, Ke));
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++)
            CX_CHECK_NEAR(Ke[6 * i + j], hand_ke[i][j], 0, 1e-15);
}

/* Rigid motion k of dim: translations, then rotations (2D: (-y, x); 3D:
 * e_a x x for a = x, y, z). */
static void rigid(const cx_mesh *m, int k, double *r)
{
    int dim = m->dim;
    for (int n = 0; n < m->nnodes; n++) {
        const double *x = m->x + dim * n;
        double *u = r + dim * n;
        for (int c = 0; c < dim; c++)
            u[c] = c == k ? 1 : 0;
        if (dim == 2 && k == 2)
            u[0] = -x[1], u[1] = x[0];
        if (dim == 3 && k >= 3) {
            int a = k - 3, b = (a + 1) % 3, c = (a + 2) % 3;
            u[a] = 0, u[b] = -x[c], u[c] = x[b];
        }
    }
}

static void test_global(cx_elem_type t)
{
    cx_mesh *m = fx_mesh(t, 1);
    CX_CHECK(m != NULL);
    if (!m)
        return;
    int dim = m->dim, nall = dim * m->nnodes;
    cx_material mat = fx_material(dim == 3 ? CX_SOLID : CX_PLANE_STRESS);
    cx_csc K = {0};
    cx_diag d;
    CX_CHECK_OK(cx_fem_assemble_stiffness(m, &mat, &K, &d));
    CX_CHECK(K.nrow == nall && K.ncol == nall);
    double kmax = fx_maxabs(&K), kf = fx_frob(&K);
    CX_CHECK_LE(cx_csc_asymmetry(&K), 1e-12 * kmax);

    double *r = calloc((size_t)nall, sizeof(double)), *y = calloc((size_t)nall, sizeof(double));
    int nr = dim == 2 ? 3 : 6;
    for (int k = 0; k < nr; k++) {
        rigid(m, k, r);
        fx_matvec(&K, r, y);
        CX_CHECK_LE(fx_norm(nall, y), 1e-10 * kf * fx_norm(nall, r));
    }
    /* u = (x^2, xy [, yz]): a non-rigid field, whose energy must be positive */
    for (int n = 0; n < m->nnodes; n++) {
        const double *x = m->x + dim * n;
        r[dim * n] = x[0] * x[0];
        r[dim * n + 1] = x[0] * x[1];
        if (dim == 3)
            r[dim * n + 2] = x[1] * x[2];
    }
    fx_matvec(&K, r, y);
    double energy = 0, rr = fx_norm(nall, r);
    for (int k = 0; k < nall; k++)
        energy += r[k] * y[k];
    fprintf(stderr, "%s: max|K| %.3g, asymmetry %.2e, u'Ku / (||K||_F ||u||^2) = %.3g\n", cx_elem_name(t),
            kmax, cx_csc_asymmetry(&K), energy / (kf * rr * rr));
    CX_CHECK(energy > 1e-4 * kf * rr * rr);
    free(r);
    free(y);
    cx_csc_clear(&K);
    cx_mesh_destroy(&m);
}

/* Two bodies (even / odd elements): the assembled K equals a dense sum of
 * element matrices, each with its body's material. */
static void test_bodies(cx_elem_type t)
{
    cx_mesh *m = fx_mesh(t, 1);
    CX_CHECK(m != NULL);
    if (!m)
        return;
    int dim = m->dim, nall = dim * m->nnodes, npe = m->npe, nd = dim * npe;
    m->nbodies = 2;
    m->body = CX_NEW(int, m->nelems);
    for (int e = 0; e < m->nelems; e++)
        m->body[e] = e % 2;
    cx_material mats[2] = {fx_material(dim == 3 ? CX_SOLID : CX_PLANE_STRAIN),
                           {.E = 3.5, .nu = 0.1, .model = dim == 3 ? CX_SOLID : CX_PLANE_STRAIN}};
    cx_csc K = {0};
    cx_diag d;
    CX_CHECK_OK(cx_fem_assemble_stiffness(m, mats, &K, &d));
    double *dense = calloc((size_t)nall * (size_t)nall, sizeof(double));
    for (int e = 0; e < m->nelems; e++) {
        double xe[24], Ke[576], D[36];
        const int *c = m->conn + npe * e;
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++)
                xe[dim * a + i] = m->x[dim * c[a] + i];
        cx_fem_elasticity(&mats[e % 2], D);
        CX_CHECK_OK(cx_fem_element_stiffness(t, xe, D, Ke));
        for (int a = 0; a < nd; a++)
            for (int b = 0; b < nd; b++)
                dense[(size_t)nall * (dim * c[a / dim] + a % dim) + dim * c[b / dim] + b % dim] += Ke[nd * a + b];
    }
    double err = 0, big = 0;
    for (int i = 0; i < nall; i++)
        for (int j = 0; j < nall; j++) {
            err = fmax(err, fabs(cx_csc_get(&K, i, j) - dense[(size_t)nall * i + j]));
            big = fmax(big, fabs(dense[(size_t)nall * i + j]));
        }
    CX_CHECK_NEAR(err, 0, 0, 1e-13 * big);

    /* a body id out of range */
    m->body[1] = 2;
    cx_csc_clear(&K);
    CX_CHECK(cx_fem_assemble_stiffness(m, mats, &K, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "element 1: body 2") != NULL);
    CX_CHECK(K.p == NULL);
    free(dense);
    cx_mesh_destroy(&m);
}

static void test_degenerate(void)
{
    double D2[9], D3[36], Ke[576], fe[24], b[3] = {1, 2, 3};
    cx_material m2 = fx_material(CX_PLANE_STRAIN), m3 = fx_material(CX_SOLID);
    cx_fem_elasticity(&m2, D2);
    cx_fem_elasticity(&m3, D3);

    double cw[6] = {0, 0, 0, 1, 1, 0}, line[6] = {0, 0, 1, 1, 2, 2};
    CX_CHECK(cx_fem_element_stiffness(CX_EL_TRI3, cw, D2, Ke) == CX_ENUMERIC);
    CX_CHECK(cx_fem_element_stiffness(CX_EL_TRI3, line, D2, Ke) == CX_ENUMERIC);
    CX_CHECK(cx_fem_element_body_force(CX_EL_TRI3, cw, b, fe) == CX_ENUMERIC);
    /* mid-node of edge 01 past the three-quarter point: det J < 0 at vertex 1 */
    double tri6[12] = {0, 0, 1, 0, 0, 1, 0.9, 0, 0.5, 0.5, 0, 0.5};
    CX_CHECK(cx_fem_element_stiffness(CX_EL_TRI6, tri6, D2, Ke) == CX_ENUMERIC);
    tri6[6] = 0.7;
    CX_CHECK_OK(cx_fem_element_stiffness(CX_EL_TRI6, tri6, D2, Ke));
    /* a non-convex quadrilateral (re-entrant corner at node 2) */
    double arrow[8] = {0, 0, 2, 0, 0.4, 0.4, 0, 2};
    CX_CHECK(cx_fem_element_stiffness(CX_EL_QUAD4, arrow, D2, Ke) == CX_ENUMERIC);
    double quad_cw[8] = {0, 0, 0, 1, 1, 1, 1, 0};
    CX_CHECK(cx_fem_element_stiffness(CX_EL_QUAD4, quad_cw, D2, Ke) == CX_ENUMERIC);
    /* the unit cube with top and bottom exchanged */
    double hex[24] = {0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    CX_CHECK(cx_fem_element_stiffness(CX_EL_HEX8, hex, D3, Ke) == CX_ENUMERIC);
    double tet[12] = {0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1};
    CX_CHECK(cx_fem_element_stiffness(CX_EL_TET4, tet, D3, Ke) == CX_ENUMERIC);
    double flat[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    CX_CHECK(cx_fem_element_stiffness(CX_EL_TET4, flat, D3, Ke) == CX_ENUMERIC);
    CX_CHECK(cx_fem_element_body_force(CX_EL_TET4, flat, b, fe) == CX_ENUMERIC);

    /* assembly names the element */
    cx_mesh *m = NULL;
    cx_diag d;
    cx_csc K = {0};
    CX_CHECK_OK(cx_mesh_rectangle(&m, 0, 0, 1, 1, 2, 2, CX_EL_QUAD4, &d));
    m->x[2 * 4] = 1.2;   /* the centre node pushed past the right side: element 0 stays convex, 1 folds */
    CX_CHECK(cx_fem_assemble_stiffness(m, &m2, &K, &d) == CX_ENUMERIC);
    CX_CHECK(strstr(d.msg, "element 1 (quad4) is degenerate or inverted") != NULL);
    CX_CHECK(K.p == NULL && cx_csc_nnz(&K) == 0);
    cx_mesh_destroy(&m);
}

static void test_bad_material(void)
{
    cx_mesh *m = NULL;
    cx_diag d;
    cx_csc K = {0};
    CX_CHECK_OK(cx_mesh_rectangle(&m, 0, 0, 1, 1, 1, 1, CX_EL_TRI3, &d));
    cx_material mat = fx_material(CX_SOLID);
    CX_CHECK(cx_fem_assemble_stiffness(m, &mat, &K, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "3D model on a 2D mesh") != NULL);
    mat = fx_material(CX_PLANE_STRAIN);
    mat.nu = 0.5;
    CX_CHECK(cx_fem_assemble_stiffness(m, &mat, &K, &d) == CX_EINVAL);
    mat.nu = 0.3;
    mat.E = 0;
    CX_CHECK(cx_fem_assemble_stiffness(m, &mat, &K, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "E > 0") != NULL);
    cx_mesh_destroy(&m);
}

static void test_alloc(void)
{
    cx_mesh *m = fx_mesh(CX_EL_TET4, 1);
    cx_material mat = fx_material(CX_SOLID);
    int points = 0, ok = 0;
    for (long n = 0; n < 1000; n++) {
        cx_csc K = {0};
        cx_diag d;
        long live = cx_alloc_live();
        cx_alloc_fail_after(n);
        int st = cx_fem_assemble_stiffness(m, &mat, &K, &d);
        cx_alloc_fail_after(-1);
        cx_csc_clear(&K);
        CX_CHECK(cx_alloc_live() == live);
        if (st == CX_OK) {
            ok = 1;
            break;
        }
        CX_CHECK(st == CX_ENOMEM);
        points++;
    }
    CX_CHECK(ok && points >= 3);
    cx_mesh_destroy(&m);
}

int main(void)
{
    long live = cx_alloc_live();
    test_hand_tri3();
    cx_elem_type types[5] = {CX_EL_TRI3, CX_EL_TRI6, CX_EL_QUAD4, CX_EL_HEX8, CX_EL_TET4};
    for (int k = 0; k < 5; k++) {
        test_global(types[k]);
        test_bodies(types[k]);
    }
    test_degenerate();
    test_bad_material();
    test_alloc();
    CX_CHECK(cx_alloc_live() == live);
    return check_finish("fem_stiffness");
}
