/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The CSV writer (see csv.h). */
#include "out/csv.h"

#include <math.h>
#include <string.h>

void cx_csv_init(cx_csv *c, FILE *out)
{
    c->out = out;
    c->col = 0;
}

void cx_csv_comment(cx_csv *c, const char *key, const char *value)
{
    fprintf(c->out, "# %s: %s\n", key, value);
}

static void csv_sep(cx_csv *c)
{
    if (c->col++ > 0)
        fputc(',', c->out);
}

void cx_csv_str(cx_csv *c, const char *s)
{
    csv_sep(c);
    if (!strpbrk(s, ",\"\r\n")) {
        fputs(s, c->out);
        return;
    }
    fputc('"', c->out);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', c->out);
        fputc(*s, c->out);
    }
    fputc('"', c->out);
}

void cx_csv_numf(cx_csv *c, const char *fmt, double v)
{
    csv_sep(c);
    if (isfinite(v))
        fprintf(c->out, fmt, v);
}

void cx_csv_num(cx_csv *c, double v) { cx_csv_numf(c, "%.17g", v); }

void cx_csv_int(cx_csv *c, long v)
{
    csv_sep(c);
    fprintf(c->out, "%ld", v);
}

void cx_csv_empty(cx_csv *c) { csv_sep(c); }

void cx_csv_end_row(cx_csv *c)
{
    fputc('\n', c->out);
    c->col = 0;
}
