#include "base/diag.h"
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
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(d->msg, sizeof d->msg, fmt, ap);
        va_end(ap);
        /* one line: a newline in a value must not break the contract */
        for (char *c = d->msg; *c; c++)
            if (*c == '\n' || *c == '\r')
                *c = ' ';
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
    snprintf(d->msg, sizeof d->msg, "%.200s: %.300s", head, old);   /* fits: no truncation */
    return d->status;
}

const char *cx_diag_msg(const cx_diag *d, int status)
{
    if (d && d->msg[0])
        return d->msg;
    return cx_status_str(status);
}
