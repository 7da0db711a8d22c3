/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini export --format fclib: the problem as an FCLIB global
 * frictional contact problem (out/export.h). FCLIB's form
 *     M v = H r + f,   u = H' v + w,   C*(mu) ∋ û ⊥ r ∈ C(mu)
 * per contact point (normal first, then the tangents) is ours with
 *     v = u, M = K, r = (lN_i, lT_i), H = -[N; T]' (point by point),
 *     w = (g_i, 0): FCLIB's normal u_N = g_i - (N u)_i is the gap left,
 *     its tangential u_T = -T u,
 * so that r_T opposes u_T exactly when our lT is along T u (solve/problem.h).
 * Tresca has no FCLIB form (the cone's radius is mu r_N, not a bound). */
#include "out/export.h"
#include "cx_config.h"

#include <errno.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#if CX_HAVE_FCLIB
#include <fclib.h>
#include <hdf5.h>

/* H (n x dim m, CSC) from N and T: column dim i is -(row i of N), column
 * dim i + 1 + k is -(row (dim-1) i + k of T). */
static int fclib_H(const cx_problem *p, struct fclib_matrix *H)
{
    cx_csc Nt = {0}, Tt = {0};
    int st = cx_csc_transpose(&Nt, &p->N);
    if (!st)
        st = cx_csc_transpose(&Tt, &p->T);
    int dim = p->dim, nc = dim * p->m;
    size_t nnz = cx_csc_nnz(&p->N) + cx_csc_nnz(&p->T);
    H->m = p->n;
    H->n = nc;
    H->nz = -1;
    H->nzmax = (int)(nnz > 0 ? nnz : 1);
    H->p = cx_calloc((size_t)nc + 1, sizeof(int));
    H->i = cx_calloc((size_t)H->nzmax, sizeof(int));
    H->x = cx_calloc((size_t)H->nzmax, sizeof(double));
    if (!st && (!H->p || !H->i || !H->x))
        st = CX_ENOMEM;
    int q = 0;
    for (int c = 0; !st && c < nc; c++) {
        int i = c / dim, k = c % dim;
        const cx_csc *B = k == 0 ? &Nt : &Tt;
        int col = k == 0 ? i : (dim - 1) * i + k - 1;
        H->p[c] = q;
        for (int r = B->p[col]; r < B->p[col + 1]; r++, q++) {
            H->i[q] = B->i[r];
            H->x[q] = -B->x[r];
        }
    }
    if (!st)
        H->p[nc] = q;
    cx_csc_clear(&Nt);
    cx_csc_clear(&Tt);
    return st;
}

int cx_export_fclib(const cx_problem *p, const cx_friction_state *fr, const char *path, const char *source,
                    int level, cx_diag *d)
{
    if (fr->law == CX_FRICTION_TRESCA)
        return cx_diag_set(d, CX_EUNSUPPORTED, "%s: Tresca friction has no FCLIB form (FCLIB's problems are "
                           "Coulomb's; use --friction coulomb or none, or --format mm)", path);
    struct stat sb;
    if (stat(path, &sb) == 0 && !S_ISREG(sb.st_mode))
        return cx_diag_set(d, CX_EIO, "%s: not a regular file", path);
    /* fclib_write_global adds to an existing file and refuses a second
     * problem: the file is replaced */
    if (stat(path, &sb) == 0 && unlink(path) != 0)
        return cx_diag_set(d, CX_EIO, "%s: %s", path, strerror(errno));
    int n = p->n, m = p->m, dim = p->dim;
    struct fclib_matrix M = {0}, H = {0};
    /* every matrix with its info: FCLIB's reader leaves a missing one
     * unset, and its fclib_delete_global would free that */
    struct fclib_matrix_info Minfo = {0}, Hinfo = {0};
    M.m = M.n = n;
    M.nz = -1;
    M.nzmax = (int)(cx_csc_nnz(&p->K) > 0 ? cx_csc_nnz(&p->K) : 1);
    M.p = p->K.p;
    M.i = p->K.i;
    M.x = p->K.x;
    Minfo.comment = (char *)"K: symmetric, both triangles stored";
    Minfo.conditioning = Minfo.determinant = -1;
    Minfo.rank = -1;
    M.info = &Minfo;
    Hinfo.comment = (char *)"H = -[N; T]': per contact point the normal column, then the tangents";
    Hinfo.conditioning = Hinfo.determinant = -1;
    Hinfo.rank = -1;
    double *w = cx_calloc((size_t)dim * m + 1, sizeof(double));
    double *mu = cx_calloc((size_t)m + 1, sizeof(double));
    int st = fclib_H(p, &H);
    H.info = &Hinfo;
    if (!st && (!w || !mu))
        st = CX_ENOMEM;
    for (int i = 0; !st && i < m; i++) {
        w[dim * i] = p->g[i];
        mu[i] = fr->law == CX_FRICTION_COULOMB ? (fr->Fi ? fr->Fi[i] : fr->F) : 0;
    }
    char title[300], descr[600];
    snprintf(title, sizeof title, "signorini %s level %d", source ? source : "", level);
    snprintf(descr, sizeof descr,
             "%dD elastic contact (signorini export), %s: M = K (u = v), H = -[N; T]' per point (normal, "
             "tangents), w = (gap, 0), mu = F per point%s", dim,
             cx_friction_name(fr->law), fr->law == CX_FRICTION_NONE ? " (frictionless: mu = 0)" : "");
    struct fclib_info info = {title, descr, (char *)"M symmetric positive semi-definite"};
    struct fclib_global g = {&M, &H, NULL, mu, p->f, NULL, w, dim, &info};
    if (!st) {
        H5Eset_auto2(H5E_DEFAULT, NULL, NULL);   /* errors are our one line, not HDF5's stack */
        if (!fclib_write_global(&g, path))
            st = cx_diag_set(d, CX_EIO, "%s: FCLIB could not write the problem", path);
    } else {
        cx_diag_set(d, st, "out of memory");
    }
    cx_free(H.p);
    cx_free(H.i);
    cx_free(H.x);
    cx_free(w);
    cx_free(mu);
    return st;
}

#else

int cx_export_fclib(const cx_problem *p, const cx_friction_state *fr, const char *path, const char *source,
                    int level, cx_diag *d)
{
    (void)p, (void)fr, (void)source, (void)level;
    return cx_diag_set(d, CX_EUNSUPPORTED, "%s: this signorini was built without FCLIB (meson -Dfclib)", path);
}

#endif
