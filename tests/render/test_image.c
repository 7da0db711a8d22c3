/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Images (render/render.h): every field of hertz (2D) and block3d (3D) at
 * a small size, read back and checked — not blank, the colour bar holds
 * the colormap in order, the body / obstacle / background where the
 * geometry says, status colours at the contact points, text chunks,
 * identical bytes twice, a bad path; and a synthetic six-body mesh drawn
 * with as many draw calls as one body. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "render_fixture.h"

enum { W = 400, H = 300 };
static const char *OUT = "test_image.png";

typedef struct solved {
    cx_scene sc;
    cx_session *s;
    int level;
    double *uall;
    cx_result *st;
} solved;

static void solve_scene(solved *o, const char *id, int level)
{
    cx_diag d;
    memset(o, 0, sizeof *o);
    fixture_solve_scene(&o->sc, &o->s, id, level, 0);
    const cx_problem *cp = cx_session_problem(o->s);
    const cx_iterate *it = cx_session_iterate(o->s);
    CX_CHECK(it->reason > 0);
    o->level = level;
    o->uall = cx_malloc(sizeof(double) * cp->map.nall);
    cx_fem_expand(&cp->map, it->u, o->uall);
    CX_CHECK_OK(cx_result_from_session(&o->st, o->s, &o->sc, level, &d));
    CX_CHECK(o->st->n == cp->n && o->st->run.kkt == it->kkt && o->st->run.level == level);
    CX_CHECK(memcmp(o->st->u, o->uall, sizeof(double) * cp->map.nall) == 0);
}

static void solved_free(solved *o)
{
    cx_free(o->uall);
    cx_result_destroy(&o->st);
    cx_session_destroy(&o->s);
}

static int colour_dist(const unsigned char *a, const unsigned char *b)
{
    return abs(a[0] - b[0]) + abs(a[1] - b[1]) + abs(a[2] - b[2]);
}

/* Is the image's colormap diverging? A signed field whose colour range
 * (the 'colour range' chunk, lo:hi) has values of both signs; a one-signed
 * field is drawn on a sequential map. */
static int img_diverging(const test_png *img, int field)
{
    const char *t = test_png_text(img, "colour range");
    double lo = 0, hi = 0;
    CX_CHECK(t && sscanf(t, "%lf:%lf", &lo, &hi) == 2);
    return cx_field_is_signed(field) && lo < 0 && hi > 0;
}

/* The colour bar, sampled up its middle, follows the colormap from its
 * bottom (t = 0) to its top (t = 1). */
static void check_bar(const test_png *img, int field)
{
    cx_render_layout l;
    cx_render_layout_get(img->w, img->h, &l);
    int bad = 0;
    for (int k = 0; k <= 10; k++) {
        double t = 0.04 + 0.92 * k / 10.0;
        int x = (int)(l.bar[0] + 0.5 * l.bar[2]);
        int y = (int)(l.bar[1] + (1 - t) * l.bar[3]);
        unsigned char want[3];
        cx_colormap(img_diverging(img, field), t, want);
        bad += colour_dist(test_png_px(img, x, y), want) > 24;
    }
    CX_CHECK(bad == 0);
}

/* The pixel of a deformed node. */
static const unsigned char *node_px(const test_png *img, const solved *o, const cx_render_opts *opt,
                                    int node, double scale)
{
    const cx_problem *p = cx_session_problem(o->s);
    double x[3], px[2];
    for (int k = 0; k < p->dim; k++)
        x[k] = p->mesh->x[p->dim * node + k] + scale * o->uall[p->dim * node + k];
    cx_render_project(o->st, opt, x, px, NULL);
    return test_png_px(img, (int)px[0], (int)px[1]);
}

static int nearest_node(const cx_mesh *m, const double *x)
{
    int best = 0;
    double bd = INFINITY;
    for (int i = 0; i < m->nnodes; i++) {
        double d2 = 0;
        for (int k = 0; k < m->dim; k++)
            d2 += (m->x[m->dim * i + k] - x[k]) * (m->x[m->dim * i + k] - x[k]);
        if (d2 < bd) {
            bd = d2;
            best = i;
        }
    }
    return best;
}

static int is_white(const unsigned char *c)
{
    return c[0] == 255 && c[1] == 255 && c[2] == 255;
}

static void test_hertz(void)
{
    solved o;
    solve_scene(&o, "hertz", 8);
    const cx_problem *p = cx_session_problem(o.s);
    double scale = cx_render_auto_scale(o.st);
    double inner[2] = {2.4, 4.8};
    int node = nearest_node(p->mesh, inner);
    double *val = cx_malloc(sizeof(double) * p->mesh->nnodes);
    test_png img;
    cx_render_opts opt;
    cx_render_opts_default(&opt);
    opt.width = W;
    opt.height = H;
    int draw_calls = -1;
    for (int f = 0; f < CX_FIELD_COUNT; f++) {
        opt.field = f;
        if (cx_field_check(f, 2, NULL) != CX_OK) {
            cx_diag d;
            CX_CHECK(cx_render_png(o.st, &opt, OUT, NULL, &d) == CX_EINVAL);
            CX_CHECK(strstr(d.msg, "only in 3D") != NULL);
            continue;
        }
        cx_render_timing t;
        if (fixture_render_read(o.st, &opt, OUT, &img, &t) != 0) {
            CX_CHECK(0);
            continue;
        }
        CX_CHECK(img.w == W && img.h == H);
        CX_CHECK(test_png_colours(&img) > 30);
        if (draw_calls < 0)
            draw_calls = t.draw_calls;
        CX_CHECK(t.draw_calls >= 1 && t.draw_calls <= 3);
        /* background above the arc, outside the disc; obstacle below y = 0 */
        double out[2] = {7.2, 1.6}, px[2];
        cx_render_project(o.st, &opt, out, px, NULL);
        CX_CHECK(is_white(test_png_px(&img, (int)px[0], (int)px[1])));
        double below[2] = {3.0, -0.2};
        cx_render_project(o.st, &opt, below, px, NULL);
        const unsigned char *c = test_png_px(&img, (int)px[0], (int)px[1]);
        /* the fill (219, 214, 204), its hatching (158, 148, 133) or a mix */
        CX_CHECK(c[0] >= 150 && c[0] <= 225 && c[0] > c[2] + 8 && c[1] > c[2]);
        if (f == CX_FIELD_STATUS) {
            /* the first contact point (the origin) touches, the last does not */
            const cx_iterate *it = cx_session_iterate(o.s);
            int m = p->contact.m;
            unsigned char want[3];
            cx_status_color(it->status[0], want);
            CX_CHECK(it->status[0] == CX_PT_CONTACT);
            CX_CHECK(colour_dist(node_px(&img, &o, &opt, p->contact.node[0], scale), want) < 30);
            cx_status_color(it->status[m - 1], want);
            CX_CHECK(it->status[m - 1] == CX_PT_FREE);
            CX_CHECK(colour_dist(node_px(&img, &o, &opt, p->contact.node[m - 1], scale), want) < 30);
        } else {
            check_bar(&img, f);
        }
        if (f != CX_FIELD_STATUS && f != CX_FIELD_PRESSURE) {
            /* inside the body: the colormap at the node's value */
            CX_CHECK_OK(cx_field_nodal(o.st, f, val, NULL));
            double lo = INFINITY, hi = -INFINITY;
            for (int i = 0; i < p->mesh->nnodes; i++) {
                lo = fmin(lo, val[i]);
                hi = fmax(hi, val[i]);
            }
            int sgn = img_diverging(&img, f);
            if (sgn) {
                hi = fmax(fabs(lo), fabs(hi));
                lo = -hi;
            } else if (hi <= 0) {   /* one-signed, negative: [min, 0] */
                hi = 0;
            } else {
                lo = fmin(lo, 0);
            }
            unsigned char want[3];
            cx_colormap(sgn, (val[node] - lo) / (hi - lo), want);
            int dist = colour_dist(node_px(&img, &o, &opt, node, scale), want);
            if (dist >= 45)
                fprintf(stderr, "field %s: node colour off by %d\n", cx_field_name(f), dist);
            CX_CHECK(dist < 45);
        }
        test_png_free(&img);
    }

    /* text chunks */
    opt.field = CX_FIELD_VON_MISES;
    CX_CHECK_OK(fixture_render_read(o.st, &opt, OUT, &img, NULL));
    const char *t;
    CX_CHECK((t = test_png_text(&img, "scene")) && strcmp(t, "hertz") == 0);
    CX_CHECK((t = test_png_text(&img, "level")) && strcmp(t, "8") == 0);
    CX_CHECK((t = test_png_text(&img, "method")) && strcmp(t, "ssn-tresca") == 0);
    CX_CHECK((t = test_png_text(&img, "friction")) && strcmp(t, "none") == 0);
    CX_CHECK((t = test_png_text(&img, "F")) && fabs(atof(t) - 0.3) < 1e-12);
    CX_CHECK((t = test_png_text(&img, "parameters")) && strncmp(t, "rho=", 4) == 0 &&
             fabs(atof(t + 4) - 1e-3) < 1e-15);
    CX_CHECK((t = test_png_text(&img, "kkt error")) && fabs(atof(t) - o.st->run.kkt) <= 1e-6 * o.st->run.kkt);
    CX_CHECK((t = test_png_text(&img, "Software")) && strncmp(t, "signorini ", 10) == 0);
    CX_CHECK((t = test_png_text(&img, "field")) && strcmp(t, "von-mises") == 0);
    test_png_free(&img);

    /* the same state twice: the same bytes */
    cx_diag d;
    CX_CHECK_OK(cx_render_png(o.st, &opt, "test_image_again.png", NULL, &d));
    CX_CHECK(test_files_equal(OUT, "test_image_again.png"));
    remove("test_image_again.png");

    /* a bad path: one line naming it, no file */
    CX_CHECK(cx_render_png(o.st, &opt, "no-such-dir/x.png", NULL, &d) == CX_EIO);
    CX_CHECK(strstr(d.msg, "no-such-dir/x.png") && !strchr(d.msg, '\n'));
    CX_CHECK(access("no-such-dir", F_OK) != 0);
    /* bad options */
    opt.width = 10;
    CX_CHECK(cx_render_png(o.st, &opt, OUT, NULL, &d) == CX_EINVAL);
    opt.width = W;
    opt.view = CX_VIEW_CONTACT;
    CX_CHECK(cx_render_png(o.st, &opt, OUT, NULL, &d) == CX_EINVAL);
    cx_free(val);
    solved_free(&o);
}

static void test_block3d(void)
{
    solved o;
    solve_scene(&o, "block3d", 2);
    const cx_problem *p = cx_session_problem(o.s);
    double scale = cx_render_auto_scale(o.st);
    test_png img;
    cx_render_opts opt;
    cx_render_opts_default(&opt);
    opt.width = W;
    opt.height = H;
    opt.edges = 1;
    opt.view = CX_VIEW_ABOVE;   /* the default is from below (the contact face) */
    double top[3] = {0.5, 0.5, 0.5};
    int node = nearest_node(p->mesh, top);
    for (int f = 0; f < CX_FIELD_COUNT; f++) {
        opt.field = f;
        if (fixture_render_read(o.st, &opt, OUT, &img, NULL) != 0) {
            CX_CHECK(0);
            continue;
        }
        CX_CHECK(test_png_colours(&img) > 20);
        if (f != CX_FIELD_STATUS)
            check_bar(&img, f);
        /* the top of the body is drawn (lit, so not the exact colormap) */
        const unsigned char *c = node_px(&img, &o, &opt, node, scale);
        CX_CHECK(!is_white(c));
        /* the plane patch beside the body: the obstacle's brown */
        double side[3] = {1.6, -0.3, 0.0}, px[2];
        cx_render_project(o.st, &opt, side, px, NULL);
        c = test_png_px(&img, (int)px[0], (int)px[1]);
        CX_CHECK(!is_white(c) && c[0] > c[2] + 10);
        test_png_free(&img);
    }
    /* the contact faces on their own: the uniform pressure 10 fills them */
    opt.view = CX_VIEW_CONTACT;
    opt.field = CX_FIELD_PRESSURE;
    CX_CHECK_OK(fixture_render_read(o.st, &opt, OUT, &img, NULL));
    double mid[3] = {0.5, 0.5, 0.0}, px[2];
    cx_render_project(o.st, &opt, mid, px, NULL);
    unsigned char want[3];
    cx_colormap(0, 1.0, want);   /* range [0, max]: the uniform value is the top */
    CX_CHECK(colour_dist(test_png_px(&img, (int)px[0], (int)px[1]), want) < 40);
    test_png_free(&img);
    solved_free(&o);
}

/* Six separate unit squares (2 x 2 quad4 cells each, bodies 0..5) on a
 * rigid line, a linear displacement ux = 0.01 (b + 1) x: one draw call for
 * all bodies, and each body's colour where it lies. */
static void test_multibody(void)
{
    enum { NB = 6, NPB = 9, EPB = 4 };
    cx_mesh *m = CX_NEW(cx_mesh, 1);
    m->dim = 2;
    m->nnodes = NB * NPB;
    m->x = CX_NEW(double, 2 * NB * NPB);
    m->etype = CX_EL_QUAD4;
    m->npe = 4;
    m->nelems = NB * EPB;
    m->conn = CX_NEW(int, 4 * NB * EPB);
    m->nbodies = NB;
    m->body = CX_NEW(int, NB * EPB);
    m->nbounds = 1;
    m->bounds = CX_NEW(cx_boundary, 1);
    snprintf(m->bounds[0].name, sizeof m->bounds[0].name, "bottom");
    m->bounds[0].npf = 2;
    m->bounds[0].nfacets = 2 * NB;
    m->bounds[0].facets = CX_NEW(int, 4 * NB);
    for (int b = 0; b < NB; b++) {
        int n0 = b * NPB;
        for (int j = 0; j < 3; j++)
            for (int i = 0; i < 3; i++) {
                m->x[2 * (n0 + 3 * j + i)] = 1.5 * b + 0.5 * i;
                m->x[2 * (n0 + 3 * j + i) + 1] = 0.01 + 0.5 * j;
            }
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++) {
                int e = b * EPB + 2 * j + i, a = n0 + 3 * j + i;
                int q[4] = {a, a + 1, a + 4, a + 3};
                memcpy(m->conn + 4 * e, q, sizeof q);
                m->body[e] = b;
            }
        for (int i = 0; i < 2; i++) {
            m->bounds[0].facets[4 * b + 2 * i] = n0 + i;
            m->bounds[0].facets[4 * b + 2 * i + 1] = n0 + i + 1;
        }
    }
    cx_material *mats = CX_NEW(cx_material, NB);
    for (int b = 0; b < NB; b++)
        mats[b] = (cx_material){1000.0 * (b + 1), 0.3, CX_PLANE_STRAIN};
    cx_obstacle ob = {CX_OBST_PLANE, {0, 0, 0}, {0, 1, 0}, 0, {0, 0, 0}};
    cx_diag d;
    cx_contact_set cs;
    memset(&cs, 0, sizeof cs);
    cx_dofmap map;
    cx_csc K;
    memset(&K, 0, sizeof K);
    double *f = CX_NEW(double, 2 * NB * NPB);
    CX_CHECK_OK(cx_contact_from_obstacle(&cs, m, &m->bounds[0], &ob, &d));
    CX_CHECK_OK(cx_dofmap_init(&map, 2 * NB * NPB));
    CX_CHECK_OK(cx_dofmap_finish(&map));
    CX_CHECK_OK(cx_fem_assemble_stiffness(m, mats, &K, &d));
    cx_problem *p = NULL;
    CX_CHECK_OK(cx_problem_create(&p, &m, &mats, &map, &cs, &K, f, &d));
    cx_csc_clear(&K);
    cx_free(f);
    if (!p)
        return;
    double *u = CX_NEW(double, p->n), *lN = CX_NEW(double, p->m);
    for (int k = 0; k < p->mesh->nnodes; k++)
        u[2 * k] = 0.01 * (p->mesh->body ? p->mesh->body[k / NPB * EPB] + 1 : 1) * p->mesh->x[2 * k];
    cx_result *st = NULL;
    CX_CHECK_OK(cx_result_create(&st, p, NULL, u, lN, NULL, NULL, &d));
    st->has_obstacle = 1;
    st->obstacle = ob;
    snprintf(st->run.scene, sizeof st->run.scene, "six blocks");
    snprintf(st->run.title, sizeof st->run.title, "six blocks");
    snprintf(st->run.method, sizeof st->run.method, "none");
    st->run.level = 1;
    cx_render_opts opt;
    cx_render_opts_default(&opt);
    opt.width = W;
    opt.height = H;
    opt.field = CX_FIELD_UX;
    opt.scale = 1.0;
    opt.edges = 1;
    test_png img;
    cx_render_timing t;
    CX_CHECK_OK(fixture_render_read(st, &opt, OUT, &img, &t));
    CX_CHECK(t.draw_calls == 2);   /* all six bodies, then all their edges */
    double umax = 0;
    for (int k = 0; k < p->n; k++)
        umax = fmax(umax, fabs(u[k]));
    for (int b = 0; b < NB; b++) {
        /* the centre node of body b (no edge passes through a cell centre:
         * sample a quarter cell off it) */
        int c = b * NPB + 4;
        double x[2] = {p->mesh->x[2 * c] + 0.125 + u[2 * c], p->mesh->x[2 * c + 1] + 0.125}, px[2];
        cx_render_project(st, &opt, x, px, NULL);
        unsigned char want[3];
        double v = 0.01 * (b + 1) * (p->mesh->x[2 * c] + 0.125);
        cx_colormap(0, v / umax, want);   /* ux > 0 everywhere: sequential, [0, max] */
        CX_CHECK(colour_dist(test_png_px(&img, (int)px[0], (int)px[1]), want) < 40);
    }
    test_png_free(&img);

    /* every 2D field renders; von Mises analytically: body b has strain
     * exx = 0.01 (b + 1) and E = 1000 (b + 1), so its stress is (b + 1)^2
     * times body 0's, and its colour sits at t = ((b + 1) / 6)^2 */
    for (int fld = 0; fld < CX_FIELD_COUNT; fld++) {
        if (cx_field_check(fld, 2, NULL) != CX_OK)
            continue;
        opt.field = fld;
        if (fixture_render_read(st, &opt, OUT, &img, &t) != 0) {
            CX_CHECK(0);
            continue;
        }
        CX_CHECK(test_png_colours(&img) > 10);
        CX_CHECK(t.draw_calls == 2);
        if (fld != CX_FIELD_STATUS)
            check_bar(&img, fld);
        for (int b = 0; b < NB && fld == CX_FIELD_VON_MISES; b++) {
            int c = b * NPB + 4;
            double x[2] = {p->mesh->x[2 * c] + 0.125 + u[2 * c], p->mesh->x[2 * c + 1] + 0.125}, px[2];
            cx_render_project(st, &opt, x, px, NULL);
            unsigned char want[3];
            cx_colormap(0, (b + 1) * (b + 1) / 36.0, want);
            CX_CHECK(colour_dist(test_png_px(&img, (int)px[0], (int)px[1]), want) < 30);
        }
        test_png_free(&img);
    }
    cx_free(u);
    cx_free(lN);
    cx_result_destroy(&st);
    cx_problem_destroy(&p);
}

int main(void)
{
    test_hertz();
    test_block3d();
    test_multibody();
    if (!getenv("CX_TEST_KEEP"))   /* keep the last image (six blocks) to look at */
        remove(OUT);
    return check_finish("render_image");
}
