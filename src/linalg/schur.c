/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Static condensation of a symmetric matrix onto a subset c of its dofs
 * from one partial sparse Cholesky factorisation (doc/design.md §5). With
 * the c dofs ordered last,
 *     P A P' = [A11 A12; A21 A22] = [L11 0; L21 I] [L11' L21'; 0 S]
 * and S = A22 - L21 L21' = A_cc - A_ci A_ii^-1 A_ic: the interior
 * supernodes are factorised, the contact columns only receive their
 * updates (schur_numeric.c). S needs A_ii positive definite only: A may be
 * singular in directions that the c dofs hold (a body held only by
 * contact). With the identity in L's trailing block the solves with L
 * condense and expand:
 *     L y = P f             gives  y2 = f_c - A_ci A_ii^-1 f_i
 *     L' x = [y1; u_c]      gives  x_c = u_c, x_i = A_ii^-1 (f_i - A_ic u_c). */
#include "linalg/linalg_impl.h"

#include <math.h>
#include <string.h>
#include <time.h>

struct cx_schur {
    int n, nc;
    int *c;             /* nc dofs, in the caller's order */
    int *tpos;          /* nc: position of c[k] in the trailing block */
    cx_counters *cnt;   /* borrowed */
    cholmod_common cc;
    cholmod_factor *L;  /* supernodal [L11 0; L21 I] of P A P' */
    cholmod_dense *X1, *X2, *Y, *E;   /* solve workspace, reused */
    double *S;          /* nc x nc, full, caller's order */
    double *fcopy;      /* n: the last f given to a forward solve ... */
    double *fy;         /* n: ... and L^-1 P f, reused while f is the same */
    int fy_valid;
    cx_schur_ordering ord;   /* what the ordering chose and why */
    cx_schur_order force_order;   /* CX_ORDER_AUTO: the fewer predicted flops */
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
    cx_free(s->S);
    cx_free(s->fcopy);
    cx_free(s->fy);
    cx_free(s);
    *Sp = NULL;
}

/* cmember[j] = 1 marks the c dofs, checked distinct and in range. */
static int schur_members(int n, const int *c, int nc, int *cmember, cx_diag *d)
{
    for (int k = 0; k < nc; k++) {
        int j = c[k];
        if (j < 0 || j >= n)
            return cx_diag_set(d, CX_EINVAL, "schur: dof %d out of range [0, %d)", j, n);
        if (cmember[j])
            return cx_diag_set(d, CX_EINVAL, "schur: dof %d given twice", j);
        cmember[j] = 1;
    }
    return CX_OK;
}

/* Symbolic analysis of A with perm kept as given (not postordered: the
 * c dofs must stay last); lnz and fl from CHOLMOD's column counts. */
static int schur_analyse(cx_schur *s, cholmod_sparse *view, int *perm, cholmod_factor **L, double *lnz,
                         double *fl, cx_diag *d)
{
    cholmod_common *cc = &s->cc;
    cc->nmethods = 1;
    cc->method[0].ordering = CHOLMOD_GIVEN;
    cc->postorder = 0;
    *L = cholmod_analyze_p(view, perm, NULL, 0, cc);
    int st = cx_cholmod_check(cc, *L, "schur: analysis", d);
    if (st == CX_OK && !*L)
        st = cx_diag_set(d, CX_EEXTERNAL, "schur: analysis failed");
    if (st != CX_OK) {
        cholmod_free_factor(L, cc);
        return st;
    }
    *lnz = cc->lnz;
    *fl = cc->fl;
    return CX_OK;
}

/* CAMD with the c dofs constrained last into perm, and its lnz and fl:
 * CAMD counts the factor of the ordering it makes (the same figures as
 * CHOLMOD's column counts on hertz 256, block3d 16 and prism 7, where that
 * analysis cost as much again as the ordering; estimates only where CAMD
 * sets dense rows aside), so it is predicted without an analysis; its
 * supernodal analysis runs only if it wins, and its counts then replace
 * CAMD's. */
static int schur_camd(cx_schur *s, cholmod_sparse *view, int *cmember, int *perm, cx_diag *d)
{
    cx_schur_ordering *o = &s->ord;
    int ok = cholmod_camd(view, NULL, 0, cmember, perm, &s->cc);
    CX_TRY(cx_cholmod_check(&s->cc, NULL, "schur: constrained ordering", d));
    if (!ok)
        return cx_diag_set(d, CX_EEXTERNAL, "schur: constrained ordering failed");
    o->lnz[CX_ORDER_CAMD] = s->cc.lnz;
    o->flops[CX_ORDER_CAMD] = s->cc.fl;
    return CX_OK;
}

/* The process's CPU clock, for the phase times of cx_schur_ordering. */
static double schur_cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Do interior dofs a and b have the same column pattern in M? */
static int schur_same_column(const cx_csc *M, int a, int b)
{
    int la = M->p[a + 1] - M->p[a], lb = M->p[b + 1] - M->p[b];
    return la == lb && memcmp(M->i + M->p[a], M->i + M->p[b], sizeof(int) * (size_t)la) == 0;
}

/* The interior dofs per vertex of the graph schur_metis compresses (3 in
 * 3D elasticity, 2 in 2D, 1 for a scalar problem). */
static double schur_dofs_per_vertex(const cx_csc *M, const int *cmember)
{
    int ni = 0, ng = 0;
    for (int j = 0; j < M->ncol; j++) {
        if (cmember[j])
            continue;
        if (ni == 0 || j == 0 || cmember[j - 1] || !schur_same_column(M, j - 1, j))
            ng++;
        ni++;
    }
    return ng > 0 ? (double)ni / ng : 0;
}

/* The graph of M over the dofs that skip does not mark (skip NULL: all),
 * compressed: consecutive kept dofs whose columns of M have the same
 * pattern (the 2 or 3 dofs of a node in elasticity) become one vertex, so
 * the ordering and CHOLMOD's pre- and post-processing around it see a
 * graph d times smaller in vertices and d^2 in edges. It is ordered by
 * nested dissection (METIS, nd = 1) or minimum degree (AMD, nd = 0), and
 * perm receives the kept dofs in that order, each vertex's dofs together. */
static int schur_node_order(cx_schur *s, const cx_csc *M, const int *skip, int nd, int *perm, cx_diag *d)
{
    int n = s->n, st = CX_ENOMEM;
    size_t cap = cx_csc_nnz(M) ? cx_csc_nnz(M) : 1;
    int *old = CX_NEW(int, n + 1), *grp = CX_NEW(int, n + 1), *gfirst = CX_NEW(int, n + 1);
    int *gperm = CX_NEW(int, n + 1);
    cx_csc G = {0};
    G.p = CX_NEW(int, n + 1);
    G.i = CX_NEW(int, cap);
    if (!old || !grp || !gfirst || !gperm || !G.p || !G.i)
        goto done;
    /* the kept dofs in order, grouped: grp[dof] = its vertex */
    int ng = 0, nk = 0;
    for (int j = 0; j < n; j++) {
        if (skip && skip[j])
            continue;
        if (nk == 0 || old[nk - 1] != j - 1 || !schur_same_column(M, j - 1, j))
            gfirst[ng++] = nk;
        grp[j] = ng - 1;
        old[nk++] = j;
    }
    gfirst[ng] = nk;
    /* the upper triangle of the vertex graph, from each vertex's first
     * dof; rows come sorted by dof, so their vertices are nondecreasing
     * and a repeat is always the previous entry */
    int nz = 0;
    for (int g = 0; g < ng; g++) {
        int j = old[gfirst[g]], last = -1;
        G.p[g] = nz;
        for (int q = M->p[j]; q < M->p[j + 1]; q++) {
            int i = M->i[q];
            if ((skip && skip[i]) || grp[i] > g || grp[i] == last)
                continue;
            G.i[nz++] = last = grp[i];
        }
    }
    G.p[ng] = nz;
    G.nrow = G.ncol = ng;
    cholmod_sparse view = cx_cholmod_view(&G, 1);
    view.xtype = CHOLMOD_PATTERN;
    view.x = NULL;
    st = CX_OK;
    if (ng > 0) {
        const char *what = nd ? "schur: nested dissection" : "schur: minimum degree ordering";
        int ok = nd ? cholmod_metis(&view, NULL, 0, 1, gperm, &s->cc) : cholmod_amd(&view, NULL, 0, gperm, &s->cc);
        st = cx_cholmod_check(&s->cc, NULL, what, d);
        if (st == CX_OK && !ok)
            st = cx_diag_set(d, CX_EEXTERNAL, "%s failed", what);
    }
    if (st == CX_OK) {
        int t = 0;
        for (int k = 0; k < ng; k++)
            for (int q = gfirst[gperm[k]]; q < gfirst[gperm[k] + 1]; q++)
                perm[t++] = old[q];
    }
done:
    if (st == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "schur: out of memory");
    cx_free(old);
    cx_free(grp);
    cx_free(gfirst);
    cx_free(gperm);
    cx_free(G.p);
    cx_free(G.i);
    return st;
}

/* perm = nested dissection (METIS) of the node graph of M_ii
 * (schur_node_order), then the c dofs in the caller's order (the
 * trailing block is dense whatever its order, and in the caller's order S
 * needs no permutation); the separators found on the node graph are what
 * the dof graph's are anyway. */
static int schur_metis(cx_schur *s, const cx_csc *M, const int *cmember, const int *c, int *perm,
                       cx_diag *d)
{
    CX_TRY(schur_node_order(s, M, cmember, 1, perm, d));
    memcpy(perm + (s->n - s->nc), c, sizeof(int) * (size_t)s->nc);
    return CX_OK;
}

/* perm = AMD on the whole of A (the ordering the baseline factorises
 * with), then the c dofs moved last in the caller's order, the others
 * keeping AMD's order. Where c is a scattered subset of the contact face
 * (the normal dofs only, one of a node's two in 2D) this fills less than
 * CAMD, which orders the interior around a constraint it knows from the
 * start (hertz 256, 257 normal dofs: 3.39 against 3.90 Gflop); where c is
 * the whole face CAMD wins (513 dofs: 4.61 against 3.99). AMD runs on the
 * node graph (schur_node_order), c dofs included: on hertz 256 that cuts
 * its time about four times. */
static int schur_amd_last(cx_schur *s, const cx_csc *M, const int *cmember, int *perm, cx_diag *d)
{
    CX_TRY(schur_node_order(s, M, NULL, 0, perm, d));
    int t = 0;
    for (int k = 0; k < s->n; k++)
        if (!cmember[perm[k]])
            perm[t++] = perm[k];
    memcpy(perm + t, s->c, sizeof(int) * (size_t)s->nc);
    return CX_OK;
}

/* The METIS candidate (schur_metis), analysed in full into *Lm: its
 * fill, flops and times into the ordering record. */
static int schur_try_metis(cx_schur *s, const cx_csc *A, cholmod_sparse *view, const int *cmember,
                           cholmod_factor **Lm, cx_diag *d)
{
    cx_schur_ordering *o = &s->ord;
    double t0 = cx_clock_now(), c0 = schur_cpu_now(), c1;
    int *pm = CX_NEW(int, s->n > 0 ? s->n : 1), st;
    if (!pm)
        return cx_diag_set(d, CX_ENOMEM, "schur: out of memory");
    if ((st = schur_metis(s, A, cmember, s->c, pm, d)) == CX_OK) {
        c1 = schur_cpu_now();
        o->cpu_ordering += c1 - c0;
        st = schur_analyse(s, view, pm, Lm, &o->lnz[CX_ORDER_METIS], &o->flops[CX_ORDER_METIS], d);
        o->cpu_symbolic += schur_cpu_now() - c1;
    }
    o->seconds[CX_ORDER_METIS] = cx_clock_now() - t0;
    cx_free(pm);
    if (st == CX_OK)
        o->tried = 1;
    return st;
}

/* The AMD-then-c-last candidate beside CAMD's prediction: analysed in
 * full at once (a prediction first would cost as much again: the
 * supernodal pattern is half the analysis), and kept in s->L only when it
 * needs fewer flops (else s->L stays as it was: NULL, or CAMD's). */
static int schur_try_amd(cx_schur *s, const cx_csc *A, cholmod_sparse *view, const int *cmember, cx_diag *d)
{
    cx_schur_ordering *o = &s->ord;
    double t0 = cx_clock_now(), c0 = schur_cpu_now(), c1;
    int *pa = CX_NEW(int, s->n > 0 ? s->n : 1);
    if (!pa)
        return cx_diag_set(d, CX_ENOMEM, "schur: out of memory");
    int st = schur_amd_last(s, A, cmember, pa, d);
    c1 = schur_cpu_now();
    o->cpu_ordering += c1 - c0;
    cholmod_factor *La = NULL;
    if (st == CX_OK)
        st = schur_analyse(s, view, pa, &La, &o->lnz[CX_ORDER_AMD], &o->flops[CX_ORDER_AMD], d);
    if (st == CX_OK && (s->force_order == CX_ORDER_AMD || o->flops[CX_ORDER_AMD] < o->flops[o->chosen])) {
        cholmod_free_factor(&s->L, &s->cc);   /* CAMD's, if analysed */
        s->L = La;
        o->chosen = CX_ORDER_AMD;
    } else {
        cholmod_free_factor(&La, &s->cc);
    }
    o->cpu_symbolic += schur_cpu_now() - c1;
    o->seconds[CX_ORDER_AMD] = cx_clock_now() - t0;
    o->tried_amd = st == CX_OK;
    cx_free(pa);
    return st;
}

/* The cost of a METIS run on the interior graph, in factorisation flops:
 * measured on this machine (2 cores), METIS takes about 3 us per vertex
 * (hertz 256: 0.43 s for 131k dofs; block3d 12: 0.06 s for 22k) while the
 * supernodal factorisation runs at about 20 Gflop/s, so a vertex costs
 * some 6e4 flops. Nested dissection is tried only when that cost is below
 * CAMD's predicted flops, and chosen only when it wins with its cost
 * counted: 2D problems of moderate size (whose CAMD fill is already near
 * nested dissection's) stop before running METIS; 3D ones go on. */
#define CX_SCHUR_METIS_FLOPS_PER_DOF 6e4

static double schur_metis_cost(int ni) { return CX_SCHUR_METIS_FLOPS_PER_DOF * (double)ni; }

/* Elasticity in 3D (3 dofs per node), where nested dissection has won by
 * 2.6-3x in flops on every scene measured (README, "The direct path in
 * 3D"): METIS is analysed first, in full, and CAMD only predicted from its
 * own counts (schur_camd); the choice is the same rule as schur_order's (whenever
 * that would try METIS at all), and CAMD's supernodal analysis runs only
 * if CAMD wins. */
#define CX_SCHUR_3D_DOFS_PER_VERTEX 2.5

static int schur_order_3d(cx_schur *s, const cx_csc *A, cholmod_sparse *view, int *cmember, int *perm,
                          cx_diag *d)
{
    int n = s->n, nc = s->nc, st;
    cx_schur_ordering *o = &s->ord;
    cholmod_factor *Lm = NULL;
    CX_TRY(schur_try_metis(s, A, view, cmember, &Lm, d));
    double t0 = cx_clock_now(), c0 = schur_cpu_now(), c1;
    st = schur_camd(s, view, cmember, perm, d);
    c1 = schur_cpu_now();
    o->cpu_ordering += c1 - c0;
    if (st == CX_OK && !(o->flops[CX_ORDER_METIS] + schur_metis_cost(n - nc) < o->flops[CX_ORDER_CAMD])) {
        cholmod_free_factor(&Lm, &s->cc);   /* the analysis's counts replace CAMD's (the same without dense rows) */
        st = schur_analyse(s, view, perm, &Lm, &o->lnz[CX_ORDER_CAMD], &o->flops[CX_ORDER_CAMD], d);
        o->chosen = CX_ORDER_CAMD;
    } else {
        o->chosen = CX_ORDER_METIS;
    }
    o->cpu_symbolic += schur_cpu_now() - c1;
    o->seconds[CX_ORDER_CAMD] = cx_clock_now() - t0;
    if (st) {
        cholmod_free_factor(&Lm, &s->cc);
        return st;
    }
    s->L = Lm;
    const int *P = s->L->Perm;
    for (int t = n - nc; t < n; t++)
        if (!cmember[P[t]])
            return cx_diag_set(d, CX_EEXTERNAL, "schur: constrained ordering not kept");
    return CX_OK;
}

/* Constrained ordering (c last) and symbolic analysis with that ordering
 * kept as is. Three orderings compete: CAMD on the whole matrix with c
 * constrained last, AMD on the whole with c then moved last
 * (schur_amd_last), and nested dissection on the interior with c
 * appended; the one whose predicted factorisation flops, plus the
 * ordering's own cost, are fewer is kept. Their analyses alone are
 * compared, before any numeric work. */
static int schur_order(cx_schur *s, const cx_csc *A, int *cmember, int *perm, cx_diag *d)
{
    int n = s->n, nc = s->nc;
    cholmod_common *cc = &s->cc;
    cx_schur_ordering *o = &s->ord;
    cholmod_sparse view = cx_cholmod_view(A, 1);
    cx_progress_step("ordering", n);
    if (s->force_order == CX_ORDER_AUTO && schur_dofs_per_vertex(A, cmember) >= CX_SCHUR_3D_DOFS_PER_VERTEX)
        return schur_order_3d(s, A, &view, cmember, perm, d);
    double t0 = cx_clock_now(), c0 = schur_cpu_now();
    CX_TRY(schur_camd(s, &view, cmember, perm, d));
    double c1 = schur_cpu_now();
    o->cpu_ordering += c1 - c0;
    /* CAMD's analysis at once unless AMD's may win */
    int amd = (s->force_order == CX_ORDER_AUTO || s->force_order == CX_ORDER_AMD);
    if (!amd)
        CX_TRY(schur_analyse(s, &view, perm, &s->L, &o->lnz[CX_ORDER_CAMD], &o->flops[CX_ORDER_CAMD], d));
    o->cpu_symbolic += schur_cpu_now() - c1;
    o->seconds[CX_ORDER_CAMD] = cx_clock_now() - t0;
    o->chosen = CX_ORDER_CAMD;
    if (amd)
        CX_TRY(schur_try_amd(s, A, &view, cmember, d));
    if (!s->L) {
        double c2 = schur_cpu_now();   /* the analysis's counts replace CAMD's (the same without dense rows) */
        CX_TRY(schur_analyse(s, &view, perm, &s->L, &o->lnz[CX_ORDER_CAMD], &o->flops[CX_ORDER_CAMD], d));
        o->cpu_symbolic += schur_cpu_now() - c2;
    }
    double cost = schur_metis_cost(n - nc);
    if (s->force_order != CX_ORDER_CAMD && s->force_order != CX_ORDER_AMD &&
        (s->force_order == CX_ORDER_METIS || cost < o->flops[o->chosen])) {
        cholmod_factor *Lm = NULL;
        CX_TRY(schur_try_metis(s, A, &view, cmember, &Lm, d));
        if (s->force_order == CX_ORDER_METIS || o->flops[CX_ORDER_METIS] + cost < o->flops[o->chosen]) {
            cholmod_free_factor(&s->L, cc);
            s->L = Lm;
            o->chosen = CX_ORDER_METIS;
        } else {
            cholmod_free_factor(&Lm, cc);
        }
    }
    const int *P = s->L->Perm;
    for (int t = n - nc; t < n; t++)
        if (!cmember[P[t]])
            return cx_diag_set(d, CX_EEXTERNAL, "schur: constrained ordering not kept");
    return CX_OK;
}

/* The strict upper triangle of the nc x nc matrix W from its lower one,
 * by tiles that stay in cache on both sides. */
static void schur_mirror(double *W, size_t nc)
{
    enum { TILE = 64 };
    for (size_t j0 = 0; j0 < nc; j0 += TILE)
        for (size_t i0 = j0; i0 < nc; i0 += TILE) {
            size_t j1 = j0 + TILE < nc ? j0 + TILE : nc, i1 = i0 + TILE < nc ? i0 + TILE : nc;
            for (size_t j = j0; j < j1; j++)
                for (size_t i = i0 > j + 1 ? i0 : j + 1; i < i1; i++)
                    W[j + i * nc] = W[i + j * nc];
        }
}

/* The numeric factorisation of the interior and S, rows and columns in
 * the caller's order. The trailing block arrives lower, in the trailing
 * order: in S itself when that is the caller's order (the METIS path),
 * else in a scratch array permuted into S. */
static int schur_numeric(cx_schur *s, const cx_csc *A, cx_diag *d)
{
    int nc = s->nc, ident = 1;
    size_t ld = (size_t)nc, nn = ld * ld;
    for (int k = 0; k < nc && ident; k++)
        ident = s->tpos[k] == k;
    double *W = ident ? s->S : CX_NEW(double, nn ? nn : 1);
    if (!W)
        return cx_diag_set(d, CX_ENOMEM, "schur: out of memory");
    cx_progress_step("factorising", s->n);
    double c0 = schur_cpu_now();
    int st = cx_schur_numeric(s->L, A, s->n - nc, W, &s->cc, d);
    double c1 = schur_cpu_now();
    s->ord.cpu_numeric += c1 - c0;
    if (s->cnt)
        s->cnt->factorizations++;
    if (st == CX_OK) {
        cx_progress_step("condensing", nc);
        schur_mirror(W, ld);
        if (!ident)
            for (size_t b = 0; b < ld; b++) {
                const double *wb = W + (size_t)s->tpos[b] * ld;
                double *sb = s->S + b * ld;
                for (size_t a = 0; a < ld; a++)
                    sb[a] = wb[s->tpos[a]];
            }
        s->ord.cpu_form += schur_cpu_now() - c1;
    }
    if (!ident)
        cx_free(W);
    return st;
}

int cx_schur_create(cx_schur **Sp, const cx_csc *A, const int *c, int nc, cx_counters *cnt, cx_diag *d)
{
    return cx_schur_create_ordered(Sp, A, c, nc, CX_ORDER_AUTO, cnt, d);
}

int cx_schur_create_ordered(cx_schur **Sp, const cx_csc *A, const int *c, int nc, cx_schur_order order,
                            cx_counters *cnt, cx_diag *d)
{
    int n = A->nrow, st = CX_ENOMEM;
    *Sp = NULL;
    if (A->ncol != n || nc < 0 || nc > n)
        return cx_diag_set(d, CX_EINVAL, "schur: %d dofs of a %d x %d matrix", nc, A->nrow, A->ncol);
    int *cmember = NULL, *perm = NULL;
    cx_schur *s = CX_NEW(cx_schur, 1);
    if (!s)
        return cx_diag_set(d, CX_ENOMEM, "schur: out of memory");
    cx_cholmod_start(&s->cc);
    s->n = n;
    s->nc = nc;
    s->cnt = cnt;
    s->force_order = order;
    s->c = CX_NEW(int, nc);
    s->tpos = CX_NEW(int, nc);
    s->S = CX_NEW(double, (size_t)nc * (size_t)nc);
    s->fcopy = CX_NEW(double, n);
    s->fy = CX_NEW(double, n);
    cmember = CX_NEW(int, n);
    perm = CX_NEW(int, n);
    if (!s->c || !s->tpos || !s->S || !s->fcopy || !s->fy || !cmember || !perm)
        goto fail;
    if (nc > 0)
        memcpy(s->c, c, sizeof(int) * (size_t)nc);

    if ((st = schur_members(n, c, nc, cmember, d)) || (st = schur_order(s, A, cmember, perm, d)))
        goto fail;
    /* cmember reused: dof -> -1 - its position in the trailing block */
    const int *P = s->L->Perm;
    for (int t = 0; t < nc; t++)
        cmember[P[n - nc + t]] = -1 - t;
    for (int k = 0; k < nc; k++)
        s->tpos[k] = -1 - cmember[c[k]];
    if ((st = schur_numeric(s, A, d)))
        goto fail;

    cx_free(cmember);
    cx_free(perm);
    *Sp = s;
    return CX_OK;

fail:
    if (st == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "schur: out of memory");
    cx_free(cmember);
    cx_free(perm);
    cx_schur_destroy(&s);
    return st;
}

int cx_schur_size(const cx_schur *s) { return s->nc; }
const double *cx_schur_matrix(const cx_schur *s) { return s->S; }
double cx_schur_factor_nnz(const cx_schur *s) { return (double)s->L->xsize; }
const cx_schur_ordering *cx_schur_ordering_of(const cx_schur *s) { return &s->ord; }

/* *X = (partial) solve of sys with B; CX_OK or the CHOLMOD failure. */
static int schur_solve(cx_schur *s, int sys, cholmod_dense *B, cholmod_dense **X)
{
    int ok = cholmod_solve2(sys, s->L, B, NULL, X, NULL, &s->Y, &s->E, &s->cc);
    int st = cx_cholmod_check(&s->cc, s->L, "schur: solve", NULL);
    if (st)
        return st;
    return ok && *X ? CX_OK : CX_EEXTERNAL;
}

/* X1 = L^-1 P f (the forward half of a solve). An iterative method
 * condenses and expands with the same load f at every iteration: the
 * forward half is then kept and copied, so that an expansion costs the
 * backward half only. */
static int schur_forward(cx_schur *s, const double *f)
{
    size_t bytes = sizeof(double) * (size_t)s->n;
    if (s->cnt)
        s->cnt->solves++;
    if (s->fy_valid && memcmp(f, s->fcopy, bytes) == 0) {
        memcpy(s->X1->x, s->fy, bytes);
        return CX_OK;
    }
    s->fy_valid = 0;
    cholmod_dense B = cx_cholmod_vec((double *)f, s->n);
    CX_TRY(schur_solve(s, CHOLMOD_P, &B, &s->X2));
    CX_TRY(schur_solve(s, CHOLMOD_L, s->X2, &s->X1));
    memcpy(s->fcopy, f, bytes);
    memcpy(s->fy, s->X1->x, bytes);
    s->fy_valid = 1;
    return CX_OK;
}

int cx_schur_condense(cx_schur *s, const double *f, double *fc)
{
    CX_TRY(schur_forward(s, f));
    const double *y2 = (const double *)s->X1->x + (s->n - s->nc);
    for (int k = 0; k < s->nc; k++)
        fc[k] = y2[s->tpos[k]];
    return CX_OK;
}

int cx_schur_expand(cx_schur *s, const double *f, const double *uc, double *u)
{
    CX_TRY(schur_forward(s, f));
    int nc = s->nc;
    double *x2 = (double *)s->X1->x + (s->n - nc);
    for (int k = 0; k < nc; k++)
        x2[s->tpos[k]] = uc[k];
    CX_TRY(schur_solve(s, CHOLMOD_Lt, s->X1, &s->X2));
    CX_TRY(schur_solve(s, CHOLMOD_Pt, s->X2, &s->X1));
    memcpy(u, s->X1->x, sizeof(double) * (size_t)s->n);
    for (int k = 0; k < nc; k++)   /* exactly, not up to rounding */
        u[s->c[k]] = uc[k];
    return CX_OK;
}
