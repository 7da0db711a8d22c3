/* SPDX-License-Identifier: GPL-3.0-or-later */
/* render/glctx.h (internal): the offscreen OpenGL context. The only file
 * that knows OSMesa or EGL is glctx.c: the meson option gl chooses one at
 * build time (EGL on Mesa's surfaceless platform where Mesa no longer ships
 * OSMesa). */
#ifndef CX_RENDER_GLCTX_H
#define CX_RENDER_GLCTX_H

#include "base/base.h"

typedef struct cx_gl cx_gl;

/* A core-profile context (4.5, else 3.3) drawing into a w x h RGBA buffer
 * with a 24-bit depth buffer, made current. CX_EEXTERNAL if none can be
 * made. One exists at a time in the process: a second thread's create
 * waits for the first's destroy; the thread that creates it uses and
 * destroys it, and never creates a second one meanwhile. */
int cx_gl_create(cx_gl **g, int w, int h, cx_diag *d);
void cx_gl_destroy(cx_gl **g);
/* The default framebuffer's pixels: RGBA bytes, rows bottom-up; valid after
 * glFinish(). */
const unsigned char *cx_gl_pixels(const cx_gl *g);
/* "4.5" or "3.3": the version the context was made with. */
const char *cx_gl_version(const cx_gl *g);

#endif
