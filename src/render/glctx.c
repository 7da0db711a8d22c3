/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The OSMesa context (doc/toolchain.md §3c, §5): link OSMesa only,
 * request the depth buffer, rows are bottom-up. */
#define GL_GLEXT_PROTOTYPES 1
#include "render/glctx.h"

#include <GL/osmesa.h>
#include <pthread.h>

/* One context at a time in the process: Mesa's OSMesa state (the current
 * context, the shader compiler's caches) is not made for two threads
 * drawing at once, so a second thread's cx_gl_create waits until the first
 * thread's cx_gl_destroy. A cx_gl is used and destroyed by the thread that
 * made it, and a thread holds one at a time. */
static pthread_mutex_t glctx_lock = PTHREAD_MUTEX_INITIALIZER;

struct cx_gl {
    OSMesaContext ctx;
    unsigned char *buf;
    int w, h;
    const char *version;
};

static OSMesaContext glctx_try(int major, int minor)
{
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                           OSMESA_STENCIL_BITS, 8, OSMESA_ACCUM_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, major,
                           OSMESA_CONTEXT_MINOR_VERSION, minor, 0};
    return OSMesaCreateContextAttribs(attribs, NULL);
}

int cx_gl_create(cx_gl **g, int w, int h, cx_diag *d)
{
    *g = NULL;
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
        return cx_diag_set(d, CX_EINVAL, "image size %dx%d: expected 1..16384 pixels each way", w, h);
    cx_gl *c = CX_NEW(cx_gl, 1);
    if (!c)
        return CX_ENOMEM;
    c->buf = cx_malloc((size_t)w * h * 4);
    if (!c->buf) {
        cx_free(c);
        return CX_ENOMEM;
    }
    pthread_mutex_lock(&glctx_lock);
    c->w = w;
    c->h = h;
    c->version = "4.5";
    c->ctx = glctx_try(4, 5);
    if (!c->ctx) {
        c->version = "3.3";
        c->ctx = glctx_try(3, 3);
    }
    if (!c->ctx) {
        pthread_mutex_unlock(&glctx_lock);
        cx_free(c->buf);
        cx_free(c);
        return cx_diag_set(d, CX_EEXTERNAL, "OSMesa: cannot create an OpenGL 3.3 core context");
    }
    if (!OSMesaMakeCurrent(c->ctx, c->buf, GL_UNSIGNED_BYTE, w, h)) {
        OSMesaDestroyContext(c->ctx);
        pthread_mutex_unlock(&glctx_lock);
        cx_free(c->buf);
        cx_free(c);
        return cx_diag_set(d, CX_EEXTERNAL, "OSMesa: cannot make the context current");
    }
    *g = c;
    return CX_OK;
}

void cx_gl_destroy(cx_gl **g)
{
    if (!g || !*g)
        return;
    OSMesaMakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext((*g)->ctx);
    pthread_mutex_unlock(&glctx_lock);
    cx_free((*g)->buf);
    cx_free(*g);
    *g = NULL;
}

const unsigned char *cx_gl_pixels(const cx_gl *g)
{
    return g->buf;
}

const char *cx_gl_version(const cx_gl *g)
{
    return g->version;
}
