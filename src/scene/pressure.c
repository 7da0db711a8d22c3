/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The error of the contact pressure against Hertz's (2D scenes with a
 * [hertz] section): nodal contact force over lumped length, against
 * p(x) on the x axis, in the L2 norm. */
#include "scene/scene.h"

#include <math.h>

/* 3D: the points' pressure (nodal force over lumped area) against p(r),
 * in the L2 norm over the contact boundary by the same lumped areas,
 * relative to Hertz's over the quarter disc r < a that the model holds
 * (an eighth of the ball: symmetry planes x = 0 and y = 0):
 * ||p||^2 = pi p0^2 a^2 / 8. */
static int pressure_error_3d(const cx_scene *s, const cx_problem *p, const double *lN,
                             double *abs_err, double *rel_err)
{
    const cx_contact_set *c = &p->contact;
    double e2 = 0;
    for (int i = 0; i < p->m; i++) {
        double r = hypot(c->x[3 * i], c->x[3 * i + 1]);
        double e = lN[i] / c->weight[i] - cx_scene_hertz_pressure(s, r);
        e2 += e * e * c->weight[i];
    }
    double a = cx_scene_hertz_halfwidth(s), p0 = cx_scene_hertz_pressure(s, 0);
    double p2 = CX_PI * p0 * p0 * a * a / 8;
    *abs_err = sqrt(e2);
    *rel_err = sqrt(e2 / p2);
    return CX_OK;
}

double cx_scene_contact_radius(const cx_scene *s, const cx_problem *p, const double *lN)
{
    (void)s;
    const cx_contact_set *c = &p->contact;
    if (p->dim != 3 || p->m < 1)
        return 0;
    /* weighted least squares of p^2 = k (a^2 - r^2) over the points in
     * contact: p^2 = alpha + beta r^2, a^2 = -alpha / beta */
    double pmax = 0;
    for (int i = 0; i < p->m; i++)
        pmax = fmax(pmax, lN[i] / c->weight[i]);
    double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < p->m; i++) {
        double pi = lN[i] / c->weight[i];
        if (!(pi > 1e-8 * pmax))
            continue;
        double r2 = c->x[3 * i] * c->x[3 * i] + c->x[3 * i + 1] * c->x[3 * i + 1];
        double w = c->weight[i];
        sw += w, sx += w * r2, sy += w * pi * pi, sxx += w * r2 * r2, sxy += w * r2 * pi * pi;
    }
    double den = sw * sxx - sx * sx;
    if (!(sw > 0) || !(fabs(den) > 0))
        return 0;
    double beta = (sw * sxy - sx * sy) / den, alpha = (sy - beta * sx) / sw;
    return beta < 0 && alpha > 0 ? sqrt(-alpha / beta) : 0;
}

int cx_scene_pressure_error(const cx_scene *s, const cx_problem *p, const double *lN,
                            double *abs_err, double *rel_err)
{
    if (s->has_hertz && p->dim == 3 && p->m >= 1)
        return pressure_error_3d(s, p, lN, abs_err, rel_err);
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
