/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The LCP form of paper 003 (§3, (3.7)-(3.8)) shared by psor, lssnn, pdas,
 * pdpc and graves: find v with
 *     A v + Sigma = b,  v_S >= 0,  Sigma_S <= 0,  Sigma_S' v_S = 0,  Sigma_E = 0,
 * where the constrained unknowns S are the slacks of the contact rows.
 *
 * From the problem of doc/design.md §2 (frictionless): each contact row r gets
 * a pivot dof p(r) that no other row touches (node-to-node and node-to-
 * plane rows always have one), and the change of variables u = u0 + T v
 * puts the slack v_p(r) = g_r - (N u)_r in that dof's slot and keeps the
 * other dofs; then A = T' K T (sparse, singular like K when bodies float),
 * b = T' (f - K u0), and the multiplier of row r is lN_r = -Sigma_p(r) =
 * (A v - b)_p(r). The reduced Schur-complement LCP ((3.17)-(3.18)) is the
 * static condensation of A onto S (dense, of order n_c); A_EE is definite
 * because closing every contact pins every body.
 *
 * Masked solves: the methods solve with principal submatrices of
 * A + eps I (+ a diagonal on S); the others are replaced by the identity, so
 * that the sparse pattern and its symbolic analysis never change. */
#ifndef CX_SOLVE_LCP_H
#define CX_SOLVE_LCP_H

#include "solve/solve.h"

typedef struct cx_lcp {
    int n;               /* order */
    int nc;              /* constrained unknowns */
    unsigned char *S;    /* n: 1 on the constrained ones */
    int dense;           /* 0: A sparse; 1: Ad dense column-major */
    cx_csc A;
    double *Ad;
    double *b;           /* n */
    double amax;         /* largest diagonal entry of A */
} cx_lcp;

typedef struct cx_lcp_map {
    cx_lcp full;         /* the LCP over all free dofs */
    cx_csc T;            /* u = u0 + T v */
    double *u0;
    int *piv;            /* m: slot of row r */
    int *sidx;           /* nc: the constrained slots, ascending (the reduced order) */
    cx_schur *schur;     /* condensation of A onto S (reduced LCP), lazily */
    cx_lcp red;
} cx_lcp_map;

/* The session's LCP (cached under "lcp003:full"); CX_EUNSUPPORTED with a
 * reason for friction or rows without a dof of their own. */
int cx_lcp_get(cx_session *s, cx_lcp_map **map, cx_diag *d);
/* The reduced (Schur-complement) LCP, cached under "lcp003:schur". */
int cx_lcp_get_reduced(cx_session *s, cx_lcp_map **map, cx_diag *d);

/* y = A v */
void cx_lcp_apply(const cx_lcp *L, const double *v, double *y);

/* Displacements and multipliers of the problem from v of the full LCP (or
 * of the reduced one: reduced = 1, expanded first; work n doubles). */
int cx_lcp_result(cx_lcp_map *map, int reduced, const double *v, double *work,
                  const cx_problem *p, double *u, double *lN);

/* Masked factorisation and solves with A + eps I + diag(dadd). */
typedef struct cx_lcp_solver {
    const cx_lcp *L;
    cx_fact *F;
    cx_csc M;            /* sparse: A's pattern (borrowed: M.p, M.i are A's), its own
                            values, rebuilt per factorisation */
    double *Md;          /* dense: n x n */
    cx_counters *cnt;
    /* updates (cx_lcp_solver_updates): a simplicial LDL' factor of the last
     * masked matrix, changed row by row when at most update_max unknowns
     * change their mask (same eps, no dadd), else refactorised */
    int update_max;      /* 0: always refactorise (cx_fact) */
    int model;           /* 1: update when the changed rows' cost is at most
                            CX_LCP_UPDATE_RATIO x nnz(L) (and update_max rows); 0: when at
                            most update_max rows change */
    cx_ldlmod *ldl;
    unsigned char *fkeep;   /* n: 1 where the factored matrix is A's (not masked) */
    double feps;            /* the eps it was factored with */
    int fvalid;             /* the factor is of (fkeep, feps) */
    int analysed;           /* F analysed (lazily: unused when every factorisation updates) */
    const struct cx_lcp_solver *like;   /* a solver on the same LCP whose analysis the
                                           first factor copies (NULL: its own) */
    /* no factor of its own (pre): the masked system is solved by CG
     * preconditioned with like's factor, when like's mask differs from this
     * one in at most CX_LCP_PCG_ROWS unknowns (a perturbation of rank 2k
     * and of eps: CG ends in a few steps), e.g. the projection's first set,
     * which is the regularised stage's last with eps = 0. When CG does not
     * reach roundoff the system is factorised after all. */
    int pre;
    double peps;            /* pre: the eps of the masked system */
    unsigned char *pmask;   /* pre: n, its mask */
    double *pwork;          /* pre: 5 n doubles */
    long pcg_iters;         /* CG steps taken (each one solve with like's factor) */
    int pcg_solves;         /* systems solved by CG */
} cx_lcp_solver;
#define CX_LCP_PCG_ROWS 16
/* The cost model's break-even (cx_lcp_solver.model): changing the factor
 * row by row touches about cx_ldlmod_row_cost entries of L per row, one
 * scalar multiply-add each along the etree paths, while a new factor is
 * a supernodal (BLAS 3) factorisation plus the conversion to the
 * simplicial LDL' the updates need. Measured on running bond (row updates
 * of a step against its refactorisation), a new factor costs about as
 * much as updates touching 25-38 x nnz(L) entries at 1/100 and 35 at
 * 1/225 (nnz(L): the analysed factor's, cx_ldlmod_factor_nnz): below
 * that the updates are cheaper. The ratio is of work, not of time,
 * so the choice is the same on every machine and every run. */
#define CX_LCP_UPDATE_RATIO 38.0
#define CX_LCP_PCG_MAXIT 40

int cx_lcp_solver_init(cx_lcp_solver *s, const cx_lcp *L, cx_counters *cnt, cx_diag *d);
void cx_lcp_solver_clear(cx_lcp_solver *s);
/* Sparse solvers: factorisations without dadd update the previous factor
 * (CHOLMOD row delete / row add) when at most update_max unknowns change
 * their mask, and refactorise otherwise (0: always, the default). */
int cx_lcp_solver_updates(cx_lcp_solver *s, int update_max, cx_diag *d);
/* zero: n flags (1: the unknown is held at 0; NULL none); dadd: n values
 * added to the diagonal (NULL none). CX_ENUMERIC if singular. */
int cx_lcp_factor(cx_lcp_solver *s, double eps, const unsigned char *zero, const double *dadd,
                  cx_diag *d);
/* Only the values of the sparse masked matrix s->M (no factorisation). */
void cx_lcp_factor_values(cx_lcp_solver *s, double eps, const unsigned char *zero, const double *dadd);
/* x = M^-1 rhs with x = 0 where zero (rhs there ignored); x, rhs may alias
 * only when equal. work: n doubles. */
int cx_lcp_solve(cx_lcp_solver *s, const unsigned char *zero, const double *rhs, double *x,
                 double *work, cx_diag *d);

/* ---- the primal-dual active set step (pdas, and the projection of §4) ---- */

/* One PDAS iteration (003 §4, block principal pivoting) on A + eps I.
 * On the first call (act[0] == 2) the set is {i in S : lam_i - c v_i > 0}
 * from the start (v, lam). Later calls flip the infeasible unknowns (active
 * with lam < 0, inactive with v < 0) as a block while their number falls
 * (or for CX_PDAS_TRIES more tries), else only the last one (Murty's rule,
 * Judice & Pires 1994), which makes the method finite on a P-matrix where
 * plain PDAS may cycle. Then one masked solve: v = 0 on the active set,
 * lam = (A v + eps v - b) there and 0 elsewhere. *same = 1 (nothing
 * solved) when no unknown is infeasible: (v, lam) solves the LCP. With
 * eps = 0 and a singular subsystem (the exact problem's u is not unique: a
 * body free to slide between open joints), g->eps_fallback is used instead
 * and counted in g->fallbacks.
 * act: n flags. work: 2 n doubles. */
#define CX_PDAS_TRIES 5
#ifndef CX_PDAS_ROUNDOFF
#define CX_PDAS_ROUNDOFF 1e-12
#endif
typedef struct cx_pdas_guard {
    double *Av;          /* n, or NULL: A v at the current v, kept between plain steps */
    int Av_valid;        /* Av is of the current v (0: recompute at the next step) */
    int best, tries;     /* fewest infeasibilities so far; block tries left */
    long single;         /* single pivots taken */
    double eps_fallback; /* eps used when the unregularised system is singular (0: fail) */
    long fallbacks;      /* times it was used */
    int ties_to_v;       /* first set: ties take v's side (the projection's start) */
} cx_pdas_guard;
/* The projection's fallback when its set leaves a motion free (relative). */
#define CX_PDAS_EPS_FALLBACK 1e-10

int cx_lcp_pdas_step(cx_lcp_solver *s, double eps, double c, double *v, double *lam,
                     unsigned char *act, cx_pdas_guard *g, int *same, double *work, cx_diag *d);

/* The damped PDAS step (pdas and the projection, search = 1): PDAS is the
 * semismooth Newton method for F(v) = 0, F_i = min(v_i, lam_i / c) on S and
 * lam_i / c elsewhere (lam = (A + eps I) v - b). Each step takes the set
 * {i in S : lam_i - c v_i > 0} at the current v, solves on it for the
 * Newton point vn (vn = 0 on the set) and moves v to v + alpha (vn - v),
 * alpha = 1, 1/2, ... until ||F||^2 falls (Armijo). A full step from an
 * iterate of plain PDAS is the plain PDAS step. The search is what keeps
 * the iterates from the swings of plain block pivoting on A + eps I, which
 * is no M-matrix: a set that leaves a brick without support moves it by
 * F / eps, and hundreds of joints flip at once (running bond). *same = 1
 * when the set repeats after a full step: v solves the LCP. The set and
 * the factor are kept while the set does not change (a shortened step only
 * moves along the same Newton direction). Indices within roundoff of the
 * switch keep their side. The first step is always full (the paper's first
 * PDAS step from the start); with memory > 0 a step is accepted when the
 * residual falls below the largest of the last `memory` ones (Grippo,
 * Lampariello & Lucidi's nonmonotone rule). */
#define CX_PDAS_HALVINGS 40
#define CX_PDAS_MEMORY 8
#define CX_PDAS_PROJ_MEMORY 4   /* the projection's (lcp.c) */
typedef struct cx_pdas_search {
    double *Av, *Ad, *vn;   /* n each: A v, A (vn - v), the Newton point */
    double *Avn;            /* n: A vn (kept with vn: a shortened step needs no product) */
    int Av_valid;           /* Av is of the current v (else recomputed) */
    double alpha;           /* the last step length; 0 before the first */
    double merit;           /* ||F(v)|| at the current v */
    long short_steps;       /* steps with alpha < 1 */
    int memory;             /* nonmonotone: compare with the largest of the last memory merits (0: monotone) */
    int steps;              /* steps taken */
    double hist[CX_PDAS_MEMORY];
} cx_pdas_search;

int cx_lcp_pdas_search_step(cx_lcp_solver *s, double eps, double c, double *v, double *lam,
                            unsigned char *act, cx_pdas_search *ls, cx_pdas_guard *g, int *same,
                            double *work, cx_diag *d);

/* Solve again with the set act on A + eps I (a new eps, same set). */
int cx_lcp_pdas_resolve(cx_lcp_solver *s, double eps, double *v, double *lam,
                        const unsigned char *act, double *work, cx_diag *d);

/* ---- Graves' principal pivoting simplex (graves.c) ---- */

/* The tableau y = M x + q of the LCP w = M z + q >= 0, z >= 0, w'z = 0
 * (dense, n x n, column-major M), with the lexicographic rows B (003 §4,
 * Graves 1967). */
typedef struct cx_graves {
    int n;
    double *T;          /* n x (1 + n + n): q | M | B, row-major per row */
    int *basic;         /* n: basic variable of row i: k (w_k) or n + k (z_k) */
    int *col;           /* n: nonbasic variable of column j, same coding */
    long pivots;        /* principal pivots done (a double pivot counts 2) */
    int state;          /* 0 running, 1 solved, -1 no solution */
} cx_graves;

int cx_graves_init(cx_graves *g, int n, const double *M, const double *q);
void cx_graves_clear(cx_graves *g);
/* Up to max_pivots principal pivots; g->state says how it ended. */
int cx_graves_run(cx_graves *g, long max_pivots, cx_diag *d);
/* z of the current tableau (the solution once g->state == 1). */
void cx_graves_z(const cx_graves *g, double *z);

/* ---- the two-stage driver shared by the regularised methods ---- */

typedef struct cx_lcp_run {
    cx_lcp_map *map;
    const cx_lcp *L;      /* map->full or map->red */
    int reduced;          /* the schur option */
    int project;          /* the projection stage (on by default) */
    int stage;            /* 0: the method; 1: the projection; 2: done */
    int proj_iters;       /* projection iterations (PDAS solves on A) */
    double eps;           /* regularisation eps * amax */
    double c;             /* PDAS / projection parameter tau * amax */
    cx_lcp_solver proj;   /* unregularised masked solves on the full LCP (projection) */
    cx_pdas_guard guard;  /* of the PDAS iterations (method and projection) */
    int search;           /* 1: damped PDAS (line search); 0: plain block pivoting */
    cx_pdas_search ls;    /* the damped steps' state (method and projection) */
    double *v, *lam, *work;
    unsigned char *act;
} cx_lcp_run;

/* Parameters of the projection stage every LCP method shares, and with eps
 * those of every regularised method (append to its table). */
#define CX_LCP_PARAMS_STAGE                                                                   \
    {"project", CX_PARAM_BOOL, 1, 0, 1, NULL,                                                  \
     "1: finish with the projection (PDAS on the unregularised A, 003 §4)", 0},               \
    {"tau", CX_PARAM_REAL, 1e-3, 1e-12, 1e12, NULL,                                           \
     "PDAS / projection parameter, relative to the largest diagonal entry of A", 0},          \
    {"search", CX_PARAM_BOOL, 1, 0, 1, NULL,                                                   \
     "1: PDAS steps (method and projection) with a line search on the natural residual "       \
     "(ours); 0: plain block pivoting with Judice-Pires single pivots (the paper's)", 0}

#define CX_LCP_PARAMS_COMMON                                                                  \
    {"eps", CX_PARAM_REAL, 1e-10, 0, 1e-2, NULL,                                              \
     "regularisation A + eps I, relative to the largest diagonal entry of A", 0},             \
    CX_LCP_PARAMS_STAGE

/* The reduced LCP's own eps. Regularising only the slacks, eps 1e-10
 * opened a degenerate running-bond joint by 2e-6 (1/10), and the paper's
 * n_c eps_machine (Table 7; 4e-13 - 6e-13 at 1/20 - 1/25) still did at 1/20
 * (lssnn) and 1/25: the projection then took 5-8 iterations. With 1e-14 it
 * takes one on every wall from 1/5 to 1/25; 1e-16 leaves the dense factor
 * singular. */
#define CX_LCP_PARAM_SCHUR                                                                    \
    {"schur", CX_PARAM_BOOL, 0, 0, 1, NULL,                                                   \
     "1: solve the reduced Schur-complement LCP on the contact unknowns (dense, 003 Table 7)", 0}
#define CX_LCP_PARAM_SCHUR_EPS                                                                \
    {"schur_eps", CX_PARAM_REAL, 1e-14, 0, 1e-2, NULL,                                        \
     "eps of the reduced LCP (schur = 1) in place of eps, relative to its largest diagonal entry", 0}

int cx_lcp_run_init(cx_lcp_run *r, cx_session *s, const cx_param_values *params, int reduced,
                    cx_diag *d);
void cx_lcp_run_clear(cx_lcp_run *r);
/* The method's own stage has converged on (r->v): start the projection, or
 * end the run when it is off. A reduced run's projection works on the full
 * LCP (r->L and r->v switch to it): the same equations without the
 * rounding of the dense condensation. */
int cx_lcp_run_stage_done(cx_lcp_run *r, cx_iterate *it, cx_diag *d);
/* One PDAS step of the run on A + eps I with this solver: damped or plain
 * as the run's search parameter says. */
int cx_lcp_run_pdas_step(cx_lcp_run *r, cx_lcp_solver *solver, double eps, int *same, cx_diag *d);
/* One projection iteration; ends the run when the set repeats. During the
 * projection (and at the end of the run) the method's own criterion is the
 * number of projection iterations (solves) done. */
int cx_lcp_run_project(cx_lcp_run *r, cx_session *s, cx_iterate *it, cx_diag *d);
/* it->u, it->lN from r->v. */
int cx_lcp_run_publish(cx_lcp_run *r, cx_session *s, cx_iterate *it);

#endif
