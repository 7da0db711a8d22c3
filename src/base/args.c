/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The option tables: parsing argv and writing the help (see args.h). */
#include "base/args.h"
#include "base/escape.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The row as a cx_param, so that the range is checked and written by the
 * parameter tables' code. */
static cx_param opt_param(const cx_opt *o)
{
    cx_param p = {o->name, CX_PARAM_STRING, 0, o->min, o->max, o->choices, o->help, o->flags};
    if (o->type == CX_OPT_INT)
        p.type = CX_PARAM_INT;
    else if (o->type == CX_OPT_REAL)
        p.type = CX_PARAM_REAL;
    else if (o->type == CX_OPT_CHOICE)
        p.type = CX_PARAM_CHOICE;
    return p;
}

void cx_opt_range(const cx_opt *o, char *buf, size_t len)
{
    cx_param p = opt_param(o);
    char r[96];
    cx_param_range(&p, r, sizeof r);
    if (o->type == CX_OPT_REAL)
        snprintf(buf, len, "a number in %s", r);
    else if (o->type == CX_OPT_INT)
        snprintf(buf, len, "an %s", r);
    else if (o->type == CX_OPT_CHOICE) {
        /* "a|b|c" as "a, b or c" */
        size_t k = 0;
        const char *last = strrchr(r, '|');
        for (const char *c = r; *c && k + 5 < len; c++) {
            if (*c != '|') {
                buf[k++] = *c;
                continue;
            }
            const char *sep = c == last ? " or " : ", ";
            for (; *sep && k + 1 < len; sep++)
                buf[k++] = *sep;
        }
        buf[k < len ? k : len - 1] = '\0';
    } else
        snprintf(buf, len, "%s", "");
}

int cx_opt_in_range(const cx_opt *o, double x)
{
    if (o->type == CX_OPT_INT && x != floor(x))
        return 0;
    return x >= o->min && x <= o->max && !((o->flags & CX_OPT_MIN_OPEN) && x == o->min) &&
           !((o->flags & CX_OPT_MAX_OPEN) && x == o->max);
}

int cx_opt_value(const cx_opt *o, const char *text, double *x, cx_diag *d)
{
    cx_param p = opt_param(o);
    if (cx_param_value(&p, text, x) == 0)
        return CX_OK;
    char r[128];
    cx_opt_range(o, r, sizeof r);
    return cx_diag_set(d, CX_EINVAL, "--%s '%s': expected %s", o->name, text, r);
}

const cx_opt *cx_opt_find(const cx_opt *table, const char *name)
{
    for (const cx_opt *o = table; o && o->name; o++)
        if (strcmp(o->name, name) == 0)
            return o;
    return NULL;
}

/* Store text as the value of o in args. */
static int opt_store(const cx_opt *o, void *args, const char *text, cx_diag *d)
{
    char *target = (char *)args + o->offset;
    double x;
    switch (o->type) {
    case CX_OPT_FLAG:
        *(int *)target = 1;
        return CX_OK;
    case CX_OPT_INT:
    case CX_OPT_CHOICE:
        CX_TRY(cx_opt_value(o, text, &x, d));
        *(int *)target = (int)x;
        return CX_OK;
    case CX_OPT_REAL:
        CX_TRY(cx_opt_value(o, text, &x, d));
        *(double *)target = x;
        return CX_OK;
    case CX_OPT_STRING:
        if (o->check)
            CX_TRY(o->check(text, d));
        *(const char **)target = text;
        return CX_OK;
    case CX_OPT_LIST: {
        cx_opt_list *l = (cx_opt_list *)(void *)target;
        if (l->n == CX_OPT_LIST_MAX)
            return cx_diag_set(d, CX_EINVAL, "--%s: more than %d times", o->name, CX_OPT_LIST_MAX);
        if (o->check)
            CX_TRY(o->check(text, d));
        l->v[l->n++] = text;
        return CX_OK;
    }
    }
    return cx_diag_set(d, CX_EINVAL, "--%s: bad option table", o->name);
}

/* The row of argument a ("--name", "--name=v", "-x") and its inline value. */
static const cx_opt *opt_lookup(const cx_opt_group *groups, const char *a, void **args,
                                const char **inline_value)
{
    *inline_value = NULL;
    for (const cx_opt_group *g = groups; g->opts; g++)
        for (const cx_opt *o = g->opts; o->name; o++) {
            *args = g->args;
            if (a[1] != '-') {
                if (o->short_name && a[1] == o->short_name && a[2] == '\0')
                    return o;
                continue;
            }
            size_t len = strlen(o->name);
            if (strncmp(a + 2, o->name, len) != 0)
                continue;
            if (a[2 + len] == '\0')
                return o;
            if (a[2 + len] == '=') {
                *inline_value = a + 3 + len;
                return o;
            }
        }
    return NULL;
}

static int opt_is_help(const char *a)
{
    return strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0;
}

int cx_opt_parse(const cx_opt_group *groups, int argc, char **argv, const char **pos, int maxpos,
                 int *npos, cx_diag *d)
{
    /* help first: "cmd --bogus --help" prints the help, as it always did */
    for (int i = 1; i < argc && strcmp(argv[i], "--") != 0; i++)
        if (opt_is_help(argv[i]))
            return CX_OPT_HELP;
    int n = 0, options = 1;
    if (npos)
        *npos = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (options && strcmp(a, "--") == 0) {
            options = 0;
            continue;
        }
        if (!options || a[0] != '-' || a[1] == '\0') {
            /* positional ("-" alone is one: standard input or output) */
            if (n >= maxpos)
                return cx_diag_set(d, CX_EINVAL, "unexpected argument '%s'", a);
            pos[n++] = a;
            if (npos)
                *npos = n;
            continue;
        }
        void *args = NULL;
        const char *value;
        const cx_opt *o = opt_lookup(groups, a, &args, &value);
        if (!o)
            return cx_diag_set(d, CX_EINVAL, "unknown option '%s'", a);
        if (o->type == CX_OPT_FLAG) {
            if (value)
                return cx_diag_set(d, CX_EINVAL, "option '--%s' takes no value", o->name);
        } else if (!value) {
            if (i + 1 >= argc)
                return cx_diag_set(d, CX_EINVAL, "option '%s' needs a value", a);
            value = argv[++i];
        }
        CX_TRY(opt_store(o, args, value, d));
    }
    return CX_OK;
}

enum { OPT_HELP_COL = 23, OPT_HELP_WIDTH = 79 };

void cx_opt_help(const cx_opt *table, FILE *out)
{
    for (const cx_opt *o = table; o && o->name; o++) {
        char left[64];
        int l;
        if (o->short_name)
            l = snprintf(left, sizeof left, "  -%c, --%s%s%s", o->short_name, o->name, o->arg ? " " : "",
                         o->arg ? o->arg : "");
        else
            l = snprintf(left, sizeof left, "  --%s%s%s", o->name, o->arg ? " " : "", o->arg ? o->arg : "");
        fputs(left, out);
        int col = l;
        if (col >= OPT_HELP_COL - 1) {
            fputc('\n', out);
            col = 0;
        }
        /* the help's lines, each at the help column */
        const char *h = o->help ? o->help : "";
        for (;;) {
            const char *nl = strchr(h, '\n');
            int hl = nl ? (int)(nl - h) : (int)strlen(h);
            fprintf(out, "%*s%.*s", OPT_HELP_COL - col, "", hl, h);
            col = OPT_HELP_COL + hl;
            if (!nl)
                break;
            fputc('\n', out);
            col = 0;
            h = nl + 1;
        }
        /* the range from the row itself, so that it is the one checked */
        char r[128];
        cx_opt_range(o, r, sizeof r);
        if (r[0] && o->type != CX_OPT_CHOICE) {
            if (col + 2 + (int)strlen(r) > OPT_HELP_WIDTH)
                fprintf(out, ";\n%*s%s", OPT_HELP_COL, "", r);
            else
                fprintf(out, "; %s", r);
        }
        fputc('\n', out);
    }
}

int cx_arg_report(FILE *out, const char *cmd, const char *msg, int status)
{
    char safe[2048];   /* msg may quote input: written escaped */
    cx_escape(safe, sizeof safe, msg, strlen(msg));
    /* a usage error points at the help, unless the message already does */
    if (status == CX_EXIT_USAGE && !strstr(msg, "(see "))
        fprintf(out, "signorini %s: %s (see 'signorini %s --help')\n", cmd, safe, cmd);
    else
        fprintf(out, "signorini %s: %s\n", cmd, safe);
    return status;
}
