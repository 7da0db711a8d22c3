/* SPDX-License-Identifier: GPL-3.0-or-later */
/* PETSc's own solvers as peer methods for frictionless contact, on the
 * same system and under the same kkt error as ssn-tresca:
 *   petsc-vi   SNES with the reduced-space active-set Newton for
 *              variational inequalities (vinewtonrsls) on K u - f = 0
 *              with the bounds of the contact dofs;
 *   petsc-tao  TAO's trust-region Newton with gradient projection
 *              (tron, Lin and More) on min 1/2 u'K u - f'u within the
 *              same bounds (bnls, its line-search sibling, stalled at a
 *              kkt error of 1e2 on hertz 32).
 * Each rows's bound: a_i u_j <= g_i (u_j <= g_i / a_i for a_i > 0, >= for
 * a_i < 0). Neither solver has multipliers of its own: the contact forces
 * are recovered from the residual, lN_i = (f - K u)_j / a_i. Both use CG
 * with algebraic multigrid for their inner systems: they solve with
 * submatrices of K (the inactive dofs), which lose K's block structure and
 * its rigid-body modes, and GAMG on them stopped with "nonconforming object
 * sizes" (PETSc 3.18, hertz 32, every way we tried: with and without the
 * near null space), so the peers take hypre's BoomerAMG where PETSc has
 * it, on a copy of K without the near null space (PETSC_OPTIONS with the prefix cx_
 * changes them: -cx_tao_type tron, -cx_snes_linesearch_type bt, ...). A
 * Tresca bound |lT| <= s is a bound on the multiplier, not on u: these
 * methods refuse it (cx_petsc_check). Their convergence test is ours: the
 * kkt error at each iterate, so that their work counts the same way. */
#include "petsc/petsc_impl.h"

#include <math.h>
#include <petscsnes.h>
#include <petsctao.h>

#ifdef PETSC_HAVE_HYPRE
#define PEER_PC PCHYPRE
#else
#define PEER_PC PCGAMG
#endif

typedef struct {
    px_run *run;
    Mat K;           /* sys->K without the near null space */
    Vec R;
    long krylov_seen;
    int status;      /* a cx status from inside a callback */
    cx_diag *d;
} peer_ctx;

/* The bounds of the contact dofs, +-inf elsewhere; the start x: every
 * contact dof on its bound, 0 elsewhere (ssn-tresca's bonded start: from
 * u = 0 with every bound inactive the first Newton system is K, singular
 * for a body that only the contact holds). */
static int peer_bounds(px_system *sys, Vec lo, Vec hi, Vec x, cx_diag *d)
{
    int status = CX_OK;
    const cx_problem *p = sys->p;
    PX(VecSet(lo, PETSC_NINFINITY));
    PX(VecSet(hi, PETSC_INFINITY));
    for (int i = 0; i < p->m; i++) {
        int dof = sys->ndof[i];
        if (dof < sys->rstart || dof >= sys->rend)
            continue;
        double b = p->g[i] / sys->nval[i];
        PX(VecSetValue(sys->nval[i] > 0 ? hi : lo, dof, b, INSERT_VALUES));
        PX(VecSetValue(x, dof, b, INSERT_VALUES));
    }
    PX(VecAssemblyBegin(x));
    PX(VecAssemblyEnd(x));
    PX(VecAssemblyBegin(lo));
    PX(VecAssemblyEnd(lo));
    PX(VecAssemblyBegin(hi));
    PX(VecAssemblyEnd(hi));
    return CX_OK;
fail:
    return status;
}

/* What both peers start from: K's copy without the near null space (the
 * header says why), x at zero within its bounds lo, hi, and the vector of
 * the residual; peer_clear undoes it, also after a failure here. */
static int peer_init(peer_ctx *c, Vec *x, Vec *lo, Vec *hi, cx_diag *d)
{
    int status = CX_OK;
    px_system *sys = c->run->sys;
    PX(MatDuplicate(sys->K, MAT_COPY_VALUES, &c->K));
    PX(MatSetNearNullSpace(c->K, NULL));
    PX(MatCreateVecs(sys->K, x, NULL));
    PX(VecDuplicate(*x, lo));
    PX(VecDuplicate(*x, hi));
    PX(VecDuplicate(*x, &c->R));
    PX(VecSet(*x, 0.0));
    return peer_bounds(sys, *lo, *hi, *x, d);
fail:
    return status;
}

/* What both peers hold at the end (PETSc's destroyers take NULL). */
static void peer_clear(peer_ctx *c, Vec *x, Vec *lo, Vec *hi)
{
    VecDestroy(x);
    VecDestroy(lo);
    VecDestroy(hi);
    VecDestroy(&c->R);
    MatDestroy(&c->K);
}

/* The iterate x with its gradient g = K x - f: gathered, multipliers from
 * -g, the kkt error; 1 if the run ends. */
static int peer_check(peer_ctx *c, Vec x, Vec g, int iter, long krylov, int *ended)
{
    cx_diag *d = c->d;
    int status = CX_OK;
    px_run *run = c->run;
    px_system *sys = run->sys;
    cx_petsc_result *r = run->r;
    if ((status = px_system_gather(sys, x, r->u, d)) != CX_OK)
        return status;
    PX(VecCopy(g, c->R));
    PX(VecScale(c->R, -1.0));
    if ((status = px_system_gather(sys, c->R, NULL, d)) != CX_OK)
        return status;
    {
        const PetscScalar *w;
        PX(VecGetArrayRead(sys->whole, &w));
        px_multipliers_from_residual(sys, w, r->lN, NULL);
        PX(VecRestoreArrayRead(sys->whole, &w));
    }
    const cx_problem *p = sys->p;
    int nc = 0;
    for (int i = 0; i < p->m; i++) {
        int j = p->map.free_of[sys->ndof[i]];
        nc += fabs(sys->nval[i] * r->u[j] - p->g[i]) <= 1e-12 * fmax(1.0, fabs(p->g[i])) && r->lN[i] > 0;
    }
    r->krylov = krylov;
    *ended = px_run_check(run, iter, nc, 0, 0, 0, (int)(krylov - c->krylov_seen), NAN);
    c->krylov_seen = krylov;
    return CX_OK;
fail:
    return status;
}

/* ---- SNES VI ------------------------------------------------------------ */

static PetscErrorCode vi_function(SNES snes, Vec x, Vec F, void *ctx)
{
    (void)snes;
    px_system *sys = ctx;
    PetscCall(MatMult(sys->K, x, F));
    PetscCall(VecAXPY(F, -1.0, sys->f));
    return 0;
}

static PetscErrorCode vi_jacobian(SNES snes, Vec x, Mat J, Mat P, void *ctx)
{
    (void)snes, (void)x, (void)J, (void)P, (void)ctx;
    return 0;   /* K, constant */
}

static PetscErrorCode vi_converged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal gnorm, PetscReal fnorm,
                                   SNESConvergedReason *reason, void *ctx)
{
    (void)xnorm, (void)gnorm, (void)fnorm;
    peer_ctx *c = ctx;
    *reason = SNES_CONVERGED_ITERATING;
    if (it == 0)
        return 0;   /* the start, u = 0 */
    Vec x, F;
    PetscInt lits;
    PetscCall(SNESGetSolution(snes, &x));
    PetscCall(SNESGetFunction(snes, &F, NULL, NULL));
    PetscCall(SNESGetLinearSolveIterations(snes, &lits));
    int ended = 0;
    c->status = peer_check(c, x, F, (int)it, (long)lits, &ended);
    if (c->status != CX_OK || ended)
        *reason = SNES_CONVERGED_ITS;   /* ours ended it: the outcome is in the result */
    return 0;
}

int px_vi_solve(px_run *run, cx_diag *d)
{
    int status = CX_OK;
    px_system *sys = run->sys;
    peer_ctx c = {run, NULL, NULL, 0, CX_OK, d};
    SNES snes = NULL;
    Vec x = NULL, F = NULL, lo = NULL, hi = NULL;
    if ((status = peer_init(&c, &x, &lo, &hi, d)) != CX_OK)
        goto fail;
    PX(VecDuplicate(x, &F));
    PX(SNESCreate(sys->comm, &snes));
    PX(SNESSetType(snes, SNESVINEWTONRSLS));
    PX(SNESSetFunction(snes, F, vi_function, sys));
    PX(SNESSetJacobian(snes, c.K, c.K, vi_jacobian, sys));
    PX(SNESVISetVariableBounds(snes, lo, hi));
    PX(SNESSetConvergenceTest(snes, vi_converged, &c, NULL));
    PX(SNESSetTolerances(snes, 0.0, 0.0, 0.0, run->opt->max_iter, 100 * run->opt->max_iter + 100));
    PX(SNESKSPSetUseEW(snes, PETSC_TRUE));   /* inexact Newton, as ssn-tresca's forcing term */
    {
        SNESLineSearch ls;
        KSP ksp;
        PC pc;
        PX(SNESGetLineSearch(snes, &ls));
        PX(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));   /* the problem is linear: full steps */
        PX(SNESGetKSP(snes, &ksp));
        PX(KSPSetType(ksp, KSPCG));
        PX(KSPGetPC(ksp, &pc));
        PX(PCSetType(pc, PEER_PC));
    }
    PX(SNESSetOptionsPrefix(snes, "cx_"));
    PX(SNESSetFromOptions(snes));
    {
        KSP ksp;
        PX(SNESGetKSP(snes, &ksp));
        px_ksp_name(ksp, run->r->solver, sizeof run->r->solver);
    }
    PX(SNESSolve(snes, NULL, x));
    if (c.status != CX_OK) {
        status = c.status;
        goto fail;
    }
    if (run->r->reason == CX_ITERATING) {   /* SNES stopped on its own */
        SNESConvergedReason sr;
        PX(SNESGetConvergedReason(snes, &sr));
        PetscInt it = 0;
        PX(SNESGetIterationNumber(snes, &it));
        snprintf(run->r->message, sizeof run->r->message, "SNES stopped: %s%s", SNESConvergedReasons[sr],
                 sr == SNES_DIVERGED_LINEAR_SOLVE && it == 0
                     ? " at the start: K on the dofs off their bounds is singular (only the contact holds "
                       "the body, and no bound is active before the first step)"
                     : "");
        run->r->reason = CX_DIVERGED_BREAKDOWN;
    }
fail:
    SNESDestroy(&snes);
    VecDestroy(&F);
    peer_clear(&c, &x, &lo, &hi);
    return status;
}

/* ---- TAO ------------------------------------------------------------------ */

static PetscErrorCode tao_fg(Tao tao, Vec x, PetscReal *fval, Vec g, void *ctx)
{
    (void)tao;
    px_system *sys = ctx;
    PetscScalar xkx, fx;
    PetscCall(MatMult(sys->K, x, g));
    PetscCall(VecDot(x, g, &xkx));
    PetscCall(VecDot(sys->f, x, &fx));
    *fval = 0.5 * xkx - fx;
    PetscCall(VecAXPY(g, -1.0, sys->f));
    return 0;
}

static PetscErrorCode tao_hessian(Tao tao, Vec x, Mat H, Mat P, void *ctx)
{
    (void)tao, (void)x, (void)H, (void)P, (void)ctx;
    return 0;   /* K, constant */
}

static PetscErrorCode tao_converged(Tao tao, void *ctx)
{
    peer_ctx *c = ctx;
    PetscInt it, lits;
    Vec x, g;
    PetscCall(TaoGetSolutionStatus(tao, &it, NULL, NULL, NULL, NULL, NULL));
    if (it == 0) {
        PetscCall(TaoSetConvergedReason(tao, TAO_CONTINUE_ITERATING));
        return 0;
    }
    PetscCall(TaoGetSolution(tao, &x));
    PetscCall(TaoGetGradient(tao, &g, NULL, NULL));
    PetscCall(TaoGetLinearSolveIterations(tao, &lits));
    int ended = 0;
    c->status = peer_check(c, x, g, (int)it, (long)lits, &ended);
    PetscCall(TaoSetConvergedReason(tao, c->status != CX_OK || ended ? TAO_CONVERGED_USER
                                                                      : TAO_CONTINUE_ITERATING));
    return 0;
}

int px_tao_solve(px_run *run, cx_diag *d)
{
    int status = CX_OK;
    px_system *sys = run->sys;
    peer_ctx c = {run, NULL, NULL, 0, CX_OK, d};
    Tao tao = NULL;
    Vec x = NULL, lo = NULL, hi = NULL;
    if ((status = peer_init(&c, &x, &lo, &hi, d)) != CX_OK)
        goto fail;
    PX(TaoCreate(sys->comm, &tao));
    PX(TaoSetType(tao, TAOTRON));
    PX(TaoSetSolution(tao, x));
    PX(TaoSetObjectiveAndGradient(tao, NULL, tao_fg, sys));
    PX(TaoSetHessian(tao, c.K, c.K, tao_hessian, sys));
    PX(TaoSetVariableBounds(tao, lo, hi));
    PX(TaoSetConvergenceTest(tao, tao_converged, &c));
    PX(TaoSetMaximumIterations(tao, run->opt->max_iter));
    {
        KSP ksp;
        PC pc;
        PX(TaoGetKSP(tao, &ksp));
        if (ksp) {
            PX(KSPGetPC(ksp, &pc));
            PX(PCSetType(pc, PEER_PC));
        }
    }
    PX(TaoSetOptionsPrefix(tao, "cx_"));
    PX(TaoSetFromOptions(tao));
    {
        KSP ksp = NULL;
        PX(TaoGetKSP(tao, &ksp));
        if (ksp)
            px_ksp_name(ksp, run->r->solver, sizeof run->r->solver);
    }
    PX(TaoSolve(tao));
    if (c.status != CX_OK) {
        status = c.status;
        goto fail;
    }
    if (run->r->reason == CX_ITERATING) {
        TaoConvergedReason tr;
        PX(TaoGetConvergedReason(tao, &tr));
        snprintf(run->r->message, sizeof run->r->message, "TAO stopped: %s", TaoConvergedReasons[tr]);
        run->r->reason = CX_DIVERGED_BREAKDOWN;
    }
fail:
    TaoDestroy(&tao);
    peer_clear(&c, &x, &lo, &hi);
    return status;
}
