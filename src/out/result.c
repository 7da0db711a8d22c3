/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The solution snapshot (see result.h). */
#include "out/result.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void *result_dup(const void *src, size_t bytes, int *bad)
{
    if (!src || bytes == 0)
        return NULL;
    void *p = cx_malloc(bytes);
    if (p)
        memcpy(p, src, bytes);
    else
        *bad = 1;
    return p;
}

static cx_mesh *result_mesh_copy(const cx_mesh *src)
{
    cx_mesh *m = CX_NEW(cx_mesh, 1);
    if (!m)
        return NULL;
    int bad = 0;
    *m = *src;
    m->x = result_dup(src->x, sizeof(double) * (size_t)src->dim * src->nnodes, &bad);
    m->conn = result_dup(src->conn, sizeof(int) * (size_t)src->npe * src->nelems, &bad);
    m->body = result_dup(src->body, sizeof(int) * (size_t)src->nelems, &bad);
    m->mat = result_dup(src->mat, sizeof(int) * (size_t)src->nelems, &bad);
    m->bounds = result_dup(src->bounds, sizeof(cx_boundary) * (size_t)src->nbounds, &bad);
    for (int k = 0; m->bounds && k < m->nbounds; k++)
        m->bounds[k].facets = bad ? NULL
                                  : result_dup(src->bounds[k].facets,
                                               sizeof(int) * (size_t)src->bounds[k].npf * src->bounds[k].nfacets, &bad);
    if (bad)
        cx_mesh_destroy(&m);
    return m;
}

/* The points' geometry without the N and T rows (which only a solver needs). */
static int result_contact_copy(cx_contact_set *c, const cx_contact_set *src)
{
    int bad = 0, m = src->m, dim = src->dim;
    memset(c, 0, sizeof *c);
    c->dim = dim;
    c->m = m;
    c->nall = src->nall;
    c->nclamped = src->nclamped;
    c->node = result_dup(src->node, sizeof(int) * (size_t)m, &bad);
    c->x = result_dup(src->x, sizeof(double) * (size_t)dim * m, &bad);
    c->weight = result_dup(src->weight, sizeof(double) * (size_t)m, &bad);
    c->normal = result_dup(src->normal, sizeof(double) * (size_t)dim * m, &bad);
    c->tangent = result_dup(src->tangent, sizeof(double) * (size_t)dim * (dim - 1) * m, &bad);
    c->gap = result_dup(src->gap, sizeof(double) * (size_t)m, &bad);
    return bad ? CX_ENOMEM : CX_OK;
}

void cx_result_destroy(cx_result **r)
{
    if (!r || !*r)
        return;
    cx_result *x = *r;
    cx_mesh_destroy(&x->mesh);
    cx_free(x->mats);
    cx_contact_clear(&x->contact);
    cx_free(x->u);
    cx_free(x->lN);
    cx_free(x->lT);
    cx_free(x->status);
    cx_free(x->stress_cache);
    cx_free(x->vm_cache);
    cx_free(x->tu);
    cx_free(x->f_contact_body);
    cx_free(x);
    *r = NULL;
}

/* The contact forces of the result (result.h, f_contact): every entry of
 * the rows N (and T with friction) is a nodal force -lN_i N_ij on the
 * node of all-dof j, added to that node's body. A row on one node only is
 * a rigid obstacle's; the rows between bodies touch two or three nodes. */
static int result_contact_forces(cx_result *x, const cx_problem *p, int friction)
{
    const cx_mesh *pm = p->mesh;
    const cx_contact_set *c = &p->contact;
    int dim = p->dim, dt = dim - 1, nn = pm->nnodes, m = p->m;
    x->nbodies = pm->nbodies > 1 && pm->body ? pm->nbodies : 1;
    x->f_contact_body = CX_NEW(double, (size_t)dim * x->nbodies);
    int *bof = CX_NEW(int, (size_t)nn + 1);      /* body of a node */
    int *rown = CX_NEW(int, (size_t)m + 1);      /* the node of a row, -2: several */
    unsigned char *hit = CX_NEW(unsigned char, (size_t)x->nbodies);
    if (!x->f_contact_body || !bof || !rown || !hit) {
        cx_free(bof);
        cx_free(rown);
        cx_free(hit);
        return CX_ENOMEM;
    }
    if (x->nbodies > 1)
        for (int e = 0; e < pm->nelems; e++)
            for (int a = 0; a < pm->npe; a++)
                bof[pm->conn[pm->npe * e + a]] = pm->body[e];
    for (int i = 0; i < m; i++)
        rown[i] = -1;
    for (size_t k = 0; k < c->N.nnz; k++) {
        int i = c->N.i[k], node = c->N.j[k] / dim;
        if (i < m && c->N.j[k] < dim * nn)
            rown[i] = rown[i] == -1 || rown[i] == node ? node : -2;
    }
    /* one pass over N, one over T: lam is lN or lT, its row's point i */
    for (int pass = 0; pass < (friction ? 2 : 1); pass++) {
        const cx_triplet *R = pass ? &c->T : &c->N;
        const double *lam = pass ? x->lT : x->lN;
        int rows = pass ? p->nt : m, per = pass ? dt : 1;
        for (size_t k = 0; k < R->nnz; k++) {
            int r = R->i[k], j = R->j[k];
            if (r >= rows || j >= dim * nn)
                continue;
            double f = -lam[r] * R->x[k];
            int node = j / dim, comp = j % dim, i = r / per;
            x->f_contact_body[dim * bof[node] + comp] += f;
            if (node == c->node[i])
                x->f_points[comp] += f;
            if (rown[i] >= 0)
                x->f_contact[comp] += f;
        }
    }
    /* in contact: lN above roundoff (1e-12 of the largest) */
    double lmax = 0;
    for (int i = 0; i < m; i++)
        lmax = fmax(lmax, x->lN[i]);
    for (int i = 0; i < m; i++)
        if (rown[i] >= 0 && x->lN[i] > 1e-12 * lmax)
            hit[bof[rown[i]]] = 1;
    for (int b = 0; b < x->nbodies; b++)
        x->nbodies_obstacle += hit[b];
    cx_free(bof);
    cx_free(rown);
    cx_free(hit);
    return CX_OK;
}

int cx_result_create(cx_result **r, const cx_problem *p, const cx_friction_state *fr,
                     const double *u, const double *lN, const double *lT,
                     const unsigned char *status, cx_diag *d)
{
    const cx_friction_state none = {CX_FRICTION_NONE, 0, 0, NULL, NULL};
    if (!fr)
        fr = &none;
    *r = NULL;
    cx_result *x = CX_NEW(cx_result, 1);
    if (!x)
        return cx_diag_set(d, CX_ENOMEM, "result: out of memory");
    const cx_mesh *pm = p->mesh;
    x->dim = p->dim;
    x->n = p->n;
    x->m = p->m;
    x->nt = p->nt;
    x->mesh = result_mesh_copy(pm);
    int nmats = cx_mesh_nmats(pm) > 0 ? cx_mesh_nmats(pm) : 1;
    x->mats = CX_NEW(cx_material, nmats);
    x->u = CX_NEW(double, (size_t)p->dim * pm->nnodes);
    x->lN = CX_NEW(double, (size_t)p->m + 1);
    x->lT = CX_NEW(double, (size_t)p->nt + 1);
    x->status = CX_NEW(unsigned char, (size_t)p->m + 1);
    x->tu = CX_NEW(double, (size_t)p->nt + 1);
    if (!x->mesh || !x->mats || !x->u || !x->lN || !x->lT || !x->status || !x->tu ||
        result_contact_copy(&x->contact, &p->contact) != CX_OK) {
        cx_result_destroy(&x);
        return cx_diag_set(d, CX_ENOMEM, "result: out of memory");
    }
    memcpy(x->mats, p->mats, sizeof(cx_material) * (size_t)cx_mesh_nmats(pm));
    cx_fem_expand(&p->map, u, x->u);
    if (p->m > 0) {
        memcpy(x->lN, lN, sizeof(double) * (size_t)p->m);
        if (status)
            memcpy(x->status, status, (size_t)p->m);
    }
    if (lT && p->nt > 0)
        memcpy(x->lT, lT, sizeof(double) * (size_t)p->nt);
    memcpy(x->f_applied, p->f_applied, sizeof x->f_applied);
    /* T u over the all-dof numbering (contact.h); the copy keeps no rows */
    const cx_triplet *T = &p->contact.T;
    for (size_t k = 0; k < T->nnz; k++)
        if (T->i[k] < p->nt && T->j[k] < p->dim * pm->nnodes)
            x->tu[T->i[k]] += T->x[k] * x->u[T->j[k]];
    if (result_contact_forces(x, p, fr->law != CX_FRICTION_NONE) != CX_OK) {
        cx_result_destroy(&x);
        return cx_diag_set(d, CX_ENOMEM, "result: out of memory");
    }
    x->run.friction = fr->law;
    x->run.F = fr->F;
    x->run.slip_bound = fr->slip_bound;
    x->run.own = NAN;
    for (int i = 0; i < p->m; i++) {
        int s = x->status[i];
        x->run.nfree += s == CX_PT_FREE;
        x->run.ncontact += s == CX_PT_CONTACT;
        x->run.nstick += s == CX_PT_STICK;
        x->run.nslip += s == CX_PT_SLIP_POS || s == CX_PT_SLIP_NEG;
    }
    *r = x;
    return CX_OK;
}


/* The contact half-width of a 2D Hertz run (cx_run_record.halfwidth). The
 * contact set orders its points along the arc with x increasing from the
 * symmetry axis (scene/pressure.c). In contact: pressure above 1e-12 of
 * the largest (roundoff of the zero multipliers). */
static double result_halfwidth(const cx_problem *p, const double *lN)
{
    const cx_contact_set *c = &p->contact;
    double pmax = 0;
    for (int i = 0; i < p->m; i++)
        pmax = fmax(pmax, lN[i] / c->weight[i]);
    int last = -1;
    for (int i = 0; i < p->m; i++)
        if (lN[i] / c->weight[i] > 1e-12 * pmax)
            last = i;
    if (last < 0)
        return 0;
    double xl = fabs(c->x[2 * last]);
    if (last + 1 >= p->m)
        return xl;   /* every point in contact: the half-width is at least xl */
    double xo = fabs(c->x[2 * (last + 1)]);
    double b = xo;
    if (last > 0) {
        /* p^2 = k (b^2 - x^2) through (x_{l-1}, p_{l-1}) and (x_l, p_l) */
        double xa = fabs(c->x[2 * (last - 1)]), pa = lN[last - 1] / c->weight[last - 1];
        double pl = lN[last] / c->weight[last];
        double den = pa * pa - pl * pl;
        if (den > 0) {
            double b2 = (pa * pa * xl * xl - pl * pl * xa * xa) / den;
            b = b2 > 0 ? sqrt(b2) : xl;
        }
    }
    return fmin(fmax(b, xl), xo);
}

int cx_result_from_session(cx_result **r, const cx_session *s, const cx_scene *sc, int level,
                           cx_diag *d)
{
    *r = NULL;
    const cx_problem *p = cx_session_problem(s);
    const cx_iterate *it = cx_session_iterate(s);
    const cx_method *m = cx_session_method(s);
    if (m && it->u_partial)
        return cx_diag_set(d, CX_EINVAL, "result: the iterate is partial (complete it first)");
    cx_result *x = NULL;
    CX_TRY(cx_result_create(&x, p, cx_session_friction(s), it->u, it->lN, it->lT,
                            m ? it->status : NULL, d));
    cx_run_record *run = &x->run;
    if (sc) {
        snprintf(run->scene, sizeof run->scene, "%s", sc->id);
        snprintf(run->title, sizeof run->title, "%s", sc->title);
        snprintf(run->unit_length, sizeof run->unit_length, "%s", sc->unit_length);
        snprintf(run->unit_stress, sizeof run->unit_stress, "%s", sc->unit_stress);
        /* where the solver has them */
        x->nobstacles = cx_scene_obstacles(sc, level, x->obstacles, CX_RESULT_MAX_OBSTACLES);
        x->has_obstacle = x->nobstacles > 0;
        if (x->has_obstacle)
            x->obstacle = x->obstacles[0];
        double pa, pr;
        if (cx_scene_pressure_error(sc, p, x->lN, &pa, &pr) == CX_OK) {
            run->has_pressure_error = 1;
            run->pressure_error_abs = pa;
            run->pressure_error_rel = pr;
            run->hertz_halfwidth = cx_scene_hertz_halfwidth(sc);
            run->halfwidth = p->dim == 3 ? cx_scene_contact_radius(sc, p, x->lN)
                                         : result_halfwidth(p, x->lN);
        }
    }
    run->level = level > 0 ? level : sc ? sc->level : 0;
    const cx_options *so = cx_session_options(s);
    run->tol = so->tol;
    run->max_iter = so->max_iter;
    run->own_stop = so->own_stop;
    run->time_limit = so->time_limit;
    if (!m) {
        *r = x;
        return CX_OK;
    }
    snprintf(run->method, sizeof run->method, "%s", m->id);
    const cx_param_values *pv = cx_session_params(s);
    if (pv) {
        run->params = *pv;
        size_t n = 0, len = sizeof run->params_text;
        for (int k = 0; k < pv->n && n + 2 < len; k++) {
            char v[64];
            cx_param_format(pv, k, v, sizeof v);
            int w = snprintf(run->params_text + n, len - n, "%s%s=%s", k ? " " : "", pv->table[k].key, v);
            if (w < 0 || (size_t)w >= len - n) {
                run->params_text[n] = '\0';
                break;
            }
            n += (size_t)w;
        }
    }
    run->iterations = it->iter;
    run->reason = it->reason;
    run->converged = it->reason > 0;
    snprintf(run->message, sizeof run->message, "%s", cx_session_reason_msg(s));
    run->kkt = it->kkt;
    run->kkt_parts = it->kkt_parts;
    run->own = it->own;
    run->nfree = it->nfree;
    run->ncontact = it->ncontact;
    run->nstick = it->nstick;
    run->nslip = it->nslip;
    run->counters = it->counters;
    run->inner_total = it->inner_total;
    run->time.setup = it->init_time;
    run->time.solve = it->time - it->init_time;
    run->time.total = it->time;
    *r = x;
    return CX_OK;
}

int cx_result_stress(cx_result *r, const double **sigma, const double **von_mises, cx_diag *d)
{
    const cx_mesh *m = r->mesh;
    int nn = m->nnodes, ns = cx_fem_nstress(m->dim);
    if (!r->stress_cache) {
        double *sig = cx_malloc(sizeof(double) * (size_t)ns * nn + 1);
        double *vm = cx_malloc(sizeof(double) * (size_t)nn + 1);
        int *owner = CX_NEW(int, (size_t)nn + 1);
        int rc = sig && vm && owner ? cx_fem_nodal_stress(m, r->mats, r->u, sig) : CX_ENOMEM;
        if (rc == CX_OK) {
            /* the material of a node: that of an element using it */
            for (int e = 0; e < m->nelems; e++)
                for (int a = 0; a < m->npe; a++)
                    owner[m->conn[m->npe * e + a]] = cx_mesh_elem_mat(m, e);
            for (int k = 0; k < nn; k++)
                vm[k] = cx_fem_von_mises(&r->mats[owner[k]], sig + (size_t)ns * k);
            r->stress_cache = sig;
            r->vm_cache = vm;
        } else {
            cx_free(sig);
            cx_free(vm);
        }
        cx_free(owner);
        if (rc != CX_OK)
            return cx_diag_set(d, rc, "stresses: %s", cx_status_str(rc));
    }
    if (sigma)
        *sigma = r->stress_cache;
    if (von_mises)
        *von_mises = r->vm_cache;
    return CX_OK;
}

void cx_result_nodal_pressure(const cx_result *r, double *val)
{
    const cx_contact_set *cs = &r->contact;
    for (int k = 0; k < r->mesh->nnodes; k++)
        val[k] = 0;
    for (int i = 0; i < cs->m; i++)
        val[cs->node[i]] = cs->weight[i] > 0 ? r->lN[i] / cs->weight[i] : 0;
}

void cx_result_nodal_status(const cx_result *r, double *val)
{
    const cx_contact_set *cs = &r->contact;
    for (int k = 0; k < r->mesh->nnodes; k++)
        val[k] = -1;
    for (int i = 0; i < cs->m; i++)
        val[cs->node[i]] = r->status[i];
}

/* The shortest %g form that reads back as v. */
static void result_num(double v, char *buf, size_t len)
{
    for (int p = 6; p <= 17; p++) {
        snprintf(buf, len, "%.*g", p, v);
        if (strtod(buf, NULL) == v)
            return;
    }
}

char *cx_run_record_solve_args(const cx_run_record *run, char *buf, size_t len)
{
    char num[40];
    size_t n = 0;
    buf[0] = '\0';
#define RESULT_ADD(...)                                                  \
    do {                                                                 \
        if (n < len) {                                                   \
            int w_ = snprintf(buf + n, len - n, __VA_ARGS__);            \
            n = w_ < 0 ? len : n + (size_t)w_;                           \
        }                                                                \
    } while (0)
    RESULT_ADD("%s --level %d", run->scene[0] ? run->scene : "-", run->level);
    if (run->method[0])
        RESULT_ADD(" --method %s", run->method);
    for (int k = 0; k < run->params.n; k++) {
        cx_param_format(&run->params, k, num, sizeof num);
        RESULT_ADD(" --set %s=%s", run->params.table[k].key, num);
    }
    RESULT_ADD(" --friction %s", cx_friction_name(run->friction));
    if (run->friction == CX_FRICTION_COULOMB) {
        result_num(run->F, num, sizeof num);
        RESULT_ADD(" --F %s", num);
    } else if (run->friction == CX_FRICTION_TRESCA) {
        result_num(run->slip_bound, num, sizeof num);
        RESULT_ADD(" --slip %s", num);
    }
    result_num(run->tol, num, sizeof num);
    RESULT_ADD(" --tol %s", num);
    if (run->max_iter > 0)
        RESULT_ADD(" --max-iter %d --stop %s", run->max_iter, run->own_stop ? "own" : "kkt");
    if (run->time_limit > 0) {
        result_num(run->time_limit, num, sizeof num);
        RESULT_ADD(" --time-limit %s", num);
    }
#undef RESULT_ADD
    return buf;
}
