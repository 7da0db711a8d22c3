/* SPDX-License-Identifier: GPL-3.0-or-later */
/* render/render_impl.h (internal): the pieces of an image — geometry
 * (vertex arrays), the camera, the GL pass and the cairo overlays. */
#ifndef CX_RENDER_IMPL_H
#define CX_RENDER_IMPL_H

#include "render/render.h"

typedef struct _cairo cairo_t;

/* A vertex: position, normal, scalar value. */
#define CX_RENDER_VFLOATS 7

typedef struct cx_render_array {
    float *v;       /* CX_RENDER_VFLOATS per vertex */
    long n, cap;    /* vertices */
} cx_render_array;

int cx_render_array_push(cx_render_array *a, const double x[3], const double nrm[3], double value);
void cx_render_array_clear(cx_render_array *a);

/* Everything one image needs, in world coordinates (z = 0 in 2D). */
typedef struct cx_render_scene {
    cx_result *r;        /* what is drawn (borrowed) */
    /* every rigid obstacle of r as drawn (a ring's two plates, a block
     * between a plane and a ball): a plane moved by (1 - s) g along its
     * normal, g the uniform initial gap of the points against it */
    int nobst;
    cx_obstacle obstacles[CX_RESULT_MAX_OBSTACLES];
    double obstacle_gap;           /* the first's g (a plane's; else 0) */
    int contact_inexact;           /* points in contact drawn off the obstacle by the scale */
    const cx_render_opts *o;
    int dim;
    const double *uall;  /* dim * nnodes: r->u */
    double *x0, *xd;     /* 3 * nnodes: undeformed, deformed (scaled) */
    double *val;         /* nnodes: the field, or NULL (status: codes) */
    double scale;        /* displacement magnification */
    double umax;         /* largest |u| */
    double lo, hi;       /* colour range */
    int colored;         /* body coloured by val (else flat grey) */
    cx_render_array tris;       /* body (or contact faces) */
    cx_render_array overlay;    /* 3D: contact faces coloured on the body */
    cx_render_array lines;      /* edges */
    cx_render_array obst;       /* 3D obstacle triangles: first those drawn (obst_drawn vertices),
                                   then the ghosts' (framed, outlined by overlay.c) */
    long obst_drawn;
    long obst_range[CX_RESULT_MAX_OBSTACLES][2];   /* obstacle j's vertices in obst: [from, to) */
    int *bedges;         /* 2D boundary edges: 3 node ids (a, mid or -1, b) */
    int nbedges;
    int *feat0;          /* 3D: feature edges of the undeformed surface (node pairs) */
    int nfeat0;
    cx_render_array feature;    /* 3D: feature edges of the deformed surface */
    int diverging;       /* the colormap is diverging (a signed field of both signs) */
    int from_below;      /* 3D body view: the eye is below the xy plane */
    /* 3D body view: obstacle j seen from its side (the eye beyond the
     * contact faces against it) is drawn as its outline (overlay.c), not
     * as a surface hiding them */
    int ghost[CX_RESULT_MAX_OBSTACLES];
    double az, el;       /* 3D body view: the camera (degrees) */
    /* --mirror: the copies across the symmetry planes (1, 2, 4 or 8); copy
     * c reflects across plane j when bit j of c is set; the overlays are
     * drawn once per copy, with copy set (cx_render_scene_project reflects) */
    int nsym, sym_axis[3];
    double sym_at[3];
    int ncopies, copy;
    double size;         /* the undeformed body's bounding-box diagonal */
    /* camera: world -> view rotation R (rows: right, up, towards the eye),
     * then view -> pixel: px = cx + k (R x)_0, py = cy - k (R x)_1 */
    double R[9];
    double k, cx, cy, zmin, zmax;
    int w, h;
} cx_render_scene;

/* geom.c: vertex arrays of the body, its edges and the obstacle. */
int cx_render_geometry(cx_render_scene *sc);
/* Do undeformed nodes a and b both lie on one symmetry plane of --mirror? */
int cx_render_on_plane(const cx_render_scene *sc, int a, int b);
/* camera.c: the view rotation (before the geometry, which needs it for
 * nothing but is framed by it), then the fit of the body (and obstacle;
 * with crop_contact the contact zone) into the layout's drawing area. */
void cx_render_camera_orient(cx_render_scene *sc);
void cx_render_camera(cx_render_scene *sc);
/* The rectangle the drawing is fitted into (x, y, w, h): the layout's
 * area, less the contact view's room for axes; --crop contact clips to it. */
void cx_render_draw_area(const cx_render_scene *sc, double area[4]);
/* x reflected as copy c (--mirror) into y (may be x). */
void cx_render_mirror(const cx_render_scene *sc, int c, const double x[3], double y[3]);
/* The pixel of world point x (reflected as copy sc->copy first). */
void cx_render_scene_project(const cx_render_scene *sc, const double x[3], double px[2]);
/* The GL matrices of the camera: column-major mvp, row-major 3x3 rotation. */
void cx_render_camera_gl(const cx_render_scene *sc, float mvp[16], float rot[9]);
/* gldraw.c: draw the vertex arrays with OpenGL into argb (cairo ARGB32,
 * premultiplied, transparent background), timing context creation apart. */
int cx_render_gl_draw(const cx_render_scene *sc, unsigned char *argb, int stride, double *t_context,
               int *draw_calls, cx_diag *d);
/* overlay.c: what goes under the GL image (the 2D obstacle) and over it
 * (title, colour bar, outlines, markers, notes). */
void cx_render_underlay(const cx_render_scene *sc, cairo_t *cr);
/* The subtitle (the run record) of the image of r with o, as 0 (no title),
 * 1 or 2 lines (overlay.c); the second line is CX_RENDER_SUBTITLE_LINE
 * fonts below the first, and the layout moves the drawing down by that. */
#define CX_RENDER_SUBTITLE_LINE 0.95
int cx_render_subtitle(const cx_result *r, const cx_render_opts *o, char *l1, char *l2, size_t len);
/* The title as 0, 1 or 2 lines (cut at a space), the second
 * CX_RENDER_TITLE_LINE fonts below the first. */
#define CX_RENDER_TITLE_LINE 1.45
int cx_render_title_split(const cx_result *r, const cx_render_opts *o, char *t1, char *t2, size_t len);
/* Pixels the title block takes beyond one line of each (0: none wraps). */
double cx_render_title_room(const cx_result *r, const cx_render_opts *o);
void cx_render_overlay(const cx_render_scene *sc, cairo_t *cr);

#endif
