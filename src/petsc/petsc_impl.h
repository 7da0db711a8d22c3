/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Inside src/petsc/: the distributed system and PETSc's error codes. */
#ifndef CX_PETSC_IMPL_H
#define CX_PETSC_IMPL_H

#include "petsc/petsc.h"

#include <petscksp.h>

/* A PETSc error as a cx status with PETSc's message; the call site is
 * where the error went up (PETSc's own traceback is switched off). */
int px_fail(PetscErrorCode ierr, const char *file, int line, cx_diag *d);
/* Evaluate a PETSc call in a function that returns a cx status and has
 * its diag in d and a fail: label. */
#define PX(call)                                              \
    do {                                                      \
        PetscErrorCode px_ierr_ = (call);                     \
        if (px_ierr_) {                                       \
            status = px_fail(px_ierr_, __FILE__, __LINE__, d); \
            goto fail;                                        \
        }                                                     \
    } while (0)

/* The backend's phases in PETSc's -log_view (registered by
 * cx_petsc_initialize): the parallel assembly of K with its Dirichlet rows
 * and near null space; a Newton step's matrix copy and pinning; its
 * residual, gathers and multipliers; the kkt error on every rank. */
extern PetscLogEvent px_ev_assemble, px_ev_system, px_ev_gather, px_ev_kkt;

/* The system of a problem on the ranks: all dofs (node k, component c ->
 * dim k + c), rows by contiguous node ranges. */
typedef struct px_system {
    const cx_problem *p;
    MPI_Comm comm;
    int rank, size;
    int dim, nall;
    PetscInt rstart, rend;   /* owned rows */
    int nelems;              /* elements this rank assembled */
    double kscale;           /* diagonal of the prescribed (and pinned) rows */
    Mat K;                   /* K with the prescribed rows and columns identity * kscale */
    Vec f;                   /* the load on the free rows (prescribed values folded in), 0 elsewhere */
    VecScatter all;          /* a vector of the system to every rank's copy */
    Vec whole;               /* that copy (nall) */
    /* contact rows, each one dof: the all-dof index and the row's value */
    int *ndof;               /* m */
    double *nval;            /* m */
    int *tdof;               /* nt: -1 for a row with no free dof */
    double *tval;            /* nt */
    double setup_time;
} px_system;

/* tangential: read the tangential rows too (Tresca). */
int px_system_create(px_system *sys, const cx_problem *p, int tangential, cx_diag *d);
void px_system_destroy(px_system *sys);
/* v (a vector of the system) into sys->whole on every rank, and its free
 * dofs into u (n), if u is not NULL. */
int px_system_gather(px_system *sys, Vec v, double *u, cx_diag *d);
/* Every rank's int or double into out (size entries) on every rank. */
int px_allgather_int(const px_system *sys, int v, int *out, cx_diag *d);
int px_allgather_double(const px_system *sys, double v, double *out, cx_diag *d);
/* A preconditioner's name ("BoomerAMG", "GAMG", else PETSc's type), and
 * a Krylov solver's with its preconditioner's ("CG + BoomerAMG"), as the
 * objects are after their options (solver_name.c). */
void px_pc_name(PC pc, char *buf, size_t len);
void px_ksp_name(KSP ksp, char *buf, size_t len);
/* The process's peak resident memory in bytes (getrusage). */
double px_peak_memory(void);

/* The multipliers recovered from the residual r = f - K u over all dofs
 * (every rank's copy): lN_i = r_j / a_i at each point's normal dof, and on
 * the tangential dofs likewise (lT may be NULL). What a method with no
 * multipliers of its own (SNES VI, TAO) reports. */
void px_multipliers_from_residual(const px_system *sys, const double *r, double *lN, double *lT);

/* The methods (ssn.c, peers.c): fill r's iterate, iterations, reason. */
typedef struct px_run {
    px_system *sys;
    const cx_friction_state *fr;   /* with per-point s for Tresca */
    const cx_options *opt;
    cx_petsc_observer obs;
    void *ctx;
    cx_petsc_result *r;
    double *work;                  /* n + m + nt: cx_kkt_error's, then n: K u */
    double t0;
    double best;                   /* the smallest kkt error so far, and its iteration */
    int best_iter;
    double last_kkt;               /* the last step's kkt error */
} px_run;
/* The kkt error of r's iterate into r, and the observer told; returns 1
 * if the run ends here (r->reason set), else 0. */
int px_run_check(px_run *run, int iter, int ncontact, int nstick, int nslip, int nchanged, int krylov,
                 double rtol);
int px_ssn_solve(px_run *run, cx_diag *d);
int px_vi_solve(px_run *run, cx_diag *d);
int px_tao_solve(px_run *run, cx_diag *d);

#endif
