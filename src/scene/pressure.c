/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The error of the contact pressure against Hertz's (2D scenes with a
 * [hertz] section): nodal contact force over lumped length, against
 * p(x) on the x axis, in the L2 norm. */
#include "scene/scene.h"

#include <math.h>

int cx_scene_pressure_error(const cx_scene *s, const cx_problem *p, const double *lN,
                            double *abs_err, double *rel_err)
{
    if (!s->has_hertz || p->dim != 2 || p->m < 2)
        return CX_EUNSUPPORTED;
    /* trapezoidal rule over the contact points, which the contact set
     * orders along the arc (x increasing from the symmetry axis) */
    double e2 = 0;
    const cx_contact_set *c = &p->contact;
    for (int i = 0; i + 1 < p->m; i++) {
        double xa = c->x[2 * i], xb = c->x[2 * (i + 1)];
        double ea = lN[i] / c->weight[i] - cx_scene_hertz_pressure(s, xa);
        double eb = lN[i + 1] / c->weight[i + 1] - cx_scene_hertz_pressure(s, xb);
        e2 += 0.5 * (ea * ea + eb * eb) * fabs(xb - xa);
    }
    /* ||p||^2 on x >= 0: (2P / (pi b^2))^2 * 2 b^3 / 3 */
    double b = cx_scene_hertz_halfwidth(s);
    double c0 = 2 * s->hertz_P / (CX_PI * b * b);
    double p2 = c0 * c0 * 2 * b * b * b / 3;
    *abs_err = sqrt(e2);
    *rel_err = sqrt(e2 / p2);
    return CX_OK;
}
