/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Anchored text with cairo's toy font API (enough for labels and titles). */
#include "render/text.h"

#include "base/base.h"

#include <cairo.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* cairo's user-data key: only its address matters (no state) */
static const cairo_user_data_key_t text_rec_key;

void cx_text_record_attach(cairo_surface_t *surf, cx_text_rec *rec)
{
    cairo_surface_set_user_data(surf, &text_rec_key, rec, NULL);
}

void cx_text_rec_clear(cx_text_rec *rec)
{
    for (int i = 0; i < rec->n; i++)
        cx_free(rec->v[i].s);
    cx_free(rec->v);
    memset(rec, 0, sizeof *rec);
}

/* Record s at the current point of cr; 1 if recorded (no glyphs drawn). */
static int text_record(cairo_t *cr, const char *s, double size, int bold)
{
    cx_text_rec *rec = cairo_surface_get_user_data(cairo_get_target(cr), &text_rec_key);
    if (!rec)
        return 0;
    if (rec->n == rec->cap) {
        int cap = rec->cap ? 2 * rec->cap : 64;
        cx_text_item *v = cx_realloc(rec->v, sizeof *v * (size_t)cap);
        if (!v) {
            rec->failed = 1;
            return 1;
        }
        rec->v = v;
        rec->cap = cap;
    }
    cx_text_item *it = &rec->v[rec->n];
    double x, y, ux = 1, uy = 0;
    cairo_get_current_point(cr, &x, &y);
    cairo_user_to_device(cr, &x, &y);
    cairo_user_to_device_distance(cr, &ux, &uy);
    it->x = x;
    it->y = y;
    it->size = size * hypot(ux, uy);
    it->angle = atan2(uy, ux) * 180 / 3.141592653589793;
    it->bold = bold;
    double a = 1;
    it->rgb[0] = it->rgb[1] = it->rgb[2] = 0;
    cairo_pattern_get_rgba(cairo_get_source(cr), &it->rgb[0], &it->rgb[1], &it->rgb[2], &a);
    size_t len = strlen(s);
    if (!(it->s = cx_malloc(len + 1))) {
        rec->failed = 1;
        return 1;
    }
    memcpy(it->s, s, len + 1);
    rec->n++;
    cairo_new_path(cr);
    return 1;
}

static void text_font(cairo_t *cr, double size, int bold)
{
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

double cx_text_width(cairo_t *cr, const char *s, double size, int bold)
{
    cairo_text_extents_t te;
    text_font(cr, size, bold);
    cairo_text_extents(cr, s, &te);
    return te.x_advance;
}

double cx_text(cairo_t *cr, const char *s, double x, double y, double size, int bold,
               double ax, double ay)
{
    cairo_text_extents_t te;
    cairo_font_extents_t fe;
    text_font(cr, size, bold);
    cairo_text_extents(cr, s, &te);
    cairo_font_extents(cr, &fe);
    /* vertical anchoring on the font's ascent/descent, not the glyphs', so
     * that labels of one row line up */
    double h = fe.ascent + fe.descent;
    cairo_move_to(cr, x - ax * te.x_advance, y - ay * h + fe.ascent);
    if (!text_record(cr, s, size, bold))
        cairo_show_text(cr, s);
    return te.x_advance;
}

void cx_text_vertical(cairo_t *cr, const char *s, double x, double y, double size, int bold)
{
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_rotate(cr, -1.5707963267948966);
    cx_text(cr, s, 0, 0, size, bold, 0.5, 0.5);
    cairo_restore(cr);
}

double cx_text_fit(cairo_t *cr, const char *s, double x, double y, double size, int bold,
                   double ax, double ay, double maxw)
{
    /* shrink to at most 3/4 of the size, then cut at a character boundary
     * and end with an ellipsis */
    double w = cx_text_width(cr, s, size, bold);
    if (w <= maxw)
        return cx_text(cr, s, x, y, size, bold, ax, ay);
    /* hinted advances are not proportional to the size (a 6 px font's
     * glyphs round up), so the scaled size is measured again */
    double fit = size * maxw / w;
    for (int k = 0; k < 8 && cx_text_width(cr, s, fit, bold) > maxw; k++)
        fit *= 0.97;
    if (fit >= 0.75 * size && cx_text_width(cr, s, fit, bold) <= maxw)
        return cx_text(cr, s, x, y, fit, bold, ax, ay);
    size *= 0.75;
    char buf[1024];
    size_t len = strlen(s) < sizeof buf - 4 ? strlen(s) : sizeof buf - 4;
    memcpy(buf, s, len);
    for (;;) {
        while (len > 0 && ((unsigned char)buf[len] & 0xC0) == 0x80)
            len--;   /* never split a UTF-8 sequence */
        memcpy(buf + len, "\xE2\x80\xA6", 4);   /* U+2026 */
        if (len == 0 || cx_text_width(cr, buf, size, bold) <= maxw)
            break;
        len--;
    }
    return cx_text(cr, buf, x, y, size, bold, ax, ay);
}
