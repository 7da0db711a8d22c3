/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Status codes of the library: 0 is success, negative is failure.
 * Codes and their messages come from the one X-macro list below, so
 * cx_status_str() cannot fall out of step with the enum. Not converging is
 * not a status but a result (cx_reason, solve/solve.h). */
#ifndef CX_STATUS_H
#define CX_STATUS_H

#define CX_STATUS_LIST(X)                                        \
    X(CX_OK, 0, "ok")                                            \
    X(CX_ENOMEM, -1, "out of memory")                            \
    X(CX_EINVAL, -2, "invalid input")                            \
    X(CX_EIO, -3, "input/output error")                          \
    X(CX_EUNSUPPORTED, -4, "unsupported combination")            \
    X(CX_ENUMERIC, -5, "numerical failure")                      \
    X(CX_EEXTERNAL, -6, "error in an external library")

typedef enum cx_status {
#define CX_STATUS_ENUM_(name, value, msg) name = value,
    CX_STATUS_LIST(CX_STATUS_ENUM_)
#undef CX_STATUS_ENUM_
} cx_status;

/* The message of a status code; "unknown status" for a value not listed. */
const char *cx_status_str(int status);

/* Evaluate expr (an int status); on failure return it from the caller. */
#define CX_TRY(expr)                                  \
    do {                                              \
        int cx_try_status_ = (expr);                  \
        if (cx_try_status_ != CX_OK)                  \
            return cx_try_status_;                    \
    } while (0)

#endif
