/* SPDX-License-Identifier: GPL-3.0-or-later */
/* render/axis.h (internal): nice axis ticks and their labels, shared by the
 * plots and the colour bar. */
#ifndef CX_RENDER_AXIS_H
#define CX_RENDER_AXIS_H

#include <stddef.h>

#define CX_AXIS_MAX_TICKS 64

typedef struct cx_axis {
    int log;                  /* base-10 logarithmic */
    double lo, hi;            /* the range shown (log: the values, > 0) */
    int nticks;
    double ticks[CX_AXIS_MAX_TICKS];   /* labelled ticks, ascending */
    int nminor;
    double minor[CX_AXIS_MAX_TICKS];   /* unlabelled ticks (log: 2..9 x 10^k) */
    double step;              /* linear: tick spacing; log: decades per tick */
    int exp10;                /* linear: labels in units of 10^exp10 (0: plain) */
} cx_axis;

/* Ticks for data in [lo, hi] with about `target` labelled ticks. With
 * expand, the range grows to the enclosing ticks (plots); without, it stays
 * [lo, hi] and only ticks inside are kept (colour bars). A degenerate range
 * is widened. Log axes need lo > 0. */
void cx_axis_make(cx_axis *a, double lo, double hi, int log, int target, int expand);

/* A linear axis of counts (iterations): integer steps of 1, 2 or 5 times
 * 10^k, never 2.5. */
void cx_axis_make_integer(cx_axis *a, double lo, double hi, int target, int expand);

/* Colour-bar ticks of [lo, hi] (not expanded). Linear: values of 10^4
 * and more, or below 10^-2, are labelled in units of a common power of
 * ten, a->exp10, which the bar's title names ("×10⁵"); log: decades. */
void cx_axis_colorbar(cx_axis *a, double lo, double hi, int log, int target);
/* The same unit on a linear axis already made (plots). */
void cx_axis_unit(cx_axis *a);
/* ", ×10⁵" for a->exp10 = 5, "" for 0: the title's suffix. */
void cx_axis_unit_suffix(const cx_axis *a, char *buf, size_t len);

/* Position of v on the axis in [0, 1] (log: of log10 v). */
double cx_axis_frac(const cx_axis *a, double v);

/* The label of tick v: "0.25", "1200", "2.5×10⁻⁶" (never C's "2.5e-06"),
 * log axes "10⁻⁶" (UTF-8 superscripts); in units of 10^exp10 if set. */
void cx_axis_label(const cx_axis *a, double v, char *buf, size_t len);

#endif
