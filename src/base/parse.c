/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "base/parse.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int cx_parse_double(const char *text, double *out)
{
    if (!text)
        return -1;
    while (isspace((unsigned char)*text))
        text++;
    if (!*text)
        return -1;
    char *end;
    errno = 0;
    double v = strtod(text, &end);
    if (end == text || errno == ERANGE || !isfinite(v))
        return -1;
    while (isspace((unsigned char)*end))
        end++;
    if (*end)
        return -1;
    *out = v;
    return 0;
}

int cx_parse_int(const char *text, long min, long max, long *out)
{
    if (!text)
        return -1;
    while (isspace((unsigned char)*text))
        text++;
    if (!*text)
        return -1;
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (end == text || errno == ERANGE)
        return -1;
    while (isspace((unsigned char)*end))
        end++;
    if (*end || v < min || v > max)
        return -1;
    *out = v;
    return 0;
}

int cx_parse_doubles(const char *text, double *out, int max)
{
    int n = 0;
    const char *p = text;
    char word[64];
    for (;;) {
        while (isspace((unsigned char)*p) || *p == ',')
            p++;
        if (!*p)
            return n;
        size_t len = strcspn(p, " \t\r\n,");
        if (len >= sizeof word || n >= max)
            return -1;
        memcpy(word, p, len);
        word[len] = '\0';
        if (cx_parse_double(word, &out[n]) != 0)
            return -1;
        n++;
        p += len;
    }
}

int cx_parse_choice(const char *text, const char *choices)
{
    if (!text || !choices)
        return -1;
    size_t tl = strlen(text);
    int idx = 0;
    const char *p = choices;
    for (;;) {
        size_t len = strcspn(p, "|");
        if (len == tl && strncmp(p, text, len) == 0)
            return idx;
        if (!p[len])
            return -1;
        p += len + 1;
        idx++;
    }
}
