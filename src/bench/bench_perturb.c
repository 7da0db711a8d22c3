/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The perturbations of 'bench stress', applied in memory: to a copy of the
 * scene (units, material, loads) or to the built problem (gaps, duplicated
 * contact points, moved nodes, material contrast between bodies). */
#include "bench/bench_perturb.h"

#include <math.h>
#include <string.h>

/* ---- on the scene ------------------------------------------------------ */

void perturb_scene_units(cx_scene *s, double L, double P)
{
    /* lengths x L, stresses x P: forces per area x P, per volume x P / L */
    for (int k = 0; k < 3; k++) {
        s->lo[k] *= L;
        s->hi[k] *= L;
        s->obstacle.point[k] *= L;
        s->body_force[k] *= P / L;
    }
    s->radius *= L;
    s->obstacle.radius *= L;
    s->mat.E *= P;
    s->slip_bound *= P;
    for (int t = 0; t < s->ntractions; t++) {
        for (int k = 0; k < 3; k++)
            s->tractions[t].t.t0[k] *= P;
        for (int k = 0; k < 9; k++)
            s->tractions[t].t.G[k] *= P / L;
    }
    for (int t = 0; t < s->nsupports; t++)
        for (int k = 0; k < 3; k++)
            s->supports[t].value[k] *= L;
    /* Hertz: P is a force per unit length (2D): stress x length */
    s->hertz_P *= P * L;
    s->hertz_R *= L;
}

void perturb_scene_loads(cx_scene *s, double factor)
{
    for (int k = 0; k < 3; k++)
        s->body_force[k] *= factor;
    for (int t = 0; t < s->ntractions; t++) {
        for (int k = 0; k < 3; k++)
            s->tractions[t].t.t0[k] *= factor;
        for (int k = 0; k < 9; k++)
            s->tractions[t].t.G[k] *= factor;
    }
    /* a prescribed displacement is a load too (the slider's punch) */
    for (int t = 0; t < s->nsupports; t++)
        for (int k = 0; k < 3; k++)
            s->supports[t].value[k] *= factor;
}

/* ---- on the problem ------------------------------------------------------ */

double perturb_body_size(const cx_problem *p)
{
    const cx_mesh *m = p->mesh;
    double size = 0;
    for (int k = 0; k < m->dim; k++) {
        double lo = INFINITY, hi = -INFINITY;
        for (int a = 0; a < m->nnodes; a++) {
            lo = fmin(lo, m->x[m->dim * a + k]);
            hi = fmax(hi, m->x[m->dim * a + k]);
        }
        size = fmax(size, hi - lo);
    }
    return size;
}

int perturb_gap(cx_problem *p, const void *arg, cx_diag *d)
{
    (void)d;
    double delta = *(const double *)arg * perturb_body_size(p);
    for (int i = 0; i < p->m; i++) {
        p->g[i] += delta;
        p->contact.gap[i] += delta;
    }
    return CX_OK;
}

/* A copy of A with the rows src[0..k-1] appended (in that order). */
static int perturb_append_rows(cx_csc *A, const int *src, int k)
{
    cx_triplet t;
    CX_TRY(cx_triplet_init(&t, A->nrow + k, A->ncol, cx_csc_nnz(A) + 16));
    int st = CX_OK;
    for (int j = 0; j < A->ncol && !st; j++)
        for (int q = A->p[j]; q < A->p[j + 1] && !st; q++) {
            st = cx_triplet_add(&t, A->i[q], j, A->x[q]);
            for (int r = 0; r < k && !st; r++)
                if (A->i[q] == src[r])
                    st = cx_triplet_add(&t, A->nrow + r, j, A->x[q]);
        }
    cx_csc B = {0};
    if (!st)
        st = cx_csc_from_triplet(&B, &t);
    cx_triplet_clear(&t);
    if (st)
        return st;
    cx_csc_clear(A);
    *A = B;
    return CX_OK;
}

/* Grow a cx_malloc'ed array of count * size bytes by one element of size
 * bytes, a copy of element src. */
static int perturb_grow(void **a, int count, size_t size, int src)
{
    char *b = cx_realloc(*a, size * (size_t)(count + 1));
    if (!b)
        return CX_ENOMEM;
    memcpy(b + size * (size_t)count, b + size * (size_t)src, size);
    *a = b;
    return CX_OK;
}

int perturb_duplicate_contact(cx_problem *p, const void *arg, cx_diag *d)
{
    double eps = *(const double *)arg * perturb_body_size(p);
    int m = p->m, dim = p->dim, dt = dim - 1;
    if (m == 0)
        return cx_diag_set(d, CX_EUNSUPPORTED, "no contact point to duplicate");
    /* the point of smallest gap nearest the middle: surely in contact */
    double gmin = INFINITY;
    for (int i = 0; i < m; i++)
        gmin = fmin(gmin, p->g[i]);
    int near[2] = {-1, -1}, count = 0;
    for (int i = 0; i < m; i++)
        if (p->g[i] <= gmin + 1e-12 * (fabs(gmin) + 1))
            count++;
    for (int i = 0, seen = 0; i < m; i++)
        if (p->g[i] <= gmin + 1e-12 * (fabs(gmin) + 1) && seen++ == count / 2)
            near[0] = i;
    int i = near[0];
    int trows[2] = {dt * i, dt * i + 1};
    cx_contact_set *c = &p->contact;
    int st;
    if ((st = perturb_append_rows(&p->N, &i, 1)) || (st = perturb_append_rows(&p->T, trows, dt)) ||
        (st = perturb_grow((void **)&p->g, m, sizeof(double), i)) ||
        (st = perturb_grow((void **)&c->node, m, sizeof(int), i)) ||
        (st = perturb_grow((void **)&c->x, m, sizeof(double) * (size_t)dim, i)) ||
        (st = perturb_grow((void **)&c->weight, m, sizeof(double), i)) ||
        (st = perturb_grow((void **)&c->normal, m, sizeof(double) * (size_t)dim, i)) ||
        (st = perturb_grow((void **)&c->tangent, m, sizeof(double) * (size_t)(dim * dt), i)) ||
        (st = perturb_grow((void **)&c->gap, m, sizeof(double), i)))
        return cx_diag_set(d, st, "out of memory");
    /* no friction values here: the session expands them per point from
     * the scalars and the weights, the copy's weight included */
    p->g[m] += eps;
    c->gap[m] += eps;
    p->m = c->m = m + 1;
    p->nt = dt * p->m;
    return CX_OK;
}

/* K and f again from the mesh and materials of p (the scene's loads). */
static int perturb_reassemble(cx_problem *p, const cx_scene *s, cx_diag *d)
{
    cx_mesh *m = p->mesh;
    cx_csc Kall = {0}, K = {0};
    double *fall = CX_NEW(double, m->dim * m->nnodes);
    int st = fall ? cx_fem_assemble_stiffness(m, p->mats, &Kall, d) : CX_ENOMEM;
    for (int k = 0; k < s->ntractions && !st; k++) {
        const cx_boundary *b = cx_mesh_boundary(m, s->tractions[k].boundary);
        st = b ? cx_fem_add_traction(m, b, &s->tractions[k].t, fall) : CX_EINVAL;
    }
    if (!st && (s->body_force[0] != 0 || s->body_force[1] != 0 || s->body_force[2] != 0))
        st = cx_fem_add_body_force(m, s->body_force, fall);
    if (!st)
        st = cx_fem_reduce(&Kall, fall, &p->map, &K, p->f);
    cx_csc_clear(&Kall);
    cx_free(fall);
    if (st && !(d && d->status == st && d->msg[0]))
        cx_diag_set(d, st, "reassembling the perturbed problem: %s", cx_status_str(st));
    if (st)
        return st;
    cx_csc_clear(&p->K);
    p->K = K;
    p->kscale = 0;
    for (int j = 0; j < p->n; j++)
        for (int q = p->K.p[j]; q < p->K.p[j + 1]; q++)
            if (p->K.i[q] == j && p->K.x[q] > p->kscale)
                p->kscale = p->K.x[q];
    return CX_OK;
}

/* A small deterministic generator (xorshift64*), so that the moved mesh
 * is the same on every machine. */
static double perturb_random(uint64_t *state)
{
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    return (double)((*state * 2685821657736338717ull) >> 11) / 9007199254740992.0;
}

int perturb_jitter(cx_problem *p, const void *arg, cx_diag *d)
{
    const perturb_jitter_arg *a = arg;
    cx_mesh *m = p->mesh;
    int dim = m->dim, npe = m->npe;
    /* boundary nodes stay: supports, loads and contact rows keep their
     * geometry; interior nodes move by up to frac x the shortest edge at
     * the node, in a random direction */
    unsigned char *fixed = CX_NEW(unsigned char, m->nnodes);
    double *h = CX_NEW(double, m->nnodes);
    if (!fixed || !h) {
        cx_free(fixed);
        cx_free(h);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    for (int b = 0; b < m->nbounds; b++)
        for (int k = 0; k < m->bounds[b].nfacets * m->bounds[b].npf; k++)
            fixed[m->bounds[b].facets[k]] = 1;
    for (int a2 = 0; a2 < m->nnodes; a2++)
        h[a2] = INFINITY;
    for (int e = 0; e < m->nelems; e++)
        for (int i = 0; i < npe; i++)
            for (int j = 0; j < npe; j++) {
                int ni = m->conn[npe * e + i], nj = m->conn[npe * e + j];
                if (ni == nj)
                    continue;
                double len = 0;
                for (int k = 0; k < dim; k++)
                    len += pow(m->x[dim * ni + k] - m->x[dim * nj + k], 2);
                h[ni] = fmin(h[ni], sqrt(len));
            }
    uint64_t state = a->seed ? a->seed : 88172645463325252ull;
    for (int n = 0; n < m->nnodes; n++) {
        double dir[3] = {0, 0, 0}, norm = 0;
        for (int k = 0; k < dim; k++) {
            dir[k] = 2 * perturb_random(&state) - 1;
            norm += dir[k] * dir[k];
        }
        double r = a->frac * h[n] * perturb_random(&state);
        if (fixed[n] || !(norm > 0) || !isfinite(h[n]))
            continue;
        for (int k = 0; k < dim; k++)
            m->x[dim * n + k] += r * dir[k] / sqrt(norm);
    }
    cx_free(fixed);
    cx_free(h);
    return perturb_reassemble(p, a->scene, d);
}

int perturb_contrast(cx_problem *p, const void *arg, cx_diag *d)
{
    const perturb_contrast_arg *a = arg;
    if (p->mesh->nbodies < 2)
        return cx_diag_set(d, CX_EUNSUPPORTED, "n/a (one body)");
    for (int k = 1; k < cx_mesh_nmats(p->mesh); k++)   /* every material id but the first */
        p->mats[k].E *= a->ratio;
    return perturb_reassemble(p, a->scene, d);
}
