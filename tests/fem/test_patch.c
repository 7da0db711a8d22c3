/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Patch tests: on distorted meshes of every element type and every model,
 * the displacement u = A x + c of a constant strain, prescribed at the
 * boundary nodes (dofmap + reduce), solved for by dense Gaussian
 * elimination and expanded, is reproduced at the interior nodes to 1e-10
 * (relative to max |u|), and the nodal stresses equal D eps to 1e-9
 * (relative to max |sigma|). Also on the Hertz meshes (naturally distorted, curved TRI6)
 * with the boundary nodes of all four sides prescribed. Plus nodal
 * stresses of a bilinear field taken at the nodes (QUAD4). */
#include "fem/fem.h"
#include "fem_fixture.h"
#include "check.h"

#include <stdio.h>
#include <stdlib.h>

static const double A3[3][3] = {{1.0e-3, 2.0e-4, -3.0e-4}, {-5.0e-4, 2.0e-3, 4.0e-4}, {7.0e-4, -1.0e-4, -1.5e-3}};
static const double c3[3] = {0.01, -0.02, 0.005};

static void exact(int dim, const double *x, double *u)
{
    for (int i = 0; i < dim; i++) {
        u[i] = c3[i];
        for (int k = 0; k < dim; k++)
            u[i] += A3[i][k] * x[k];
    }
}

/* Solve K x = f in place by dense Gaussian elimination with partial
 * pivoting: the reduced systems here are small, and the test then does not
 * depend on the sparse factorisations. 0, or 1 for a singular K. */
static int dense_solve(const cx_csc *K, double *f)
{
    int n = K->nrow;
    double *A = calloc((size_t)n * (size_t)n + 1, sizeof(double));
    if (!A)
        return 1;
    for (int j = 0; j < n; j++)
        for (int q = K->p[j]; q < K->p[j + 1]; q++)
            A[(size_t)n * K->i[q] + j] += K->x[q];
    int bad = 0;
    for (int k = 0; k < n && !bad; k++) {
        int piv = k;
        for (int r = k + 1; r < n; r++)
            if (fabs(A[(size_t)n * r + k]) > fabs(A[(size_t)n * piv + k]))
                piv = r;
        if (A[(size_t)n * piv + k] == 0) {
            bad = 1;
            break;
        }
        if (piv != k) {
            for (int j = 0; j < n; j++) {
                double t = A[(size_t)n * k + j];
                A[(size_t)n * k + j] = A[(size_t)n * piv + j];
                A[(size_t)n * piv + j] = t;
            }
            double t = f[k];
            f[k] = f[piv];
            f[piv] = t;
        }
        for (int r = k + 1; r < n; r++) {
            double l = A[(size_t)n * r + k] / A[(size_t)n * k + k];
            if (l == 0)
                continue;
            for (int j = k; j < n; j++)
                A[(size_t)n * r + j] -= l * A[(size_t)n * k + j];
            f[r] -= l * f[k];
        }
    }
    for (int k = n - 1; k >= 0 && !bad; k--) {
        double s = f[k];
        for (int j = k + 1; j < n; j++)
            s -= A[(size_t)n * k + j] * f[j];
        f[k] = s / A[(size_t)n * k + k];
    }
    free(A);
    return bad;
}

static void run_patch(const char *label, cx_mesh *m, cx_model model)
{
    int dim = m->dim, nall = dim * m->nnodes, ns = cx_fem_nstress(dim);
    cx_material mat = fx_material(model);
    cx_csc Kall = {0}, K = {0};
    cx_dofmap map;
    cx_diag d;
    double *fall = calloc((size_t)nall, sizeof(double)), *uall = calloc((size_t)nall, sizeof(double));
    double *sig = calloc((size_t)(ns * m->nnodes), sizeof(double));
    double *f = NULL;

    CX_CHECK_OK(cx_fem_assemble_stiffness(m, &mat, &Kall, &d));
    CX_CHECK_OK(cx_dofmap_init(&map, nall));
    for (int b = 0; b < m->nbounds; b++)
        for (int c = 0; c < dim; c++)
            CX_CHECK_OK(cx_dofmap_fix(&map, m, &m->bounds[b], c, 0.0));
    CX_CHECK_OK(cx_dofmap_finish(&map));
    /* the fix above puts every boundary dof to 0; the patch needs u(x) there */
    for (int k = 0; k < m->nnodes; k++) {
        double u[3];
        exact(dim, m->x + dim * k, u);
        for (int c = 0; c < dim; c++)
            if (map.free_of[dim * k + c] < 0)
                map.value[dim * k + c] = u[c];
    }
    CX_CHECK(map.nfree > 0 && map.nfree < nall);
    f = calloc((size_t)map.nfree, sizeof(double));
    CX_CHECK_OK(cx_fem_reduce(&Kall, fall, &map, &K, f));

    CX_CHECK_OK(dense_solve(&K, f));
    cx_fem_expand(&map, f, uall);

    double umax = 0, err = 0;
    for (int k = 0; k < m->nnodes; k++) {
        double u[3];
        exact(dim, m->x + dim * k, u);
        for (int c = 0; c < dim; c++) {
            umax = fmax(umax, fabs(u[c]));
            err = fmax(err, fabs(uall[dim * k + c] - u[c]));
        }
    }
    fprintf(stderr, "%-28s %5d free dofs: max |u - u_exact| = %.2e of max |u| %.2e\n", label,
            map.nfree, err, umax);
    CX_CHECK_NEAR(err, 0, 0, 1e-10 * umax);

    /* stresses: D eps with eps from A (engineering shear) */
    double eps[6], D[36], s_ex[6];
    if (dim == 2) {
        eps[0] = A3[0][0], eps[1] = A3[1][1], eps[2] = A3[0][1] + A3[1][0];
    } else {
        eps[0] = A3[0][0], eps[1] = A3[1][1], eps[2] = A3[2][2];
        eps[3] = A3[1][2] + A3[2][1], eps[4] = A3[0][2] + A3[2][0], eps[5] = A3[0][1] + A3[1][0];
    }
    cx_fem_elasticity(&mat, D);
    double smax = 0;
    for (int r = 0; r < ns; r++) {
        s_ex[r] = 0;
        for (int k = 0; k < ns; k++)
            s_ex[r] += D[ns * r + k] * eps[k];
        smax = fmax(smax, fabs(s_ex[r]));
    }
    CX_CHECK_OK(cx_fem_nodal_stress(m, &mat, uall, sig));
    double serr = 0;
    for (int k = 0; k < m->nnodes; k++)
        for (int r = 0; r < ns; r++)
            serr = fmax(serr, fabs(sig[ns * k + r] - s_ex[r]));
    CX_CHECK_NEAR(serr, 0, 0, 1e-9 * smax);

    cx_csc_clear(&Kall);
    cx_csc_clear(&K);
    cx_dofmap_clear(&map);
    free(fall);
    free(uall);
    free(sig);
    free(f);
}

/* Non-P1 stresses are taken at each node, not at a centre: u = (x y, 0) on
 * a 2 x 1 QUAD4 grid is bilinear, so exx = y and sxx = D00 y exactly at
 * every node (both elements agree on the shared ones), while syy = D10 y
 * and sxy = D22 x. */
static void test_nodal_positions(void)
{
    cx_mesh *m = NULL;
    cx_material mat = fx_material(CX_PLANE_STRESS);
    double D[9], u[12], sig[18];
    CX_CHECK_OK(cx_mesh_rectangle(&m, 0, 0, 2, 1, 2, 1, CX_EL_QUAD4, NULL));
    if (!m)
        return;
    cx_fem_elasticity(&mat, D);
    for (int k = 0; k < 6; k++)
        u[2 * k] = m->x[2 * k] * m->x[2 * k + 1], u[2 * k + 1] = 0;
    CX_CHECK_OK(cx_fem_nodal_stress(m, &mat, u, sig));
    for (int k = 0; k < 6; k++) {
        double x = m->x[2 * k], y = m->x[2 * k + 1];
        CX_CHECK_NEAR(sig[3 * k], D[0] * y, 1e-14, 1e-14);
        CX_CHECK_NEAR(sig[3 * k + 1], D[3] * y, 1e-14, 1e-14);
        CX_CHECK_NEAR(sig[3 * k + 2], D[8] * x, 1e-14, 1e-14);
    }
    cx_mesh_destroy(&m);
}

int main(void)
{
    test_nodal_positions();
    long live = cx_alloc_live();
    static const struct {
        cx_elem_type t;
        int straight;
    } types[] = {
        {CX_EL_TRI3, 1}, {CX_EL_TRI6, 1}, {CX_EL_TRI6, 0}, {CX_EL_QUAD4, 1}, {CX_EL_HEX8, 1}, {CX_EL_TET4, 1},
    };
    for (size_t k = 0; k < sizeof types / sizeof types[0]; k++) {
        cx_elem_type t = types[k].t;
        cx_model models[2] = {CX_PLANE_STRAIN, CX_PLANE_STRESS};
        int nm = cx_elem_dim(t) == 2 ? 2 : 1;
        if (nm == 1)
            models[0] = CX_SOLID;
        for (int j = 0; j < nm; j++) {
            char label[64];
            snprintf(label, sizeof label, "%s%s %s", cx_elem_name(t), types[k].straight ? "" : " curved",
                     models[j] == CX_SOLID ? "3d" : models[j] == CX_PLANE_STRAIN ? "strain" : "stress");
            cx_mesh *m = fx_mesh(t, types[k].straight);
            CX_CHECK(m != NULL);
            if (m)
                run_patch(label, m, models[j]);
            cx_mesh_destroy(&m);
        }
    }
    cx_elem_type t2[3] = {CX_EL_TRI3, CX_EL_TRI6, CX_EL_QUAD4};
    for (int k = 0; k < 3; k++) {
        cx_mesh *m = NULL;
        char label[64];
        snprintf(label, sizeof label, "hertz %s strain", cx_elem_name(t2[k]));
        CX_CHECK_OK(cx_mesh_hertz(&m, 2.0, 6, t2[k], NULL));
        if (m)
            run_patch(label, m, CX_PLANE_STRAIN);
        cx_mesh_destroy(&m);
    }
    CX_CHECK(cx_alloc_live() == live);
    return check_finish("fem_patch");
}
