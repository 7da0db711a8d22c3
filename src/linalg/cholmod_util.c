/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The CHOLMOD glue shared by fact.c and schur.c: a silenced Common whose
 * errors become cx_diag lines, zero-copy views of our arrays, and the
 * checks after every call. */
#define _GNU_SOURCE   /* dlsym(RTLD_DEFAULT): the OpenMP runtime CHOLMOD loaded */
#include "linalg/linalg_impl.h"

#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* CHOLMOD's error handler has no user pointer, so the last message is kept
 * here, one per thread (each session runs in one thread). */
static _Thread_local char cholmod_last_msg[256];

static void cholmod_record(int status, const char *file, int line, const char *message)
{
    (void)file;
    (void)line;
    snprintf(cholmod_last_msg, sizeof cholmod_last_msg, "%s (CHOLMOD status %d)",
             message ? message : "?", status);
}

/* Debian's CHOLMOD 3 opens its parallel loops (clearing and filling each
 * supernode) with num_threads(4), whatever OMP_NUM_THREADS says, so they
 * run 4 threads beside OpenBLAS's on a 2-core machine; the threads then
 * spin for the next region while BLAS works. OMP_THREAD_LIMIT would cap
 * them, but the runtime reads it when it loads, before main. A program
 * that wants those loops serial says so here; each thread that starts a
 * CHOLMOD Common then sets its own max-active-levels to 0 (an ICV of the
 * calling thread: the runtime then runs every region with one thread).
 * The library's default leaves the runtime alone. */
static _Atomic int cholmod_serial;

void cx_linalg_cholmod_serial(int on)
{
    cholmod_serial = on != 0;
}

static void cholmod_apply_threads(void)
{
    if (!cholmod_serial)
        return;
    void (*levels)(int) = (void (*)(int))dlsym(RTLD_DEFAULT, "omp_set_max_active_levels");
    if (levels)
        levels(0);
}

void cx_cholmod_start(cholmod_common *c)
{
    cholmod_apply_threads();
    cholmod_start(c);
    c->print = 0;
    c->error_handler = cholmod_record;
    c->supernodal = CHOLMOD_SUPERNODAL;
    c->final_ll = 1;
}

cholmod_sparse cx_cholmod_view(const cx_csc *A, int stype)
{
    cholmod_sparse s;
    memset(&s, 0, sizeof s);
    s.nrow = (size_t)A->nrow;
    s.ncol = (size_t)A->ncol;
    s.nzmax = cx_csc_nnz(A) ? cx_csc_nnz(A) : 1;
    s.p = A->p;
    s.i = A->i;
    s.x = A->x;
    s.stype = stype;
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 1;
    return s;
}

cholmod_dense cx_cholmod_vec(double *x, int n)
{
    cholmod_dense v;
    memset(&v, 0, sizeof v);
    v.nrow = (size_t)n;
    v.ncol = 1;
    v.nzmax = (size_t)(n > 0 ? n : 1);
    v.d = (size_t)(n > 0 ? n : 1);
    v.x = x;
    v.xtype = CHOLMOD_REAL;
    v.dtype = CHOLMOD_DOUBLE;
    return v;
}

int cx_cholmod_column(const cholmod_factor *L, int k)
{
    if (!L || k < 0 || (size_t)k >= L->n)
        return k;
    return L->Perm ? ((const int *)L->Perm)[k] : k;
}

int cx_cholmod_check(cholmod_common *c, const cholmod_factor *L, const char *what, cx_diag *d)
{
    if (c->status == CHOLMOD_OK)
        return CX_OK;
    if (c->status == CHOLMOD_NOT_POSDEF)
        return cx_diag_set(d, CX_ENUMERIC, "%s: matrix not positive definite (pivot at column %d)", what,
                           L ? cx_cholmod_column(L, (int)L->minor) : -1);
    if (c->status == CHOLMOD_OUT_OF_MEMORY)
        return cx_diag_set(d, CX_ENOMEM, "%s: out of memory", what);
    if (c->status > 0) /* another warning (tiny diagonal): the pivot check decides */
        return CX_OK;
    return cx_diag_set(d, CX_EEXTERNAL, "%s: %s", what, cholmod_last_msg);
}

int cx_cholmod_check_pivots(const cholmod_factor *L, const cx_csc *A, const char *what, cx_diag *d)
{
    if (!L->is_super || !L->is_ll)
        return cx_diag_set(d, CX_EEXTERNAL, "%s: expected a supernodal LL' factor", what);
    double amax = 0;
    for (int j = 0; j < A->ncol; j++)
        amax = fmax(amax, fabs(cx_csc_get(A, j, j)));
    const int *super = L->super, *pi = L->pi, *px = L->px;
    const double *lx = L->x;
    for (size_t k = 0; k < L->nsuper; k++) {
        int nrow = pi[k + 1] - pi[k];
        for (int j = 0; j < super[k + 1] - super[k]; j++) {
            double l = lx[px[k] + j + j * nrow];
            if (!(l * l > CX_PIVOT_RTOL * amax))   /* also catches NaN */
                return cx_diag_set(d, CX_ENUMERIC,
                                   "%s: matrix singular to working precision (pivot %g at column %d)",
                                   what, l * l, cx_cholmod_column(L, super[k] + j));
        }
    }
    return CX_OK;
}
