/* SPDX-License-Identifier: GPL-3.0-or-later */
/* petsc/: the second linear-algebra backend, on PETSc and MPI (doc/design.md
 * §10). It takes a problem built on every rank (the mesh replicated) and
 * assembles K again, in parallel: an MPIAIJ matrix over all dofs, each rank
 * the rows of a contiguous range of nodes and the elements whose first node
 * it owns, the prescribed dofs kept as identity rows (so that every node
 * keeps its dim dofs: block size dim), the rigid-body modes attached as the
 * near null space. The methods on it solve contact rows that each pin one
 * dof (a flat obstacle along an axis): the primal semismooth Newton of
 * ssn-tresca with a Krylov solve per step (CG + GAMG in 3D, CG +
 * BoomerAMG in 2D where PETSc has hypre), and PETSc's own SNES VI and TAO
 * as peers for frictionless contact.
 *
 * This header includes no PETSc or MPI header: the program's other layers
 * see plain C. Only src/petsc/ includes them. Every call below is
 * collective: all ranks call it with the same problem and arguments. */
#ifndef CX_PETSC_H
#define CX_PETSC_H

#include "solve/solve.h"

/* PetscInitialize once per process, without the command line (PETSc
 * options come from the PETSC_OPTIONS environment variable, e.g.
 * "-log_view"); PETSc's errors return instead of printing. A second call
 * does nothing. CX_EEXTERNAL if MPI or PETSc cannot start. */
int cx_petsc_initialize(cx_diag *d);
/* PetscFinalize (and MPI's), if cx_petsc_initialize started them. */
void cx_petsc_finalize(void);
int cx_petsc_rank(void);   /* 0 before initialisation */
int cx_petsc_size(void);   /* 1 before initialisation */

/* The methods of this backend, in one table. */
typedef struct cx_petsc_method {
    const char *id;
    const char *summary;
    unsigned supports;     /* CX_FRICTIONLESS | CX_TRESCA ... (solve.h) */
} cx_petsc_method;
/* The id's method, or NULL; "ssn-tresca" (the default) is the primal
 * semismooth Newton: the same iteration as the direct path's method of
 * that id without its Schur reduction. */
const cx_petsc_method *cx_petsc_method_find(const char *id);
const cx_petsc_method *cx_petsc_method_at(int k);   /* NULL past the end */

/* CX_EUNSUPPORTED with the reason if the backend cannot take the problem
 * under the law with the method: a contact row that is not one dof (a
 * general normal or tangent, two bodies), a dof in two rows, or a law the
 * method does not solve. */
int cx_petsc_check(const cx_problem *p, const char *method, cx_friction law, cx_diag *d);

/* One step of a run, for the observer: the same on every rank. */
typedef struct cx_petsc_step {
    int iter;            /* 1, 2, ... */
    double kkt;          /* doc/design.md §3 error of the iterate */
    int ncontact, nstick, nslip, nchanged;
    int krylov;          /* Krylov iterations of the step */
    double rtol;         /* the step's forcing term (relative residual asked) */
    double time;         /* seconds since the run began */
} cx_petsc_step;
/* Called on every rank after each step; non-zero stops the run. */
typedef int (*cx_petsc_observer)(void *ctx, const cx_petsc_step *st);

typedef struct cx_petsc_result {
    int reason;          /* cx_reason */
    int iterations;      /* Newton (or SNES, TAO) iterations */
    double kkt;
    cx_kkt kkt_parts;
    double kkt_floor;    /* the roundoff floor of the kkt error at the last iterate where it was
                            near it (eps max_i sum_j |K_ij u_j| over the force scale; run.c), else 0:
                            a run that stops there ends CX_DIVERGED_STALL and says so */
    double *u, *lN, *lT; /* n, m, nt: the last iterate, on every rank */
    long krylov;         /* Krylov iterations in all */
    int pc_setups;       /* Krylov solves (each with its preconditioner set up, unless reused) */
    int pc_reused;       /* of which reused the last step's preconditioner (the sets unchanged) */
    int pc_rebuilt;      /* preconditioners built afresh after one failed */
    char solver[96];     /* the inner solves' Krylov method and preconditioner as they ran:
                            "CG + BoomerAMG"; after a failure ", from step 8 CG + GAMG (SOR)" */
    double t_setup;      /* parallel assembly, Dirichlet rows, near null space */
    double t_solve;      /* the method */
    int nranks;
    /* per rank (nranks entries, the same on every rank) */
    int *rows;           /* rows of the MPIAIJ matrix owned (all dofs of its nodes) */
    int *elems;          /* elements it assembled */
    double *mem_peak;    /* peak resident memory of the process (bytes) */
    char message[CX_DIAG_LEN];   /* why a run ended early, if it did */
} cx_petsc_result;
void cx_petsc_result_clear(cx_petsc_result *r);

/* Solve p under fr (per-point slip bounds in fr->s, or NULL: slip_bound
 * times each point's weight, as the session does) with the method id,
 * opt's tolerance, iteration and time limits. r must be zeroed or cleared.
 * Not converging is a result (r->reason); CX_EUNSUPPORTED (cx_petsc_check),
 * CX_EEXTERNAL (PETSc failed: its message), CX_ENOMEM are errors. */
int cx_petsc_solve(const cx_problem *p, const cx_friction_state *fr, const char *method,
                   const cx_options *opt, cx_petsc_observer obs, void *ctx, cx_petsc_result *r,
                   cx_diag *d);

/* The status of each contact point (CX_PT_*) of a solution's forces, as
 * the direct path's methods set it: free where lN is at the noise of a
 * force recovered from a residual (1e-9 of the largest), stick inside the
 * Tresca bound, else slip. st has p->m entries. */
void cx_petsc_point_status(const cx_problem *p, const cx_friction_state *fr, const double *lN, const double *lT,
                           unsigned char *st);

#endif
