/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Dense vector kernels. */
#include "linalg/linalg.h"

#include <math.h>

double cx_vec_dot(int n, const double *x, const double *y)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += x[i] * y[i];
    return s;
}

double cx_vec_norm2(int n, const double *x) { return sqrt(cx_vec_dot(n, x, x)); }

double cx_vec_norminf(int n, const double *x)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s = fmax(s, fabs(x[i]));
    return s;
}

void cx_vec_axpy(int n, double a, const double *x, double *y)
{
    for (int i = 0; i < n; i++)
        y[i] += a * x[i];
}

int cx_vec_finite(int n, const double *x)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}
