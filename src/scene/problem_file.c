/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The discrete problem read back (scene/problem_file.h): the manifest
 * (a small JSON reader for the flat object export_mm.c writes), the
 * MatrixMarket files through linalg/mm.c, each checked against the
 * manifest and the others before cx_problem_from_data copies them. */
#include "scene/problem_file.h"
#include "scene/scene.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ---- the manifest ------------------------------------------------------ */

/* The files by key, with the names export_mm.c gives them. */
enum { F_K, F_F, F_N, F_T, F_G, F_WEIGHT, F_POINTS, F_MU, F_SLIP, F_COUNT };
static const char *const manifest_keys[F_COUNT] = {"K", "f", "N", "T", "g", "weight", "points", "mu",
                                                   "slip_bound"};
static const char *const manifest_default[F_COUNT] = {"K.mtx", "f.mtx", "N.mtx", "T.mtx", "g.mtx",
                                                      "weight.mtx", "points.mtx", "mu.mtx", "slip_bound.mtx"};

typedef struct {
    const char *p, *end, *name, *start;
    cx_diag *d;
} mjson;

static void mj_ws(mjson *j)
{
    while (j->p < j->end && (*j->p == ' ' || *j->p == '\t' || *j->p == '\n' || *j->p == '\r'))
        j->p++;
}

static int mj_fail(mjson *j, const char *what)
{
    return cx_diag_set(j->d, CX_EINVAL, "%s: malformed JSON at byte %ld: %s", j->name, (long)(j->p - j->start),
                       what);
}

static int mj_expect(mjson *j, char c)
{
    mj_ws(j);
    if (j->p >= j->end || *j->p != c) {
        char what[32];
        snprintf(what, sizeof what, "expected '%c'", c);
        return mj_fail(j, what);
    }
    j->p++;
    return CX_OK;
}

/* A string into out (len bytes, always terminated; longer ones cut). */
static int mj_string(mjson *j, char *out, size_t len)
{
    CX_TRY(mj_expect(j, '"'));
    size_t k = 0;
    while (j->p < j->end && *j->p != '"') {
        char c = *j->p++;
        if ((unsigned char)c < 0x20)
            return mj_fail(j, "control character in a string");
        if (c == '\\') {
            if (j->p >= j->end)
                break;
            c = *j->p++;
            if (c == 'u') {
                for (int h = 0; h < 4; h++, j->p++)
                    if (j->p >= j->end || !strchr("0123456789abcdefABCDEF", *j->p) || !*j->p)
                        return mj_fail(j, "bad \\u escape");
                c = '?';
            } else {
                const char *from = "\"\\/bfnrt", *to = "\"\\/\b\f\n\r\t";
                const char *q = c ? strchr(from, c) : NULL;
                if (!q)
                    return mj_fail(j, "bad escape");
                c = to[q - from];
            }
        }
        if (k + 1 < len)
            out[k++] = c;
    }
    if (len)
        out[k] = 0;
    return mj_expect(j, '"');
}

static int mj_number(mjson *j, double *v)
{
    mj_ws(j);
    char buf[64];
    size_t k = 0;
    while (j->p + k < j->end && k + 1 < sizeof buf && strchr("+-.0123456789eE", j->p[k]) && j->p[k])
        k++;
    memcpy(buf, j->p, k);
    buf[k] = 0;
    char *e;
    *v = strtod(buf, &e);
    if (k == 0 || *e)
        return mj_fail(j, "expected a number");
    j->p += k;
    return CX_OK;
}

static int mj_skip(mjson *j, int depth);

static int mj_word(mjson *j, const char *w)
{
    size_t n = strlen(w);
    if ((size_t)(j->end - j->p) < n || memcmp(j->p, w, n) != 0)
        return mj_fail(j, "unexpected value");
    j->p += n;
    return CX_OK;
}

/* Skip any value (nested at most 32 deep). */
static int mj_skip(mjson *j, int depth)
{
    mj_ws(j);
    if (j->p >= j->end)
        return mj_fail(j, "unexpected end");
    if (depth > 32)
        return mj_fail(j, "nested too deep");
    char c = *j->p;
    if (c == '"') {
        char tmp[2];
        return mj_string(j, tmp, sizeof tmp);
    }
    if (c == '{' || c == '[') {
        char close = c == '{' ? '}' : ']';
        j->p++;
        mj_ws(j);
        if (j->p < j->end && *j->p == close) {
            j->p++;
            return CX_OK;
        }
        for (;;) {
            if (c == '{') {
                char key[2];
                CX_TRY(mj_string(j, key, sizeof key));
                CX_TRY(mj_expect(j, ':'));
            }
            CX_TRY(mj_skip(j, depth + 1));
            mj_ws(j);
            if (j->p < j->end && *j->p == ',') {
                j->p++;
                continue;
            }
            return mj_expect(j, close);
        }
    }
    if (c == 't')
        return mj_word(j, "true");
    if (c == 'f')
        return mj_word(j, "false");
    if (c == 'n')
        return mj_word(j, "null");
    double v;
    return mj_number(j, &v);
}

static int mj_files(mjson *j, cx_problem_manifest *mf)
{
    CX_TRY(mj_expect(j, '{'));
    mj_ws(j);
    if (j->p < j->end && *j->p == '}') {
        j->p++;
        return CX_OK;
    }
    for (;;) {
        char key[64], val[64];
        CX_TRY(mj_string(j, key, sizeof key));
        CX_TRY(mj_expect(j, ':'));
        CX_TRY(mj_string(j, val, sizeof val));
        for (int k = 0; k < F_COUNT; k++)
            if (strcmp(key, manifest_keys[k]) == 0) {
                if (!val[0] || strchr(val, '/'))
                    return cx_diag_set(j->d, CX_EINVAL, "%s: files.%s: '%s' is not a file name in the directory",
                                       j->name, key, val);
                snprintf(mf->file[k], sizeof mf->file[k], "%s", val);
            }
        mj_ws(j);
        if (j->p < j->end && *j->p == ',') {
            j->p++;
            continue;
        }
        return mj_expect(j, '}');
    }
}

static int mj_int(mjson *j, const char *key, int *v)
{
    double x;
    CX_TRY(mj_number(j, &x));
    if (!(x >= 0 && x <= 1e9) || x != floor(x))
        return cx_diag_set(j->d, CX_EINVAL, "%s: %s: expected a whole number >= 0, got %g", j->name, key, x);
    *v = (int)x;
    return CX_OK;
}

int cx_problem_manifest_parse(const char *text, size_t len, const char *name, cx_problem_manifest *mf,
                              cx_diag *d)
{
    memset(mf, 0, sizeof *mf);
    mf->law = (cx_friction)-1;
    mf->dim = mf->n = mf->m = -1;
    for (int k = 0; k < F_COUNT; k++)
        snprintf(mf->file[k], sizeof mf->file[k], "%s", manifest_default[k]);
    mjson j = {text, text + len, name, text, d};
    char format[64] = "";
    CX_TRY(mj_expect(&j, '{'));
    mj_ws(&j);
    if (j.p < j.end && *j.p == '}')
        j.p++;
    else
        for (;;) {
            char key[64];
            CX_TRY(mj_string(&j, key, sizeof key));
            CX_TRY(mj_expect(&j, ':'));
            mj_ws(&j);
            if (strcmp(key, "format") == 0) {
                CX_TRY(mj_string(&j, format, sizeof format));
            } else if (strcmp(key, "source") == 0) {
                CX_TRY(mj_string(&j, mf->source, sizeof mf->source));
            } else if (strcmp(key, "friction") == 0) {
                char law[32];
                CX_TRY(mj_string(&j, law, sizeof law));
                int l = cx_friction_from_name(law);
                if (l < 0)
                    return cx_diag_set(d, CX_EINVAL, "%s: friction: unknown law '%s' (none, tresca, coulomb)", name,
                                       law);
                mf->law = (cx_friction)l;
            } else if (strcmp(key, "files") == 0) {
                CX_TRY(mj_files(&j, mf));
            } else if (strcmp(key, "dim") == 0) {
                CX_TRY(mj_int(&j, key, &mf->dim));
            } else if (strcmp(key, "n") == 0) {
                CX_TRY(mj_int(&j, key, &mf->n));
            } else if (strcmp(key, "m") == 0) {
                CX_TRY(mj_int(&j, key, &mf->m));
            } else if (strcmp(key, "level") == 0) {
                CX_TRY(mj_int(&j, key, &mf->level));
            } else if (strcmp(key, "version") == 0) {
                CX_TRY(mj_int(&j, key, &mf->version));
            } else if (strcmp(key, "F") == 0 || strcmp(key, "slip_bound") == 0 || strcmp(key, "E") == 0) {
                double v = 0;
                if (j.p < j.end && *j.p == 'n')
                    CX_TRY(mj_word(&j, "null"));
                else
                    CX_TRY(mj_number(&j, &v));
                if (!isfinite(v) || v < 0)
                    return cx_diag_set(d, CX_EINVAL, "%s: %s: expected a finite value >= 0", name, key);
                *(key[0] == 'F' ? &mf->F : key[0] == 's' ? &mf->slip_bound : &mf->E) = v;
            } else {
                CX_TRY(mj_skip(&j, 0));
            }
            mj_ws(&j);
            if (j.p < j.end && *j.p == ',') {
                j.p++;
                continue;
            }
            CX_TRY(mj_expect(&j, '}'));
            break;
        }
    mj_ws(&j);
    if (j.p != j.end)
        return mj_fail(&j, "text after the object");
    if (strcmp(format, "signorini-problem") != 0)
        return cx_diag_set(d, CX_EINVAL, "%s: format: expected \"signorini-problem\"", name);
    if (mf->version != 1)
        return cx_diag_set(d, CX_EINVAL, "%s: version %d: this program reads version 1", name, mf->version);
    if (mf->dim != 2 && mf->dim != 3)
        return cx_diag_set(d, CX_EINVAL, "%s: dim: expected 2 or 3", name);
    if (mf->n < 1 || mf->m < 0)
        return cx_diag_set(d, CX_EINVAL, "%s: n and m: expected n >= 1 and m >= 0", name);
    if ((int)mf->law < 0)
        return cx_diag_set(d, CX_EINVAL, "%s: no friction law", name);
    return CX_OK;
}

/* ---- the MatrixMarket directory ----------------------------------------- */

typedef struct {
    const char *dir;
    char path[4096];
    cx_diag *d;
} mmdir;

/* File key of the directory read into mm, checked to be nrow x ncol and
 * sparse (coordinate) or dense (array) as asked. */
static int mm_get(mmdir *r, const cx_problem_manifest *mf, int key, int dense, int nrow, int ncol, cx_mm *mm)
{
    snprintf(r->path, sizeof r->path, "%s/%s", r->dir, mf->file[key]);
    CX_TRY(cx_mm_read(r->path, mm, r->d));
    int st = CX_OK;
    if (mm->dense != dense)
        st = cx_diag_set(r->d, CX_EINVAL, "%s: a%s file, expected a%s file (%s)", r->path,
                         mm->dense ? "n array" : " coordinate", dense ? "n array" : " coordinate",
                         dense ? "a dense vector" : "a sparse matrix");
    else if (mm->nrow != nrow || mm->ncol != ncol)
        st = cx_diag_set(r->d, CX_EINVAL, "%s: %d x %d, expected %d x %d (n = %d, m = %d in %s)", r->path, mm->nrow,
                         mm->ncol, nrow, ncol, mf->n, mf->m, CX_PROBLEM_MANIFEST_NAME);
    if (st)
        cx_mm_clear(mm);
    return st;
}

/* A dense vector's entries >= 0 (gaps, weights, friction values). */
static int mm_nonneg(mmdir *r, const cx_mm *mm, const char *what)
{
    for (int i = 0; i < mm->nrow; i++)
        if (mm->x[i] < 0)
            return cx_diag_set(r->d, CX_EINVAL, "%s: entry at row %d, column 1 is %g: %s must be >= 0", r->path, i + 1,
                               mm->x[i], what);
    return CX_OK;
}

/* K from a general file: equal to its transpose (to 1e-12 of its largest
 * entry), the first entry that is not named as in the file. */
static int mm_symmetric(mmdir *r, const cx_csc *K)
{
    double amax = 0;
    for (size_t q = 0; q < cx_csc_nnz(K); q++)
        amax = fmax(amax, fabs(K->x[q]));
    for (int j = 0; j < K->ncol; j++)
        for (int q = K->p[j]; q < K->p[j + 1]; q++) {
            int i = K->i[q];
            double kt = cx_csc_get(K, j, i);
            if (fabs(K->x[q] - kt) > 1e-12 * amax)
                return cx_diag_set(r->d, CX_EINVAL,
                                   "%s: not symmetric: entry at row %d, column %d is %.17g, at row %d, column %d %.17g",
                                   r->path, i + 1, j + 1, K->x[q], j + 1, i + 1, kt);
        }
    return CX_OK;
}

static int csc_data(const cx_csc *A, cx_sparse_data *s)
{
    s->form = CX_SPARSE_CSC;
    s->nrow = A->nrow;
    s->ncol = A->ncol;
    s->p = A->p;
    s->i = A->i;
    s->x = A->x;
    return CX_OK;
}

static int read_mm_dir(const char *dir, cx_problem_file *pf, cx_diag *d)
{
    mmdir r = {dir, "", d};
    snprintf(r.path, sizeof r.path, "%s/%s", dir, CX_PROBLEM_MANIFEST_NAME);
    FILE *f = fopen(r.path, "rb");
    if (!f)
        return cx_diag_set(d, CX_EIO, "%s: %s (a problem directory holds %s and the .mtx files of 'signorini "
                           "export')", r.path, strerror(errno), CX_PROBLEM_MANIFEST_NAME);
    char text[65536];
    size_t len = fread(text, 1, sizeof text, f);
    int big = len == sizeof text;
    fclose(f);
    if (big)
        return cx_diag_set(d, CX_EINVAL, "%s: larger than 64 KiB", r.path);
    cx_problem_manifest mf;
    char name[4096];
    snprintf(name, sizeof name, "%s", r.path);
    CX_TRY(cx_problem_manifest_parse(text, len, name, &mf, d));

    int n = mf.n, m = mf.m, dim = mf.dim, nt = (dim - 1) * m;
    cx_mm mm[F_COUNT];
    memset(mm, 0, sizeof mm);
    int st;
    if ((st = mm_get(&r, &mf, F_K, 0, n, n, &mm[F_K])) || (!mm[F_K].symmetric && (st = mm_symmetric(&r, &mm[F_K].A))) ||
        (st = mm_get(&r, &mf, F_F, 1, n, 1, &mm[F_F])) || (st = mm_get(&r, &mf, F_N, 0, m, n, &mm[F_N])) ||
        (st = mm_get(&r, &mf, F_T, 0, nt, n, &mm[F_T])) || (st = mm_get(&r, &mf, F_G, 1, m, 1, &mm[F_G])) ||
        (st = mm_nonneg(&r, &mm[F_G], "a gap")) || (st = mm_get(&r, &mf, F_WEIGHT, 1, m, 1, &mm[F_WEIGHT])) ||
        (st = mm_nonneg(&r, &mm[F_WEIGHT], "a weight")) ||
        (st = mm_get(&r, &mf, F_POINTS, 1, m, dim, &mm[F_POINTS])))
        goto done;
    int fkey = mf.law == CX_FRICTION_COULOMB ? F_MU : mf.law == CX_FRICTION_TRESCA ? F_SLIP : -1;
    if (fkey >= 0 && ((st = mm_get(&r, &mf, fkey, 1, m, 1, &mm[fkey])) ||
                      (st = mm_nonneg(&r, &mm[fkey], fkey == F_MU ? "a friction coefficient" : "a slip bound"))))
        goto done;

    /* points.mtx is m x dim column-major; the problem keeps rows */
    double *x = CX_NEW(double, (size_t)dim * m + 1);
    if (!x) {
        st = cx_diag_set(d, CX_ENOMEM, "out of memory");
        goto done;
    }
    for (int i = 0; i < m; i++)
        for (int k = 0; k < dim; k++)
            x[dim * i + k] = mm[F_POINTS].x[i + (size_t)k * m];
    cx_problem_data pd = {.dim = dim, .n = n, .m = m, .K_lower = 0, .f = mm[F_F].x, .g = mm[F_G].x,
                          .weight = mm[F_WEIGHT].x, .x = x, .E = mf.E};
    csc_data(&mm[F_K].A, &pd.K);
    csc_data(&mm[F_N].A, &pd.N);
    csc_data(&mm[F_T].A, &pd.T);
    cx_diag why;
    st = cx_problem_from_data(&pf->p, &pd, &why);
    cx_free(x);
    if (st) {
        cx_diag_set(d, st, "%s: %s", dir, why.msg);
        goto done;
    }
    pf->fr.law = mf.law;
    pf->fr.F = mf.F;
    pf->fr.slip_bound = mf.slip_bound;
    if (fkey == F_MU) {
        pf->Fi = mm[F_MU].x;
        mm[F_MU].x = NULL;
    } else if (fkey == F_SLIP) {
        pf->s = mm[F_SLIP].x;
        mm[F_SLIP].x = NULL;
    }
    pf->fr.s = pf->s;
    pf->fr.Fi = pf->Fi;
    snprintf(pf->format, sizeof pf->format, "mm");
    snprintf(pf->source, sizeof pf->source, "%s", mf.source);
    pf->level = mf.level;
done:
    for (int k = 0; k < F_COUNT; k++)
        cx_mm_clear(&mm[k]);
    return st;
}

void cx_problem_file_clear(cx_problem_file *pf)
{
    cx_problem_destroy(&pf->p);
    cx_free(pf->s);
    cx_free(pf->Fi);
    memset(pf, 0, sizeof *pf);
}

int cx_problem_read(const char *path, cx_problem_file *pf, cx_diag *d)
{
    memset(pf, 0, sizeof *pf);
    struct stat sb;
    if (stat(path, &sb) != 0)
        return cx_diag_set(d, CX_EIO, "%s: %s", path, strerror(errno));
    int st = S_ISDIR(sb.st_mode) ? read_mm_dir(path, pf, d) : cx_problem_read_fclib(path, pf, d);
    if (st)
        cx_problem_file_clear(pf);
    return st;
}

int cx_problem_from_scene(const char *id_or_path, int level, cx_problem **p, cx_friction_state *fr,
                          cx_diag *d)
{
    *p = NULL;
    cx_scene sc;
    CX_TRY(cx_scene_open(id_or_path, &sc, d));
    return cx_scene_build(&sc, level, p, fr, d);
}
