/* Static condensation of a symmetric matrix onto a subset of its dofs from
 * one sparse Cholesky factorisation (DESIGN.md §5): order the subset last,
 * and the trailing block L22 of the factor of A + D gives
 *     L22 L22' = A_cc + D - A_ci A_ii^-1 A_ic = S + D.
 * D = diag(A_cc) keeps the factorisation possible when A is singular in
 * directions that the c dofs hold (a body held only by contact); it touches
 * neither L11 nor L21, so the partial solves with L still condense and
 * expand with the true A. */
#include "linalg/linalg_impl.h"

#include <math.h>
#include <string.h>

extern void dsyrk_(const char *uplo, const char *trans, const int *n, const int *k, const double *alpha,
                   const double *a, const int *lda, const double *beta, double *c, const int *ldc);
extern void dtrmv_(const char *uplo, const char *trans, const char *diag, const int *n, const double *a,
                   const int *lda, double *x, const int *incx);

struct cx_schur {
    int n, nc;
    int *c;             /* nc dofs, in the caller's order */
    int *tpos;          /* nc: position in the trailing block of c[k] */
    cx_counters *cnt;   /* borrowed */
    cholmod_common cc;
    cholmod_factor *L;
    cholmod_dense *X1, *X2, *Y, *E;   /* solve workspace */
    double *L22;        /* nc x nc, lower, trailing order */
    double *S;          /* nc x nc, full, caller's order */
    double *t;          /* nc: scratch in trailing order */
};

void cx_schur_destroy(cx_schur **Sp)
{
    if (!Sp || !*Sp)
        return;
    cx_schur *s = *Sp;
    cholmod_free_factor(&s->L, &s->cc);
    cholmod_free_dense(&s->X1, &s->cc);
    cholmod_free_dense(&s->X2, &s->cc);
    cholmod_free_dense(&s->Y, &s->cc);
    cholmod_free_dense(&s->E, &s->cc);
    cholmod_finish(&s->cc);
    cx_free(s->c);
    cx_free(s->tpos);
    cx_free(s->L22);
    cx_free(s->S);
    cx_free(s->t);
    cx_free(s);
    *Sp = NULL;
}

/* Copy the trailing nc x nc block of the supernodal factor into L22. */
static void schur_extract(cx_schur *s)
{
    const cholmod_factor *L = s->L;
    const int *super = L->super, *pi = L->pi, *px = L->px, *ls = L->s;
    const double *lx = L->x;
    int first = s->n - s->nc;
    for (size_t k = 0; k < L->nsuper; k++) {
        int c0 = super[k], c1 = super[k + 1], nrow = pi[k + 1] - pi[k];
        if (c1 <= first)
            continue;
        for (int j = c0 > first ? c0 : first; j < c1; j++)
            for (int r = j - c0; r < nrow; r++) {
                int row = ls[pi[k] + r];
                s->L22[(size_t)(row - first) + (size_t)(j - first) * (size_t)s->nc] =
                    lx[px[k] + r + (j - c0) * nrow];
            }
    }
}

int cx_schur_create(cx_schur **Sp, const cx_csc *A, const int *c, int nc, cx_counters *cnt, cx_diag *d)
{
    int n = A->nrow, st = CX_ENOMEM;
    cx_csc M = {0};
    int *cmember = NULL, *perm = NULL;
    double *dshift = NULL;
    cx_schur *s = CX_NEW(cx_schur, 1);
    if (!s)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    cx_cholmod_start(&s->cc);
    s->n = n;
    s->nc = nc;
    s->cnt = cnt;
    s->c = CX_NEW(int, nc);
    s->tpos = CX_NEW(int, nc);
    s->L22 = CX_NEW(double, (size_t)nc * (size_t)nc);
    s->S = CX_NEW(double, (size_t)nc * (size_t)nc);
    s->t = CX_NEW(double, nc);
    cmember = CX_NEW(int, n);
    perm = CX_NEW(int, n);
    dshift = CX_NEW(double, nc);
    if (!s->c || !s->tpos || !s->L22 || !s->S || !s->t || !cmember || !perm || !dshift)
        goto fail;
    memcpy(s->c, c, sizeof(int) * (size_t)nc);

    /* ---- M = A + D on the c dofs ---- */
    if ((st = cx_csc_copy(&M, A)))
        goto fail;
    double dmax = 0;
    for (int j = 0; j < n; j++)
        dmax = fmax(dmax, cx_csc_get(A, j, j));
    for (int k = 0; k < nc; k++) {
        int j = c[k], q;
        if (j < 0 || j >= n || cmember[j]) {
            st = cx_diag_set(d, CX_EINVAL, "schur: dof %d out of range or repeated", j);
            goto fail;
        }
        cmember[j] = 1;
        for (q = M.p[j]; q < M.p[j + 1] && M.i[q] != j; q++)
            ;
        if (q == M.p[j + 1]) {
            st = cx_diag_set(d, CX_EINVAL, "schur: no diagonal entry in column %d", j);
            goto fail;
        }
        dshift[k] = M.x[q] > 0 ? M.x[q] : (dmax > 0 ? dmax : 1);
        M.x[q] += dshift[k];
    }

    /* ---- constrained ordering (c last), analysis, factorisation ---- */
    cholmod_sparse view = cx_cholmod_view(&M, 1);
    cholmod_camd(&view, NULL, 0, cmember, perm, &s->cc);
    if ((st = cx_cholmod_check(&s->cc, NULL, "schur: constrained ordering", d)))
        goto fail;
    s->cc.nmethods = 1;
    s->cc.method[0].ordering = CHOLMOD_GIVEN;
    s->cc.postorder = 0;
    s->cc.supernodal = CHOLMOD_SUPERNODAL;
    s->L = cholmod_analyze_p(&view, perm, NULL, 0, &s->cc);
    if ((st = cx_cholmod_check(&s->cc, s->L, "schur: analyse", d)))
        goto fail;
    const int *P = s->L->Perm;
    for (int t = n - nc; t < n; t++)
        if (!cmember[P[t]]) {
            st = cx_diag_set(d, CX_EEXTERNAL, "schur: constrained ordering not kept by the analysis");
            goto fail;
        }
    cholmod_factorize(&view, s->L, &s->cc);
    if (cnt)
        cnt->factorizations++;
    if ((st = cx_cholmod_check(&s->cc, s->L, "schur: Cholesky factorisation", d)))
        goto fail;
    if ((st = cx_cholmod_check_pivots(s->L, &M, "schur: Cholesky factorisation", d)))
        goto fail;
    if (!s->L->is_super || !s->L->is_ll) {
        st = cx_diag_set(d, CX_EEXTERNAL, "schur: expected a supernodal LL' factor");
        goto fail;
    }

    /* ---- S = L22 L22' - D, in the caller's order ---- */
    for (int t = 0; t < nc; t++)
        cmember[P[n - nc + t]] = -1 - t;   /* reuse: dof -> trailing position */
    for (int k = 0; k < nc; k++)
        s->tpos[k] = -1 - cmember[c[k]];
    schur_extract(s);
    double *T = CX_NEW(double, (size_t)nc * (size_t)nc);
    if (!T) {
        st = CX_ENOMEM;
        goto fail;
    }
    double one = 1, zero = 0;
    if (nc > 0)
        dsyrk_("L", "N", &nc, &nc, &one, s->L22, &nc, &zero, T, &nc);
    for (int a = 0; a < nc; a++)
        for (int b = 0; b < nc; b++) {
            int ta = s->tpos[a], tb = s->tpos[b];
            double v = ta >= tb ? T[ta + (size_t)tb * nc] : T[tb + (size_t)ta * nc];
            s->S[a + (size_t)b * nc] = v - (a == b ? dshift[a] : 0);
        }
    cx_free(T);
    cx_csc_clear(&M);
    cx_free(cmember);
    cx_free(perm);
    cx_free(dshift);
    *Sp = s;
    return CX_OK;

fail:
    if (st == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "schur: out of memory");
    cx_csc_clear(&M);
    cx_free(cmember);
    cx_free(perm);
    cx_free(dshift);
    cx_schur_destroy(&s);
    return st;
}

int cx_schur_size(const cx_schur *s) { return s->nc; }
const double *cx_schur_matrix(const cx_schur *s) { return s->S; }
double cx_schur_factor_nnz(const cx_schur *s) { return (double)s->L->xsize; }

/* X1 = L^-1 P f (the forward half of a solve). */
static int schur_forward(cx_schur *s, const double *f)
{
    cholmod_dense B = cx_cholmod_vec((double *)f, s->n);
    if (!cholmod_solve2(CHOLMOD_P, s->L, &B, NULL, &s->X2, NULL, &s->Y, &s->E, &s->cc) ||
        !cholmod_solve2(CHOLMOD_L, s->L, s->X2, NULL, &s->X1, NULL, &s->Y, &s->E, &s->cc))
        return CX_EEXTERNAL;
    return CX_OK;
}

int cx_schur_condense(cx_schur *s, const double *f, double *fc)
{
    CX_TRY(schur_forward(s, f));
    if (s->cnt)
        s->cnt->solves++;
    int nc = s->nc, one = 1;
    if (nc == 0)
        return CX_OK;
    /* fc = L22 y2 */
    memcpy(s->t, (double *)s->X1->x + (s->n - nc), sizeof(double) * (size_t)nc);
    dtrmv_("L", "N", "N", &nc, s->L22, &nc, s->t, &one);
    for (int k = 0; k < nc; k++)
        fc[k] = s->t[s->tpos[k]];
    return CX_OK;
}

int cx_schur_expand(cx_schur *s, const double *f, const double *uc, double *u)
{
    CX_TRY(schur_forward(s, f));
    if (s->cnt)
        s->cnt->solves++;
    int nc = s->nc, one = 1;
    /* y2 = L22' uc, then x = P' L^-T y: x_c = uc, x_i = A_ii^-1 (f_i - A_ic uc) */
    for (int k = 0; k < nc; k++)
        s->t[s->tpos[k]] = uc[k];
    if (nc > 0)
        dtrmv_("L", "T", "N", &nc, s->L22, &nc, s->t, &one);
    memcpy((double *)s->X1->x + (s->n - nc), s->t, sizeof(double) * (size_t)nc);
    if (!cholmod_solve2(CHOLMOD_Lt, s->L, s->X1, NULL, &s->X2, NULL, &s->Y, &s->E, &s->cc) ||
        !cholmod_solve2(CHOLMOD_Pt, s->L, s->X2, NULL, &s->X1, NULL, &s->Y, &s->E, &s->cc))
        return CX_EEXTERNAL;
    memcpy(u, s->X1->x, sizeof(double) * (size_t)s->n);
    for (int k = 0; k < nc; k++)
        u[s->c[k]] = uc[k];
    return CX_OK;
}
