/* SPDX-License-Identifier: GPL-3.0-or-later */
/* out/result.h: the solution snapshot. A cx_result holds everything the
 * writers (VTU, JSON, text) and the renderer read about one solution —
 * the mesh and the contact geometry, the full displacement, the
 * multipliers and per-point status, and the run record (scene, level,
 * method and parameters, friction law, tolerance, outcome, kkt error,
 * counters, times) — as copies: it owns them, and stays valid after the
 * session that produced it steps again or is destroyed. Stresses are
 * computed when first asked for and kept.
 *
 * Fields are public to read; the program that made a result may fill the
 * times it measured itself (run.time.assemble, .total, .baseline). One
 * result is not to be used by two threads at once (the stress cache).
 * Errors: CX_ENOMEM, CX_EINVAL (a partial iterate), CX_ENUMERIC (stresses
 * of a degenerate element). */
#ifndef CX_OUT_RESULT_H
#define CX_OUT_RESULT_H

#include "base/base.h"
#include "solve/solve.h"
#include "scene/scene.h"

/* What the run was and how it ended. */
#define CX_RESULT_MAX_OBSTACLES 8   /* drawn rigid obstacles of one result */

typedef struct cx_run_record {
    char scene[CX_SCENE_NAMELEN];   /* scene id ("" = none) */
    char title[128];                /* scene title */
    char unit_length[16];           /* the scene's declared units ([units]; "" = none) */
    char unit_stress[16];
    int level;                      /* mesh level */
    char method[CX_SCENE_NAMELEN];  /* method id ("" = none) */
    int method_auto;                /* chosen by --method auto (set by the program) */
    cx_param_values params;         /* its parameters (params.n = 0: none) */
    char params_text[256];          /* the same as "key=value ..." */
    cx_friction friction;
    double F;                       /* Coulomb coefficient */
    double slip_bound;              /* Tresca bound (a traction) */
    double tol;
    int max_iter;                   /* the run's other stopping options (cx_options) */
    int own_stop;
    double time_limit;
    int iterations;
    int converged;                  /* kkt error at or below tol (reason > 0) */
    int reason;                     /* cx_reason: cx_reason_id / cx_reason_str */
    char message[CX_DIAG_LEN];      /* the method's reason for a breakdown, or "" */
    double kkt;
    cx_kkt kkt_parts;
    double own;                     /* the method's own criterion (NaN: none) */
    int nfree, ncontact, nstick, nslip;   /* contact points by status */
    cx_counters counters;
    long inner_total;
    struct {
        double assemble, setup, solve, total;   /* seconds */
        double baseline;            /* one factorisation + solve of K (if has_baseline) */
    } time;
    int has_baseline;
    int has_pressure_error;         /* the scene has Hertz's pressure */
    double pressure_error_abs, pressure_error_rel;
    double hertz_halfwidth;         /* b (0: none) */
    /* The computed contact half-width (result.c, cx_result_halfwidth):
     * p^2 = (lN / weight)^2 extrapolated linearly in x^2 through the last
     * two points in contact to p = 0 (exact for Hertz's p ~ sqrt(b^2 - x^2)),
     * kept between the last point in contact and its open neighbour. */
    double halfwidth;
} cx_run_record;

typedef struct cx_result {
    int dim;
    int n;                    /* free dofs of the problem */
    int m;                    /* contact points */
    int nt;                   /* tangential rows: m (dim - 1) */
    cx_mesh *mesh;            /* a copy */
    cx_material *mats;        /* mesh->nbodies */
    cx_contact_set contact;   /* the points' geometry (node, x, weight, normal,
                                 tangent, gap); no N, T rows */
    int has_obstacle;
    cx_obstacle obstacle;     /* the rigid obstacle (if has_obstacle): the first of */
    int nobstacles;           /* every rigid obstacle (a ring between two plates: 2) */
    cx_obstacle obstacles[CX_RESULT_MAX_OBSTACLES];
    double f_applied[3];      /* resultant of the applied loads */
    /* The contact's forces, from the rows N and T (all-dof numbering):
     * -(N'lN + T'lT) is a nodal force on every node a row touches, so a
     * node-to-node or node-to-segment row acts on both of its bodies
     * with opposite forces. f_contact is their sum over all bodies, which
     * is the force of the rigid obstacles alone (the rows between bodies
     * cancel): it is summed over the rigid-obstacle rows (a row on one
     * node); one body: the contact force on it. */
    double f_contact[3];
    int nbodies;              /* mesh->nbodies (1 if the mesh has no body ids) */
    double *f_contact_body;   /* dim * nbodies: the contact force on body b,
                                 -(N'lN + T'lT) summed over b's nodes; with
                                 b's applied load and its support reactions it
                                 balances */
    int nbodies_obstacle;     /* bodies with a rigid-obstacle point in contact
                                 (lN above 1e-12 of the largest lN) */
    /* -(lN n + lT t) summed over the points (at their slave nodes): what the
     * VTU's tractions x weights sum to; one body's force only for one body */
    double f_points[3];
    double *u;                /* dim * nnodes: the full displacement */
    double *lN;               /* m */
    double *lT;               /* nt */
    unsigned char *status;    /* m, cx_point_status */
    cx_run_record run;
    double *stress_cache;     /* private: see cx_result_stress */
    double *vm_cache;
    /* The tangential relative displacement T u of each point (nt values,
     * rows as lT; the rows T of the problem applied to the full u), so
     * that node-to-node points slip by u_k - u_l; the slip of a point
     * that slips (status CX_PT_SLIP_*), read with the status. */
    double *tu;
} cx_result;

/* A result for the solution (u: the n free dofs, lN: m, lT: nt or NULL for
 * zero, status: m or NULL for all free) of problem p under the friction
 * state fr (NULL: frictionless); the run record holds fr's law and values
 * and zeros. Everything is copied. */
int cx_result_create(cx_result **r, const cx_problem *p, const cx_friction_state *fr,
                     const double *u, const double *lN, const double *lT,
                     const unsigned char *status, cx_diag *d);
/* A result for the session's current iterate and its run (method,
 * parameters, options, outcome, counters, setup and solve times). sc (may
 * be NULL) gives the scene id, title, obstacle and Hertz's pressure error;
 * level <= 0 means the scene's. The iterate must be whole: during a run,
 * call cx_session_complete_iterate first (CX_EINVAL otherwise). */
int cx_result_from_session(cx_result **r, const cx_session *s, const cx_scene *sc, int level,
                           cx_diag *d);
void cx_result_destroy(cx_result **r);

/* The 'signorini solve' arguments that repeat the run (no output path, no
 * date: the same text for the same run), e.g. "hertz --level 32 --method
 * ssn-tresca --set rho=0.001 --friction none --tol 1e-10 --max-iter 500
 * --stop own"; numbers in their shortest exact form. Into buf (len
 * bytes, always terminated; cut if too small); returns buf. */
char *cx_run_record_solve_args(const cx_run_record *run, char *buf, size_t len);

/* Nodal stresses (Voigt: 3 per node in 2D, 6 in 3D; cx_fem_nodal_stress)
 * and von Mises stress (per node, with the material of a body using it),
 * computed on the first call and kept. Either output may be NULL. */
int cx_result_stress(cx_result *r, const double **sigma, const double **von_mises, cx_diag *d);

/* Per node (mesh->nnodes values): the contact pressure lN / weight (0 away
 * from the contact points), and the status (cx_point_status, -1 away). */
void cx_result_nodal_pressure(const cx_result *r, double *val);
void cx_result_nodal_status(const cx_result *r, double *val);

#endif
