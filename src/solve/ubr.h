/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Private to solve/: the Uzawa block relaxation core shared by ubr-c and
 * ubr-tf (paper 002 §4.3 and §5), so that both methods differ only in what
 * they project. See ubr.c for the algorithm and the r = auto rule. */
#ifndef CX_SOLVE_UBR_H
#define CX_SOLVE_UBR_H

#include "solve/solve.h"

typedef struct ubr_core {
    int n, m, dt;         /* free dofs, contact points, tangent components (0: frictionless) */
    double E;             /* Young modulus (largest of the bodies): the unit of r */
    double r;             /* current penalty (absolute: force / length^(d+1)) */
    int auto_r;           /* 1: r chosen by the a-priori rule of ubr.c */
    double eps;           /* the paper's criterion (4.16)/(5.6) */
    cx_fact *F;           /* factor of K + r (N'WN + T'WT), borrowed from the cache */
    const double *w;      /* m: lumped contact-boundary measure W (the problem's) */
    double *sb;           /* m: Tresca bound as a traction s_i / w_i */
    double *phiN, *lamN;  /* m: auxiliary normal displacement, normal pressure */
    double *phiT, *lamT;  /* m dt: auxiliary slip, tangential traction */
    double *phiN0, *phiT0;/* m, m dt: the previous phi (criterion, auto rule) */
    double *un, *ut;      /* m, m dt: N u, T u */
    double *rhs;          /* n */
    double *uprev;        /* n */
    double *tmp;          /* max(m, m dt) */
} ubr_core;

/* Penalty parameters of ubr-c / ubr-tf: r in units of E, or auto. */
#define UBR_PARAMS(rdef, rhelp)                                                            \
    {"r", CX_PARAM_REAL, rdef, 1e-12, 1e12, NULL, rhelp, CX_PARAM_AUTO},                   \
    {"eps", CX_PARAM_REAL, 1e-5, 1e-16, 1, NULL,                                            \
     "the paper's relative-change criterion (4.16)/(5.6)", 0}

/* Allocate, take the factor from the session's cache, start from the
 * session's iterate (zero, or a warm start). tangential: Tresca rows. */
int ubr_core_init(ubr_core *c, cx_session *s, const cx_param_values *params, int tangential,
                  const char *id, cx_diag *d);
void ubr_core_clear(ubr_core *c);
/* One iteration (002 (4.13)-(4.15), (5.3)-(5.5)); writes u, lN, lT, own. */
int ubr_core_step(ubr_core *c, cx_session *s, cx_iterate *it, cx_diag *d);
/* The factor of K + r(N'WN + T'WT), from the session's cache (built once
 * per session and r). */
int ubr_factor(cx_session *s, double r, int tangential, cx_fact **F, cx_diag *d);

#endif
