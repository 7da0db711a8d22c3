/* SPDX-License-Identifier: GPL-3.0-or-later */
/* render/vector.h: figures as SVG or PDF (cairo), for papers. A plot is
 * drawn as vectors: paths for the axes, grid, curves and markers, text as
 * text (in SVG, <text> elements in DejaVu Sans; in PDF, the font embedded
 * with its Unicode map, so the words can be searched and copied). An
 * image of a field embeds the rendered GL layer (the body's colours) as a
 * bitmap at the image's pixel size, under vector text, colour bar,
 * outlines, obstacle and markers.
 *
 * The page is the figure's size in pixels times 0.5 points (1200 x 900
 * pixels: 600 x 450 pt, 8.3 x 6.25 in), every proportion as in the PNG.
 * The file is written through out/outfile.h (a temporary renamed into
 * place; a failure leaves none). Errors: CX_EINVAL (sizes, options),
 * CX_EIO (path), CX_EEXTERNAL (cairo), CX_ENOMEM. */
#ifndef CX_RENDER_VECTOR_H
#define CX_RENDER_VECTOR_H

#include "base/base.h"
#include "render/plot.h"
#include "render/render.h"

typedef enum cx_vector_format { CX_VECTOR_SVG, CX_VECTOR_PDF } cx_vector_format;

/* Points per pixel of the figure. */
#define CX_VECTOR_PT_PER_PX 0.5

int cx_plot_write_vector(const cx_plot *p, const char *path, int w, int h, cx_vector_format fmt,
                         cx_diag *d);
int cx_render_vector(cx_result *r, const cx_render_opts *o, const char *path, cx_vector_format fmt,
                     cx_diag *d);

#endif
