/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Colormaps: a perceptual one for magnitudes (a polynomial fit of
 * matplotlib's viridis) and a diverging one for signed fields (Moreland's
 * cool-warm, control points every 1/8), and the status colours (the one
 * table of out/palette.h). */
#include "render/render.h"

#include "out/palette.h"

#include <math.h>
#include <string.h>

static unsigned char cmap_byte(double v)
{
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    return (unsigned char)lround(255.0 * v);
}

static void cmap_viridis(double t, unsigned char rgb[3])
{
    /* degree-6 least-squares fit of viridis, per channel */
    static const double c[7][3] = {
        {0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
        {0.1050930431085774, 1.404613529898575, 1.384590162594685},
        {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
        {-4.634230498983486, -5.799100973351585, -19.33244095627987},
        {6.228269936347081, 14.17993336680509, 56.69055260068105},
        {4.776384997670288, -13.74514537774601, -65.35303263337234},
        {-5.435455855934631, 4.645852612178535, 26.3124352495832}};
    for (int k = 0; k < 3; k++) {
        double v = c[6][k];
        for (int i = 5; i >= 0; i--)
            v = c[i][k] + t * v;
        rgb[k] = cmap_byte(v);
    }
}

/* Piecewise-linear through n + 1 control points, every 1/n (rgb 0..255). */
static void cmap_points(const double (*pts)[3], int n, double t, unsigned char rgb[3])
{
    double s = t * n;
    int i = (int)floor(s);
    if (i > n - 1)
        i = n - 1;
    double f = s - i;
    for (int k = 0; k < 3; k++)
        rgb[k] = cmap_byte(((1 - f) * pts[i][k] + f * pts[i + 1][k]) / 255.0);
}

static void cmap_coolwarm(double t, unsigned char rgb[3])
{
    static const double pts[9][3] = {
        {59, 76, 192}, {98, 130, 234}, {141, 176, 254}, {184, 208, 249}, {221, 221, 221},
        {245, 196, 173}, {244, 154, 123}, {222, 96, 77}, {180, 4, 38}};
    cmap_points(pts, 8, t, rgb);
}

void cx_colormap(int diverging, double t, unsigned char rgb[3])
{
    if (!(t >= 0))
        t = 0;
    if (t > 1)
        t = 1;
    if (diverging)
        cmap_coolwarm(t, rgb);
    else
        cmap_viridis(t, rgb);
}

void cx_status_color(int status, unsigned char rgb[3])
{
    int s = status >= 0 && status < CX_PALETTE_NSTATUS ? status : 0;
    rgb[0] = cx_palette_status[s][0];
    rgb[1] = cx_palette_status[s][1];
    rgb[2] = cx_palette_status[s][2];
}

static const char *const cmap_names[CX_CMAP_COUNT] = {"viridis", "cividis", "magma", "coolwarm", "gray"};

const char *cx_cmap_name(int cmap)
{
    return cmap >= 0 && cmap < CX_CMAP_COUNT ? cmap_names[cmap] : "auto";
}

int cx_cmap_from_name(const char *name)
{
    if (strcmp(name, "auto") == 0)
        return CX_CMAP_AUTO;
    for (int k = 0; k < CX_CMAP_COUNT; k++)
        if (strcmp(name, cmap_names[k]) == 0)
            return k;
    return -2;
}

void cx_colormap_named(int cmap, int diverging, double t, unsigned char rgb[3])
{
    if (!(t >= 0))
        t = 0;
    if (t > 1)
        t = 1;
    /* cividis (Nuñez et al. 2018) and magma (van der Walt & Smith): the
     * published maps sampled every 1/16, rgb 0..255 */
    static const double cividis[17][3] = {
        {0, 34, 78}, {0, 46, 106}, {26, 56, 111}, {50, 67, 109}, {67, 78, 108}, {83, 90, 109},
        {97, 101, 111}, {111, 112, 115}, {125, 124, 120}, {140, 136, 120}, {155, 148, 118},
        {171, 160, 114}, {188, 174, 108}, {205, 187, 99}, {222, 201, 88}, {240, 216, 70},
        {254, 232, 56}};
    static const double magma[17][3] = {
        {0, 0, 4}, {10, 8, 34}, {29, 17, 71}, {54, 16, 107}, {81, 18, 124}, {106, 28, 129},
        {131, 38, 129}, {156, 46, 127}, {183, 55, 121}, {208, 65, 111}, {231, 82, 99},
        {245, 107, 92}, {252, 137, 97}, {254, 167, 114}, {254, 196, 136}, {253, 226, 163},
        {252, 253, 191}};
    switch (cmap) {
    case CX_CMAP_VIRIDIS: cmap_viridis(t, rgb); break;
    case CX_CMAP_CIVIDIS: cmap_points(cividis, 16, t, rgb); break;
    case CX_CMAP_MAGMA: cmap_points(magma, 16, t, rgb); break;
    case CX_CMAP_COOLWARM: cmap_coolwarm(t, rgb); break;
    case CX_CMAP_GRAY: rgb[0] = rgb[1] = rgb[2] = cmap_byte(0.08 + 0.88 * t); break;
    default: cx_colormap(diverging, t, rgb); break;
    }
}
