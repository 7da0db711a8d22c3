/* SPDX-License-Identifier: GPL-3.0-or-later */
/* MatrixMarket files through CHOLMOD's reader and writer (linalg.h). The
 * reader accepts what CHOLMOD accepts and then refuses what it lets
 * through and we cannot use: NaN and Inf values, complex entries. */
#include "linalg/linalg_impl.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

int cx_mm_write_csc(FILE *f, const char *name, const cx_csc *A, int symmetric, cx_diag *d)
{
    cholmod_common c;
    cx_cholmod_start(&c);
    /* stype -1: CHOLMOD reads (and writes) only the lower triangle */
    cholmod_sparse v = cx_cholmod_view(A, symmetric ? -1 : 0);
    int ok = cholmod_write_sparse(f, &v, NULL, NULL, &c) >= 0;
    cholmod_finish(&c);
    return ok ? CX_OK : cx_diag_set(d, CX_EIO, "%s: CHOLMOD could not write the matrix", name);
}

int cx_mm_write_dense(FILE *f, const char *name, const double *x, int nrow, int ncol, cx_diag *d)
{
    cholmod_common c;
    cx_cholmod_start(&c);
    cholmod_dense v;
    memset(&v, 0, sizeof v);
    v.nrow = (size_t)nrow;
    v.ncol = (size_t)ncol;
    v.d = (size_t)(nrow > 0 ? nrow : 1);
    v.nzmax = v.d * (size_t)(ncol > 0 ? ncol : 1);
    v.x = (double *)x;   /* only read */
    v.xtype = CHOLMOD_REAL;
    v.dtype = CHOLMOD_DOUBLE;
    int ok = cholmod_write_dense(f, &v, NULL, &c) >= 0;
    cholmod_finish(&c);
    return ok ? CX_OK : cx_diag_set(d, CX_EIO, "%s: CHOLMOD could not write the matrix", name);
}

void cx_mm_clear(cx_mm *mm)
{
    cx_csc_clear(&mm->A);
    cx_free(mm->x);
    memset(mm, 0, sizeof *mm);
}

/* The triplet T (any stype) into mm->A, full storage. */
static int mm_from_triplet(cx_mm *mm, const cholmod_triplet *T, const char *name, cx_diag *d)
{
    const int *ti = T->i, *tj = T->j;
    const double *tx = T->x;
    cx_triplet t;
    size_t cap = 2 * T->nnz;
    CX_TRY(cx_triplet_init(&t, (int)T->nrow, (int)T->ncol, cap));
    int st = CX_OK;
    for (size_t k = 0; k < T->nnz && !st; k++) {
        if (!isfinite(tx[k])) {
            st = cx_diag_set(d, CX_EINVAL, "%s: entry at row %d, column %d is %g, expected a finite value", name,
                             ti[k] + 1, tj[k] + 1, tx[k]);
            break;
        }
        st = cx_triplet_add(&t, ti[k], tj[k], tx[k]);
        if (!st && T->stype != 0 && ti[k] != tj[k])
            st = cx_triplet_add(&t, tj[k], ti[k], tx[k]);
        if (st == CX_ENOMEM)
            cx_diag_set(d, st, "%s: out of memory", name);
    }
    if (!st && (st = cx_csc_from_triplet(&mm->A, &t)))
        cx_diag_set(d, st, "%s: out of memory", name);
    cx_triplet_clear(&t);
    return st;
}

/* The entries of a coordinate file inside its declared size, checked
 * before CHOLMOD reads it: its reader names no entry, and (SuiteSparse
 * 5.12) leaks its work on that error. Anything else malformed is left to
 * CHOLMOD. f is rewound; a stream that cannot be is not checked. */
static int mm_prescan(FILE *f, const char *name, cx_diag *d)
{
    long start = ftell(f);
    if (start < 0)
        return CX_OK;
    char *line = NULL;
    size_t cap = 0;
    int st = CX_OK, coordinate = 0, have_size = 0;
    long nrow = 0, ncol = 0;
    ssize_t len = getline(&line, &cap, f);
    if (len > 0 && strncmp(line, "%%MatrixMarket", 14) == 0)
        coordinate = strstr(line, "coordinate") != NULL;
    while (coordinate && !st && (len = getline(&line, &cap, f)) > 0) {
        char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == '%' || *p == '\n' || *p == '\r' || *p == 0)
            continue;
        long a, b;
        char *e1, *e2;
        a = strtol(p, &e1, 10);
        b = strtol(e1, &e2, 10);
        if (e1 == p || e2 == e1)
            break;   /* CHOLMOD's to refuse */
        if (!have_size) {
            nrow = a, ncol = b, have_size = 1;
        } else if (a < 1 || a > nrow || b < 1 || b > ncol) {
            st = cx_diag_set(d, CX_EINVAL, "%s: entry at row %ld, column %ld is outside the %ld x %ld matrix", name,
                             a, b, nrow, ncol);
        }
    }
    free(line);
    if (fseek(f, start, SEEK_SET) != 0 && !st)
        st = cx_diag_set(d, CX_EIO, "%s: cannot read it twice", name);
    clearerr(f);
    return st;
}

int cx_mm_read_file(FILE *f, const char *name, cx_mm *mm, cx_diag *d)
{
    memset(mm, 0, sizeof *mm);
    CX_TRY(mm_prescan(f, name, d));
    cholmod_common c;
    cx_cholmod_start(&c);
    int mtype = 0, st = CX_OK;
    void *obj = cholmod_read_matrix(f, 0, &mtype, &c);
    if (!obj) {
        cx_diag why;
        st = cx_cholmod_check(&c, NULL, name, &why);
        cholmod_finish(&c);
        if (st == CX_ENOMEM)
            return cx_diag_set(d, st, "%s: out of memory", name);
        /* why.msg is "name: CHOLMOD's message (CHOLMOD status n)" */
        return cx_diag_set(d, CX_EINVAL, "%s: not a MatrixMarket file CHOLMOD reads (%s)", name,
                           st && strlen(why.msg) > strlen(name) + 2 ? why.msg + strlen(name) + 2 : "no matrix");
    }
    if (mtype == CHOLMOD_DENSE) {
        cholmod_dense *X = obj;
        mm->dense = 1;
        mm->nrow = (int)X->nrow;
        mm->ncol = (int)X->ncol;
        if (X->xtype != CHOLMOD_REAL) {
            st = cx_diag_set(d, CX_EINVAL, "%s: not a real matrix", name);
        } else {
            size_t len = X->nrow * X->ncol;
            mm->x = CX_NEW(double, len > 0 ? len : 1);
            if (!mm->x)
                st = cx_diag_set(d, CX_ENOMEM, "%s: out of memory", name);
            const double *x = X->x;
            for (size_t j = 0; !st && j < X->ncol; j++)
                for (size_t i = 0; !st && i < X->nrow; i++) {
                    double v = x[i + j * X->d];
                    if (!isfinite(v))
                        st = cx_diag_set(d, CX_EINVAL,
                                         "%s: entry at row %zu, column %zu is %g, expected a finite value", name,
                                         i + 1, j + 1, v);
                    mm->x[i + j * X->nrow] = v;
                }
        }
        cholmod_free_dense(&X, &c);
    } else if (mtype == CHOLMOD_TRIPLET) {
        cholmod_triplet *T = obj;
        mm->nrow = (int)T->nrow;
        mm->ncol = (int)T->ncol;
        mm->symmetric = T->stype != 0;
        if (T->xtype != CHOLMOD_REAL)
            st = cx_diag_set(d, CX_EINVAL, "%s: not a real matrix (a pattern or complex file)", name);
        else
            st = mm_from_triplet(mm, T, name, d);
        cholmod_free_triplet(&T, &c);
    } else {
        st = cx_diag_set(d, CX_EINVAL, "%s: unexpected CHOLMOD result", name);
    }
    cholmod_finish(&c);
    if (st)
        cx_mm_clear(mm);
    return st;
}

int cx_mm_read(const char *path, cx_mm *mm, cx_diag *d)
{
    memset(mm, 0, sizeof *mm);
    FILE *f = fopen(path, "r");
    if (!f)
        return cx_diag_set(d, CX_EIO, "%s: %s", path, strerror(errno));
    int st = cx_mm_read_file(f, path, mm, d);
    fclose(f);
    return st;
}
