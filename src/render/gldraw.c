/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The GL pass: shaders read from shaders/ at run time, one vertex buffer
 * per array (one draw call each, whatever the number of bodies), the
 * scalar mapped through a colormap texture, 4x MSAA through a multisample
 * FBO resolved by a blit (doc/toolchain.md §3c). */
#define GL_GLEXT_PROTOTYPES 1
#include "render/render_impl.h"
#include "render/glctx.h"

#include <GL/gl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/data.h"
#include "shaders_builtin.h"

/* Read shaders/NAME from the data directories (base/data.h:
 * $SIGNORINI_SHADERS, $SIGNORINI_DATA/shaders, the source tree for the build
 * tree's code, share/signorini/shaders beside the installed library), then
 * the copy compiled into the library. *src is cx_malloc'ed. */
static int gl_read_shader(const char *name, char **src, cx_diag *d)
{
    char dirs[CX_DATA_MAXDIRS][CX_DATA_PATHLEN];
    int ndirs = cx_data_dirs("shaders", "SIGNORINI_SHADERS", dirs);
    for (int i = 0; i < ndirs; i++) {
        char path[CX_DATA_PATHLEN + 64];
        snprintf(path, sizeof path, "%.*s/%s", CX_DATA_PATHLEN - 1, dirs[i], name);
        FILE *f = fopen(path, "rb");
        if (!f)
            continue;
        fseek(f, 0, SEEK_END);
        long n = ftell(f);
        fseek(f, 0, SEEK_SET);
        char *s = n >= 0 ? cx_malloc((size_t)n + 1) : NULL;
        if (!s || fread(s, 1, (size_t)n, f) != (size_t)n) {
            cx_free(s);
            fclose(f);
            return cx_diag_set(d, CX_EIO, "%s: cannot read", path);
        }
        s[n] = '\0';
        fclose(f);
        *src = s;
        return CX_OK;
    }
    for (int i = 0; gl_builtin_shaders[i].name; i++) {
        if (strcmp(gl_builtin_shaders[i].name, name) != 0)
            continue;
        size_t n = strlen(gl_builtin_shaders[i].src);
        char *s = cx_malloc(n + 1);
        if (!s)
            return cx_diag_set(d, CX_ENOMEM, "out of memory reading shader '%s'", name);
        memcpy(s, gl_builtin_shaders[i].src, n + 1);
        *src = s;
        return CX_OK;
    }
    return cx_diag_set(d, CX_EEXTERNAL, "shader '%s' not found (nor compiled in)", name);
}

static int gl_compile(GLenum kind, const char *name, GLuint *out, cx_diag *d)
{
    char *src = NULL;
    CX_TRY(gl_read_shader(name, &src, d));
    GLuint sh = glCreateShader(kind);
    const char *s = src;
    glShaderSource(sh, 1, &s, NULL);
    glCompileShader(sh);
    cx_free(src);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[400] = "";
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        for (char *c = log; *c; c++)
            if (*c == '\n')
                *c = ' ';
        glDeleteShader(sh);
        return cx_diag_set(d, CX_EEXTERNAL, "shader %s: %s", name, log);
    }
    *out = sh;
    return CX_OK;
}

static int gl_program(GLuint *prog, cx_diag *d)
{
    GLuint vs = 0, fs = 0;
    CX_TRY(gl_compile(GL_VERTEX_SHADER, "field.vert", &vs, d));
    int rc = gl_compile(GL_FRAGMENT_SHADER, "field.frag", &fs, d);
    if (rc != CX_OK) {
        glDeleteShader(vs);
        return rc;
    }
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        glDeleteProgram(p);
        return cx_diag_set(d, CX_EEXTERNAL, "shaders field.vert/field.frag do not link");
    }
    *prog = p;
    return CX_OK;
}

typedef struct gl_mesh {
    GLuint vao, vbo;
    GLsizei n;
} gl_mesh;

static void gl_upload(gl_mesh *g, const cx_render_array *a)
{
    g->n = (GLsizei)a->n;
    glGenVertexArrays(1, &g->vao);
    glGenBuffers(1, &g->vbo);
    glBindVertexArray(g->vao);
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * CX_RENDER_VFLOATS * (size_t)a->n),
                 a->n ? a->v : NULL, GL_STATIC_DRAW);
    GLsizei stride = sizeof(float) * CX_RENDER_VFLOATS;
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, (void *)0);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, (void *)(3 * sizeof(float)));
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, stride, (void *)(6 * sizeof(float)));
    for (GLuint i = 0; i < 3; i++)
        glEnableVertexAttribArray(i);
}

static void gl_free(gl_mesh *g)
{
    glDeleteBuffers(1, &g->vbo);
    glDeleteVertexArrays(1, &g->vao);
}

typedef struct gl_uniforms {
    GLint mode, color, lit, range;
} gl_uniforms;

static void gl_draw(const gl_mesh *g, GLenum prim, const gl_uniforms *u, int colormap,
                    const float *color, int lit, int *calls)
{
    if (g->n == 0)
        return;
    (*calls)++;
    glUniform1i(u->mode, colormap ? 0 : 1);
    if (color)
        glUniform4fv(u->color, 1, color);
    glUniform1i(u->lit, lit);
    glBindVertexArray(g->vao);
    glDrawArrays(prim, 0, g->n);
}

static void gl_draw_scene(const cx_render_scene *sc, GLuint prog, int *calls)
{
    float mvp[16], rot[9];
    cx_render_camera_gl(sc, mvp, rot);
    glUseProgram(prog);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_mvp"), 1, GL_FALSE, mvp);
    glUniformMatrix3fv(glGetUniformLocation(prog, "u_normal_mat"), 1, GL_TRUE, rot);
    glUniform2f(glGetUniformLocation(prog, "u_range"), (float)sc->lo, (float)sc->hi);
    glUniform1i(glGetUniformLocation(prog, "u_cmap"), 0);
    gl_uniforms u = {glGetUniformLocation(prog, "u_mode"), glGetUniformLocation(prog, "u_color"),
                     glGetUniformLocation(prog, "u_lit"), 0};

    /* the colormap as a 256 x 1 texture, sampled at texel centres */
    unsigned char tex[256 * 4];
    for (int i = 0; i < 256; i++) {
        cx_colormap_named(sc->o->cmap, sc->diverging, i / 255.0, tex + 4 * i);
        tex[4 * i + 3] = 255;
    }
    GLuint t;
    glGenTextures(1, &t);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 256, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

    gl_mesh body, over, lines, obst, feat;
    gl_upload(&body, &sc->tris);
    gl_upload(&over, &sc->overlay);
    gl_upload(&lines, &sc->lines);
    /* the obstacles seen from their side (halfball from below) would hide
     * the contact zone: overlay.c draws their outline; the others are
     * obst's first vertices */
    const cx_render_array drawn = {sc->obst.v, sc->obst_drawn, sc->obst_drawn};
    gl_upload(&obst, &drawn);
    gl_upload(&feat, &sc->feature);

    /* 3D lighting: the body's colours within 12 % of the colour bar's
     * (lit 1: the faces towards the viewer exactly, the others a little
     * darker), the shape told by its dark edges; the obstacle, which
     * carries no value, fully shaded (lit 2) */
    int lit = sc->dim == 3;
    static const float grey2d[4] = {0.80f, 0.80f, 0.80f, 1}, grey3d[4] = {0.72f, 0.73f, 0.76f, 1};
    static const float obst_col[4] = {0.62f, 0.58f, 0.52f, 1};
    static const float edge2d[4] = {0.10f, 0.10f, 0.10f, 0.45f}, edge3d[4] = {0.05f, 0.05f, 0.05f, 0.6f};
    static const float feat_col[4] = {0.08f, 0.08f, 0.08f, 0.85f};
    if (sc->o->crop_contact) {   /* the zoomed drawing stays in its area */
        double a[4];
        cx_render_draw_area(sc, a);
        glEnable(GL_SCISSOR_TEST);
        glScissor((GLint)floor(a[0]), (GLint)floor(sc->h - a[1] - a[3]), (GLsizei)ceil(a[2]), (GLsizei)ceil(a[3]));
    }
    if (lit) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LEQUAL);
    }
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    gl_draw(&obst, GL_TRIANGLES, &u, 0, obst_col, 2, calls);
    gl_draw(&body, GL_TRIANGLES, &u, sc->colored, lit ? grey3d : grey2d, lit, calls);
    glPolygonOffset(-1.0f, -1.0f);
    gl_draw(&over, GL_TRIANGLES, &u, 1, NULL, lit, calls);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    gl_draw(&lines, GL_LINES, &u, 0, lit ? edge3d : edge2d, 0, calls);
    gl_draw(&feat, GL_LINES, &u, 0, feat_col, 0, calls);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_SCISSOR_TEST);
    gl_free(&body);
    gl_free(&over);
    gl_free(&lines);
    gl_free(&obst);
    gl_free(&feat);
    glDeleteTextures(1, &t);
}

int cx_render_gl_draw(const cx_render_scene *sc, unsigned char *argb, int stride, double *t_context,
               int *draw_calls, cx_diag *d)
{
    double t0 = cx_clock_now();
    cx_gl *ctx = NULL;
    CX_TRY(cx_gl_create(&ctx, sc->w, sc->h, d));
    GLuint prog = 0;
    int rc = gl_program(&prog, d);
    *t_context = cx_clock_now() - t0;
    if (rc != CX_OK) {
        cx_gl_destroy(&ctx);
        return rc;
    }
    GLuint fbo = 0, rb[2] = {0, 0};
    if (sc->o->msaa > 0) {
        glGenFramebuffers(1, &fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glGenRenderbuffers(2, rb);
        glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, sc->o->msaa, GL_RGBA8, sc->w, sc->h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
        glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, sc->o->msaa, GL_DEPTH24_STENCIL8, sc->w, sc->h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            rc = cx_diag_set(d, CX_EEXTERNAL, "OpenGL: the %dx multisample framebuffer is incomplete",
                             sc->o->msaa);
    }
    if (rc == CX_OK) {
        glViewport(0, 0, sc->w, sc->h);
        glClearColor(0, 0, 0, 0);   /* transparent: composited by cairo */
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        *draw_calls = 0;
        gl_draw_scene(sc, prog, draw_calls);
        if (fbo) {
            glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
            glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
            glBlitFramebuffer(0, 0, sc->w, sc->h, 0, 0, sc->w, sc->h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
        }
        glFinish();
        GLenum err = glGetError();
        if (err != GL_NO_ERROR)
            rc = cx_diag_set(d, CX_EEXTERNAL, "OpenGL error 0x%x while drawing", (unsigned)err);
    }
    if (rc == CX_OK) {
        /* OSMesa rows are bottom-up RGBA; over a transparent clear the
         * resolved colours are premultiplied, which is cairo's ARGB32
         * (top-down 0xAARRGGBB words) */
        const unsigned char *px = cx_gl_pixels(ctx);
        for (int y = 0; y < sc->h; y++) {
            const unsigned char *src = px + (size_t)(sc->h - 1 - y) * sc->w * 4;
            uint32_t *dst = (uint32_t *)(void *)(argb + (size_t)y * stride);
            for (int x = 0; x < sc->w; x++)
                dst[x] = (uint32_t)src[4 * x + 3] << 24 | (uint32_t)src[4 * x] << 16 | (uint32_t)src[4 * x + 1] << 8 |
                         src[4 * x + 2];
        }
    }
    if (fbo) {
        glDeleteFramebuffers(1, &fbo);
        glDeleteRenderbuffers(2, rb);
    }
    glDeleteProgram(prog);
    cx_gl_destroy(&ctx);
    return rc;
}
