/* SPDX-License-Identifier: GPL-3.0-or-later */
/* render/text.h (internal): text with cairo, anchored. One font family
 * (DejaVu Sans through fontconfig), so every image looks the same. */
#ifndef CX_RENDER_TEXT_H
#define CX_RENDER_TEXT_H

/* cairo's own typedef (C11 allows repeating it), so this header does not
 * need cairo's include path. */
typedef struct _cairo cairo_t;

/* Draw s with its anchor point at (x, y): ax = 0 left, 0.5 centre, 1 right;
 * ay = 0 top, 0.5 middle, 1 baseline-ish bottom. Returns the text width. */
double cx_text(cairo_t *cr, const char *s, double x, double y, double size, int bold,
               double ax, double ay);
/* Width of s at this size (no drawing). */
double cx_text_width(cairo_t *cr, const char *s, double size, int bold);
/* The same, rotated by -90 degrees (reading upwards), centred at (x, y). */
void cx_text_vertical(cairo_t *cr, const char *s, double x, double y, double size, int bold);
/* cx_text within maxw: the size shrinks down to 3/4, then the text is cut
 * with an ellipsis. */
double cx_text_fit(cairo_t *cr, const char *s, double x, double y, double size, int bold,
                   double ax, double ay, double maxw);

/* Text as text, for SVG: while a recorder is attached to a surface, cx_text
 * on it records each string (where it starts, in device units, its size,
 * angle, weight and colour) instead of drawing glyphs, so that the file can
 * carry <text> elements a reader can select, search and edit. */
typedef struct _cairo_surface cairo_surface_t;
typedef struct cx_text_item {
    char *s;
    double x, y, size, angle;   /* baseline start (device units), degrees clockwise */
    int bold;
    double rgb[3];
} cx_text_item;
typedef struct cx_text_rec {
    cx_text_item *v;
    int n, cap;
    int failed;                 /* out of memory: some text was lost */
} cx_text_rec;
void cx_text_record_attach(cairo_surface_t *surf, cx_text_rec *rec);
void cx_text_rec_clear(cx_text_rec *rec);

#endif
