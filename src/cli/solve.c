/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini solve SCENE [options]: build, solve, report (text or JSON). */
#include "cli/cli.h"
#include "cli/progress.h"
#include "out/out.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <sys/stat.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static const char solve_usage[] =
    "usage: signorini solve SCENE [options]\n"
    "\n"
    "SCENE is a scene id (see 'signorini list') or a path to an .ini file.\n"
    "\n"
    "Exit status: 0 converged (kkt error <= tol), 1 error, 2 usage (a malformed\n"
    "command line), 3 not converged (stopped by its own criterion above tol,\n"
    "stalled, iteration or time limit, breakdown, overflow or NaN), 130\n"
    "interrupted (Ctrl-C: the partial result is printed as cancelled).\n";

typedef struct {
    cx_solve_args s;          /* the options every solve has (base/opt_solve.h) */
    int json, baseline, quiet;
    int backend;              /* --backend: 0 direct, 1 petsc */
    const char *vtu_series;   /* --vtu-series DIR */
    const char *problem;      /* --problem DIR|FILE (cli/solve_problem.c) */
    cli_render_args render;   /* --png, --vtu and the drawing options (cli/render.c) */
} solve_args;

/* --friction is a CHOICE of base/opt_solve.h stored as its index */
_Static_assert(CX_FRICTION_NONE == 0 && CX_FRICTION_TRESCA == 1 && CX_FRICTION_COULOMB == 2,
               "--friction's choices none|tresca|coulomb follow cx_friction");

/* What only the command line's solve has. */
static const cx_opt solve_own_opts[] = {
    {"json", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "print one JSON object on stdout instead of the summary",
     offsetof(solve_args, json), NULL},
    {"baseline", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "also time one factorisation + solve of K alone",
     offsetof(solve_args, baseline), NULL},
    {"problem", 0, CX_OPT_STRING, 0, 0, 0, NULL, "DIR|FILE",
     "solve the discrete problem of 'signorini export' (a directory\n"
     "of MatrixMarket files or an FCLIB .hdf5) instead of a SCENE", offsetof(solve_args, problem), NULL},
    {"quiet", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "no per-iteration lines", offsetof(solve_args, quiet),
     NULL},
    {"backend", 0, CX_OPT_CHOICE, 0, 0, 0, "direct|petsc", "NAME",
     "direct (sparse Cholesky, the default) | petsc (CG + algebraic multigrid on the MPI ranks, GAMG in 3D "
     "and BoomerAMG in 2D: mpirun -n N signorini solve ...; methods ssn-tresca, petsc-vi, petsc-tao)", offsetof(solve_args, backend), NULL},
    {"vtu-series", 0, CX_OPT_STRING, 0, 0, 0, NULL, "DIR",
     "write every iterate as DIR/iter_NNNN.vtu and DIR/series.pvd (a ParaView time series, time = "
     "iteration); each iterate is completed first, as the explorer does", offsetof(solve_args, vtu_series),
     NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

static const cx_opt *const solve_tables[] = {cx_solve_opts, solve_own_opts, cli_render_opts, NULL};

/* CX_OK, CX_OPT_HELP, or CX_EINVAL for a malformed command line. */
static int solve_parse(int argc, char **argv, const char **scene, solve_args *a, cx_diag *d)
{
    cx_options o;
    cx_options_default(&o);
    memset(a, 0, sizeof *a);
    cx_solve_args_default(&a->s, o.tol, o.max_iter, o.own_stop, o.time_limit);
    cli_render_args_init(&a->render);
    cx_opt_group groups[] = {{cx_solve_opts, &a->s}, {solve_own_opts, a}, {cli_render_opts, &a->render},
                             {NULL, NULL}};
    int npos = 0;
    int r = cx_opt_parse(groups, argc, argv, scene, 1, &npos, d);
    if (r)
        return r;
    cli_render_finish(&a->render);
    if (npos == 0 && !a->problem)
        return cx_diag_set(d, CX_EINVAL, "missing SCENE");
    if (npos > 0 && a->problem)
        return cx_diag_set(d, CX_EINVAL, "a SCENE and --problem: give one");
    /* a method id is a word of the registry: known before anything is built */
    for (int k = 0; k < a->s.methods.n && !a->backend; k++) {   /* the PETSc backend checks its own */
        const char *id = a->s.methods.v[k];
        if (strcmp(id, "auto") != 0 && !cx_method_find(id))
            return cx_diag_set(d, CX_EINVAL, "--method: unknown method '%s' (see 'signorini list')", id);
        if (a->s.methods.n > 1 && strcmp(id, "auto") == 0)
            return cx_diag_set(d, CX_EINVAL, "--method auto: not in a comparison of several methods");
    }
    if (a->s.methods.n > 1 && a->render.plot != 1 && a->render.plot != 2)
        return cx_diag_set(d, CX_EINVAL, "--method given %d times: only --plot convergence|work compares "
                           "methods", a->s.methods.n);
    if (a->s.methods.n > 1)
        CX_TRY(cli_sets_check(&a->s.methods, &a->s.sets, d));
    a->s.method = a->s.methods.n ? a->s.methods.v[0] : NULL;
    a->render.methods = &a->s.methods;
    a->render.sets = &a->s.sets;
    /* the summary (or JSON) and a file on standard output cannot share it */
    if (cli_render_stdout_users(&a->render) + a->json > 1)
        return cx_diag_set(d, CX_EINVAL, "--json, --png - and --vtu -: only one can go to standard output");
    return CX_OK;
}

/* A number of the text output with printf's fmt, or "-" if it is not
 * finite: no NaN or Inf is ever printed as a result. */
static const char *solve_num(char *buf, size_t len, const char *fmt, double v)
{
    if (isfinite(v))
        snprintf(buf, len, fmt, v);
    else
        snprintf(buf, len, "-");
    return buf;
}

/* One iterate of --vtu-series: DIR/iter_NNNN.vtu. Non-zero on an error
 * (in w->d), which stops the run. */
static int solve_series_step(cli_watch *w, int iter)
{
    char path[4096];
    cx_result *r = NULL;
    if (cx_session_complete_iterate(w->s, w->d) ||
        cx_result_from_session(&r, w->s, w->sc, w->level, w->d))
        return 1;
    snprintf(path, sizeof path, "%s/iter_%04d.vtu", w->series, iter);
    int rc = cx_vtu_write(r, path, 0, w->d);
    cx_result_destroy(&r);
    w->nseries = rc ? w->nseries : iter;
    return rc != CX_OK;
}

/* DIR/series.pvd: the iterates 1..n as time steps. */
static int solve_series_pvd(const cli_watch *w, cx_diag *d)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/series.pvd", w->series);
    cx_outfile out;
    CX_TRY(cx_outfile_open(&out, path, d));
    fprintf(out.f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n");
    for (int k = 1; k <= w->nseries; k++)
        fprintf(out.f, "    <DataSet timestep=\"%d\" part=\"0\" file=\"iter_%04d.vtu\"/>\n", k, k);
    fprintf(out.f, "  </Collection>\n</VTKFile>\n");
    return cx_outfile_close(&out, 1, d);
}

static int solve_print_step(void *ctx, const cx_session *s, const cx_iterate *it)
{
    (void)s;
    cli_watch *w = ctx;
    char kkt[32], own[32];
    cli_progress_stop();   /* the setup is over: the iterations have their lines */
    if (w->series && solve_series_step(w, it->iter))
        return 1;   /* the file could not be written: stop (the error is in w->d) */
    if (w->history && cx_history_add(w->history, it))
        return 1;   /* out of memory: stop; the run reads as stopped by the observer */
    if (!w->quiet)
        fprintf(w->out, "%6d  %10s  %10s  %7d %6d %6d %7d  %9.4f\n", it->iter,
                solve_num(kkt, sizeof kkt, "%.3e", it->kkt), solve_num(own, sizeof own, "%.3e", it->own),
                it->ncontact + it->nstick + it->nslip, it->nstick, it->nslip, it->nchanged, it->time);
    return 0;
}

#define SOLVE_BODY_LINES 4   /* bodies listed one a line; more: a summary */

void cli_solve_write_text(const cx_result *r, FILE *out)
{
    const cx_run_record *run = &r->run;
    char outcome[CX_DIAG_LEN + 160], b1[32], b2[32], b3[32], b4[32];
    cx_reason_format(run->reason, run->iterations, run->kkt, run->tol, run->message, outcome,
                     sizeof outcome);
    fprintf(out, "%s\n", outcome);
    fprintf(out, "contact: %d of %d points (%d stick, %d slip)\n",
            run->ncontact + run->nstick + run->nslip, r->m, run->nstick, run->nslip);
    const char *axes = "xyz";
    fprintf(out, "force:   applied");
    for (int k = 0; k < r->dim; k++)
        fprintf(out, " %c %s", axes[k], solve_num(b1, sizeof b1, "%.6g", r->f_applied[k]));
    /* several bodies: the rigid obstacles' force on them all, then each
     * body's contact force (a wall of many bodies: their count) */
    fprintf(out, r->nbodies > 1 ? ";  from rigid obstacles" : ";  contact");
    for (int k = 0; k < r->dim; k++)
        fprintf(out, " %c %s", axes[k], solve_num(b1, sizeof b1, "%.6g", r->f_contact[k]));
    if (r->nbodies > SOLVE_BODY_LINES)
        fprintf(out, " (on %d of %d bodies)", r->nbodies_obstacle, r->nbodies);
    fprintf(out, "\n");
    for (int b = 0; r->nbodies > 1 && b < r->nbodies && r->nbodies <= SOLVE_BODY_LINES; b++) {
        fprintf(out, "         contact on body %d", b + 1);
        for (int k = 0; k < r->dim; k++)
            fprintf(out, " %c %s", axes[k],
                    solve_num(b1, sizeof b1, "%.6g", r->f_contact_body[r->dim * b + k]));
        fprintf(out, "\n");
    }
    if (run->has_pressure_error)
        fprintf(out, "pressure vs Hertz: L2 error %s (%s %%), %s %s computed, %s = %s Hertz\n",
                solve_num(b1, sizeof b1, "%.4g", run->pressure_error_abs),
                solve_num(b2, sizeof b2, "%.2f", 100 * run->pressure_error_rel),
                r->dim == 3 ? "contact radius" : "half-width", 
                solve_num(b4, sizeof b4, "%.4g", run->halfwidth), r->dim == 3 ? "a" : "b",
                solve_num(b3, sizeof b3, "%.4g", run->hertz_halfwidth));
    fprintf(out, "time:    assemble %.3f s, setup %.3f s, solve %.3f s, total %.3f s\n", run->time.assemble,
            run->time.setup, run->time.solve, run->time.total);
    if (run->has_baseline)
        fprintf(out, "         baseline (factorise + solve K) %.3f s; (setup + solve) / baseline = %.2f\n",
                run->time.baseline,
                run->time.baseline > 0 ? (run->time.setup + run->time.solve) / run->time.baseline : 0);
    fprintf(out, "work:    %ld factorisations, %ld solves, %ld products with K\n",
            run->counters.factorizations, run->counters.solves, run->counters.matvecs);
}

/* Ctrl-C. While the method runs, the handler sets the session's cancel
 * flag (an atomic store, safe in a handler): the run ends at the next
 * check and its partial result is printed as cancelled. Before or after
 * the run, it removes a temporary output file being written and stops. */
static cx_session *volatile solve_running;

static void solve_on_sigint(int sig)
{
    (void)sig;
    cx_session *s = solve_running;
    if (s) {
        cx_session_cancel(s);
        return;
    }
    cx_outfile_abandon_pending();
    _exit(CX_EXIT_INTERRUPTED);
}

int cli_method_params(const cx_method *m, const char *auto_sets, const cx_solve_args *a, cx_param_values *pv,
                      cx_diag *d)
{
    cx_param_default(pv, m->params);
    char owner[64];
    snprintf(owner, sizeof owner, "method '%s'", m->id);
    char buf[256];
    snprintf(buf, sizeof buf, "%s", auto_sets);
    for (char *save = NULL, *tok = strtok_r(buf, " ", &save); tok; tok = strtok_r(NULL, " ", &save))
        CX_TRY(cx_param_set_pair(pv, tok, owner, d));
    for (int k = 0; k < a->sets.n; k++)
        CX_TRY(cli_param_set_for(pv, a->sets.v[k], a->methods.n, owner, d));
    return CX_OK;
}

int cli_solve_run(cx_session *s, const char *title, int is_auto, cli_watch *w, cx_diag *d)
{
    solve_running = s;   /* from here Ctrl-C cancels the run (the header may be seen first) */
    if (!w->quiet) {
        const cx_problem *p = cx_session_problem(s);
        cli_progress_stop();
        char clamped[32] = "";   /* points of the contact boundary a support holds */
        if (p->contact.nclamped > 0)
            snprintf(clamped, sizeof clamped, ", %d clamped", p->contact.nclamped);
        fprintf(w->out, "%s: %dD, %d dofs, %d contact points%s; %s%s, friction %s\n", title, p->dim, p->n, p->m,
                clamped, cx_session_method(s)->id, is_auto ? " (auto)" : "",
                cx_friction_name(cx_session_friction(s)->law));
        fprintf(w->out, "  iter  kkt error   own crit.   contact  stick   slip changed   time (s)\n");
        fflush(w->out);          /* the run may be long: show where it is */
        cli_progress_start();   /* until the first iteration's line */
    }
    int rc = cx_solver_solve(s, solve_print_step, w, d);
    cli_progress_stop();
    solve_running = NULL;
    return rc;
}

int cli_exit_status(int reason)
{
    return reason == CX_CONVERGED_KKT ? CX_EXIT_OK : reason == CX_CANCELLED ? CX_EXIT_INTERRUPTED
                                                                          : CX_EXIT_NOT_CONVERGED;
}

int cli_solve(int argc, char **argv)
{
    return cli_solve_as("solve", solve_usage, argc, argv);
}

int cli_solve_as(const char *cmd, const char *usage, int argc, char **argv)
{
    cx_diag d;
    cx_diag_clear(&d);
    solve_args a;
    const char *scene = NULL;
    int parsed = solve_parse(argc, argv, &scene, &a, &d);
    if (parsed == CX_OPT_HELP) {
        cli_help(usage, solve_tables, stdout);
        return CX_EXIT_OK;
    }
    if (parsed)
        return cli_usage(cmd, d.msg);
    if (strcmp(cmd, "render") == 0 && !cli_render_wanted(&a.render))
        return cli_usage(cmd, "missing --png FILE (or --svg, --pdf, --gif, --frames)");
    if (a.backend && (strcmp(cmd, "solve") != 0 || cli_render_wanted(&a.render) || a.vtu_series || a.problem ||
                      a.s.methods.n > 1 || a.s.sets.n > 0))
        return cli_usage(cmd, "--backend petsc: solve SCENE only, with one method, and no --set, --problem, --png or "
                         "--vtu-series");
    cx_options opt;
    cx_options_default(&opt);
    opt.tol = a.s.tol;
    opt.max_iter = a.s.max_iter;
    opt.own_stop = a.s.own_stop;
    opt.time_limit = a.s.time_limit;
    int to_stdout = cli_render_stdout_users(&a.render);
    FILE *summary = to_stdout ? stderr : stdout;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = solve_on_sigint;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);

    if (a.problem) {   /* no mesh: nothing to draw or write it with */
        if (a.render.png || a.render.vtu || a.vtu_series || a.baseline || a.render.plot >= 0 || strcmp(cmd, "solve"))
            return cli_fail(cmd, "--problem: --png, --vtu, --vtu-series, --plot and --baseline need the mesh, "
                            "which a problem file has not");
        return cli_solve_problem(cmd, a.problem, &a.s, &opt, a.json, a.quiet);
    }
    double t0 = cx_clock_now();
    cx_scene sc;
    if (cx_scene_open(scene, &sc, &d))
        return cli_fail(cmd, d.msg);

    /* friction and a named method with its parameters are checked before
     * anything is built; --method auto needs the problem */
    int law = a.s.friction >= 0 ? a.s.friction : (int)sc.friction;
    if (!(sc.laws & (1u << law))) {
        char laws[32] = "";
        for (int k = 0; k < 3; k++)
            if (sc.laws & (1u << k))
                snprintf(laws + strlen(laws), sizeof laws - strlen(laws), "%s%s", laws[0] ? ", " : "",
                         cx_friction_name((cx_friction)k));
        cx_diag_set(&d, CX_EINVAL, "--friction %s: scene '%s' allows only %s (its 'laws')",
                    cx_friction_name((cx_friction)law), sc.id, laws);
        return cli_fail(cmd, d.msg);
    }
    double F = sc.F, slip = sc.slip_bound;
    if (!isnan(a.s.F))
        F = a.s.F;
    if (!isnan(a.s.slip))
        slip = a.s.slip;
    int is_auto = !a.s.method || strcmp(a.s.method, "auto") == 0;
    const cx_method *m = NULL;
    cx_param_values pv;
    if (!is_auto && !a.backend) {
        m = cx_method_find(a.s.method);
        if (cli_method_params(m, "", &a.s, &pv, &d))
            return cli_usage(cmd, d.msg);   /* --set names a key or a value the method has not */
    }

    cx_problem *p = NULL;
    cli_progress_start();   /* on a terminal: assembly, then the session's setup */
    /* --backend petsc assembles its own K from the mesh and reads no
     * product with the serial one (its kkt error takes K u from its
     * residual): the scene is built without it, unless --baseline
     * factorises it (hertz 1024: 0.35 GB a rank, half the build's time) */
    unsigned build_flags = a.backend && !a.baseline ? CX_SCENE_BUILD_NO_K : 0u;
    if (cx_scene_build_flags(&sc, a.s.level, build_flags, &p, NULL, &d))
        return cli_fail(cmd, d.msg);
    double t_assemble = cx_clock_now() - t0;
    if (cli_render_check(&a.render, p->dim, &d)) {
        cx_problem_destroy(&p);
        return cli_fail(cmd, d.msg);
    }
    /* the scene's friction with the command line's law and values: the
     * session's, set once it exists */
    cx_friction_state fr = {(cx_friction)law, slip, F, NULL, NULL};
    /* a scene's several contacts keep their own values unless --F / --slip set them all */
    if (isnan(a.s.F))
        fr.Fi = p->contact.Fpt;
    if (isnan(a.s.slip))
        fr.s = p->contact.spt;
    if (cx_friction_check(&fr, 0, &d)) {
        cx_problem_destroy(&p);
        return cli_fail(cmd, d.msg);
    }
    if (a.backend) {   /* cli/solve_petsc.c */
        cli_petsc_args pa = {a.s.method, a.s.level, a.json, a.quiet, a.baseline, a.render.vtu, t_assemble};
        int code = cli_solve_petsc(cmd, &sc, p, &fr, &opt, &pa, summary);
        cx_problem_destroy(&p);
        return code;
    }
    if (is_auto) {
        const char *auto_sets;
        m = cx_method_find(cx_scene_auto_method(&sc, a.s.level, p, (cx_friction)law, &auto_sets));
        if (!m || cli_method_params(m, auto_sets, &a.s, &pv, &d)) {
            cx_problem_destroy(&p);
            return m ? cli_usage(cmd, d.msg) : cli_fail(cmd, "--method auto: no method");
        }
    }

    cx_history history = {0};
    cx_session *s = NULL;
    if (cx_session_create(&s, &p, &d)) {
        cx_problem_destroy(&p);
        return cli_fail(cmd, d.msg);
    }
    int code = CX_EXIT_ERROR;
    if (cx_session_set_friction(s, &fr, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    if (cx_session_set_method(s, m, &pv, &opt, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    const cx_problem *cp = cx_session_problem(s);
    if (a.vtu_series && mkdir(a.vtu_series, 0777) != 0 && errno != EEXIST) {
        cx_diag_set(&d, CX_EIO, "--vtu-series %s: %s", a.vtu_series, strerror(errno));
        cli_fail(cmd, d.msg);
        goto done;
    }
    /* the baseline before the run, as bench times it: both then start
     * from the state the assembly left, whatever the run frees or keeps */
    double t_base = 0, t_base_wall = 0;
    if (a.baseline) {
        double tb0 = cx_clock_now();
        cli_progress_start();
        int base_failed = cx_problem_baseline(cp, &t_base, &d);
        cli_progress_stop();
        t_base_wall = cx_clock_now() - tb0;
        if (base_failed) {
            cli_fail(cmd, d.msg);
            goto done;
        }
    }
    cx_diag series_d = {0};
    cli_watch w = {a.json || a.quiet, summary, a.json ? &history : NULL, a.vtu_series, s, &sc,
                   a.s.level, 0, &series_d};
    char title[CX_SCENE_NAMELEN + 32];
    snprintf(title, sizeof title, "%s level %d", sc.id, a.s.level > 0 ? a.s.level : sc.level);
    if (cli_solve_run(s, title, is_auto, &w, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    if (a.vtu_series && (series_d.msg[0] || solve_series_pvd(&w, &series_d))) {
        cli_fail(cmd, series_d.msg);
        goto done;
    }
    double t_total = cx_clock_now() - t0 - t_base_wall;
    cx_result *res = NULL;
    if (cx_result_from_session(&res, s, &sc, a.s.level, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    res->run.time.assemble = t_assemble;
    res->run.time.total = t_total;
    res->run.has_baseline = a.baseline;
    res->run.time.baseline = t_base;
    res->run.method_auto = is_auto;
    if (a.json)
        cx_result_write_json_history(res, &history, stdout);
    else
        cli_solve_write_text(res, summary);
    const cx_schur *S = a.baseline && !a.json ? cx_session_schur_built(s) : NULL;
    if (S) {   /* the orderings' predicted fill, each that was analysed */
        const cx_schur_ordering *o = cx_schur_ordering_of(S);
        static const char *const what[] = {[CX_ORDER_CAMD] = "CAMD", [CX_ORDER_METIS] = "METIS",
                                           [CX_ORDER_AMD] = "AMD then contact last"};
        const int shown[] = {CX_ORDER_CAMD, o->tried_amd ? CX_ORDER_AMD : -1, o->tried ? CX_ORDER_METIS : -1};
        fprintf(summary, "         contact-last ordering:");
        for (int k = 0, sep = 0; k < 3; k++)
            if (shown[k] >= 0) {
                int j = shown[k];
                fprintf(summary, "%s %s%s %.3g nnz(L) %.3g Gflop %.3f s", sep++ ? ";" : "", what[j],
                        j == (int)o->chosen ? " (chosen)" : "", o->lnz[j], o->flops[j] * 1e-9, o->seconds[j]);
            }
        fprintf(summary, "\n");
        /* where the reduction's time went (CPU seconds of the process) */
        fprintf(summary, "         reduction CPU (all threads): orderings %.3f s, analysis %.3f s, factorisation %.3f s, S %.3f s\n",
                o->cpu_ordering, o->cpu_symbolic, o->cpu_numeric, o->cpu_form);
    }
    code = cli_exit_status(res->run.reason);
    if (cli_render_outputs(&a.render, &sc, s, res, a.json, &d))
        code = cli_fail(cmd, d.msg);
    cx_result_destroy(&res);
done:
    cx_history_clear(&history);
    cx_session_destroy(&s);
    /* a summary or JSON lost on a full disk is an error, not a result */
    if (code != CX_EXIT_ERROR && cx_outfile_close_stdout(&d))
        code = cli_fail(cmd, d.msg);
    return code;
}
