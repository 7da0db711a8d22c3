/* SPDX-License-Identifier: GPL-3.0-or-later */
/* solve/: the kkt error of doc/design.md §3 — zero at a solution, positive off
 * it, unchanged when the units of the scene change. */
#include "solve_fixture.h"
#include "check.h"

#include <math.h>
#include <string.h>

static void scale_problem(cx_problem *p, double *sb, double force, double length)
{
    /* K: force/length, f and multipliers: force, u and g: length */
    for (size_t k = 0; k < cx_csc_nnz(&p->K); k++)
        p->K.x[k] *= force / length;
    for (int i = 0; i < p->n; i++)
        p->f[i] *= force;
    for (int i = 0; i < p->m; i++) {
        p->g[i] *= length;
        sb[i] *= force;   /* the slip bounds: the session's, copied */
    }
    p->kscale *= force / length;
}

int main(void)
{
    cx_scene sc;
    cx_diag d;
    for (int law = CX_FRICTION_NONE; law <= CX_FRICTION_TRESCA; law++) {
        cx_session *s = fixture_session("hertz", 8, &sc);
        CX_CHECK_OK(cx_session_set_friction(s, &(cx_friction_state){(cx_friction)law, 20, 20, NULL, NULL}, &d));
        CX_CHECK_OK(cx_session_set_method(s, cx_method_find("ssn-tresca"), NULL, NULL, &d));
        CX_CHECK_OK(cx_solver_solve(s, NULL, NULL, &d));
        const cx_iterate *it = cx_session_iterate(s);
        cx_problem *p = (cx_problem *)cx_session_problem(s);
        int n = p->n, m = p->m, nt = p->nt;
        double *work = calloc((size_t)(n + m + nt), sizeof(double));
        double *u = malloc(sizeof(double) * (size_t)n), *lN = malloc(sizeof(double) * (size_t)m);
        double *lT = malloc(sizeof(double) * (size_t)(nt ? nt : 1));
        cx_kkt parts;
        /* the session's friction state, with its slip bounds copied so
         * that the units test can scale them */
        cx_friction_state fr = *cx_session_friction(s);
        double *sb = malloc(sizeof(double) * (size_t)(m ? m : 1));
        memcpy(sb, fr.s, sizeof(double) * (size_t)m);
        fr.s = sb;

        /* at the solution */
        double e0 = cx_kkt_error(p, &fr, it->u, it->lN, it->lT, work, NULL, &parts);
        CX_CHECK_LE(e0, 1e-12);

        /* off it: a 1 % change of one multiplier is seen */
        memcpy(u, it->u, sizeof(double) * (size_t)n);
        memcpy(lN, it->lN, sizeof(double) * (size_t)m);
        memcpy(lT, it->lT, sizeof(double) * (size_t)nt);
        lN[0] *= 1.01;
        double e1 = cx_kkt_error(p, &fr, u, lN, lT, work, NULL, &parts);
        CX_CHECK(e1 > 1e-4);
        CX_CHECK(parts.equilibrium > 1e-4);
        /* a penetration of 1e-3 of the largest displacement is seen */
        lN[0] = it->lN[0];
        for (int k = 0; k < n; k++)
            u[k] = it->u[k] * 1.001;
        double e2 = cx_kkt_error(p, &fr, u, lN, lT, work, NULL, &parts);
        CX_CHECK(parts.contact > 1e-4 && e2 > 1e-4);
        /* with K u given (the PETSc backend's way) the same error, off the
         * solution and at it (to rounding: K u - f + N'lN cancels to 1e-3
         * of its terms, so the sums' order shows at 1e-13) */
        {
            double *Ku = calloc((size_t)n, sizeof(double));
            cx_kkt pk;
            cx_csc_gemv(&p->K, 1.0, u, 0.0, Ku);
            double e2k = cx_kkt_error_Ku(p, &fr, u, lN, lT, Ku, work, NULL, &pk);
            CX_CHECK_NEAR(e2k, e2, 1e-10, 0);
            CX_CHECK_NEAR(pk.equilibrium, parts.equilibrium, 1e-10, 0);
            cx_csc_gemv(&p->K, 1.0, it->u, 0.0, Ku);
            CX_CHECK_NEAR(cx_kkt_error_Ku(p, &fr, it->u, it->lN, it->lT, Ku, work, NULL, NULL), e0, 1e-6, 1e-14);
            free(Ku);
        }

        /* units: mm-MPa-like scaling changes nothing */
        double force = 1e6, length = 1e-3;
        scale_problem(p, sb, force, length);
        for (int k = 0; k < n; k++)
            u[k] *= length;
        for (int i = 0; i < m; i++)
            lN[i] *= force;
        for (int i = 0; i < nt; i++)
            lT[i] *= force;
        double e3 = cx_kkt_error(p, &fr, u, lN, lT, work, NULL, &parts);
        CX_CHECK_NEAR(e3, e2, 1e-12, 0);

        /* NaN in the iterate: +inf, never a number */
        u[0] = NAN;
        CX_CHECK(isinf(cx_kkt_error(p, &fr, u, lN, lT, work, NULL, NULL)));
        free(work);
        free(u);
        free(lN);
        free(lT);
        free(sb);
        cx_session_destroy(&s);
    }
    return check_finish("solve_kkt");
}
