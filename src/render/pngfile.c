/* SPDX-License-Identifier: GPL-3.0-or-later */
/* PNG writing with libpng (see pngfile.h). */
#include "render/pngfile.h"
#include "out/outfile.h"

#include <png.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

typedef struct pngfile_job {
    FILE *fp;
    const unsigned char *buf;
    int w, h, stride;
    const cx_png_text *text;
    int ntext;
    unsigned char *row;       /* 3 w bytes */
    char err[200];
} pngfile_job;

static void pngfile_on_error(png_structp png, png_const_charp msg)
{
    pngfile_job *job = png_get_error_ptr(png);
    snprintf(job->err, sizeof job->err, "%s", msg);
    longjmp(png_jmpbuf(png), 1);
}

static void pngfile_on_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;
}

/* Encode job into job->fp; 0 on success. Kept apart so that setjmp only
 * sees variables that do not change after it. */
static int pngfile_encode(pngfile_job *job)
{
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, job, pngfile_on_error,
                                              pngfile_on_warning);
    if (!png) {
        snprintf(job->err, sizeof job->err, "libpng: cannot create the write struct");
        return -1;
    }
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        snprintf(job->err, sizeof job->err, "libpng: cannot create the info struct");
        return -1;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return -1;
    }
    png_init_io(png, job->fp);
    /* Rendered images are smooth: SUB/UP filters at level 6 are a good
     * size/speed balance (doc/toolchain.md §4). */
    png_set_compression_level(png, 6);
    png_set_filter(png, 0, PNG_FILTER_SUB | PNG_FILTER_UP);
    png_set_IHDR(png, info, (png_uint_32)job->w, (png_uint_32)job->h, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_text txt[32];
    int nt = 0;
    for (int i = 0; i < job->ntext && nt < 32; i++) {
        if (!job->text[i].key || !job->text[i].key[0] || !job->text[i].value)
            continue;
        memset(&txt[nt], 0, sizeof txt[nt]);
        txt[nt].compression = PNG_TEXT_COMPRESSION_NONE;
        txt[nt].key = (png_charp)job->text[i].key;
        txt[nt].text = (png_charp)job->text[i].value;
        txt[nt].text_length = strlen(job->text[i].value);
        nt++;
    }
    if (nt > 0)
        png_set_text(png, info, txt, nt);
    png_write_info(png, info);
    for (int y = 0; y < job->h; y++) {
        const uint32_t *src = (const uint32_t *)(const void *)(job->buf + (size_t)y * job->stride);
        for (int x = 0; x < job->w; x++) {
            uint32_t v = src[x];
            job->row[3 * x] = (unsigned char)(v >> 16);
            job->row[3 * x + 1] = (unsigned char)(v >> 8);
            job->row[3 * x + 2] = (unsigned char)v;
        }
        png_write_row(png, job->row);
    }
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return 0;
}

int cx_png_write_xrgb(const char *path, const unsigned char *buf, int w, int h, int stride,
                      const cx_png_text *text, int ntext, cx_diag *d)
{
    if (w < 1 || h < 1 || stride < 4 * w)
        return cx_diag_set(d, CX_EINVAL, "%s: bad image size %dx%d", path ? path : "PNG", w, h);
    pngfile_job job = {0};
    job.buf = buf;
    job.w = w;
    job.h = h;
    job.stride = stride;
    job.text = text;
    job.ntext = ntext;
    job.row = cx_malloc((size_t)w * 3);
    if (!job.row)
        return cx_diag_set(d, CX_ENOMEM, "%s: out of memory", path ? path : "PNG");
    cx_outfile out;
    int rc = cx_outfile_open(&out, path, d);
    if (rc == CX_OK) {
        job.fp = out.f;
        int enc = pngfile_encode(&job);
        rc = cx_outfile_close(&out, enc == 0, d);
        if (enc != 0)
            rc = cx_diag_set(d, CX_EEXTERNAL, "%s: %s", path, job.err);
    }
    cx_free(job.row);
    return rc;
}
