/* SPDX-License-Identifier: GPL-3.0-or-later */
/* material.c: the D matrices against hand values (E = 2.6, nu = 0.3:
 * mu = 1, plane-strain lambda = 1.5, plane-stress E/(1 - nu^2) = 2.857...),
 * plane stress as the 3D law with szz = 0 (static condensation of D), and
 * von Mises: uniaxial |s| (plane stress and 3D, both signs), plane-strain
 * uniaxial |s| sqrt(1 - nu + nu^2), pure shear sqrt(3) |t|, hydrostatic 0. */
#include "fem/fem.h"
#include "check.h"

static void test_d(void)
{
    double D[36];
    cx_material m = {.E = 2.6, .nu = 0.3, .model = CX_PLANE_STRAIN};
    CX_CHECK(cx_fem_nstress(2) == 3 && cx_fem_nstress(3) == 6);
    cx_fem_elasticity(&m, D);
    double strain[9] = {3.5, 1.5, 0, 1.5, 3.5, 0, 0, 0, 1};   /* lambda + 2 mu, lambda, mu */
    for (int k = 0; k < 9; k++)
        CX_CHECK_NEAR(D[k], strain[k], 1e-14, 1e-15);

    m.model = CX_PLANE_STRESS;
    cx_fem_elasticity(&m, D);
    double c = 2.6 / (1 - 0.09);
    double stress[9] = {c, 0.3 * c, 0, 0.3 * c, c, 0, 0, 0, 1};
    for (int k = 0; k < 9; k++)
        CX_CHECK_NEAR(D[k], stress[k], 1e-14, 1e-15);

    /* 3D, and condensing szz = 0 out of it gives plane stress */
    m.model = CX_SOLID;
    double D3[36];
    cx_fem_elasticity(&m, D3);
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
            double want = i < 3 && j < 3 ? (i == j ? 3.5 : 1.5) : (i == j ? 1 : 0);
            CX_CHECK_NEAR(D3[6 * i + j], want, 1e-14, 1e-15);
        }
    int idx[2] = {0, 1};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double cond = D3[6 * idx[i] + idx[j]] - D3[6 * idx[i] + 2] * D3[12 + idx[j]] / D3[14];
            CX_CHECK_NEAR(cond, stress[3 * i + j], 1e-14, 0);
        }
}

static void test_von_mises(void)
{
    cx_material ps = {.E = 1, .nu = 0.3, .model = CX_PLANE_STRESS};
    cx_material pe = {.E = 1, .nu = 0.3, .model = CX_PLANE_STRAIN};
    cx_material s3 = {.E = 1, .nu = 0.3, .model = CX_SOLID};
    double u2[3] = {-7.5, 0, 0}, u2y[3] = {0, 4, 0}, shear2[3] = {0, 0, 2};
    CX_CHECK_NEAR(cx_fem_von_mises(&ps, u2), 7.5, 1e-15, 0);
    CX_CHECK_NEAR(cx_fem_von_mises(&ps, u2y), 4, 1e-15, 0);
    CX_CHECK_NEAR(cx_fem_von_mises(&ps, shear2), 2 * sqrt(3), 1e-15, 0);
    CX_CHECK_NEAR(cx_fem_von_mises(&pe, u2), 7.5 * sqrt(1 - 0.3 + 0.09), 1e-15, 0);
    for (int k = 0; k < 3; k++) {
        double s[6] = {0}, t[6] = {0};
        s[k] = k == 1 ? -3 : 3;
        t[3 + k] = 1.5;
        CX_CHECK_NEAR(cx_fem_von_mises(&s3, s), 3, 1e-15, 0);
        CX_CHECK_NEAR(cx_fem_von_mises(&s3, t), 1.5 * sqrt(3), 1e-15, 0);
    }
    double hydro[6] = {-2, -2, -2, 0, 0, 0};
    CX_CHECK_NEAR(cx_fem_von_mises(&s3, hydro), 0, 0, 1e-15);
    /* equal biaxial s in plane strain: szz = 2 nu s = 0.6 s, vm = |s - szz| = 0.4 |s| */
    double bi[3] = {5, 5, 0};
    CX_CHECK_NEAR(cx_fem_von_mises(&pe, bi), 0.4 * 5, 1e-14, 0);
}

int main(void)
{
    test_d();
    test_von_mises();
    return check_finish("fem_material");
}
