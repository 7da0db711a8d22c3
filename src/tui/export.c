/* Export of the runs on the current scene: one CSV row per step, and one
 * JSON document with every run and its steps. Each file is written to a
 * temporary name beside it and renamed, so nothing is half-written. */
#include "tui/tui_impl.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

/* A number, or null for NaN/Inf (never printed as a result). */
static void json_num(FILE *f, double x)
{
    if (isfinite(x))
        fprintf(f, "%.17g", x);
    else
        fputs("null", f);
}

static void csv_num(FILE *f, double x)
{
    if (isfinite(x))
        fprintf(f, "%.17g", x);
}

static void export_csv(const tui_state *st, FILE *f)
{
    fputs("run,method,params,friction,coef,iter,kkt,own,free,contact,stick,slip,changed,inner,"
          "solves,time_s,step_time_s,outcome\n", f);
    for (int r = 0; r < st->nruns; r++) {
        const tui_run *run = &st->runs[r];
        for (int k = 0; k < run->nsteps; k++) {
            const tui_step *s = &run->steps[k];
            fprintf(f, "%d,%s,\"%s\",%s,", r + 1, run->method, run->params, cx_friction_name(run->law));
            csv_num(f, run->law == CX_FRICTION_NONE ? NAN : run->coef);
            fprintf(f, ",%d,", s->iter);
            csv_num(f, s->kkt);
            fputc(',', f);
            csv_num(f, s->own);
            fprintf(f, ",%d,%d,%d,%d,%d,%ld,%ld,", s->nfree, s->ncontact, s->nstick, s->nslip, s->nchanged,
                    s->inner, s->solves);
            csv_num(f, s->time);
            fputc(',', f);
            csv_num(f, s->step_time);
            fprintf(f, ",%s\n", k == run->nsteps - 1 ? cx_reason_id(run->reason) : "iterating");
        }
    }
}

static void export_json(const tui_state *st, FILE *f)
{
    fputs("{\"scene\": ", f);
    json_str(f, st->scene.id);
    fprintf(f, ", \"level\": %d, \"dim\": %d, \"dofs\": %d, \"contact_points\": %d, \"runs\": [", st->level,
            st->info.dim, st->info.n, st->info.m);
    for (int r = 0; r < st->nruns; r++) {
        const tui_run *run = &st->runs[r];
        fputs(r ? ",\n  {\"method\": " : "\n  {\"method\": ", f);
        json_str(f, run->method);
        fputs(", \"params\": ", f);
        json_str(f, run->params);
        fputs(", \"friction\": ", f);
        json_str(f, cx_friction_name(run->law));
        fputs(", \"coef\": ", f);
        json_num(f, run->law == CX_FRICTION_NONE ? NAN : run->coef);
        fputs(", \"tol\": ", f);
        json_num(f, run->tol);
        fputs(", \"reason\": ", f);
        json_str(f, cx_reason_id(run->reason));
        fputs(", \"reason_msg\": ", f);
        json_str(f, run->reason_msg);
        fputs(", \"steps\": [", f);
        for (int k = 0; k < run->nsteps; k++) {
            const tui_step *s = &run->steps[k];
            fprintf(f, "%s\n    {\"iter\": %d, \"kkt\": ", k ? "," : "", s->iter);
            json_num(f, s->kkt);
            fputs(", \"own\": ", f);
            json_num(f, s->own);
            fprintf(f, ", \"free\": %d, \"contact\": %d, \"stick\": %d, \"slip\": %d, \"changed\": %d, "
                       "\"inner\": %ld, \"solves\": %ld, \"time\": ",
                    s->nfree, s->ncontact, s->nstick, s->nslip, s->nchanged, s->inner, s->solves);
            json_num(f, s->time);
            fputs(", \"step_time\": ", f);
            json_num(f, s->step_time);
            fputs("}", f);
        }
        fputs("]}", f);
    }
    fputs("\n]}\n", f);
}

static int export_file(const tui_state *st, const char *path, void (*write)(const tui_state *, FILE *),
                       cx_diag *d)
{
    char tmp[600];
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid());
    FILE *f = fopen(tmp, "w");
    if (!f)
        return cx_diag_set(d, CX_EIO, "cannot write '%s'", tmp);
    write(st, f);
    int bad = ferror(f);
    bad |= fclose(f) != 0;
    if (bad || rename(tmp, path) != 0) {
        remove(tmp);
        return cx_diag_set(d, CX_EIO, "cannot write '%s'", path);
    }
    return CX_OK;
}

int tui_export(const tui_state *st, const char *dir, char *csv, char *json, size_t len, cx_diag *d)
{
    if (st->nruns == 0 || (st->nruns == 1 && st->runs[0].nsteps == 0))
        return cx_diag_set(d, CX_EINVAL, "no steps to export yet");
    snprintf(csv, len, "%s/signorini-%s-L%d-runs.csv", dir, st->scene.id, st->level);
    snprintf(json, len, "%s/signorini-%s-L%d-runs.json", dir, st->scene.id, st->level);
    CX_TRY(export_file(st, csv, export_csv, d));
    return export_file(st, json, export_json, d);
}
