/* SPDX-License-Identifier: GPL-3.0-or-later */
/* MatrixMarket files through CHOLMOD's reader and writer (linalg.h). The
 * reader accepts what CHOLMOD accepts and then refuses what it lets
 * through and we cannot use: NaN and Inf values, complex entries. */
#include "linalg/linalg_impl.h"

#include <ctype.h>
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

/* The syntax of the file, checked before CHOLMOD reads it: CHOLMOD's
 * reader names no line or entry in its errors, and (SuiteSparse 5.12)
 * leaks its work on several of them (seen under LeakSanitizer and
 * libFuzzer). Accepted: "%%MatrixMarket matrix coordinate|array
 * real|integer general|symmetric" (any case; coordinate files also
 * "pattern", all values 1, as CHOLMOD writes a matrix of ones), comments,
 * the size line, then exactly the declared entries, each "row column
 * value" (coordinate, inside the size) or "value" (array). f is rewound; a stream that
 * cannot be rewound is left to CHOLMOD alone. */
static int mm_word(char **p, char *w, size_t len)
{
    while (**p == ' ' || **p == '\t')
        (*p)++;
    size_t k = 0;
    while (**p && !strchr(" \t\r\n", **p)) {
        if (k + 1 < len)
            w[k++] = (char)tolower((unsigned char)**p);
        (*p)++;
    }
    w[k] = 0;
    return k > 0;
}

/* The next whitespace-separated number of *p: an integer (is_int) or a
 * real (strtod's, nan and inf included: the value check names them). */
static int mm_number(char **p, int is_int, double *v)
{
    char w[128];
    if (!mm_word(p, w, sizeof w) || strlen(w) >= sizeof w - 1)
        return 0;
    char *e;
    if (is_int) {
        errno = 0;
        long x = strtol(w, &e, 10);
        if (*e || errno || x < 0 || x > 2147483647L)
            return 0;
        *v = (double)x;
        return 1;
    }
    *v = strtod(w, &e);
    return *e == 0;
}

static int mm_prescan(FILE *f, const char *name, cx_diag *d)
{
    long start = ftell(f);
    if (start < 0)
        return CX_OK;
    char *line = NULL;
    size_t cap = 0;
    int st = CX_OK, lineno = 0;
    ssize_t len;
    char w[5][32] = {"", "", "", "", ""};
    /* CHOLMOD knows the banner by its exact spelling only, and looks for
     * it further down when the first line has another one (it then read
     * "%%matrixmarket ... coordinate" as the array of a later banner and
     * leaked it on the error that followed: found by libFuzzer) */
    static const char banner[] = "%%MatrixMarket";
    int banner_ok = 0;
    if ((len = getline(&line, &cap, f)) > 0) {
        banner_ok = strncmp(line, banner, sizeof banner - 1) == 0;
        char *p = line;
        lineno = 1;
        for (int k = 0; k < 5; k++)
            mm_word(&p, w[k], sizeof w[k]);
    }
    int coordinate = !strcmp(w[2], "coordinate"), symmetric = !strcmp(w[4], "symmetric");
    int pattern = coordinate && !strcmp(w[3], "pattern");   /* CHOLMOD writes all-one matrices so */
    if (!banner_ok || strcmp(w[0], "%%matrixmarket") != 0 || strcmp(w[1], "matrix") != 0 ||
        (!coordinate && strcmp(w[2], "array") != 0))
        st = cx_diag_set(d, CX_EINVAL, "%s: not a MatrixMarket file: the first line must be '%%%%MatrixMarket "
                         "matrix coordinate|array real|integer|pattern general|symmetric'", name);
    else if (strcmp(w[3], "real") != 0 && strcmp(w[3], "integer") != 0 && !pattern)
        st = cx_diag_set(d, CX_EINVAL, "%s: a %s matrix: expected real values", name, w[3][0] ? w[3] : "typeless");
    else if (!symmetric && strcmp(w[4], "general") != 0)
        st = cx_diag_set(d, CX_EINVAL, "%s: a %s matrix: expected general or symmetric", name,
                         w[4][0] ? w[4] : "typeless");
    double size[3] = {0, 0, 0};
    int have_size = 0;
    long long want = 0, got = 0;
    while (!st && (len = getline(&line, &cap, f)) > 0) {
        lineno++;
        char *p = line, tail[2];
        while (*p == ' ' || *p == '\t')
            p++;
        if (strncmp(line, banner, sizeof banner - 1) == 0) {
            st = cx_diag_set(d, CX_EINVAL, "%s: line %d: a second '%s' line", name, lineno, banner);
            break;
        }
        /* a comment, or a line of blanks only: a carriage return before
         * more text ("\r3 3") is not one (CHOLMOD took such a line for
         * the size and returned a bad object: found by libFuzzer) */
        if (*p == '%' || p[strspn(p, " \t\r\n")] == 0)
            continue;
        if ((size_t)len != strlen(line)) {
            st = cx_diag_set(d, CX_EINVAL, "%s: line %d: a NUL byte", name, lineno);
            break;
        }
        if (!have_size) {
            int ok = mm_number(&p, 1, &size[0]) && mm_number(&p, 1, &size[1]) &&
                     (!coordinate || mm_number(&p, 1, &size[2])) && !mm_word(&p, tail, sizeof tail);
            if (!ok)
                st = cx_diag_set(d, CX_EINVAL, "%s: line %d: expected the size '%s'", name, lineno,
                                 coordinate ? "rows columns entries" : "rows columns");
            else if (symmetric && size[0] != size[1])
                st = cx_diag_set(d, CX_EINVAL, "%s: line %d: a symmetric matrix of %.0f x %.0f", name, lineno, size[0],
                                 size[1]);
            have_size = 1;
            want = coordinate ? (long long)size[2]
                   : symmetric ? (long long)size[0] * ((long long)size[0] + 1) / 2
                               : (long long)size[0] * (long long)size[1];
            continue;
        }
        double i = 0, j = 0, x;
        int ok = coordinate ? mm_number(&p, 1, &i) && mm_number(&p, 1, &j) && (pattern || mm_number(&p, 0, &x))
                            : mm_number(&p, 0, &x);
        if (!ok || mm_word(&p, tail, sizeof tail))
            st = cx_diag_set(d, CX_EINVAL, "%s: line %d: expected '%s'", name, lineno,
                             !coordinate ? "value" : pattern ? "row column" : "row column value");
        else if (++got > want)
            st = cx_diag_set(d, CX_EINVAL, "%s: line %d: more entries than the %lld declared", name, lineno, want);
        else if (coordinate && (i < 1 || i > size[0] || j < 1 || j > size[1]))
            st = cx_diag_set(d, CX_EINVAL, "%s: entry at row %.0f, column %.0f is outside the %.0f x %.0f matrix",
                             name, i, j, size[0], size[1]);
    }
    if (!st && !have_size)
        st = cx_diag_set(d, CX_EINVAL, "%s: no size line", name);
    else if (!st && got < want)
        st = cx_diag_set(d, CX_EINVAL, "%s: %lld entries of the %lld declared", name, got, want);
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
