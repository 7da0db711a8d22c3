/* SPDX-License-Identifier: GPL-3.0-or-later */
/* PETSc's start and end, its errors as cx statuses, and the little MPI
 * the layer needs besides PETSc's objects. */
#include "petsc/petsc_impl.h"

#include <string.h>
#include <sys/resource.h>

static int px_started;   /* 1 once PetscInitialize has run here */

PetscLogEvent px_ev_assemble, px_ev_system, px_ev_gather, px_ev_kkt;

int px_fail(PetscErrorCode ierr, const char *file, int line, cx_diag *d)
{
    const char *text = NULL;
    PetscErrorMessage(ierr, &text, NULL);
    const char *base = strrchr(file, '/');
    return cx_diag_set(d, ierr == PETSC_ERR_MEM ? CX_ENOMEM : CX_EEXTERNAL, "%s:%d: PETSc error %d: %s",
                       base ? base + 1 : file, line, (int)ierr, text ? text : "unknown");
}

int cx_petsc_initialize(cx_diag *d)
{
    PetscBool done = PETSC_FALSE;
    PetscInitialized(&done);
    if (done)
        return CX_OK;
    /* no argc/argv: the program's options are not PETSc's; PETSC_OPTIONS
     * and ~/.petscrc still reach it */
    PetscErrorCode ierr = PetscInitializeNoArguments();
    if (ierr)
        return cx_diag_set(d, CX_EEXTERNAL, "PETSc could not start (error %d)", (int)ierr);
    /* errors come back as codes, printed once by the program, not as
     * PETSc's traceback on stderr */
    PetscPushErrorHandler(PetscReturnErrorHandler, NULL);
    PetscClassId cls;
    PetscClassIdRegister("signorini", &cls);
    PetscLogEventRegister("cxAssemble", cls, &px_ev_assemble);
    PetscLogEventRegister("cxStepSystem", cls, &px_ev_system);
    PetscLogEventRegister("cxStepGather", cls, &px_ev_gather);
    PetscLogEventRegister("cxStepKKT", cls, &px_ev_kkt);
    px_started = 1;
    return CX_OK;
}

void cx_petsc_finalize(void)
{
    if (!px_started)
        return;
    PetscFinalize();
    px_started = 0;
}

int cx_petsc_rank(void)
{
    PetscMPIInt r = 0;
    if (px_started)
        MPI_Comm_rank(PETSC_COMM_WORLD, &r);
    return r;
}

int cx_petsc_size(void)
{
    PetscMPIInt s = 1;
    if (px_started)
        MPI_Comm_size(PETSC_COMM_WORLD, &s);
    return s;
}

int px_allgather_int(const px_system *sys, int v, int *out, cx_diag *d)
{
    if (MPI_Allgather(&v, 1, MPI_INT, out, 1, MPI_INT, sys->comm) != MPI_SUCCESS)
        return cx_diag_set(d, CX_EEXTERNAL, "MPI_Allgather failed");
    return CX_OK;
}

int px_allgather_double(const px_system *sys, double v, double *out, cx_diag *d)
{
    if (MPI_Allgather(&v, 1, MPI_DOUBLE, out, 1, MPI_DOUBLE, sys->comm) != MPI_SUCCESS)
        return cx_diag_set(d, CX_EEXTERNAL, "MPI_Allgather failed");
    return CX_OK;
}

double px_peak_memory(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0)
        return 0;
    return 1024.0 * (double)ru.ru_maxrss;   /* Linux: kilobytes */
}
