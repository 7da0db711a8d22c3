/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "base/diag.h"
#include "base/escape.h"
#include "base/status.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

void cx_diag_clear(cx_diag *d)
{
    if (d) {
        d->status = CX_OK;
        d->msg[0] = '\0';
    }
}

int cx_diag_set(cx_diag *d, int status, const char *fmt, ...)
{
    if (d) {
        char raw[CX_DIAG_LEN];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(raw, sizeof raw, fmt, ap);
        va_end(ap);
        /* one printable line: a newline (read as a space) or a terminal
         * escape quoted from the input must not break the contract */
        for (char *c = raw; *c; c++)
            if (*c == '\n' || *c == '\r')
                *c = ' ';
        cx_escape(d->msg, sizeof d->msg, raw, strlen(raw));
        d->status = status;
    }
    return status;
}

int cx_diag_prefix(cx_diag *d, const char *fmt, ...)
{
    if (!d)
        return CX_OK;
    char head[CX_DIAG_LEN], old[CX_DIAG_LEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(head, sizeof head, fmt, ap);
    va_end(ap);
    memcpy(old, d->msg, sizeof old);
    char raw[CX_DIAG_LEN];
    snprintf(raw, sizeof raw, "%.200s: %.300s", head, old);   /* fits: no truncation */
    cx_escape(d->msg, sizeof d->msg, raw, strlen(raw));
    return d->status;
}

const char *cx_diag_msg(const cx_diag *d, int status)
{
    if (d && d->msg[0])
        return d->msg;
    return cx_status_str(status);
}
