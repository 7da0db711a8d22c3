/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The offscreen OpenGL context, one of two chosen at build time (meson
 * option gl): OSMesa (doc/toolchain.md §3c, §5: link OSMesa only, request
 * the depth buffer, rows are bottom-up), the default on Debian 12; or EGL
 * on Mesa's surfaceless platform, where OSMesa is gone (Mesa 25.1 removed
 * it): no window system, a pbuffer as the default framebuffer, GL from
 * GLVND's libOpenGL. Both draw with the same Mesa rasteriser (llvmpipe when
 * there is no GPU), so the images agree (tests/render/test_egl.py). */
#define GL_GLEXT_PROTOTYPES 1
#include "render/glctx.h"
#include "cx_config.h"

#if CX_GL_EGL
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <string.h>
#else
#include <GL/osmesa.h>
#endif
#include <pthread.h>

/* One context at a time in the process: Mesa's OSMesa state (the current
 * context, the shader compiler's caches) is not made for two threads
 * drawing at once, so a second thread's cx_gl_create waits until the first
 * thread's cx_gl_destroy. A cx_gl is used and destroyed by the thread that
 * made it, and a thread holds one at a time. */
static pthread_mutex_t glctx_lock = PTHREAD_MUTEX_INITIALIZER;

/* A context of either backend, and the RGBA buffer of its pixels. */
struct cx_gl {
#if CX_GL_EGL
    EGLDisplay dpy;
    EGLContext ctx;
    EGLSurface surf;
#else
    OSMesaContext ctx;
#endif
    unsigned char *buf;   /* OSMesa draws into it; EGL's pbuffer is read back into it */
    int w, h;
    const char *version;
};

#if CX_GL_EGL

/* Mesa's surfaceless platform through EGL_EXT_platform_base (EGL 1.4
 * names it eglGetPlatformDisplayEXT; the core eglGetPlatformDisplay of
 * EGL 1.5 takes the same arguments). */
static EGLDisplay glctx_display(cx_diag *d)
{
    const char *ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!ext || !strstr(ext, "EGL_MESA_platform_surfaceless")) {
        cx_diag_set(d, CX_EEXTERNAL, "EGL: no surfaceless platform (EGL_MESA_platform_surfaceless)");
        return EGL_NO_DISPLAY;
    }
    PFNEGLGETPLATFORMDISPLAYEXTPROC get =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay dpy = get ? get(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL) : EGL_NO_DISPLAY;
    EGLint major, minor;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor)) {
        cx_diag_set(d, CX_EEXTERNAL, "EGL: cannot initialise the surfaceless display (error 0x%x)",
                    (unsigned)eglGetError());
        return EGL_NO_DISPLAY;
    }
    return dpy;
}

static EGLContext glctx_try(EGLDisplay dpy, EGLConfig cfg, int major, int minor)
{
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, major, EGL_CONTEXT_MINOR_VERSION, minor,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
    return eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, attribs);
}

/* The context of c (w, h and buf set), made current; on an error what
 * was made stays in c for glctx_close. */
static int glctx_open(cx_gl *c, cx_diag *d)
{
    c->dpy = EGL_NO_DISPLAY;
    c->ctx = EGL_NO_CONTEXT;
    c->surf = EGL_NO_SURFACE;
    if ((c->dpy = glctx_display(d)) == EGL_NO_DISPLAY)
        return CX_EEXTERNAL;
    const EGLint cattr[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                            EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
                            EGL_DEPTH_SIZE, 24, EGL_STENCIL_SIZE, 8, EGL_NONE};
    EGLConfig cfg;
    EGLint ncfg = 0;
    if (!eglBindAPI(EGL_OPENGL_API) || !eglChooseConfig(c->dpy, cattr, &cfg, 1, &ncfg) || ncfg < 1)
        return cx_diag_set(d, CX_EEXTERNAL, "EGL: no RGBA8 pbuffer configuration with a 24-bit depth buffer");
    const EGLint sattr[] = {EGL_WIDTH, c->w, EGL_HEIGHT, c->h, EGL_NONE};
    if ((c->surf = eglCreatePbufferSurface(c->dpy, cfg, sattr)) == EGL_NO_SURFACE)
        return cx_diag_set(d, CX_EEXTERNAL, "EGL: cannot create a %dx%d pbuffer (error 0x%x)", c->w, c->h,
                           (unsigned)eglGetError());
    c->version = "4.5";
    c->ctx = glctx_try(c->dpy, cfg, 4, 5);
    if (c->ctx == EGL_NO_CONTEXT) {
        c->version = "3.3";
        c->ctx = glctx_try(c->dpy, cfg, 3, 3);
    }
    if (c->ctx == EGL_NO_CONTEXT)
        return cx_diag_set(d, CX_EEXTERNAL, "EGL: cannot create an OpenGL 3.3 core context");
    if (!eglMakeCurrent(c->dpy, c->surf, c->surf, c->ctx))
        return cx_diag_set(d, CX_EEXTERNAL, "EGL: cannot make the context current");
    return CX_OK;
}

/* Releases what glctx_open made. */
static void glctx_close(cx_gl *c)
{
    if (c->dpy == EGL_NO_DISPLAY)
        return;
    eglMakeCurrent(c->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (c->ctx != EGL_NO_CONTEXT)
        eglDestroyContext(c->dpy, c->ctx);
    if (c->surf != EGL_NO_SURFACE)
        eglDestroySurface(c->dpy, c->surf);
    eglTerminate(c->dpy);
    eglReleaseThread();
}

/* The pbuffer is GL memory, not ours (OSMesa draws into our buffer): read
 * it back, rows bottom-up as OSMesa leaves them. */
const unsigned char *cx_gl_pixels(const cx_gl *g)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, g->w, g->h, GL_RGBA, GL_UNSIGNED_BYTE, g->buf);
    return g->buf;
}

#else /* OSMesa */

static OSMesaContext glctx_try(int major, int minor)
{
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                           OSMESA_STENCIL_BITS, 8, OSMESA_ACCUM_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, major,
                           OSMESA_CONTEXT_MINOR_VERSION, minor, 0};
    return OSMesaCreateContextAttribs(attribs, NULL);
}

/* The context of c (w, h and buf set), made current; on an error what
 * was made stays in c for glctx_close. */
static int glctx_open(cx_gl *c, cx_diag *d)
{
    c->version = "4.5";
    c->ctx = glctx_try(4, 5);
    if (!c->ctx) {
        c->version = "3.3";
        c->ctx = glctx_try(3, 3);
    }
    if (!c->ctx)
        return cx_diag_set(d, CX_EEXTERNAL, "OSMesa: cannot create an OpenGL 3.3 core context");
    if (!OSMesaMakeCurrent(c->ctx, c->buf, GL_UNSIGNED_BYTE, c->w, c->h))
        return cx_diag_set(d, CX_EEXTERNAL, "OSMesa: cannot make the context current");
    return CX_OK;
}

/* Releases what glctx_open made. */
static void glctx_close(cx_gl *c)
{
    if (!c->ctx)
        return;
    OSMesaMakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(c->ctx);
}

const unsigned char *cx_gl_pixels(const cx_gl *g)
{
    return g->buf;
}

#endif

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
    c->w = w;
    c->h = h;
    pthread_mutex_lock(&glctx_lock);
    int st = glctx_open(c, d);
    if (st) {
        cx_gl_destroy(&c);   /* what was made, the lock, the memory */
        return st;
    }
    *g = c;
    return CX_OK;
}

void cx_gl_destroy(cx_gl **g)
{
    if (!g || !*g)
        return;
    glctx_close(*g);
    pthread_mutex_unlock(&glctx_lock);
    cx_free((*g)->buf);
    cx_free(*g);
    *g = NULL;
}

const char *cx_gl_version(const cx_gl *g)
{
    return g->version;
}
