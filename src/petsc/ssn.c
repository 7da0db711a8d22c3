/* SPDX-License-Identifier: GPL-3.0-or-later */
/* ssn-tresca on the PETSc backend: the primal semismooth Newton / active
 * set iteration of src/solve/ssn_tresca.c (paper 000 §4.2) without its
 * Schur reduction.
 *
 * The sets are predicted as there (contact where lN + rho (N u - g) > 0,
 * stick where |lT + rho T u| <= s, slip beyond, the first step bonded:
 * every point in contact and sticking, which holds the body whatever K's
 * null space). Since every contact row pins one dof, a step is a linear
 * solve with K in which the active dofs are pinned (u_j = g_i / a_i in
 * contact, 0 sticking): K copied, the pinned rows and columns made
 * identity with their values moved to the right-hand side, the slip
 * forces added to it (2D: -s sign; 3D: -s q with the linearised
 * tangential stiffness beta P added to K's node block, as ssn-tresca
 * does), and the system solved by CG preconditioned with algebraic
 * multigrid: in 3D GAMG (the rigid-body modes as its near null space), in
 * 2D hypre's BoomerAMG where PETSc has hypre (ssn_ksp says why). The
 * multiplier of a pinned
 * dof is what its equilibrium row lacks: (f - K u)_j / a_i.
 *
 * Inexact Newton: the step's relative residual (the forcing term) is
 * 1e-2 times the last kkt error, within [1e-14, 1e-2], and a hundred times
 * smaller than the last one when the sets have not changed (what is left
 * is the linear solve's error); where the step is then linear in u (no 3D
 * slip point) it is solved at once to a tenth of the tolerance over the
 * last error, with the last step's preconditioner (the matrix is the
 * same). Every other step sets its preconditioner up on its own matrix
 * (GAMG keeping its prolongator while the sets change little). The run
 * stops on the kkt error alone.
 *
 * Each step communicates: the matrix copy and the pinning (local), the
 * Krylov solve (each CG iteration one halo exchange of the product with K,
 * the multigrid's smoothing and restriction on every level, two
 * all-reduces), one
 * product f - K u, and two all-gathers of a vector of the system (u and
 * the residual), after which every rank holds the whole iterate and
 * predicts the same sets and computes the same kkt error. */
#include "petsc/petsc_impl.h"

#include <math.h>
#include <string.h>

typedef struct {
    px_system *sys;
    const cx_problem *p;
    int tangential, dt, nrow;
    double rho;
    signed char *set, *prev;   /* nrow: normal 1 contact / 0 free; tangential 0 stick, +-1 slip */
    double *q, *beta;          /* 3D slip direction (nt), linearised stiffness (m) */
    PetscInt *rows;            /* owned pinned rows */
    PetscScalar *vals;         /* their values */
    Mat A;
    KSP ksp[3];                /* the stages (ssn_ksp): CG + the first preconditioner, then the
                                  fallbacks */
    int gamg[3];               /* stage k's preconditioner is GAMG (its prolongator kept or not per step) */
    char name[3][64];          /* stage k's solver, as the summaries name it */
    int nstage;
    int stage;                 /* the one in use: a failure moves on for the rest of the run */
    int failed;                /* the last solve failed: no reuse of its preconditioner */
    Vec U, B, X, R, U0;
} ssn_ctx;

/* N_i u and T_t u from the free-dof u */
static double ssn_rowval(const ssn_ctx *c, int dof, double a, const double *u)
{
    int j = c->p->map.free_of[dof];
    return j >= 0 ? a * u[j] : 0.0;
}

static void ssn_predict(ssn_ctx *c, const cx_friction_state *fr, const double *u, const double *lN,
                        const double *lT)
{
    const cx_problem *p = c->p;
    const px_system *sys = c->sys;
    int m = p->m;
    for (int i = 0; i < m; i++)
        c->set[i] = lN[i] + c->rho * (ssn_rowval(c, sys->ndof[i], sys->nval[i], u) - p->g[i]) > 0;
    if (!c->tangential)
        return;
    for (int i = 0; i < m; i++) {
        if (c->dt == 1) {
            double z = lT[i] + c->rho * (sys->tdof[i] >= 0 ? ssn_rowval(c, sys->tdof[i], sys->tval[i], u) : 0);
            c->set[m + i] = z > fr->s[i] ? 1 : (z < -fr->s[i] ? -1 : 0);
            continue;
        }
        double z[2];
        for (int a = 0; a < 2; a++) {
            int t = 2 * i + a;
            z[a] = lT[t] + c->rho * (sys->tdof[t] >= 0 ? ssn_rowval(c, sys->tdof[t], sys->tval[t], u) : 0);
        }
        double nz = sqrt(z[0] * z[0] + z[1] * z[1]);
        int slip = nz > fr->s[i];
        c->set[m + 2 * i] = c->set[m + 2 * i + 1] = (signed char)slip;
        c->q[2 * i] = slip ? z[0] / nz : 0;
        c->q[2 * i + 1] = slip ? z[1] / nz : 0;
        /* capped at 100 times the stiffest dof of K: beta grows without
         * bound as |z| comes down to s, and a spring far stiffer than K
         * only worsens the Krylov solve's conditioning. A guard, not a
         * fix: it did not change prism 8's preconditioner failure at step
         * 8 (ssn_ksp). It changes the step, not the solution (there,
         * P T u = 0) */
        c->beta[i] = slip ? fmin(fr->s[i] * c->rho / (nz - fr->s[i]), 1e2 * c->sys->kscale) : 0;
    }
}

static void ssn_bonded(ssn_ctx *c)
{
    for (int r = 0; r < c->nrow; r++)
        c->set[r] = r < c->p->m ? 1 : 0;
}

static int ssn_owned(const px_system *sys, int row) { return row >= sys->rstart && row < sys->rend; }

/* The step's system into c->A, c->B, and the pinned values into U. */
static int ssn_system(ssn_ctx *c, const cx_friction_state *fr, cx_diag *d)
{
    int status = CX_OK;
    px_system *sys = c->sys;
    const cx_problem *p = c->p;
    int m = p->m, npin = 0;
    PX(MatCopy(sys->K, c->A, SAME_NONZERO_PATTERN));
    PX(VecCopy(sys->f, c->B));
    for (int i = 0; i < m; i++)
        if (c->set[i] == 1 && ssn_owned(sys, sys->ndof[i])) {
            c->rows[npin] = sys->ndof[i];
            c->vals[npin++] = p->g[i] / sys->nval[i];
        }
    for (int i = 0; c->tangential && i < m; i++) {
        for (int a = 0; a < c->dt; a++) {
            int t = c->dt * i + a, dof = sys->tdof[t];
            if (dof < 0 || !ssn_owned(sys, dof))
                continue;
            if (c->set[m + t] == 0) {
                c->rows[npin] = dof;
                c->vals[npin++] = 0.0;
                continue;
            }
            /* slip: the force -T' lT with lT = s sign (2D) or s q (3D) */
            double lt = c->dt == 1 ? c->set[m + t] * fr->s[i] : fr->s[i] * c->q[t];
            PX(VecSetValue(c->B, dof, -sys->tval[t] * lt, ADD_VALUES));
            if (c->dt == 2) {
                const double *q = c->q + 2 * i;
                for (int b = 0; b < 2; b++) {
                    int tb = 2 * i + b;
                    if (sys->tdof[tb] < 0)
                        continue;
                    double P = (a == b ? 1.0 : 0.0) - q[a] * q[b];
                    PX(MatSetValue(c->A, dof, sys->tdof[tb], c->beta[i] * P * sys->tval[t] * sys->tval[tb],
                                   ADD_VALUES));
                }
            }
        }
    }
    PX(VecAssemblyBegin(c->B));
    PX(VecAssemblyEnd(c->B));
    PX(MatAssemblyBegin(c->A, MAT_FINAL_ASSEMBLY));
    PX(MatAssemblyEnd(c->A, MAT_FINAL_ASSEMBLY));
    PX(VecSet(c->X, 0.0));
    PX(VecSetValues(c->X, npin, c->rows, c->vals, INSERT_VALUES));
    PX(VecAssemblyBegin(c->X));
    PX(VecAssemblyEnd(c->X));
    PX(MatZeroRowsColumns(c->A, npin, c->rows, sys->kscale, c->X, c->B));
    /* the start: the last solution with the pinned values */
    PX(VecSetValues(c->U, npin, c->rows, c->vals, INSERT_VALUES));
    PX(VecAssemblyBegin(c->U));
    PX(VecAssemblyEnd(c->U));
    return CX_OK;
fail:
    return status;
}

/* The new iterate's multipliers from the residual f - K u (sys->whole). */
static int ssn_multipliers(ssn_ctx *c, const cx_friction_state *fr, cx_petsc_result *r, cx_diag *d)
{
    int status = CX_OK;
    px_system *sys = c->sys;
    const cx_problem *p = c->p;
    int m = p->m;
    const PetscScalar *res;
    PX(VecGetArrayRead(sys->whole, &res));
    for (int i = 0; i < m; i++)
        r->lN[i] = c->set[i] == 1 ? res[sys->ndof[i]] / sys->nval[i] : 0.0;
    for (int i = 0; c->tangential && i < m; i++) {
        double tu[2] = {0, 0};
        for (int a = 0; a < c->dt; a++) {
            int t = c->dt * i + a;
            tu[a] = sys->tdof[t] >= 0 ? ssn_rowval(c, sys->tdof[t], sys->tval[t], r->u) : 0;
        }
        for (int a = 0; a < c->dt; a++) {
            int t = c->dt * i + a;
            if (c->set[m + t] == 0)
                r->lT[t] = sys->tdof[t] >= 0 ? res[sys->tdof[t]] / sys->tval[t] : 0.0;
            else if (c->dt == 1)
                r->lT[t] = c->set[m + t] * fr->s[i];
            else {   /* lT = s q + beta P T u */
                const double *q = c->q + 2 * i;
                double qt = q[0] * tu[0] + q[1] * tu[1];
                r->lT[t] = fr->s[i] * q[a] + c->beta[i] * (tu[a] - qt * q[a]);
            }
        }
    }
    PX(VecRestoreArrayRead(sys->whole, &res));
    return CX_OK;
fail:
    return status;
}

static void ssn_clear(ssn_ctx *c)
{
    if (c->A)
        MatDestroy(&c->A);
    for (int k = 0; k < 3; k++)
        if (c->ksp[k])
            KSPDestroy(&c->ksp[k]);
    if (c->U0)
        VecDestroy(&c->U0);
    if (c->U)
        VecDestroy(&c->U);
    if (c->B)
        VecDestroy(&c->B);
    if (c->X)
        VecDestroy(&c->X);
    if (c->R)
        VecDestroy(&c->R);
    cx_free(c->set);
    cx_free(c->prev);
    cx_free(c->q);
    cx_free(c->beta);
    cx_free(c->rows);
    cx_free(c->vals);
}

/* A Krylov solver of the steps: CG on the true residual, relative to the
 * step's initial residual (the Newton residual at the last iterate with
 * the new sets: the inexact-Newton condition), preconditioned by type
 * (PETSC_OPTIONS with the prefix change it: -cx_pc_type gamg). The stages
 * a run moves through when a preconditioner fails (px_ssn_solve):
 *
 * "cx_": the first. 3D: GAMG with Chebyshev smoothing (its default) and
 * the rigid-body near null space. 2D: BoomerAMG where PETSc has hypre. On
 * hertz GAMG's iterations per solve grew with the level whatever its
 * settings (with the defaults 1.5x per level: 128 took 29, 256 45.6; with
 * the graph's weak couplings dropped at 0.02 and three Chebyshev steps
 * per level 10.6 at 128, 12.2 at 256, 26 at 512, and at 1024 on 2 ranks
 * an earlier run did not converge): the mesh's elliptical map from the
 * square (mesh/hertz.c) has a singular Jacobian at the corner u = v = 1,
 * the point at 45 degrees on the arc, where the elements flatten more
 * with each level, and GAMG's smoothed aggregation does not follow that
 * anisotropy. BoomerAMG's classical coarsening does: 4.6-6.6 iterations
 * per solve from hertz 128 to 2048 (1024: 5.7, 2048: 6.6 on 2 ranks). Its
 * iteration costs about three of GAMG's (operator complexity 2.9 on hertz
 * 256 with hypre's defaults; HMIS coarsening, ext+i interpolation or
 * aggressive first-level coarsening, which lower it, took more iterations
 * and more time there), and its set-up is not worth keeping across steps
 * whose sets changed: kept while they changed in at most 5 % of the
 * contact rows, hertz 256 (1 rank) took 321 iterations in 11 solves
 * against 52, its steps 6-11 30-78 each. -cx_pc_type gamg restores GAMG
 * in 2D, with its 2D settings (below).
 * "cx_sor_": GAMG's levels smoothed by symmetric SOR instead of
 * Chebyshev. A 3D slip point adds beta P with beta = s rho / (|z| - s), as
 * large as |z| is close to s, and Chebyshev's eigenvalue estimate then
 * made the preconditioner indefinite (prism 5; prism 3 on 2 ranks); SOR
 * in turn failed on a coarse level of hertz 128 (a zero pivot), so a run
 * starts with the first and changes for good at the first step where a
 * fresh set-up on that step's matrix fails too (with GAMG built afresh on
 * every step none of prism 3-7, block3d 8, hertz 16-512 gets there).
 * "cx_hypre_": where both GAMG stages failed (prism 8, step 8:
 * "SUBPC_ERROR" after 4 iterations), BoomerAMG, where PETSc has it and
 * the first stage was not BoomerAMG already. */
static int ssn_ksp(px_system *sys, const char *prefix, PCType type, KSP *ksp, int *is_gamg, char *name,
                   size_t len, cx_diag *d)
{
    int status = CX_OK;
    PC pc;
    PCType t;
    PX(KSPCreate(sys->comm, ksp));
    PX(KSPSetType(*ksp, KSPCG));
    PX(KSPSetNormType(*ksp, KSP_NORM_UNPRECONDITIONED));
    PX(KSPSetInitialGuessNonzero(*ksp, PETSC_TRUE));
    PX(KSPConvergedDefaultSetUIRNorm(*ksp));
    PX(KSPGetPC(*ksp, &pc));
    PX(PCSetType(pc, type));
    PX(KSPSetOptionsPrefix(*ksp, prefix));   /* PETSC_OPTIONS="-cx_ksp_monitor ..." */
    if (strcmp(prefix, "cx_sor_") == 0) {
        static const char *const dflt[][2] = {{"-cx_sor_mg_levels_ksp_type", "richardson"},
                                              {"-cx_sor_mg_levels_pc_type", "sor"}};
        for (int k = 0; k < 2; k++) {
            PetscBool has = PETSC_FALSE;
            PX(PetscOptionsHasName(NULL, NULL, dflt[k][0], &has));
            if (!has)
                PX(PetscOptionsSetValue(NULL, dflt[k][0], dflt[k][1]));
        }
    }
    PX(KSPSetFromOptions(*ksp));
    PX(PCGetType(pc, &t));
    *is_gamg = strcmp(t, PCGAMG) == 0;
    if (*is_gamg)   /* set per step by px_ssn_solve: kept while the sets change little */
        PX(PCGAMGSetReuseInterpolation(pc, PETSC_FALSE));
    if (*is_gamg && sys->dim == 2 && strcmp(prefix, "cx_") == 0) {
        /* GAMG in 2D (-cx_pc_type gamg, or no hypre): the graph's weak
         * couplings dropped (threshold 0.02) and three Chebyshev steps
         * per level instead of two; with GAMG's defaults the iterations
         * per solve grew about 1.5x per level (hertz 128: 14.1, 256: 22.8
         * with the set-up afresh), with these 10.3 and 11.6; a higher
         * threshold (0.05) was worse. Options given win: the smoothers
         * read theirs at the first set-up, after this */
        PetscBool has = PETSC_FALSE;
        PX(PetscOptionsHasName(NULL, NULL, "-cx_pc_gamg_threshold", &has));
        if (!has) {
            PetscReal thr = 0.02;
            PX(PCGAMGSetThreshold(pc, &thr, 1));
        }
        PX(PetscOptionsHasName(NULL, NULL, "-cx_mg_levels_ksp_max_it", &has));
        if (!has)
            PX(PetscOptionsSetValue(NULL, "-cx_mg_levels_ksp_max_it", "3"));
    }
    px_ksp_name(*ksp, name, len);
    if (strcmp(prefix, "cx_sor_") == 0 && *is_gamg)
        snprintf(name + strlen(name), len - strlen(name), " (SOR)");
    return CX_OK;
fail:
    return status;
}

int px_ssn_solve(px_run *run, cx_diag *d)
{
    int status = CX_OK;
    px_system *sys = run->sys;
    const cx_problem *p = sys->p;
    const cx_friction_state *fr = run->fr;
    cx_petsc_result *r = run->r;
    ssn_ctx c = {0};
    c.sys = sys;
    c.p = p;
    c.tangential = fr->law == CX_FRICTION_TRESCA;
    c.dt = p->dim - 1;
    c.nrow = p->m + (c.tangential ? p->nt : 0);
    c.rho = 1e-3 * sys->kscale;   /* ssn-tresca's default rho (its header says why it is small) */
    int nloc = (int)(sys->rend - sys->rstart);
    c.set = CX_NEW(signed char, c.nrow + 1);
    c.prev = CX_NEW(signed char, c.nrow + 1);
    c.q = CX_NEW(double, p->nt + 1);
    c.beta = CX_NEW(double, p->m + 1);
    c.rows = CX_NEW(PetscInt, nloc + 1);
    c.vals = CX_NEW(PetscScalar, nloc + 1);
    if (!c.set || !c.prev || !c.q || !c.beta || !c.rows || !c.vals) {
        status = cx_diag_set(d, CX_ENOMEM, "out of memory");
        goto fail;
    }
    PX(MatDuplicate(sys->K, MAT_COPY_VALUES, &c.A));
    PX(MatSetOption(c.A, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));   /* K's pattern, for the next copy */
    {
        MatNullSpace nsp;
        PX(MatGetNearNullSpace(sys->K, &nsp));
        PX(MatSetNearNullSpace(c.A, nsp));
    }
    PX(MatCreateVecs(sys->K, &c.U, &c.B));
    PX(VecDuplicate(c.U, &c.X));
    PX(VecDuplicate(c.U, &c.R));
    PX(VecSet(c.U, 0.0));
#ifdef PETSC_HAVE_HYPRE
    PCType first = sys->dim == 2 ? PCHYPRE : PCGAMG;
#else
    PCType first = PCGAMG;
#endif
    if ((status = ssn_ksp(sys, "cx_", first, &c.ksp[0], &c.gamg[0], c.name[0], sizeof c.name[0], d)) != CX_OK ||
        (status = ssn_ksp(sys, "cx_sor_", PCGAMG, &c.ksp[1], &c.gamg[1], c.name[1], sizeof c.name[1], d)) !=
            CX_OK)
        goto fail;
    c.nstage = 2;
#ifdef PETSC_HAVE_HYPRE
    if (c.gamg[0]) {
        if ((status = ssn_ksp(sys, "cx_hypre_", PCHYPRE, &c.ksp[2], &c.gamg[2], c.name[2], sizeof c.name[2], d)) !=
            CX_OK)
            goto fail;
        c.nstage = 3;
    }
#endif
    snprintf(r->solver, sizeof r->solver, "%s", c.name[0]);
    PX(VecDuplicate(c.U, &c.U0));

    double kkt_prev = INFINITY, eta_prev = 1e-2;
    ssn_bonded(&c);
    memset(c.prev, 0x7f, (size_t)c.nrow);
    for (int k = 1;; k++) {
        if (k > 1)
            ssn_predict(&c, fr, r->u, r->lN, r->lT);
        int nchanged = 0;
        for (int i = 0; i < c.nrow; i++)
            nchanged += c.set[i] != c.prev[i];
        if (k == 1)
            nchanged = 0;
        memcpy(c.prev, c.set, (size_t)c.nrow);
        double eta = fmin(1e-2, fmax(1e-14, 1e-2 * kkt_prev));
        int slip3d = 0;   /* 3D slip points: beta and q are linearised */
        for (int i = 0; c.tangential && c.dt == 2 && i < p->m; i++)
            slip3d += c.set[i] == 1 && c.set[p->m + 2 * i] != 0;
        if (k > 1 && nchanged == 0)
            eta = fmax(1e-14, fmin(eta, 1e-2 * eta_prev));
        if (k > 1 && nchanged == 0 && slip3d == 0) {
            /* the sets held and the step is linear in u (no 3D slip
             * direction to linearise): the sets' solution is this step's
             * exact solve, so the step is solved at once to what the
             * tolerance asks of it (the solve's residual is relative to
             * the last iterate's, about kkt_prev) instead of a hundredfold
             * per step (hertz 256: two more steps, each with its own set-up).
             * With 3D slip the linearisation's own error (quadratic, kkt
             * 2e-4 -> 7e-6 -> 5e-9 on prism 5 whatever the solve's
             * accuracy) is what is left, and the rule above is kept */
            double tol = run->opt->tol > 0 ? run->opt->tol : 1e-10;
            eta = fmax(1e-14, fmin(eta, 1e-1 * tol / fmax(kkt_prev, tol)));
        }
        eta_prev = eta;
        (void)PetscLogEventBegin(px_ev_system, 0, 0, 0, 0);
        status = ssn_system(&c, fr, d);
        (void)PetscLogEventEnd(px_ev_system, 0, 0, 0, 0);
        if (status != CX_OK)
            goto fail;
        KSPConvergedReason kr;
        PetscInt its, its0 = 0;
        /* the same sets and no 3D slip point (whose beta and q change the
         * matrix from step to step; a preconditioner kept across those
         * took 25-39 iterations per step on prism 5 against 8-13): the
         * same matrix, so the last step's preconditioner serves again
         * without a set-up; a failure below builds a fresh one */
        int reuse = k > 1 && nchanged == 0 && slip3d == 0 && !c.failed, fresh = 0;
        /* GAMG's aggregates and prolongator kept from the last set-up
         * (its Galerkin products and Chebyshev bounds formed again) while
         * the sets change in at most 5 % of the rows; after larger changes
         * (the first steps after the bonded one) built afresh: kept from
         * the bonded step they served the later steps badly (hertz 128:
         * 23-32 iterations per step against 7-17; prism 7: 199 in all
         * against 102) and sent prism 5 and 7 indefinite; built afresh on
         * every step the set-up cost more than that saved (prism 6, 1
         * rank: 10.7 s of set-up against 6.5 s, 100 iterations against
         * 88) */
        int keep = k > 2 && !c.failed && 20 * nchanged <= c.nrow;
        PX(VecCopy(c.U, c.U0));
        for (;;) {
            KSP ksp = c.ksp[c.stage];
            PX(KSPSetOperators(ksp, c.A, c.A));
            PX(KSPSetReusePreconditioner(ksp, reuse ? PETSC_TRUE : PETSC_FALSE));
            if (c.gamg[c.stage] && !reuse) {
                PC pc;
                PX(KSPGetPC(ksp, &pc));
                PX(PCGAMGSetReuseInterpolation(pc, keep ? PETSC_TRUE : PETSC_FALSE));
            }
            PX(KSPSetTolerances(ksp, eta, 0.0, PETSC_DEFAULT, 100000));
            PX(KSPSolve(ksp, c.B, c.U));
            r->pc_setups++;
            r->pc_reused += reuse;
            PX(KSPGetConvergedReason(ksp, &kr));
            PX(KSPGetIterationNumber(ksp, &its));
            r->krylov += its;
            its += its0;
            c.failed = kr < 0;
            if (kr >= 0 || (kr != KSP_DIVERGED_INDEFINITE_PC && kr != KSP_DIVERGED_PC_FAILED))
                break;
            its0 = its;
            PX(VecCopy(c.U0, c.U));
            if (!fresh) {
                /* first a fresh set-up of the same preconditioner on this
                 * step's matrix: a reused one, or GAMG's prolongator and
                 * Chebyshev bounds kept from an earlier step (whose
                 * estimate of the largest eigenvalue a 3D slip point's
                 * stiffness beta P may exceed: prism 5 step 6 went
                 * indefinite so), is the usual cause */
                PC pc;
                PX(KSPGetPC(ksp, &pc));
                PX(PCReset(pc));
                fresh = 1;
                reuse = 0;
                r->pc_rebuilt++;
                continue;
            }
            if (c.stage + 1 >= c.nstage)
                break;
            /* the preconditioner failed afresh: this step and the next by the next one */
            c.stage++;
            size_t l = strlen(r->solver);
            snprintf(r->solver + l, sizeof r->solver - l, ", from step %d %s", k, c.name[c.stage]);
            fresh = 0;
            reuse = 0;
        }
        if (kr < 0) {
            PC pc;
            PCFailedReason pr = PC_NOERROR;
            PX(KSPGetPC(c.ksp[c.stage], &pc));
            PX(PCGetFailedReasonRank(pc, &pr));
            snprintf(r->message, sizeof r->message, "step %d: %s stopped: %s after %d iterations%s%s", k,
                     c.name[c.stage], KSPConvergedReasons[kr], (int)its, pr != PC_NOERROR ? ", preconditioner: " : "",
                     pr != PC_NOERROR ? PCFailedReasons[pr] : "");
            r->reason = CX_DIVERGED_BREAKDOWN;
            r->iterations = k;
            break;
        }
        /* exactly on the pinned values (the Krylov solve leaves them within its tolerance) */
        {
            PetscScalar *ua;
            const PetscScalar *xa;
            PX(VecGetArray(c.U, &ua));
            PX(VecGetArrayRead(c.X, &xa));
            for (int i = 0; i < p->m; i++)
                if (c.set[i] == 1 && ssn_owned(sys, sys->ndof[i]))
                    ua[sys->ndof[i] - sys->rstart] = xa[sys->ndof[i] - sys->rstart];
            for (int t = 0; c.tangential && t < p->nt; t++)
                if (c.set[p->m + t] == 0 && sys->tdof[t] >= 0 && ssn_owned(sys, sys->tdof[t]))
                    ua[sys->tdof[t] - sys->rstart] = 0.0;
            PX(VecRestoreArrayRead(c.X, &xa));
            PX(VecRestoreArray(c.U, &ua));
        }
        (void)PetscLogEventBegin(px_ev_gather, 0, 0, 0, 0);
        PX(MatMult(sys->K, c.U, c.R));
        PX(VecAYPX(c.R, -1.0, sys->f));   /* R = f - K u */
        if ((status = px_system_gather(sys, c.U, r->u, d)) != CX_OK ||
            (status = px_system_gather(sys, c.R, NULL, d)) != CX_OK ||
            (status = ssn_multipliers(&c, fr, r, d)) != CX_OK)
            goto fail;
        (void)PetscLogEventEnd(px_ev_gather, 0, 0, 0, 0);
        int nc = 0, nst = 0, nsl = 0;
        for (int i = 0; i < p->m; i++) {
            if (c.set[i] != 1)
                continue;
            if (!c.tangential)
                nc++;
            else if (c.set[p->m + c.dt * i] == 0)
                nst++;
            else
                nsl++;
        }
        if (px_run_check(run, k, nc, nst, nsl, nchanged, (int)its, eta))
            break;
        kkt_prev = r->kkt;
    }
    ssn_clear(&c);
    return CX_OK;
fail:
    ssn_clear(&c);
    return status;
}
