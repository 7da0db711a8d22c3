/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Result tables of the benchmarks: typed cells, a header of "key: value"
 * lines, and three writers (aligned text; CSV and JSON through out/'s
 * writers and its safe-output helper, so that a failed or interrupted
 * write never leaves half a file under the real name). */
#define _GNU_SOURCE   /* dlsym(RTLD_DEFAULT) to ask which BLAS is loaded */
#include "bench/bench.h"
#include "out/out.h"
#include "cx_config.h"

#include <ctype.h>
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

void bench_table_init(bench_table *t, const char *const *cols)
{
    memset(t, 0, sizeof *t);
    while (cols[t->ncols] && t->ncols < BENCH_MAX_COLS) {
        t->cols[t->ncols] = cols[t->ncols];
        t->ncols++;
    }
}

void bench_table_clear(bench_table *t)
{
    free(t->cells);
    t->cells = NULL;
    t->nrows = t->cap = 0;
}

int bench_table_row(bench_table *t)
{
    if (t->nrows == t->cap) {
        int cap = t->cap ? 2 * t->cap : 32;
        bench_cell *c = realloc(t->cells, sizeof *c * (size_t)cap * (size_t)t->ncols);
        if (!c) {
            fputs("signorini bench: out of memory\n", stderr);
            exit(CX_EXIT_ERROR);
        }
        t->cells = c;
        t->cap = cap;
    }
    memset(t->cells + (size_t)t->nrows * t->ncols, 0, sizeof(bench_cell) * (size_t)t->ncols);
    return t->nrows++;
}

static bench_cell *table_cell(const bench_table *t, int row, const char *col)
{
    for (int c = 0; c < t->ncols; c++)
        if (strcmp(t->cols[c], col) == 0)
            return t->cells + (size_t)row * t->ncols + c;
    return NULL;  /* a column the table does not have: ignored */
}

void bench_set_num(bench_table *t, int row, const char *col, double v)
{
    bench_cell *c = table_cell(t, row, col);
    if (c && isfinite(v)) {
        c->kind = 1;
        c->v = v;
    } else if (c) {
        /* never a NaN as a result: an empty cell says "not available" */
        c->kind = 0;
    }
}

void bench_set_int(bench_table *t, int row, const char *col, long v)
{
    bench_cell *c = table_cell(t, row, col);
    if (c) {
        c->kind = 2;
        c->v = (double)v;
    }
}

void bench_set_str(bench_table *t, int row, const char *col, const char *fmt, ...)
{
    bench_cell *c = table_cell(t, row, col);
    if (!c)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->s, sizeof c->s, fmt, ap);
    va_end(ap);
    c->kind = 3;
}

double bench_get_num(const bench_table *t, int row, const char *col)
{
    const bench_cell *c = table_cell(t, row, col);
    return c && (c->kind == 1 || c->kind == 2) ? c->v : NAN;
}

const char *bench_get_str(const bench_table *t, int row, const char *col)
{
    const bench_cell *c = table_cell(t, row, col);
    return c && c->kind == 3 ? c->s : "";
}

void bench_meta(bench_table *t, const char *key, const char *fmt, ...)
{
    int k;
    for (k = 0; k < t->nmeta; k++)
        if (strcmp(t->meta[k][0], key) == 0)
            break;
    if (k == t->nmeta) {
        if (t->nmeta == (int)(sizeof t->meta / sizeof t->meta[0]))
            return;
        t->nmeta++;
    }
    snprintf(t->meta[k][0], sizeof t->meta[k][0], "%s", key);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(t->meta[k][1], sizeof t->meta[k][1], fmt, ap);
    va_end(ap);
}

/* Which BLAS the process runs on: OpenBLAS answers openblas_get_config. */
static void table_blas(char *buf, size_t len)
{
    char *(*config)(void) = (char *(*)(void))dlsym(RTLD_DEFAULT, "openblas_get_config");
    int (*threads)(void) = (int (*)(void))dlsym(RTLD_DEFAULT, "openblas_get_num_threads");
    if (config)
        snprintf(buf, len, "OpenBLAS (%s; %d threads)", config(), threads ? threads() : 1);
    else
        snprintf(buf, len, "reference BLAS/LAPACK (no OpenBLAS loaded)");
}

void bench_meta_machine(bench_table *t)
{
    char blas[160], date[32];
    table_blas(blas, sizeof blas);
    time_t now = time(NULL);
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    bench_meta(t, "program", "signorini %s", CX_VERSION);
    bench_meta(t, "machine", "%ld cores", sysconf(_SC_NPROCESSORS_ONLN));
    bench_meta(t, "blas", "%s", blas);
    bench_meta(t, "date", "%s", date);
}

static void cell_text(const bench_cell *c, char *buf, size_t len, int exact)
{
    if (c->kind == 1)
        snprintf(buf, len, exact ? "%.10g" : "%.4g", c->v);
    else if (c->kind == 2)
        snprintf(buf, len, "%.0f", c->v);
    else if (c->kind == 3)
        snprintf(buf, len, "%s", c->s);
    else
        snprintf(buf, len, "%s", exact ? "" : "-");
}

void bench_table_print(const bench_table *t, FILE *out)
{
    int w[BENCH_MAX_COLS];
    char buf[BENCH_CELL_LEN + 32];
    for (int k = 0; k < t->nmeta; k++)
        fprintf(out, "# %s: %s\n", t->meta[k][0], t->meta[k][1]);
    for (int c = 0; c < t->ncols; c++) {
        w[c] = (int)strlen(t->cols[c]);
        for (int r = 0; r < t->nrows; r++) {
            cell_text(t->cells + (size_t)r * t->ncols + c, buf, sizeof buf, 0);
            if ((int)strlen(buf) > w[c])
                w[c] = (int)strlen(buf);
        }
    }
    for (int c = 0; c < t->ncols; c++)
        fprintf(out, "%s%-*s", c ? "  " : "", w[c], t->cols[c]);
    fputc('\n', out);
    for (int r = 0; r < t->nrows; r++) {
        for (int c = 0; c < t->ncols; c++) {
            const bench_cell *cell = t->cells + (size_t)r * t->ncols + c;
            cell_text(cell, buf, sizeof buf, 0);
            /* numbers right-aligned, text left-aligned */
            fprintf(out, "%s%*s", c ? "  " : "", cell->kind == 3 ? -w[c] : w[c], buf);
        }
        fputc('\n', out);
    }
}

int bench_table_write_csv(const bench_table *t, const char *path, cx_diag *d)
{
    char buf[BENCH_CELL_LEN + 32];
    cx_outfile f;
    CX_TRY(cx_outfile_open(&f, path, d));
    cx_csv c;
    cx_csv_init(&c, f.f);
    for (int k = 0; k < t->nmeta; k++)
        cx_csv_comment(&c, t->meta[k][0], t->meta[k][1]);
    for (int k = 0; k < t->ncols; k++)
        cx_csv_str(&c, t->cols[k]);
    cx_csv_end_row(&c);
    for (int r = 0; r < t->nrows; r++) {
        for (int k = 0; k < t->ncols; k++) {
            cell_text(t->cells + (size_t)r * t->ncols + k, buf, sizeof buf, 1);
            cx_csv_str(&c, buf);
        }
        cx_csv_end_row(&c);
    }
    return cx_outfile_close(&f, 1, d);
}

/* JSON is typed where the table's text is prose (doc/design.md §6): a
 * text that is a whole number ("0.0001") is a number; a column whose every
 * text is yes, no or n/a is boolean (n/a: null, the run did not happen);
 * a header value "0.00309 s (...)" is the number of seconds under its key
 * and the sentence under "KEY text". Ids that look like numbers but start
 * with 0 ("000") stay text, as do the CSV and the table. */
static int json_number(const char *s, double *x)
{
    char *end;
    if (!s[0] || isspace((unsigned char)s[0]) || (s[0] == '0' && isdigit((unsigned char)s[1])) ||
        !strpbrk(s, "0123456789"))
        return 0;
    *x = strtod(s, &end);
    return end != s && *end == '\0' && isfinite(*x);
}

static int json_yesno(const char *s)
{
    return strcmp(s, "yes") == 0 ? 1 : strcmp(s, "no") == 0 ? 0 : strcmp(s, "n/a") == 0 ? -1 : -2;
}

static int json_bool_column(const bench_table *t, int c)
{
    int any = 0;
    for (int r = 0; r < t->nrows; r++) {
        const bench_cell *cell = t->cells + (size_t)r * t->ncols + c;
        if (cell->kind == 0)
            continue;
        if (cell->kind != 3 || json_yesno(cell->s) == -2)
            return 0;
        any |= json_yesno(cell->s) >= 0;
    }
    return any;
}

static void json_meta(cx_json *j, const char *key, const char *v)
{
    double x;
    char *end;
    if (json_number(v, &x)) {
        cx_json_num(j, key, x);
        return;
    }
    if (json_yesno(v) >= 0) {
        cx_json_bool(j, key, json_yesno(v));
        return;
    }
    /* "NUMBER s" or "NUMBER s (...)": seconds */
    x = strtod(v, &end);
    if (end != v && isdigit((unsigned char)v[0]) && isfinite(x) && strncmp(end, " s", 2) == 0 &&
        (end[2] == '\0' || end[2] == ' ')) {
        char tkey[200];
        cx_json_num(j, key, x);
        snprintf(tkey, sizeof tkey, "%s text", key);
        cx_json_str(j, tkey, v);
        return;
    }
    cx_json_str(j, key, v);
}

int bench_table_write_json(const bench_table *t, const char *path, cx_diag *d)
{
    cx_outfile f;
    CX_TRY(cx_outfile_open(&f, path, d));
    cx_json j;
    cx_json_init(&j, f.f);
    cx_json_object(&j, NULL);
    cx_json_object(&j, "meta");
    for (int k = 0; k < t->nmeta; k++)
        json_meta(&j, t->meta[k][0], t->meta[k][1]);
    cx_json_end_object(&j);
    int boolean[BENCH_MAX_COLS];
    for (int c = 0; c < t->ncols; c++)
        boolean[c] = json_bool_column(t, c);
    cx_json_array(&j, "rows");
    for (int r = 0; r < t->nrows; r++) {
        cx_json_object(&j, NULL);
        for (int c = 0; c < t->ncols; c++) {
            const bench_cell *cell = t->cells + (size_t)r * t->ncols + c;
            double x;
            if (cell->kind == 1)
                cx_json_num(&j, t->cols[c], cell->v);
            else if (cell->kind == 2)
                cx_json_int(&j, t->cols[c], (long)cell->v);
            else if (cell->kind == 3 && boolean[c] && json_yesno(cell->s) >= 0)
                cx_json_bool(&j, t->cols[c], json_yesno(cell->s));
            else if (cell->kind == 3 && boolean[c])
                cx_json_null(&j, t->cols[c]);
            else if (cell->kind == 3 && json_number(cell->s, &x))
                cx_json_num(&j, t->cols[c], x);
            else if (cell->kind == 3)
                cx_json_str(&j, t->cols[c], cell->s);
            else
                cx_json_null(&j, t->cols[c]);
        }
        cx_json_end_object(&j);
    }
    cx_json_end_array(&j);
    cx_json_end_object(&j);
    return cx_outfile_close(&f, 1, d);
}
