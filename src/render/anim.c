/* SPDX-License-Identifier: GPL-3.0-or-later */
/* An animation of a run (anim.h): frames drawn with the last iterate's
 * camera, scale and colour range, written as PNGs and/or one GIF. */
#include "render/anim.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "cx_config.h"
#include "out/palette.h"
#include "render/image_impl.h"

#if CX_HAVE_GIF
#include <gif_lib.h>
#endif

/* The GIF's frame times, in hundredths of a second: long enough to see a
 * change of the contact set, and the end held so that it can be read. */
#define ANIM_DELAY_CS 50
#define ANIM_LAST_CS 300

struct cx_anim {
    cx_render_opts o;
    cx_render_fix fix;
    double lo, hi;               /* the colour range (the field's values) */
    char dir[CX_OUTFILE_PATHLEN];
    int has_dir, nframes;
    double seconds;
    /* the GIF: a global table, a cache from 15-bit colours to its
     * entries, and the frame before the last (written when the next
     * arrives, so that the last one gets the long delay) */
    int has_gif, gif_open;
    cx_outfile out;
    unsigned char table[256][3];
    unsigned short *cache;       /* 32768 entries, 0xffff: not looked up yet */
    unsigned char *pending;      /* w * h indices of the frame not yet written */
    int w, h, have_pending;
#if CX_HAVE_GIF
    GifFileType *g;
#endif
};

int cx_anim_count(const cx_anim *a)
{
    return a->nframes;
}

void cx_anim_range(const cx_anim *a, double *lo, double *hi)
{
    *lo = a->lo;
    *hi = a->hi;
}

double cx_anim_seconds(const cx_anim *a)
{
    return a->seconds;
}

/* The 256 colours: 118 of the colormap (the field), the status colours
 * and the banner's, 8 greys (text and outlines are anti-aliased grey on
 * white), the rest a 5 x 5 x 5 cube for everything else. */
static void anim_table(cx_anim *a)
{
    int n = 0, div = cx_field_is_signed(a->o.field);
    for (int i = 0; i < 118; i++)
        cx_colormap_named(a->o.cmap, div, i / 117.0, a->table[n++]);
    for (int i = 0; i < CX_PALETTE_NSTATUS - 1; i++)
        memcpy(a->table[n++], cx_palette_status[i], 3);
    const double warn[3] = {CX_PALETTE_WARNING_RGB};
    for (int k = 0; k < 3; k++)
        a->table[n][k] = (unsigned char)lround(255 * warn[k]);
    n++;
    static const unsigned char greys[] = {26, 38, 51, 89, 102, 153, 204, 230};
    for (int i = 0; i < 8; i++)
        memset(a->table[n++], greys[i], 3);
    for (int r = 0; r < 5; r++)
        for (int g = 0; g < 5; g++)
            for (int b = 0; b < 5; b++) {
                a->table[n][0] = (unsigned char)(r * 255 / 4);
                a->table[n][1] = (unsigned char)(g * 255 / 4);
                a->table[n][2] = (unsigned char)(b * 255 / 4);
                n++;
            }
    /* 118 + 4 + 1 + 8 + 125 = 256 */
}

/* The nearest entry of the table to an RGB24 word, looked up once per
 * 15-bit colour (the centre of its cell). */
static unsigned char anim_index(cx_anim *a, unsigned int px)
{
    unsigned int r = (px >> 16) & 255, g = (px >> 8) & 255, b = px & 255;
    unsigned int key = (r >> 3) << 10 | (g >> 3) << 5 | (b >> 3);
    if (a->cache[key] == 0xffff) {
        int best = 0;
        long bd = -1;
        int cr = (int)(r | 4), cg = (int)(g | 4), cb = (int)(b | 4);
        for (int i = 0; i < 256; i++) {
            long dr = cr - a->table[i][0], dg = cg - a->table[i][1], db = cb - a->table[i][2];
            long dd = 3 * dr * dr + 4 * dg * dg + 2 * db * db;
            if (bd < 0 || dd < bd) {
                bd = dd;
                best = i;
            }
        }
        a->cache[key] = (unsigned short)best;
    }
    return (unsigned char)a->cache[key];
}

#if CX_HAVE_GIF
static int anim_gif_write(GifFileType *g, const GifByteType *buf, int n)
{
    cx_outfile *o = g->UserData;
    return (int)fwrite(buf, 1, (size_t)n, o->f);
}

static int anim_gif_fail(cx_anim *a, int err, cx_diag *d)
{
    return cx_diag_set(d, CX_EIO, "%s: cannot write the GIF: %s", a->out.path, GifErrorString(err));
}

/* The frame held back, with its delay. */
static int anim_gif_flush(cx_anim *a, int delay, cx_diag *d)
{
    if (!a->have_pending)
        return CX_OK;
    GraphicsControlBlock gcb = {DISPOSAL_UNSPECIFIED, false, delay, NO_TRANSPARENT_COLOR};
    GifByteType ext[4];
    size_t n = EGifGCBToExtension(&gcb, ext);
    if (EGifPutExtension(a->g, GRAPHICS_EXT_FUNC_CODE, (int)n, ext) != GIF_OK ||
        EGifPutImageDesc(a->g, 0, 0, a->w, a->h, false, NULL) != GIF_OK)
        return anim_gif_fail(a, a->g->Error, d);
    for (int y = 0; y < a->h; y++)
        if (EGifPutLine(a->g, a->pending + (size_t)y * a->w, a->w) != GIF_OK)
            return anim_gif_fail(a, a->g->Error, d);
    a->have_pending = 0;
    return CX_OK;
}

static int anim_gif_open(cx_anim *a, const char *path, const cx_result *final, cx_diag *d)
{
    CX_TRY(cx_outfile_open(&a->out, path, d));
    a->gif_open = 1;
    int err = 0;
    a->g = EGifOpen(&a->out, anim_gif_write, &err);
    if (!a->g)
        return anim_gif_fail(a, err, d);
    GifColorType colors[256];
    for (int i = 0; i < 256; i++)
        colors[i] = (GifColorType){a->table[i][0], a->table[i][1], a->table[i][2]};
    ColorMapObject *cm = GifMakeMapObject(256, colors);
    if (!cm)
        return cx_diag_set(d, CX_ENOMEM, "%s: out of memory", path);
    EGifSetGifVersion(a->g, true);
    int rc = EGifPutScreenDesc(a->g, a->w, a->h, 8, 0, cm);
    GifFreeMapObject(cm);
    if (rc != GIF_OK)
        return anim_gif_fail(a, a->g->Error, d);
    /* loop for ever (the NETSCAPE2.0 extension) */
    static const GifByteType loop[3] = {1, 0, 0};
    if (EGifPutExtensionLeader(a->g, APPLICATION_EXT_FUNC_CODE) != GIF_OK ||
        EGifPutExtensionBlock(a->g, 11, "NETSCAPE2.0") != GIF_OK ||
        EGifPutExtensionBlock(a->g, 3, loop) != GIF_OK || EGifPutExtensionTrailer(a->g) != GIF_OK)
        return anim_gif_fail(a, a->g->Error, d);
    char note[240];
    snprintf(note, sizeof note, "signorini %s: %s level %d, %s, colour range %.9g:%.9g%s, scale %.6g",
             CX_VERSION, final->run.scene, final->run.level, cx_field_name(a->o.field), a->lo, a->hi,
             a->o.log ? " (log)" : "", a->fix.scale);
    if (EGifPutComment(a->g, note) != GIF_OK)
        return anim_gif_fail(a, a->g->Error, d);
    return CX_OK;
}
#endif

int cx_anim_create(cx_anim **ap, cx_result *final, const cx_render_opts *o, const char *dir, const char *gif,
                   cx_diag *d)
{
    *ap = NULL;
    if (!dir && !gif)
        return cx_diag_set(d, CX_EINVAL, "animation: neither --frames nor --gif");
#if !CX_HAVE_GIF
    if (gif)
        return cx_diag_set(d, CX_EUNSUPPORTED, "--gif: built without giflib (meson -Dgif=disabled)");
#endif
    cx_anim *a = CX_NEW(cx_anim, 1);
    if (!a)
        return cx_diag_set(d, CX_ENOMEM, "animation: out of memory");
    memset(a, 0, sizeof *a);
    a->o = *o;
    a->o.title = NULL;
    a->o.band_always = 1;   /* the start, each iterate and the outcome captioned alike */
    *ap = a;
    /* the range from the last iterate with the field drawn */
    cx_render_fix fin;
    CX_TRY(cx_render_image_fix(final, o, &fin, d));
    /* the camera as the frames that carry the "still running" banner are
     * framed: a copy of the result's header that reads as a snapshot
     * (|u| needs no stresses, so nothing is cached in the copy) */
    cx_result snap = *final;
    snap.run.reason = CX_ITERATING;
    snap.run.iterations = final->run.iterations > 0 ? final->run.iterations : 1;
    snap.stress_cache = NULL;
    snap.vm_cache = NULL;
    cx_render_opts oc = *o;
    oc.field = CX_FIELD_UMAG;
    oc.log = 0;
    oc.has_range = 0;
    CX_TRY(cx_render_image_fix(&snap, &oc, &a->fix, d));
    a->fix.lo = fin.lo;
    a->fix.hi = fin.hi;
    a->fix.scale = fin.scale;
    /* earlier iterates may stand nearer or farther (3D depth) */
    double dz = a->fix.zmax - a->fix.zmin;
    a->fix.zmin -= 0.5 * dz;
    a->fix.zmax += 0.5 * dz;
    a->lo = o->log ? pow(10.0, fin.lo) : fin.lo;
    a->hi = o->log ? pow(10.0, fin.hi) : fin.hi;
    a->w = o->width;
    a->h = o->height;
    if (dir) {
        snprintf(a->dir, sizeof a->dir, "%s", dir);
        a->has_dir = 1;
        if (mkdir(dir, 0777) != 0 && errno != EEXIST)
            return cx_diag_set(d, CX_EIO, "--frames %s: %s", dir, strerror(errno));
        struct stat st;
        if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
            return cx_diag_set(d, CX_EIO, "--frames %s: not a directory", dir);
    }
    if (gif) {
        a->has_gif = 1;
        anim_table(a);
        a->cache = cx_malloc(sizeof(unsigned short) * 32768);
        a->pending = cx_malloc((size_t)a->w * (size_t)a->h);
        if (!a->cache || !a->pending)
            return cx_diag_set(d, CX_ENOMEM, "animation: out of memory");
        memset(a->cache, 0xff, sizeof(unsigned short) * 32768);
#if CX_HAVE_GIF
        CX_TRY(anim_gif_open(a, gif, final, d));
#endif
    }
    return CX_OK;
}

int cx_anim_add(cx_anim *a, cx_result *frame, cx_diag *d)
{
    double t0 = cx_clock_now();
    cx_render_buf b;
    CX_TRY(cx_render_image_draw(frame, &a->o, &a->fix, 1, &b, NULL, d));
    int rc = CX_OK;
    if (a->has_dir) {
        char path[CX_OUTFILE_PATHLEN + 32], num[32];
        snprintf(path, sizeof path, "%s/frame_%04d.png", a->dir, a->nframes);
        snprintf(num, sizeof num, "%d", a->nframes);
        const char *extra[] = {"frame", num, NULL};
        rc = cx_render_image_write_png(frame, &a->o, &b, path, extra, d);
    }
#if CX_HAVE_GIF
    if (rc == CX_OK && a->has_gif && (rc = anim_gif_flush(a, ANIM_DELAY_CS, d)) == CX_OK) {
        for (int y = 0; y < a->h; y++) {
            const unsigned int *row = (const unsigned int *)(b.rgb + (size_t)y * b.stride);
            unsigned char *out = a->pending + (size_t)y * a->w;
            for (int x = 0; x < a->w; x++)
                out[x] = anim_index(a, row[x]);
        }
        a->have_pending = 1;
    }
#endif
    cx_render_buf_clear(&b);
    if (rc == CX_OK)
        a->nframes++;
    a->seconds += cx_clock_now() - t0;
    return rc;
}

int cx_anim_finish(cx_anim *a, cx_diag *d)
{
#if CX_HAVE_GIF
    if (a->has_gif && a->gif_open) {
        double t0 = cx_clock_now();
        int rc = anim_gif_flush(a, ANIM_LAST_CS, d);
        int err = 0;
        if (EGifCloseFile(a->g, &err) != GIF_OK && rc == CX_OK)
            rc = anim_gif_fail(a, err, d);
        a->g = NULL;
        a->gif_open = 0;
        int rc2 = cx_outfile_close(&a->out, rc == CX_OK, d);
        a->seconds += cx_clock_now() - t0;
        return rc != CX_OK ? rc : rc2;
    }
#endif
    (void)d;
    return CX_OK;
}

void cx_anim_destroy(cx_anim **ap)
{
    cx_anim *a = *ap;
    if (!a)
        return;
#if CX_HAVE_GIF
    if (a->g) {
        int err;
        EGifCloseFile(a->g, &err);
    }
#endif
    if (a->gif_open)
        cx_outfile_close(&a->out, 0, NULL);
    cx_free(a->cache);
    cx_free(a->pending);
    cx_free(a);
    *ap = NULL;
}
