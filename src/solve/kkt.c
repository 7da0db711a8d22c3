/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The one error measure of doc/design.md §3: dimensionless, solver-independent,
 * zero exactly at a solution, and unchanged when the scene's units change
 * (every term is a ratio of like quantities; rho = mult / disp). */
#include "solve/problem.h"

#include <math.h>

static double norminf(int n, const double *x)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s = fmax(s, fabs(x[i]));
    return s;
}

void cx_kkt_scales(const cx_problem *p, cx_friction law, const double *u, const double *lN,
                   const double *lT, double *mult, double *disp)
{
    /* multiplier scale: the largest nodal force, applied or of contact;
     * displacement scale: the largest displacement, floored by the
     * displacement that force would produce at the stiffest dof, so that a
     * zero iterate still gets a finite rho. */
    double L = norminf(p->n, p->f);
    L = fmax(L, norminf(p->m, lN));
    if (law != CX_FRICTION_NONE)
        L = fmax(L, norminf(p->nt, lT));
    double k = p->kscale > 0 ? p->kscale : 1;
    if (L == 0)
        L = k * fmax(norminf(p->n, u), 1e-300);
    *mult = L;
    *disp = fmax(norminf(p->n, u), L / k);
}

/* The natural-map residuals of the contact and friction conditions, into
 * k->contact and k->friction; work: m + nt doubles. */
static void kkt_maps(const cx_problem *p, const cx_friction_state *fr, const double *u,
                     const double *lN, const double *lT, double *work, cx_kkt *k)
{
    int m = p->m, dim = p->dim;
    int fric = fr->law != CX_FRICTION_NONE;
    double *Nu = work, *Tu = work + m;
    double L, U;
    cx_kkt_scales(p, fr->law, u, lN, lT, &L, &U);
    double rho = L / U;
    cx_csc_gemv(&p->N, 1.0, u, 0.0, Nu);
    double rc = 0;
    for (int i = 0; i < m; i++)
        rc = fmax(rc, fabs(lN[i] - fmax(0.0, lN[i] + rho * (Nu[i] - p->g[i]))));
    k->contact = rc / L;

    double rf = 0;
    if (fric) {
        cx_csc_gemv(&p->T, 1.0, u, 0.0, Tu);
        int dt = dim - 1;
        for (int i = 0; i < m; i++) {
            double z[2], nz = 0, s = cx_friction_slip_bound(fr, i, lN[i]);
            for (int c = 0; c < dt; c++) {
                z[c] = lT[dt * i + c] + rho * Tu[dt * i + c];
                nz += z[c] * z[c];
            }
            nz = sqrt(nz);
            double scale = nz > s ? s / nz : 1.0;
            for (int c = 0; c < dt; c++)
                rf = fmax(rf, fabs(lT[dt * i + c] - scale * z[c]));
        }
    }
    k->friction = rf / L;
    k->total = fmax(k->equilibrium, fmax(k->contact, k->friction));
}

/* r = N' lN + T' lT (n); false if an input is not finite. */
static int kkt_contact_forces(const cx_problem *p, cx_friction law, const double *u,
                              const double *lN, const double *lT, double *r)
{
    int fric = law != CX_FRICTION_NONE;
    if (!cx_vec_finite(p->n, u) || !cx_vec_finite(p->m, lN) || (fric && !cx_vec_finite(p->nt, lT)))
        return 0;
    cx_csc_gemv_t(&p->N, 1.0, lN, 0.0, r);
    if (fric)
        cx_csc_gemv_t(&p->T, 1.0, lT, 1.0, r);
    return 1;
}

static double kkt_ratio(double num, double den) { return den > 0 ? num / den : (num > 0 ? 1.0 : 0.0); }

double cx_kkt_error(const cx_problem *p, const cx_friction_state *fr, const double *u,
                    const double *lN, const double *lT, double *work, cx_counters *cnt,
                    cx_kkt *parts)
{
    return cx_kkt_error_Ku(p, fr, u, lN, lT, NULL, work, cnt, parts);
}

double cx_kkt_error_Ku(const cx_problem *p, const cx_friction_state *fr, const double *u,
                       const double *lN, const double *lT, const double *Ku, double *work,
                       cx_counters *cnt, cx_kkt *parts)
{
    int n = p->n;
    cx_kkt k = {INFINITY, INFINITY, INFINITY, INFINITY};
    double *r = work;
    if (!kkt_contact_forces(p, fr->law, u, lN, lT, r)) {
        if (parts)
            *parts = k;
        return INFINITY;
    }
    /* ---- equilibrium: K u - f + N' lN + T' lT ---- */
    double nB = norminf(n, r), nf = norminf(n, p->f);
    if (Ku) {
        cx_vec_axpy(n, 1.0, Ku, r);
    } else {
        cx_csc_gemv(&p->K, 1.0, u, 1.0, r);
        if (cnt)
            cnt->matvecs++;
    }
    cx_vec_axpy(n, -1.0, p->f, r);
    k.equilibrium = kkt_ratio(norminf(n, r), nf + nB);
    kkt_maps(p, fr, u, lN, lT, work + n, &k);
    if (parts)
        *parts = k;
    return k.total;
}

double cx_kkt_error_condensed(const cx_problem *p, const cx_friction_state *fr, const double *S,
                              const double *fc, const double *u, const double *lN,
                              const double *lT, double *work, cx_kkt *parts)
{
    int n = p->n, nc = p->nc;
    cx_kkt k = {INFINITY, INFINITY, INFINITY, INFINITY};
    double *r = work;
    if (!kkt_contact_forces(p, fr->law, u, lN, lT, r)) {
        if (parts)
            *parts = k;
        return INFINITY;
    }
    /* ---- equilibrium on the contact rows: S u_c - fc + (N' lN + T' lT)_c ---- */
    double nB = norminf(n, r), nf = norminf(n, p->f), nr = 0;
    for (int a = 0; a < nc; a++) {
        double sum = r[p->cdofs[a]] - fc[a];
        const double *Sa = S + (size_t)nc * a;   /* row a = column a: S is symmetric */
        for (int b = 0; b < nc; b++)
            sum += Sa[b] * u[p->cdofs[b]];
        nr = fmax(nr, fabs(sum));
    }
    k.equilibrium = kkt_ratio(nr, nf + nB);
    kkt_maps(p, fr, u, lN, lT, work + n, &k);
    if (parts)
        *parts = k;
    return k.total;
}
