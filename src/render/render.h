/* SPDX-License-Identifier: GPL-3.0-or-later */
/* render/: images of a solution snapshot (cx_result, out/result.h): PNG
 * through offscreen Mesa, with text, colour bar and markers drawn by
 * cairo; and line plots (render/plot.h). Files are written through
 * out/outfile.h. VTU files need no GL: out/out.h.
 *
 * An image shows one field on the deformed body: 2D meshes flat with the
 * displacement magnified (auto scale: the largest displacement is drawn as
 * 7 % of the body size, stated on the image), the undeformed outline faint,
 * the rigid obstacle and the contact points coloured by status, the
 * scene's supports; 3D bodies as their softly lit surface (colours within
 * 12 % of the colour bar's, dark feature edges) from the side of their
 * contact faces (cx_view), with the undeformed shape as a dashed wireframe
 * and an axis triad, or with view CX_VIEW_CONTACT only the contact faces
 * seen from the obstacle, with axes. --crop contact frames the points in
 * contact; --mirror draws a half or quarter model whole across the
 * scene's symmetry planes. All bodies of a mesh go into one vertex buffer:
 * one draw call per field whatever the number of bodies (copies of
 * --mirror included).
 *
 * The OpenGL context (OSMesa, render/glctx.c) is created inside
 * cx_render_png() and destroyed before it returns; nothing is created when
 * only plots are written. Shaders are read at run time from the data
 * directories of base/data.h ($SIGNORINI_SHADERS, $SIGNORINI_DATA, the
 * source tree for the build tree, share/signorini beside the installed
 * library), else from the copies compiled in. The same result rendered
 * twice gives the same bytes. */
#ifndef CX_RENDER_H
#define CX_RENDER_H

#include "base/base.h"
#include "out/out.h"
#include "render/plot.h"

/* ---- fields -------------------------------------------------------------- */

typedef enum cx_field {
    CX_FIELD_VON_MISES,   /* von Mises stress (magnitude colormap) */
    CX_FIELD_SXX,         /* stress components (diverging, symmetric about 0) */
    CX_FIELD_SYY,
    CX_FIELD_SZZ,         /* 3D only */
    CX_FIELD_SYZ,         /* 3D only */
    CX_FIELD_SXZ,         /* 3D only */
    CX_FIELD_SXY,
    CX_FIELD_UMAG,        /* |u| (magnitude) */
    CX_FIELD_UX,          /* displacement components (diverging) */
    CX_FIELD_UY,
    CX_FIELD_UZ,          /* 3D only */
    CX_FIELD_PRESSURE,    /* contact pressure lN / weight on the contact boundary */
    CX_FIELD_STATUS,      /* contact status markers (no colour bar) */
    CX_FIELD_COUNT
} cx_field;

const char *cx_field_name(int f);         /* "von-mises", "sxx", ..., "status" */
const char *cx_field_label(int f);        /* "von Mises stress", ... */
int cx_field_from_name(const char *name); /* -1 if unknown */
/* The label of a quantity with the run's declared units (the scene's
 * [units]): "what [MPa]" (stress: a stress unit, else a length unit), or
 * "what (units of the scene)" when none is declared. Into buf; returns it. */
char *cx_quantity_label(const cx_run_record *run, const char *what, int stress, char *buf,
                        size_t len);
/* The colour bar / axis label of field f: "von Mises stress σ_vM [MPa]",
 * "displacement u_x (units of the scene)"; status: its name alone. */
char *cx_field_axis_label(const cx_run_record *run, int f, char *buf, size_t len);
int cx_field_is_stress(int f);
int cx_field_is_signed(int f);            /* diverging colormap */
/* CX_OK if the field exists in this dimension, else CX_EINVAL with
 * "--field szz: only in 3D". */
int cx_field_check(int f, int dim, cx_diag *d);

/* Nodal values of field f of r (mesh->nnodes values; the pressure is 0
 * away from the contact points; status gives the cx_point_status code at
 * contact nodes, -1 elsewhere). Stresses come from cx_result_stress
 * (computed once, for stress fields only). CX_ENOMEM, CX_ENUMERIC. */
int cx_field_nodal(cx_result *r, int f, double *val, cx_diag *d);

/* ---- colormaps ---------------------------------------------------------- */

/* Colour of t in [0, 1] (clamped): perceptual (viridis-like) for
 * magnitudes, diverging blue-grey-red for signed fields. rgb in [0, 255]. */
void cx_colormap(int diverging, double t, unsigned char rgb[3]);
/* Named colormaps (--cmap); CX_CMAP_AUTO: viridis for magnitudes,
 * coolwarm for signed fields. */
typedef enum cx_cmap {
    CX_CMAP_AUTO = -1,
    CX_CMAP_VIRIDIS,
    CX_CMAP_CIVIDIS,
    CX_CMAP_MAGMA,
    CX_CMAP_COOLWARM,
    CX_CMAP_GRAY,
    CX_CMAP_COUNT
} cx_cmap;
const char *cx_cmap_name(int cmap);          /* "viridis", ...; "auto" */
int cx_cmap_from_name(const char *name);     /* -2 if unknown ("auto": CX_CMAP_AUTO) */
/* Colour of t in [0, 1] (clamped) in colormap cmap; AUTO as cx_colormap(diverging). */
void cx_colormap_named(int cmap, int diverging, double t, unsigned char rgb[3]);
/* The marker colour of a contact status (cx_point_status). */
void cx_status_color(int status, unsigned char rgb[3]);

/* ---- images ------------------------------------------------------------- */

/* 3D: CX_VIEW_BODY is the body seen from the side of its contact faces
 * (from below, az 35 el -35, when they face down, as on halfball, block3d
 * and prism; else from above, az 35 el 30); BELOW and ABOVE force the side;
 * CONTACT shows the contact faces alone, seen from the obstacle, with axes. */
typedef enum cx_view { CX_VIEW_BODY, CX_VIEW_CONTACT, CX_VIEW_BELOW, CX_VIEW_ABOVE } cx_view;

typedef struct cx_render_opts {
    int width, height;            /* pixels (default 1200 x 900) */
    int field;                    /* cx_field (default von Mises) */
    double scale;                 /* displacement magnification, <= 0: auto */
    int edges;                    /* draw mesh edges */
    int view;                     /* cx_view */
    int msaa;                     /* 4 (default) or 0 */
    double font_scale;            /* text size factor (default 1; 0.25..4) */
    int cmap;                     /* cx_cmap (default CX_CMAP_AUTO) */
    int has_range;                /* colour range fixed to [range_lo, range_hi] */
    double range_lo, range_hi;    /* (so that several figures share one scale) */
    int no_title;                 /* no title lines (a caption says it) */
    int band_always;              /* an animation's frames: the band above the
                                     drawing in every frame (start, running,
                                     the outcome), so that nothing jumps */
    const char *title;            /* the title instead of the scene's (NULL: the scene's) */
    /* camera and framing (3D views, crop, mirror) */
    int has_camera;               /* 3D: look from azimuth cam_az, elevation cam_el */
    double cam_az, cam_el;        /* degrees: az from -y towards +x, el above the xy plane */
    int crop_contact;             /* frame the contact zone (points in contact) only */
    int mirror;                   /* draw the full body across the scene's symmetry planes */
    const cx_scene *scene;        /* its supports (2D rollers) and symmetry planes; NULL: none */
    int log;                      /* logarithmic colour scale (magnitudes; with range: 0 < lo) */
} cx_render_opts;

void cx_render_opts_default(cx_render_opts *o);

/* Seconds spent in each stage of the last cx_render_png(). */
typedef struct cx_render_timing {
    double context;   /* OSMesa context + shaders */
    double fields;    /* field values, geometry, buffers */
    double draw;      /* GL drawing until glFinish, read back */
    double text;      /* cairo overlays */
    double png;       /* PNG encoding and writing */
    int draw_calls;   /* glDrawArrays calls (independent of the number of bodies) */
} cx_render_timing;

/* The automatic displacement scale: largest displacement drawn as 7 % of
 * the body's bounding-box diagonal (1 when u is zero). */
double cx_render_auto_scale(const cx_result *r);

/* Where the overlays go in a w x h image (pixels, top-left origin), so that
 * tests can sample them: the drawing area and the colour bar (value lo at
 * the bottom, hi at the top). */
typedef struct cx_render_layout {
    double area[4];   /* x, y, w, h of the body's drawing area */
    double bar[4];    /* x, y, w, h of the colour bar gradient */
    double banner[4]; /* x, y, w, h of the "not converged" banner (h = 0: none) */
    double font;      /* tick-label font size (pixels): cx_render_font_px */
} cx_render_layout;
/* The tick-label font size of a w x h figure (images and plots): 2.2 % of
 * the width, matplotlib's default ratio (10 pt in a 6.4 inch figure), so
 * that it stays legible when the figure is printed a column wide; at most
 * 4.5 % of the height; times font_scale. Titles are 1.2 times larger,
 * notes 0.8 times. */
double cx_render_font_px(int w, int h, double font_scale);
/* The layout at font scale 1 for a converged run. */
void cx_render_layout_get(int w, int h, cx_render_layout *l);
/* Every dimension in proportion to the font, at font_scale. */
void cx_render_layout_font(int w, int h, double font_scale, cx_render_layout *l);
/* The layout of an image of a run: with the banner above the drawing
 * area (which moves down to make room) when cx_render_unconverged(run). */
void cx_render_layout_run(const cx_run_record *run, int w, int h, cx_render_layout *l);
/* The layout of the image that cx_render_png draws of r with o. */
void cx_render_layout_image(const cx_result *r, const cx_render_opts *o, cx_render_layout *l);
/* Non-zero if the image of this run must say that it did not converge:
 * it ended without converging, or it is still running (a snapshot), or
 * it is a run's start (iterating, no iterations, an infinite kkt error:
 * an animation's first frame, whose band says "start (iteration 0)"). A
 * result without a run (no iterations, reason 0, finite error) is not
 * flagged. */
int cx_render_unconverged(const cx_run_record *run);

/* The pixel (top-left origin) where the world point x (dim coordinates,
 * in the drawn frame: deformed points are x + scale u) appears in the image
 * that cx_render_png would draw with these options. No GL is involved. */
int cx_render_project(cx_result *r, const cx_render_opts *o, const double *x, double px[2],
                      cx_diag *d);

/* Draw r (the image shows its obstacle if it has one, the title and run
 * record from r->run) and write a PNG through out/outfile.h, with tEXt
 * chunks scene, level, method, friction, F, parameters, kkt error, field,
 * scale and Software. t may be NULL. CX_EINVAL (options, field not in this
 * dimension), CX_EIO (path: one line, no file left), CX_EEXTERNAL (no GL
 * context, shader missing or not compiling: the message says which). */
int cx_render_png(cx_result *r, const cx_render_opts *o, const char *path, cx_render_timing *t,
                  cx_diag *d);

#endif
