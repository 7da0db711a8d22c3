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
    cx_history_write_json(&j, h);
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
    int is_auto = !a->method || strcmp(a->method, "auto") == 0;
    const char *id = a->method, *auto_sets = "";
    if (is_auto) {
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
    if (cli_method_params(m, auto_sets, a, &pv, &d)) {   /* --set names a key or a value the method has not */
        cx_problem_file_clear(&pf);
        return cli_usage(cmd, d.msg);
    }
    char title[4096 + 512];
    snprintf(title, sizeof title, "problem %s (%s, from %s level %d)", path, pf.format,
             pf.source[0] ? pf.source : "?", pf.level);
    cx_session *s = NULL;
    int code = CX_EXIT_ERROR;
    cx_history history = {0};
    if (cx_session_create(&s, &pf.p, &d) || cx_session_set_friction(s, &fr, &d) ||
        cx_session_set_method(s, m, &pv, opt, &d)) {
        cli_fail(cmd, d.msg);
        goto done;
    }
    const cx_problem *p = cx_session_problem(s);
    cli_watch w = {json || quiet, stdout, json ? &history : NULL, NULL, s, NULL, 0, 0, NULL};
    if (cli_solve_run(s, title, is_auto, &w, &d)) {
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
    code = cli_exit_status(it->reason);
done:
    cx_history_clear(&history);
    cx_session_destroy(&s);
    cx_problem_file_clear(&pf);
    if (code != CX_EXIT_ERROR && cx_outfile_close_stdout(&d))
        code = cli_fail(cmd, d.msg);
    return code;
}
