/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini export --format mm: the discrete problem as MatrixMarket files
 * (CHOLMOD's writer, linalg/mm.c) and a manifest stating what each file
 * holds and the sign conventions, so that another solver can read the
 * problem without our source (out/export.h). */
#include "out/export.h"
#include "out/json.h"
#include "out/outfile.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

static int mm_path(char *buf, size_t len, const char *dir, const char *name, cx_diag *d)
{
    if ((size_t)snprintf(buf, len, "%s/%s", dir, name) >= len)
        return cx_diag_set(d, CX_EINVAL, "%s: path too long", dir);
    return CX_OK;
}

/* One file of the directory, through out/outfile.h (a temporary renamed
 * onto it when complete): the sparse A, or the dense x when A is NULL. */
static int mm_write(const char *dir, const char *name, const cx_csc *A, int sym, const double *x, int nrow,
                    int ncol, cx_diag *d)
{
    char path[4096];
    CX_TRY(mm_path(path, sizeof path, dir, name, d));
    cx_outfile o;
    CX_TRY(cx_outfile_open(&o, path, d));
    int st = A ? cx_mm_write_csc(o.f, path, A, sym, d) : cx_mm_write_dense(o.f, path, x, nrow, ncol, d);
    int cst = cx_outfile_close(&o, st == CX_OK, d);
    return st ? st : cst;
}

static int mm_csc(const char *dir, const char *name, const cx_csc *A, int sym, cx_diag *d)
{
    return mm_write(dir, name, A, sym, NULL, 0, 0, d);
}

static int mm_dense(const char *dir, const char *name, const double *x, int nrow, int ncol, cx_diag *d)
{
    return mm_write(dir, name, NULL, 0, x, nrow, ncol, d);
}

/* An nrow x ncol column-major copy of the row-major a (stride ncol). */
static int mm_rows(const char *dir, const char *name, const double *a, int nrow, int ncol, cx_diag *d)
{
    double *c = CX_NEW(double, (size_t)nrow * ncol + 1);
    if (!c)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    for (int i = 0; i < nrow; i++)
        for (int k = 0; k < ncol; k++)
            c[i + (size_t)k * nrow] = a[(size_t)i * ncol + k];
    int st = mm_dense(dir, name, c, nrow, ncol, d);
    cx_free(c);
    return st;
}

/* The mesh's part: dofs.mtx, nodes.mtx, point_nodes.mtx. */
static int mm_mesh(const cx_problem *p, const char *dir, cx_diag *d)
{
    int n = p->n, m = p->m, nn = p->mesh->nnodes;
    double *a = CX_NEW(double, 2 * (size_t)n + (size_t)m + 1);
    if (!a)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    for (int k = 0; k < n; k++) {
        int all = p->map.all_of[k];
        a[k] = all / p->dim + 1;
        a[n + k] = all % p->dim + 1;
    }
    for (int i = 0; i < m; i++)
        a[2 * n + i] = p->contact.node[i] + 1;
    int st = mm_dense(dir, "dofs.mtx", a, n, 2, d);
    if (!st)
        st = mm_dense(dir, "point_nodes.mtx", a + 2 * n, m, 1, d);
    if (!st)
        st = mm_rows(dir, "nodes.mtx", p->mesh->x, nn, p->dim, d);
    cx_free(a);
    return st;
}

static int mm_manifest(const cx_problem *p, const cx_friction_state *fr, const char *dir, const char *source,
                       int level, cx_diag *d)
{
    char path[4096];
    CX_TRY(mm_path(path, sizeof path, dir, CX_PROBLEM_MANIFEST, d));
    cx_outfile o;
    CX_TRY(cx_outfile_open(&o, path, d));
    cx_json j;
    cx_json_init(&j, o.f);
    cx_json_object(&j, NULL);
    cx_json_str(&j, "format", "signorini-problem");
    cx_json_int(&j, "version", 1);
    cx_json_str(&j, "source", source ? source : "");
    cx_json_int(&j, "level", level);
    cx_json_int(&j, "dim", p->dim);
    cx_json_int(&j, "n", p->n);
    cx_json_int(&j, "m", p->m);
    cx_json_int(&j, "nt", p->nt);
    cx_json_str(&j, "friction", cx_friction_name(fr->law));
    cx_json_num(&j, "F", fr->F);
    cx_json_num(&j, "slip_bound", fr->slip_bound);
    cx_json_num(&j, "E", cx_problem_stiffness(p));
    cx_json_object(&j, "files");
    cx_json_str(&j, "K", "K.mtx");
    cx_json_str(&j, "f", "f.mtx");
    cx_json_str(&j, "N", "N.mtx");
    cx_json_str(&j, "T", "T.mtx");
    cx_json_str(&j, "g", "g.mtx");
    cx_json_str(&j, "weight", "weight.mtx");
    cx_json_str(&j, "points", "points.mtx");
    if (fr->law == CX_FRICTION_COULOMB)
        cx_json_str(&j, "mu", "mu.mtx");
    if (fr->law == CX_FRICTION_TRESCA)
        cx_json_str(&j, "slip_bound", "slip_bound.mtx");
    if (p->mesh) {
        cx_json_str(&j, "dofs", "dofs.mtx");
        cx_json_str(&j, "nodes", "nodes.mtx");
        cx_json_str(&j, "point_nodes", "point_nodes.mtx");
    }
    cx_json_end_object(&j);
    cx_json_object(&j, "conventions");
    cx_json_str(&j, "equilibrium", "K u - f + N' lN + T' lT = 0 (u: the n unknowns, Dirichlet dofs eliminated)");
    cx_json_str(&j, "contact", "N u - g <= 0, lN >= 0, lN_i (N u - g)_i = 0: (N u)_i closes gap g_i >= 0; "
                "the obstacle's force on the body is -N' lN");
    cx_json_str(&j, "friction", "|lT_i| <= s_i, s_i = slip_bound_i (tresca) or mu_i lN_i (coulomb); "
                "|lT_i| < s_i: T_i u = 0; |lT_i| = s_i: T_i u = c lT_i, c >= 0; the tangential force on the "
                "body is -T' lT");
    cx_json_str(&j, "T_rows", "point i owns rows (dim-1) i .. (dim-1) i + dim - 2 of T (0-based)");
    cx_json_str(&j, "K_storage", "K.mtx is symmetric: its lower triangle");
    cx_json_str(&j, "weight", "the contact boundary's length (2D) or area (3D) lumped at each point");
    cx_json_str(&j, "E", "the material's stiffness scale, by which penalty methods scale their parameter r");
    cx_json_str(&j, "dofs", "row k: the node (row of nodes.mtx) and component (1..dim) of unknown k");
    cx_json_end_object(&j);
    cx_json_end_object(&j);
    fputc('\n', o.f);
    return cx_outfile_close(&o, 1, d);
}

int cx_export_mm(const cx_problem *p, const cx_friction_state *fr, const char *dir, const char *source,
                 int level, cx_diag *d)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
        return cx_diag_set(d, CX_EIO, "%s: %s", dir, strerror(errno));
    struct stat sb;
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return cx_diag_set(d, CX_EIO, "%s: not a directory", dir);
    CX_TRY(mm_csc(dir, "K.mtx", &p->K, 1, d));
    CX_TRY(mm_dense(dir, "f.mtx", p->f, p->n, 1, d));
    CX_TRY(mm_csc(dir, "N.mtx", &p->N, 0, d));
    CX_TRY(mm_csc(dir, "T.mtx", &p->T, 0, d));
    CX_TRY(mm_dense(dir, "g.mtx", p->g, p->m, 1, d));
    CX_TRY(mm_dense(dir, "weight.mtx", p->contact.weight, p->m, 1, d));
    CX_TRY(mm_rows(dir, "points.mtx", p->contact.x, p->m, p->dim, d));
    if (fr->law == CX_FRICTION_COULOMB)
        CX_TRY(mm_dense(dir, "mu.mtx", fr->Fi, p->m, 1, d));
    if (fr->law == CX_FRICTION_TRESCA)
        CX_TRY(mm_dense(dir, "slip_bound.mtx", fr->s, p->m, 1, d));
    if (p->mesh)
        CX_TRY(mm_mesh(p, dir, d));
    return mm_manifest(p, fr, dir, source, level, d);
}
