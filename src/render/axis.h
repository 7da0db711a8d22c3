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
} cx_axis;

/* Ticks for data in [lo, hi] with about `target` labelled ticks. With
 * expand, the range grows to the enclosing ticks (plots); without, it stays
 * [lo, hi] and only ticks inside are kept (colour bars). A degenerate range
 * is widened. Log axes need lo > 0. */
void cx_axis_make(cx_axis *a, double lo, double hi, int log, int target, int expand);

/* Position of v on the axis in [0, 1] (log: of log10 v). */
double cx_axis_frac(const cx_axis *a, double v);

/* The label of tick v: "0.25", "1200", "2.5e-06", log axes "10⁻⁶"
 * (UTF-8 superscripts). */
void cx_axis_label(const cx_axis *a, double v, char *buf, size_t len);

#endif
