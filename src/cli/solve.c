/* signorini solve SCENE [options]: build, solve, report (text or JSON). */
#include "cli/cli.h"
#include "out/json.h"
#include "cx_config.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

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

typedef struct {
    int quiet;
} solve_watch;

static int solve_print_step(void *ctx, const cx_session *s, const cx_iterate *it)
{
    (void)s;
    const solve_watch *w = ctx;
    if (!w->quiet)
        printf("%6d  %10.3e  %10.3e  %7d %6d %6d %7d  %9.4f\n", it->iter, it->kkt, it->own,
               it->ncontact + it->nstick + it->nslip, it->nstick, it->nslip, it->nchanged, it->time);
    return 0;
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
    cx_json_str(&j, "friction", cx_friction_name(p->friction));
    if (p->friction == CX_FRICTION_TRESCA)
        cx_json_num(&j, "slip_bound", p->slip_bound);
    if (p->friction == CX_FRICTION_COULOMB)
        cx_json_num(&j, "F", p->F);
    cx_json_int(&j, "dim", p->dim);
    cx_json_int(&j, "dofs", p->n);
    cx_json_int(&j, "contact_points", p->m);
    cx_json_int(&j, "iterations", it->iter);
    cx_json_bool(&j, "converged", it->reason > 0);
    cx_json_str(&j, "reason", cx_reason_id(it->reason));
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
                             double p_abs, double p_rel, const char *msg)
{
    const cx_problem *p = cx_session_problem(s);
    const cx_iterate *it = cx_session_iterate(s);
    double fc[3];
    solve_contact_force(p, it, fc);
    printf("%s after %d iterations: kkt error %.3e%s%s\n", cx_reason_str(it->reason), it->iter,
           it->kkt, msg && msg[0] ? "\n  " : "", msg ? msg : "");
    printf("contact: %d of %d points (%d stick, %d slip)\n", it->ncontact + it->nstick + it->nslip,
           p->m, it->nstick, it->nslip);
    const char *axes = "xyz";
    printf("force:   applied");
    for (int k = 0; k < p->dim; k++)
        printf(" %c %.6g", axes[k], p->f_applied[k]);
    printf(";  contact");
    for (int k = 0; k < p->dim; k++)
        printf(" %c %.6g", axes[k], fc[k]);
    printf("\n");
    if (has_p)
        printf("pressure vs Hertz: L2 error %.4g (%.2f %%), half-width b = %.4g\n", p_abs, 100 * p_rel,
               cx_scene_hertz_halfwidth(sc));
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
        char clamped[32] = "";   /* points of the contact boundary a support holds */
        if (cp->contact.nclamped > 0)
            snprintf(clamped, sizeof clamped, ", %d clamped", cp->contact.nclamped);
        printf("%s level %d: %dD, %d dofs, %d contact points%s; %s, friction %s\n", sc.id,
               a.level > 0 ? a.level : sc.level, cp->dim, cp->n, cp->m, clamped, m->id,
               cx_friction_name(cp->friction));
        printf("  iter  kkt error   own crit.   contact  stick   slip changed   time (s)\n");
    }
    solve_watch w = {a.json || a.quiet};
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
    const cx_iterate *it = cx_session_iterate(s);
    double p_abs = 0, p_rel = 0;
    int has_p = cx_scene_pressure_error(&sc, cp, it->lN, &p_abs, &p_rel) == CX_OK;
    const char *msg = cx_session_reason_msg(s);
    if (a.json)
        solve_write_json(&a, &sc, s, t_assemble, t_total, t_base, has_p, p_abs, p_rel, msg);
    else
        solve_write_text(&sc, s, t_assemble, t_total, a.baseline, t_base, has_p, p_abs, p_rel, msg);
    code = it->reason > 0 ? CX_EXIT_OK : CX_EXIT_NOT_CONVERGED;
    if (cli_render_outputs(&a.render, &sc, s, a.level > 0 ? a.level : sc.level, a.json, &d))
        code = cli_fail(cmd, d.msg);
done:
    cx_session_destroy(&s);
    return code;
}
