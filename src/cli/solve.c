/* signorini solve SCENE [options]: build, solve, report (text or JSON). */
#include "cli/cli.h"
#include "out/out.h"

#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static const char solve_usage[] =
    "usage: signorini solve SCENE [options]\n"
    "\n"
    "SCENE is a scene id (see 'signorini list') or a path to an .ini file.\n"
    "\n"
    "  --method ID          solver (default: the scene's first method)\n"
    "  --friction LAW       none | tresca | coulomb (default: the scene's)\n"
    "  --F VALUE            Coulomb coefficient (default: the scene's)\n"
    "  --slip VALUE         Tresca slip bound, a traction (default: the scene's)\n"
    "  --level L            mesh level (default: the scene's)\n"
    "  --tol T              stop when the kkt error is below T (default 1e-10)\n"
    "  --max-iter N         iteration limit (default 500)\n"
    "  --stop kkt|own       stop on the kkt error only, or also on the method's\n"
    "                       own criterion (default own)\n"
    "  --set KEY=VALUE      a method parameter (repeatable; see 'signorini list')\n"
    "  --json               print one JSON object on stdout instead of the summary\n"
    "  --baseline           also time one factorisation + solve of K alone\n"
    "  --quiet              no per-iteration lines\n"
    "  --png FILE           also draw the solution (see 'signorini render --help'\n"
    "                       for --field, --scale, --size, --view, --edges)\n"
    "  --vtu FILE           also write a VTK XML UnstructuredGrid for ParaView\n"
    "                       ('-' for standard output: the summary goes to stderr)\n"
    "\n"
    "Exit status: 0 converged, 1 error, 3 not converged.\n";

typedef struct {
    const char *scene;
    const char *method;
    const char *friction;
    const char *F, *slip;
    int level;
    cx_options opt;
    const char *sets[CX_PARAM_MAX];
    int nsets;
    int json, baseline, quiet;
    cli_render_args render;   /* --png, --vtu and the drawing options (cli/render.c) */
} solve_args;

enum { OPT_METHOD, OPT_FRICTION, OPT_F, OPT_SLIP, OPT_LEVEL, OPT_TOL, OPT_MAXIT, OPT_STOP, OPT_SET };
static const char *const solve_value_opts[] = {"--method", "--friction", "--F", "--slip", "--level",
                                               "--tol", "--max-iter", "--stop", "--set", NULL};

static int solve_parse(int argc, char **argv, solve_args *a, cx_diag *d)
{
    memset(a, 0, sizeof *a);
    cx_options_default(&a->opt);
    cli_render_args_init(&a->render);
    for (int i = 1; i < argc; i++) {
        int r = cli_render_option(argc, argv, &i, &a->render, d);
        if (r < 0)
            return CX_EINVAL;
        if (r)
            continue;
        if (strcmp(argv[i], "--json") == 0) { a->json = 1; continue; }
        if (strcmp(argv[i], "--baseline") == 0) { a->baseline = 1; continue; }
        if (strcmp(argv[i], "--quiet") == 0) { a->quiet = 1; continue; }
        const char *v = NULL;
        int which = -1;
        for (int k = 0; solve_value_opts[k] && which < 0; k++) {
            int r = cx_arg_option(argc, argv, &i, solve_value_opts[k], &v, d);
            if (r < 0)
                return CX_EINVAL;
            if (r)
                which = k;
        }
        long n;
        switch (which) {
        case OPT_METHOD: a->method = v; break;
        case OPT_FRICTION: a->friction = v; break;
        case OPT_F: a->F = v; break;
        case OPT_SLIP: a->slip = v; break;
        case OPT_LEVEL:
            CX_TRY(cx_arg_level(v, &a->level, d));
            break;
        case OPT_TOL:
            if (cx_parse_double(v, &a->opt.tol) || !(a->opt.tol > 0))
                return cx_diag_set(d, CX_EINVAL, "--tol '%s': expected a positive number", v);
            break;
        case OPT_MAXIT:
            if (cx_parse_int(v, 1, 100000000, &n))
                return cx_diag_set(d, CX_EINVAL, "--max-iter '%s': expected a positive integer", v);
            a->opt.max_iter = (int)n;
            break;
        case OPT_STOP:
            if ((n = cx_parse_choice(v, "kkt|own")) < 0)
                return cx_diag_set(d, CX_EINVAL, "--stop '%s': expected kkt or own", v);
            a->opt.own_stop = n == 1;
            break;
        case OPT_SET:
            if (a->nsets == CX_PARAM_MAX)
                return cx_diag_set(d, CX_EINVAL, "--set: too many parameters");
            a->sets[a->nsets++] = v;
            break;
        default:
            if (argv[i][0] == '-' && argv[i][1] != '\0')
                return cx_diag_set(d, CX_EINVAL, "unknown option '%s' (see 'signorini solve --help')", argv[i]);
            if (a->scene)
                return cx_diag_set(d, CX_EINVAL, "unexpected argument '%s': one scene only", argv[i]);
            a->scene = argv[i];
        }
    }
    if (!a->scene)
        return cx_diag_set(d, CX_EINVAL, "missing SCENE (see 'signorini solve --help')");
    return CX_OK;
}

typedef struct {
    int quiet;
    FILE *out;
} solve_watch;

static int solve_print_step(void *ctx, const cx_session *s, const cx_iterate *it)
{
    (void)s;
    const solve_watch *w = ctx;
    if (!w->quiet)
        fprintf(w->out, "%6d  %10.3e  %10.3e  %7d %6d %6d %7d  %9.4f\n", it->iter, it->kkt, it->own,
               it->ncontact + it->nstick + it->nslip, it->nstick, it->nslip, it->nchanged, it->time);
    return 0;
}

static void solve_write_text(const cx_result *r, FILE *out)
{
    const cx_run_record *run = &r->run;
    const char *msg = run->message;
    fprintf(out, "%s after %d iterations: kkt error %.3e%s%s\n", cx_reason_str(run->reason),
            run->iterations, run->kkt, msg[0] ? "\n  " : "", msg);
    fprintf(out, "contact: %d of %d points (%d stick, %d slip)\n",
            run->ncontact + run->nstick + run->nslip, r->m, run->nstick, run->nslip);
    const char *axes = "xyz";
    fprintf(out, "force:   applied");
    for (int k = 0; k < r->dim; k++)
        fprintf(out, " %c %.6g", axes[k], r->f_applied[k]);
    fprintf(out, ";  contact");
    for (int k = 0; k < r->dim; k++)
        fprintf(out, " %c %.6g", axes[k], r->f_contact[k]);
    fprintf(out, "\n");
    if (run->has_pressure_error)
        fprintf(out, "pressure vs Hertz: L2 error %.4g (%.2f %%), half-width b = %.4g\n",
                run->pressure_error_abs, 100 * run->pressure_error_rel, run->hertz_halfwidth);
    fprintf(out, "time:    assemble %.3f s, setup %.3f s, solve %.3f s, total %.3f s\n", run->time.assemble,
            run->time.setup, run->time.solve, run->time.total);
    if (run->has_baseline)
        fprintf(out, "         baseline (factorise + solve K) %.3f s; (setup + solve) / baseline = %.2f\n",
                run->time.baseline,
                run->time.baseline > 0 ? (run->time.setup + run->time.solve) / run->time.baseline : 0);
    fprintf(out, "work:    %ld factorisations, %ld solves, %ld products with K\n",
            run->counters.factorizations, run->counters.solves, run->counters.matvecs);
}

/* Ctrl-C: remove a temporary output file being written, then stop. */
static void solve_on_sigint(int sig)
{
    (void)sig;
    cx_outfile_abandon_pending();
    _exit(CX_EXIT_INTERRUPTED);
}

int cli_solve(int argc, char **argv)
{
    return cli_solve_as("solve", argc, argv);
}

int cli_solve_as(const char *cmd, int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            fputs(solve_usage, stdout);
            return CX_EXIT_OK;
        }
    cx_diag d;
    cx_diag_clear(&d);
    solve_args a;
    if (solve_parse(argc, argv, &a, &d))
        return cli_fail(cmd, d.msg);
    /* the summary (or JSON) and a file on standard output cannot share it */
    int to_stdout = cli_render_stdout_users(&a.render);
    if (to_stdout + a.json > 1)
        return cli_fail(cmd, "--json, --png - and --vtu -: only one can go to standard output");
    FILE *summary = to_stdout ? stderr : stdout;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = solve_on_sigint;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);

    double t0 = cx_clock_now();
    cx_scene sc;
    if (cx_scene_open(a.scene, &sc, &d))
        return cli_fail(cmd, d.msg);

    /* method, friction and parameters are checked before anything is built */
    const char *mid = a.method ? a.method : (sc.nmethods > 0 ? sc.methods[0] : "ssn-tresca");
    const cx_method *m = cx_method_find(mid);
    if (!m) {
        cx_diag_set(&d, CX_EINVAL, "--method: unknown method '%s' (see 'signorini list')", mid);
        return cli_fail(cmd, d.msg);
    }
    cx_param_values pv;
    cx_param_default(&pv, m->params);
    char owner[64];
    snprintf(owner, sizeof owner, "method '%s'", m->id);
    for (int k = 0; k < a.nsets; k++)
        if (cx_param_set_pair(&pv, a.sets[k], owner, &d))
            return cli_fail(cmd, d.msg);
    int law = sc.friction;
    if (a.friction && (law = cx_friction_from_name(a.friction)) < 0) {
        cx_diag_set(&d, CX_EINVAL, "--friction '%s': expected none, tresca or coulomb", a.friction);
        return cli_fail(cmd, d.msg);
    }
    double F = sc.F, slip = sc.slip_bound;
    if (a.F && (cx_parse_double(a.F, &F) || F < 0)) {
        cx_diag_set(&d, CX_EINVAL, "--F '%s': expected a non-negative number", a.F);
        return cli_fail(cmd, d.msg);
    }
    if (a.slip && (cx_parse_double(a.slip, &slip) || slip < 0)) {
        cx_diag_set(&d, CX_EINVAL, "--slip '%s': expected a non-negative number", a.slip);
        return cli_fail(cmd, d.msg);
    }

    cx_problem *p = NULL;
    if (cx_scene_build(&sc, a.level, &p, &d))
        return cli_fail(cmd, d.msg);
    double t_assemble = cx_clock_now() - t0;
    if (cli_render_check(&a.render, p->dim, &d)) {
        cx_problem_destroy(&p);
        return cli_fail(cmd, d.msg);
    }
    p->F = F;
    p->slip_bound = slip;
    if (cx_problem_set_friction(p, (cx_friction)law, law == CX_FRICTION_COULOMB ? F : slip, &d)) {
        cx_problem_destroy(&p);
        return cli_fail(cmd, d.msg);
    }

    cx_session *s = NULL;
    if (cx_session_create(&s, &p, &d)) {
        cx_problem_destroy(&p);
        return cli_fail(cmd, d.msg);
    }
    int code = CX_EXIT_ERROR;
    if (cx_session_set_method(s, m, &pv, &a.opt, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    const cx_problem *cp = cx_session_problem(s);
    if (!a.json && !a.quiet) {
        fprintf(summary, "%s level %d: %dD, %d dofs, %d contact points; %s, friction %s\n", sc.id,
                a.level > 0 ? a.level : sc.level, cp->dim, cp->n, cp->m, m->id,
                cx_friction_name(cp->friction));
        fprintf(summary, "  iter  kkt error   own crit.   contact  stick   slip changed   time (s)\n");
    }
    solve_watch w = {a.json || a.quiet, summary};
    if (cx_solver_solve(s, solve_print_step, &w, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    double t_total = cx_clock_now() - t0;
    double t_base = 0;
    if (a.baseline && cx_problem_baseline(cp, &t_base, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    cx_result *res = NULL;
    if (cx_result_from_session(&res, s, &sc, a.level, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    res->run.time.assemble = t_assemble;
    res->run.time.total = t_total;
    res->run.has_baseline = a.baseline;
    res->run.time.baseline = t_base;
    if (a.json)
        cx_result_write_json(res, stdout);
    else
        solve_write_text(res, summary);
    code = res->run.converged ? CX_EXIT_OK : CX_EXIT_NOT_CONVERGED;
    if (cli_render_outputs(&a.render, &sc, s, res, a.json, &d))
        code = cli_fail(cmd, d.msg);
    cx_result_destroy(&res);
done:
    cx_session_destroy(&s);
    /* a summary or JSON lost on a full disk is an error, not a result */
    if (code != CX_EXIT_ERROR && cx_outfile_close_stdout(&d))
        code = cli_fail(cmd, d.msg);
    return code;
}
