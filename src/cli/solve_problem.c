/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini solve --problem DIR|FILE: a discrete problem read back from
 * 'signorini export' (or written by another program in its form), solved
 * by any method that needs only the algebra. It has no mesh: what draws
 * or writes the mesh is refused before (cli/solve.c). */
#include "cli/cli.h"
#include "out/out.h"
#include "scene/problem_file.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct {
    FILE *out;
    int quiet;
    cx_history *history;
} sp_watch;

static int sp_step(void *ctx, const cx_session *s, const cx_iterate *it)
{
    (void)s;
    sp_watch *w = ctx;
    if (w->history && cx_history_add(w->history, it))
        return 1;
    if (!w->quiet)
        fprintf(w->out, "%6d  %10.3e  %10.3e  %7d %6d %6d %7d  %9.4f\n", it->iter, it->kkt, it->own,
                it->ncontact + it->nstick + it->nslip, it->nstick, it->nslip, it->nchanged, it->time);
    return 0;
}

static void sp_json(const cx_problem_file *pf, const char *path, const cx_session *s, const cx_history *h)
{
    const cx_iterate *it = cx_session_iterate(s);
    const cx_problem *p = cx_session_problem(s);
    char outcome[CX_DIAG_LEN + 160];
    cx_session_outcome(s, outcome, sizeof outcome);
    cx_json j;
    cx_json_init(&j, stdout);
    cx_json_object(&j, NULL);
    cx_json_str(&j, "problem", path);
    cx_json_str(&j, "format", pf->format);
    cx_json_str(&j, "source", pf->source);
    cx_json_str(&j, "method", cx_session_method(s)->id);
    cx_json_str(&j, "friction", cx_friction_name(cx_session_friction(s)->law));
    cx_json_int(&j, "dim", p->dim);
    cx_json_int(&j, "dofs", p->n);
    cx_json_int(&j, "contact_points", p->m);
    cx_json_bool(&j, "converged", it->reason == CX_CONVERGED_KKT);
    cx_json_str(&j, "reason", cx_reason_id(it->reason));
    cx_json_str(&j, "outcome", outcome);
    cx_json_int(&j, "iterations", it->iter);
    cx_json_num(&j, "kkt", it->kkt);
    cx_json_int(&j, "contact", it->ncontact + it->nstick + it->nslip);
    cx_json_int(&j, "stick", it->nstick);
    cx_json_int(&j, "slip", it->nslip);
    cx_json_object(&j, "counters");
    cx_json_int(&j, "factorizations", it->counters.factorizations);
    cx_json_int(&j, "solves", it->counters.solves);
    cx_json_int(&j, "matvecs", it->counters.matvecs);
    cx_json_end_object(&j);
    cx_json_num(&j, "time", it->time);
    cx_json_array(&j, "history");
    for (int k = 0; h && k < h->n; k++) {
        const cx_history_row *r = &h->rows[k];
        cx_json_object(&j, NULL);
        cx_json_int(&j, "iter", r->iter);
        cx_json_num(&j, "kkt", r->kkt);
        cx_json_num(&j, "own", r->own);
        cx_json_int(&j, "contact", r->ncontact);
        cx_json_int(&j, "changed", r->nchanged);
        cx_json_num(&j, "time", r->time);
        cx_json_end_object(&j);
    }
    cx_json_end_array(&j);
    cx_json_end_object(&j);
    fputc('\n', stdout);
}

int cli_solve_problem(const char *cmd, const char *path, const cx_solve_args *a, const cx_options *opt, int json,
                      int quiet)
{
    cx_diag d;
    cx_diag_clear(&d);
    cx_problem_file pf;
    if (cx_problem_read(path, &pf, &d))
        return cli_fail(cmd, d.msg);
    /* the file's law and values; --friction, --F, --slip-bound replace them
     * by the scalars at every point (a slip bound times the point's weight) */
    cx_friction_state fr = pf.fr;
    if (a->friction >= 0 && a->friction != (int)fr.law) {
        fr.law = (cx_friction)a->friction;
        fr.s = fr.Fi = NULL;
    }
    if (!isnan(a->F)) {
        fr.F = a->F;
        fr.Fi = NULL;
    }
    if (!isnan(a->slip)) {
        fr.slip_bound = a->slip;
        fr.s = NULL;
    }
    const char *id = a->method && strcmp(a->method, "auto") != 0 ? a->method : NULL;
    const char *auto_sets = "";
    if (!id) {
        /* --method auto: the choice for the scene it came from, when that
         * scene is here (the same method and parameters as 'solve SCENE'),
         * else the rule from the problem's properties */
        cx_scene sc;
        cx_diag ignored;
        int known = pf.source[0] && cx_scene_open(pf.source, &sc, &ignored) == CX_OK;
        id = cx_scene_auto_method(known ? &sc : NULL, pf.level, pf.p, fr.law, &auto_sets);
    }
    const cx_method *m = cx_method_find(id);
    cx_param_values pv;
    cx_param_default(&pv, m->params);
    char owner[64];
    snprintf(owner, sizeof owner, "method '%s'", m->id);
    char buf[256];
    snprintf(buf, sizeof buf, "%s", auto_sets);
    for (char *save = NULL, *tok = strtok_r(buf, " ", &save); tok; tok = strtok_r(NULL, " ", &save))
        if (cx_param_set_pair(&pv, tok, owner, &d)) {
            cx_problem_file_clear(&pf);
            return cli_fail(cmd, d.msg);
        }
    for (int k = 0; k < a->sets.n; k++)
        if (cli_param_set_for(&pv, a->sets.v[k], a->methods.n, owner, &d)) {
            cx_problem_file_clear(&pf);
            return cli_usage(cmd, d.msg);
        }
    int level = pf.level;
    char source[256];
    snprintf(source, sizeof source, "%s", pf.source[0] ? pf.source : "?");
    cx_session *s = NULL;
    int code = CX_EXIT_ERROR;
    cx_history history = {0};
    if (cx_session_create(&s, &pf.p, &d) || cx_session_set_friction(s, &fr, &d) ||
        cx_session_set_method(s, m, &pv, opt, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    const cx_problem *p = cx_session_problem(s);
    if (!json && !quiet) {
        printf("problem %s (%s, from %s level %d): %dD, %d dofs, %d contact points; %s%s, friction %s\n", path,
               pf.format, source, level, p->dim, p->n, p->m, m->id, a->method && strcmp(a->method, "auto") ? ""
               : " (auto)", cx_friction_name(cx_session_friction(s)->law));
        printf("  iter  kkt error   own crit.   contact  stick   slip changed   time (s)\n");
        fflush(stdout);
    }
    sp_watch w = {stdout, json || quiet, json ? &history : NULL};
    if (cx_solver_solve(s, sp_step, &w, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    const cx_iterate *it = cx_session_iterate(s);
    if (json) {
        sp_json(&pf, path, s, &history);
    } else {
        char outcome[CX_DIAG_LEN + 160];
        printf("%s\n", cx_session_outcome(s, outcome, sizeof outcome));
        printf("contact: %d of %d points (%d stick, %d slip)\n", it->ncontact + it->nstick + it->nslip, p->m,
               it->nstick, it->nslip);
        printf("time:    setup %.3f s, solve %.3f s\n", it->init_time, it->time - it->init_time);
        printf("work:    %ld factorisations, %ld solves, %ld products with K\n", it->counters.factorizations,
               it->counters.solves, it->counters.matvecs);
    }
    code = it->reason == CX_CONVERGED_KKT ? CX_EXIT_OK
           : it->reason == CX_CANCELLED   ? CX_EXIT_INTERRUPTED
                                          : CX_EXIT_NOT_CONVERGED;
done:
    cx_history_clear(&history);
    cx_session_destroy(&s);
    cx_problem_file_clear(&pf);
    if (code != CX_EXIT_ERROR && cx_outfile_close_stdout(&d))
        code = cli_fail(cmd, d.msg);
    return code;
}
