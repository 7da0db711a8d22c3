/* SPDX-License-Identifier: GPL-3.0-or-later */
/* solve/: the session (a problem, its cache of shared operators, the current
 * method and its history) and the generic stepping of doc/design.md §4.
 *
 * A method is a constant descriptor (cx_method) in the one registry table
 * (registry.c). cx_solver_step() calls the method's step and then, in one
 * place, computes the kkt error, the contact status and its changes, times
 * the step, detects NaN/Inf, stalls and limits, and sets the reason.
 * Switching method, tolerance, parameters or friction keeps the operator
 * cache: nothing is reassembled or refactorised.
 *
 * Ownership: a session owns its problem (given at create). Iterates are
 * owned by the session; pointers into them are valid until the next step,
 * reset or method change. Errors: CX_ENOMEM, CX_EINVAL, CX_EUNSUPPORTED
 * (method refused at init, with the reason in the diag), CX_ENUMERIC. */
#ifndef CX_SOLVE_H
#define CX_SOLVE_H

#include "solve/problem.h"

/* ---- outcomes -------------------------------------------------------- *
 *
 * The one table of outcome words (doc/design.md §3): every output (text, JSON,
 * explorer, bench tables, PNG metadata) names an outcome by its id and
 * describes it with cx_reason_format's sentence. A run is converged only
 * when its kkt error is at or below the tolerance: positive values are
 * converged, negative values ended the run without converging. A method
 * stopping on its own criterion above the tolerance has stopped
 * (CX_STOPPED_OWN), not converged. A method ends its run with its own
 * outcome by setting CX_DIVERGED_BREAKDOWN or CX_DIVERGED in it->reason,
 * with its message in the step's diag. */
#define CX_REASON_LIST(X)                                                         \
    X(CX_ITERATING, 0, "iterating", "iterating")                                  \
    X(CX_CONVERGED_KKT, 1, "converged", "converged")                              \
    X(CX_STOPPED_OWN, -6, "stopped_own", "stopped by its own criterion")          \
    X(CX_DIVERGED_STALL, -3, "stalled", "stalled")                                \
    X(CX_DIVERGED_MAXIT, -1, "max_iter", "did not converge")                      \
    X(CX_DIVERGED, -7, "diverged", "diverged")                                    \
    X(CX_DIVERGED_BREAKDOWN, -4, "breakdown", "breakdown")                        \
    X(CX_REFUSED, -8, "refused", "refused")                                       \
    X(CX_CANCELLED, -9, "cancelled", "cancelled")                                 \
    X(CX_DIVERGED_TIME, -5, "time_limit", "time limit")                           \
    X(CX_DIVERGED_NAN, -2, "nonfinite", "overflow or NaN")

typedef enum cx_reason {
#define CX_REASON_ENUM_(name, value, id, word) name = value,
    CX_REASON_LIST(CX_REASON_ENUM_)
#undef CX_REASON_ENUM_
} cx_reason;

/* The outcome's short word ("stopped by its own criterion"; "unknown"). */
const char *cx_reason_str(int reason);
/* The outcome's id for machine-readable output ("converged", "stopped_own",
 * "max_iter", ...; "unknown"). Literals: safe from any thread. */
const char *cx_reason_id(int reason);
/* The full sentence of an outcome into buf (len bytes, always terminated;
 * returns buf): the word with what it depends on, e.g. "converged in 5
 * iterations: kkt error 3.1e-12 <= tol 1e-10", "stopped by its own
 * criterion at kkt 2.8e+00 > tol 1e-10 after 4 iterations: not converged",
 * "breakdown at iteration 3: <msg>". iter, kkt, tol: the iterate's; msg:
 * the method's or the generic layer's message (NULL or "" if none); a
 * non-finite kkt is not printed. */
char *cx_reason_format(int reason, int iter, double kkt, double tol, const char *msg, char *buf,
                       size_t len);
/* Non-zero if a run ended where its stopping rules say: converged, or
 * stopped by the method's own criterion (the papers' tables count such
 * runs; they are still not converged unless the kkt error is small). */
static inline int cx_reason_criterion_met(int reason)
{
    return reason == CX_CONVERGED_KKT || reason == CX_STOPPED_OWN;
}

/* Per-point contact status. */
typedef enum cx_point_status {
    CX_PT_FREE = 0,    /* not in contact */
    CX_PT_CONTACT,     /* in contact, frictionless */
    CX_PT_STICK,       /* in contact, sticking */
    CX_PT_SLIP_POS,    /* slipping, lT along +t (2D), or 3D slip */
    CX_PT_SLIP_NEG     /* slipping along -t (2D) */
} cx_point_status;

/* ---- options ---------------------------------------------------------- */

typedef struct cx_options {
    double tol;          /* stop when kkt <= tol (default 1e-10) */
    int max_iter;        /* default 500 */
    int own_stop;        /* also stop on the method's own criterion (default 1) */
    int stall_window;    /* stalled if kkt has not fallen below 0.5 x its best
                            for this many iterations (default 50) */
    double time_limit;   /* seconds, 0 = none */
} cx_options;

void cx_options_default(cx_options *o);

/* ---- the iterate --------------------------------------------------------- */

typedef struct cx_iterate {
    int iter;            /* outer iterations done */
    int reason;          /* cx_reason */
    double kkt;          /* doc/design.md §3 error */
    cx_kkt kkt_parts;
    double own;          /* the method's own criterion (NaN if none) */
    int own_done;        /* set by the method when its own criterion is met */
    int progress;        /* set by a method whose own criterion made headway
                            the kkt error cannot show (a regularised first
                            stage at its O(eps) floor): restarts the stall clock */
    double *u;           /* n */
    int u_partial;       /* CX_PARTIAL_CONTACT: only u's contact dofs (p->cdofs)
                            are of this iterate, the rest is of an earlier one
                            (below); CX_PARTIAL_NORMAL: only its normal dofs
                            (cx_session_schur_normal) */
    double *lN;          /* m */
    double *lT;          /* nt */
    unsigned char *status;    /* m, cx_point_status */
    unsigned char *changed;   /* m, 1 if the status changed in the last step */
    int nfree, ncontact, nstick, nslip, nchanged;
    long inner;          /* inner iterations in the last step (method's own count) */
    long inner_total;
    cx_counters counters;/* work done by this run (since reset/set_method) */
    double step_time;    /* seconds of the last step */
    double time;         /* seconds of all steps of this run (init included) */
    double init_time;    /* seconds of the method's init (setup) */
} cx_iterate;

/* ---- methods ------------------------------------------------------------ */

/* What a method supports (cx_method.supports). */
#define CX_FRICTIONLESS 0x01u
#define CX_TRESCA       0x02u
#define CX_COULOMB      0x04u
#define CX_2D           0x08u
#define CX_3D           0x10u
#define CX_MULTIBODY    0x20u

typedef struct cx_session cx_session;

typedef struct cx_method {
    const char *id;          /* "ssn-tresca" */
    const char *name;        /* "Semismooth Newton / active set (Tresca)" */
    const char *source;      /* "000 §4.2" */
    const char *summary;     /* one line: what it does and how */
    unsigned supports;       /* CX_FRICTIONLESS | ... */
    size_t state_size;       /* bytes of private state, zeroed before init */
    const cx_param *params;  /* NULL-key terminated, may be NULL */
    /* Check the problem and allocate workspace; take shared operators from
     * the session's cache. Refuse with CX_EUNSUPPORTED and a reason. */
    int (*init)(void *state, cx_session *s, const cx_param_values *params, cx_diag *d);
    /* One outer iteration: update it->u, it->lN, it->lT (and it->own,
     * it->own_done, it->progress, it->inner). No printing, no kkt. A non-zero status or
     * CX_DIVERGED_BREAKDOWN in it->reason ends the run. */
    int (*step)(void *state, cx_session *s, cx_iterate *it, cx_diag *d);
    void (*destroy)(void *state);
} cx_method;

/* The registry (registry.c). */
int cx_method_count(void);
const cx_method *cx_method_at(int i);
const cx_method *cx_method_find(const char *id);    /* NULL if unknown */
/* CX_OK if m supports p under the friction law (law, dimension, bodies),
 * else CX_EUNSUPPORTED with the reason ("method 'x' does not support
 * Coulomb friction"). */
int cx_method_check(const cx_method *m, const cx_problem *p, cx_friction law, cx_diag *d);

/* ---- the session --------------------------------------------------------- */

/* Takes ownership of *p (set to NULL); frictionless (slip bound and F 0)
 * until a friction setter says otherwise. */
int cx_session_create(cx_session **s, cx_problem **p, cx_diag *d);
void cx_session_destroy(cx_session **s);

/* The system: not changed by anything after build. */
const cx_problem *cx_session_problem(const cx_session *s);

/* ---- the friction state ------------------------------------------------
 *
 * The session's law, scalars and per-point values (cx_friction_state,
 * problem.h; s and Fi always point to m values). Valid until the next
 * friction setter. The kkt error, the classification and the methods read
 * it here. */
const cx_friction_state *cx_session_friction(const cx_session *s);
/* Every setter checks its values (CX_EINVAL, nothing changed), keeps the
 * operator cache and re-inits the current method (a new run).
 * cx_session_set_friction: the whole state (law, both scalars; s, Fi per
 * point or NULL: from the scalars). If the current method refuses the new
 * law, its error is returned and the old state and method are kept. */
int cx_session_set_friction(cx_session *s, const cx_friction_state *fr, cx_diag *d);
/* Tresca with the traction bound slip_bound at every point (s_i =
 * slip_bound x the point's lumped weight); Coulomb with coefficient F at
 * every point; frictionless. The other scalar is kept. As set_friction. */
int cx_session_set_tresca(cx_session *s, double slip_bound, cx_diag *d);
int cx_session_set_coulomb(cx_session *s, double F, cx_diag *d);
int cx_session_set_frictionless(cx_session *s, cx_diag *d);
/* Counters of the operator cache (factorisations done for the session). */
const cx_counters *cx_session_cache_counters(const cx_session *s);

/* Operator cache (lazy, built once per session, shared by every method):
 * the static condensation of K onto the contact dofs p->cdofs, and of the
 * load f (*fc, nc values; fc may be NULL). Its work is counted in the cache
 * counters and, when built during a run, in the run's counters too. */
int cx_session_schur(cx_session *s, cx_schur **S, const double **fc, cx_diag *d);
/* The reduction onto the contact dofs if a run has built it, else NULL
 * (for reports: builds nothing). */
const cx_schur *cx_session_schur_built(const cx_session *s);
/* The same condensation onto the normal dofs only (the dofs the rows of N
 * touch: on flat obstacles a third of the contact dofs in 3D, half in 2D),
 * for frictionless runs, where the tangential contact dofs carry no force
 * and may be condensed away with the interior. Cached beside the full one,
 * so that a change of law refactorises nothing already factorised. It is
 * the full one itself (p->cdofs) when N touches every contact dof, or
 * when the full one is built and this one is not (nothing new is
 * factorised then).
 * *dofs: *nd ascending dof indices, S and *fc in their order (fc, dofs may
 * be NULL). S NULL: only which dofs, building nothing. */
int cx_session_schur_normal(cx_session *s, cx_schur **S, const double **fc, const int **dofs, int *nd,
                            cx_diag *d);
enum { CX_PARTIAL_CONTACT = 1, CX_PARTIAL_NORMAL = 2 };   /* cx_iterate.u_partial */
/* Any other shared operator (a factorisation of K + r M, the dual operator,
 * a regularised K, ...), built lazily once per session under a key that
 * names it and every value it depends on ("ubr:K+rM r=2.2e+02"). The first
 * call builds it with build(obj, problem, arg, counters, d), counting its
 * work in the cache counters and the current run's; later calls with the
 * same key return it without work. destroy frees it with the session.
 * A build that fails with CX_ENUMERIC (the matrix cannot be factorised) is
 * remembered: later calls return the same status and message, no work.
 * Keys are at most CX_CACHE_KEYLEN - 1 characters (longer: CX_EINVAL). */
#define CX_CACHE_KEYLEN 96
typedef int (*cx_cache_build_fn)(void **obj, const cx_problem *p, const void *arg,
                                 cx_counters *cnt, cx_diag *d);
typedef void (*cx_cache_destroy_fn)(void *obj);
int cx_session_cache_get(cx_session *s, const char *key, cx_cache_build_fn build,
                         const void *arg, cx_cache_destroy_fn destroy, void **obj, cx_diag *d);
/* Number of operators in the cache (the Schur complement included). */
int cx_session_cache_size(const cx_session *s);
/* The work counters methods pass to linalg (the current run's). */
cx_counters *cx_session_counters(cx_session *s);

/* Select method m with parameters (NULL: its defaults) and options (NULL:
 * keep). Destroys the previous method's state only; calls m->init. */
int cx_session_set_method(cx_session *s, const cx_method *m, const cx_param_values *params,
                          const cx_options *opt, cx_diag *d);
const cx_method *cx_session_method(const cx_session *s);
const cx_param_values *cx_session_params(const cx_session *s);
const cx_options *cx_session_options(const cx_session *s);
void cx_session_set_options(cx_session *s, const cx_options *opt);

/* Unselect the current method (its state is destroyed, the iterate
 * cleared; the operator cache stays), e.g. before changing to a friction
 * law it does not support. */
void cx_session_clear_method(cx_session *s);

/* Restart the current method from its initial guess (re-init). */
int cx_session_reset(cx_session *s, cx_diag *d);

/* One step of the current method plus the generic bookkeeping. Returns a
 * status (CX_OK unless something failed outright); the outcome is in
 * cx_session_iterate(s)->reason. A step after the run ended does nothing. */
int cx_solver_step(cx_session *s, cx_diag *d);

/* Observer called after every step; return non-zero to stop early. */
typedef int (*cx_observer)(void *ctx, const cx_session *s, const cx_iterate *it);

/* Step until the reason is non-zero (or the observer stops it). */
int cx_solver_solve(cx_session *s, cx_observer obs, void *ctx, cx_diag *d);

const cx_iterate *cx_session_iterate(const cx_session *s);
/* Partial iterates. A method that works on the system condensed onto the
 * contact dofs (the session's Schur complement) may update only u's
 * contact dofs in a step and set it->u_partial: expanding u costs a solve
 * with the whole factor, more than the rest of such a step. The kkt error
 * is then computed on the condensed system, where the equilibrium rows of
 * the other dofs are zero by construction; its displacement scale takes
 * the other dofs from the last expansion. The step that ends a run
 * expands u (the run's last iterate is always whole) and decides the
 * outcome on the whole iterate's kkt error. Anyone who reads u during a
 * run (the explorer draws it) calls this first: it expands u if partial
 * and recomputes the kkt error (and the outcome) on the whole iterate. */
int cx_session_complete_iterate(cx_session *s, cx_diag *d);
/* Why the run broke down (the method's message), or "" . */
const char *cx_session_reason_msg(const cx_session *s);
/* The full sentence of the current iterate's outcome (cx_reason_format
 * with its iterations, kkt error, tolerance and message) into buf. */
char *cx_session_outcome(const cx_session *s, char *buf, size_t len);

/* ---- cancelling and the time limit -------------------------------------
 *
 * cx_session_cancel sets the session's cancel flag (an atomic int): safe
 * from a signal handler or another thread. The run then ends as
 * CX_CANCELLED at the next check: after the current step, and inside long
 * steps every CX_CHECK_INTERVAL inner iterations (PSOR sweeps, CG steps,
 * pivots), where methods call cx_session_interrupted. The time limit
 * (cx_options.time_limit) is checked at the same places. The flag is
 * cleared when a new run starts (set_method, reset, friction change). A
 * nested session is interrupted when any session above it is. */
#define CX_CHECK_INTERVAL 16
void cx_session_cancel(cx_session *s);
/* Non-zero if the run must stop now: the cancel flag is set or the time
 * limit has passed. For methods, inside their long loops; cheap (an atomic
 * load, and a clock read only when a time limit is set). */
int cx_session_interrupted(cx_session *s);
/* The same as a linalg stop test (cx_stop_fn, e.g. for cx_pcg_stop):
 * session is the cx_session. */
int cx_session_stop(void *session);
/* The clock of the time limit (seconds; default cx_clock_now): a test
 * may inject its own to count checks instead of timing them. NULL
 * restores the default. */
typedef double (*cx_clock_fn)(void *ctx);
void cx_session_set_clock(cx_session *s, cx_clock_fn now, void *ctx);

/* ---- nested sessions (nested.c): a method that runs another method ----
 *
 * A wrapper such as cf-fp (002 CF-FP: Coulomb by successive Tresca
 * problems) runs any registered Tresca method as its inner method through
 * a nested session: cx_session_nested_create gives a child session whose
 * problem is the parent's own (the same cx_problem, not a copy; its own
 * friction state: Tresca with per-point slip bounds), which shares the
 * parent's operator cache (a factorisation built by the first inner run is
 * reused by every later one and by the parent) and counts all its work in
 * the parent's run counters (so the parent's 'factorizations', 'solves'
 * include the inner runs'). The child is driven by the ordinary calls:
 *
 *     cx_session_nested_create(&child, s, d);                   (in init)
 *     cx_session_set_method(child, inner, &inner_params, &opt, d);
 *     each outer step:
 *         cx_session_set_start(child, u, lN, lT, d);           (warm start)
 *         cx_session_set_slip_bounds(child, s_bounds, d);      (re-inits the run)
 *         cx_solver_solve(child, NULL, NULL, d);
 *         read cx_session_iterate(child): u, lN, lT, iter, reason
 *     cx_session_destroy(&child);                               (in destroy)
 *
 * The child's iterate counters are the work of its own run. Its last
 * iterate may be partial (u_partial, above): the method that runs it copies
 * u_partial with u, or calls cx_session_complete_iterate(child). The child
 * must be destroyed before the parent. */
int cx_session_nested_create(cx_session **child, cx_session *parent, cx_diag *d);
/* (session.c) Tresca friction with per-point slip bounds sb (m nodal forces >= 0; e.g.
 * s_i = F_i lN_i of a fixed-point step, or a bound times Hertz's pressure
 * times the lumped length). Keeps the operator cache; re-inits the current
 * method (a new run). If that method refuses Tresca, its error is returned
 * and the session keeps the new bounds with no method selected (unlike
 * cx_session_set_friction, which restores the old law). CX_EINVAL for a
 * negative or non-finite bound (nothing changed). Works on any session. */
int cx_session_set_slip_bounds(cx_session *s, const double *sb, cx_diag *d);
/* The starting iterate of every later run (set_method, reset, friction or
 * slip-bound changes): u (n), lN (m), lT (nt; may be NULL: zero). NULL u
 * clears it (runs start from zero). A method's init may read the iterate
 * as its start (ubr-c, ubr-tf do; others start from their own guess). */
int cx_session_set_start(cx_session *s, const double *u, const double *lN, const double *lT,
                         cx_diag *d);

/* The penalty r that ubr-c and ubr-tf choose for r = auto (ubr.c), for a
 * body of Young modulus E: c E / sqrt(h L) over the contact points the
 * obstacle can reach. In the units of the problem (force / length^d). */
double cx_ubr_auto_r(const cx_problem *p, double E);

/* The baseline of doc/design.md §5: analyse + factorise + solve K (with springs
 * diag(K) on the contact dofs when K alone is singular, as every contact
 * method effectively does), CHOLMOD's default ordering, timed. */
int cx_problem_baseline(const cx_problem *p, double *seconds, cx_diag *d);

#endif
