/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Hertz's solution for a long elastic cylinder (radius R, load P per unit
 * length) pressed onto a rigid plane, the reference of paper 002 §7.1
 * (Johnson, Contact Mechanics, §4.2): contact half-width
 *     b = 2 sqrt(P R / (pi E*)),  E* = E / (1 - nu^2) in plane strain,
 * and the elliptical pressure p(x) = 2P / (pi b^2) sqrt(b^2 - x^2). The
 * rigid plane contributes nothing to E*. In plane stress (a thin disc) the
 * out-of-plane strain is free, and E* = E. */
#include "scene/scene.h"

#include <math.h>

/* 3D (a ball of radius R, load P, on a rigid plane; Johnson §4.2.1):
 * contact radius a = (3 P R / (4 E*))^(1/3), E* = E / (1 - nu^2), and
 * p(r) = p0 sqrt(1 - r^2 / a^2) with p0 = 3 P / (2 pi a^2), r the distance
 * from the axis x = y = 0. */
double cx_scene_hertz_halfwidth(const cx_scene *s)
{
    if (!s->has_hertz || !(s->mat.E > 0))
        return 0;
    if (s->dim == 3)
        return cbrt(3 * s->hertz_P * s->hertz_R * (1 - s->mat.nu * s->mat.nu) / (4 * s->mat.E));
    double nu2 = s->mat.model == CX_PLANE_STRESS ? 0 : s->mat.nu * s->mat.nu;
    return 2 * sqrt(s->hertz_P * s->hertz_R * (1 - nu2) / (CX_PI * s->mat.E));
}

double cx_scene_hertz_pressure(const cx_scene *s, double x)
{
    double b = cx_scene_hertz_halfwidth(s);
    if (!(b > 0) || !(fabs(x) < b))
        return 0;
    if (s->dim == 3)
        return 3 * s->hertz_P / (2 * CX_PI * b * b) * sqrt(1 - x * x / (b * b));
    return 2 * s->hertz_P / (CX_PI * b * b) * sqrt(b * b - x * x);
}
