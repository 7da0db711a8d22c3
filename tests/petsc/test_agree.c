/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The PETSc backend against the direct path, on as many ranks as the test
 * is started with (mpirun -n N or alone):
 *
 *   test_petsc_agree SCENE LEVEL LAW METHOD DIRECT MAXREL KRYLOV_MAX [SOLVER]
 *
 * builds the scene on every rank, solves it with the backend's METHOD, and
 * on rank 0 with the direct path's DIRECT method; checks that both
 * converge (kkt <= 1e-10), that the solutions agree to MAXREL in the
 * energy norm, ||u - u_direct||_K / ||u_direct||_K, and that the mean
 * Krylov iterations per solve stay at or below KRYLOV_MAX (the multigrid
 * is what keeps that bounded as the level grows; 0: no check), and, if
 * SOLVER is given, that the inner solves ran it ("CG + BoomerAMG"; the
 * result's name begins with it).
 * METHOD petsc-vi or petsc-tao may end early with a reason instead, if
 * DIRECT is "-" (the peers on a problem they may not take). */
#include "petsc/petsc.h"
#include "scene/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double energy(const cx_problem *p, const double *u, double *w)
{
    cx_csc_gemv(&p->K, 1.0, u, 0.0, w);
    double e = 0;
    for (int i = 0; i < p->n; i++)
        e += u[i] * w[i];
    return sqrt(fmax(e, 0));
}

int main(int argc, char **argv)
{
    if (argc != 8 && argc != 9) {
        fprintf(stderr, "usage: %s SCENE LEVEL LAW METHOD DIRECT MAXREL KRYLOV_MAX [SOLVER]\n", argv[0]);
        return 2;
    }
    const char *id = argv[1], *method = argv[4], *direct = argv[5];
    int level = atoi(argv[2]);
    int law = cx_friction_from_name(argv[3]);
    double maxrel = atof(argv[6]), kmax = atof(argv[7]);
    const char *solver = argc == 9 ? argv[8] : NULL;
    cx_diag d;
    cx_diag_clear(&d);
    if (cx_petsc_initialize(&d)) {
        fprintf(stderr, "%s\n", d.msg);
        return 1;
    }
    int rank = cx_petsc_rank(), fail = 0;
    char path[512];
    cx_scene sc;
    cx_problem *p = NULL;
    cx_friction_state fr;
    cx_session *s = NULL;
    if (cx_scene_resolve(id, path, sizeof path, &d) || cx_scene_load(&sc, path, &d) ||
        cx_scene_build(&sc, level, &p, &fr, &d) || cx_session_create(&s, &p, &d)) {
        fprintf(stderr, "%s level %d: %s\n", id, level, d.msg);
        return 1;
    }
    fr.law = (cx_friction)law;
    if (cx_session_set_friction(s, &fr, &d)) {
        fprintf(stderr, "%s\n", d.msg);
        return 1;
    }
    const cx_problem *cp = cx_session_problem(s);
    cx_options opt;
    cx_options_default(&opt);
    opt.tol = 1e-10;

    /* the direct path, on rank 0 */
    double *ud = NULL;
    if (rank == 0 && strcmp(direct, "-") != 0) {
        const cx_method *m = cx_method_find(direct);
        cx_param_values pv;
        if (!m) {
            fprintf(stderr, "unknown direct method %s\n", direct);
            return 2;
        }
        cx_param_default(&pv, m->params);
        if (cx_session_set_method(s, m, &pv, &opt, &d) || cx_solver_solve(s, NULL, NULL, &d) ||
            cx_session_complete_iterate(s, &d)) {
            fprintf(stderr, "direct %s: %s\n", direct, d.msg);
            return 1;
        }
        const cx_iterate *it = cx_session_iterate(s);
        printf("direct %s: %s after %d iterations, kkt %.3e\n", direct, cx_reason_str(it->reason), it->iter,
               it->kkt);
        if (it->reason <= 0 || it->kkt > opt.tol)
            fail = 1;
        ud = malloc(sizeof(double) * (size_t)cp->n);
        memcpy(ud, it->u, sizeof(double) * (size_t)cp->n);
    }

    cx_petsc_result r = {0};
    if (cx_petsc_solve(cp, cx_session_friction(s), method, &opt, NULL, NULL, &r, &d)) {
        fprintf(stderr, "rank %d: petsc %s: %s\n", rank, method, d.msg);
        return 1;
    }
    if (rank == 0) {
        printf("%s level %d (%d dofs), %s, petsc %s on %d ranks: %s after %d iterations, kkt %.3e; "
               "%ld Krylov iterations in %d solves with %s (%.1f per solve)%s%s\n",
               id, level, cp->n, argv[3], method, r.nranks, cx_reason_str(r.reason), r.iterations, r.kkt,
               r.krylov, r.pc_setups, r.solver, r.pc_setups ? (double)r.krylov / r.pc_setups : 0.0,
               r.message[0] ? ": " : "", r.message);
        for (int k = 0; k < r.nranks; k++)
            printf("  rank %d: %d rows, %d elements, peak %.0f MB\n", k, r.rows[k], r.elems[k],
                   r.mem_peak[k] / 1048576.0);
        if (ud) {
            if (r.reason <= 0 || r.kkt > opt.tol) {
                printf("FAIL: the backend did not converge\n");
                fail = 1;
            }
            double *w = malloc(sizeof(double) * (size_t)cp->n), *e = malloc(sizeof(double) * (size_t)cp->n);
            for (int i = 0; i < cp->n; i++)
                e[i] = r.u[i] - ud[i];
            double rel = energy(cp, e, w) / energy(cp, ud, w);
            printf("||u - u_direct||_K / ||u_direct||_K = %.3e (at most %.1e)\n", rel, maxrel);
            if (!(rel <= maxrel)) {
                printf("FAIL: the solutions differ\n");
                fail = 1;
            }
            free(w);
            free(e);
        } else if (r.reason <= 0 && !r.message[0]) {
            printf("FAIL: the peer neither converged nor said why\n");
            fail = 1;
        }
        double per = r.pc_setups ? (double)r.krylov / r.pc_setups : 0;
        if (kmax > 0 && !(per <= kmax)) {
            printf("FAIL: %.1f Krylov iterations per solve, above the band's %.0f\n", per, kmax);
            fail = 1;
        }
        if (solver && strncmp(r.solver, solver, strlen(solver)) != 0) {
            printf("FAIL: the inner solves ran '%s', not '%s'\n", r.solver, solver);
            fail = 1;
        }
    }
    free(ud);
    cx_petsc_result_clear(&r);
    cx_session_destroy(&s);
    cx_petsc_finalize();
    return fail;
}
