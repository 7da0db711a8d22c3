/* SPDX-License-Identifier: GPL-3.0-or-later */
/* ubr-tf — Uzawa block relaxation for Tresca friction, paper 002 §5
 * (Algorithm UBR-TF), 2D and 3D.
 *
 * As ubr-c with the tangential displacement split off as well: each
 * iteration solves (K + r(N'WN + T'WT)) u = f + N'W(r phi_N - lam_N)
 * + T'W(r phi_T - lam_T) with the one factorisation of the run, then
 * phi_N by the projection (4.15) and phi_T by the shrinkage (5.5):
 * phi_T = (|z| - s)+ z / (r |z|), z = lam_T + r u_T, where |.| is the
 * Euclidean norm of z in R^2 in 3D (the disc: isotropic friction), and the
 * multipliers take the step r. s is the problem's per-point slip bound as a
 * traction (s_i / W_i), so per-point bounds (Hertz's pressure, a Coulomb
 * fixed point's F lN) work unchanged. Own criterion: the paper's (5.6).
 * The inner method of cf-fp by default. r = auto: ubr.c. */
#include "solve/ubr.h"

typedef struct {
    ubr_core core;   /* the shared UBR iteration and its workspace */
} ubrtf_state;

static const cx_param ubrtf_params[] = {
    UBR_PARAMS(0.13, "penalty r in units of E, or auto (paper: 0.13 for hertz, 2.75 for halfball)"),
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

static void ubrtf_destroy(void *state)
{
    ubrtf_state *st = state;
    ubr_core_clear(&st->core);
}

static int ubrtf_init(void *state, cx_session *s, const cx_param_values *params, cx_diag *d)
{
    ubrtf_state *st = state;
    return ubr_core_init(&st->core, s, params, 1, "ubr-tf", d);
}

static int ubrtf_step(void *state, cx_session *s, cx_iterate *it, cx_diag *d)
{
    ubrtf_state *st = state;
    return ubr_core_step(&st->core, s, it, d);
}

const cx_method cx_method_ubr_tf = {
    .id = "ubr-tf",
    .name = "Uzawa block relaxation (Tresca)",
    .source = "002 §5",
    .summary = "augmented Lagrangian, one factorisation of K + r(N'WN + T'WT), disc shrinkage per iteration",
    .supports = CX_TRESCA | CX_2D | CX_3D,
    .state_size = sizeof(ubrtf_state),
    .params = ubrtf_params,
    .init = ubrtf_init,
    .step = ubrtf_step,
    .destroy = ubrtf_destroy,
};
