/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Export of the runs on the current scene: one CSV row per step, and one
 * JSON document with every run and its steps, through out/'s CSV and JSON
 * writers and its safe-output helper (nothing is left half-written). */
#include "tui/tui_impl.h"
#include "out/out.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static void export_csv(const tui_state *st, FILE *f)
{
    static const char *const cols[] = {"run", "method", "params", "friction", "coef", "iter", "kkt",
                                       "own", "free", "contact", "stick", "slip", "changed", "inner",
                                       "solves", "time_s", "step_time_s", "outcome", NULL};
    cx_csv c;
    cx_csv_init(&c, f);
    for (int k = 0; cols[k]; k++)
        cx_csv_str(&c, cols[k]);
    cx_csv_end_row(&c);
    for (int r = 0; r < tui_state_nruns(st); r++) {
        const tui_run *run = tui_state_run_at(st, r);
        for (int k = 0; k < run->nsteps; k++) {
            const tui_step *s = &run->steps[k];
            cx_csv_int(&c, r + 1);
            cx_csv_str(&c, run->method);
            cx_csv_str(&c, run->params);
            cx_csv_str(&c, cx_friction_name(run->law));
            cx_csv_num(&c, run->law == CX_FRICTION_NONE ? NAN : run->coef);
            cx_csv_int(&c, s->iter);
            cx_csv_num(&c, s->kkt);
            cx_csv_num(&c, s->own);
            cx_csv_int(&c, s->nfree);
            cx_csv_int(&c, s->ncontact);
            cx_csv_int(&c, s->nstick);
            cx_csv_int(&c, s->nslip);
            cx_csv_int(&c, s->nchanged);
            cx_csv_int(&c, s->inner);
            cx_csv_int(&c, s->solves);
            cx_csv_num(&c, s->time);
            cx_csv_num(&c, s->step_time);
            cx_csv_str(&c, k == run->nsteps - 1 ? cx_reason_id(run->reason) : "iterating");
            cx_csv_end_row(&c);
        }
    }
}

static void export_json(const tui_state *st, FILE *f)
{
    cx_json j;
    cx_json_init(&j, f);
    cx_json_object(&j, NULL);
    cx_json_str(&j, "scene", st->scene.id);
    cx_json_int(&j, "level", st->level);
    cx_json_int(&j, "dim", st->info->dim);
    cx_json_int(&j, "dofs", st->info->n);
    cx_json_int(&j, "contact_points", st->info->m);
    cx_json_array(&j, "runs");
    for (int r = 0; r < tui_state_nruns(st); r++) {
        const tui_run *run = tui_state_run_at(st, r);
        cx_json_object(&j, NULL);
        cx_json_str(&j, "method", run->method);
        cx_json_str(&j, "params", run->params);
        cx_json_str(&j, "friction", cx_friction_name(run->law));
        cx_json_num(&j, "coef", run->law == CX_FRICTION_NONE ? NAN : run->coef);
        cx_json_num(&j, "tol", run->tol);
        cx_json_str(&j, "reason", cx_reason_id(run->reason));
        cx_json_str(&j, "reason_msg", run->reason_msg);
        /* the run's own work (solve's counts), its setup apart from the
         * steps' time, and the explorer's work for drawing apart */
        cx_json_int(&j, "factorizations", run->factorizations);
        cx_json_num(&j, "setup_time", run->setup);
        cx_json_int(&j, "drawing_solves", run->draw.solves);
        cx_json_array(&j, "steps");
        for (int k = 0; k < run->nsteps; k++) {
            const tui_step *s = &run->steps[k];
            cx_json_object(&j, NULL);
            cx_json_int(&j, "iter", s->iter);
            cx_json_num(&j, "kkt", s->kkt);
            cx_json_num(&j, "own", s->own);
            cx_json_int(&j, "free", s->nfree);
            cx_json_int(&j, "contact", s->ncontact);
            cx_json_int(&j, "stick", s->nstick);
            cx_json_int(&j, "slip", s->nslip);
            cx_json_int(&j, "changed", s->nchanged);
            cx_json_int(&j, "inner", s->inner);
            cx_json_int(&j, "solves", s->solves);
            cx_json_num(&j, "time", s->time);
            cx_json_num(&j, "step_time", s->step_time);
            cx_json_end_object(&j);
        }
        cx_json_end_array(&j);
        cx_json_end_object(&j);
    }
    cx_json_end_array(&j);
    cx_json_end_object(&j);
}

static int export_file(const tui_state *st, const char *path, void (*write)(const tui_state *, FILE *),
                       cx_diag *d)
{
    cx_outfile o;
    CX_TRY(cx_outfile_open(&o, path, d));
    write(st, o.f);
    return cx_outfile_close(&o, 1, d);
}

int tui_export(const tui_state *st, const char *dir, char *csv, char *json, size_t len, cx_diag *d)
{
    if (tui_state_nruns(st) == 0 || (tui_state_nruns(st) == 1 && tui_state_run_at(st, 0)->nsteps == 0))
        return cx_diag_set(d, CX_EINVAL, "no steps to export yet");
    snprintf(csv, len, "%s/signorini-%s-L%d-runs.csv", dir, st->scene.id, st->level);
    snprintf(json, len, "%s/signorini-%s-L%d-runs.json", dir, st->scene.id, st->level);
    CX_TRY(export_file(st, csv, export_csv, d));
    return export_file(st, json, export_json, d);
}
