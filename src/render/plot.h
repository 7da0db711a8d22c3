/* SPDX-License-Identifier: GPL-3.0-or-later */
/* render/plot.h: line plots to PNG, drawn with cairo (no GL, no display).
 *
 * A cx_plot is a plain struct the caller fills: a title, axis labels, linear
 * or logarithmic axes, up to CX_PLOT_MAX_SERIES series and a few reference
 * lines. Nothing is allocated until cx_plot_write_png(), which draws the
 * plot with readable axes (nice ticks, decades on log axes), a grid and a
 * legend, and writes an 8-bit RGB PNG through a temporary file renamed into
 * place (a failure leaves no file). The PNG carries tEXt chunks: "Title",
 * "Software" (signorini VERSION) and any pairs added with
 * cx_plot_add_text(). The same plot written twice gives identical bytes.
 *
 * Ownership: labels and text are copied into the struct (truncated to the
 * array sizes); the x[] and y[] arrays of a series are BORROWED and must
 * stay valid until cx_plot_write_png() returns.
 *
 * Points that cannot be drawn are skipped and break the line there: NaN or
 * Inf, and values < 0 on a logarithmic axis, or 0 on a logarithmic x axis.
 * An exact 0 on a logarithmic y axis (an error that vanished) is drawn in
 * a shaded band below the lowest decade, labelled "0 (exact)", not at an
 * arbitrary floor.
 *
 * Series k is drawn in colour k % 12 of the series palette shared with
 * the explorer (out/palette.h; unless its color says) with marker shape
 * k % 11: twelve series differ in colour, every pair differs for up to
 * 132 series, and neighbours in both. The legend goes in a corner of
 * the plot area with nothing under it, else below the plot in columns. The PNG's "Series"
 * tEXt chunk lists them, one line each: "LABEL\tcolor=C\tmarker=SHAPE". Axis ranges come from the drawable data
 * and the reference lines, unless fixed with cx_plot_set_xrange/yrange.
 *
 * Example (convergence history of two methods, semilog):
 *
 *     cx_plot pl;
 *     cx_plot_init(&pl, "hertz N=64: convergence", "iteration", "kkt error");
 *     pl.logy = 1;
 *     cx_plot_add_series(&pl, "ssn-tresca", n1, it1, kkt1, CX_PLOT_LINE | CX_PLOT_MARKERS);
 *     cx_plot_add_series(&pl, "pdas", n2, it2, kkt2, CX_PLOT_LINE | CX_PLOT_DASHED);
 *     cx_plot_add_hline(&pl, 1e-10, "tol");
 *     cx_plot_add_text(&pl, "scene", "hertz");
 *     if (cx_plot_write_png(&pl, "conv.png", 1200, 800, &diag) != CX_OK)
 *         fprintf(stderr, "%s\n", diag.msg);
 */
#ifndef CX_RENDER_PLOT_H
#define CX_RENDER_PLOT_H

#include "base/base.h"

#define CX_PLOT_MAX_SERIES 32
#define CX_PLOT_MAX_REFS 8
#define CX_PLOT_MAX_TEXT 12
#define CX_PLOT_LABELLEN 96

/* Series style bits (combine with |; 0 means CX_PLOT_LINE). */
#define CX_PLOT_LINE    0x1u   /* a polyline through the points */
#define CX_PLOT_MARKERS 0x2u   /* a marker at each point */
#define CX_PLOT_DASHED  0x4u   /* the line dashed (with CX_PLOT_LINE) */

typedef struct cx_plot_series {
    char label[CX_PLOT_LABELLEN];   /* legend entry ("" = not in the legend) */
    int n;
    const double *x, *y;            /* borrowed, n values each */
    unsigned style;                 /* CX_PLOT_* bits */
    int color;                      /* palette index; -1 = the series index */
} cx_plot_series;

/* A reference line across the plot: vertical at x = value (e.g. the
 * baseline's time in a work-precision plot) or horizontal at y = value
 * (e.g. the tolerance). Drawn grey and dotted, labelled at its end. */
typedef struct cx_plot_ref {
    int vertical;                   /* 1: x = value, 0: y = value */
    double value;
    char label[CX_PLOT_LABELLEN];
} cx_plot_ref;

typedef struct cx_plot_text {
    char key[32];                   /* PNG tEXt keyword: 1-79 Latin-1 chars */
    char value[256];
} cx_plot_text;

typedef struct cx_plot {
    char title[160];
    char xlabel[CX_PLOT_LABELLEN], ylabel[CX_PLOT_LABELLEN];
    int logx, logy;                 /* 1: logarithmic axis (base 10) */
    int fixed_x, fixed_y;           /* set by cx_plot_set_xrange/yrange */
    double xmin, xmax, ymin, ymax;
    int legend;                     /* 1 (default): draw the legend; 0: none */
    int integer_x;                  /* x counts (iterations): integer ticks only */
    double font_scale;              /* text size factor (default 1: cx_render_font_px) */
    int nseries;
    cx_plot_series series[CX_PLOT_MAX_SERIES];
    int nrefs;
    cx_plot_ref refs[CX_PLOT_MAX_REFS];
    int ntext;
    cx_plot_text text[CX_PLOT_MAX_TEXT];
} cx_plot;

/* Empty plot with linear axes, a legend, and these labels (NULL = ""). */
void cx_plot_init(cx_plot *p, const char *title, const char *xlabel, const char *ylabel);

/* Add a series (x, y borrowed; n >= 0). CX_EINVAL when the plot is full
 * or n < 0 or an array is NULL with n > 0. */
int cx_plot_add_series(cx_plot *p, const char *label, int n, const double *x,
                       const double *y, unsigned style);
/* Reference lines; CX_EINVAL when CX_PLOT_MAX_REFS are already set. */
int cx_plot_add_vline(cx_plot *p, double x, const char *label);
int cx_plot_add_hline(cx_plot *p, double y, const char *label);
/* A tEXt chunk for the PNG (e.g. "scene"/"hertz"); CX_EINVAL when full or
 * the key is empty or longer than 31 chars. */
int cx_plot_add_text(cx_plot *p, const char *key, const char *value);
/* Fix an axis range instead of fitting the data (lo < hi; > 0 on a log axis). */
void cx_plot_set_xrange(cx_plot *p, double lo, double hi);
void cx_plot_set_yrange(cx_plot *p, double lo, double hi);

/* The colour (palette index) and marker shape name ("circle", "square",
 * "triangle", "diamond", "triangle-down", "plus", "cross") of series k. */
void cx_plot_series_style(const cx_plot *p, int k, int *color, const char **marker);

/* Draw and write the plot as a w x h PNG (64 <= w, h <= 16384). Errors:
 * CX_EINVAL (sizes; no drawable point at all), CX_EIO (cannot write path:
 * one line naming it, no file left behind), CX_EEXTERNAL (cairo/libpng). */
int cx_plot_write_png(const cx_plot *p, const char *path, int w, int h, cx_diag *d);

/* Draw the plot into an RGB24 buffer the caller owns (top-down rows of w
 * pixels, `stride` bytes apart, stride >= 4 w; cairo's native-endian
 * 0x00RRGGBB words), e.g. to compose it into a larger image. */
int cx_plot_draw_rgb(const cx_plot *p, unsigned char *buf, int w, int h, int stride, cx_diag *d);

/* Where the legend goes in a w x h figure: *outside 1 when it is below
 * the plot area (every corner of the area held something), and *covered
 * the data points and reference lines under it (0 unless nothing else
 * was possible). CX_EINVAL as cx_plot_write_png. */
int cx_plot_legend_place(const cx_plot *p, int w, int h, int *outside, long *covered, cx_diag *d);

/* Draw the plot on any cairo context (an image, SVG or PDF surface:
 * render/vector.h), in w x h units. */
typedef struct _cairo cairo_t;
int cx_plot_draw_cairo(const cx_plot *p, cairo_t *cr, int w, int h, cx_diag *d);

#endif
