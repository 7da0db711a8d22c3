/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The discrete contact problem in the one convention of doc/design.md §2:
 *     K u - f + N' lN + T' lT = 0
 *     N u - g <= 0,  lN >= 0,  lN_i (N u - g)_i = 0
 *     |lT_i| <= s_i, |lT_i| < s_i => (T u)_i = 0, |lT_i| = s_i => (T u)_i = c lT_i
 * over the n free dofs (Dirichlet dofs eliminated) and m contact points.
 * s_i is the Tresca slip bound (a nodal force) or F_i lN_i for Coulomb.
 * The problem is the assembled system and the geometry it came from (mesh,
 * dof map, contact points, for output): it owns everything it points to and
 * is not changed after cx_problem_create (every later user holds it const).
 * The friction state (law, F_i, s_i) is not part of it: it belongs to the
 * session (cx_session_friction, solve.h), so that one system serves any law
 * and a nested session can share the system with its own bounds. */
#ifndef CX_PROBLEM_H
#define CX_PROBLEM_H

#include "base/base.h"
#include "linalg/linalg.h"
#include "mesh/mesh.h"
#include "fem/fem.h"
#include "contact/contact.h"

typedef enum cx_friction {
    CX_FRICTION_NONE,
    CX_FRICTION_TRESCA,
    CX_FRICTION_COULOMB
} cx_friction;

const char *cx_friction_name(cx_friction f);   /* "none", "tresca", "coulomb" */
int cx_friction_from_name(const char *name);    /* -1 if unknown */

/* The friction state: the law and its values, one field per meaning.
 * slip_bound and F are the scalars a scene or a command line gives; s and
 * Fi the per-point values the kkt error and the methods read. In a
 * session's state (cx_session_friction) s and Fi point to m values the
 * session owns; given to a setter, NULL means "from the scalar"
 * (s_i = slip_bound * weight_i, F_i = F). */
typedef struct cx_friction_state {
    cx_friction law;
    double slip_bound;  /* Tresca bound as a traction (force / area) */
    double F;           /* Coulomb coefficient */
    const double *s;    /* m: Tresca slip bound per point (nodal force), or NULL */
    const double *Fi;   /* m: Coulomb coefficient per point, or NULL */
} cx_friction_state;

/* CX_EINVAL unless the law is known and slip_bound, F (and s, Fi where
 * given, m values) are finite and non-negative. */
int cx_friction_check(const cx_friction_state *fr, int m, cx_diag *d);

typedef struct cx_problem {
    int dim;
    int n;              /* free dofs */
    int m;              /* contact points */
    int nt;             /* tangential rows: m (dim - 1) */
    cx_csc K;           /* n x n, symmetric, full storage */
    double *f;          /* n */
    cx_csc N;           /* m x n */
    cx_csc T;           /* nt x n */
    double *g;          /* m, initial gap (prescribed dofs folded in) */
    int nc;             /* dofs touched by N or T */
    int *cdofs;         /* nc ascending free-dof indices */

    double kscale;      /* max diagonal entry of K: the stiffness scale */
    double E;           /* the material's stiffness scale given with plain data
                           (cx_problem_from_data; 0: from mats) */

    /* geometry, for output */
    cx_mesh *mesh;
    cx_material *mats;  /* cx_mesh_nmats(mesh): per body, or per material id */
    cx_dofmap map;
    cx_contact_set contact;
    double f_applied[3];/* resultant of the applied loads (tractions + body forces) */
} cx_problem;

/* Build the problem from an assembled system: takes ownership of mesh,
 * mats (cx_malloc'ed array), map and cs (their contents move in and the
 * arguments are zeroed); fall (over all dofs) is only read, and so is Kall
 * when it is over all dofs; a Kall over the free dofs (cx_fem_assemble_free)
 * moves in (cx_fem_reduce_move). CX_ENOMEM, CX_EINVAL (e.g. a contact
 * point whose every dof is prescribed). */
int cx_problem_create(cx_problem **p, cx_mesh **mesh, cx_material **mats,
                      cx_dofmap *map, cx_contact_set *cs,
                      cx_csc *Kall, const double *fall, cx_diag *d);
void cx_problem_destroy(cx_problem **p);

/* ---- a problem from plain arrays (problem_arrays.c) ----------------------
 *
 * For a system assembled elsewhere (another FE code, a file): the same
 * problem, sessions, methods, stepping, results and kkt error as a scene's,
 * without a mesh (p->mesh is NULL: outputs that draw or write the mesh
 * refuse such a problem). Sign conventions are those at the top of this
 * header: N u - g <= 0 with g >= 0 the initial gap, lN >= 0 pushes the
 * body away from the obstacle (its force on the body is -N'lN), T's rows
 * of point i are (dim-1) i .. (dim-1) i + dim - 2.
 *
 * A sparse matrix given as plain arrays, 0-based indices, not changed and
 * not kept (everything is copied): */
typedef enum cx_sparse_form {
    CX_SPARSE_CSC = 0,      /* p (ncol + 1 column starts), i, x; nnz = p[ncol] */
    CX_SPARSE_TRIPLET = 1   /* i, j, x (nnz each); duplicates are summed */
} cx_sparse_form;

typedef struct cx_sparse_data {
    cx_sparse_form form;
    int nrow, ncol;
    size_t nnz;             /* triplet: entries (CSC: ignored, p[ncol]) */
    const int *p;           /* CSC: column starts (ncol + 1) */
    const int *i;           /* row of each entry */
    const int *j;           /* triplet: column of each entry */
    const double *x;        /* value of each entry */
} cx_sparse_data;

typedef struct cx_problem_data {
    int dim;                /* 2 or 3 */
    int n;                  /* unknowns (free dofs) */
    int m;                  /* contact points */
    cx_sparse_data K;       /* n x n, symmetric positive semi-definite */
    int K_lower;            /* 1: only the lower triangle (row >= column) is
                               given, the upper is its mirror (an upper
                               entry is an error); 0: both triangles, equal
                               to 1e-12 of the largest |K_ij| */
    const double *f;        /* n: the load */
    cx_sparse_data N;       /* m x n: normal rows, (N u)_i closes gap i */
    cx_sparse_data T;       /* m (dim - 1) x n: tangential rows */
    const double *g;        /* m: initial gaps, >= 0 */
    /* optional (NULL or 0: the default) */
    const double *weight;   /* m: the contact boundary's measure at each point
                               (length in 2D, area in 3D; default 1: a
                               scalar Tresca bound is then a nodal force);
                               ubr-c, ubr-tf and ssn-c weigh their penalty
                               by it */
    const double *x;        /* dim m: the points' positions (default 0;
                               ubr's r = auto measures the contact zone) */
    double E;               /* the material's stiffness scale (Young's
                               modulus; 0: K's largest diagonal entry), by
                               which penalty methods scale their r */
} cx_problem_data;

/* Check and copy data into a new problem. CX_EINVAL with one line naming
 * the first bad array and entry (sizes, an index out of range, a NaN or
 * Inf, an upper entry with K_lower, an asymmetric K, a negative gap or
 * weight, dim not 2 or 3), CX_ENOMEM. The friction law and its per-point
 * values go to the session (cx_session_set_friction with s or Fi). */
int cx_problem_from_data(cx_problem **p, const cx_problem_data *data, cx_diag *d);
/* The stiffness scale penalty methods scale their r by: the largest
 * Young's modulus of the bodies, else p->E, else p->kscale (else 1). */
double cx_problem_stiffness(const cx_problem *p);

/* doc/design.md §3: the solver-independent, dimensionless error, the largest of
 * the relative equilibrium residual and the natural-map residuals of the
 * contact and friction conditions. Zero exactly at a solution; +inf if an
 * input is not finite. work: at least n + m + nt doubles. Counts one
 * product with K in cnt (may be NULL). */
typedef struct cx_kkt {
    double total;         /* the max of the three */
    double equilibrium;
    double contact;
    double friction;
} cx_kkt;
double cx_kkt_error(const cx_problem *p, const cx_friction_state *fr, const double *u,
                    const double *lN, const double *lT, double *work, cx_counters *cnt,
                    cx_kkt *parts);
/* The same error with K u given (n values; NULL: computed from p->K), for
 * a caller that has the product without p->K: the PETSc backend, whose K
 * is distributed and whose driver may free the serial one. */
double cx_kkt_error_Ku(const cx_problem *p, const cx_friction_state *fr, const double *u,
                       const double *lN, const double *lT, const double *Ku, double *work,
                       cx_counters *cnt, cx_kkt *parts);

/* The same error for an iterate whose u is exact on the contact dofs and
 * whose other dofs solve their equilibrium rows (u_i = K_ii^-1 (f_i -
 * K_ic u_c)), from the Schur complement S (nc x nc, column-major, in
 * p->cdofs order) and the condensed load fc: the equilibrium rows of the
 * other dofs are zero, those of the contact dofs are S u_c - fc + (N'lN +
 * T'lT)_c. u's other dofs enter only the displacement scale. */
double cx_kkt_error_condensed(const cx_problem *p, const cx_friction_state *fr, const double *S,
                              const double *fc, const double *u, const double *lN,
                              const double *lT, double *work, cx_kkt *parts);

/* The scales used by cx_kkt_error, exposed for methods that need a
 * consistent rho: multiplier scale, displacement scale, rho = mult / disp.
 * lT counts unless the law is CX_FRICTION_NONE. */
void cx_kkt_scales(const cx_problem *p, cx_friction law, const double *u, const double *lN,
                   const double *lT, double *mult, double *disp);

/* Slip bound of point i at the current normal multiplier. */
static inline double cx_friction_slip_bound(const cx_friction_state *fr, int i, double lNi)
{
    if (fr->law == CX_FRICTION_TRESCA)
        return fr->s[i];
    if (fr->law == CX_FRICTION_COULOMB)
        return fr->Fi[i] * (lNi > 0 ? lNi : 0);
    return 0;
}

#endif
