/* signorini solve SCENE [options]: build, solve, report (text or JSON). */
#include "cli/cli.h"
#include "out/json.h"
#include "cx_config.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

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

/* Resultant force of the contact on the body: -(N' lN + T' lT) per component. */
static void solve_contact_force(const cx_problem *p, const cx_iterate *it, double force[3])
{
    const cx_contact_set *c = &p->contact;
    int dim = p->dim, dt = dim - 1;
    force[0] = force[1] = force[2] = 0;
    for (int i = 0; i < p->m; i++)
        for (int k = 0; k < dim; k++) {
            force[k] -= it->lN[i] * c->normal[dim * i + k];
            if (p->friction != CX_FRICTION_NONE)
                for (int r = 0; r < dt; r++)
                    force[k] -= it->lT[dt * i + r] * c->tangent[dim * (dt * i + r) + k];
        }
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
} solve_watch;

static int solve_print_step(void *ctx, const cx_session *s, const cx_iterate *it)
{
    (void)s;
    const solve_watch *w = ctx;
    char kkt[32], own[32];
    if (!w->quiet)
        printf("%6d  %10s  %10s  %7d %6d %6d %7d  %9.4f\n", it->iter, solve_num(kkt, sizeof kkt, "%.3e", it->kkt),
               solve_num(own, sizeof own, "%.3e", it->own), it->ncontact + it->nstick + it->nslip, it->nstick,
               it->nslip, it->nchanged, it->time);
    return 0;
}

/* Ctrl-C: the handler sets the running session's cancel flag (an atomic
 * store, safe in a handler); the run ends at the next check, within a
 * fraction of a second, and its partial result is printed. */
static cx_session *volatile solve_running;

static void solve_on_sigint(int sig)
{
    (void)sig;
    cx_session *s = solve_running;
    if (s)
        cx_session_cancel(s);
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

static void solve_write_json(const solve_args *a, const cx_scene *sc, const cx_session *s,
                             double t_assemble, double t_total, double t_base, int has_p,
                             double p_abs, double p_rel, const char *msg)
{
    const cx_problem *p = cx_session_problem(s);
    const cx_iterate *it = cx_session_iterate(s);
    const cx_method *m = cx_session_method(s);
    const cx_param_values *pv = cx_session_params(s);
    double fc[3];
    solve_contact_force(p, it, fc);
    cx_json j;
    cx_json_init(&j, stdout);
    cx_json_object(&j, NULL);
    cx_json_str(&j, "scene", sc->id);
    cx_json_int(&j, "level", a->level > 0 ? a->level : sc->level);
    cx_json_str(&j, "method", m->id);
    cx_json_bool(&j, "method_auto", !a->method || strcmp(a->method, "auto") == 0);
    cx_json_str(&j, "friction", cx_friction_name(p->friction));
    if (p->friction == CX_FRICTION_TRESCA)
        cx_json_num(&j, "slip_bound", p->slip_bound);
    if (p->friction == CX_FRICTION_COULOMB)
        cx_json_num(&j, "F", p->F);
    cx_json_int(&j, "dim", p->dim);
    cx_json_int(&j, "dofs", p->n);
    cx_json_int(&j, "contact_points", p->m);
    cx_json_int(&j, "iterations", it->iter);
    char outcome[CX_DIAG_LEN + 160];
    cx_json_bool(&j, "converged", it->reason == CX_CONVERGED_KKT);
    cx_json_str(&j, "reason", cx_reason_id(it->reason));
    cx_json_str(&j, "reason_text", cx_session_outcome(s, outcome, sizeof outcome));
    if (msg && msg[0])
        cx_json_str(&j, "message", msg);
    cx_json_num(&j, "kkt_error", it->kkt);
    cx_json_object(&j, "kkt_parts");
    cx_json_num(&j, "equilibrium", it->kkt_parts.equilibrium);
    cx_json_num(&j, "contact", it->kkt_parts.contact);
    cx_json_num(&j, "friction", it->kkt_parts.friction);
    cx_json_end_object(&j);
    cx_json_num(&j, "own_criterion", it->own);
    cx_json_num(&j, "tol", cx_session_options(s)->tol);
    cx_json_object(&j, "time");
    cx_json_num(&j, "assemble", t_assemble);
    cx_json_num(&j, "setup", it->init_time);
    cx_json_num(&j, "solve", it->time - it->init_time);
    cx_json_num(&j, "total", t_total);
    if (a->baseline)
        cx_json_num(&j, "linear_solve", t_base);
    cx_json_end_object(&j);
    cx_json_object(&j, "counts");
    cx_json_int(&j, "factorizations", it->counters.factorizations);
    cx_json_int(&j, "solves", it->counters.solves);
    cx_json_int(&j, "matvecs", it->counters.matvecs);
    cx_json_int(&j, "dual_products", it->counters.dual_products);
    cx_json_int(&j, "inner_iterations", it->inner_total);
    cx_json_end_object(&j);
    cx_json_int(&j, "active", it->ncontact + it->nstick + it->nslip);
    cx_json_int(&j, "stick", it->nstick);
    cx_json_int(&j, "slip", it->nslip);
    cx_json_int(&j, "free", it->nfree);
    cx_json_object(&j, "force");
    cx_json_vec(&j, "applied", p->f_applied, p->dim);
    cx_json_vec(&j, "contact", fc, p->dim);
    cx_json_end_object(&j);
    cx_json_object(&j, "params");
    for (int k = 0; k < pv->n; k++) {
        char buf[64];
        const cx_param *q = &pv->table[k];
        if (q->type == CX_PARAM_REAL && !isnan(pv->num[k]))
            cx_json_num(&j, q->key, pv->num[k]);
        else if (q->type == CX_PARAM_INT)
            cx_json_int(&j, q->key, (long)pv->num[k]);
        else if (q->type == CX_PARAM_BOOL)
            cx_json_bool(&j, q->key, pv->num[k] != 0);
        else {
            cx_param_format(pv, k, buf, sizeof buf);
            cx_json_str(&j, q->key, buf);
        }
    }
    cx_json_end_object(&j);
    if (has_p) {
        cx_json_object(&j, "pressure_error_l2");
        cx_json_num(&j, "abs", p_abs);
        cx_json_num(&j, "rel", p_rel);
        cx_json_end_object(&j);
    }
    cx_json_str(&j, "version", CX_VERSION);
    cx_json_end_object(&j);
}

static void solve_write_text(const cx_scene *sc, const cx_session *s, double t_assemble,
                             double t_total, int baseline, double t_base, int has_p,
                             double p_abs, double p_rel)
{
    const cx_problem *p = cx_session_problem(s);
    const cx_iterate *it = cx_session_iterate(s);
    double fc[3];
    char b1[32], b2[32], b3[32];
    solve_contact_force(p, it, fc);
    char outcome[CX_DIAG_LEN + 160];
    printf("%s\n", cx_session_outcome(s, outcome, sizeof outcome));
    printf("contact: %d of %d points (%d stick, %d slip)\n", it->ncontact + it->nstick + it->nslip,
           p->m, it->nstick, it->nslip);
    const char *axes = "xyz";
    printf("force:   applied");
    for (int k = 0; k < p->dim; k++)
        printf(" %c %s", axes[k], solve_num(b1, sizeof b1, "%.6g", p->f_applied[k]));
    printf(";  contact");
    for (int k = 0; k < p->dim; k++)
        printf(" %c %s", axes[k], solve_num(b1, sizeof b1, "%.6g", fc[k]));
    printf("\n");
    if (has_p)
        printf("pressure vs Hertz: L2 error %s (%s %%), half-width b = %s\n",
               solve_num(b1, sizeof b1, "%.4g", p_abs), solve_num(b2, sizeof b2, "%.2f", 100 * p_rel),
               solve_num(b3, sizeof b3, "%.4g", cx_scene_hertz_halfwidth(sc)));
    printf("time:    assemble %.3f s, setup %.3f s, solve %.3f s, total %.3f s\n", t_assemble,
           it->init_time, it->time - it->init_time, t_total);
    if (baseline)
        printf("         baseline (factorise + solve K) %.3f s; (setup + solve) / baseline = %.2f\n", t_base,
               t_base > 0 ? (it->time) / t_base : 0);
    printf("work:    %ld factorisations, %ld solves, %ld products with K\n", it->counters.factorizations,
           it->counters.solves, it->counters.matvecs);
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
    if (cx_session_set_method(s, m, &pv, &a.opt, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    const cx_problem *cp = cx_session_problem(s);
    struct sigaction sa, old_sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = solve_on_sigint;
    sigemptyset(&sa.sa_mask);
    solve_running = s;
    sigaction(SIGINT, &sa, &old_sa);
    if (!a.json && !a.quiet) {
        printf("%s level %d: %dD, %d dofs, %d contact points; %s%s, friction %s\n", sc.id,
               a.level > 0 ? a.level : sc.level, cp->dim, cp->n, cp->m, m->id, is_auto ? " (auto)" : "",
               cx_friction_name(cp->friction));
        printf("  iter  kkt error   own crit.   contact  stick   slip changed   time (s)\n");
        fflush(stdout);   /* the run may be long: show where it is */
    }
    solve_watch w = {a.json || a.quiet};
    int solved = cx_solver_solve(s, solve_print_step, &w, &d);
    sigaction(SIGINT, &old_sa, NULL);
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
    const cx_iterate *it = cx_session_iterate(s);
    double p_abs = 0, p_rel = 0;
    int has_p = cx_scene_pressure_error(&sc, cp, it->lN, &p_abs, &p_rel) == CX_OK;
    const char *msg = cx_session_reason_msg(s);
    if (a.json)
        solve_write_json(&a, &sc, s, t_assemble, t_total, t_base, has_p, p_abs, p_rel, msg);
    else
        solve_write_text(&sc, s, t_assemble, t_total, a.baseline, t_base, has_p, p_abs, p_rel);
    code = it->reason == CX_CONVERGED_KKT ? CX_EXIT_OK
           : it->reason == CX_CANCELLED   ? CX_EXIT_INTERRUPTED
                                          : CX_EXIT_NOT_CONVERGED;
    if (cli_render_outputs(&a.render, &sc, s, a.level > 0 ? a.level : sc.level, a.json, &d))
        code = cli_fail(cmd, d.msg);
done:
    cx_session_destroy(&s);
    return code;
}
