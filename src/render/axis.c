/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Nice ticks: steps of 1, 2 or 5 times a power of ten (linear axes), whole
 * decades (log axes). */
#include "render/axis.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* integer: counts (iterations), steps of 1, 2 or 5 times 10^k, k >= 0 */
static double axis_nice_step(double span, int target, int integer)
{
    double raw = span / (target > 1 ? target : 1);
    double p = pow(10.0, floor(log10(raw)));
    double f = raw / p;
    double nice = f <= 1.0 ? 1.0 : f <= 2.0 ? 2.0 : f <= 2.5 && !integer ? 2.5 : f <= 5.0 ? 5.0 : 10.0;
    return integer ? fmax(1.0, nice * p) : nice * p;
}

static void axis_make_linear(cx_axis *a, double lo, double hi, int target, int expand, int integer)
{
    /* a span of rounding noise (a uniform pressure 1 ± 1e-8) reads as a
     * constant, not as ticks with nine digits */
    if (!(hi - lo > 1e-6 * fmax(fabs(lo), fabs(hi)))) {
        lo = hi = 0.5 * (lo + hi);
        double c = lo, w = fabs(lo) > 0 ? 0.1 * fabs(lo) : 1.0;
        lo = c - w;
        hi = c + w;
    }
    double step = axis_nice_step(hi - lo, target, integer);
    double t0 = floor(lo / step + 1e-9) * step;
    double t1 = ceil(hi / step - 1e-9) * step;
    if (expand) {
        lo = t0;
        hi = t1;
    }
    a->lo = lo;
    a->hi = hi;
    a->step = step;
    a->nticks = 0;
    double eps = 1e-9 * step;
    for (long k = (long)floor(t0 / step + 0.5); a->nticks < CX_AXIS_MAX_TICKS; k++) {
        double v = (double)k * step;
        if (v > hi + eps)
            break;
        if (v < lo - eps)
            continue;
        if (fabs(v) < eps)
            v = 0.0;
        a->ticks[a->nticks++] = v;
    }
}

static void axis_make_log(cx_axis *a, double lo, double hi, int target, int expand)
{
    if (!(lo > 0))
        lo = hi > 0 ? hi * 1e-3 : 1e-3;
    if (!(hi > lo))
        hi = lo * 10.0;
    double e0 = floor(log10(lo) + 1e-9), e1 = ceil(log10(hi) - 1e-9);
    if (e1 <= e0)
        e1 = e0 + 1;
    if (expand) {
        lo = pow(10.0, e0);
        hi = pow(10.0, e1);
    }
    a->lo = lo;
    a->hi = hi;
    int decades = (int)(e1 - e0);
    int every = 1;
    while (decades / every > (target > 1 ? target + 2 : 3))
        every++;
    a->step = every;
    a->nticks = a->nminor = 0;
    /* the span shown, not the decades touched: a bar from 2e3 to 3e5 spans
     * 2.2 decades but touches 4, and two labels would leave it unreadable */
    double span = log10(hi / lo);
    for (int e = (int)e0; e <= (int)e1; e++) {
        double v = pow(10.0, e);
        if ((e - (int)e0) % every == 0 && v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9) &&
            a->nticks < CX_AXIS_MAX_TICKS)
            a->ticks[a->nticks++] = v;
        if (every == 1 && decades <= 8)
            for (int m = 2; m <= 9 && a->nminor < CX_AXIS_MAX_TICKS; m++) {
                double u = m * v;
                if (!(u >= lo * (1 - 1e-9) && u <= hi * (1 + 1e-9)))
                    continue;
                /* up to 2.5 decades: label 2 and 5 too; under one: every
                 * multiple (a bar from 0.3 to 2 has 10⁰ alone otherwise) */
                int label = span <= 2.5 && (m == 2 || m == 5);
                if (span < 0.8)
                    label = 1;
                if (label && a->nticks < CX_AXIS_MAX_TICKS)
                    a->ticks[a->nticks++] = u;
                else
                    a->minor[a->nminor++] = u;
            }
    }
    /* ascending, as the header promises (2 and 5 were appended after their
     * decade) */
    for (int i = 1; i < a->nticks; i++)
        for (int j = i; j > 0 && a->ticks[j - 1] > a->ticks[j]; j--) {
            double t = a->ticks[j];
            a->ticks[j] = a->ticks[j - 1];
            a->ticks[j - 1] = t;
        }
}

void cx_axis_make(cx_axis *a, double lo, double hi, int log, int target, int expand)
{
    memset(a, 0, sizeof *a);
    a->log = log;
    if (log)
        axis_make_log(a, lo, hi, target, expand);
    else
        axis_make_linear(a, lo, hi, target, expand, 0);
}

void cx_axis_make_integer(cx_axis *a, double lo, double hi, int target, int expand)
{
    memset(a, 0, sizeof *a);
    axis_make_linear(a, lo, hi, target, expand, 1);
}

double cx_axis_frac(const cx_axis *a, double v)
{
    if (a->log)
        return (log10(v) - log10(a->lo)) / (log10(a->hi) - log10(a->lo));
    return (v - a->lo) / (a->hi - a->lo);
}

/* Append the UTF-8 superscript form of an integer exponent. */
static void axis_superscript(int e, char *buf, size_t len)
{
    static const char *digits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
    char plain[16];
    snprintf(plain, sizeof plain, "%d", e);
    size_t n = strlen(buf);
    for (const char *c = plain; *c && n + 4 < len; c++) {
        const char *s = *c == '-' ? "⁻" : digits[*c - '0'];
        size_t k = strlen(s);
        memcpy(buf + n, s, k);
        n += k;
    }
    buf[n] = '\0';
}

void cx_axis_colorbar(cx_axis *a, double lo, double hi, int log, int target)
{
    cx_axis_make(a, lo, hi, log, target, 0);
    cx_axis_unit(a);
}

void cx_axis_unit(cx_axis *a)
{
    if (a->log || a->nticks == 0)
        return;
    double big = fmax(fabs(a->lo), fabs(a->hi));
    int e = big > 0 ? (int)floor(log10(big) + 1e-9) : 0;
    if (e >= 4 || e <= -3)
        a->exp10 = e;
}

void cx_axis_unit_suffix(const cx_axis *a, char *buf, size_t len)
{
    buf[0] = '\0';
    if (a->exp10 == 0 || len < 8)
        return;
    snprintf(buf, len, ", ×10");
    axis_superscript(a->exp10, buf, len);
}

/* "1.5×10⁹": v with `digits` significant digits, in the form a reader
 * writes, trailing zeros dropped. */
static void axis_sci(double v, int digits, char *buf, size_t len)
{
    int e = (int)floor(log10(fabs(v)) + 1e-9);
    double m = v / pow(10.0, e);
    char mant[32];
    snprintf(mant, sizeof mant, "%.*f", digits > 1 ? digits - 1 : 0, m);
    if (strchr(mant, '.')) {   /* 1.50 -> 1.5, 2.0 -> 2 */
        char *z = mant + strlen(mant) - 1;
        while (*z == '0')
            *z-- = '\0';
        if (*z == '.')
            *z = '\0';
    }
    if (strcmp(mant, "10") == 0 || strcmp(mant, "-10") == 0) {   /* rounded up a decade */
        snprintf(mant, sizeof mant, "%s1", v < 0 ? "-" : "");
        e++;
    }
    snprintf(buf, len, "%s×10", mant);
    axis_superscript(e, buf, len);
}

/* The fewest decimals that write every tick of a linear axis exactly
 * (one count for the whole axis, so that 0.5 and 1.0 line up): steps of 0.2
 * need one, of 0.25 two. Computed from the ticks, not from log10 of the
 * step, so that a step of 0.2500000001 after scaling by 10^n is still 0.25. */
static int axis_decimals(const cx_axis *a)
{
    for (int dec = 0; dec < 9; dec++) {
        double q = pow(10.0, dec);
        int ok = 1;
        for (int i = 0; i < a->nticks && ok; i++)
            ok = fabs(round(a->ticks[i] * q) / q - a->ticks[i]) <= 1e-6 * a->step;
        /* the ticks of the axis, or the step alone when there are none */
        if (ok && (a->nticks > 0 || fabs(round(a->step * q) / q - a->step) <= 1e-6 * a->step))
            return dec;
    }
    return 9;
}

void cx_axis_label(const cx_axis *a, double v, char *buf, size_t len)
{
    if (!a->log && a->exp10 != 0) {   /* in units of 10^exp10 */
        cx_axis u = *a;
        double unit = pow(10.0, a->exp10);
        u.exp10 = 0;
        u.lo /= unit;
        u.hi /= unit;
        u.step /= unit;
        for (int i = 0; i < u.nticks; i++)
            u.ticks[i] /= unit;
        cx_axis_label(&u, v / unit, buf, len);
        return;
    }
    if (a->log) {
        int e = (int)floor(log10(v) + 0.5);
        if (fabs(v / pow(10.0, e) - 1.0) > 1e-9) {   /* 2 or 5 x 10^k */
            /* in the decade's own notation, so that 0.002 does not sit
             * between 10⁻³ and 10⁻²: "2×10⁻³" (plain beside 1 and 10) */
            int k = (int)floor(log10(v) + 1e-9);
            if (k >= -1 && k <= 1) {
                snprintf(buf, len, "%g", v);
                return;
            }
            snprintf(buf, len, "%.0f×10", v / pow(10.0, k));
            axis_superscript(k, buf, len);
            return;
        }
        if (e == 0 || e == 1) {
            snprintf(buf, len, "%g", pow(10.0, e));
            return;
        }
        snprintf(buf, len, "10");
        axis_superscript(e, buf, len);
        return;
    }
    double mag = fmax(fabs(a->lo), fabs(a->hi));
    if (v == 0.0) {
        snprintf(buf, len, "0");
    } else if (mag >= 1e5 || mag < 1e-3) {
        /* scientific with as many digits as the step needs */
        int digits = (int)ceil(log10(mag / a->step) - 1e-9) + 1;
        if (digits < 1)
            digits = 1;
        if (digits > 6)
            digits = 6;
        axis_sci(v, digits, buf, len);
    } else {
        snprintf(buf, len, "%.*f", axis_decimals(a), v);
        return;
    }
}
