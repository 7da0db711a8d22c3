/* SPDX-License-Identifier: GPL-3.0-or-later */
/* render/pngfile.h: PNG files with text chunks, written with libpng to a
 * temporary file in the target's directory and renamed into place, so a
 * failed write leaves nothing behind. No timestamps are written: the same
 * pixels and text give the same bytes. */
#ifndef CX_RENDER_PNGFILE_H
#define CX_RENDER_PNGFILE_H

#include "base/base.h"

typedef struct cx_png_text {
    const char *key;     /* 1-79 Latin-1 characters */
    const char *value;
} cx_png_text;

/* Write a w x h image given as cairo RGB24/ARGB32 words (native-endian
 * uint32 0xAARRGGBB, alpha ignored), top-down rows `stride` bytes apart, as
 * an 8-bit RGB PNG with the text chunks. CX_EIO with "PATH: reason" when
 * the file cannot be written, CX_EEXTERNAL for a libpng failure. */
int cx_png_write_xrgb(const char *path, const unsigned char *buf, int w, int h, int stride,
                      const cx_png_text *text, int ntext, cx_diag *d);

#endif
