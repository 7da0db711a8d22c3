/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The panels of the right-hand side, drawn from the state only: the
 * per-step table, the contact strip (or 3D face) over the pressure
 * profile, the convergence plot, the mesh view and the table of runs. */
#include "tui/tui_impl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- contact status ------------------------------------------------------- */

static const char *status_glyph(int s)
{
    switch (s) {
    case CX_PT_CONTACT: return tui_sym("█", "#");
    case CX_PT_STICK: return tui_sym("●", "o");
    case CX_PT_SLIP_POS: return tui_sym("▶", ">");
    case CX_PT_SLIP_NEG: return tui_sym("◀", "<");
    default: return tui_sym("·", ".");
    }
}

static int status_role(int s)
{
    switch (s) {
    case CX_PT_CONTACT: return TUI_C_CONTACT;
    case CX_PT_STICK: return TUI_C_STICK;
    case CX_PT_SLIP_POS:
    case CX_PT_SLIP_NEG: return TUI_C_SLIP;
    default: return TUI_C_FREE;
    }
}

/* 3D slip: an arrow along the friction force's direction in x, y. */
static const char *arrow_glyph(double fx, double fy)
{
    static const char *const utf8[8] = {"→", "↗", "↑", "↖", "←", "↙", "↓", "↘"};
    static const char *const ascii[8] = {">", "/", "^", "\\", "<", "/", "v", "\\"};
    if (fx == 0 && fy == 0)
        return tui_sym("▶", ">");
    double a = atan2(fy, fx);
    int k = ((int)lround(a / (CX_PI / 4)) + 8) % 8;
    return tui_sym(utf8[k], ascii[k]);
}

/* ---- per-step table ----------------------------------------------------------- */

static void fmt_num(char *buf, size_t len, double v, int w)
{
    if (isnan(v))
        snprintf(buf, len, "%*s", w, "-");
    else
        snprintf(buf, len, "%*.1e", w, v);
}

void tui_panel_steps(const tui_state *st, tui_box b)
{
    const tui_run *run = tui_state_run(st);
    int y = b.y;
    int wide = b.w >= 82;
    const char *hdr = wide ? "iter   kkt error   own crit.  free cont stick slip chg  inner K-solves   time ms"
                           : "iter     kkt     own  fr  ct  st  sl  ch  inn   nK   ms";
    tui_term_put(y++, b.x, TUI_C_LABEL, hdr, b.w);
    int rows = b.h - 1;
    if (!run)
        return;
    int first = run->nsteps - rows;
    if (first < 0)
        first = 0;
    for (int k = first; k < run->nsteps; k++, y++) {
        const tui_step *s = &run->steps[k];
        char kkt[24], own[24];
        fmt_num(kkt, sizeof kkt, s->kkt, wide ? 11 : 7);
        fmt_num(own, sizeof own, s->own, wide ? 11 : 7);
        int role = k == run->nsteps - 1 ? TUI_C_NORMAL : TUI_C_FAINT;
        if (k == run->nsteps - 1 && run->reason > 0)
            role = TUI_C_OK;
        if (k == run->nsteps - 1 && run->reason < 0)
            role = TUI_C_ERROR;
        if (wide)
            tui_put(y, b.x, role, b.w, "%4d %s %s %5d %4d %5d %4d %3d %6ld %8ld %9.1f", s->iter, kkt, own, s->nfree,
                s->ncontact + s->nstick + s->nslip, s->nstick, s->nslip, s->nchanged, s->inner, s->solves,
                1e3 * s->time);
        else
            tui_put(y, b.x, role, b.w, "%4d %s %s %3d %3d %3d %3d %3d %4ld %4ld %4.0f", s->iter, kkt, own, s->nfree,
                s->ncontact + s->nstick + s->nslip, s->nstick, s->nslip, s->nchanged, s->inner, s->solves,
                1e3 * s->time);
    }
    if (run->nsteps == 0)
        tui_put(y, b.x, TUI_C_FAINT, b.w, "   (no step yet: s steps, r runs)");
}

/* ---- contact strip -------------------------------------------------------------- */

static void draw_strip_2d(const tui_state *st, int y, int x, int w)
{
    int m = st->m;
    for (int c = 0; c < w && m > 0; c++) {
        int lo = (int)((long)c * m / w), hi = (int)((long)(c + 1) * m / w);
        if (hi <= lo)
            hi = lo + 1;
        if (lo >= m)
            break;
        int ch;
        int s = tui_bucket_status(st->status, st->changed, lo, hi, &ch);
        tui_term_put(y, x + c, ch ? TUI_C_CHANGED : status_role(s), status_glyph(s), 1);
    }
}

/* The pressure p = lN / weight per point as bars, Hertz's over it. */
static void draw_pressure(const tui_state *st, int y, int x, int w, int h)
{
    int m = st->m;
    double pmax = 0;
    for (int i = 0; i < m; i++) {
        if (isfinite(st->pressure[i]))
            pmax = fmax(pmax, st->pressure[i]);
        if (isfinite(st->hertz[i]))
            pmax = fmax(pmax, st->hertz[i]);
    }
    if (!(pmax > 0) || h <= 0 || w <= 0)
        return;
    tui_canvas c;
    tui_canvas_init(&c, w, h);
    int ny = 4 * h;
    for (int xd = 0; xd < 2 * w; xd++) {
        int i = (int)((long)xd * m / (2 * w));
        if (i >= m)
            i = m - 1;
        double v = st->pressure[i] > 0 ? st->pressure[i] : 0;
        int top = ny - (int)lround(v / pmax * ny);
        for (int yd = top; yd < ny; yd++)
            tui_canvas_dot(&c, xd, yd, TUI_C_BAR);
        if (isfinite(st->hertz[i]) && st->hertz[i] > 0) {
            int hy = ny - (int)lround(st->hertz[i] / pmax * ny);
            tui_canvas_dot(&c, xd, hy < ny ? hy : ny - 1, TUI_C_REF);
        }
    }
    tui_put_canvas(&c, y, x);
    tui_canvas_free(&c);
}

/* 3D: a grid of the contact face (x right, y up), slip as arrows. */
static void draw_face_3d(const tui_state *st, int y, int x, int w, int h)
{
    const cx_contact_set *cs = &st->info->contact;
    int m = st->m;
    if (m == 0 || h <= 0)
        return;
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int i = 0; i < m; i++) {
        x0 = fmin(x0, cs->x[3 * i]);
        x1 = fmax(x1, cs->x[3 * i]);
        y0 = fmin(y0, cs->x[3 * i + 1]);
        y1 = fmax(y1, cs->x[3 * i + 1]);
    }
    /* as many columns and rows as distinct coordinates, within the room */
    int gw = (int)lround(sqrt((double)m) * (x1 - x0) / fmax(1e-300, sqrt((x1 - x0) * (y1 - y0))));
    int gh = gw > 0 ? m / gw : 1;
    gw = gw < 1 ? 1 : gw > w / 2 ? w / 2 : gw;
    gh = gh < 1 ? 1 : gh > h ? h : gh;
    int cells = gw * gh;
    int best[64 * 64], chg[64 * 64], who[64 * 64];
    if (gw > 64)
        gw = 64;
    if (gh > 64)
        gh = 64;
    cells = gw * gh;
    for (int k = 0; k < cells; k++)
        best[k] = -1, chg[k] = 0, who[k] = -1;
    for (int i = 0; i < m; i++) {
        int cx = x1 > x0 ? (int)lround((cs->x[3 * i] - x0) / (x1 - x0) * (gw - 1)) : 0;
        int cy = y1 > y0 ? (int)lround((cs->x[3 * i + 1] - y0) / (y1 - y0) * (gh - 1)) : 0;
        int k = (gh - 1 - cy) * gw + cx;
        if (best[k] < 0 || tui_status_rank(st->status[i]) > tui_status_rank(best[k])) {
            best[k] = st->status[i];
            who[k] = i;
        }
        chg[k] |= st->changed[i];
    }
    for (int k = 0; k < cells; k++) {
        if (best[k] < 0)
            continue;
        const char *g = status_glyph(best[k]);
        if (best[k] == CX_PT_SLIP_POS)
            g = arrow_glyph(st->slip_dir[2 * who[k]], st->slip_dir[2 * who[k] + 1]);
        tui_term_put(y + k / gw, x + 2 * (k % gw), chg[k] ? TUI_C_CHANGED : status_role(best[k]), g, 1);
    }
}

void tui_panel_contact(const tui_state *st, tui_box b)
{
    int y = b.y;
    char legend[160];
    snprintf(legend, sizeof legend, "contact %s", st->info->dim == 3 ? "face" : "strip");
    tui_rule(y, b.x, b.w, legend);
    /* legend on the rule's right */
    int lx = b.x + 16;
    const int roles[] = {TUI_C_FREE, TUI_C_CONTACT, TUI_C_STICK, TUI_C_SLIP, TUI_C_CHANGED};
    const char *names[] = {"free", "contact", "stick", "slip", "changed"};
    const char *glyphs[] = {status_glyph(CX_PT_FREE), status_glyph(CX_PT_CONTACT), status_glyph(CX_PT_STICK),
                            st->info->dim == 3 ? tui_sym("→", ">") : tui_sym("▶◀", "><"), tui_sym("▒", "%")};
    for (int k = 0; k < 5 && lx < b.x + b.w - 8; k++) {
        tui_put(y, lx - 1, TUI_C_LABEL, 1, " ");
        tui_put(y, lx, roles[k], b.w - (lx - b.x), "%s", glyphs[k]);
        lx += k == 3 && st->info->dim != 3 ? 2 : 1;
        tui_put(y, lx, TUI_C_LABEL, b.w - (lx - b.x), "%s ", names[k]);
        lx += (int)strlen(names[k]) + 2;
    }
    y++;
    if (st->m <= 0)
        return;
    if (st->info->dim == 3) {
        draw_face_3d(st, y, b.x, b.w, b.h - 1);
        return;
    }
    /* the strip and the profile share their columns: cell c is the same
     * points in both */
    int lw = 12, w = b.w - lw;
    draw_strip_2d(st, y, b.x, w);
    tui_put(y++, b.x + w + 1, TUI_C_LABEL, lw - 1, "%d pts", st->m);
    int ph = b.h - 2;
    if (ph > 0) {
        double pmax = 0, hmax = 0;
        for (int i = 0; i < st->m; i++) {
            pmax = fmax(pmax, st->pressure[i]);
            if (isfinite(st->hertz[i]))
                hmax = fmax(hmax, st->hertz[i]);
        }
        draw_pressure(st, y, b.x, w, ph);
        tui_put(y, b.x + w + 1, TUI_C_BAR, lw - 1, "p %.3g", pmax);
        if (hmax > 0 && ph > 1)
            tui_put(y + 1, b.x + w + 1, TUI_C_REF, lw - 1, "%s %.3g", tui_sym("⠒Hertz", "'Hertz"), hmax);
    }
}

/* ---- convergence plot ---------------------------------------------------------- */

void tui_panel_plot(const tui_state *st, tui_box b)
{
    tui_rule(b.y, b.x, b.w, "log10 kkt error vs iteration");
    int lw = 6;
    int w = b.w - lw, h = b.h - 2;
    if (w < 4 || h < 2)
        return;
    int itmax = 10;
    double lo = -12, hi = 0;
    for (int r = 0; r < tui_state_nruns(st); r++)
        for (int k = 0; k < tui_state_run_at(st, r)->nsteps; k++) {
            const tui_step *s = &tui_state_run_at(st, r)->steps[k];
            itmax = s->iter > itmax ? s->iter : itmax;
            if (s->kkt > 0 && isfinite(s->kkt)) {
                lo = fmin(lo, floor(log10(s->kkt)));
                hi = fmax(hi, ceil(log10(s->kkt)));
            }
        }
    lo = fmax(lo, -18);
    tui_canvas c, cur;
    tui_canvas_init(&c, w, h);
    tui_canvas_init(&cur, w, h);
    double sx = (2.0 * w - 1) / itmax, sy = (4.0 * h - 1) / (hi - lo);
#define PX(it) ((it) * sx)
#define PY(v) ((hi - (v)) * sy)
    /* the tolerance, dotted (labelled below) */
    double lt = log10(st->cur_opt.tol);
    if (lt >= lo && lt <= hi)
        for (int xd = 0; xd < 2 * w; xd += 3)
            tui_canvas_dot(&c, xd, (int)lround(PY(lt)), TUI_C_FAINT);
    /* each run in its own colour; the current one on its own canvas, laid
     * over the others so that it wins every shared cell */
    int nr = tui_state_nruns(st), top = nr - 1;
    for (int r = 0; r < nr; r++)
        if (st->highlight && tui_state_run_at(st, r)->serial + 1 == st->highlight)
            top = r;   /* a run clicked in the runs table is drawn on top instead */
    for (int r = 0; r < nr; r++) {
        const tui_run *run = tui_state_run_at(st, r);
        tui_canvas *on = r == top ? &cur : &c;
        int role = TUI_C_SERIES0 + tui_run_colour(run);
        double px = NAN, py = NAN;
        for (int k = 0; k < run->nsteps; k++) {
            double v = run->steps[k].kkt > 0 ? log10(run->steps[k].kkt) : lo;
            if (!isfinite(v))
                v = hi;
            v = fmax(lo, fmin(hi, v));
            double qx = PX(run->steps[k].iter), qy = PY(v);
            if (isfinite(px))
                tui_canvas_line(on, px, py, qx, qy, role);
            else
                tui_canvas_dot(on, (int)lround(qx), (int)lround(qy), role);
            px = qx;
            py = qy;
        }
    }
    for (int k = 0; k < w * h; k++)
        if (cur.bits[k]) {
            c.bits[k] |= cur.bits[k];
            c.role[k] = cur.role[k];
        }
    tui_canvas_free(&cur);
    tui_put_canvas(&c, b.y + 1, b.x + lw);
    tui_canvas_free(&c);
    /* ticks at whole decades, on the row each decade's line is drawn on,
     * every decade that the rows leave room for */
    int every = 1;
    while ((hi - lo) / every + 1 > h)
        every++;
    int last_row = -2;
    for (int v = (int)hi; v >= (int)lo; v--) {
        if (((int)hi - v) % every)
            continue;
        int row = (int)lround(PY(v)) / 4;
        if (row <= last_row || row >= h)
            continue;
        last_row = row;
        tui_put(b.y + 1 + row, b.x, TUI_C_LABEL, lw, "%4d %s", v, tui_sym("┤", "|"));
    }
    if (lt >= lo && lt <= hi) {
        char tl[32];
        int n = snprintf(tl, sizeof tl, " tol %.0e ", st->cur_opt.tol);
        int row = (int)lround(PY(lt)) / 4;
        if (n < w)
            tui_put(b.y + 1 + row, b.x + lw + w - n, TUI_C_LABEL, n, "%s", tl);
    }
#undef PX
#undef PY
    tui_put(b.y + b.h - 1, b.x + lw, TUI_C_LABEL, w, "0%*d", w - 1, itmax);
    tui_put(b.y + b.h - 1, b.x + lw + 3, TUI_C_FAINT, w - 8, "iteration");
    /* the legend, top right (where converging curves do not go): the
     * newest runs, each in its colour, method and changed parameters */
    int nleg = nr < h - 1 ? nr : h - 1;
    int lgw = 0, laws = 0;
    char leg[TUI_MAX_RUNS][64];
    /* the law too, when the runs shown differ in it (ssn-tresca under
     * none and under tresca would read the same) */
    for (int k = 0; k < nleg; k++)
        laws |= 1 << tui_state_run_at(st, nr - nleg + k)->law;
    for (int k = 0; k < nleg; k++) {
        const tui_run *run = tui_state_run_at(st, nr - nleg + k);
        char one[64];
        tui_run_legend(run, one, sizeof one);
        if (laws & (laws - 1)) {
            size_t at = strcspn(one, " ");
            snprintf(leg[k], sizeof leg[k], "%.*s %s%s", (int)at, one, cx_friction_name(run->law), one + at);
        } else {
            snprintf(leg[k], sizeof leg[k], "%s", one);
        }
        int l = (int)strlen(leg[k]) + 3;
        lgw = l > lgw ? l : lgw;
    }
    lgw = lgw > w / 2 ? w / 2 : lgw;
    for (int k = 0; nr > 1 && k < nleg && lgw > 4; k++) {
        const tui_run *run = tui_state_run_at(st, nr - nleg + k);
        int x = b.x + b.w - lgw;
        tui_put(b.y + 1 + k, x, TUI_C_SERIES0 + tui_run_colour(run), 3, "%s ", tui_sym("━━", "--"));
        /* short of room: cut with an ellipsis (a click on the run in the
         * runs table shows the whole legend) */
        if ((int)strlen(leg[k]) > lgw - 3)
            snprintf(leg[k] + lgw - 4, sizeof leg[k] - (size_t)(lgw - 4), "%s", tui_sym("…", "~"));
        tui_put(b.y + 1 + k, x + 3, TUI_C_SERIES0 + tui_run_colour(run), lgw - 3, "%-*s", lgw - 3, leg[k]);
    }
}

/* ---- mesh view -------------------------------------------------------------------- */

static void project(int dim, const double *x, double *px, double *py)
{
    if (dim == 2) {
        *px = x[0];
        *py = x[1];
    } else {
        /* an oblique view: x right, z up, y into the screen */
        *px = x[0] + 0.45 * x[1];
        *py = x[2] + 0.3 * x[1];
    }
}

/* The side of the body the obstacle is on, as a unit vector: a plane's
 * inside (-normal), a disc's or a sphere's centre seen from the body. */
static void obstacle_side(const cx_obstacle *ob, const double *centre, int dim, double v[3])
{
    double l = 0;
    for (int c = 0; c < 3; c++) {
        v[c] = ob->kind == CX_OBST_PLANE ? -ob->normal[c] : c < dim ? ob->point[c] - centre[c] : 0;
        l += v[c] * v[c];
    }
    l = sqrt(l);
    for (int c = 0; c < 3; c++)
        v[c] = l > 0 ? v[c] / l : 0;
}

/* The obstacle on the canvas (clipped by it): a plane as its line (2D) or
 * a quadrilateral under the body (3D), with short hatching on the
 * obstacle's side; a disc or a sphere as its circle. to(x, px, py) maps a
 * point to dots. */
typedef struct mesh_map {
    int dim;
    double x0, y1, s;
} mesh_map;

static void map_point(const mesh_map *m, const double *x, double *px, double *py)
{
    double q[3] = {x[0], x[1], m->dim == 3 ? x[2] : 0}, a, b;
    project(m->dim, q, &a, &b);
    *px = (a - m->x0) * m->s;
    *py = (m->y1 - b) * m->s;
}

static void draw_obstacle(tui_canvas *c, const mesh_map *m, const cx_obstacle *ob, const double lo[3],
                          const double hi[3])
{
    int dim = m->dim, role = TUI_C_LABEL;
    if (ob->kind == CX_OBST_PLANE) {
        /* two directions in the plane, spanning the body's extent and a
         * margin */
        const double *n = ob->normal;
        double t1[3], t2[3] = {0, 0, 0};
        if (dim == 2) {
            t1[0] = -n[1], t1[1] = n[0], t1[2] = 0;
        } else {
            double a[3] = {fabs(n[0]) < 0.9 ? 1 : 0, fabs(n[0]) < 0.9 ? 0 : 1, 0};
            t1[0] = a[1] * n[2] - a[2] * n[1], t1[1] = a[2] * n[0] - a[0] * n[2], t1[2] = a[0] * n[1] - a[1] * n[0];
            double l = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
            for (int k = 0; k < 3; k++)
                t1[k] /= l;
            t2[0] = n[1] * t1[2] - n[2] * t1[1], t2[1] = n[2] * t1[0] - n[0] * t1[2], t2[2] = n[0] * t1[1] - n[1] * t1[0];
        }
        /* the body's centre put on the plane, and its half extents along t1, t2 */
        double ctr[3], e1 = 0, e2 = 0, dn = 0;
        for (int k = 0; k < 3; k++)
            ctr[k] = 0.5 * (lo[k] + hi[k]);
        for (int k = 0; k < dim; k++)
            dn += (ctr[k] - ob->point[k]) * n[k];
        for (int k = 0; k < 3; k++) {
            ctr[k] -= dn * n[k];
            e1 += 0.5 * (hi[k] - lo[k]) * fabs(t1[k]);
            e2 += 0.5 * (hi[k] - lo[k]) * fabs(t2[k]);
        }
        e1 = 1.15 * e1 + 1e-12;
        e2 = 1.15 * e2;
        double P[4][3], px[4], py[4];
        for (int k = 0; k < 4; k++) {
            double s1 = k == 0 || k == 3 ? -e1 : e1, s2 = k < 2 ? -e2 : e2;
            for (int d = 0; d < 3; d++)
                P[k][d] = ctr[d] + s1 * t1[d] + s2 * t2[d];
            map_point(m, P[k], &px[k], &py[k]);
        }
        int nedge = dim == 2 ? 1 : 4;
        for (int k = 0; k < nedge; k++)
            tui_canvas_line(c, px[k], py[k], px[(k + 1) % 4], py[(k + 1) % 4], role);
        /* hatching along the front edge, into the obstacle */
        double in[3], ipx, ipy, opx, opy, h = 3 / m->s;
        for (int d = 0; d < 3; d++)
            in[d] = P[0][d] - h * n[d];
        map_point(m, P[0], &opx, &opy);
        map_point(m, in, &ipx, &ipy);
        double dx = ipx - opx + 1.5, dy = ipy - opy;
        double len = hypot(px[1] - px[0], py[1] - py[0]);
        for (double a = 0; a <= len; a += 4) {
            double x = px[0] + (px[1] - px[0]) * a / fmax(len, 1e-12), y = py[0] + (py[1] - py[0]) * a / fmax(len, 1e-12);
            tui_canvas_line(c, x, y, x + dx, y + dy, role);
        }
        return;
    }
    if (ob->kind == CX_OBST_DISC || ob->kind == CX_OBST_SPHERE) {
        /* the circle in the view's plane through the centre (a sphere seen
         * from the front) */
        double px0 = NAN, py0 = NAN;
        for (int k = 0; k <= 96; k++) {
            double a = 2 * 3.14159265358979323846 * k / 96, q[3] = {ob->point[0], ob->point[1], ob->point[2]}, px, py;
            q[0] += ob->radius * cos(a);
            q[dim == 2 ? 1 : 2] += ob->radius * sin(a);
            map_point(m, q, &px, &py);
            if (k)
                tui_canvas_line(c, px0, py0, px, py, role);
            px0 = px, py0 = py;
        }
    }
}

void tui_panel_mesh(const tui_state *st, tui_box b)
{
    const cx_mesh *mesh = st->info->mesh;
    double scale = st->disp_scale > 0 ? st->disp_scale : tui_mesh_auto_scale(st);
    char title[96];
    snprintf(title, sizeof title, "deformed mesh, displacement x%.3g", scale);
    tui_rule(b.y, b.x, b.w, title);
    int w = b.w, h = b.h - 1;
    if (!mesh || !st->uall || w < 4 || h < 2)
        return;
    int dim = mesh->dim, nn = mesh->nnodes;
    double *P = tui_xalloc(NULL, sizeof(double) * 2 * (size_t)nn);
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int c = 0; c < dim; c++)
        lo[c] = INFINITY, hi[c] = -INFINITY;
    for (int k = 0; k < nn; k++) {
        double q[3];
        for (int c = 0; c < dim; c++) {
            q[c] = mesh->x[dim * k + c] + scale * st->uall[dim * k + c];
            lo[c] = fmin(lo[c], q[c]);
            hi[c] = fmax(hi[c], q[c]);
        }
        project(dim, q, &P[2 * k], &P[2 * k + 1]);
        x0 = fmin(x0, P[2 * k]);
        x1 = fmax(x1, P[2 * k]);
        y0 = fmin(y0, P[2 * k + 1]);
        y1 = fmax(y1, P[2 * k + 1]);
    }
    /* the view fits the deformed body whatever the scale (refitted every
     * frame, so a larger scale shrinks the picture instead of leaving it),
     * with room on the obstacle's side to show it */
    const tui_meshview *mv = &st->mesh_view;
    if (mv->has_obstacle) {
        double ctr[3], v[3], pv[2], o[3] = {0, 0, 0}, po[2];
        for (int c = 0; c < 3; c++)
            ctr[c] = 0.5 * (lo[c] + hi[c]);
        obstacle_side(&mv->obstacle, ctr, dim, v);
        project(dim, v, &pv[0], &pv[1]);
        project(dim, o, &po[0], &po[1]);
        double ext = 0.12 * fmax(x1 - x0, y1 - y0);
        double vx = pv[0] - po[0], vy = pv[1] - po[1];
        if (vx < 0)
            x0 += ext * vx;
        else
            x1 += ext * vx;
        if (vy < 0)
            y0 += ext * vy;
        else
            y1 += ext * vy;
    }
    /* dots are about square: one scale for both axes */
    double s = fmin((2.0 * w - 2) / fmax(x1 - x0, 1e-300), (4.0 * h - 2) / fmax(y1 - y0, 1e-300));
    tui_canvas c;
    tui_canvas_init(&c, w, h);
    mesh_map map = {dim, x0, y1, s};
    if (mv->has_obstacle)
        draw_obstacle(&c, &map, &mv->obstacle, lo, hi);
    /* 2D: every edge while they are at least 3 dots long on average, else
     * the outline (the edges of the surface facets); 3D: the surface's
     * feature edges (its folds), which read where every surface edge
     * would fill the panel */
    double len = 0;
    int sampled = 0, seg[6][2];
    for (int e = 0; dim == 2 && e < mesh->nelems && sampled < 4000; e += 1 + mesh->nelems / 2000) {
        int ne = tui_meshview_elem_edges(mesh, e, seg);
        for (int k = 0; k < ne; k++, sampled++) {
            int a = seg[k][0], bb = seg[k][1];
            len += s * hypot(P[2 * a] - P[2 * bb], P[2 * a + 1] - P[2 * bb + 1]);
        }
    }
    if (dim == 2 && sampled && len / sampled >= 3) {
        for (int e = 0; e < mesh->nelems; e++) {
            int ne = tui_meshview_elem_edges(mesh, e, seg);
            for (int k = 0; k < ne; k++) {
                int a = seg[k][0], bb = seg[k][1];
                tui_canvas_line(&c, (P[2 * a] - x0) * s, (y1 - P[2 * a + 1]) * s, (P[2 * bb] - x0) * s,
                                (y1 - P[2 * bb + 1]) * s, TUI_C_FAINT);
            }
        }
    } else {
        int nout;
        const int *out = tui_state_outline(st, &nout);
        if (dim == 3) {
            out = mv->features;
            nout = mv->nfeatures;
        }
        for (int k = 0; k < nout; k++) {
            int a = out[2 * k], bb = out[2 * k + 1];
            tui_canvas_line(&c, (P[2 * a] - x0) * s, (y1 - P[2 * a + 1]) * s, (P[2 * bb] - x0) * s,
                            (y1 - P[2 * bb + 1]) * s, TUI_C_NORMAL);
        }
    }
    const cx_contact_set *cs = &st->info->contact;
    for (int i = 0; i < st->m && cs->node; i++) {
        int k = cs->node[i];
        tui_canvas_dot(&c, (int)lround((P[2 * k] - x0) * s), (int)lround((y1 - P[2 * k + 1]) * s),
                       status_role(st->status[i]));
    }
    tui_put_canvas(&c, b.y + 1, b.x);
    tui_canvas_free(&c);
    free(P);
}

/* ---- finished runs --------------------------------------------------------------------- */

void tui_panel_runs(const tui_state *st, tui_box b)
{
    tui_rule(b.y, b.x, b.w, "runs");
    /* narrow: the time and K-solve columns go, the outcome stays */
    int wide = b.w >= 91;
    /* each row opens with its run's colour, as in the plot and its legend */
    b.x += 2;
    b.w -= 2;
    if (wide)   /* fact and nK: the run's own factorisations and K-solves, as solve counts them */
        tui_put(b.y + 1, b.x, TUI_C_LABEL, b.w, "%-11s %-7s %-7s %4s %7s %7s %4s %4s  %s", "method", "law",
            "F/slip", "iter", "kkt", "ms", "fact", "nK", "outcome; changed parameters");
    else
        tui_put(b.y + 1, b.x, TUI_C_LABEL, b.w, "%-10s %-7s %-6s %4s %7s %4s  %s", "method", "law", "F/slip", "iter",
            "kkt", "fact", "outcome; changed");
    int rows = b.h - 2;
    int first = tui_state_nruns(st) - rows;
    if (first < 0)
        first = 0;
    for (int r = first, y = b.y + 2; r < tui_state_nruns(st); r++, y++) {
        const tui_run *run = tui_state_run_at(st, r);
        const tui_step *s = run->nsteps ? &run->steps[run->nsteps - 1] : NULL;
        char kkt[24], coef[24], outcome[CX_DIAG_LEN];
        fmt_num(kkt, sizeof kkt, s ? s->kkt : NAN, 7);
        if (run->law == CX_FRICTION_NONE)
            snprintf(coef, sizeof coef, "-");
        else
            snprintf(coef, sizeof coef, "%s%.3g", run->law == CX_FRICTION_COULOMB ? "F " : "s ", run->coef);
        /* the outcome in words: cx_reason_format's sentence up to its
         * colon ("converged in 7 iterations", "did not converge in 500
         * iterations"), the numbers being in the columns */
        if (run->reason && run->outcome[0])
            snprintf(outcome, sizeof outcome, "%.*s", (int)strcspn(run->outcome, ":"), run->outcome);
        else
            snprintf(outcome, sizeof outcome, "%s",
                     run->reason ? cx_reason_str(run->reason) : r == tui_state_nruns(st) - 1 ? "current" : "stopped");
        /* a run the operator cache served says so */
        if (tui_run_cached(run))
            snprintf(outcome + strlen(outcome), sizeof outcome - strlen(outcome), ", cached");
        int role = run->reason > 0 ? TUI_C_OK : run->reason < 0 ? TUI_C_ERROR : TUI_C_NORMAL;
        if (r == tui_state_nruns(st) - 1 && run->reason == 0)
            role = TUI_C_CURRENT;
        /* the run clicked: its row in the selection's colours, its curve on top */
        if (st->highlight && run->serial + 1 == st->highlight)
            role = TUI_C_SELECT;
        tui_put(y, b.x - 2, TUI_C_SERIES0 + tui_run_colour(run), 2, "%s", tui_sym("■", "#"));
        tui_hit_add(y, b.x - 2, b.x + b.w, TUI_HIT_RUN, r);
        if (wide)
            tui_put(y, b.x, role, b.w, "%-11.11s %-7s %-7.7s %4d %s %7.1f %4ld %4ld  %s%s%s", run->method,
                cx_friction_name(run->law), coef, s ? s->iter : 0, kkt, s ? 1e3 * s->time : 0, run->factorizations,
                s ? s->solves : 0, outcome, run->changed[0] ? "; " : "", run->changed);
        else {
            /* the sentence if it fits, else the outcome's word (the
             * iterations are in their column), cut with an ellipsis only
             * when even that is too long */
            int avail = b.w - 45;
            char tail[CX_DIAG_LEN + 200];
            snprintf(tail, sizeof tail, "%s%s%s", outcome, run->changed[0] ? "; " : "", run->changed);
            if ((int)strlen(tail) > avail && run->reason)
                snprintf(tail, sizeof tail, "%s%s%s%s", cx_reason_str(run->reason),
                         tui_run_cached(run) ? ", cached" : "", run->changed[0] ? "; " : "", run->changed);
            /* the full legend is in the status line when the run is clicked */
            if ((int)strlen(tail) > avail && avail > 1)
                snprintf(tail + avail - 1, sizeof tail - (size_t)avail + 1, "%s", tui_sym("…", "~"));
            tui_put(y, b.x, role, b.w, "%-10.10s %-7s %-6.6s %4d %s %4ld  %s", run->method, cx_friction_name(run->law),
                coef, s ? s->iter : 0, kkt, run->factorizations, tail);
        }
    }
}
