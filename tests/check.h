/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The tiny assertion helper of the test suite. Every check prints what it
 * compared; the test program returns check_finish(), non-zero if any failed. */
#ifndef CX_TEST_CHECK_H
#define CX_TEST_CHECK_H

#include <math.h>
#include <stdio.h>

static int check_failures_;
static int check_count_;

#define CX_CHECK(cond)                                                          \
    do {                                                                        \
        check_count_++;                                                         \
        if (!(cond)) {                                                          \
            check_failures_++;                                                  \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
        }                                                                       \
    } while (0)

/* |a - b| <= atol + rtol |b| */
#define CX_CHECK_NEAR(a, b, rtol, atol)                                         \
    do {                                                                        \
        double ca_ = (double)(a), cb_ = (double)(b);                            \
        check_count_++;                                                         \
        if (!(fabs(ca_ - cb_) <= (atol) + (rtol) * fabs(cb_))) {                \
            check_failures_++;                                                  \
            fprintf(stderr, "%s:%d: %s = %.17g, expected %s = %.17g (rtol %g, atol %g)\n", \
                    __FILE__, __LINE__, #a, ca_, #b, cb_, (double)(rtol), (double)(atol)); \
        }                                                                       \
    } while (0)

/* a <= b */
#define CX_CHECK_LE(a, b)                                                       \
    do {                                                                        \
        double ca_ = (double)(a), cb_ = (double)(b);                            \
        check_count_++;                                                         \
        if (!(ca_ <= cb_)) {                                                    \
            check_failures_++;                                                  \
            fprintf(stderr, "%s:%d: %s = %.17g, expected <= %s = %.17g\n",      \
                    __FILE__, __LINE__, #a, ca_, #b, cb_);                      \
        }                                                                       \
    } while (0)

#define CX_CHECK_OK(expr)                                                       \
    do {                                                                        \
        int cs_ = (expr);                                                       \
        check_count_++;                                                         \
        if (cs_ != 0) {                                                         \
            check_failures_++;                                                  \
            fprintf(stderr, "%s:%d: %s returned %d\n", __FILE__, __LINE__, #expr, cs_); \
        }                                                                       \
    } while (0)

static inline int check_finish(const char *name)
{
    fprintf(stderr, "%s: %d checks, %d failed\n", name, check_count_, check_failures_);
    return check_failures_ ? 1 : 0;
}

#endif
