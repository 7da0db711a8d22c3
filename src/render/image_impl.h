/* SPDX-License-Identifier: GPL-3.0-or-later */
/* render/image_impl.h (internal): an image composed into memory rather
 * than written, with its camera, scale and colour range fixed from
 * outside, for the frames of an animation (anim.c) and the vector files
 * (vector.c), which draw the same image as cx_render_png. */
#ifndef CX_RENDER_IMAGE_IMPL_H
#define CX_RENDER_IMAGE_IMPL_H

#include "render/render.h"

typedef struct _cairo cairo_t;

/* What makes two images of one run comparable: where the camera stands
 * and how far it sees, the displacement scale, and the colour range (as
 * the GL draws it: log10 of the values under --log). */
typedef struct cx_render_fix {
    double R[9], k, cx, cy, zmin, zmax;
    double scale;
    double lo, hi;
} cx_render_fix;

/* The camera, scale and range that cx_render_png would draw r with (no
 * GL). */
int cx_render_image_fix(cx_result *r, const cx_render_opts *o, cx_render_fix *fix, cx_diag *d);

/* A composed image: cairo RGB24 words (0x00RRGGBB), h rows `stride` bytes
 * apart; and the GL layer alone (ARGB32 premultiplied, transparent where
 * nothing was drawn), for the vector files. */
typedef struct cx_render_buf {
    int w, h, stride;
    unsigned char *rgb;     /* the whole image (NULL when not asked for) */
    unsigned char *gl;      /* the GL layer */
    cx_render_fix fix;      /* the camera, scale and range it was drawn with */
    double lo, hi;          /* the colour range in the field's values */
    char camera[96];        /* where it was seen from, for the PNG's text */
} cx_render_buf;

/* Draw r with o; with fix (may be NULL) its camera, scale and range
 * instead of r's own. compose: also the whole image in b->rgb. */
int cx_render_image_draw(cx_result *r, const cx_render_opts *o, const cx_render_fix *fix, int compose,
                         cx_render_buf *b, cx_render_timing *t, cx_diag *d);
/* Draw what goes under and over the GL layer of b on cr (any cairo
 * surface, in b's pixel units): the obstacle, then gl, then the text,
 * colour bar and markers. */
int cx_render_image_vector(cx_result *r, const cx_render_opts *o, const cx_render_buf *b, cairo_t *cr,
                           cx_diag *d);
/* Write b->rgb as a PNG with the image's text chunks, and the extra pairs
 * (NULL-terminated keys; may be NULL). */
int cx_render_image_write_png(const cx_result *r, const cx_render_opts *o, const cx_render_buf *b,
                              const char *path, const char *const *extra, cx_diag *d);
void cx_render_buf_clear(cx_render_buf *b);

#endif
