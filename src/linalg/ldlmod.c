/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A simplicial LDL' factor whose rows and columns are switched between the
 * matrix's and the identity's by CHOLMOD's row delete / row add (Modify
 * module): the single principal pivots of Lawson-Hanson change the factor
 * by one row and column each, far cheaper than a new factorisation. The
 * factor is of P A P' (fill-reducing P); CHOLMOD's k and R are in that
 * order, so indices are mapped through the inverse permutation here. */
#include "linalg/linalg_impl.h"

#include <math.h>
#include <string.h>

struct cx_ldlmod {
    cholmod_common c;
    cholmod_factor *L;
    cholmod_factor *sym;   /* the symbolic analysis, kept for refactorisations */
    int super;             /* factorise supernodal, then convert (create_super) */
    cx_counters *cnt;
    int n;
    int *pinv;         /* n: position in L's order of an original index */
    int *ri;           /* n: row buffer of R */
    double *rx;        /* n */
    double *w;         /* n: solve workspace */
    int *parent;       /* n: elimination tree of the analysed pattern, in L's order (-1: root) */
    int *mark;         /* n: visit stamps of the row reaches */
    int *sp, *si;      /* super: the lower triangle of P A P' (CSC, sorted), factorised in
                          place of A so that CHOLMOD need not permute A each time */
    double *sx;
    int *smap;         /* its entries' places in A->x */
    int *dirty;        /* n: the columns whose pivot an update changed since the last check */
    int ndirty;
    unsigned char *isdirty;   /* n: 1 on those */
    int stamp;
    cholmod_dense *X, *Y, *E;   /* cholmod_solve2's workspace, kept between solves */
    double lnz_full;   /* entries of L as factorised, before the zeros are dropped */
};

void cx_ldlmod_destroy(cx_ldlmod **F)
{
    if (!F || !*F)
        return;
    cx_ldlmod *f = *F;
    cholmod_free_factor(&f->L, &f->c);
    cholmod_free_factor(&f->sym, &f->c);
    cholmod_free_dense(&f->X, &f->c);
    cholmod_free_dense(&f->Y, &f->c);
    cholmod_free_dense(&f->E, &f->c);
    cholmod_finish(&f->c);
    cx_free(f->pinv), cx_free(f->ri), cx_free(f->rx), cx_free(f->w);
    cx_free(f->parent), cx_free(f->mark), cx_free(f->dirty), cx_free(f->isdirty);
    cx_free(f->sp), cx_free(f->si), cx_free(f->sx), cx_free(f->smap);
    cx_free(f);
    *F = NULL;
}

/* Drop the exact zeros below the diagonal of the simplicial factor: the
 * relaxed supernodes' padding, and the rows and columns that the mask
 * holds at the identity (the closed start masks every contact unknown, so
 * its factor has the pattern of A's but far fewer non-zeros). Solves and
 * updates then walk only the true non-zeros. The columns are packed
 * towards the front, in order, each left one free slot where the space
 * allows (the space dropped before it; the first columns may have none),
 * and the space freed goes to the end of L (Lp[n], CHOLMOD's free
 * space). CHOLMOD's row add moves a column to that free space whenever
 * the column is full, even when it already holds the new row; with the
 * columns packed as they were (the zeros left in place, no space at the
 * end) the first such move grew the whole factor (a copy of L, 30-40 ms
 * at 1/100), and every column keeps room for what its updates add:
 * the masked matrices' patterns are all within A's. */
static void ldlmod_drop_zeros(cx_ldlmod *f)
{
    cholmod_factor *L = f->L;
    int *lp = L->p, *li = L->i, *lnz = L->nz;
    double *lx = L->x;
    /* a new factor's columns lie in order (monotonic): packing keeps it */
    int packs = L->is_monotonic, end = 0;   /* end: of the packed columns so far */
    for (int j = 0; j < f->n; j++) {
        int p0 = lp[j], pend = p0 + lnz[j];
        /* end <= p0 (the columns before ended there at most) */
        int start = !packs ? p0 : j == 0 ? p0 : end + 1 <= p0 ? end + 1 : p0;
        li[start] = li[p0];   /* the diagonal (D) stays first */
        lx[start] = lx[p0];
        int w = start + 1;
        for (int p = p0 + 1; p < pend; p++)
            if (lx[p] != 0) {
                li[w] = li[p];
                lx[w++] = lx[p];
            }
        lp[j] = start;
        lnz[j] = w - start;
        end = w;
    }
    if (packs)   /* the last column's slot, then CHOLMOD's free space */
        lp[f->n] = (size_t)end + 1 <= L->nzmax ? end + 1 : end;
}

/* One entry A(i, k), i < k, of Liu's ancestor walk with path compression:
 * climb from i to the root of its subtree so far, pointing each node on the
 * way at k; the root found becomes k's child. */
static inline void etree_visit(int *anc, int *parent, int i, int k)
{
    while (i != -1 && i < k) {
        int next = anc[i];
        anc[i] = k;
        if (next == -1)
            parent[i] = k;
        i = next;
    }
}

/* The lower triangle of P A P' (P: the analysis's order) as its own
 * pattern, with the place in A of each entry's value, built once: a
 * factorisation then gathers A's values into it and hands CHOLMOD the
 * permuted matrix with the natural order, where CHOLMOD otherwise
 * transposes A through P at every factorisation (a sixth of a
 * refactorisation at 1/100). Row r of P A P' is column perm[r] of A (the
 * pattern symmetric), so walking r upwards fills each column's rows in
 * order; each value is read from A's upper triangle, as CHOLMOD's view of
 * A (stype 1) reads it, so that the factor is the same to the last bit
 * when A's triangles differ by roundoff (T' K T can). The same walk
 * gives the elimination tree (as ldlmod_etree, which it saves a pass). */
static int ldlmod_permuted(cx_ldlmod *f, const cx_csc *A)
{
    int n = f->n, st = CX_ENOMEM;
    size_t anz = cx_csc_nnz(A);
    const int *perm = f->sym->Perm;
    int *pinv = f->pinv, *pos = CX_NEW(int, n + 1), *upper = CX_NEW(int, anz + 1);
    f->sp = CX_NEW(int, n + 1);
    if (!pos || !upper || !f->sp)
        goto done;
    /* upper[q]: the place of A(j, i) for a lower entry q = A(i, j), i > j
     * (itself if not stored): column i's rows ascend as j does */
    for (int c = 0; c < n; c++)
        pos[c] = A->p[c];
    for (int j = 0; j < n; j++)
        for (int q = A->p[j]; q < A->p[j + 1]; q++) {
            int i = A->i[q];
            upper[q] = q;
            if (i <= j)
                continue;
            while (pos[i] < A->p[i + 1] && A->i[pos[i]] < j)
                pos[i]++;
            if (pos[i] < A->p[i + 1] && A->i[pos[i]] == j)
                upper[q] = pos[i];
        }
    for (int r = 0; r < n; r++)
        pinv[perm ? perm[r] : r] = r;
    for (int r = 0; r < n; r++) {
        int col = perm ? perm[r] : r;
        for (int q = A->p[col]; q < A->p[col + 1]; q++)
            if (pinv[A->i[q]] <= r)
                f->sp[pinv[A->i[q]] + 1]++;
    }
    for (int c = 0; c < n; c++)
        f->sp[c + 1] += f->sp[c];
    size_t nz = (size_t)f->sp[n];
    f->si = CX_NEW(int, nz + 1);
    f->sx = CX_NEW(double, nz + 1);
    f->smap = CX_NEW(int, nz + 1);
    if (!f->si || !f->sx || !f->smap)
        goto done;
    /* the same walk gives the elimination tree (ldlmod_etree's, fused) */
    int *anc = f->mark;
    memcpy(pos, f->sp, sizeof(int) * (size_t)n);
    for (int r = 0; r < n; r++) {
        int col = perm ? perm[r] : r;
        f->parent[r] = -1, anc[r] = -1;
        for (int q = A->p[col]; q < A->p[col + 1]; q++) {
            int c = pinv[A->i[q]];
            if (c > r)
                continue;
            int t = pos[c]++;
            f->si[t] = r;
            f->smap[t] = upper[q];
            etree_visit(anc, f->parent, c, r);
        }
    }
    for (int k = 0; k < n; k++)
        f->mark[k] = 0;
    f->stamp = 0;
    st = CX_OK;
done:
    cx_free(pos);
    cx_free(upper);
    return st;
}

/* The numeric factor of A from the kept analysis: a copy of the symbolic
 * factor (a modified L's columns may have moved), factorised, and with
 * super the supernodal LL' converted to the simplicial LDL' that Modify
 * needs (the supernodal factorisation is several times faster on the
 * larger meshes; the conversion is one pass over L). */
/* The mask of a factorisation (cx_ldlmod_create_masked): NULL, or keep
 * (n: 1 where row and column are A's, 0 where the identity's) and the
 * shift added to the kept diagonal. */
typedef struct {
    const unsigned char *keep;
    double shift;
} ldlmod_mask;

/* Entry (i, j) of the masked matrix, a its value in A. */
static inline double ldlmod_masked(const ldlmod_mask *m, int i, int j, double a)
{
    if (!m->keep[i] || !m->keep[j])
        return i == j;
    return i == j ? a + m->shift : a;
}

/* A copy of A masked (the simplicial path, which factorises A itself). */
static int ldlmod_masked_copy(cx_csc *M, const cx_csc *A, const ldlmod_mask *m)
{
    if (cx_csc_copy(M, A))
        return CX_ENOMEM;
    for (int j = 0; j < A->ncol; j++)
        for (int q = A->p[j]; q < A->p[j + 1]; q++)
            M->x[q] = ldlmod_masked(m, A->i[q], j, A->x[q]);
    return CX_OK;
}

static int ldlmod_factor(cx_ldlmod *f, const cx_csc *A, const ldlmod_mask *mask, cx_diag *d)
{
    for (int a = 0; a < f->ndirty; a++)   /* a new factor is checked in full */
        f->isdirty[f->dirty[a]] = 0;
    f->ndirty = 0;
    cholmod_free_factor(&f->L, &f->c);
    f->L = cholmod_copy_factor(f->sym, &f->c);
    CX_TRY(cx_cholmod_check(&f->c, f->L, "copy of the analysis (ldlmod)", d));
    if (f->sp) {
        /* P A P' gathered, factorised in the natural order (the order
         * restored after: the solves and updates permute through L->Perm) */
        int n = f->n, ord = f->L->ordering;
        if (!mask) {
            for (int t = 0; t < f->sp[n]; t++)
                f->sx[t] = A->x[f->smap[t]];
        } else {
            /* the mask applied as the values are gathered: the masked
             * matrix is never formed */
            const int *perm = f->sym->Perm;
            for (int c = 0; c < n; c++) {
                int j = perm ? perm[c] : c;
                for (int t = f->sp[c]; t < f->sp[c + 1]; t++) {
                    int i = perm ? perm[f->si[t]] : f->si[t];
                    f->sx[t] = ldlmod_masked(mask, i, j, A->x[f->smap[t]]);
                }
            }
        }
        cholmod_sparse s;
        memset(&s, 0, sizeof s);
        s.nrow = s.ncol = (size_t)n;
        s.nzmax = (size_t)f->sp[n] + 1;
        s.p = f->sp, s.i = f->si, s.x = f->sx;
        s.stype = -1, s.itype = CHOLMOD_INT, s.xtype = CHOLMOD_REAL, s.dtype = CHOLMOD_DOUBLE;
        s.sorted = 1, s.packed = 1;
        f->L->ordering = CHOLMOD_NATURAL;
        cholmod_factorize(&s, f->L, &f->c);
        f->L->ordering = ord;
    } else {
        cx_csc M = {0};
        if (mask && ldlmod_masked_copy(&M, A, mask))
            return cx_diag_set(d, CX_ENOMEM, "out of memory");
        cholmod_sparse s = cx_cholmod_view(mask ? &M : A, 1);
        cholmod_factorize(&s, f->L, &f->c);
        cx_csc_clear(&M);
    }
    CX_TRY(cx_cholmod_check(&f->c, f->L, "LDL' factorisation", d));
    if (f->cnt)
        f->cnt->factorizations++;
    if (f->L->minor < f->L->n)
        return cx_diag_set(d, CX_ENUMERIC, "LDL' factorisation: matrix not positive definite");
    if (f->super) {
        cholmod_change_factor(CHOLMOD_REAL, 0, 0, 1, 1, f->L, &f->c);
        CX_TRY(cx_cholmod_check(&f->c, f->L, "supernodal to simplicial LDL'", d));
    }
    f->lnz_full = 0;
    for (int j = 0; j < f->n; j++)
        f->lnz_full += ((const int *)f->L->nz)[j];
    ldlmod_drop_zeros(f);
    return CX_OK;
}

/* The elimination tree of P A P' (A's pattern: every masked matrix's is
 * within it) by Liu's ancestor walk with path compression; mark serves as
 * the ancestor array. Node j's parent is the first row below j in column j
 * of the factor of A, and a non-zero L(k, j) of any masked matrix's factor
 * makes k an ancestor of j in this tree (its factor's pattern is within
 * A's). */
static void ldlmod_etree(cx_ldlmod *f, const cx_csc *A)
{
    int n = f->n, *anc = f->mark;
    for (int k = 0; k < n; k++) {
        f->parent[k] = -1, anc[k] = -1;
        int col = cx_cholmod_column(f->L, k);
        for (int q = A->p[col]; q < A->p[col + 1]; q++) {
            etree_visit(anc, f->parent, f->pinv[A->i[q]], k);
        }
    }
    for (int k = 0; k < n; k++)
        f->mark[k] = 0;
    f->stamp = 0;
}

static int ldlmod_new(cx_ldlmod **F, const cx_csc *A, const ldlmod_mask *mask, int super,
                      const cx_ldlmod *like, cx_counters *cnt, cx_diag *d)
{
    int n = A->ncol;
    cx_ldlmod *f = CX_NEW(cx_ldlmod, 1);
    *F = NULL;
    if (!f)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    cx_cholmod_start(&f->c);
    if (!super)
        f->c.supernodal = CHOLMOD_SIMPLICIAL;   /* Modify needs a simplicial LDL' */
    f->c.final_ll = 0;
    f->super = super;
    f->cnt = cnt;
    f->n = n;
    f->pinv = CX_NEW(int, n);
    f->ri = CX_NEW(int, n);
    f->rx = CX_NEW(double, n);
    f->w = CX_NEW(double, n);
    f->parent = CX_NEW(int, n);
    f->mark = CX_NEW(int, n);
    f->dirty = CX_NEW(int, n + 1);
    f->isdirty = CX_NEW(unsigned char, n + 1);
    if (!f->pinv || !f->ri || !f->rx || !f->w || !f->parent || !f->mark || !f->dirty || !f->isdirty) {
        cx_ldlmod_destroy(&f);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    int st;
    if (like) {
        /* the same pattern: the other factor's analysis (ordering and
         * supernodes) instead of a new one */
        f->sym = cholmod_copy_factor(like->sym, &f->c);
        st = cx_cholmod_check(&f->c, f->sym, "copy of an analysis (ldlmod)", d);
    } else {
        cholmod_sparse s = cx_cholmod_view(A, 1);
        f->sym = cholmod_analyze(&s, &f->c);
        st = cx_cholmod_check(&f->c, f->sym, "analyse (ldlmod)", d);
    }
    if (st == CX_OK && super && ldlmod_permuted(f, A) != CX_OK)
        st = cx_diag_set(d, CX_ENOMEM, "out of memory");
    if (st == CX_OK)
        st = ldlmod_factor(f, A, mask, d);
    if (st != CX_OK) {
        cx_ldlmod_destroy(&f);
        return st;
    }
    for (int k = 0; k < n; k++)
        f->pinv[cx_cholmod_column(f->L, k)] = k;
    if (!f->sp)   /* else ldlmod_permuted built it */
        ldlmod_etree(f, A);
    *F = f;
    return CX_OK;
}

int cx_ldlmod_create(cx_ldlmod **F, const cx_csc *A, cx_counters *cnt, cx_diag *d)
{
    return ldlmod_new(F, A, NULL, 0, NULL, cnt, d);
}

int cx_ldlmod_create_super(cx_ldlmod **F, const cx_csc *A, cx_counters *cnt, cx_diag *d)
{
    return ldlmod_new(F, A, NULL, 1, NULL, cnt, d);
}

int cx_ldlmod_create_masked(cx_ldlmod **F, const cx_csc *A, const unsigned char *keep, double shift,
                            const cx_ldlmod *like, cx_counters *cnt, cx_diag *d)
{
    if (like && like->n != A->ncol)
        return cx_diag_set(d, CX_EINVAL, "ldlmod: the matrix is not of the other factor's order");
    ldlmod_mask m = {keep, shift};
    return ldlmod_new(F, A, keep ? &m : NULL, like ? like->super : 1, like, cnt, d);
}

/* Pivot k against amax. D(k,k) is the first entry of column k of the
 * simplicial LDL' factor; the same relative bound as the Cholesky
 * factorisations' (fact.c). */
static int ldlmod_pivot(const cx_ldlmod *f, int k, double amax, cx_diag *d)
{
    double dk = ((const double *)f->L->x)[((const int *)f->L->p)[k]];
    if (!(dk > CX_PIVOT_RTOL * amax))   /* also catches NaN */
        return cx_diag_set(d, CX_ENUMERIC,
                           "LDL' factor: matrix singular to working precision (pivot %g at column %d)", dk,
                           cx_cholmod_column(f->L, k));
    return CX_OK;
}

int cx_ldlmod_check(cx_ldlmod *f, double amax, cx_diag *d)
{
    for (int k = 0; k < f->n; k++)
        CX_TRY(ldlmod_pivot(f, k, amax, d));
    return CX_OK;
}

double cx_ldlmod_min_pivot(const cx_ldlmod *f)
{
    const int *lp = f->L->p;
    const double *lx = f->L->x;
    double m = INFINITY;
    for (int k = 0; k < f->n; k++)
        m = fmin(m, lx[lp[k]]);
    return m;
}

int cx_ldlmod_refactor(cx_ldlmod *f, const cx_csc *A, cx_diag *d)
{
    CX_TRY(ldlmod_factor(f, A, NULL, d));
    double amax = 0;
    for (int j = 0; j < A->ncol; j++)
        amax = fmax(amax, fabs(cx_csc_get(A, j, j)));
    return cx_ldlmod_check(f, amax, d);
}

int cx_ldlmod_refactor_masked(cx_ldlmod *f, const cx_csc *A, const unsigned char *keep, double shift,
                              cx_diag *d)
{
    ldlmod_mask m = {keep, shift};
    CX_TRY(ldlmod_factor(f, A, keep ? &m : NULL, d));
    double amax = 0;   /* the masked matrix's largest diagonal entry */
    for (int j = 0; j < A->ncol; j++)
        amax = fmax(amax, fabs(keep ? ldlmod_masked(&m, j, j, cx_csc_get(A, j, j)) : cx_csc_get(A, j, j)));
    return cx_ldlmod_check(f, amax, d);
}

/* A row change at k alters the pivots on the path from k to the root of
 * the elimination tree of the factor modified, which lies on the path in
 * A's tree (a subset pattern's tree has each column's parent among its
 * ancestors in A's): recorded for cx_ldlmod_check_updated. A column
 * already recorded has its ancestors recorded too. */
static void ldlmod_touch(cx_ldlmod *f, int k)
{
    for (int j = f->pinv[k]; j != -1 && !f->isdirty[j]; j = f->parent[j]) {
        f->isdirty[j] = 1;
        f->dirty[f->ndirty++] = j;
    }
}

int cx_ldlmod_check_updated(cx_ldlmod *f, double amax, cx_diag *d)
{
    int st = CX_OK;
    for (int a = 0; a < f->ndirty; a++) {
        int k = f->dirty[a];
        f->isdirty[k] = 0;
        if (st == CX_OK)
            st = ldlmod_pivot(f, k, amax, d);
    }
    f->ndirty = 0;
    return st;
}

int cx_ldlmod_delete(cx_ldlmod *f, int k, cx_diag *d)
{
    cholmod_rowdel((size_t)f->pinv[k], NULL, f->L, &f->c);
    ldlmod_touch(f, k);
    CX_TRY(cx_cholmod_check(&f->c, f->L, "row delete", d));
    if (f->cnt)
        f->cnt->updates++;
    return CX_OK;
}

/* The pattern of row kk (L's order) of the factor of the current matrix,
 * or a superset: the etree paths from the rows i < kk of A's column k
 * that the current matrix keeps (keep NULL: all) up to kk. Into f->ri;
 * returns its length. */
static int ldlmod_row_reach(cx_ldlmod *f, int k, const cx_csc *A, const unsigned char *keep)
{
    int kk = f->pinv[k], nz = 0;
    if (++f->stamp == 0x7fffffff) {
        for (int j = 0; j < f->n; j++)
            f->mark[j] = 0;
        f->stamp = 1;
    }
    f->mark[kk] = f->stamp;
    for (int q = A->p[k]; q < A->p[k + 1]; q++) {
        int r = A->i[q];
        if (keep && !keep[r])
            continue;
        for (int i = f->pinv[r]; i != -1 && i < kk && f->mark[i] != f->stamp; i = f->parent[i]) {
            f->mark[i] = f->stamp;
            f->ri[nz++] = i;
        }
    }
    return nz;
}

int cx_ldlmod_delete_row(cx_ldlmod *f, int k, const cx_csc *A, const unsigned char *keep, cx_diag *d)
{
    int nz = ldlmod_row_reach(f, k, A, keep), p[2] = {0, nz};
    cholmod_sparse R;
    memset(&R, 0, sizeof R);
    R.nrow = (size_t)f->n, R.ncol = 1, R.nzmax = nz > 0 ? (size_t)nz : 1;
    R.p = p, R.i = f->ri, R.x = NULL;
    R.stype = 0, R.itype = CHOLMOD_INT, R.xtype = CHOLMOD_PATTERN, R.dtype = CHOLMOD_DOUBLE;
    R.sorted = 0, R.packed = 1;
    cholmod_rowdel((size_t)f->pinv[k], &R, f->L, &f->c);
    ldlmod_touch(f, k);
    CX_TRY(cx_cholmod_check(&f->c, f->L, "row delete", d));
    if (f->cnt)
        f->cnt->updates++;
    return CX_OK;
}

double cx_ldlmod_row_cost(cx_ldlmod *f, int k, const cx_csc *A, const unsigned char *keep)
{
    const int *lnz = f->L->nz;
    double cost = 0;
    int nz = ldlmod_row_reach(f, k, A, keep);
    for (int a = 0; a < nz; a++)
        cost += lnz[f->ri[a]];
    for (int j = f->pinv[k]; j != -1; j = f->parent[j])
        cost += lnz[j];
    return cost;
}

double cx_ldlmod_factor_nnz(const cx_ldlmod *f)
{
    return f->lnz_full;
}

int cx_ldlmod_add(cx_ldlmod *f, int k, const cx_csc *A, const unsigned char *keep, double shift,
                  cx_diag *d)
{
    int nz = 0, p[2];
    for (int q = A->p[k]; q < A->p[k + 1]; q++) {
        int i = A->i[q];
        if (i != k && !keep[i])
            continue;
        f->ri[nz] = f->pinv[i];
        f->rx[nz++] = A->x[q] + (i == k ? shift : 0);
    }
    /* CHOLMOD wants sorted rows in R: insertion sort (a column is short) */
    for (int a = 1; a < nz; a++) {
        int ri = f->ri[a];
        double rx = f->rx[a];
        int b = a;
        for (; b > 0 && f->ri[b - 1] > ri; b--)
            f->ri[b] = f->ri[b - 1], f->rx[b] = f->rx[b - 1];
        f->ri[b] = ri, f->rx[b] = rx;
    }
    p[0] = 0, p[1] = nz;
    cholmod_sparse R;
    memset(&R, 0, sizeof R);
    R.nrow = (size_t)f->n, R.ncol = 1, R.nzmax = nz > 0 ? (size_t)nz : 1;
    R.p = p, R.i = f->ri, R.x = f->rx;
    R.stype = 0, R.itype = CHOLMOD_INT, R.xtype = CHOLMOD_REAL, R.dtype = CHOLMOD_DOUBLE;
    R.sorted = 1, R.packed = 1;
    cholmod_rowadd((size_t)f->pinv[k], &R, f->L, &f->c);
    ldlmod_touch(f, k);
    CX_TRY(cx_cholmod_check(&f->c, f->L, "row add", d));
    if (f->L->minor < f->L->n)
        return cx_diag_set(d, CX_ENUMERIC, "row add: the matrix is no longer positive definite");
    if (f->cnt)
        f->cnt->updates++;
    return CX_OK;
}

int cx_ldlmod_solve(cx_ldlmod *f, const double *b, double *x, cx_diag *d)
{
    /* solve2 with the workspace kept: no allocation per solve */
    cholmod_dense B = cx_cholmod_vec((double *)b, f->n);
    int ok = cholmod_solve2(CHOLMOD_A, f->L, &B, NULL, &f->X, NULL, &f->Y, &f->E, &f->c);
    int st = cx_cholmod_check(&f->c, f->L, "solve (ldlmod)", d);
    if (st == CX_OK && (!ok || !f->X))
        st = cx_diag_set(d, CX_EEXTERNAL, "solve (ldlmod) failed");
    if (st == CX_OK)
        memcpy(x, f->X->x, sizeof(double) * (size_t)f->n);
    if (f->cnt)
        f->cnt->solves++;
    return st;
}
