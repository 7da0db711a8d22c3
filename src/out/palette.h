/* SPDX-License-Identifier: GPL-3.0-or-later */
/* out/palette.h: the one table of contact-status colours, shared by the
 * renderer (render/colormap.c: cx_status_color) and the explorer, so that
 * a figure and the screen agree. Okabe & Ito's colour-blind-safe set
 * ("Color Universal Design", 2008): every pair stays distinct under the
 * common colour-vision deficiencies, and free stays a neutral grey.
 * Indexed by cx_point_status (solve/solve.h). */
#ifndef CX_OUT_PALETTE_H
#define CX_OUT_PALETTE_H

enum { CX_PALETTE_NSTATUS = 5 };

/* rgb in [0, 255] */
static const unsigned char cx_palette_status[CX_PALETTE_NSTATUS][3] = {
    {153, 153, 153},   /* CX_PT_FREE: grey */
    {0, 114, 178},     /* CX_PT_CONTACT (frictionless): Okabe-Ito blue */
    {0, 158, 115},     /* CX_PT_STICK: Okabe-Ito bluish green */
    {213, 94, 0},      /* CX_PT_SLIP_POS: Okabe-Ito vermillion */
    {213, 94, 0},      /* CX_PT_SLIP_NEG: the same (the arrow gives the direction) */
};

/* The words of the statuses in legends, in the same order. */
static const char *const cx_palette_status_name[CX_PALETTE_NSTATUS] = {
    "free", "contact", "stick", "slip", "slip"};

/* The colours of compared series: the explorer's runs (one each, in the
 * plot, the runs table and the legend) and the series of the renderer's
 * plots (render/plot.c), so that a method has one colour on the screen
 * and in the figure. First Okabe & Ito's set — blue, orange, bluish
 * green, vermillion, sky blue, reddish purple (their yellow and black
 * left out: yellow washes out on white, black vanishes on a dark
 * terminal) — then six of Paul Tol's "muted" scheme, also chosen to stay
 * apart under colour-vision deficiencies: indigo, olive, wine, teal,
 * green, rose. Twelve, so that a work-precision plot of twelve methods
 * gives each its own colour (and, render/plot.c, its own marker for the
 * first eleven). Every entry has a hue (never a terminal's black or
 * white) and its own xterm-256 cell. A series k takes entry k mod the
 * count. */
enum { CX_PALETTE_NSERIES = 12 };
static const unsigned char cx_palette_series[CX_PALETTE_NSERIES][3] = {
    {0, 114, 178}, {230, 159, 0}, {0, 158, 115}, {213, 94, 0}, {86, 180, 233}, {204, 121, 167},
    {51, 34, 136}, {153, 153, 51}, {136, 34, 85}, {68, 170, 153}, {17, 119, 51}, {204, 102, 119},
};
static const char *const cx_palette_series_name[CX_PALETTE_NSERIES] = {
    "blue", "orange", "green", "vermillion", "sky blue", "purple",
    "indigo", "olive", "wine", "teal", "dark green", "rose"};

/* The "not converged" banner: a dark vermillion that white bold text
 * reads on (contrast above 4.5:1), as cairo's doubles. */
#define CX_PALETTE_WARNING_RGB 0.66, 0.22, 0.0

#endif
