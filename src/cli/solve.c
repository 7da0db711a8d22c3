/* signorini solve SCENE [options]: build, solve, report (text or JSON). */
#include "cli/cli.h"
#include "out/out.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static const char solve_usage[] =
    "usage: signorini solve SCENE [options]\n"
    "\n"
    "SCENE is a scene id (see 'signorini list') or a path to an .ini file.\n"
    "\n"
    "  --method ID|auto     solver (default auto: the fastest measured for the scene\n"
    "                       and law, or a rule from the problem; see the README)\n"
    "  --friction LAW       none | tresca | coulomb (default: the scene's)\n"
    "  --F VALUE            Coulomb coefficient (default: the scene's)\n"
    "  --slip VALUE         Tresca slip bound, a traction (default: the scene's)\n"
    "  --level L            mesh level (default: the scene's)\n"
    "  --tol T              stop when the kkt error is below T (default 1e-10)\n"
    "  --max-iter N         iteration limit (default 500)\n"
    "  --stop kkt|own       stop on the kkt error only, or also on the method's\n"
    "                       own criterion (default own; a run it stops above the\n"
    "                       tolerance has not converged)\n"
    "  --time-limit S       stop the run after S seconds (checked inside long steps)\n"
    "  --set KEY=VALUE      a method parameter (repeatable; see 'signorini list')\n"
    "  --json               print one JSON object on stdout instead of the summary\n"
    "  --baseline           also time one factorisation + solve of K alone\n"
    "  --quiet              no per-iteration lines\n"
    "  --png FILE           also draw the solution (see 'signorini render --help'\n"
    "                       for --field, --scale, --size, --view, --edges)\n"
    "  --vtu FILE           also write a VTK XML UnstructuredGrid for ParaView\n"
    "                       ('-' for standard output: the summary goes to stderr)\n"
    "\n"
    "Exit status: 0 converged (kkt error <= tol), 1 error, 2 usage, 3 not converged\n"
    "(stopped by its own criterion above tol, stalled, iteration or time limit,\n"
    "breakdown, overflow or NaN), 130 interrupted (Ctrl-C: the partial result is\n"
    "printed as cancelled).\n";

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

enum { OPT_METHOD, OPT_FRICTION, OPT_F, OPT_SLIP, OPT_LEVEL, OPT_TOL, OPT_MAXIT, OPT_STOP, OPT_SET,
       OPT_TIME };
static const char *const solve_value_opts[] = {"--method", "--friction", "--F", "--slip", "--level",
                                               "--tol", "--max-iter", "--stop", "--set", "--time-limit",
                                               NULL};

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
        case OPT_TIME:
            if (cx_parse_double(v, &a->opt.time_limit) || !(a->opt.time_limit > 0) ||
                !isfinite(a->opt.time_limit))
                return cx_diag_set(d, CX_EINVAL, "--time-limit '%s': expected a positive number of seconds", v);
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

typedef struct {
    int quiet;
    FILE *out;
} solve_watch;

static int solve_print_step(void *ctx, const cx_session *s, const cx_iterate *it)
{
    (void)s;
    const solve_watch *w = ctx;
    char kkt[32], own[32];
    if (!w->quiet)
        fprintf(w->out, "%6d  %10s  %10s  %7d %6d %6d %7d  %9.4f\n", it->iter,
                solve_num(kkt, sizeof kkt, "%.3e", it->kkt), solve_num(own, sizeof own, "%.3e", it->own),
                it->ncontact + it->nstick + it->nslip, it->nstick, it->nslip, it->nchanged, it->time);
    return 0;
}

static void solve_write_text(const cx_result *r, FILE *out)
{
    const cx_run_record *run = &r->run;
    char outcome[CX_DIAG_LEN + 160], b1[32], b2[32], b3[32];
    cx_reason_format(run->reason, run->iterations, run->kkt, run->tol, run->message, outcome,
                     sizeof outcome);
    fprintf(out, "%s\n", outcome);
    fprintf(out, "contact: %d of %d points (%d stick, %d slip)\n",
            run->ncontact + run->nstick + run->nslip, r->m, run->nstick, run->nslip);
    const char *axes = "xyz";
    fprintf(out, "force:   applied");
    for (int k = 0; k < r->dim; k++)
        fprintf(out, " %c %s", axes[k], solve_num(b1, sizeof b1, "%.6g", r->f_applied[k]));
    fprintf(out, ";  contact");
    for (int k = 0; k < r->dim; k++)
        fprintf(out, " %c %s", axes[k], solve_num(b1, sizeof b1, "%.6g", r->f_contact[k]));
    fprintf(out, "\n");
    if (run->has_pressure_error)
        fprintf(out, "pressure vs Hertz: L2 error %s (%s %%), half-width b = %s\n",
                solve_num(b1, sizeof b1, "%.4g", run->pressure_error_abs),
                solve_num(b2, sizeof b2, "%.2f", 100 * run->pressure_error_rel),
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

/* The method's parameters: its defaults, then auto_sets ("key=value ...",
 * --method auto's choice), then --set. */
static int solve_method_params(const cx_method *m, const char *auto_sets, const solve_args *a,
                               cx_param_values *pv, cx_diag *d)
{
    cx_param_default(pv, m->params);
    char owner[64];
    snprintf(owner, sizeof owner, "method '%s'", m->id);
    char buf[256];
    snprintf(buf, sizeof buf, "%s", auto_sets);
    for (char *save = NULL, *tok = strtok_r(buf, " ", &save); tok; tok = strtok_r(NULL, " ", &save))
        CX_TRY(cx_param_set_pair(pv, tok, owner, d));
    for (int k = 0; k < a->nsets; k++)
        CX_TRY(cx_param_set_pair(pv, a->sets[k], owner, d));
    return CX_OK;
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

    /* friction and a named method with its parameters are checked before
     * anything is built; --method auto needs the problem */
    int law = sc.friction;
    if (a.friction && (law = cx_friction_from_name(a.friction)) < 0) {
        cx_diag_set(&d, CX_EINVAL, "--friction '%s': expected none, tresca or coulomb", a.friction);
        return cli_fail(cmd, d.msg);
    }
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
    if (a.F && (cx_parse_double(a.F, &F) || F < 0)) {
        cx_diag_set(&d, CX_EINVAL, "--F '%s': expected a non-negative number", a.F);
        return cli_fail(cmd, d.msg);
    }
    if (a.slip && (cx_parse_double(a.slip, &slip) || slip < 0)) {
        cx_diag_set(&d, CX_EINVAL, "--slip '%s': expected a non-negative number", a.slip);
        return cli_fail(cmd, d.msg);
    }
    int is_auto = !a.method || strcmp(a.method, "auto") == 0;
    const cx_method *m = NULL;
    cx_param_values pv;
    if (!is_auto) {
        if (!(m = cx_method_find(a.method))) {
            cx_diag_set(&d, CX_EINVAL, "--method: unknown method '%s' (see 'signorini list')", a.method);
            return cli_fail(cmd, d.msg);
        }
        if (solve_method_params(m, "", &a, &pv, &d))
            return cli_fail(cmd, d.msg);
    }

    cx_problem *p = NULL;
    if (cx_scene_build(&sc, a.level, &p, NULL, &d))
        return cli_fail(cmd, d.msg);
    double t_assemble = cx_clock_now() - t0;
    if (cli_render_check(&a.render, p->dim, &d)) {
        cx_problem_destroy(&p);
        return cli_fail(cmd, d.msg);
    }
    /* the scene's friction with the command line's law and values: the
     * session's, set once it exists */
    cx_friction_state fr = {(cx_friction)law, slip, F, NULL, NULL};
    if (cx_friction_check(&fr, 0, &d)) {
        cx_problem_destroy(&p);
        return cli_fail(cmd, d.msg);
    }
    if (is_auto) {
        const char *auto_sets;
        m = cx_method_find(cx_scene_auto_method(&sc, a.level, p, (cx_friction)law, &auto_sets));
        if (!m || solve_method_params(m, auto_sets, &a, &pv, &d)) {
            cx_problem_destroy(&p);
            return cli_fail(cmd, m ? d.msg : "--method auto: no method");
        }
    }

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
    if (cx_session_set_method(s, m, &pv, &a.opt, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    const cx_problem *cp = cx_session_problem(s);
    solve_running = s;   /* from here Ctrl-C cancels the run (the header may be seen first) */
    if (!a.json && !a.quiet) {
        fprintf(summary, "%s level %d: %dD, %d dofs, %d contact points; %s%s, friction %s\n", sc.id,
                a.level > 0 ? a.level : sc.level, cp->dim, cp->n, cp->m, m->id, is_auto ? " (auto)" : "",
                cx_friction_name(cx_session_friction(s)->law));
        fprintf(summary, "  iter  kkt error   own crit.   contact  stick   slip changed   time (s)\n");
        fflush(summary);   /* the run may be long: show where it is */
    }
    solve_watch w = {a.json || a.quiet, summary};
    int solved = cx_solver_solve(s, solve_print_step, &w, &d);
    solve_running = NULL;
    if (solved) {
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
    res->run.method_auto = is_auto;
    if (a.json)
        cx_result_write_json(res, stdout);
    else
        solve_write_text(res, summary);
    code = res->run.converged                   ? CX_EXIT_OK
           : res->run.reason == CX_CANCELLED ? CX_EXIT_INTERRUPTED
                                               : CX_EXIT_NOT_CONVERGED;
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
