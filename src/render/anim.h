/* SPDX-License-Identifier: GPL-3.0-or-later */
/* render/anim.h: a run drawn iterate by iterate, for a lecture: the
 * contact set and the deformed shape as they evolve. Frames are added as
 * the run makes them (nothing is kept but the frame being encoded), and
 * each is drawn like cx_render_png draws a result, with what must not move
 * between frames fixed from the run's last iterate, given first: the
 * camera (framed for the "still running" banner the frames carry), the
 * displacement scale and the colour range (--range if set). So a colour
 * means the same value in every frame, and a point that does not move
 * stays on the same pixel.
 *
 * Outputs: a directory of PNGs DIR/frame_0000.png ... (each with the
 * image's text chunks and "frame"), and/or an animated GIF (giflib) with
 * one global 256-colour table built from the colormap, the status
 * palette, greys and a colour cube (no dithering: the same frames give
 * the same bytes), looping, each frame shown 0.5 s and the last 3 s, and a
 * comment naming the scene, field, colour range and frame count. Files go
 * through out/outfile.h (a temporary renamed into place when finished;
 * an animation destroyed unfinished leaves no GIF). */
#ifndef CX_RENDER_ANIM_H
#define CX_RENDER_ANIM_H

#include "base/base.h"
#include "out/out.h"
#include "render/render.h"

typedef struct cx_anim cx_anim;

/* An animation of the run whose last iterate is final (borrowed until
 * create returns), drawn with o (copied; its title is not), into the
 * directory dir (created if missing; NULL: none) and the GIF gif (NULL:
 * none). CX_EINVAL (options; neither output), CX_EIO (the directory or
 * the GIF cannot be written), CX_EUNSUPPORTED (a GIF without giflib). */
int cx_anim_create(cx_anim **a, cx_result *final, const cx_render_opts *o, const char *dir, const char *gif,
                   cx_diag *d);
/* Draw and write the next frame: an iterate of the run (frame 0 is the
 * start, before the first step). */
int cx_anim_add(cx_anim *a, cx_result *frame, cx_diag *d);
/* Write the end of the GIF and rename it into place. */
int cx_anim_finish(cx_anim *a, cx_diag *d);
/* Frees; an unfinished GIF is removed. NULL-safe. */
void cx_anim_destroy(cx_anim **a);
/* Frames added so far, and the colour range every frame shares. */
int cx_anim_count(const cx_anim *a);
void cx_anim_range(const cx_anim *a, double *lo, double *hi);
/* Seconds spent drawing and encoding (the run's steps not included). */
double cx_anim_seconds(const cx_anim *a);

#endif
