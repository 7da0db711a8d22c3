/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini solve SCENE --backend petsc: the problem solved by the PETSc
 * backend (src/petsc/) on the MPI ranks the program was started with
 * (mpirun -n N, srun, or alone: one rank). Every rank builds the scene and
 * takes part in every call; rank 0 alone prints and writes files. */
#include "cli/cli.h"
#include "out/out.h"
#include "cx_config.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#if CX_HAVE_PETSC
#include "petsc/petsc.h"

typedef struct {
    FILE *out;
    int quiet;
    cx_history *history;   /* --json: every step */
} petsc_watch;

static int petsc_print_step(void *ctx, const cx_petsc_step *st)
{
    petsc_watch *w = ctx;
    if (w->history) {
        cx_iterate it;
        memset(&it, 0, sizeof it);
        it.iter = st->iter;
        it.kkt = st->kkt;
        it.own = NAN;
        it.ncontact = st->ncontact;
        it.nstick = st->nstick;
        it.nslip = st->nslip;
        it.nchanged = st->nchanged;
        it.time = st->time;
        if (cx_history_add(w->history, &it))
            return 1;
    }
    if (!w->quiet && w->out) {
        fprintf(w->out, "%6d  %10.3e  %7d %6d %6d %7d  %7d  %8.1e  %9.4f\n", st->iter, st->kkt,
                st->ncontact + st->nstick + st->nslip, st->nstick, st->nslip, st->nchanged, st->krylov,
                st->rtol, st->time);
        fflush(w->out);
    }
    return 0;
}

int cli_solve_petsc(const char *cmd, const cx_scene *sc, const cx_problem *p, const cx_friction_state *fr,
                    const cx_options *opt, const cli_petsc_args *a, FILE *summary)
{
    cx_diag d;
    cx_diag_clear(&d);
    if (cx_petsc_initialize(&d))
        return cli_fail(cmd, d.msg);
    int rank = cx_petsc_rank(), size = cx_petsc_size();
    const char *method = a->method && strcmp(a->method, "auto") != 0 ? a->method : "ssn-tresca";
    if (cx_petsc_check(p, method, fr->law, &d))
        return rank == 0 ? cli_fail(cmd, d.msg) : CX_EXIT_ERROR;
    FILE *out = rank == 0 ? summary : NULL;
    if (out && !a->json && !a->quiet) {
        fprintf(out, "%s level %d: %dD, %d dofs, %d contact points; %s (petsc, %d rank%s), friction %s\n", sc->id,
                a->level > 0 ? a->level : sc->level, p->dim, p->n, p->m, method, size, size > 1 ? "s" : "",
                cx_friction_name(fr->law));
        fprintf(out, "  iter  kkt error   contact  stick   slip changed   krylov      rtol   time (s)\n");
        fflush(out);
    }
    cx_history history = {0};
    petsc_watch w = {out, a->json || a->quiet, rank == 0 && a->json ? &history : NULL};
    cx_petsc_result r = {0};
    double t1 = cx_clock_now();
    if (cx_petsc_solve(p, fr, method, opt, petsc_print_step, &w, &r, &d)) {
        cx_history_clear(&history);
        return rank == 0 ? cli_fail(cmd, d.msg) : CX_EXIT_ERROR;
    }
    double t_total = a->t_assemble + (cx_clock_now() - t1);
    int code = cli_exit_status(r.reason);
    if (rank != 0) {
        cx_petsc_result_clear(&r);
        return code;
    }
    /* rank 0: the summary and the files, from the gathered solution; the
     * baseline (serial, rank 0 only) after the run here, not before it as
     * on the direct path, so that the other ranks do not wait for it */
    double t_base = 0;
    if (a->baseline && cx_problem_baseline(p, &t_base, &d)) {
        cx_petsc_result_clear(&r);
        cx_history_clear(&history);
        return cli_fail(cmd, d.msg);
    }
    unsigned char *st = CX_NEW(unsigned char, p->m + 1);
    cx_result *res = NULL;
    if (!st || cx_result_create(&res, p, fr, r.u, r.lN, r.lT, (cx_petsc_point_status(p, fr, r.lN, r.lT, st), st), &d)) {
        cx_free(st);
        cx_petsc_result_clear(&r);
        cx_history_clear(&history);
        return cli_fail(cmd, st ? d.msg : "out of memory");
    }
    cx_free(st);
    cx_run_record *run = &res->run;
    snprintf(run->scene, sizeof run->scene, "%s", sc->id);
    snprintf(run->title, sizeof run->title, "%s", sc->title);
    snprintf(run->method, sizeof run->method, "%s", method);
    run->level = a->level > 0 ? a->level : sc->level;
    run->tol = opt->tol;
    run->max_iter = opt->max_iter;
    run->time_limit = opt->time_limit;
    run->iterations = r.iterations;
    run->reason = r.reason;
    run->converged = r.reason > 0;
    snprintf(run->message, sizeof run->message, "%s", r.message);
    run->kkt = r.kkt;
    run->kkt_parts = r.kkt_parts;
    run->own = NAN;
    run->counters.matvecs = r.krylov;
    run->time.assemble = a->t_assemble;
    run->time.setup = r.t_setup;
    run->time.solve = r.t_solve;
    run->time.total = t_total;
    run->has_baseline = a->baseline;
    run->time.baseline = t_base;
    if (a->json)
        cx_result_write_json_history(res, &history, stdout);
    else {
        cli_solve_write_text(res, summary);
        double mem = 0;
        for (int k = 0; k < r.nranks; k++)
            mem += r.mem_peak[k];
        fprintf(summary, "petsc:   %d rank%s; ", r.nranks, r.nranks > 1 ? "s" : "");
        if (r.pc_setups)
            fprintf(summary, "%s: %ld Krylov iterations in %d solves (%.1f per solve)", r.solver, r.krylov,
                    r.pc_setups, (double)r.krylov / r.pc_setups);
        else
            fprintf(summary, "%ld Krylov iterations in the method's inner solves (%s)", r.krylov,
                    r.solver[0] ? r.solver : "no Krylov solver");
        fprintf(summary, "; peak memory %.0f MB in all\n", mem / 1048576.0);
        if (r.reason == CX_DIVERGED_STALL && r.message[0])   /* at the roundoff floor (petsc/run.c) */
            fprintf(summary, "stalled: %s\n", r.message);
        for (int k = 0; k < r.nranks; k++)
            fprintf(summary, "  rank %d: %d rows, %d elements assembled, peak memory %.0f MB\n", k, r.rows[k],
                    r.elems[k], r.mem_peak[k] / 1048576.0);
    }
    if (a->vtu && cx_vtu_write(res, a->vtu, 0, &d))
        code = cli_fail(cmd, d.msg);
    cx_result_destroy(&res);
    cx_petsc_result_clear(&r);
    cx_history_clear(&history);
    return code;
}

#else

int cli_solve_petsc(const char *cmd, const cx_scene *sc, const cx_problem *p, const cx_friction_state *fr,
                    const cx_options *opt, const cli_petsc_args *a, FILE *summary)
{
    (void)sc, (void)p, (void)fr, (void)opt, (void)a, (void)summary;
    return cli_fail(cmd, "--backend petsc: this build has no PETSc backend (meson setup -Dpetsc=enabled)");
}

#endif
