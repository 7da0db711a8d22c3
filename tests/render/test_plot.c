/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Plots (render/plot.h): axis ticks, a plot written, read back and checked
 * pixel by pixel, text chunks, determinism, bad paths and empty plots. */
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "pngread.h"
#include "render/axis.h"
#include "out/palette.h"
#include "render/plot.h"

static void test_axis(void)
{
    cx_axis a;
    cx_axis_make(&a, 0.0, 0.97, 0, 5, 1);
    CX_CHECK(a.nticks == 6);
    CX_CHECK_NEAR(a.step, 0.2, 0, 1e-15);
    CX_CHECK_NEAR(a.hi, 1.0, 0, 1e-12);
    char lab[32];
    cx_axis_label(&a, a.ticks[3], lab, sizeof lab);
    CX_CHECK(strcmp(lab, "0.6") == 0);
    /* colour-bar mode: the range stays, ticks inside it */
    cx_axis_make(&a, 3.0, 117.0, 0, 5, 0);
    CX_CHECK(a.lo == 3.0 && a.hi == 117.0);
    CX_CHECK_NEAR(a.ticks[0], 25.0, 0, 1e-12);
    CX_CHECK_NEAR(a.ticks[a.nticks - 1], 100.0, 0, 1e-12);
    /* log: decades, labels with superscripts */
    cx_axis_make(&a, 3e-11, 0.5, 1, 6, 1);
    CX_CHECK_NEAR(a.lo, 1e-11, 1e-12, 0);
    CX_CHECK_NEAR(a.hi, 1.0, 1e-12, 0);
    CX_CHECK(a.nticks >= 4 && a.nticks <= 12);
    cx_axis_label(&a, 1e-10, lab, sizeof lab);
    CX_CHECK(strcmp(lab, "10⁻¹⁰") == 0);
    /* large values are scientific, as a reader writes them (never C's
     * "1.5e+06") */
    cx_axis_make(&a, 0.0, 2.5e6, 0, 5, 1);
    cx_axis_label(&a, 1.5e6, lab, sizeof lab);
    CX_CHECK(strcmp(lab, "1.5×10⁶") == 0);
    cx_axis_label(&a, 1e6, lab, sizeof lab);
    CX_CHECK(strcmp(lab, "1×10⁶") == 0);
    cx_axis_make(&a, 0.0, 4e-4, 0, 4, 1);
    cx_axis_label(&a, 2e-4, lab, sizeof lab);
    CX_CHECK(strcmp(lab, "2×10⁻⁴") == 0);
    /* colour bars: a common power of ten named once in the title */
    char suf[32];
    cx_axis_colorbar(&a, 0.0, 2.9e5, 0, 6);
    CX_CHECK(a.exp10 == 5);
    cx_axis_label(&a, 1e5, lab, sizeof lab);
    CX_CHECK(strcmp(lab, "1.0") == 0 || strcmp(lab, "1") == 0);
    cx_axis_unit_suffix(&a, suf, sizeof suf);
    CX_CHECK(strcmp(suf, ", ×10⁵") == 0);
    /* 10^4: steps of 0.5 x 10^4 keep their decimal (the step in the unit) */
    cx_axis_colorbar(&a, 0.0, 2.0e4, 0, 5);
    CX_CHECK(a.exp10 == 4);
    cx_axis_label(&a, 5e3, lab, sizeof lab);
    CX_CHECK(strcmp(lab, "0.5") == 0);
    /* counts: 1..10 never in steps of 2.5 */
    cx_axis_make_integer(&a, 1.0, 10.0, 6, 1);
    CX_CHECK(a.step == 1.0 || a.step == 2.0 || a.step == 5.0);
    for (int i = 0; i < a.nticks; i++)
        CX_CHECK(a.ticks[i] == floor(a.ticks[i]));
    cx_axis_make_integer(&a, 0.0, 3.0, 8, 1);
    CX_CHECK(a.step == 1.0);
    /* log bars: decades */
    cx_axis_colorbar(&a, 1e-3, 10.0, 1, 6);
    CX_CHECK(a.exp10 == 0 && a.nticks >= 4);
    cx_axis_label(&a, 1e-3, lab, sizeof lab);
    CX_CHECK(strcmp(lab, "10⁻³") == 0);
    /* log bars over few decades: 2 and 5 labelled, the rest minor ticks,
     * ascending; under one decade every multiple */
    cx_axis_colorbar(&a, 2e3, 3e5, 1, 8);
    CX_CHECK(a.nticks == 7 && a.nminor > 0);
    for (int i = 1; i < a.nticks; i++)
        CX_CHECK(a.ticks[i] > a.ticks[i - 1]);
    cx_axis_label(&a, a.ticks[0], lab, sizeof lab);
    CX_CHECK(strcmp(lab, "2×10³") == 0);
    cx_axis_colorbar(&a, 1.2, 7.0, 1, 8);
    CX_CHECK(a.nticks == 6 && a.ticks[0] == 2.0 && a.ticks[5] == 7.0);
    cx_axis_colorbar(&a, 1e-3, 1e3, 1, 8);
    CX_CHECK(a.nticks == 7 && a.nminor == 48);
    /* the fewest decimals that write the ticks: a bar of -1e-3..0 in units
     * of 10^-3 reads -1.0 ... -0.2, 0 (one decimal, not three); steps of
     * 0.25 two */
    cx_axis_colorbar(&a, -1.02e-3, 0.0, 0, 6);
    CX_CHECK(a.exp10 == -3);
    cx_axis_label(&a, a.ticks[0], lab, sizeof lab);
    CX_CHECK(strcmp(lab, "-1.0") == 0);
    cx_axis_colorbar(&a, -1e-3, 1e-3, 0, 8);
    cx_axis_label(&a, a.ticks[1], lab, sizeof lab);
    CX_CHECK(strcmp(lab, "-0.75") == 0);
    cx_axis_make(&a, 0.0, 10.0, 0, 5, 1);
    cx_axis_label(&a, a.ticks[1], lab, sizeof lab);
    CX_CHECK(strcmp(lab, "2") == 0);
    /* moderate values: plain, no unit */
    cx_axis_colorbar(&a, 0.0, 262.0, 0, 6);
    CX_CHECK(a.exp10 == 0);
}

int main(void)
{
    test_axis();

    enum { N = 60 };
    double x[N], y[N], yh[N];
    for (int i = 0; i < N; i++) {
        x[i] = -1.5 + 3.0 * i / (N - 1);
        y[i] = fabs(x[i]) < 1 ? sqrt(1 - x[i] * x[i]) : 0;
        yh[i] = y[i] * 1.02;
    }
    cx_plot pl;
    cx_plot_init(&pl, "contact pressure", "x [mm]", "p [MPa]");
    CX_CHECK_OK(cx_plot_add_series(&pl, "computed", N, x, y, CX_PLOT_MARKERS));
    CX_CHECK_OK(cx_plot_add_series(&pl, "Hertz", N, x, yh, CX_PLOT_LINE | CX_PLOT_DASHED));
    CX_CHECK_OK(cx_plot_add_vline(&pl, 1.0, "b"));
    CX_CHECK_OK(cx_plot_add_text(&pl, "scene", "hertz"));
    CX_CHECK(cx_plot_add_text(&pl, "", "x") == CX_EINVAL);
    const char *a = "test_plot_a.png", *b = "test_plot_b.png";
    cx_diag d;
    cx_diag_clear(&d);
    CX_CHECK_OK(cx_plot_write_png(&pl, a, 600, 400, &d));
    CX_CHECK_OK(cx_plot_write_png(&pl, b, 600, 400, &d));
    CX_CHECK(test_files_equal(a, b));

    test_png img;
    CX_CHECK_OK(test_png_read(&img, a));
    CX_CHECK(img.w == 600 && img.h == 400);
    CX_CHECK(test_png_colours(&img) > 20);
    /* series 0 and 1 in the explorer's first two series colours (one
     * table, out/palette.h): blue, orange */
    const unsigned char *c0 = cx_palette_series[0], *c1 = cx_palette_series[1];
    CX_CHECK(test_png_count(&img, c0[0], c0[1], c0[2], 12) > 200);
    CX_CHECK(test_png_count(&img, c1[0], c1[1], c1[2], 40) > 50);
    /* white background in the corner, and the markers where the data say:
     * the peak (x = 0, y = 1) is at the top-centre of the plot area */
    const unsigned char *c = test_png_px(&img, 2, 2);
    CX_CHECK(c[0] == 255 && c[1] == 255 && c[2] == 255);
    const char *t = test_png_text(&img, "scene");
    CX_CHECK(t && strcmp(t, "hertz") == 0);
    t = test_png_text(&img, "Software");
    CX_CHECK(t && strncmp(t, "signorini ", 10) == 0);
    t = test_png_text(&img, "Title");
    CX_CHECK(t && strcmp(t, "contact pressure") == 0);
    test_png_free(&img);

    /* log-log with a zero and a NaN (skipped), one reference line */
    double tx[5] = {1e-3, 2e-3, 5e-3, 1e-2, 2e-2}, ty[5] = {1e-2, 1e-5, 0.0, NAN, 1e-12};
    cx_plot lg;
    cx_plot_init(&lg, "work-precision", "time [s]", "error");
    lg.logx = lg.logy = 1;
    CX_CHECK_OK(cx_plot_add_series(&lg, "m", 5, tx, ty, CX_PLOT_LINE | CX_PLOT_MARKERS));
    CX_CHECK_OK(cx_plot_add_vline(&lg, 4e-3, "baseline"));
    CX_CHECK_OK(cx_plot_write_png(&lg, a, 400, 300, &d));
    /* the exact 0 is drawn in the labelled band below the decades: its
     * grey (0.95 -> 242) fill is there, the marker (series blue) in it */
    CX_CHECK_OK(test_png_read(&img, a));
    CX_CHECK(test_png_count(&img, 242, 242, 242, 1) > 1000);
    {
        int in_band = 0;
        for (int yy = img.h / 2; yy < img.h; yy++)
            for (int xx = 0; xx < img.w; xx++) {
                const unsigned char *q = test_png_px(&img, xx, yy);
                const unsigned char *below = yy + 6 < img.h ? test_png_px(&img, xx, yy + 6) : q;
                in_band += abs(q[0] - c0[0]) + abs(q[1] - c0[1]) + abs(q[2] - c0[2]) < 30 &&
                           abs(below[0] - 242) <= 2 && below[0] == below[2];
            }
        CX_CHECK(in_band > 0);
    }
    t = test_png_text(&img, "Series");
    CX_CHECK(t && strcmp(t, "m\tcolor=0\tmarker=circle") == 0);
    test_png_free(&img);

    /* 32 series: every (colour, marker) pair differs, and neighbours
     * differ in both */
    cx_plot many;
    cx_plot_init(&many, "many", "x", "y");
    for (int k = 0; k < CX_PLOT_MAX_SERIES; k++)
        CX_CHECK_OK(cx_plot_add_series(&many, "s", 1, tx, ty, CX_PLOT_MARKERS));
    for (int k = 0; k < CX_PLOT_MAX_SERIES; k++) {
        int ck, cj;
        const char *mk, *mj;
        cx_plot_series_style(&many, k, &ck, &mk);
        for (int j = 0; j < k; j++) {
            cx_plot_series_style(&many, j, &cj, &mj);
            CX_CHECK(ck != cj || strcmp(mk, mj) != 0);
            if (j == k - 1)
                CX_CHECK(ck != cj && strcmp(mk, mj) != 0);
        }
    }
    /* twelve series: twelve colours, the first eleven their own shape */
    {
        int cs[12];
        const char *ms[12];
        for (int k = 0; k < 12; k++) {
            cx_plot_series_style(&many, k, &cs[k], &ms[k]);
            for (int j = 0; j < k; j++) {
                CX_CHECK(cs[j] != cs[k]);
                if (k < 11)
                    CX_CHECK(strcmp(ms[j], ms[k]) != 0);
            }
        }
    }
    /* the legend covers no data: twelve series filling the area go right
     * of it; one series along the diagonal leaves a corner free */
    {
        enum { NP = 40 };
        static double gx[12][NP], gy[12][NP];
        cx_plot full;
        cx_plot_init(&full, "work-precision", "time [s]", "kkt error");
        full.logx = full.logy = 1;
        for (int k = 0; k < 12; k++) {
            for (int i = 0; i < NP; i++) {
                gx[k][i] = pow(10.0, -3 + 3.0 * i / (NP - 1));
                gy[k][i] = pow(10.0, -12 + 12.0 * ((i * 7 + k * 5) % NP) / (NP - 1));
            }
            CX_CHECK_OK(cx_plot_add_series(&full, "ssn-tresca rho=0.001", NP, gx[k], gy[k], CX_PLOT_MARKERS));
        }
        int outside = -1;
        long covered = -1;
        CX_CHECK_OK(cx_plot_legend_place(&full, 1200, 900, &outside, &covered, &d));
        CX_CHECK(outside == 1 && covered == 0);
        cx_plot one;
        cx_plot_init(&one, "diagonal", "x", "y");
        CX_CHECK_OK(cx_plot_add_series(&one, "m", NP, gx[0], gx[0], CX_PLOT_LINE | CX_PLOT_MARKERS));
        one.logx = one.logy = 1;
        CX_CHECK_OK(cx_plot_legend_place(&one, 1200, 900, &outside, &covered, &d));
        CX_CHECK(outside == 0 && covered == 0);
        CX_CHECK_OK(cx_plot_write_png(&full, "full_legend.png", 1200, 900, &d));
        if (!getenv("CX_TEST_KEEP"))   /* kept to be looked at */
            remove("full_legend.png");
    }
    /* 2 and 5 ticks of a log axis in the decades' notation */
    {
        cx_axis ax;
        char lab[64];
        cx_axis_make(&ax, 1e-4, 1e-2, 1, 6, 1);
        cx_axis_label(&ax, 2e-4, lab, sizeof lab);
        CX_CHECK(strcmp(lab, "2×10⁻⁴") == 0);
        cx_axis_label(&ax, 5e-3, lab, sizeof lab);
        CX_CHECK(strcmp(lab, "5×10⁻³") == 0);
        cx_axis_make(&ax, 0.1, 10, 1, 6, 1);
        cx_axis_label(&ax, 2, lab, sizeof lab);
        CX_CHECK(strcmp(lab, "2") == 0);
    }

    /* bad path: one line naming it, no file, no temporary */
    CX_CHECK(cx_plot_write_png(&pl, "no-such-dir/x.png", 300, 200, &d) == CX_EIO);
    CX_CHECK(strstr(d.msg, "no-such-dir/x.png") != NULL && strchr(d.msg, '\n') == NULL);
    CX_CHECK(access("no-such-dir", F_OK) != 0);
    /* a directory as the target: rename fails, the temporary is removed */
    CX_CHECK(cx_plot_write_png(&pl, ".", 300, 200, &d) == CX_EIO);
    /* nothing to draw; bad size */
    cx_plot empty;
    cx_plot_init(&empty, "e", "x", "y");
    CX_CHECK(cx_plot_write_png(&empty, b, 300, 200, &d) == CX_EINVAL);
    CX_CHECK(cx_plot_write_png(&pl, b, 10, 200, &d) == CX_EINVAL);
    remove(a);
    remove(b);
    return check_finish("render_plot");
}
