/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Rigid obstacles: gap and normal of a point. */
#include "contact/contact.h"

#include <math.h>
#include <string.h>

static const char *const obstacle_names[] = {"plane", "disc", "cylinder", "sphere"};

const char *cx_obstacle_name(cx_obstacle_kind k)
{
    return (unsigned)k < 4 ? obstacle_names[k] : "?";
}

int cx_obstacle_from_name(const char *name)
{
    for (int k = 0; k < 4; k++)
        if (strcmp(name, obstacle_names[k]) == 0)
            return k;
    return -1;
}

static double dot(int dim, const double *a, const double *b)
{
    double s = 0;
    for (int k = 0; k < dim; k++)
        s += a[k] * b[k];
    return s;
}

void cx_tangent_basis(int dim, const double *n, double *t)
{
    if (dim == 2) {
        t[0] = -n[1];
        t[1] = n[0];
        return;
    }
    /* t1 = n x e with e the axis least aligned with n, t2 = n x t1, so
     * that t1 x t2 = n. */
    int a = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(n[k]) < fabs(n[a]))
            a = k;
    double e[3] = {0, 0, 0};
    e[a] = 1;
    double t1[3] = {n[1] * e[2] - n[2] * e[1], n[2] * e[0] - n[0] * e[2], n[0] * e[1] - n[1] * e[0]};
    double l = sqrt(dot(3, t1, t1));
    for (int k = 0; k < 3; k++)
        t1[k] /= l;
    double t2[3] = {n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2], n[0] * t1[1] - n[1] * t1[0]};
    memcpy(t, t1, sizeof t1);
    memcpy(t + 3, t2, sizeof t2);
}

/* Smallest t >= -inf with a t^2 + 2 b t + q = 0 (a > 0): where a ray from
 * outside first meets a circle, sphere or cylinder; +inf if it misses. */
static double ray_hit(double a, double b, double q)
{
    double disc = b * b - a * q;
    if (a <= 0 || disc < 0)
        return INFINITY;
    return (-b - sqrt(disc)) / a;
}

int cx_obstacle_gap(const cx_obstacle *ob, int dim, const double *x, double *gap, double *normal)
{
    double dlen = sqrt(dot(dim, ob->direction, ob->direction));
    int along = dlen > 0;
    double w[3];
    for (int k = 0; k < dim; k++)
        w[k] = x[k] - ob->point[k];

    switch (ob->kind) {
    case CX_OBST_PLANE: {
        double d = dot(dim, w, ob->normal);
        if (along) {
            double cosang = -dot(dim, ob->direction, ob->normal) / dlen;
            *gap = cosang > 0 ? d / cosang : INFINITY;
            for (int k = 0; k < dim; k++)
                normal[k] = ob->direction[k] / dlen;
        } else {
            *gap = d;
            for (int k = 0; k < dim; k++)
                normal[k] = -ob->normal[k];
        }
        return CX_OK;
    }
    case CX_OBST_DISC:
    case CX_OBST_SPHERE:
    case CX_OBST_CYLINDER: {
        if (ob->kind == CX_OBST_CYLINDER) {
            double a = dot(dim, w, ob->normal);
            for (int k = 0; k < dim; k++)
                w[k] -= a * ob->normal[k];
        }
        double len = sqrt(dot(dim, w, w));
        if (along) {
            /* w and the direction projected off the axis for a cylinder */
            double dir[3];
            for (int k = 0; k < dim; k++)
                dir[k] = ob->direction[k] / dlen;
            if (ob->kind == CX_OBST_CYLINDER) {
                double a = dot(dim, dir, ob->normal);
                for (int k = 0; k < dim; k++)
                    dir[k] -= a * ob->normal[k];
            }
            *gap = ray_hit(dot(dim, dir, dir), dot(dim, dir, w), len * len - ob->radius * ob->radius);
            for (int k = 0; k < dim; k++)
                normal[k] = ob->direction[k] / dlen;
        } else {
            if (len == 0)
                return CX_EINVAL;
            *gap = len - ob->radius;
            for (int k = 0; k < dim; k++)
                normal[k] = -w[k] / len;
        }
        return CX_OK;
    }
    }
    return CX_EINVAL;
}
