/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "base/param.h"
#include "base/parse.h"
#include "base/status.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

int cx_param_count(const cx_param *table)
{
    int n = 0;
    while (table && table[n].key)
        n++;
    return n;
}

void cx_param_default(cx_param_values *v, const cx_param *table)
{
    memset(v, 0, sizeof *v);
    v->table = table;
    v->n = cx_param_count(table);
    assert(v->n <= CX_PARAM_MAX);
    for (int i = 0; i < v->n; i++) {
        v->num[i] = table[i].def;
        if (table[i].type == CX_PARAM_STRING && table[i].choices)
            snprintf(v->str[i], CX_PARAM_STRLEN, "%s", table[i].choices);
    }
}

int cx_param_find(const cx_param_values *v, const char *key)
{
    for (int i = 0; i < v->n; i++)
        if (strcmp(v->table[i].key, key) == 0)
            return i;
    return -1;
}

static int param_parse_bool(const char *t)
{
    static const char *yes[] = {"1", "true", "yes", "on"};
    static const char *no[] = {"0", "false", "no", "off"};
    for (int i = 0; i < 4; i++) {
        if (strcasecmp(t, yes[i]) == 0)
            return 1;
        if (strcasecmp(t, no[i]) == 0)
            return 0;
    }
    return -1;
}

void cx_param_range(const cx_param *p, char *buf, size_t len)
{
    switch (p->type) {
    case CX_PARAM_REAL:
        snprintf(buf, len, "%c%g, %g%c%s", (p->flags & CX_PARAM_MIN_OPEN) ? '(' : '[', p->min, p->max,
                 (p->flags & CX_PARAM_MAX_OPEN) ? ')' : ']', (p->flags & CX_PARAM_AUTO) ? " or auto" : "");
        break;
    case CX_PARAM_INT:
        snprintf(buf, len, "integer in [%.0f, %.0f]", p->min, p->max);
        break;
    case CX_PARAM_BOOL:
        snprintf(buf, len, "true|false");
        break;
    case CX_PARAM_CHOICE:
        snprintf(buf, len, "%s", p->choices);
        break;
    case CX_PARAM_STRING:
        snprintf(buf, len, "text");
        break;
    }
}

int cx_param_value(const cx_param *p, const char *text, double *x)
{
    long k;
    switch (p->type) {
    case CX_PARAM_REAL:
        if (cx_parse_double(text, x) != 0 || *x < p->min || *x > p->max ||
            ((p->flags & CX_PARAM_MIN_OPEN) && *x == p->min) ||
            ((p->flags & CX_PARAM_MAX_OPEN) && *x == p->max))
            return -1;
        return 0;
    case CX_PARAM_INT:
        if (cx_parse_int(text, (long)p->min, (long)p->max, &k) != 0)
            return -1;
        break;
    case CX_PARAM_BOOL:
        if ((k = param_parse_bool(text)) < 0)
            return -1;
        break;
    case CX_PARAM_CHOICE:
        if ((k = cx_parse_choice(text, p->choices)) < 0)
            return -1;
        break;
    default:
        return -1;
    }
    *x = (double)k;
    return 0;
}

int cx_param_set(cx_param_values *v, const char *key, const char *text,
                 const char *owner, cx_diag *d)
{
    int i = cx_param_find(v, key);
    if (i < 0)
        return cx_diag_set(d, CX_EINVAL, "unknown parameter '%s' of %s", key, owner);
    const cx_param *p = &v->table[i];
    char range[128];
    cx_param_range(p, range, sizeof range);
    double x;
    if (p->type == CX_PARAM_REAL && (p->flags & CX_PARAM_AUTO) && strcmp(text, "auto") == 0) {
        v->num[i] = NAN;
        return CX_OK;
    }
    if (p->type == CX_PARAM_STRING) {
        if (strlen(text) == 0 || strlen(text) >= CX_PARAM_STRLEN)
            goto bad;
        snprintf(v->str[i], CX_PARAM_STRLEN, "%s", text);
        return CX_OK;
    }
    if (cx_param_value(p, text, &x) != 0)
        goto bad;
    v->num[i] = x;
    return CX_OK;
bad:
    return cx_diag_set(d, CX_EINVAL, "parameter '%s' of %s: '%s' is not in %s",
                       key, owner, text, range);
}

int cx_param_set_pair(cx_param_values *v, const char *pair, const char *owner, cx_diag *d)
{
    const char *eq = strchr(pair, '=');
    if (!eq || eq == pair)
        return cx_diag_set(d, CX_EINVAL, "--set '%s': expected key=value", pair);
    char key[64];
    size_t len = (size_t)(eq - pair);
    if (len >= sizeof key)
        return cx_diag_set(d, CX_EINVAL, "--set '%s': key too long", pair);
    memcpy(key, pair, len);
    key[len] = '\0';
    return cx_param_set(v, key, eq + 1, owner, d);
}

double cx_param_get(const cx_param_values *v, const char *key)
{
    int i = cx_param_find(v, key);
    assert(i >= 0 && "unknown parameter key");
    return i >= 0 ? v->num[i] : NAN;
}

const char *cx_param_get_str(const cx_param_values *v, const char *key)
{
    int i = cx_param_find(v, key);
    assert(i >= 0 && "unknown parameter key");
    return i >= 0 ? v->str[i] : "";
}

void cx_param_format(const cx_param_values *v, int i, char *buf, size_t len)
{
    const cx_param *p = &v->table[i];
    switch (p->type) {
    case CX_PARAM_REAL:
        if (isnan(v->num[i]))
            snprintf(buf, len, "auto");
        else
            snprintf(buf, len, "%g", v->num[i]);
        break;
    case CX_PARAM_INT:
        snprintf(buf, len, "%.0f", v->num[i]);
        break;
    case CX_PARAM_BOOL:
        snprintf(buf, len, "%s", v->num[i] != 0 ? "true" : "false");
        break;
    case CX_PARAM_CHOICE: {
        const char *c = p->choices;
        for (int k = 0; k < (int)v->num[i] && c; k++) {
            c = strchr(c, '|');
            if (c)
                c++;
        }
        size_t l = c ? strcspn(c, "|") : 0;
        snprintf(buf, len, "%.*s", (int)l, c ? c : "");
        break;
    }
    case CX_PARAM_STRING:
        snprintf(buf, len, "%s", v->str[i]);
        break;
    }
}
