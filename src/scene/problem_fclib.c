/* SPDX-License-Identifier: GPL-3.0-or-later */
/* An FCLIB global problem read back as ours (scene/problem_file.h; the
 * correspondence is in out/export_fclib.c): K = M, N and T from -H' point
 * by point, g = w_N, F_i = mu_i (all zero: frictionless, T kept). What
 * has no form of ours is refused: equality constraints G, a tangential
 * w, a negative gap. */
#include "scene/problem_file.h"
#include "cx_config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if CX_HAVE_FCLIB
#include <fclib.h>
#include <hdf5.h>

/* FCLIB's reader leaves a matrix's info unset (not NULL) when the file
 * has none, so fclib_delete_global cannot be trusted with a file another
 * program wrote: free what is there, info only where the file has it. */
static void fclib_free_matrix(struct fclib_matrix *A, int has_info)
{
    if (!A)
        return;
    free(A->p);
    free(A->i);
    free(A->x);
    if (has_info && A->info) {
        free(A->info->comment);
        free(A->info);
    }
    free(A);
}

static void fclib_free(struct fclib_global *g, const int has_info[3])
{
    if (!g)
        return;
    fclib_free_matrix(g->M, has_info[0]);
    fclib_free_matrix(g->H, has_info[1]);
    fclib_free_matrix(g->G, has_info[2]);
    free(g->mu);
    free(g->f);
    free(g->b);
    free(g->w);
    if (g->info) {
        free(g->info->title);
        free(g->info->description);
        free(g->info->math_info);
        free(g->info);
    }
    free(g);
}

static int fclib_sparse(const struct fclib_matrix *A, cx_sparse_data *s)
{
    if (A->nz == -1)
        s->form = CX_SPARSE_CSC;
    else if (A->nz >= 0)
        s->form = CX_SPARSE_TRIPLET;
    else
        return -1;   /* compressed rows: not written by FCLIB's own tools we read */
    s->nrow = A->m;
    s->ncol = A->n;
    s->nnz = A->nz >= 0 ? (size_t)A->nz : 0;
    s->p = A->nz == -1 ? A->p : NULL;
    s->i = A->i;
    s->j = A->nz >= 0 ? A->p : NULL;   /* FCLIB's triplets keep the columns in p */
    s->x = A->x;
    return 0;
}

/* ---- the file checked before FCLIB reads it -------------------------- */

/* libfclib stops the process (exit) when an HDF5 call fails or a size does
 * not divide, and reads each dataset whole into a buffer it sized from
 * other datasets (a longer one overruns it). So every group and dataset
 * fclib_read_global will read is checked here first with the HDF5 API:
 * present, numeric (a string where it reads one), of the size fclib will
 * allocate, and readable (read once, which also finds damaged data); the
 * first fault is one line naming the file and the dataset. HDF5's own
 * error printing is off (H5Eset_auto2) while we look. */
typedef struct h5chk {
    hid_t fid;
    const char *path;
    cx_diag *d;
} h5chk;

static int h5_fail(h5chk *c, const char *name, const char *what)
{
    return cx_diag_set(c->d, CX_EINVAL, "%s: FCLIB dataset %s %s", c->path, name, what);
}

/* Does the link name exist (each group on the way too)? */
static int h5_exists(h5chk *c, const char *name)
{
    char part[128];
    size_t n = strlen(name);
    for (size_t k = 1; k <= n; k++)
        if (name[k] == '/' || name[k] == 0) {
            if (k >= sizeof part)
                return 0;
            memcpy(part, name, k);
            part[k] = 0;
            if (H5Lexists(c->fid, part, H5P_DEFAULT) <= 0)
                return 0;
        }
    return 1;
}

/* Dataset name: present, of class string (str) or numeric, of want values
 * (want < 0: any; its count in *count), read whole: ints into ibuf when
 * given (else a scratch buffer), strings into scratch. */
static int h5_dataset(h5chk *c, const char *name, int str, long long want, int *ibuf, long long *count)
{
    if (!h5_exists(c, name))
        return h5_fail(c, name, "is missing");
    hid_t ds = H5Dopen2(c->fid, name, H5P_DEFAULT);
    if (ds < 0)
        return h5_fail(c, name, "is not a dataset");
    hid_t ty = H5Dget_type(ds), sp = H5Dget_space(ds);
    H5T_class_t cl = ty >= 0 ? H5Tget_class(ty) : H5T_NO_CLASS;
    long long np = sp >= 0 ? (long long)H5Sget_simple_extent_npoints(sp) : -1;
    int st = CX_OK;
    char what[96];
    if (str ? cl != H5T_STRING : cl != H5T_INTEGER && cl != H5T_FLOAT) {
        st = h5_fail(c, name, str ? "is not a string" : "is not numeric");
    } else if (str && H5Tis_variable_str(ty) > 0) {
        st = h5_fail(c, name, "is a variable-length string (FCLIB reads fixed-length ones)");
    } else if (np < 0 || (want >= 0 && np != want)) {
        snprintf(what, sizeof what, "has %lld values, expected %lld", np, want);
        st = h5_fail(c, name, what);
    } else {
        size_t esz = str ? H5Tget_size(ty) : cl == H5T_INTEGER ? sizeof(int) : sizeof(double);
        void *buf = ibuf ? (void *)ibuf : cx_malloc(esz * (size_t)np + 1);
        hid_t mt = str ? ty : cl == H5T_INTEGER ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE;
        if (!buf)
            st = cx_diag_set(c->d, CX_ENOMEM, "%s: out of memory checking %s", c->path, name);
        else if (esz == 0 || H5Dread(ds, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0)
            st = h5_fail(c, name, "cannot be read (a damaged file?)");
        if (buf != ibuf)
            cx_free(buf);
    }
    if (count)
        *count = np;
    if (sp >= 0)
        H5Sclose(sp);
    if (ty >= 0)
        H5Tclose(ty);
    H5Dclose(ds);
    return st;
}

/* One int of a one-value dataset. */
static int h5_int(h5chk *c, const char *name, int *v)
{
    return h5_dataset(c, name, 0, 1, v, NULL);
}

/* A matrix group (fclib's read_matrix): nzmax, m, n, nz, p, i, x, and its
 * info when it has conditioning. dims[0..1] = m, n. */
static int h5_matrix(h5chk *c, const char *grp, int dims[2])
{
    char name[128];
    int nzmax, m, n, nz;
#define H5_NAME(leaf) (snprintf(name, sizeof name, "%s/%s", grp, leaf), name)
    CX_TRY(h5_int(c, H5_NAME("nzmax"), &nzmax));
    CX_TRY(h5_int(c, H5_NAME("m"), &m));
    CX_TRY(h5_int(c, H5_NAME("n"), &n));
    CX_TRY(h5_int(c, H5_NAME("nz"), &nz));
    if (m < 0 || n < 0 || nzmax < 0 || nz < -2 || (nz >= 0 && nz > nzmax))
        return cx_diag_set(c->d, CX_EINVAL, "%s: FCLIB matrix %s: m = %d, n = %d, nzmax = %d, nz = %d "
                           "(expected m, n, nzmax >= 0 and nz in [-2, nzmax])", c->path, grp, m, n,
                           nzmax, nz);
    long long np = nz >= 0 ? nz : nz == -1 ? (long long)n + 1 : (long long)m + 1;
    CX_TRY(h5_dataset(c, H5_NAME("p"), 0, np, NULL, NULL));
    CX_TRY(h5_dataset(c, H5_NAME("i"), 0, nz >= 0 ? nz : nzmax, NULL, NULL));
    CX_TRY(h5_dataset(c, H5_NAME("x"), 0, nzmax, NULL, NULL));
    if (h5_exists(c, H5_NAME("conditioning"))) {
        if (h5_exists(c, H5_NAME("comment")))
            CX_TRY(h5_dataset(c, name, 1, -1, NULL, NULL));
        /* Debian's libfclib 3.1 reads these three (no sparsity) */
        static const char *const info[3] = {"conditioning", "determinant", "rank"};
        for (int k = 0; k < 3; k++)
            CX_TRY(h5_dataset(c, H5_NAME(info[k]), 0, 1, NULL, NULL));
    }
#undef H5_NAME
    dims[0] = m;
    dims[1] = n;
    return CX_OK;
}

static int h5_check_global(h5chk *c)
{
    int dim, M[2], H[2];
    CX_TRY(h5_int(c, "/fclib_global/spacedim", &dim));
    if (dim != 2 && dim != 3)
        return cx_diag_set(c->d, CX_EINVAL, "%s: spacedim %d, expected 2 or 3", c->path, dim);
    CX_TRY(h5_matrix(c, "/fclib_global/M", M));
    CX_TRY(h5_matrix(c, "/fclib_global/H", H));
    if (h5_exists(c, "/fclib_global/G"))
        return cx_diag_set(c->d, CX_EUNSUPPORTED, "%s: equality constraints G: not supported", c->path);
    if (H[1] % dim != 0)
        return cx_diag_set(c->d, CX_EINVAL, "%s: H has %d columns, not a multiple of spacedim %d", c->path,
                           H[1], dim);
    CX_TRY(h5_dataset(c, "/fclib_global/vectors/f", 0, M[0], NULL, NULL));
    CX_TRY(h5_dataset(c, "/fclib_global/vectors/w", 0, H[1], NULL, NULL));
    CX_TRY(h5_dataset(c, "/fclib_global/vectors/mu", 0, H[1] / dim, NULL, NULL));
    static const char *const info[3] = {"/fclib_global/info/title", "/fclib_global/info/description",
                                        "/fclib_global/info/math_info"};
    for (int k = 0; h5_exists(c, "/fclib_global/info") && k < 3; k++)
        if (h5_exists(c, info[k]))
            CX_TRY(h5_dataset(c, info[k], 1, -1, NULL, NULL));
    return CX_OK;
}

int cx_problem_read_fclib(const char *path, cx_problem_file *pf, cx_diag *d)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    htri_t is = H5Fis_hdf5(path);
    if (is <= 0)
        return cx_diag_set(d, CX_EINVAL, "%s: not a problem directory or an HDF5 file", path);
    hid_t fid = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (fid < 0)
        return cx_diag_set(d, CX_EINVAL, "%s: an HDF5 file that HDF5 cannot open (truncated or damaged?)",
                           path);
    int global = H5Lexists(fid, "/fclib_global", H5P_DEFAULT) > 0;
    h5chk chk = {fid, path, d};
    int bad = global ? h5_check_global(&chk) : CX_OK;
    if (bad) {
        H5Fclose(fid);
        return bad;
    }
    int has_info[3] = {0, 0, 0};
    const char *const groups[3] = {"/fclib_global/M", "/fclib_global/H", "/fclib_global/G"};
    for (int k = 0; global && k < 3; k++)
        if (H5Lexists(fid, groups[k], H5P_DEFAULT) > 0) {
            char name[64];
            snprintf(name, sizeof name, "%s/conditioning", groups[k]);
            has_info[k] = H5Lexists(fid, name, H5P_DEFAULT) > 0;
        }
    H5Fclose(fid);
    if (!global)
        return cx_diag_set(d, CX_EINVAL, "%s: no FCLIB global problem (/fclib_global) in it", path);
    struct fclib_global *g = fclib_read_global(path);
    if (!g)
        return cx_diag_set(d, CX_EINVAL, "%s: FCLIB could not read the global problem", path);
    int st = CX_OK, dim = g->spacedim;
    cx_sparse_data K = {0}, H = {0};
    if (g->G)
        st = cx_diag_set(d, CX_EUNSUPPORTED, "%s: equality constraints G: not supported", path);
    else if (dim != 2 && dim != 3)
        st = cx_diag_set(d, CX_EINVAL, "%s: spacedim %d, expected 2 or 3", path, dim);
    else if (fclib_sparse(g->M, &K) || fclib_sparse(g->H, &H))
        st = cx_diag_set(d, CX_EUNSUPPORTED, "%s: a matrix in compressed rows: not supported", path);
    else if (g->M->m != g->M->n || g->H->m != g->M->n || g->H->n % dim != 0)
        st = cx_diag_set(d, CX_EINVAL, "%s: M is %d x %d and H %d x %d: expected M n x n and H n x %d nc", path,
                         g->M->m, g->M->n, g->H->m, g->H->n, dim);
    if (st) {
        fclib_free(g, has_info);
        return st;
    }
    int n = g->M->n, m = g->H->n / dim, nt = (dim - 1) * m;
    /* N and T: rows of -H', H's column dim i + k to row i of N (k = 0) or
     * row (dim-1) i + k - 1 of T */
    cx_problem_data pd = {.dim = dim, .n = n, .m = m, .K = K, .f = g->f, .g = NULL};
    double *gap = cx_calloc((size_t)m + 1, sizeof(double));
    cx_triplet Nt = {0}, Tt = {0};
    st = gap ? CX_OK : cx_diag_set(d, CX_ENOMEM, "out of memory");
    size_t hn = H.form == CX_SPARSE_CSC ? (size_t)g->H->p[g->H->n] : H.nnz;
    if (!st && ((st = cx_triplet_init(&Nt, m, n, hn)) || (st = cx_triplet_init(&Tt, nt, n, hn))))
        cx_diag_set(d, st, "out of memory");
    for (size_t q = 0, col = 0; !st && q < hn; q++) {
        int i, j;
        if (H.form == CX_SPARSE_CSC) {
            while ((int)col < g->H->n && (size_t)g->H->p[col + 1] <= q)
                col++;
            j = (int)col;
        } else {
            j = H.j[q];
        }
        i = H.i[q];
        double x = H.x[q];
        if (i < 0 || i >= n || j < 0 || j >= g->H->n || !isfinite(x)) {
            st = cx_diag_set(d, CX_EINVAL, "%s: H: entry %zu (row %d, column %d): %s", path, q, i + 1, j + 1,
                             isfinite(x) ? "index out of range" : "not a finite value");
            break;
        }
        int pt = j / dim, k = j % dim;
        st = k == 0 ? cx_triplet_add(&Nt, pt, i, -x) : cx_triplet_add(&Tt, (dim - 1) * pt + k - 1, i, -x);
    }
    int coulomb = 0;
    for (int i = 0; !st && i < m; i++) {
        for (int k = 1; k < dim; k++)
            if (g->w[dim * i + k] != 0)
                st = cx_diag_set(d, CX_EUNSUPPORTED, "%s: w at contact %d, component %d is %g: a tangential offset "
                                 "has no form in signorini", path, i + 1, k + 1, g->w[dim * i + k]);
        gap[i] = g->w[dim * i];
        if (!st && !(gap[i] >= 0 && isfinite(gap[i])))
            st = cx_diag_set(d, CX_EINVAL, "%s: w at contact %d is %g: the initial gap must be >= 0", path, i + 1,
                             gap[i]);
        if (!st && !(g->mu[i] >= 0 && isfinite(g->mu[i])))
            st = cx_diag_set(d, CX_EINVAL, "%s: mu at contact %d is %g, expected >= 0", path, i + 1, g->mu[i]);
        coulomb |= !st && g->mu[i] > 0;
    }
    cx_csc Nc = {0}, Tc = {0};
    if (!st && ((st = cx_csc_from_triplet(&Nc, &Nt)) || (st = cx_csc_from_triplet(&Tc, &Tt))))
        cx_diag_set(d, st, "out of memory");
    if (!st) {
        pd.N = (cx_sparse_data){CX_SPARSE_CSC, m, n, 0, Nc.p, Nc.i, NULL, Nc.x};
        pd.T = (cx_sparse_data){CX_SPARSE_CSC, nt, n, 0, Tc.p, Tc.i, NULL, Tc.x};
        pd.g = gap;
        cx_diag why;
        if ((st = cx_problem_from_data(&pf->p, &pd, &why)))
            cx_diag_set(d, st, "%s: %s", path, why.msg);
    }
    if (!st && coulomb) {
        pf->Fi = cx_calloc((size_t)m, sizeof(double));
        if (!pf->Fi)
            st = cx_diag_set(d, CX_ENOMEM, "out of memory");
        for (int i = 0; !st && i < m; i++)
            pf->Fi[i] = g->mu[i];
    }
    if (!st) {
        pf->fr.law = coulomb ? CX_FRICTION_COULOMB : CX_FRICTION_NONE;
        pf->fr.Fi = pf->Fi;
        pf->fr.F = m > 0 ? g->mu[0] : 0;
        snprintf(pf->format, sizeof pf->format, "fclib");
        /* our title is "signorini SCENE level L"; another program's is kept whole */
        const char *title = g->info && g->info->title ? g->info->title : "";
        char id[256];
        int level = 0;
        if (sscanf(title, "signorini %255s level %d", id, &level) == 2) {
            snprintf(pf->source, sizeof pf->source, "%s", id);
            pf->level = level;
        } else {
            snprintf(pf->source, sizeof pf->source, "%s", title);
        }
    }
    cx_csc_clear(&Nc);
    cx_csc_clear(&Tc);
    cx_triplet_clear(&Nt);
    cx_triplet_clear(&Tt);
    cx_free(gap);
    fclib_free(g, has_info);
    return st;
}

#else

int cx_problem_read_fclib(const char *path, cx_problem_file *pf, cx_diag *d)
{
    (void)pf;
    return cx_diag_set(d, CX_EUNSUPPORTED, "%s: not a directory; an FCLIB file needs a signorini built with FCLIB "
                       "(meson -Dfclib)", path);
}

#endif
