/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The discrete problem out and back in: export a scene's problem
 * (MatrixMarket, FCLIB), read it back, and solve both with every method
 * that takes the law: the same iterations, outcome and kkt error, and the
 * solutions equal in the energy norm to 1e-12 relative. */
#include "out/export.h"
#include "scene/problem_file.h"
#include "scene/scene.h"
#include "cx_config.h"
#include "check.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#if CX_HAVE_FCLIB
#include <fclib.h>
#endif

/* ||a - b||_K / ||a||_K */
static double energy_diff(const cx_problem *p, const double *a, const double *b)
{
    double *e = calloc((size_t)p->n, sizeof *e), *Ke = calloc((size_t)p->n, sizeof *Ke);
    double *Ka = calloc((size_t)p->n, sizeof *Ka);
    for (int i = 0; i < p->n; i++)
        e[i] = a[i] - b[i];
    cx_csc_gemv(&p->K, 1, e, 0, Ke);
    cx_csc_gemv(&p->K, 1, a, 0, Ka);
    double num = 0, den = 0;
    for (int i = 0; i < p->n; i++) {
        num += e[i] * Ke[i];
        den += a[i] * Ka[i];
    }
    free(e);
    free(Ke);
    free(Ka);
    return den > 0 ? sqrt(fabs(num) / den) : sqrt(fabs(num));
}

static int solve(cx_session *s, const cx_method *m)
{
    cx_diag d;
    cx_options opt;
    cx_options_default(&opt);
    int st = cx_session_set_method(s, m, NULL, &opt, &d);
    if (!st)
        st = cx_solver_solve(s, NULL, NULL, &d);
    return st;
}

/* Methods whose run depends on what FCLIB does not carry (the points'
 * weights and the material's E): compared only through MatrixMarket. */
static int uses_geometry(const cx_method *m)
{
    return !strcmp(m->id, "ubr-c") || !strcmp(m->id, "ubr-tf") || !strcmp(m->id, "ssn-c");
}

#if CX_HAVE_FCLIB
/* y = A x (+ y if acc) for an FCLIB CSC matrix; At: y = A' x. */
static void fc_gemv(const struct fclib_matrix *A, int trans, const double *x, double *y)
{
    memset(y, 0, sizeof(double) * (size_t)(trans ? A->n : A->m));
    for (int j = 0; j < A->n; j++)
        for (int q = A->p[j]; q < A->p[j + 1]; q++) {
            if (trans)
                y[j] += A->x[q] * x[A->i[q]];
            else
                y[A->i[q]] += A->x[q] * x[j];
        }
}

/* Our solution read in FCLIB's own terms, from the file FCLIB reads:
 * v = u, r = (lN_i, lT_i) per point must solve M v = H r + f,
 * û = H' v + w + (mu |u_T|, 0) in the dual cone, r in the cone
 * |r_T| <= mu r_N, û' r = 0 per point; a slipping point's r_T opposes
 * u_T. This checks the signs of H and w against FCLIB's definition. */
static void fclib_semantics(const char *path, const cx_session *s)
{
    struct fclib_global *g = fclib_read_global(path);
    CX_CHECK(g != NULL);
    if (!g)
        return;
    const cx_iterate *it = cx_session_iterate(s);
    const cx_problem *p = cx_session_problem(s);
    int n = g->M->n, nc = g->H->n, dim = g->spacedim, m = nc / dim;
    CX_CHECK(n == p->n && m == p->m && dim == p->dim && g->M->nz == -1 && g->H->nz == -1);
    double *r = calloc((size_t)nc, sizeof *r), *Mv = calloc((size_t)n, sizeof *Mv),
           *Hr = calloc((size_t)n, sizeof *Hr), *uloc = calloc((size_t)nc, sizeof *uloc);
    for (int i = 0; i < m; i++) {
        r[dim * i] = it->lN[i];
        for (int k = 1; k < dim; k++)
            r[dim * i + k] = it->lT[(dim - 1) * i + k - 1];
    }
    fc_gemv(g->M, 0, it->u, Mv);
    fc_gemv(g->H, 0, r, Hr);
    double res = 0, fmax_ = 0;
    for (int j = 0; j < n; j++) {
        res = fmax(res, fabs(Mv[j] - Hr[j] - g->f[j]));
        fmax_ = fmax(fmax_, fabs(g->f[j]));
    }
    CX_CHECK_LE(res, 1e-8 * fmax_);
    fc_gemv(g->H, 1, it->u, uloc);
    int slipping = 0, touching = 0;
    double rmax = 0;
    for (int i = 0; i < m; i++)
        rmax = fmax(rmax, it->lN[i]);
    for (int i = 0; i < m; i++) {
        double *ul = uloc + dim * i, *ri = r + dim * i, mu = g->mu[i];
        for (int k = 0; k < dim; k++)
            ul[k] += g->w[dim * i + k];
        double ut = 0, rt = 0, dot = 0;
        for (int k = 1; k < dim; k++) {
            ut += ul[k] * ul[k];
            rt += ri[k] * ri[k];
            dot += ul[k] * ri[k];
        }
        ut = sqrt(ut), rt = sqrt(rt);
        double uhat = ul[0] + mu * ut;   /* FCLIB's û_N */
        CX_CHECK(ri[0] >= 0);
        CX_CHECK_LE(rt, mu * ri[0] + 1e-9 * rmax);
        CX_CHECK(uhat >= -1e-12);
        CX_CHECK_LE(fabs(uhat * ri[0] + dot), 1e-8 * rmax * (fabs(ul[0]) + ut + 1e-12));
        touching += ri[0] > 0;
        if (ri[0] > 0 && ut > 1e-12 && mu > 0) {   /* slipping: r_T = -mu r_N u_T / |u_T| */
            slipping++;
            CX_CHECK_NEAR(dot, -mu * ri[0] * ut, 1e-6, 1e-9 * rmax * ut);
        }
    }
    fprintf(stderr, "%s in FCLIB's terms: |M v - H r - f| %.1e (|f| %.1e), %d points touching, %d slipping\n",
            path, res, fmax_, touching, slipping);
    CX_CHECK(touching > 0);
    free(r), free(Mv), free(Hr), free(uloc);
    /* freed by hand, as src/scene/problem_fclib.c does: fclib_delete_global
     * differs between FCLIB versions in what it frees (and a double free
     * inside it was seen under ASan with this file) */
    struct fclib_matrix *mats[2] = {g->M, g->H};
    for (int k = 0; k < 2; k++) {
        free(mats[k]->p), free(mats[k]->i), free(mats[k]->x);
        if (mats[k]->info)
            free(mats[k]->info->comment);
        free(mats[k]->info), free(mats[k]);
    }
    free(g->mu), free(g->f), free(g->w);
    if (g->info)
        free(g->info->title), free(g->info->description), free(g->info->math_info);
    free(g->info), free(g);
}
#endif

static void roundtrip(const char *scene, cx_friction law, int fclib, const char *tmp)
{
    cx_diag d;
    cx_scene sc;
    CX_CHECK_OK(cx_scene_open(scene, &sc, &d));
    cx_problem *p = NULL;
    cx_friction_state fr0;
    if (cx_scene_build(&sc, 0, &p, &fr0, &d)) {
        fprintf(stderr, "%s: %s\n", scene, d.msg);
        CX_CHECK(0);
        return;
    }
    fr0.law = law;
    cx_session *a = NULL, *b = NULL;
    CX_CHECK_OK(cx_session_create(&a, &p, &d));
    CX_CHECK_OK(cx_session_set_friction(a, &fr0, &d));
    char path[512];
    snprintf(path, sizeof path, "%s/%s-%s%s", tmp, scene, cx_friction_name(law), fclib ? ".hdf5" : "");
    int st = fclib ? cx_export_fclib(cx_session_problem(a), cx_session_friction(a), path, scene, 0, &d)
                   : cx_export_mm(cx_session_problem(a), cx_session_friction(a), path, scene, 0, &d);
    if (st)
        fprintf(stderr, "export: %s\n", d.msg);
    CX_CHECK_OK(st);
    cx_problem_file pf;
    st = cx_problem_read(path, &pf, &d);
    if (st)
        fprintf(stderr, "read: %s\n", d.msg);
    CX_CHECK_OK(st);
    if (st) {
        cx_session_destroy(&a);
        return;
    }
    CX_CHECK(pf.fr.law == law);
    CX_CHECK_OK(cx_session_create(&b, &pf.p, &d));
    CX_CHECK_OK(cx_session_set_friction(b, &pf.fr, &d));
    const cx_problem *pa = cx_session_problem(a), *pb = cx_session_problem(b);
    CX_CHECK(pa->n == pb->n && pa->m == pb->m && pa->nc == pb->nc);
    CX_CHECK(cx_csc_nnz(&pa->K) == cx_csc_nnz(&pb->K));
    int nmethods = 0;
    for (int k = 0; k < cx_method_count(); k++) {
        const cx_method *m = cx_method_at(k);
        if (cx_method_check(m, pa, law, NULL) || (fclib && uses_geometry(m)))
            continue;
        int sa = solve(a, m), sb = solve(b, m);
        CX_CHECK(sa == sb);
        if (sa || sb)
            continue;
        const cx_iterate *ia = cx_session_iterate(a), *ib = cx_session_iterate(b);
        double e = energy_diff(pa, ia->u, ib->u);
        fprintf(stderr, "%-8s %-7s %-5s %-16s iter %3d/%3d  kkt %.6e/%.6e  energy diff %.1e  %s\n", scene,
                cx_friction_name(law), fclib ? "fclib" : "mm", m->id, ia->iter, ib->iter, ia->kkt, ib->kkt, e,
                cx_reason_id(ib->reason));
        CX_CHECK(ia->iter == ib->iter);
        CX_CHECK(ia->reason == ib->reason);
        CX_CHECK_NEAR(ib->kkt, ia->kkt, 1e-6, 1e-16);
        CX_CHECK_LE(e, 1e-12);
        nmethods++;
#if CX_HAVE_FCLIB
        if (fclib && ia->reason == CX_CONVERGED_KKT && !strcmp(m->id, law == CX_FRICTION_COULOMB && pa->dim == 2
                                                                        ? "ssn-coulomb" : "ssn-tresca"))
            fclib_semantics(path, b);
#endif
    }
    CX_CHECK(nmethods >= (pa->dim == 3 && law == CX_FRICTION_COULOMB ? 1 : 2));
    cx_session_destroy(&a);
    cx_session_destroy(&b);
    cx_problem_file_clear(&pf);
}

int main(void)
{
    char tmp[] = "/tmp/cx_roundtrip_XXXXXX";
    if (!mkdtemp(tmp))
        return 1;
    roundtrip("hertz", CX_FRICTION_NONE, 0, tmp);
    roundtrip("hertz", CX_FRICTION_COULOMB, 0, tmp);
    roundtrip("slider", CX_FRICTION_TRESCA, 0, tmp);
    roundtrip("slider", CX_FRICTION_COULOMB, 0, tmp);
    roundtrip("block3d", CX_FRICTION_NONE, 0, tmp);
    roundtrip("block3d", CX_FRICTION_TRESCA, 0, tmp);
    roundtrip("block3d", CX_FRICTION_COULOMB, 0, tmp);
#if CX_HAVE_FCLIB
    roundtrip("hertz", CX_FRICTION_COULOMB, 1, tmp);
    roundtrip("hertz", CX_FRICTION_NONE, 1, tmp);
    roundtrip("block3d", CX_FRICTION_NONE, 1, tmp);
    roundtrip("block3d", CX_FRICTION_COULOMB, 1, tmp);
#endif
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
    if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", tmp);
    return check_finish("problem_roundtrip");
}
