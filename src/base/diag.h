/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cx_diag: the one-line diagnostic that a failing function leaves for the
 * program to print, e.g. "scenes/hertz.ini:14: key 'E': expected a positive
 * number". Functions that can fail on user input take a cx_diag * last; it
 * may be NULL. Nothing in the library prints: cli/ and tui/ show msg. */
#ifndef CX_DIAG_H
#define CX_DIAG_H

#include <stddef.h>

#define CX_DIAG_LEN 512

typedef struct cx_diag {
    int status;              /* the status that came with the message */
    char msg[CX_DIAG_LEN];   /* one line, no trailing newline */
} cx_diag;

void cx_diag_clear(cx_diag *d);

/* Format a message into d (if d is not NULL) and return status, so that a
 * failure reads: return cx_diag_set(d, CX_EINVAL, "...", ...); bytes a
 * terminal would act on (newlines, ESC, ...) come out escaped (cx_escape). */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
int cx_diag_set(cx_diag *d, int status, const char *fmt, ...);

/* Put "prefix: " in front of the message already in d (to add context at a
 * higher level, e.g. the file name). Returns d->status (or CX_OK if d NULL). */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
int cx_diag_prefix(cx_diag *d, const char *fmt, ...);

/* The message of d, or the status text when d holds no message. */
const char *cx_diag_msg(const cx_diag *d, int status);

#endif
