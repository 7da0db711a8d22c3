/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The backend's one entry: the methods' table, the run's bookkeeping (the
 * kkt error, the limits, the observer) in one place, as solve/solver.c
 * does for the direct path, and what each rank did. */
#include "petsc/petsc_impl.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const cx_petsc_method px_methods[] = {
    {"ssn-tresca", "primal semismooth Newton / active set, a Krylov solve per step: CG + GAMG in 3D, CG + "
                   "BoomerAMG in 2D where PETSc has hypre (000 §4.2 without the Schur reduction)",
     CX_FRICTIONLESS | CX_TRESCA},
    {"petsc-vi", "PETSc SNES vinewtonrsls: reduced-space active-set Newton on the bounds", CX_FRICTIONLESS},
    {"petsc-tao", "PETSc TAO tron: trust-region Newton with gradient projection on the energy", CX_FRICTIONLESS},
};
#define PX_NMETHODS ((int)(sizeof px_methods / sizeof px_methods[0]))

const cx_petsc_method *cx_petsc_method_at(int k)
{
    return k >= 0 && k < PX_NMETHODS ? &px_methods[k] : NULL;
}

const cx_petsc_method *cx_petsc_method_find(const char *id)
{
    for (int k = 0; id && k < PX_NMETHODS; k++)
        if (strcmp(px_methods[k].id, id) == 0)
            return &px_methods[k];
    return NULL;
}

void cx_petsc_result_clear(cx_petsc_result *r)
{
    cx_free(r->u);
    cx_free(r->lN);
    cx_free(r->lT);
    cx_free(r->rows);
    cx_free(r->elems);
    cx_free(r->mem_peak);
    memset(r, 0, sizeof *r);
}

/* The roundoff floor of the kkt error's equilibrium term at the iterate:
 * eps max_i sum_j |K_ij u_j| over the free rows (what rounding leaves of
 * (K u)_i, and about what rounding u itself to doubles leaves of the
 * residual), over the force scale the error divides by, ||f|| + ||N'lN +
 * T'lT|| (infinity norms). No iterate in double precision has a smaller
 * error, whatever the method: on hertz the direct path's solutions sit at
 * 0.4-1.1 times this (128: 1.3e-12 against 3.0e-12; 512: 5.2e-11 against
 * 4.8e-11). It grows as the level squared there: K's largest entries grow
 * with the level at the mesh's singular corner (mesh/hertz.c), the nodal
 * forces shrink with it, and |u| stays (hertz 2048: about 8e-10, above the
 * default tolerance). Rows of sys->K over the free dofs (the prescribed
 * columns are zero in it, their share is in f); r->u on every rank;
 * collective. work: n doubles. */
static double px_kkt_floor(px_run *run, double *work)
{
    px_system *sys = run->sys;
    const cx_problem *p = sys->p;
    const cx_petsc_result *r = run->r;
    double big = 0, all = 0;
    for (PetscInt row = sys->rstart; row < sys->rend; row++) {
        if (p->map.free_of[row] < 0)
            continue;
        PetscInt nc;
        const PetscInt *cols;
        const PetscScalar *vals;
        if (MatGetRow(sys->K, row, &nc, &cols, &vals) != 0)
            return NAN;
        double sum = 0;
        for (PetscInt q = 0; q < nc; q++) {
            int j = p->map.free_of[cols[q]];
            if (j >= 0)
                sum += fabs(vals[q] * r->u[j]);
        }
        (void)MatRestoreRow(sys->K, row, &nc, &cols, &vals);
        big = fmax(big, sum);
    }
    MPI_Allreduce(&big, &all, 1, MPI_DOUBLE, MPI_MAX, sys->comm);
    /* the force scale, as cx_kkt_error_Ku takes it */
    double nf = 0, nB = 0;
    for (int j = 0; j < p->n; j++)
        nf = fmax(nf, fabs(p->f[j]));
    cx_csc_gemv_t(&p->N, 1.0, r->lN, 0.0, work);
    if (run->fr->law != CX_FRICTION_NONE)
        cx_csc_gemv_t(&p->T, 1.0, r->lT, 1.0, work);
    for (int j = 0; j < p->n; j++)
        nB = fmax(nB, fabs(work[j]));
    return nf + nB > 0 ? DBL_EPSILON * all / (nf + nB) : 0.0;
}

int px_run_check(px_run *run, int iter, int ncontact, int nstick, int nslip, int nchanged, int krylov,
                 double rtol)
{
    const cx_problem *p = run->sys->p;
    cx_petsc_result *r = run->r;
    /* every rank holds the same iterate: the same error everywhere */
    (void)PetscLogEventBegin(px_ev_kkt, 0, 0, 0, 0);
    /* K u from the residual f - K u the method gathered last (sys->whole,
     * over all dofs): the serial p->K is not read, so a driver may free it */
    {
        double *Ku = run->work + p->n + p->m + p->nt + 1;
        const PetscScalar *w;
        if (VecGetArrayRead(run->sys->whole, &w) == 0) {
            for (int j = 0; j < p->n; j++)
                Ku[j] = p->f[j] - w[p->map.all_of[j]];
            (void)VecRestoreArrayRead(run->sys->whole, &w);
            r->kkt = cx_kkt_error_Ku(p, run->fr, r->u, r->lN, r->lT, Ku, run->work, NULL, &r->kkt_parts);
        } else {
            r->kkt = NAN;
        }
    }
    /* the floor at every iterate not yet converged (a pass over K's rows,
     * less than a product with K; every rank computes the same: the same
     * decision below) */
    double last = run->last_kkt;
    run->last_kkt = r->kkt;
    if (isfinite(r->kkt) && r->kkt > run->opt->tol)
        r->kkt_floor = px_kkt_floor(run, run->work);
    (void)PetscLogEventEnd(px_ev_kkt, 0, 0, 0, 0);
    r->iterations = iter;
    cx_petsc_step st = {iter, r->kkt, ncontact, nstick, nslip, nchanged, krylov, rtol,
                        cx_clock_now() - run->t0};
    int stop = run->obs && run->obs(run->ctx, &st) != 0;
    /* what differs between ranks (the clock, an observer) is decided by
     * all of them together, so that none is left waiting in a collective */
    int late = run->opt->time_limit > 0 && st.time > run->opt->time_limit;
    int flags[2] = {stop, late}, all[2];
    MPI_Allreduce(flags, all, 2, MPI_INT, MPI_MAX, run->sys->comm);
    /* stalled as the direct path's solver says it: no fall below half the
     * best error for stall_window iterations */
    if (r->kkt < 0.5 * run->best || iter == 1) {
        run->best = r->kkt;
        run->best_iter = iter;
    }
    if (!isfinite(r->kkt))
        r->reason = CX_DIVERGED_NAN;
    else if (r->kkt <= run->opt->tol)
        r->reason = CX_CONVERGED_KKT;
    else if (nchanged == 0 && iter > 1 && r->kkt > 0.5 * last && r->kkt <= 4 * r->kkt_floor) {
        /* the sets held, the step's solve did not halve the error, and it
         * is within a few times the floor (the direct path's solutions sit
         * at 0.4-1.1 times it): no step in double precision goes lower,
         * so the run says so instead of stepping on to the stall window */
        r->reason = CX_DIVERGED_STALL;
        snprintf(r->message, sizeof r->message,
                 "kkt %.2e is at the roundoff floor of K u for this problem (eps max_i sum_j |K_ij u_j| over "
                 "the force scale: %.2e); tol %.0e is below what double precision reaches here",
                 r->kkt, r->kkt_floor, run->opt->tol);
    }
    else if (all[0])
        r->reason = CX_CANCELLED;
    else if (all[1])
        r->reason = CX_DIVERGED_TIME;
    else if (iter >= run->opt->max_iter)
        r->reason = CX_DIVERGED_MAXIT;
    else if (run->opt->stall_window > 0 && iter - run->best_iter >= run->opt->stall_window)
        r->reason = CX_DIVERGED_STALL;
    return r->reason != CX_ITERATING;
}

int cx_petsc_solve(const cx_problem *p, const cx_friction_state *fr, const char *method,
                   const cx_options *opt, cx_petsc_observer obs, void *ctx, cx_petsc_result *r,
                   cx_diag *d)
{
    CX_TRY(cx_petsc_initialize(d));
    CX_TRY(cx_petsc_check(p, method, fr->law, d));
    memset(r, 0, sizeof *r);
    r->kkt = NAN;   /* no iterate yet */
    int status = CX_OK;
    px_system sys = {0};
    double *s = NULL;
    cx_friction_state frs = *fr;
    r->nranks = cx_petsc_size();
    r->u = CX_NEW(double, p->n + 1);
    r->lN = CX_NEW(double, p->m + 1);
    r->lT = CX_NEW(double, p->nt + 1);
    r->rows = CX_NEW(int, r->nranks);
    r->elems = CX_NEW(int, r->nranks);
    r->mem_peak = CX_NEW(double, r->nranks);
    double *work = CX_NEW(double, 2 * (size_t)p->n + p->m + p->nt + 1);
    if (fr->law == CX_FRICTION_TRESCA && !fr->s) {   /* the session's rule: s_i = bound x weight_i */
        s = CX_NEW(double, p->m + 1);
        for (int i = 0; s && i < p->m; i++)
            s[i] = fr->slip_bound * p->contact.weight[i];
        frs.s = s;
    }
    if (!r->u || !r->lN || !r->lT || !r->rows || !r->elems || !r->mem_peak || !work ||
        (fr->law == CX_FRICTION_TRESCA && !frs.s)) {
        status = cx_diag_set(d, CX_ENOMEM, "out of memory");
        goto fail;
    }
    double t0 = cx_clock_now();
    (void)PetscLogEventBegin(px_ev_assemble, 0, 0, 0, 0);
    status = px_system_create(&sys, p, fr->law == CX_FRICTION_TRESCA, d);
    (void)PetscLogEventEnd(px_ev_assemble, 0, 0, 0, 0);
    if (status != CX_OK)
        goto fail;
    r->t_setup = cx_clock_now() - t0;
    px_run run = {&sys, &frs, opt, obs, ctx, r, work, cx_clock_now(), INFINITY, 0, INFINITY};
    if (strcmp(method, "petsc-vi") == 0)
        status = px_vi_solve(&run, d);
    else if (strcmp(method, "petsc-tao") == 0)
        status = px_tao_solve(&run, d);
    else
        status = px_ssn_solve(&run, d);
    r->t_solve = cx_clock_now() - run.t0;
    if (status != CX_OK)
        goto fail;
    if ((status = px_allgather_int(&sys, (int)(sys.rend - sys.rstart), r->rows, d)) != CX_OK ||
        (status = px_allgather_int(&sys, sys.nelems, r->elems, d)) != CX_OK ||
        (status = px_allgather_double(&sys, px_peak_memory(), r->mem_peak, d)) != CX_OK)
        goto fail;
    px_system_destroy(&sys);
    cx_free(work);
    cx_free(s);
    return CX_OK;
fail:
    px_system_destroy(&sys);
    cx_free(work);
    cx_free(s);
    cx_petsc_result_clear(r);
    return status;
}

/* The per-point status of a solution, as the direct path's methods set it
 * (cli/solve_petsc.c and the explorer draw it). */
void cx_petsc_point_status(const cx_problem *p, const cx_friction_state *fr, const double *lN, const double *lT,
                         unsigned char *st)
{
    int dt = p->dim - 1;
    double lmax = 0;   /* a force recovered from a residual is in contact above its noise */
    for (int i = 0; i < p->m; i++)
        lmax = fmax(lmax, lN[i]);
    for (int i = 0; i < p->m; i++) {
        if (lN[i] <= 1e-9 * lmax) {
            st[i] = CX_PT_FREE;
            continue;
        }
        if (fr->law != CX_FRICTION_TRESCA) {
            st[i] = CX_PT_CONTACT;
            continue;
        }
        double n2 = 0, s = fr->slip_bound * p->contact.weight[i];
        for (int c = 0; c < dt; c++)
            n2 += lT[dt * i + c] * lT[dt * i + c];
        st[i] = sqrt(n2) < s * (1 - 1e-9) ? CX_PT_STICK
                : (dt == 1 && lT[i] < 0)  ? CX_PT_SLIP_NEG
                                          : CX_PT_SLIP_POS;
    }
}
