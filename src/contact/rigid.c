/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Contact points of a boundary against a rigid obstacle: one point per
 * boundary node, with its normal and tangent rows, gap and lumped weight. */
#include "contact/contact_impl.h"
#include "fem/fem.h"

#include <math.h>
#include <string.h>

/* contact_impl.h */
int contact_order_2d_chain(const cx_boundary *b, int nnodes, int *order, int *facet_of, int *seen)
{
    int npf = b->npf, placed = 0, start = -1;
    for (int k = 0; k < nnodes; k++)
        facet_of[k] = -1, seen[k] = 0;
    for (int f = 0; f < b->nfacets; f++) {
        facet_of[b->facets[npf * f]] = f;
        seen[b->facets[npf * f + 1]] = 1;   /* ends a facet */
    }
    for (int f = 0; f < b->nfacets && start < 0; f++)
        if (!seen[b->facets[npf * f]])
            start = f;
    if (start < 0)
        return 0;
    for (int k = 0; k < nnodes; k++)
        seen[k] = 0;
    for (int f = start, steps = 0; f >= 0 && steps < b->nfacets; steps++) {
        int seq[3] = {b->facets[npf * f], npf == 3 ? b->facets[npf * f + 2] : -1,
                      b->facets[npf * f + 1]};
        for (int s = 0; s < 3; s++)
            if (seq[s] >= 0 && !seen[seq[s]]) {
                seen[seq[s]] = 1;
                order[placed++] = seq[s];
            }
        f = facet_of[b->facets[npf * f + 1]];
    }
    return placed;
}

/* 3D contact faces: the nodes by z, then y, then x (rows of a grid).
 * ks: count elements of workspace. */
static void sort_by_coords(int *order, int count, const double *x, cx_sort_key *ks)
{
    for (int i = 0; i < count; i++) {
        const double *xi = x + 3 * order[i];
        ks[i] = (cx_sort_key){{xi[2], xi[1], xi[0]}, order[i]};
    }
    cx_sort_keys(ks, (size_t)count);
    for (int i = 0; i < count; i++)
        order[i] = ks[i].id;
}

static double mesh_size(const cx_mesh *m)
{
    double diag = 0;
    for (int k = 0; k < m->dim; k++) {
        double lo = INFINITY, hi = -INFINITY;
        for (int i = 0; i < m->nnodes; i++) {
            /* comparisons, not fmin/fmax calls (over every node): a NaN is
             * passed over by both alike */
            double v = m->x[m->dim * i + k];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        diag += (hi - lo) * (hi - lo);
    }
    return sqrt(diag);
}

int cx_contact_from_obstacle(cx_contact_set *cs, const cx_mesh *m, const cx_boundary *b,
                             const cx_obstacle *ob, cx_diag *d)
{
    int dim = m->dim, count = 0, status = CX_OK;
    int *nodes = NULL, *order = NULL, *facet_of = NULL, *seen = NULL, *pos = NULL;
    memset(cs, 0, sizeof *cs);

    /* ---- the points, in boundary order ---- */
    CX_TRY(cx_boundary_nodes(b, &nodes, &count));
    order = CX_NEW(int, count);
    facet_of = CX_NEW(int, m->nnodes);
    seen = CX_NEW(int, m->nnodes);
    pos = CX_NEW(int, m->nnodes);
    if (!order || !facet_of || !seen || !pos) {
        status = CX_ENOMEM;
        goto fail;
    }
    if (dim == 2 && contact_order_2d_chain(b, m->nnodes, order, facet_of, seen) == count) {
        /* order[] holds the chain */
    } else {
        memcpy(order, nodes, sizeof(int) * (size_t)count);
        if (dim == 3) {
            cx_sort_key *ks = CX_NEW(cx_sort_key, count);
            if (!ks) {
                status = CX_ENOMEM;
                goto fail;
            }
            sort_by_coords(order, count, m->x, ks);
            cx_free(ks);
        }
    }

    if ((status = contact_alloc(cs, dim, count, dim * m->nnodes, (size_t)(dim * count),
                                (size_t)(dim * (dim - 1) * count))))
        goto fail;

    /* ---- lumped weights: the share of each facet's measure ---- */
    for (int k = 0; k < m->nnodes; k++)
        pos[k] = -1;
    for (int i = 0; i < count; i++)
        pos[order[i]] = i;
    contact_weights(cs->weight, m, b, pos);

    /* ---- gap, normal, tangents and rows ---- */
    double tol = 1e-12 * mesh_size(m), far = 1e3 * mesh_size(m);
    for (int i = 0; i < count; i++) {
        int k = order[i];
        const double *x = m->x + dim * k;
        double *n = cs->normal + dim * i, *t = cs->tangent + dim * (dim - 1) * i;
        cs->node[i] = k;
        memcpy(cs->x + dim * i, x, sizeof(double) * (size_t)dim);
        double g;
        if (cx_obstacle_gap(ob, dim, x, &g, n) != CX_OK) {
            status = cx_diag_set(d, CX_EINVAL, "contact point %d (node %d) is at the centre of the %s obstacle",
                                 i, k, cx_obstacle_name(ob->kind));
            goto fail;
        }
        if (g < -tol) {
            status = cx_diag_set(d, CX_EINVAL,
                                 "contact point %d (node %d at (%g, %g, %g)) penetrates the %s obstacle by %g",
                                 i, k, x[0], x[1], dim == 3 ? x[2] : 0.0, cx_obstacle_name(ob->kind), -g);
            goto fail;
        }
        /* a point the obstacle can never reach along the given direction
         * keeps a finite, far gap so that every number stays finite */
        cs->gap[i] = g < 0 ? 0 : (isfinite(g) ? g : far);
        cx_tangent_basis(dim, n, t);
        /* exact zeros stay out of the pattern: a row that touches only a
         * prescribed dof must come out empty, not as a zero row */
        for (int c = 0; c < dim; c++) {
            if (n[c] != 0 && (status = cx_triplet_add(&cs->N, i, dim * k + c, n[c])))
                goto fail;
            for (int r = 0; r < dim - 1; r++)
                if (t[dim * r + c] != 0 &&
                    (status = cx_triplet_add(&cs->T, (dim - 1) * i + r, dim * k + c, t[dim * r + c])))
                    goto fail;
        }
    }
    cx_free(nodes);
    cx_free(order);
    cx_free(facet_of);
    cx_free(seen);
    cx_free(pos);
    return CX_OK;

fail:
    cx_free(nodes);
    cx_free(order);
    cx_free(facet_of);
    cx_free(seen);
    cx_free(pos);
    cx_contact_clear(cs);
    if (status == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "out of memory building contact rows");
    return status;
}
