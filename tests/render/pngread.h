/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Test helper: read a PNG back (RGB, top-down) with its tEXt chunks. */
#ifndef CX_TEST_PNGREAD_H
#define CX_TEST_PNGREAD_H

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct test_png {
    int w, h;
    unsigned char *rgb;          /* 3 w h, top-down */
    int ntext;
    char key[32][80];
    char value[32][512];
} test_png;

static inline int test_png_read(test_png *img, const char *path)
{
    memset(img, 0, sizeof *img);
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return -1;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(fp);
        return -1;
    }
    png_init_io(png, fp);
    png_read_info(png, info);
    img->w = (int)png_get_image_width(png, info);
    img->h = (int)png_get_image_height(png, info);
    png_set_strip_alpha(png);
    png_set_strip_16(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != (size_t)img->w * 3) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(fp);
        return -1;
    }
    img->rgb = malloc((size_t)img->w * img->h * 3);
    for (int y = 0; y < img->h; y++)
        png_read_row(png, img->rgb + (size_t)y * img->w * 3, NULL);
    png_read_end(png, info);
    png_textp t;
    int nt = 0;
    png_get_text(png, info, &t, &nt);
    for (int i = 0; i < nt && i < 32; i++) {
        snprintf(img->key[i], sizeof img->key[i], "%s", t[i].key);
        snprintf(img->value[i], sizeof img->value[i], "%s", t[i].text);
    }
    img->ntext = nt < 32 ? nt : 32;
    png_destroy_read_struct(&png, &info, NULL);
    fclose(fp);
    return 0;
}

static inline void test_png_free(test_png *img)
{
    free(img->rgb);
    img->rgb = NULL;
}

static inline const char *test_png_text(const test_png *img, const char *key)
{
    for (int i = 0; i < img->ntext; i++)
        if (strcmp(img->key[i], key) == 0)
            return img->value[i];
    return NULL;
}

static inline const unsigned char *test_png_px(const test_png *img, int x, int y)
{
    return img->rgb + ((size_t)y * img->w + x) * 3;
}

/* Pixels within tol (per channel) of colour c. */
static inline long test_png_count(const test_png *img, int r, int g, int b, int tol)
{
    long n = 0;
    for (long i = 0; i < (long)img->w * img->h; i++) {
        const unsigned char *p = img->rgb + 3 * i;
        n += abs(p[0] - r) <= tol && abs(p[1] - g) <= tol && abs(p[2] - b) <= tol;
    }
    return n;
}

/* Number of distinct colours (capped), to tell an image from a blank one. */
static inline int test_png_colours(const test_png *img)
{
    static unsigned char seen[1 << 15];
    memset(seen, 0, sizeof seen);
    int n = 0;
    for (long i = 0; i < (long)img->w * img->h; i++) {
        const unsigned char *p = img->rgb + 3 * i;
        int k = ((p[0] >> 3) << 10) | ((p[1] >> 3) << 5) | (p[2] >> 3);
        if (!seen[k]) {
            seen[k] = 1;
            n++;
        }
    }
    return n;
}

static inline int test_files_equal(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    int eq = fa && fb;
    while (eq) {
        int ca = fgetc(fa), cb = fgetc(fb);
        if (ca != cb)
            eq = 0;
        if (ca == EOF || cb == EOF)
            break;
    }
    if (fa)
        fclose(fa);
    if (fb)
        fclose(fb);
    return eq;
}

#endif
