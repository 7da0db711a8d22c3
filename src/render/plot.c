/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Line plots with cairo (see plot.h): axes with nice ticks and a grid,
 * series with lines/markers, reference lines, a legend in the emptiest
 * corner, then the PNG through png.c. */
#include "render/plot.h"
#include "render/render.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cx_config.h"
#include "out/palette.h"
#include "render/axis.h"
#include "render/pngfile.h"
#include "render/text.h"

static void plot_copy(char *dst, size_t len, const char *src)
{
    snprintf(dst, len, "%s", src ? src : "");
}

void cx_plot_init(cx_plot *p, const char *title, const char *xlabel, const char *ylabel)
{
    memset(p, 0, sizeof *p);
    plot_copy(p->title, sizeof p->title, title);
    plot_copy(p->xlabel, sizeof p->xlabel, xlabel);
    plot_copy(p->ylabel, sizeof p->ylabel, ylabel);
    p->legend = 1;
    p->font_scale = 1;
}

int cx_plot_add_series(cx_plot *p, const char *label, int n, const double *x,
                       const double *y, unsigned style)
{
    if (p->nseries >= CX_PLOT_MAX_SERIES || n < 0 || (n > 0 && (!x || !y)))
        return CX_EINVAL;
    cx_plot_series *s = &p->series[p->nseries];
    memset(s, 0, sizeof *s);
    plot_copy(s->label, sizeof s->label, label);
    s->n = n;
    s->x = x;
    s->y = y;
    s->style = style ? style : CX_PLOT_LINE;
    s->color = -1;
    p->nseries++;
    return CX_OK;
}

static int plot_add_ref(cx_plot *p, int vertical, double v, const char *label)
{
    if (p->nrefs >= CX_PLOT_MAX_REFS)
        return CX_EINVAL;
    cx_plot_ref *r = &p->refs[p->nrefs++];
    r->vertical = vertical;
    r->value = v;
    plot_copy(r->label, sizeof r->label, label);
    return CX_OK;
}

int cx_plot_add_vline(cx_plot *p, double x, const char *label)
{
    return plot_add_ref(p, 1, x, label);
}

int cx_plot_add_hline(cx_plot *p, double y, const char *label)
{
    return plot_add_ref(p, 0, y, label);
}

int cx_plot_add_text(cx_plot *p, const char *key, const char *value)
{
    if (p->ntext >= CX_PLOT_MAX_TEXT || !key || !key[0] || strlen(key) >= sizeof p->text[0].key)
        return CX_EINVAL;
    plot_copy(p->text[p->ntext].key, sizeof p->text[0].key, key);
    plot_copy(p->text[p->ntext].value, sizeof p->text[0].value, value);
    p->ntext++;
    return CX_OK;
}

void cx_plot_set_xrange(cx_plot *p, double lo, double hi)
{
    p->fixed_x = 1;
    p->xmin = lo;
    p->xmax = hi;
}

void cx_plot_set_yrange(cx_plot *p, double lo, double hi)
{
    p->fixed_y = 1;
    p->ymin = lo;
    p->ymax = hi;
}

/* ---- drawing ------------------------------------------------------------ */

/* The series colours: the one table the explorer uses too (out/palette.h). */
static void plot_rgb(cairo_t *cr, int color)
{
    const unsigned char *c = cx_palette_series[color % CX_PALETTE_NSERIES];
    cairo_set_source_rgb(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
}

static int plot_ok(double v, int log)
{
    return isfinite(v) && (!log || v > 0);
}

typedef struct plot_frame {
    double x0, y0, x1, y1;   /* plot area in pixels (y0 top) */
    double yd;               /* bottom of the data's y range (y1 without a zero band) */
    int zband;               /* log y with exact zeros: a band below the decades */
    double yz;               /* the band's centre, where y = 0 is drawn */
    double W;                /* the figure's width */
    double mx, my;           /* data kept this far inside the frame (markers whole) */
    cx_axis ax, ay;
} plot_frame;

/* A point is drawn if finite and positive on a log axis, or an exact 0
 * on a log y axis with its band. */
static int plot_drawable(const cx_plot *p, const plot_frame *f, double x, double y)
{
    return plot_ok(x, p->logx) && (plot_ok(y, p->logy) || (f->zband && y == 0.0));
}

static double plot_px(const plot_frame *f, double x)
{
    return f->x0 + f->mx + cx_axis_frac(&f->ax, x) * (f->x1 - f->x0 - 2 * f->mx);
}

static double plot_py(const plot_frame *f, double y)
{
    if (f->zband && y == 0.0)
        return f->yz;
    double bot = f->zband ? f->yd : f->yd - f->my;
    return bot - cx_axis_frac(&f->ay, y) * (bot - f->y0 - f->my);
}

/* Data ranges over drawable points and reference lines; 0 if none. */
static int plot_ranges(const cx_plot *p, double *xr, double *yr)
{
    xr[0] = yr[0] = INFINITY;
    xr[1] = yr[1] = -INFINITY;
    int any = 0, zeros = 0;
    for (int k = 0; k < p->nseries; k++) {
        const cx_plot_series *s = &p->series[k];
        for (int i = 0; i < s->n; i++) {
            if (p->logy && s->y[i] == 0.0 && plot_ok(s->x[i], p->logx)) {
                /* an exact 0: drawn in the zero band, at its x */
                xr[0] = fmin(xr[0], s->x[i]);
                xr[1] = fmax(xr[1], s->x[i]);
                zeros = 1;
                continue;
            }
            if (!plot_ok(s->x[i], p->logx) || !plot_ok(s->y[i], p->logy))
                continue;
            xr[0] = fmin(xr[0], s->x[i]);
            xr[1] = fmax(xr[1], s->x[i]);
            yr[0] = fmin(yr[0], s->y[i]);
            yr[1] = fmax(yr[1], s->y[i]);
            any = 1;
        }
    }
    for (int k = 0; k < p->nrefs; k++) {
        const cx_plot_ref *r = &p->refs[k];
        double *rr = r->vertical ? xr : yr;
        if (plot_ok(r->value, r->vertical ? p->logx : p->logy)) {
            rr[0] = fmin(rr[0], r->value);
            rr[1] = fmax(rr[1], r->value);
        }
    }
    if (!any && zeros && !(yr[1] >= yr[0])) {   /* zeros only: some decades above the band */
        yr[0] = 1e-3;
        yr[1] = 1;
    }
    if (!any && !zeros)
        return 0;
    if (p->fixed_x) {
        xr[0] = p->xmin;
        xr[1] = p->xmax;
    }
    if (p->fixed_y) {
        yr[0] = p->ymin;
        yr[1] = p->ymax;
    }
    return 1;
}

/* Eleven marker shapes: with the twelve colours (11 and 12 coprime),
 * series k gets colour k % 12 and shape k % 11, so that the first twelve
 * series differ in colour, the first eleven in shape too, the first 132
 * by the pair, and neighbours by both (told apart in grey print too). */
#define PLOT_NSHAPES 11
static const char *const plot_shape_names[PLOT_NSHAPES] = {
    "circle", "square", "triangle", "diamond", "triangle-down", "plus", "cross", "star", "pentagon",
    "triangle-left", "triangle-right"};

static int plot_color_of(const cx_plot_series *sr, int k)
{
    return (sr->color >= 0 ? sr->color : k) % CX_PALETTE_NSERIES;
}

/* Filled shapes are filled; the plus and the cross are stroked. */
static void plot_marker(cairo_t *cr, int shape, double x, double y, double r)
{
    switch (shape % PLOT_NSHAPES) {
    case 0:
        cairo_new_sub_path(cr);
        cairo_arc(cr, x, y, r, 0, 2 * CX_PI);
        break;
    case 1:
        cairo_rectangle(cr, x - 0.85 * r, y - 0.85 * r, 1.7 * r, 1.7 * r);
        break;
    case 2:
        cairo_move_to(cr, x, y - 1.15 * r);
        cairo_line_to(cr, x + r, y + 0.7 * r);
        cairo_line_to(cr, x - r, y + 0.7 * r);
        cairo_close_path(cr);
        break;
    case 3:
        cairo_move_to(cr, x, y - 1.2 * r);
        cairo_line_to(cr, x + r, y);
        cairo_line_to(cr, x, y + 1.2 * r);
        cairo_line_to(cr, x - r, y);
        cairo_close_path(cr);
        break;
    case 4:
        cairo_move_to(cr, x, y + 1.15 * r);
        cairo_line_to(cr, x + r, y - 0.7 * r);
        cairo_line_to(cr, x - r, y - 0.7 * r);
        cairo_close_path(cr);
        break;
    case 5:
        cairo_move_to(cr, x - 1.2 * r, y);
        cairo_line_to(cr, x + 1.2 * r, y);
        cairo_move_to(cr, x, y - 1.2 * r);
        cairo_line_to(cr, x, y + 1.2 * r);
        break;
    case 6:
        cairo_move_to(cr, x - r, y - r);
        cairo_line_to(cr, x + r, y + r);
        cairo_move_to(cr, x - r, y + r);
        cairo_line_to(cr, x + r, y - r);
        break;
    case 7:   /* a five-pointed star */
    case 8:   /* a pentagon */
    {
        int star = shape % PLOT_NSHAPES == 7, np = star ? 10 : 5;
        for (int i = 0; i < np; i++) {
            double a = -CX_PI / 2 + 2 * CX_PI * i / np, rr = star && (i & 1) ? 0.5 * r : 1.2 * r;
            if (i == 0)
                cairo_move_to(cr, x + rr * cos(a), y + rr * sin(a));
            else
                cairo_line_to(cr, x + rr * cos(a), y + rr * sin(a));
        }
        cairo_close_path(cr);
        break;
    }
    case 9:
        cairo_move_to(cr, x - 1.15 * r, y);
        cairo_line_to(cr, x + 0.7 * r, y - r);
        cairo_line_to(cr, x + 0.7 * r, y + r);
        cairo_close_path(cr);
        break;
    default:
        cairo_move_to(cr, x + 1.15 * r, y);
        cairo_line_to(cr, x - 0.7 * r, y - r);
        cairo_line_to(cr, x - 0.7 * r, y + r);
        cairo_close_path(cr);
        break;
    }
}

static void plot_marker_ink(cairo_t *cr, int shape, double s)
{
    if (shape % PLOT_NSHAPES == 5 || shape % PLOT_NSHAPES == 6) {
        cairo_set_line_width(cr, 2.0 * s);
        cairo_stroke(cr);
    } else {
        cairo_fill(cr);
    }
}

void cx_plot_series_style(const cx_plot *p, int k, int *color, const char **marker)
{
    *color = plot_color_of(&p->series[k], k);
    *marker = plot_shape_names[k % PLOT_NSHAPES];
}

static void plot_grid(cairo_t *cr, const plot_frame *f, const double *xs, int nx, const double *ys,
                      int ny, double grey)
{
    cairo_set_source_rgb(cr, grey, grey, grey);
    for (int i = 0; i < nx; i++) {
        double x = floor(plot_px(f, xs[i])) + 0.5;
        cairo_move_to(cr, x, f->y0);
        cairo_line_to(cr, x, f->y1);
    }
    for (int i = 0; i < ny; i++) {
        double y = floor(plot_py(f, ys[i])) + 0.5;
        cairo_move_to(cr, f->x0, y);
        cairo_line_to(cr, f->x1, y);
    }
    cairo_stroke(cr);
}

static void plot_axes(cairo_t *cr, const cx_plot *p, const plot_frame *f, double s)
{
    char lab[64];
    /* grid: minor then major, on pixel centres for crisp 1-px lines */
    cairo_set_line_width(cr, 1.0);
    plot_grid(cr, f, f->ax.minor, f->ax.nminor, f->ay.minor, f->ay.nminor, 0.93);
    plot_grid(cr, f, f->ax.ticks, f->ax.nticks, f->ay.ticks, f->ay.nticks, 0.82);
    /* frame and tick labels */
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_set_line_width(cr, 1.2 * s);
    cairo_rectangle(cr, f->x0, f->y0, f->x1 - f->x0, f->y1 - f->y0);
    cairo_stroke(cr);
    double fs = 14 * s, tick = 6 * s;
    for (int i = 0; i < f->ax.nticks; i++) {
        double x = plot_px(f, f->ax.ticks[i]);
        cairo_move_to(cr, x, f->y1);
        cairo_line_to(cr, x, f->y1 - tick);
        cairo_stroke(cr);
        cx_axis_label(&f->ax, f->ax.ticks[i], lab, sizeof lab);
        cx_text(cr, lab, x, f->y1 + 5 * s, fs, 0, 0.5, 0.0);
    }
    double maxw = 0;
    for (int i = 0; i < f->ay.nticks; i++) {
        double y = plot_py(f, f->ay.ticks[i]);
        cairo_move_to(cr, f->x0, y);
        cairo_line_to(cr, f->x0 + tick, y);
        cairo_stroke(cr);
        cx_axis_label(&f->ay, f->ay.ticks[i], lab, sizeof lab);
        double w = cx_text(cr, lab, f->x0 - 7 * s, y, fs, 0, 1.0, 0.5);
        maxw = fmax(maxw, w);
    }
    /* axis labels and title */
    /* labels and title shrink to fit the image's width rather than be
     * cut, and are centred on the image when the frame's centre leaves
     * them too little room on one side */
    double W = f->W, room = W - 8 * s;
    /* large or small linear values: ticks in units of 10^n, named after
     * the label as on the colour bar */
    char xlabel[CX_PLOT_LABELLEN + 32], ylabel[CX_PLOT_LABELLEN + 32];
    snprintf(xlabel, sizeof xlabel, "%s", p->xlabel);
    snprintf(ylabel, sizeof ylabel, "%s", p->ylabel);
    cx_axis_unit_suffix(&f->ax, xlabel + strlen(xlabel), sizeof xlabel - strlen(xlabel));
    cx_axis_unit_suffix(&f->ay, ylabel + strlen(ylabel), sizeof ylabel - strlen(ylabel));
    double fx = 16 * s, ft = 18 * s, wx = cx_text_width(cr, xlabel, fx, 0);
    double wt = cx_text_width(cr, p->title, ft, 1);
    if (wx > room) {
        fx *= room / wx;
        wx = room;
    }
    if (wt > room) {
        ft *= room / wt;
        wt = room;
    }
    double mid = 0.5 * (f->x0 + f->x1);
    double xc = 0.5 * wx + 4 * s > fmin(mid, W - mid) ? 0.5 * W : mid;
    double tc = 0.5 * wt + 4 * s > fmin(mid, W - mid) ? 0.5 * W : mid;
    cx_text(cr, xlabel, xc, f->y1 + 30 * s, fx, 0, 0.5, 0.0);
    cx_text_vertical(cr, ylabel, f->x0 - maxw - 24 * s, 0.5 * (f->y0 + f->y1), 16 * s, 0);
    cx_text(cr, p->title, tc, f->y0 - 14 * s, ft, 1, 0.5, 1.0);
}

static void plot_refs(cairo_t *cr, const cx_plot *p, const plot_frame *f, double s)
{
    double dash[] = {2 * s, 4 * s};
    for (int k = 0; k < p->nrefs; k++) {
        const cx_plot_ref *r = &p->refs[k];
        if (!plot_ok(r->value, r->vertical ? p->logx : p->logy))
            continue;
        cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
        cairo_set_line_width(cr, 1.5 * s);
        cairo_set_dash(cr, dash, 2, 0);
        if (r->vertical) {
            double x = plot_px(f, r->value);
            cairo_move_to(cr, x, f->y0);
            cairo_line_to(cr, x, f->y1);
            cairo_stroke(cr);
            cairo_set_dash(cr, NULL, 0, 0);
            cx_text_vertical(cr, r->label, x - 9 * s, f->y0 + 10 * s +
                             0.5 * cx_text_width(cr, r->label, 12 * s, 0), 12 * s, 0);
        } else {
            double y = plot_py(f, r->value);
            cairo_move_to(cr, f->x0, y);
            cairo_line_to(cr, f->x1, y);
            cairo_stroke(cr);
            cairo_set_dash(cr, NULL, 0, 0);
            cx_text(cr, r->label, f->x1 - 6 * s, y - 3 * s, 12 * s, 0, 1.0, 1.0);
        }
    }
    cairo_set_dash(cr, NULL, 0, 0);
}

/* The band of exact zeros on a log y axis: shaded, below a dashed break,
 * labelled where a tick label would be. */
static void plot_zero_band(cairo_t *cr, const plot_frame *f, double s)
{
    if (!f->zband)
        return;
    cairo_set_source_rgb(cr, 0.95, 0.95, 0.95);
    cairo_rectangle(cr, f->x0, f->yd + 3 * s, f->x1 - f->x0, f->y1 - f->yd - 3 * s);
    cairo_fill(cr);
    double dash[] = {5 * s, 4 * s};
    cairo_set_dash(cr, dash, 2, 0);
    cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
    cairo_set_line_width(cr, 1.2 * s);
    cairo_move_to(cr, f->x0, f->yd + 3 * s);
    cairo_line_to(cr, f->x1, f->yd + 3 * s);
    cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0);
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cx_text(cr, "0 (exact)", f->x0 - 7 * s, f->yz, 14 * s, 0, 1.0, 0.5);
}

static void plot_series(cairo_t *cr, const cx_plot *p, const plot_frame *f, double s)
{
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    double r = 4.0 * s;
    for (int k = 0; k < p->nseries; k++) {
        const cx_plot_series *sr = &p->series[k];
        plot_rgb(cr, plot_color_of(sr, k));
        if (sr->style & CX_PLOT_LINE) {
            /* lines stop at the frame */
            cairo_save(cr);
            cairo_rectangle(cr, f->x0, f->y0, f->x1 - f->x0, f->y1 - f->y0);
            cairo_clip(cr);
            double dash[] = {8 * s, 5 * s};
            cairo_set_dash(cr, dash, (sr->style & CX_PLOT_DASHED) ? 2 : 0, 0);
            cairo_set_line_width(cr, 2.2 * s);
            int pen = 0;
            for (int i = 0; i < sr->n; i++) {
                if (!plot_drawable(p, f, sr->x[i], sr->y[i])) {
                    pen = 0;
                    continue;
                }
                double x = plot_px(f, sr->x[i]), y = plot_py(f, sr->y[i]);
                if (pen)
                    cairo_line_to(cr, x, y);
                else
                    cairo_move_to(cr, x, y);
                pen = 1;
            }
            cairo_stroke(cr);
            cairo_set_dash(cr, NULL, 0, 0);
            cairo_restore(cr);
        }
        if (sr->style & CX_PLOT_MARKERS) {
            /* a marker on the frame (the last iterate, the largest time) is
             * drawn whole: markers are clipped only a marker beyond it */
            cairo_save(cr);
            cairo_rectangle(cr, f->x0 - 2 * r, f->y0 - 2 * r, f->x1 - f->x0 + 4 * r, f->y1 - f->y0 + 4 * r);
            cairo_clip(cr);
            /* a long series (hundreds of iterations) marks every few
             * points, and its last, so that the markers do not merge */
            int every = (int)fmax(1, ceil(sr->n * 3.0 * r / fmax(f->x1 - f->x0, 1)));
            for (int i = 0; i < sr->n; i++)
                if ((i % every == 0 || i == sr->n - 1) && plot_drawable(p, f, sr->x[i], sr->y[i]))
                    plot_marker(cr, k, plot_px(f, sr->x[i]), plot_py(f, sr->y[i]), r);
            plot_marker_ink(cr, k, s);
            cairo_restore(cr);
        }
    }
}

/* The legend: its box's size at scale s (a row per labelled series). */
typedef struct plot_legend_box {
    int n;                    /* entries */
    double fs, row, pad, sample;
    double x, y, w, h;        /* where it goes */
    int cols;                 /* entries side by side (below the plot) */
    double entry_w;           /* the width of one entry */
    int outside;              /* below the plot area (every corner covered something) */
    long hits;                /* data points and reference lines under it */
} plot_legend_box;

static void plot_legend_size(cairo_t *cr, const cx_plot *p, double s, plot_legend_box *b)
{
    double wmax = 0;
    b->n = 0;
    b->fs = 14 * s;
    for (int k = 0; k < p->nseries; k++)
        if (p->series[k].label[0]) {
            b->n++;
            wmax = fmax(wmax, cx_text_width(cr, p->series[k].label, b->fs, 0));
        }
    b->row = 22 * s;
    b->pad = 8 * s;
    b->sample = 34 * s;
    b->cols = 1;
    b->entry_w = b->pad * 2 + b->sample + wmax;
    b->w = b->pad + b->entry_w;
    b->h = b->pad * 2 + b->row * b->n;
}

/* The legend in columns across a width of room, rows as needed. */
static void plot_legend_columns(plot_legend_box *b, double room)
{
    int cols = (int)fmax(1, floor((room - b->pad) / b->entry_w));
    if (cols > b->n)
        cols = b->n;
    int rows = (b->n + cols - 1) / cols;
    cols = (b->n + rows - 1) / rows;   /* as even as the rows allow */
    b->cols = cols;
    b->w = b->pad + cols * b->entry_w;
    b->h = b->pad * 2 + b->row * rows;
}

/* Data points (and reference lines, their labels beside them, as many
 * points each) under the box at (bx, by). */
static long plot_legend_cover(const cx_plot *p, const plot_frame *f, double s, double bx, double by,
                              double bw, double bh)
{
    long hits = 0;
    double r = 5 * s;   /* a marker's reach */
    for (int k = 0; k < p->nseries; k++) {
        const cx_plot_series *sr = &p->series[k];
        double px = 0, py = 0;
        int prev = 0;
        for (int i = 0; i < sr->n; i++) {
            if (!plot_drawable(p, f, sr->x[i], sr->y[i])) {
                prev = 0;
                continue;
            }
            double x = plot_px(f, sr->x[i]), y = plot_py(f, sr->y[i]);
            hits += x >= bx - r && x <= bx + bw + r && y >= by - r && y <= by + bh + r;
            /* the line between points too: its midpoints */
            if (prev && (sr->style & CX_PLOT_LINE))
                for (int q = 1; q < 8; q++) {
                    double mx = px + (x - px) * q / 8, my = py + (y - py) * q / 8;
                    hits += mx >= bx && mx <= bx + bw && my >= by && my <= by + bh;
                }
            px = x;
            py = y;
            prev = 1;
        }
    }
    for (int k = 0; k < p->nrefs; k++) {
        const cx_plot_ref *rf = &p->refs[k];
        if (!plot_ok(rf->value, rf->vertical ? p->logx : p->logy))
            continue;
        double v = rf->vertical ? plot_px(f, rf->value) : plot_py(f, rf->value);
        double a = rf->vertical ? bx - 20 * s : by - 20 * s, b = rf->vertical ? bx + bw : by + bh + 4 * s;
        hits += (v >= a && v <= b) ? 50 : 0;
    }
    return hits;
}

/* The corner of the plot area that covers the fewest points. */
static void plot_legend_corner(const cx_plot *p, const plot_frame *f, double s, plot_legend_box *b)
{
    b->hits = -1;
    b->outside = 0;
    for (int corner = 0; corner < 4; corner++) {
        double bx = (corner & 1) ? f->x0 + b->pad : f->x1 - b->w - b->pad;
        double by = (corner & 2) ? f->y1 - b->h - b->pad : f->y0 + b->pad;
        long hits = plot_legend_cover(p, f, s, bx, by, b->w, b->h);
        if (b->hits < 0 || hits < b->hits) {
            b->hits = hits;
            b->x = bx;
            b->y = by;
        }
    }
}

static void plot_legend(cairo_t *cr, const cx_plot *p, const plot_legend_box *b, double s)
{
    if (!p->legend || b->n == 0)
        return;
    cairo_set_source_rgba(cr, 1, 1, 1, 0.9);
    cairo_rectangle(cr, b->x, b->y, b->w, b->h);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
    cairo_set_line_width(cr, 1.0 * s);
    cairo_stroke(cr);
    int r = 0;
    for (int k = 0; k < p->nseries; k++) {
        const cx_plot_series *sr = &p->series[k];
        if (!sr->label[0])
            continue;
        double y = b->y + b->pad + b->row * (r / b->cols + 0.5), x = b->x + b->pad + b->entry_w * (r % b->cols);
        plot_rgb(cr, plot_color_of(sr, k));
        if (sr->style & CX_PLOT_LINE) {
            double dash[] = {8 * s, 5 * s};
            cairo_set_dash(cr, dash, (sr->style & CX_PLOT_DASHED) ? 2 : 0, 0);
            cairo_set_line_width(cr, 2.2 * s);
            cairo_move_to(cr, x, y);
            cairo_line_to(cr, x + b->sample, y);
            cairo_stroke(cr);
            cairo_set_dash(cr, NULL, 0, 0);
        }
        if (sr->style & CX_PLOT_MARKERS) {
            plot_marker(cr, k, x + 0.5 * b->sample, y, 4.0 * s);
            plot_marker_ink(cr, k, s);
        }
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        cx_text(cr, sr->label, x + b->sample + b->pad, y, b->fs, 0, 0.0, 0.5);
        r++;
    }
}

/* The frame and axes of a w x h plot whose bottom `reserve` pixels hold
 * the legend. */
static void plot_layout(const cx_plot *p, plot_frame *f, int w, int h, double s, const double *xr,
                        const double *yr, double reserve)
{
    f->W = w;
    f->x0 = 88 * s;
    f->x1 = w - 22 * s;
    f->y0 = 46 * s;
    f->y1 = h - 60 * s - reserve;
    f->yd = f->y1;
    f->mx = f->my = 6 * s;
    f->zband = 0;
    if (p->logy)
        for (int k = 0; k < p->nseries && !f->zband; k++)
            for (int i = 0; i < p->series[k].n; i++)
                if (p->series[k].y[i] == 0.0 && plot_ok(p->series[k].x[i], p->logx)) {
                    f->zband = 1;
                    break;
                }
    if (f->zband) {
        f->yd = f->y1 - 34 * s;
        f->yz = 0.5 * (f->yd + 3 * s + f->y1);
    }
    int xt = (int)fmax(3, (f->x1 - f->x0) / (110 * s));
    if (p->integer_x && !p->logx)   /* integer steps: no tick at 1.5 or 2.5 */
        cx_axis_make_integer(&f->ax, xr[0], xr[1], xt, !p->fixed_x);
    else
        cx_axis_make(&f->ax, xr[0], xr[1], p->logx, xt, !p->fixed_x);
    cx_axis_make(&f->ay, yr[0], yr[1], p->logy, (int)fmax(3, (f->y1 - f->y0) / (70 * s)), !p->fixed_y);
    cx_axis_unit(&f->ax);
    cx_axis_unit(&f->ay);
}

/* Lay the plot out: the legend in a corner of the plot area where it
 * covers nothing (no point, line or reference line), else below the
 * plot in as many columns as the width holds (the area gets shorter),
 * its text shrinking if it would take more than a third of the height. */
static int plot_arrange(cairo_t *cr, const cx_plot *p, int w, int h, plot_frame *f, plot_legend_box *lb,
                        double *sp, cx_diag *d)
{
    double xr[2], yr[2];
    if (!plot_ranges(p, xr, yr))
        return cx_diag_set(d, CX_EINVAL, "plot '%s': no point to draw", p->title);
    if ((p->logx && !(xr[0] > 0)) || (p->logy && !(yr[0] > 0)))
        return cx_diag_set(d, CX_EINVAL, "plot '%s': a log axis needs a positive range", p->title);
    /* every size in proportion to the tick-label font (14 s), which is
     * cx_render_font_px: legible when the figure is printed small */
    double s = cx_render_font_px(w, h, p->font_scale) / 14.0;
    *sp = s;
    plot_layout(p, f, w, h, s, xr, yr, 0);
    memset(lb, 0, sizeof *lb);
    if (!p->legend)
        return CX_OK;
    plot_legend_size(cr, p, s, lb);
    if (lb->n == 0)
        return CX_OK;
    plot_legend_corner(p, f, s, lb);
    if (lb->hits == 0)
        return CX_OK;
    double s2 = s, room = w - 16 * s;
    for (int tries = 0; tries < 4; tries++) {
        plot_legend_size(cr, p, s2, lb);
        plot_legend_columns(lb, room);
        if (lb->h <= h / 3.0 && lb->w <= room)
            break;
        s2 *= fmin(h / 3.0 / lb->h, room / lb->w) * 0.98;
    }
    plot_layout(p, f, w, h, s, xr, yr, lb->h + 6 * s);
    lb->outside = 1;
    lb->x = 0.5 * (w - lb->w);
    lb->y = h - lb->h - 6 * s;
    lb->hits = 0;
    return CX_OK;
}

int cx_plot_legend_place(const cx_plot *p, int w, int h, int *outside, long *covered, cx_diag *d)
{
    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 8, 8);
    cairo_t *cr = cairo_create(surf);
    plot_frame f;
    plot_legend_box lb;
    double s;
    int rc = plot_arrange(cr, p, w, h, &f, &lb, &s, d);
    if (rc == CX_OK) {
        *outside = lb.outside;
        *covered = lb.n ? plot_legend_cover(p, &f, s, lb.x, lb.y, lb.w, lb.h) : 0;
    }
    cairo_destroy(cr);
    cairo_surface_destroy(surf);
    return rc;
}

int cx_plot_draw_cairo(const cx_plot *p, cairo_t *cr, int w, int h, cx_diag *d)
{
    plot_frame f;
    plot_legend_box lb;
    double s;
    CX_TRY(plot_arrange(cr, p, w, h, &f, &lb, &s, d));
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    plot_axes(cr, p, &f, s);
    plot_zero_band(cr, &f, s);
    plot_refs(cr, p, &f, s);
    plot_series(cr, p, &f, s);
    plot_legend(cr, p, &lb, lb.fs / 14.0);
    cairo_status_t st = cairo_status(cr);
    if (st != CAIRO_STATUS_SUCCESS)
        return cx_diag_set(d, CX_EEXTERNAL, "cairo: %s", cairo_status_to_string(st));
    return CX_OK;
}

int cx_plot_draw_rgb(const cx_plot *p, unsigned char *buf, int w, int h, int stride, cx_diag *d)
{
    if (w < 64 || h < 64 || w > 16384 || h > 16384 || stride < 4 * w)
        return cx_diag_set(d, CX_EINVAL, "plot size %dx%d: expected 64..16384 pixels each way", w, h);
    cairo_surface_t *surf = cairo_image_surface_create_for_data(buf, CAIRO_FORMAT_RGB24, w, h, stride);
    if (cairo_surface_status(surf) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(surf);
        return cx_diag_set(d, CX_EEXTERNAL, "cairo: cannot create a %dx%d surface", w, h);
    }
    cairo_t *cr = cairo_create(surf);
    int rc = cx_plot_draw_cairo(p, cr, w, h, d);
    cairo_destroy(cr);
    cairo_surface_flush(surf);
    cairo_surface_destroy(surf);
    return rc;
}

int cx_plot_write_png(const cx_plot *p, const char *path, int w, int h, cx_diag *d)
{
    if (w < 64 || h < 64 || w > 16384 || h > 16384)
        return cx_diag_set(d, CX_EINVAL, "plot size %dx%d: expected 64..16384 pixels each way", w, h);
    int stride = cairo_format_stride_for_width(CAIRO_FORMAT_RGB24, w);
    unsigned char *buf = cx_calloc((size_t)stride, (size_t)h);
    if (!buf)
        return cx_diag_set(d, CX_ENOMEM, "plot %dx%d: out of memory", w, h);
    int rc = cx_plot_draw_rgb(p, buf, w, h, stride, d);
    if (rc == CX_OK) {
        /* "Series": one line per series, its legend entry, colour index
         * and marker shape, so that a reader (or a test) can tell which
         * mark is which without the pixels */
        char series[CX_PLOT_MAX_SERIES * (CX_PLOT_LABELLEN + 40)];
        size_t ns = 0;
        series[0] = '\0';
        for (int k = 0; k < p->nseries; k++) {
            int c;
            const char *m;
            cx_plot_series_style(p, k, &c, &m);
            ns += (size_t)snprintf(series + ns, sizeof series - ns, "%s%s\tcolor=%d\tmarker=%s",
                                   k ? "\n" : "", p->series[k].label, c, m);
        }
        cx_png_text text[CX_PLOT_MAX_TEXT + 3];
        int nt = 0;
        text[nt++] = (cx_png_text){"Title", p->title};
        text[nt++] = (cx_png_text){"Software", "signorini " CX_VERSION};
        text[nt++] = (cx_png_text){"Series", series};
        for (int i = 0; i < p->ntext; i++)
            text[nt++] = (cx_png_text){p->text[i].key, p->text[i].value};
        rc = cx_png_write_xrgb(path, buf, w, h, stride, text, nt, d);
    }
    cx_free(buf);
    return rc;
}
