/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Isotropic linear elasticity: the matrix D of sigma = D eps in Voigt
 * notation with engineering shear strains, and the von Mises stress. */
#include "fem/fem.h"

#include <math.h>
#include <string.h>

int cx_fem_nstress(int dim) { return dim == 3 ? 6 : 3; }

void cx_fem_elasticity(const cx_material *mat, double *D)
{
    double E = mat->E, nu = mat->nu;
    double mu = E / (2 * (1 + nu));
    if (mat->model == CX_SOLID) {
        double lam = E * nu / ((1 + nu) * (1 - 2 * nu));
        memset(D, 0, 36 * sizeof(double));
        for (int i = 0; i < 3; i++) {
            for (int j = 0; j < 3; j++)
                D[6 * i + j] = lam;
            D[6 * i + i] = lam + 2 * mu;
            D[6 * (i + 3) + i + 3] = mu;
        }
        return;
    }
    /* plane stress is the 3D law with szz = 0, which replaces lambda by
     * 2 mu lambda / (lambda + 2 mu) = E nu / (1 - nu^2); plane strain keeps
     * lambda (ezz = 0) */
    double lam = mat->model == CX_PLANE_STRESS ? E * nu / (1 - nu * nu)
                                                : E * nu / ((1 + nu) * (1 - 2 * nu));
    D[0] = lam + 2 * mu, D[1] = lam, D[2] = 0;
    D[3] = lam, D[4] = lam + 2 * mu, D[5] = 0;
    D[6] = 0, D[7] = 0, D[8] = mu;
}

double cx_fem_von_mises(const cx_material *mat, const double *sig)
{
    double sxx, syy, szz, syz, sxz, sxy;
    if (mat->model == CX_SOLID) {
        sxx = sig[0], syy = sig[1], szz = sig[2], syz = sig[3], sxz = sig[4], sxy = sig[5];
    } else {
        sxx = sig[0], syy = sig[1], sxy = sig[2], syz = 0, sxz = 0;
        szz = mat->model == CX_PLANE_STRAIN ? mat->nu * (sxx + syy) : 0;
    }
    double a = sxx - syy, b = syy - szz, c = szz - sxx;
    return sqrt(0.5 * (a * a + b * b + c * c) + 3 * (syz * syz + sxz * sxz + sxy * sxy));
}
