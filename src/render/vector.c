/* SPDX-License-Identifier: GPL-3.0-or-later */
/* SVG and PDF through cairo's vector surfaces (vector.h). The surface
 * writes into memory; SVG text is recorded by text.c and added as <text>
 * elements before the closing tag; then the bytes go to the file. */
#include "render/vector.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cx_config.h"
#include "out/outfile.h"
#include "render/image_impl.h"
#include "render/text.h"

typedef struct vec_buf {
    unsigned char *b;
    size_t n, cap;
    int failed;
} vec_buf;

static int vec_put(vec_buf *v, const void *data, size_t len)
{
    if (v->n + len > v->cap) {
        size_t cap = v->cap ? v->cap : 1 << 16;
        while (cap < v->n + len)
            cap *= 2;
        unsigned char *b = cx_realloc(v->b, cap);
        if (!b) {
            v->failed = 1;
            return 0;
        }
        v->b = b;
        v->cap = cap;
    }
    memcpy(v->b + v->n, data, len);
    v->n += len;
    return 1;
}

static cairo_status_t vec_write(void *ctx, const unsigned char *data, unsigned int len)
{
    return vec_put(ctx, data, len) ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

/* s with XML's five characters escaped */
static void vec_xml(vec_buf *v, const char *s)
{
    for (; *s; s++) {
        const char *e = *s == '<' ? "&lt;" : *s == '>' ? "&gt;" : *s == '&' ? "&amp;" : *s == '"' ? "&quot;"
                      : *s == '\'' ? "&apos;" : NULL;
        if (e)
            vec_put(v, e, strlen(e));
        else
            vec_put(v, s, 1);
    }
}

/* The recorded text as <text> elements, inserted before "</svg>". */
static int vec_svg_text(vec_buf *v, const cx_text_rec *rec)
{
    const char *end = "</svg>";
    size_t at = v->n;
    while (at >= 6 && memcmp(v->b + at - 6, end, 6) != 0)
        at--;
    if (at < 6)
        return 0;
    at -= 6;
    vec_buf t = {0};
    char line[512];
    snprintf(line, sizeof line, "<g id=\"text\" font-family=\"DejaVu Sans, Verdana, sans-serif\" xml:space=\"preserve\">\n");
    vec_put(&t, line, strlen(line));
    for (int i = 0; i < rec->n; i++) {
        const cx_text_item *it = &rec->v[i];
        int n = snprintf(line, sizeof line, "<text x=\"%.2f\" y=\"%.2f\" font-size=\"%.2f\"%s fill=\"#%02x%02x%02x\"",
                         it->x, it->y, it->size, it->bold ? " font-weight=\"bold\"" : "",
                         (int)lround(255 * it->rgb[0]), (int)lround(255 * it->rgb[1]), (int)lround(255 * it->rgb[2]));
        if (fabs(it->angle) > 1e-6)
            n += snprintf(line + n, sizeof line - (size_t)n, " transform=\"rotate(%.2f %.2f %.2f)\"", it->angle,
                          it->x, it->y);
        snprintf(line + n, sizeof line - (size_t)n, ">");
        vec_put(&t, line, strlen(line));
        vec_xml(&t, it->s);
        vec_put(&t, "</text>\n", 8);
    }
    vec_put(&t, "</g>\n", 5);
    int ok = !t.failed && vec_put(v, t.b, t.n);   /* room for the insertion */
    if (ok) {
        memmove(v->b + at + t.n, v->b + at, v->n - t.n - at);
        memcpy(v->b + at, t.b, t.n);
    }
    cx_free(t.b);
    return ok;
}

typedef int (*vec_draw_fn)(void *ctx, cairo_t *cr, cx_diag *d);

/* Draw with fn on a w x h pixel figure as fmt, and write it to path. */
static int vec_write_file(const char *path, int w, int h, cx_vector_format fmt, const char *title,
                          vec_draw_fn fn, void *ctx, cx_diag *d)
{
    vec_buf v = {0};
    cx_text_rec rec = {0};
    double pw = w * CX_VECTOR_PT_PER_PX, ph = h * CX_VECTOR_PT_PER_PX;
    cairo_surface_t *surf;
    if (fmt == CX_VECTOR_SVG) {
        surf = cairo_svg_surface_create_for_stream(vec_write, &v, pw, ph);
        cairo_svg_surface_restrict_to_version(surf, CAIRO_SVG_VERSION_1_1);
        cx_text_record_attach(surf, &rec);
    } else {
        surf = cairo_pdf_surface_create_for_stream(vec_write, &v, pw, ph);
        cairo_pdf_surface_set_metadata(surf, CAIRO_PDF_METADATA_TITLE, title);
        cairo_pdf_surface_set_metadata(surf, CAIRO_PDF_METADATA_CREATOR, "signorini " CX_VERSION);
        /* no date (cairo writes the clock's by default): the same figure
         * gives the same bytes, as the PNG does */
        cairo_pdf_surface_set_metadata(surf, CAIRO_PDF_METADATA_CREATE_DATE, "");
    }
    cairo_t *cr = cairo_create(surf);
    cairo_scale(cr, CX_VECTOR_PT_PER_PX, CX_VECTOR_PT_PER_PX);
    int rc = fn(ctx, cr, d);
    cairo_destroy(cr);
    cairo_surface_finish(surf);
    cairo_status_t st = cairo_surface_status(surf);
    cairo_surface_destroy(surf);
    if (rc == CX_OK && (st != CAIRO_STATUS_SUCCESS || v.failed))
        rc = v.failed ? cx_diag_set(d, CX_ENOMEM, "%s: out of memory", path)
                      : cx_diag_set(d, CX_EEXTERNAL, "cairo: %s", cairo_status_to_string(st));
    if (rc == CX_OK && fmt == CX_VECTOR_SVG && (rec.failed || !vec_svg_text(&v, &rec)))
        rc = cx_diag_set(d, CX_ENOMEM, "%s: out of memory", path);
    if (rc == CX_OK) {
        cx_outfile out;
        rc = cx_outfile_open(&out, path, d);
        if (rc == CX_OK) {
            int ok = fwrite(v.b, 1, v.n, out.f) == v.n;
            rc = cx_outfile_close(&out, ok, d);
            if (rc == CX_OK && !ok)
                rc = cx_diag_set(d, CX_EIO, "%s: cannot write", path);
        }
    }
    cx_text_rec_clear(&rec);
    cx_free(v.b);
    return rc;
}

typedef struct vec_plot {
    const cx_plot *p;
    int w, h;
} vec_plot;

static int vec_draw_plot(void *ctx, cairo_t *cr, cx_diag *d)
{
    vec_plot *vp = ctx;
    return cx_plot_draw_cairo(vp->p, cr, vp->w, vp->h, d);
}

int cx_plot_write_vector(const cx_plot *p, const char *path, int w, int h, cx_vector_format fmt,
                         cx_diag *d)
{
    if (w < 64 || h < 64 || w > 16384 || h > 16384)
        return cx_diag_set(d, CX_EINVAL, "plot size %dx%d: expected 64..16384 pixels each way", w, h);
    vec_plot vp = {p, w, h};
    return vec_write_file(path, w, h, fmt, p->title, vec_draw_plot, &vp, d);
}

typedef struct vec_image {
    cx_result *r;
    const cx_render_opts *o;
    const cx_render_buf *b;
} vec_image;

static int vec_draw_image(void *ctx, cairo_t *cr, cx_diag *d)
{
    vec_image *vi = ctx;
    return cx_render_image_vector(vi->r, vi->o, vi->b, cr, d);
}

int cx_render_vector(cx_result *r, const cx_render_opts *o, const char *path, cx_vector_format fmt,
                     cx_diag *d)
{
    cx_render_buf b;
    CX_TRY(cx_render_image_draw(r, o, NULL, 0, &b, NULL, d));
    vec_image vi = {r, o, &b};
    int rc = vec_write_file(path, b.w, b.h, fmt, r->run.title, vec_draw_image, &vi, d);
    cx_render_buf_clear(&b);
    return rc;
}
