/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Geometric checks shared by the mesh tests: element orientation, measure,
 * and the outward orientation of boundary facets. */
#ifndef CX_TEST_MESH_CHECK_H
#define CX_TEST_MESH_CHECK_H

#include "mesh/mesh.h"

#include <math.h>
#include <stdlib.h>

static const double *mc_node(const cx_mesh *m, int k) { return m->x + m->dim * k; }

static double mc_cross2(const double *o, const double *a, const double *b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

static double mc_triple(const double *o, const double *a, const double *b, const double *c)
{
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++)
        u[k] = a[k] - o[k], v[k] = b[k] - o[k], w[k] = c[k] - o[k];
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]);
}

/* The smallest corner measure of element e, relative to its size: > 0 when
 * every corner turns counter-clockwise (2D) or is right-handed (3D). */
static double mc_min_corner(const cx_mesh *m, int e)
{
    const int *c = m->conn + m->npe * e;
    double best = INFINITY;
    switch (m->etype) {
    case CX_EL_TRI3:
    case CX_EL_TRI6:
    case CX_EL_QUAD4: {
        int nv = m->etype == CX_EL_QUAD4 ? 4 : 3;
        for (int a = 0; a < nv; a++)
            best = fmin(best, mc_cross2(mc_node(m, c[a]), mc_node(m, c[(a + 1) % nv]),
                                        mc_node(m, c[(a + nv - 1) % nv])));
        break;
    }
    case CX_EL_TET4:
        best = mc_triple(mc_node(m, c[0]), mc_node(m, c[1]), mc_node(m, c[2]), mc_node(m, c[3]));
        break;
    case CX_EL_HEX8: {
        /* each corner with its x-, y- and z-neighbours in reference order */
        static const int nb[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
                                     {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
        for (int a = 0; a < 8; a++)
            best = fmin(best, mc_triple(mc_node(m, c[a]), mc_node(m, c[nb[a][0]]),
                                        mc_node(m, c[nb[a][1]]), mc_node(m, c[nb[a][2]])));
        break;
    }
    }
    return best;
}

/* Total area (TRI3/TRI6 by their vertices, QUAD4 by the shoelace) or
 * volume (TET4; HEX8 from the edges at corner 0: exact for boxes). */
static double mc_measure(const cx_mesh *m)
{
    double s = 0;
    for (int e = 0; e < m->nelems; e++) {
        const int *c = m->conn + m->npe * e;
        if (m->etype == CX_EL_TRI3 || m->etype == CX_EL_TRI6)
            s += 0.5 * mc_cross2(mc_node(m, c[0]), mc_node(m, c[1]), mc_node(m, c[2]));
        else if (m->etype == CX_EL_QUAD4)
            s += 0.5 * (mc_cross2(mc_node(m, c[0]), mc_node(m, c[1]), mc_node(m, c[2])) +
                        mc_cross2(mc_node(m, c[0]), mc_node(m, c[2]), mc_node(m, c[3])));
        else if (m->etype == CX_EL_TET4)
            s += mc_triple(mc_node(m, c[0]), mc_node(m, c[1]), mc_node(m, c[2]), mc_node(m, c[3])) / 6;
        else
            s += mc_triple(mc_node(m, c[0]), mc_node(m, c[1]), mc_node(m, c[3]), mc_node(m, c[4]));
    }
    return s;
}

/* 1 if every node is used by some element. */
static int mc_all_nodes_used(const cx_mesh *m)
{
    char *used = calloc((size_t)m->nnodes, 1);
    int ok = 1;
    for (int k = 0; k < m->npe * m->nelems; k++)
        used[m->conn[k]] = 1;
    for (int k = 0; k < m->nnodes; k++)
        ok &= used[k];
    free(used);
    return ok;
}

/* Run gen with the n-th allocation failing, n = 0, 1, ...: each failure
 * must be CX_ENOMEM with nothing leaked, until gen succeeds. Returns the
 * number of failure points, or -1 on a wrong status or a leak. */
#define MC_ALLOC_LOOP(result, gen)                                          \
    do {                                                                    \
        (result) = 0;                                                       \
        for (long n_ = 0; n_ < 1000; n_++) {                                \
            cx_mesh *am_ = NULL;                                            \
            long live_ = cx_alloc_live();                                   \
            cx_alloc_fail_after(n_);                                        \
            int st_ = (gen);                                                \
            cx_alloc_fail_after(-1);                                        \
            if (st_ == CX_OK) {                                             \
                cx_mesh_destroy(&am_);                                      \
                break;                                                      \
            }                                                               \
            if (st_ != CX_ENOMEM || am_ != NULL || cx_alloc_live() != live_) { \
                (result) = -1;                                              \
                break;                                                      \
            }                                                               \
            (result)++;                                                     \
        }                                                                   \
    } while (0)

/* Number of facets of b whose outward normal (right of the edge in 2D,
 * right-hand rule in 3D) does not point away from the centroid of the
 * element that owns the facet, or that belong to no element. */
static int mc_bad_facets(const cx_mesh *m, const cx_boundary *b)
{
    int bad = 0, dim = m->dim;
    for (int f = 0; f < b->nfacets; f++) {
        const int *fn = b->facets + b->npf * f;
        int owner = -1;
        for (int e = 0; e < m->nelems && owner < 0; e++) {
            int hits = 0;
            for (int a = 0; a < b->npf; a++)
                for (int k = 0; k < m->npe; k++)
                    hits += m->conn[m->npe * e + k] == fn[a];
            if (hits == b->npf)
                owner = e;
        }
        if (owner < 0) {
            bad++;
            continue;
        }
        double fc[3] = {0}, ec[3] = {0}, n[3] = {0};
        for (int a = 0; a < b->npf; a++)
            for (int k = 0; k < dim; k++)
                fc[k] += mc_node(m, fn[a])[k] / b->npf;
        for (int a = 0; a < m->npe; a++)
            for (int k = 0; k < dim; k++)
                ec[k] += mc_node(m, m->conn[m->npe * owner + a])[k] / m->npe;
        const double *p0 = mc_node(m, fn[0]), *p1 = mc_node(m, fn[1]);
        if (dim == 2) {
            n[0] = p1[1] - p0[1];
            n[1] = -(p1[0] - p0[0]);
        } else {
            const double *p2 = mc_node(m, fn[b->npf - 1]);   /* the node before p0 */
            double u[3], v[3];
            for (int k = 0; k < 3; k++)
                u[k] = p1[k] - p0[k], v[k] = p2[k] - p0[k];
            n[0] = u[1] * v[2] - u[2] * v[1];
            n[1] = u[2] * v[0] - u[0] * v[2];
            n[2] = u[0] * v[1] - u[1] * v[0];
        }
        double dot = 0;
        for (int k = 0; k < dim; k++)
            dot += n[k] * (fc[k] - ec[k]);
        if (!(dot > 0))
            bad++;
    }
    return bad;
}

#endif
