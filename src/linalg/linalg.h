/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linalg/: sparse and dense linear algebra, the only layer that includes a
 * SuiteSparse header. Triplet and CSC matrices (int indices, double values),
 * a factorisation object over CHOLMOD (symmetric positive definite) and
 * UMFPACK (unsymmetric) that keeps the symbolic analysis for reuse, the
 * static condensation of a symmetric matrix onto a subset of its dofs taken
 * from one Cholesky factorisation, dense kernels over LAPACK, and PCG.
 * Work counters (cx_counters) are incremented here, where the work is done.
 * Failures return a cx_status and leave one line in a cx_diag; a
 * non-positive pivot is CX_ENUMERIC naming the column, never a NaN. */
#ifndef CX_LINALG_H
#define CX_LINALG_H

#include "base/base.h"

#include <stddef.h>
#include <stdio.h>

/* ---- counters ------------------------------------------------------- */

typedef struct cx_counters {
    long factorizations;   /* sparse numeric factorisations (CHOLMOD, UMFPACK) */
    long solves;           /* solves with a factor (forward + backward = 1) */
    long matvecs;          /* products with the stiffness matrix K */
    long dual_products;    /* products with a dual operator B K^-1 B' */
    long updates;          /* factor rows added or deleted (cx_ldlmod) */
    long dense_factorizations;   /* dense (LAPACK) factorisations of size > 0, counted
                                    apart: a method on the condensed contact system
                                    factorises a small dense matrix per step */
} cx_counters;

/* ---- progress of long steps ----------------------------------------- */

/* A program that shows where a long run is (a progress line on a
 * terminal) installs a hook in the thread that runs it; the layers that do
 * the long steps (assembly in scene/, orderings, factorisations and
 * condensation here) say when one starts. Nothing is printed below the
 * program: the hook draws. step is called in the working thread, with the
 * step's name ("assembling", "ordering", "factorising", "condensing") and
 * its size in dofs. */
typedef struct cx_progress {
    void (*step)(void *ctx, const char *what, double size);
    void *ctx;
} cx_progress;
/* Install p (NULL: none) for the calling thread; returns the previous hook. */
const cx_progress *cx_progress_set(const cx_progress *p);
/* Report a step to the calling thread's hook, if any. */
void cx_progress_step(const char *what, double size);

/* ---- triplet / CSC --------------------------------------------------- */

typedef struct cx_triplet {
    int nrow, ncol;
    size_t nnz, cap;
    int *i, *j;
    double *x;
} cx_triplet;

/* Empty nrow x ncol triplet with room for cap entries (grows as needed). */
int cx_triplet_init(cx_triplet *t, int nrow, int ncol, size_t cap);
/* Append (i, j, x), 0 <= i < nrow, 0 <= j < ncol (asserted); duplicates are
 * summed on conversion. CX_ENOMEM. */
int cx_triplet_add(cx_triplet *t, int i, int j, double x);
void cx_triplet_clear(cx_triplet *t);

/* Compressed sparse column: column j holds rows i[p[j] .. p[j+1]-1],
 * sorted ascending, no duplicates. Symmetric matrices are stored in full
 * (both triangles). */
typedef struct cx_csc {
    int nrow, ncol;
    int *p;        /* ncol + 1 */
    int *i;        /* p[ncol] */
    double *x;     /* p[ncol] */
} cx_csc;

/* A from T (duplicates summed, explicit zeros kept: the pattern is what was
 * added). A must be empty or cleared; on failure A is left empty. */
int cx_csc_from_triplet(cx_csc *A, const cx_triplet *T);
int cx_csc_copy(cx_csc *dst, const cx_csc *src);
int cx_csc_transpose(cx_csc *At, const cx_csc *A);
void cx_csc_clear(cx_csc *A);             /* frees, leaves a 0x0 matrix */
static inline size_t cx_csc_nnz(const cx_csc *A) { return A->p ? (size_t)A->p[A->ncol] : 0; }

/* y = alpha A x + beta y  (beta = 0 ignores the old y, even if NaN). */
void cx_csc_gemv(const cx_csc *A, double alpha, const double *x, double beta, double *y);
/* y = alpha A' x + beta y */
void cx_csc_gemv_t(const cx_csc *A, double alpha, const double *x, double beta, double *y);
/* C = A B (C must be empty; sorted columns, no explicit zeros dropped).
 * CX_EINVAL if the sizes do not fit, CX_ENOMEM (C left empty). */
int cx_csc_multiply(cx_csc *C, const cx_csc *A, const cx_csc *B);
/* C = T' K T (K square, T with K's rows; C empty on entry): one pass per
 * column, K T never stored, the output allocated once. Sorted columns,
 * explicit zeros kept. CX_EINVAL if the sizes do not fit, CX_ENOMEM. */
int cx_csc_congruence(cx_csc *C, const cx_csc *K, const cx_csc *T);
/* A(i, j), 0 if not stored (binary search). */
double cx_csc_get(const cx_csc *A, int i, int j);
/* The place of (i, j) in A->i / A->x, -1 if not stored (binary search). */
int cx_csc_find(const cx_csc *A, int i, int j);
/* Largest |A(i,j) - A(j,i)| over the stored entries. */
double cx_csc_asymmetry(const cx_csc *A);

/* ---- K + B'WB on a fixed pattern ------------------------------------- */

/* K + sum_r w_r b_r' b_r over the rows b_r of B (a penalty or an augmented
 * Lagrangian on the constraints B u), held on the pattern of K + B'B with
 * the place of every term, so that it can be refilled for other weights
 * (w_r = 0 leaves a row out, its entries stay as explicit zeros) and
 * refactorised without a new symbolic analysis. */
typedef struct cx_csc_aug {
    cx_csc A;        /* n x n: the pattern, and the values of the last fill */
    int *kpos;       /* nnz(K): the place in A.x of each entry of K */
    size_t nprod;    /* entries of the row products */
    int *prow;       /* nprod: the row r of each */
    int *ppos;       /* nprod: its place in A.x */
    double *pval;    /* nprod: b_ra b_rb */
} cx_csc_aug;

/* The pattern for K (n x n) and the rows of nb <= 4 blocks B[b] (each
 * with n columns), numbered block after block. Values are left at 0 until
 * cx_csc_aug_fill. CX_EINVAL for sizes that do not fit, CX_ENOMEM (S left
 * empty either way). */
int cx_csc_aug_build(cx_csc_aug *S, const cx_csc *K, const cx_csc *const *B, int nb);
/* A = K + sum_r w[r] b_r' b_r (w: one weight per row of the blocks). */
void cx_csc_aug_fill(cx_csc_aug *S, const cx_csc *K, const double *w);
void cx_csc_aug_clear(cx_csc_aug *S);

/* ---- sparse factorisation ------------------------------------------- */

/* CHOLMOD's own OpenMP loops serial (on != 0) in every thread that starts
 * a factorisation from then on; BLAS keeps its threads. For programs: the
 * library alone leaves the OpenMP runtime as the environment set it. */
void cx_linalg_cholmod_serial(int on);

typedef enum cx_fact_kind {
    CX_FACT_CHOLESKY,   /* CHOLMOD, A symmetric positive definite (full storage given) */
    CX_FACT_LU          /* UMFPACK, A square */
} cx_fact_kind;

typedef struct cx_fact cx_fact;   /* opaque */

/* A new factorisation object; cnt (may be NULL) receives the counts and is
 * borrowed: it must outlive the object. */
int cx_fact_create(cx_fact **F, cx_fact_kind kind, cx_counters *cnt, cx_diag *d);
void cx_fact_destroy(cx_fact **F);

/* Symbolic analysis of the pattern of A (fill-reducing ordering), kept for
 * every later cx_fact_factorize with the same pattern. */
int cx_fact_analyze(cx_fact *F, const cx_csc *A, cx_diag *d);
/* Numeric factorisation of A (same pattern as analysed, else CX_EINVAL).
 * A non-positive pivot (Cholesky), a singular matrix (LU), or a pivot below
 * 1e-14 of the largest (singular to working precision) is CX_ENUMERIC with
 * the column, in A's numbering, in the message; the object then refuses to
 * solve until a factorisation succeeds. */
int cx_fact_factorize(cx_fact *F, const cx_csc *A, cx_diag *d);
/* x = A^-1 b (x and b may alias). Counts one solve. CX_EINVAL without a
 * successful factorisation. Allocates nothing. */
int cx_fact_solve(cx_fact *F, const double *b, double *x, cx_diag *d);
/* Number of non-zeros of the factor(s), 0 before factorize. */
double cx_fact_nnz(const cx_fact *F);

/* ---- a factor modified row by row (CHOLMOD Modify) ------------------- */

/* A simplicial LDL' factor of a symmetric positive definite A (full
 * storage) whose row and column k can be set to the identity's (delete)
 * and back to a matrix's (add), each a rank-2 change of the factor instead
 * of a new factorisation. Used by active-set methods that change one
 * unknown at a time. Counts one factorisation at create, one update per
 * add/delete, one solve per solve. */
typedef struct cx_ldlmod cx_ldlmod;

int cx_ldlmod_create(cx_ldlmod **F, const cx_csc *A, cx_counters *cnt, cx_diag *d);
/* The same, factorised supernodal and converted (faster on large meshes). */
int cx_ldlmod_create_super(cx_ldlmod **F, const cx_csc *A, cx_counters *cnt, cx_diag *d);
/* The factor of A masked: rows and columns k with keep[k] = 0 the
 * identity's, shift added to the other diagonal entries (keep NULL: A
 * itself), factorised supernodal and converted (or, with like, from
 * like's analysis); the masked matrix is never formed (its values are
 * gathered into the factorisation's input). A is the matrix analysed and
 * the one the later adds and deletes read. */
int cx_ldlmod_create_masked(cx_ldlmod **F, const cx_csc *A, const unsigned char *keep, double shift,
                            const cx_ldlmod *like, cx_counters *cnt, cx_diag *d);
void cx_ldlmod_destroy(cx_ldlmod **F);
/* A new numeric factorisation of A (same pattern), the analysis kept. */
int cx_ldlmod_refactor(cx_ldlmod *F, const cx_csc *A, cx_diag *d);
/* The same for A masked (cx_ldlmod_create_masked). */
int cx_ldlmod_refactor_masked(cx_ldlmod *F, const cx_csc *A, const unsigned char *keep, double shift,
                              cx_diag *d);
/* CX_ENUMERIC if a pivot of D is below CX_PIVOT_RTOL amax (singular). */
int cx_ldlmod_check(cx_ldlmod *F, double amax, cx_diag *d);
/* The same over the pivots that row changes (add, delete) altered since
 * the factorisation or the last call: the factor passed a check before
 * them, the other pivots are as they were. */
int cx_ldlmod_check_updated(cx_ldlmod *F, double amax, cx_diag *d);
/* The smallest entry of D. */
double cx_ldlmod_min_pivot(const cx_ldlmod *F);
/* Row and column k become the identity's. */
int cx_ldlmod_delete(cx_ldlmod *F, int k, cx_diag *d);
/* Row and column k (now the identity's) become A's column k on the rows
 * i with keep[i] (and k itself, plus shift on the diagonal); the other rows
 * must be the identity's. CX_ENUMERIC if no longer positive definite. */
int cx_ldlmod_add(cx_ldlmod *F, int k, const cx_csc *A, const unsigned char *keep, double shift,
                  cx_diag *d);
/* The same as cx_ldlmod_delete, with the pattern of row k of L given to
 * CHOLMOD from the elimination tree (the paths from the entries of A's
 * column k on the rows keep says the current matrix has, keep NULL: all),
 * instead of CHOLMOD's search of every column before k: the cost of a
 * delete is then that of its update, not O(nnz(L)). A: the matrix every
 * masked matrix's pattern is within (the one analysed). */
int cx_ldlmod_delete_row(cx_ldlmod *F, int k, const cx_csc *A, const unsigned char *keep, cx_diag *d);
/* The entries of L a delete or add of row k would touch (estimated): the
 * columns of row k's pattern (keep, A as above) and those on the path from
 * k to the root of the elimination tree, at the factor's current counts. */
double cx_ldlmod_row_cost(cx_ldlmod *F, int k, const cx_csc *A, const unsigned char *keep);
/* Entries of L as a factorisation fills them (the analysed pattern, the
 * unit diagonal and D counted once per column): the size of a new
 * factor, against which updates are weighed. The factor kept holds only
 * its non-zeros, often far fewer (the masked rows' are dropped). */
double cx_ldlmod_factor_nnz(const cx_ldlmod *F);
/* x = A^-1 b for the current matrix. */
int cx_ldlmod_solve(cx_ldlmod *F, const double *b, double *x, cx_diag *d);

/* ---- static condensation onto a subset of dofs ---------------------- */

/* For A symmetric positive semi-definite of order n, split into dofs c
 * (given) and the rest i, with A_ii positive definite:
 *     S = A_cc - A_ci A_ii^-1 A_ic          (the Schur complement)
 * obtained from ONE sparse Cholesky factorisation of A ordered with the
 * c dofs last (constrained ordering) that stops before them: the updates
 * gathered into the trailing block are S (schur_numeric.c). A may be
 * singular in directions that involve the c dofs (a floating body held
 * only by contact). */
typedef struct cx_schur cx_schur;

/* c: nc distinct dof indices (copied; CX_EINVAL if repeated or out of
 * range). cnt borrowed, may be NULL. Counts one factorisation. CX_ENUMERIC,
 * naming a column, if A_ii is not positive definite. */
int cx_schur_create(cx_schur **S, const cx_csc *A, const int *c, int nc,
                    cx_counters *cnt, cx_diag *d);
/* The fill-reducing ordering of the factor (c last in all): CAMD on the
 * whole matrix, nested dissection (METIS) on the i dofs, or AMD on the
 * whole matrix with the c dofs then moved last. AUTO analyses CAMD's and
 * (below 3 dofs per node) AMD's, then METIS's unless its own cost could
 * not be won back, and factorises the one with fewer predicted flops (the
 * METIS run counted); with 3 dofs per node (3D elasticity) METIS's first,
 * CAMD's predicted from its column counts only. */
typedef enum cx_schur_order {
    CX_ORDER_CAMD = 0,
    CX_ORDER_METIS = 1,
    CX_ORDER_AMD = 2,
    CX_ORDER_AUTO = 3
} cx_schur_order;
typedef struct cx_schur_ordering {
    cx_schur_order chosen;   /* CAMD, METIS or AMD */
    int tried;               /* METIS analysed (its entries below are set) */
    int tried_amd;           /* AMD-then-c-last analysed (likewise) */
    double lnz[3];           /* predicted factor non-zeros, by cx_schur_order */
    double flops[3];         /* predicted factorisation flops */
    double seconds[3];       /* ordering + symbolic analysis */
    /* where the set-up's CPU time went (seconds of the process's CPU
     * clock): the orderings, their symbolic analyses, the numeric
     * factorisation, and forming S from the factor's trailing block */
    double cpu_ordering, cpu_symbolic, cpu_numeric, cpu_form;
} cx_schur_ordering;
/* cx_schur_create with the ordering given (tests, bench comparisons). */
int cx_schur_create_ordered(cx_schur **S, const cx_csc *A, const int *c, int nc, cx_schur_order order,
                            cx_counters *cnt, cx_diag *d);
const cx_schur_ordering *cx_schur_ordering_of(const cx_schur *S);
void cx_schur_destroy(cx_schur **S);
int cx_schur_size(const cx_schur *S);                 /* nc */
/* S as a dense nc x nc column-major symmetric matrix, rows and columns in
 * the order of c as given to create. Borrowed, valid until destroy. */
const double *cx_schur_matrix(const cx_schur *S);
/* fc = f_c - A_ci A_ii^-1 f_i  (nc values in the order of c). One solve. */
int cx_schur_condense(cx_schur *S, const double *f, double *fc);
/* The full vector u with u_c = uc and u_i = A_ii^-1 (f_i - A_ic u_c).
 * One solve. */
int cx_schur_expand(cx_schur *S, const double *f, const double *uc, double *u);
/* Factor non-zeros (for reports). */
double cx_schur_factor_nnz(const cx_schur *S);
/* The same S the way paper 001 computes it (schur_solves.c): a Cholesky
 * factorisation of A_ii alone and one solve per dof of c. S: nc x nc,
 * column-major, in the order of c. For the bench's comparison; counts one
 * factorisation and nc solves. CX_ENUMERIC if A_ii is not positive
 * definite. */
int cx_schur_by_solves(const cx_csc *A, const int *c, int nc, double *S, cx_counters *cnt, cx_diag *d);

/* ---- dense kernels (column-major, LAPACK) --------------------------- */

/* Solve the symmetric (possibly indefinite) system A x = b in place
 * (b <- x) with Bunch-Kaufman (dsysv). A (n x n, lda = n) is overwritten.
 * ipiv: n ints; work: lwork doubles (lwork >= n; 64 n is better).
 * CX_ENUMERIC if A is singular or x not finite. Counts one factorisation
 * when cnt given. */
int cx_dense_sym_solve(int n, double *A, double *b, int *ipiv,
                       double *work, int lwork, cx_counters *cnt);
/* Cholesky A = L L' in place (lower); CX_ENUMERIC if not positive definite
 * (or NaN). */
int cx_dense_cholesky(int n, double *A, cx_counters *cnt);
/* Solve with the Cholesky factor from cx_dense_cholesky: b <- A^-1 b (nrhs columns). */
void cx_dense_cholesky_solve(int n, const double *L, double *b, int nrhs);
/* General LU solve (dgesv), b <- A^-1 b; A overwritten. CX_ENUMERIC if
 * singular or x not finite. */
int cx_dense_lu_solve(int n, double *A, double *b, int *ipiv, cx_counters *cnt);
/* y = alpha A x + beta y for dense m x n A (dgemv). */
void cx_dense_gemv(int m, int n, double alpha, const double *A, const double *x,
                   double beta, double *y);

/* ---- vectors --------------------------------------------------------- */

double cx_vec_dot(int n, const double *x, const double *y);
double cx_vec_norm2(int n, const double *x);
double cx_vec_norminf(int n, const double *x);
/* y = a x + y */
void cx_vec_axpy(int n, double a, const double *x, double *y);
/* 1 if every entry is finite */
int cx_vec_finite(int n, const double *x);

/* ---- preconditioned conjugate gradients ------------------------------ */

/* y = A x for an SPD operator */
typedef void (*cx_apply_fn)(void *ctx, const double *x, double *y);

/* Solve A x = b from the initial x with Jacobi preconditioner inv_diag (may
 * be NULL: none) until ||r|| <= rtol ||b|| (b = 0: x = 0). work: 4 n
 * doubles. Returns CX_OK, or CX_ENUMERIC on breakdown (p'Ap <= 0 or NaN)
 * or when maxit is reached (message says which); *iters receives the
 * iteration count. */
int cx_pcg(int n, cx_apply_fn apply, void *ctx, const double *inv_diag,
           const double *b, double *x, double rtol, int maxit, int *iters,
           double *work, cx_diag *d);
/* The same with a stop test (a session's cancel flag and time limit):
 * stop(stop_ctx) is asked every CX_PCG_CHECK_INTERVAL iterations; non-zero
 * ends the iteration with CX_ENUMERIC ("interrupted"), x the last iterate.
 * stop may be NULL. */
#define CX_PCG_CHECK_INTERVAL 16
typedef int (*cx_stop_fn)(void *stop_ctx);
int cx_pcg_stop(int n, cx_apply_fn apply, void *ctx, const double *inv_diag,
                const double *b, double *x, double rtol, int maxit, cx_stop_fn stop,
                void *stop_ctx, int *iters, double *work, cx_diag *d);


/* ---- MatrixMarket files (CHOLMOD's reader and writer; mm.c) --------- */

/* Into f (opened by the caller: files are written through out/), named
 * name in messages: a coordinate file of A, "symmetric" with A's lower
 * triangle (A in full storage) or "general"; values written so that they
 * read back exactly. CX_EIO with name. */
int cx_mm_write_csc(FILE *f, const char *name, const cx_csc *A, int symmetric, cx_diag *d);
/* An array file ("array real general") of the nrow x ncol column-major x. */
int cx_mm_write_dense(FILE *f, const char *name, const double *x, int nrow, int ncol, cx_diag *d);

/* What a MatrixMarket file holds: a coordinate file as A (full storage: a
 * symmetric file's off-diagonal entries mirrored, duplicates summed), an
 * array file as x (column-major, nrow x ncol). */
typedef struct cx_mm {
    int dense;          /* 1: an array file (x), 0: a coordinate file (A) */
    int symmetric;      /* the header said symmetric */
    int nrow, ncol;
    cx_csc A;
    double *x;
} cx_mm;

/* Read f (named name in messages) with CHOLMOD, then check what CHOLMOD
 * lets through: every value finite (CHOLMOD reads nan and inf), real
 * values only. One line "name: ..." naming the first bad entry's row and
 * column (1-based, as in the file); CX_EINVAL for a malformed file (with
 * CHOLMOD's reason), CX_ENOMEM. mm is cleared first. */
int cx_mm_read_file(FILE *f, const char *name, cx_mm *mm, cx_diag *d);
int cx_mm_read(const char *path, cx_mm *mm, cx_diag *d);
void cx_mm_clear(cx_mm *mm);

#endif
