/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Two-body node-to-segment contact rows (paper 000 §3), 2D.
 *
 * Every node x of the slave boundary (body 1 in the paper) that has a free
 * dof (000 §3: the contact nodes lie on Gamma_c minus Gamma_u) is paired
 * with chi(x), its closest point on the master boundary (body 2), which
 * lies on a master segment [x_p, x_q] at delta = |chi - x_p| / |x_q - x_p|.
 * The gap is d = |chi(x) - x|, the critical direction nu = (chi - x) / d,
 * or the slave's outward normal n^1 where d = 0, and t is nu turned by
 * +90 degrees. With u^1 - u^2(chi) the relative displacement,
 *     N row:  nu at x's dofs, -(1 - delta) nu at x_p's, -delta nu at x_q's,
 *     T row:  the same with t,
 * at most 2 + 4 non-zeros (exact zeros, e.g. delta = 0 on matching meshes,
 * stay out of the pattern). Closing the gap is positive: N u - d <= 0.
 *
 * The pairing is a projection onto the master's segments, so a curved
 * slave (a punch's rounded corner) or a curved master pairs each node with
 * the nearest point of the master, wherever it lies; the points are listed
 * in their order along the slave boundary (the chain of its facets, walked
 * from the end with the smaller x; by x then y only when the boundary is
 * not one open chain). A P2 (3-node) edge
 * is taken as its two straight halves, end-mid and mid-end, on both sides. */
#include "contact/contact_impl.h"
#include "fem/fem.h"

#include <math.h>
#include <string.h>

/* Slave nodes by x, then y: the order when the slave is not one chain. */
static int seg_sort(int *nodes, int count, const double *x)
{
    cx_sort_key *ks = CX_NEW(cx_sort_key, count);
    if (!ks)
        return CX_ENOMEM;
    for (int i = 0; i < count; i++)
        ks[i] = (cx_sort_key){{x[2 * nodes[i]], x[2 * nodes[i] + 1], 0}, nodes[i]};
    cx_sort_keys(ks, (size_t)count);
    for (int i = 0; i < count; i++)
        nodes[i] = ks[i].id;
    cx_free(ks);
    return CX_OK;
}

/* The straight segments of a boundary, 2 node ids each in the facet's
 * direction: a 2-node edge as it is, a 3-node edge (ends, then mid) as
 * its two halves. *segs (cx_free), *count. */
static int seg_segments(const cx_boundary *b, int **segs, int *count)
{
    int per = b->npf == 3 ? 2 : 1;
    int *s = CX_NEW(int, 2 * per * (b->nfacets > 0 ? b->nfacets : 1));
    if (!s)
        return CX_ENOMEM;
    for (int f = 0; f < b->nfacets; f++) {
        const int *fn = b->facets + b->npf * f;
        if (per == 1) {
            s[2 * f] = fn[0], s[2 * f + 1] = fn[1];
        } else {
            s[4 * f] = fn[0], s[4 * f + 1] = fn[2];
            s[4 * f + 2] = fn[2], s[4 * f + 3] = fn[1];
        }
    }
    *segs = s;
    *count = per * b->nfacets;
    return CX_OK;
}

/* The outward unit normal of the slave boundary at node k: the mean of the
 * normals of its segments (each to the right of the segment's direction). */
static void seg_slave_normal(const cx_mesh *m, const int *segs, int nsegs, int k, double *n)
{
    n[0] = n[1] = 0;
    for (int f = 0; f < nsegs; f++) {
        const int *fn = segs + 2 * f;
        if (fn[0] != k && fn[1] != k)
            continue;
        double tx = m->x[2 * fn[1]] - m->x[2 * fn[0]], ty = m->x[2 * fn[1] + 1] - m->x[2 * fn[0] + 1];
        double l = hypot(tx, ty);
        n[0] += ty / l;
        n[1] -= tx / l;
    }
    double l = hypot(n[0], n[1]);
    n[0] /= l;
    n[1] /= l;
}

/* The closest point of the master segments to x: segment index, delta and
 * the point. */
static int seg_closest(const cx_mesh *m, const int *segs, int nsegs, const double *x,
                       double *delta, double *chi)
{
    int best = -1;
    double bd = INFINITY;
    for (int f = 0; f < nsegs; f++) {
        const double *a = m->x + 2 * segs[2 * f], *e = m->x + 2 * segs[2 * f + 1];
        double tx = e[0] - a[0], ty = e[1] - a[1], l2 = tx * tx + ty * ty;
        double s = ((x[0] - a[0]) * tx + (x[1] - a[1]) * ty) / l2;
        s = s < 0 ? 0 : (s > 1 ? 1 : s);
        double cx = a[0] + s * tx, cy = a[1] + s * ty;
        double dd = (x[0] - cx) * (x[0] - cx) + (x[1] - cy) * (x[1] - cy);
        if (dd < bd) {
            bd = dd, best = f, *delta = s;
            chi[0] = cx, chi[1] = cy;
        }
    }
    return best;
}

static int seg_add(cx_triplet *R, int row, int col, double v)
{
    return v != 0 ? cx_triplet_add(R, row, col, v) : CX_OK;
}

int cx_contact_node_to_segment(cx_contact_set *cs, const cx_mesh *m, const cx_boundary *slave,
                               const cx_boundary *master, const cx_dofmap *map, cx_diag *d)
{
    int *nodes = NULL, count = 0, status = CX_OK, *pos = NULL, *seen = NULL;
    int *ssegs = NULL, *msegs = NULL, nss = 0, nms = 0;
    memset(cs, 0, sizeof *cs);
    if (m->dim != 2 || slave->npf < 2 || slave->npf > 3 || master->npf < 2 || master->npf > 3 ||
        master->nfacets < 1)
        return cx_diag_set(d, CX_EUNSUPPORTED,
                           "node-to-segment contact needs a 2D mesh with 2- or 3-node edges");
    CX_TRY(cx_boundary_nodes(slave, &nodes, &count));
    pos = CX_NEW(int, m->nnodes);
    seen = CX_NEW(int, m->nnodes);
    if (!pos || !seen || (status = seg_segments(slave, &ssegs, &nss)) ||
        (status = seg_segments(master, &msegs, &nms))) {
        status = CX_ENOMEM;
        goto fail;
    }
    /* the slave nodes along the boundary (pos: workspace here), else by x */
    int *chain = CX_NEW(int, count > 0 ? count : 1);
    if (!chain) {
        status = CX_ENOMEM;
        goto fail;
    }
    if (contact_order_2d_chain(slave, m->nnodes, chain, pos, seen) == count) {
        /* walked with x growing from end to end, so that a straight interface
         * lists its points by x whichever body it belongs to */
        int rev = count > 1 && m->x[2 * chain[0]] > m->x[2 * chain[count - 1]];
        for (int i = 0; i < count; i++)
            nodes[i] = chain[rev ? count - 1 - i : i];
        cx_free(chain);
    } else {
        cx_free(chain);
        if ((status = seg_sort(nodes, count, m->x)))
            goto fail;
    }
    /* the contact nodes: slave nodes with a free dof */
    int mc = 0;
    for (int i = 0; i < count; i++) {
        int k = nodes[i];
        if (!map || map->free_of[2 * k] >= 0 || map->free_of[2 * k + 1] >= 0)
            nodes[mc++] = k;
    }
    if ((status = contact_alloc(cs, 2, mc, 2 * m->nnodes, (size_t)(6 * mc), (size_t)(6 * mc))))
        goto fail;
    cs->nclamped = count - mc;

    /* lumped lengths of the slave boundary (Tresca bounds are tractions) */
    for (int k = 0; k < m->nnodes; k++)
        pos[k] = -1;
    for (int i = 0; i < mc; i++)
        pos[nodes[i]] = i;
    contact_weights(cs->weight, m, slave, pos);

    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int k = 0; k < m->nnodes; k++)
        for (int c = 0; c < 2; c++)
            lo[c] = fmin(lo[c], m->x[2 * k + c]), hi[c] = fmax(hi[c], m->x[2 * k + c]);
    double tol = 1e-12 * hypot(hi[0] - lo[0], hi[1] - lo[1]);

    for (int i = 0; i < mc; i++) {
        int k = nodes[i];
        const double *x = m->x + 2 * k;
        double delta = 0, chi[2] = {0, 0}, *nu = cs->normal + 2 * i, *t = cs->tangent + 2 * i, n1[2];
        int f = seg_closest(m, msegs, nms, x, &delta, chi);
        int p = msegs[2 * f], q = msegs[2 * f + 1];
        double gap = hypot(chi[0] - x[0], chi[1] - x[1]);
        seg_slave_normal(m, ssegs, nss, k, n1);
        if (gap > tol) {
            nu[0] = (chi[0] - x[0]) / gap, nu[1] = (chi[1] - x[1]) / gap;
            /* nu against the slave's outward normal: x is inside body 2 */
            if (nu[0] * n1[0] + nu[1] * n1[1] < 0) {
                status = cx_diag_set(d, CX_EINVAL,
                                     "contact point %d (node %d at (%g, %g)) penetrates the master "
                                     "boundary by %g", i, k, x[0], x[1], gap);
                goto fail;
            }
        } else {
            gap = 0;
            nu[0] = n1[0], nu[1] = n1[1];
        }
        cx_tangent_basis(2, nu, t);
        cs->node[i] = k;
        cs->x[2 * i] = x[0], cs->x[2 * i + 1] = x[1];
        cs->gap[i] = gap;
        const int col[3] = {k, p, q};
        const double w[3] = {1, -(1 - delta), -delta};
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 2; c++)
                if ((status = seg_add(&cs->N, i, 2 * col[a] + c, w[a] * nu[c])) ||
                    (status = seg_add(&cs->T, i, 2 * col[a] + c, w[a] * t[c])))
                    goto fail;
    }
    cx_free(nodes);
    cx_free(pos);
    cx_free(seen);
    cx_free(ssegs);
    cx_free(msegs);
    return CX_OK;

fail:
    cx_free(nodes);
    cx_free(pos);
    cx_free(seen);
    cx_free(ssegs);
    cx_free(msegs);
    cx_contact_clear(cs);
    if (status == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "out of memory building contact rows");
    return status;
}
