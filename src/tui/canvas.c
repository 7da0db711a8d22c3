/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A canvas of braille characters: each cell holds 2 x 4 dots (Unicode
 * U+2800 + an 8-bit mask), so a panel of w x h cells plots at 2w x 4h. */
#include "tui/tui_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Braille dot numbering: column 0 rows 0-2 are bits 0-2, column 1 rows
 * 0-2 bits 3-5, row 3 bits 6 (column 0) and 7 (column 1). */
static const unsigned char canvas_bit[4][2] = {{0x01, 0x08}, {0x02, 0x10}, {0x04, 0x20}, {0x40, 0x80}};

void tui_canvas_init(tui_canvas *c, int w, int h)
{
    c->w = w > 0 ? w : 0;
    c->h = h > 0 ? h : 0;
    size_t n = (size_t)c->w * (size_t)c->h;
    c->bits = tui_xalloc(NULL, n);
    c->role = tui_xalloc(NULL, n);
    memset(c->bits, 0, n);
    memset(c->role, 0, n);
}

void tui_canvas_free(tui_canvas *c)
{
    free(c->bits);
    free(c->role);
    memset(c, 0, sizeof *c);
}

void tui_canvas_dot(tui_canvas *c, int x, int y, int role)
{
    if (x < 0 || y < 0 || x >= 2 * c->w || y >= 4 * c->h)
        return;
    size_t k = (size_t)(y / 4) * (size_t)c->w + (size_t)(x / 2);
    c->bits[k] |= canvas_bit[y % 4][x % 2];
    if (role >= c->role[k])
        c->role[k] = (unsigned char)role;
}

void tui_canvas_line(tui_canvas *c, double x0, double y0, double x1, double y1, int role)
{
    if (!isfinite(x0) || !isfinite(y0) || !isfinite(x1) || !isfinite(y1))
        return;
    double dx = x1 - x0, dy = y1 - y0;
    double len = fmax(fabs(dx), fabs(dy));
    /* a line far outside the canvas costs nothing */
    double lim = 8.0 * (c->w + c->h) + 16;
    if (len > 4 * lim)
        len = 4 * lim;
    int n = (int)ceil(len);
    for (int k = 0; k <= n; k++) {
        double t = n ? (double)k / n : 0;
        tui_canvas_dot(c, (int)lround(x0 + t * dx), (int)lround(y0 + t * dy), role);
    }
}

void tui_canvas_glyph(const tui_canvas *c, int i, int j, int utf8, char out[8])
{
    unsigned b = c->bits[(size_t)j * (size_t)c->w + (size_t)i];
    if (utf8) {
        if (!b) {
            out[0] = ' ';
            out[1] = '\0';
            return;
        }
        /* U+2800 + b in UTF-8: 1110 0010, 10 1000bb, 10 bbbbbb */
        out[0] = (char)0xE2;
        out[1] = (char)(0xA0 | (b >> 6));
        out[2] = (char)(0x80 | (b & 0x3F));
        out[3] = '\0';
        return;
    }
    int top = (b & 0x1B) != 0, bottom = (b & 0xE4) != 0;
    out[0] = top && bottom ? ':' : top ? '\'' : bottom ? '.' : ' ';
    out[1] = '\0';
}

/* ---- the contact strip's cells ---- */

int tui_status_rank(int s)
{
    static const int rank[] = {[CX_PT_FREE] = 0, [CX_PT_CONTACT] = 1, [CX_PT_STICK] = 2,
                               [CX_PT_SLIP_POS] = 3, [CX_PT_SLIP_NEG] = 3};
    return s >= 0 && s <= CX_PT_SLIP_NEG ? rank[s] : 0;
}

int tui_bucket_status(const unsigned char *status, const unsigned char *changed, int lo, int hi,
                      int *changed_out)
{
    int best = CX_PT_FREE, ch = 0;
    for (int i = lo; i < hi; i++) {
        if (tui_status_rank(status[i]) > tui_status_rank(best))
            best = status[i];
        ch |= changed[i] != 0;
    }
    *changed_out = ch;
    return best;
}


/* ---- palette mapping ---------------------------------------------------- */

static long rgb_dist2(const unsigned char a[3], int r, int g, int b)
{
    long dr = a[0] - r, dg = a[1] - g, db = a[2] - b;
    return dr * dr + dg * dg + db * db;
}

int tui_palette_xterm256(const unsigned char rgb[3])
{
    /* the cube's six levels per channel, then the 24 greys 8, 18, ..., 238 */
    static const int level[6] = {0, 95, 135, 175, 215, 255};
    int best = 16;
    long bd = -1;
    for (int i = 0; i < 216; i++) {
        long dd = rgb_dist2(rgb, level[i / 36], level[(i / 6) % 6], level[i % 6]);
        if (bd < 0 || dd < bd) {
            bd = dd;
            best = 16 + i;
        }
    }
    for (int i = 0; i < 24; i++) {
        int v = 8 + 10 * i;
        long dd = rgb_dist2(rgb, v, v, v);
        if (dd < bd) {
            bd = dd;
            best = 232 + i;
        }
    }
    return best;
}

int tui_palette_basic8(const unsigned char rgb[3])
{
    /* the basic colours by hue: the channels above half their largest
     * (black and white only for colours without a hue, so that a series
     * colour never becomes invisible on one of the two backgrounds) */
    int mx = rgb[0] > rgb[1] ? rgb[0] : rgb[1];
    mx = mx > rgb[2] ? mx : rgb[2];
    int mn = rgb[0] < rgb[1] ? rgb[0] : rgb[1];
    mn = mn < rgb[2] ? mn : rgb[2];
    if (mx - mn < 40)
        return mx >= 128 ? 7 : 0;
    int bits = 0;
    for (int c = 0; c < 3; c++)
        if (2 * rgb[c] > mx + mn)
            bits |= 1 << c;   /* red 1, green 2, blue 4: curses' order */
    return bits == 7 ? 7 : bits;
}
