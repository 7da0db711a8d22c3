/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Contact rows of a masonry wall (paper 003 §2, §5): Signorini points on
 * the settlement part of the ground, and frictionless node-to-node rows
 * [u_N] <= 0 between the coincident nodes of neighbouring bodies. */
#include "contact/contact_impl.h"
#include "fem/fem.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    int k, l;        /* node below/left (the point), node above/right */
    double n[2];     /* outward normal of k's body */
    double w;        /* lumped length */
} cm_pair;

static void cm_facet_normal(const double *x, const int *f, double *n)
{
    double ex = x[2 * f[1]] - x[2 * f[0]], ey = x[2 * f[1] + 1] - x[2 * f[0] + 1];
    double len = sqrt(ex * ex + ey * ey);
    n[0] = ey / len, n[1] = -ex / len;   /* body on the left: normal to the right */
}

/* The joint facets by their middle node's position (y, then x): the two
 * coincident facets of a joint edge come next to each other. */
static void cm_sort_facets(const double *x, const cx_boundary *jb, cx_sort_key *ks)
{
    for (int f = 0; f < jb->nfacets; f++) {
        const double *xm = x + 2 * jb->facets[3 * f + 2];
        ks[f] = (cx_sort_key){{xm[1], xm[0], 0}, f};
    }
    cx_sort_keys(ks, (size_t)jb->nfacets);
}

static int cm_cmp_pair(const void *a, const void *b)
{
    const cm_pair *p = a, *q = b;
    if (p->k != q->k)
        return p->k < q->k ? -1 : 1;
    return (p->l > q->l) - (p->l < q->l);
}

static int cm_same_point(const double *x, int a, int b)
{
    return x[2 * a] == x[2 * b] && x[2 * a + 1] == x[2 * b + 1];
}

/* The pairs of coincident joint nodes, once each, with summed weights. */
static int cm_pairs(const cx_mesh *m, const cx_boundary *jb, cm_pair **out, int *count, cx_diag *d)
{
    int nf = jb->nfacets, np = 0;
    cx_sort_key *idx = CX_NEW(cx_sort_key, nf);
    cm_pair *pairs = CX_NEW(cm_pair, 3 * (size_t)nf / 2 + 1);
    *out = NULL;
    *count = 0;
    if (!idx || !pairs) {
        cx_free(idx);
        cx_free(pairs);
        return cx_diag_set(d, CX_ENOMEM, "out of memory building joint rows");
    }
    cm_sort_facets(m->x, jb, idx);
    for (int q = 0; q < nf; q += 2) {
        const int *fa = jb->facets + 3 * idx[q].id, *fb = q + 1 < nf ? jb->facets + 3 * idx[q + 1].id : NULL;
        double na[2], nb[2];
        if (fb)
            cm_facet_normal(m->x, fa, na), cm_facet_normal(m->x, fb, nb);
        if (!fb || !cm_same_point(m->x, fa[2], fb[2]) || !cm_same_point(m->x, fa[0], fb[1]) ||
            !cm_same_point(m->x, fa[1], fb[0]) || fabs(na[0] + nb[0]) + fabs(na[1] + nb[1]) > 1e-12) {
            cx_free(idx);
            cx_free(pairs);
            return cx_diag_set(d, CX_EINVAL,
                               "joint edge at (%g, %g) has no matching edge of a neighbouring body",
                               m->x[2 * fa[2]], m->x[2 * fa[2] + 1]);
        }
        if (na[0] + na[1] < 0) {   /* k on the body below / to the left */
            const int *t = fa;
            fa = fb, fb = t;
            double n0 = na[0], n1 = na[1];
            na[0] = nb[0], na[1] = nb[1], nb[0] = n0, nb[1] = n1;
        }
        double xf[6], w[3];
        for (int a = 0; a < 3; a++)
            memcpy(xf + 2 * a, m->x + 2 * fa[a], 2 * sizeof(double));
        cx_fem_facet_lumped(2, 3, xf, w);
        static const int partner[3] = {1, 0, 2};
        for (int a = 0; a < 3; a++) {
            cm_pair *p = &pairs[np++];
            p->k = fa[a], p->l = fb[partner[a]], p->n[0] = na[0], p->n[1] = na[1], p->w = w[a];
        }
    }
    cx_free(idx);
    /* a vertex shared by two edges of the same two bodies appears twice */
    qsort(pairs, (size_t)np, sizeof *pairs, cm_cmp_pair);
    int u = 0;
    for (int q = 0; q < np; q++) {
        if (u > 0 && pairs[u - 1].k == pairs[q].k && pairs[u - 1].l == pairs[q].l)
            pairs[u - 1].w += pairs[q].w;
        else
            pairs[u++] = pairs[q];
    }
    *out = pairs;
    *count = u;
    return CX_OK;
}

/* Signorini nodes: on settle, not on fixed, ordered by x; how many were
 * left out for fixed. */
static int cm_signorini(const cx_mesh *m, const cx_boundary *settle, const cx_boundary *fixed,
                        int **nodes, int *count, int *nfixed)
{
    int *sn = NULL, *fn = NULL, ns = 0, nfix = 0;
    *nodes = NULL, *count = 0, *nfixed = 0;
    CX_TRY(cx_boundary_nodes(settle, &sn, &ns));
    if (cx_boundary_nodes(fixed, &fn, &nfix)) {
        cx_free(sn);
        return CX_ENOMEM;
    }
    int keep = 0;
    for (int a = 0, b = 0; a < ns; a++) {   /* both ascending */
        while (b < nfix && fn[b] < sn[a])
            b++;
        if (!(b < nfix && fn[b] == sn[a]))
            sn[keep++] = sn[a];
    }
    cx_free(fn);
    /* by x; ties keep node order (the key's id is the node) */
    cx_sort_key *order = CX_NEW(cx_sort_key, keep > 0 ? keep : 1);
    if (!order) {
        cx_free(sn);
        return CX_ENOMEM;
    }
    for (int q = 0; q < keep; q++)
        order[q] = (cx_sort_key){{m->x[2 * sn[q]], 0, 0}, sn[q]};
    cx_sort_keys(order, (size_t)keep);
    for (int q = 0; q < keep; q++)
        sn[q] = order[q].id;
    cx_free(order);
    *nodes = sn, *count = keep, *nfixed = ns - keep;
    return CX_OK;
}

int cx_contact_masonry(cx_contact_set *cs, const cx_mesh *m, const cx_boundary *settle,
                       const cx_boundary *fixed, const cx_boundary *joints,
                       const cx_obstacle *ob, cx_diag *d)
{
    memset(cs, 0, sizeof *cs);
    if (m->dim != 2 || settle->npf != 3 || fixed->npf != 3 || joints->npf != 3)
        return cx_diag_set(d, CX_EINVAL, "masonry contact: needs a 2D P2 mesh (3-node edges)");
    cm_pair *pairs = NULL;
    int *sn = NULL, *pos = NULL, ns = 0, np = 0, nfixed = 0, st;
    CX_TRY(cm_pairs(m, joints, &pairs, &np, d));
    if ((st = cm_signorini(m, settle, fixed, &sn, &ns, &nfixed))) {
        cx_free(pairs);
        return cx_diag_set(d, st, "out of memory building Signorini rows");
    }
    int count = ns + np;
    st = CX_ENOMEM;
    pos = CX_NEW(int, m->nnodes);
    if (!pos || (st = contact_alloc(cs, 2, count, 2 * m->nnodes, (size_t)(4 * count),
                                    (size_t)(4 * count))))
        goto fail;
    cs->nclamped = nfixed;
    /* the Signorini points' lumped lengths on settle */
    for (int k = 0; k < m->nnodes; k++)
        pos[k] = -1;
    for (int i = 0; i < ns; i++)
        pos[sn[i]] = i;
    contact_weights(cs->weight, m, settle, pos);
    for (int i = 0; i < count; i++) {
        int k = i < ns ? sn[i] : pairs[i - ns].k, l = i < ns ? -1 : pairs[i - ns].l;
        double *n = cs->normal + 2 * i, *t = cs->tangent + 2 * i, g = 0;
        cs->node[i] = k;
        memcpy(cs->x + 2 * i, m->x + 2 * k, 2 * sizeof(double));
        if (i < ns) {
            if (cx_obstacle_gap(ob, 2, m->x + 2 * k, &g, n) != CX_OK || !(g >= 0) || !isfinite(g)) {
                st = cx_diag_set(d, CX_EINVAL, "settlement point %d (node %d at (%g, %g)): gap %g to the "
                                 "%s obstacle (expected a finite gap >= 0)", i, k, m->x[2 * k],
                                 m->x[2 * k + 1], g, cx_obstacle_name(ob->kind));
                goto fail;
            }
        } else {
            cs->weight[i] = pairs[i - ns].w;
            n[0] = pairs[i - ns].n[0], n[1] = pairs[i - ns].n[1];
        }
        cs->gap[i] = g;
        cx_tangent_basis(2, n, t);
        for (int c = 0; c < 2; c++) {
            if (n[c] != 0 && ((st = cx_triplet_add(&cs->N, i, 2 * k + c, n[c])) ||
                              (l >= 0 && (st = cx_triplet_add(&cs->N, i, 2 * l + c, -n[c])))))
                goto fail;
            if (t[c] != 0 && ((st = cx_triplet_add(&cs->T, i, 2 * k + c, t[c])) ||
                              (l >= 0 && (st = cx_triplet_add(&cs->T, i, 2 * l + c, -t[c])))))
                goto fail;
        }
    }
    cx_free(pairs), cx_free(sn), cx_free(pos);
    return CX_OK;

fail:
    cx_free(pairs), cx_free(sn), cx_free(pos);
    cx_contact_clear(cs);
    if (st == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "out of memory building masonry contact rows");
    return st;
}
