/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The perturbations of 'bench stress' (bench/bench_perturb.c): functions of
 * a scene copy, and bench_perturb_fn's of the built problem. */
#ifndef CX_BENCH_PERTURB_H
#define CX_BENCH_PERTURB_H

#include "bench/bench.h"

/* Lengths x L and stresses x P (SI -> mm-MPa: L = 1e3, P = 1e-6);
 * displacements scale by L, nodal forces by P L^(dim-1). */
void perturb_scene_units(cx_scene *s, double L, double P);
/* Tractions, body forces and prescribed displacements x factor. */
void perturb_scene_loads(cx_scene *s, double factor);

/* The largest extent of the mesh's bounding box. */
double perturb_body_size(const cx_problem *p);

/* arg: const double *, the gap added to every point as a fraction of the
 * body size. */
int perturb_gap(cx_problem *p, const void *arg, cx_diag *d);
/* arg: const double *: a copy of the contact point of smallest gap, its
 * gap larger by that fraction of the body size (0: coincident). */
int perturb_duplicate_contact(cx_problem *p, const void *arg, cx_diag *d);

typedef struct perturb_jitter_arg {
    const cx_scene *scene;   /* its loads, to reassemble */
    double frac;             /* of the shortest edge at each node */
    uint64_t seed;
} perturb_jitter_arg;
/* Move the interior nodes randomly (fixed seed), reassemble K and f. */
int perturb_jitter(cx_problem *p, const void *arg, cx_diag *d);

typedef struct perturb_contrast_arg {
    const cx_scene *scene;
    double ratio;            /* E of bodies 1.. times ratio */
} perturb_contrast_arg;
/* CX_EUNSUPPORTED "n/a (one body)" on a one-body mesh. */
int perturb_contrast(cx_problem *p, const void *arg, cx_diag *d);

#endif
