/* SPDX-License-Identifier: GPL-3.0-or-later */
/* ubr-c — Uzawa block relaxation for frictionless contact, paper 002 §4.3
 * (Algorithm UBR-C), 2D and 3D.
 *
 * Augmented Lagrangian with an auxiliary normal displacement phi = u_N:
 * each iteration solves (K + r N'WN) u = f + N'W(r phi - lam) with the one
 * factorisation of the run (W: the lumped contact-boundary measure, so r
 * has the paper's units: r (u_N, v_N) is the boundary integral of (4.5)),
 * projects phi onto phi <= g in closed form (4.15) and updates
 * lam <- lam + r(u_N - phi). Linearly convergent; r decides the rate.
 * Its own criterion is the paper's relative change (4.16) of (u, phi)
 * below eps. Needs a sparse Cholesky of K + r N'WN (the session's cache,
 * keyed by r: a second run reuses it). r = auto: ubr.c. */
#include "solve/ubr.h"

typedef struct {
    ubr_core core;   /* the shared UBR iteration and its workspace */
} ubrc_state;

static const cx_param ubrc_params[] = {
    UBR_PARAMS(0.11, "penalty r in units of E, or auto (paper: 0.11 for hertz, 4 for halfball)"),
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void ubrc_destroy(void *state)
{
    ubrc_state *st = state;
    ubr_core_clear(&st->core);
}

static int ubrc_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    ubrc_state *st = state;
    return ubr_core_init(&st->core, s, params, 0, "ubr-c", d);
}

static int ubrc_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    ubrc_state *st = state;
    return ubr_core_step(&st->core, s, it, d);
}

const cx_method cx_method_ubr_c = {
    .id = "ubr-c",
    .name = "Uzawa block relaxation (frictionless)",
    .source = "002 §4.3",
    .summary = "augmented Lagrangian, one factorisation of K + rM, closed-form projection per iteration",
    .supports = CX_FRICTIONLESS | CX_2D | CX_3D,
    .state_size = sizeof(ubrc_state),
    .params = ubrc_params,
    .init = ubrc_init,
    .step = ubrc_step,
    .destroy = ubrc_destroy,
};
