/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "out/json.h"

#include <math.h>

void cx_json_init(cx_json *j, FILE *out)
{
    j->out = out;
    j->depth = 0;
    j->count[0] = 0;
}

static void json_string(FILE *out, const char *s)
{
    fputc('"', out);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(out, "\\%c", c);
        else if (c == '\n')
            fputs("\\n", out);
        else if (c == '\t')
            fputs("\\t", out);
        else if (c < 0x20)
            fprintf(out, "\\u%04x", c);
        else
            fputc(c, out);
    }
    fputc('"', out);
}

/* comma, newline and indentation before a member, then its key */
static void json_member(cx_json *j, const char *key)
{
    if (j->depth > 0) {
        fputs(j->count[j->depth]++ ? ",\n" : "\n", j->out);
        for (int k = 0; k < j->depth; k++)
            fputs("  ", j->out);
    }
    if (key) {
        json_string(j->out, key);
        fputs(": ", j->out);
    }
}

static void json_open(cx_json *j, const char *key, char c)
{
    json_member(j, key);
    fputc(c, j->out);
    j->count[++j->depth] = 0;
}

static void json_close(cx_json *j, char c)
{
    int had = j->count[j->depth] > 0;
    j->depth--;
    if (had) {
        fputc('\n', j->out);
        for (int k = 0; k < j->depth; k++)
            fputs("  ", j->out);
    }
    fputc(c, j->out);
    if (j->depth == 0)
        fputc('\n', j->out);
}

void cx_json_object(cx_json *j, const char *key) { json_open(j, key, '{'); }
void cx_json_array(cx_json *j, const char *key) { json_open(j, key, '['); }
void cx_json_end_object(cx_json *j) { json_close(j, '}'); }
void cx_json_end_array(cx_json *j) { json_close(j, ']'); }

void cx_json_num(cx_json *j, const char *key, double v)
{
    json_member(j, key);
    if (isfinite(v))
        fprintf(j->out, "%.17g", v);
    else
        fputs("null", j->out);
}

void cx_json_int(cx_json *j, const char *key, long v)
{
    json_member(j, key);
    fprintf(j->out, "%ld", v);
}

void cx_json_bool(cx_json *j, const char *key, int v)
{
    json_member(j, key);
    fputs(v ? "true" : "false", j->out);
}

void cx_json_str(cx_json *j, const char *key, const char *v)
{
    json_member(j, key);
    json_string(j->out, v);
}

void cx_json_null(cx_json *j, const char *key)
{
    json_member(j, key);
    fputs("null", j->out);
}

void cx_json_vec(cx_json *j, const char *key, const double *v, int n)
{
    json_member(j, key);
    fputc('[', j->out);
    for (int k = 0; k < n; k++) {
        if (isfinite(v[k]))
            fprintf(j->out, "%s%.17g", k ? ", " : "", v[k]);
        else
            fprintf(j->out, "%snull", k ? ", " : "");
    }
    fputc(']', j->out);
}
