/* SPDX-License-Identifier: GPL-3.0-or-later */
/* scene/: scene files (scenes/NAME.ini, read with inih) and the building of a
 * problem from a scene at a mesh level. Every key is checked against a table
 * of the section's keys; errors are one line "file:line: key 'E': expected a
 * positive number" (CX_EINVAL). Unknown sections and keys are errors.
 *
 * Scene ids are file names without ".ini" found in the scene directories
 * of base/data.h: $SIGNORINI_SCENES (one directory, or several separated by
 * ':'), $SIGNORINI_DATA/scenes, then the source tree's scenes/ for the
 * build tree's code or share/signorini/scenes beside the installed library
 * or program. No scene anywhere is an error of cx_scene_list. */
#ifndef CX_SCENE_H
#define CX_SCENE_H

#include "base/base.h"
#include "mesh/mesh.h"
#include "fem/fem.h"
#include "contact/contact.h"
#include "solve/solve.h"

#define CX_SCENE_MAX_LOADS 8
#define CX_SCENE_MAX_METHODS 16
#define CX_SCENE_NAMELEN 32
#define CX_SCENE_ALL_LAWS 0x7u   /* cx_scene.laws: none, tresca and coulomb */

typedef struct cx_scene_traction {
    char boundary[CX_SCENE_NAMELEN];
    char name[CX_SCENE_NAMELEN];   /* NAME of [traction NAME] */
    int line;                      /* of its header */
    cx_traction t;
} cx_scene_traction;

typedef struct cx_scene_support {
    char boundary[CX_SCENE_NAMELEN];
    unsigned comps;        /* bit c set: component c prescribed */
    double value[3];       /* prescribed displacement per component */
    char name[CX_SCENE_NAMELEN];   /* NAME of [support NAME] */
    int line;                      /* of its header */
} cx_scene_support;

typedef enum cx_scene_generator {
    CX_GEN_RECTANGLE,
    CX_GEN_HERTZ,
    CX_GEN_BRICK,
    CX_GEN_TWOBLOCKS     /* two stacked rectangles, two bodies (paper 000) */,
    CX_GEN_MASONRY     /* paper 003: unit square of bodies, level = courses */,
    CX_GEN_FILE        /* [mesh] file = NAME.geo | NAME.msh, read through Gmsh */
} cx_scene_generator;

/* What a scene names in a Gmsh file's physical groups, checked against the
 * mesh when it is built: a boundary (dimension dim - 1), a region (dim) or
 * a point (0). */
typedef enum cx_scene_ref_kind {
    CX_REF_BOUNDARY,
    CX_REF_REGION,
    CX_REF_POINT
} cx_scene_ref_kind;

#define CX_SCENE_MAX_REFS 64
typedef struct cx_scene_ref {
    char name[CX_SCENE_NAMELEN];
    char key[16];                  /* the key that names it */
    int line;                      /* of that key */
    cx_scene_ref_kind kind;
} cx_scene_ref;

/* [material NAME] with region = GROUP: a region's own material and body
 * force (Gmsh meshes). The unnamed [material] covers the rest. */
typedef struct cx_scene_material {
    char name[CX_SCENE_NAMELEN];
    char region[CX_SCENE_NAMELEN];
    int line;
    cx_material mat;
    double body_force[3];
} cx_scene_material;

/* [pressure NAME]: p normal to a boundary (positive pushes into the body). */
typedef struct cx_scene_pressure {
    char name[CX_SCENE_NAMELEN];
    char boundary[CX_SCENE_NAMELEN];
    int line;
    double p;
} cx_scene_pressure;

/* [force NAME]: a force on a physical point (split evenly if the group
 * holds several nodes). */
typedef struct cx_scene_force {
    char name[CX_SCENE_NAMELEN];
    char point[CX_SCENE_NAMELEN];
    int line;
    double F[3];
} cx_scene_force;

/* [contact] or [contact NAME]: a rigid obstacle against a boundary, or a
 * 2D pair of bodies (master set). Each has its own F and slip bound. */
typedef struct cx_scene_contact {
    char name[CX_SCENE_NAMELEN];   /* "" for [contact] */
    char boundary[CX_SCENE_NAMELEN];
    char master[CX_SCENE_NAMELEN]; /* "" = obstacle */
    int line;
    cx_obstacle obstacle;
    double slip_bound;
    double F;
} cx_scene_contact;

/* How cells grow with the mesh level (cx_scene_cells). */
typedef enum cx_level_rule {
    CX_LEVEL_LINEAR,   /* level L: L * cells */
    CX_LEVEL_SQRT2     /* level L: ceil(cells * 2^(L/2)), paper 001's rule */
} cx_level_rule;

typedef struct cx_scene {
    char path[512];
    char id[CX_SCENE_NAMELEN];
    char title[128];
    int dim;
    /* [scene] symmetry = x=0 y=0: planes axis = at across which the model
     * is a half or a quarter of the body (render --mirror) */
    int nsymmetry;
    int symmetry_axis[3];
    double symmetry_at[3];

    /* [mesh] */
    cx_scene_generator generator;
    cx_elem_type element;
    double lo[3], hi[3];          /* rectangle / brick extents */
    double radius;                /* hertz */
    int cells[3];                 /* cells per level step along x, y, z */
    int level;                    /* default level */
    int level_max;                /* largest level allowed */
    double interface;             /* twoblocks: y of the interface (lo < it < hi) */
    int cells_lower[3];           /* twoblocks: cells of the lower body per level step */
    cx_level_rule level_rule;     /* how cells grow with the level */
    cx_bond bond;                 /* masonry: stack, running or laminae */
    char mesh_file[512];          /* file: the path (resolved against the scene's folder) */
    char mesh_file_key[512];      /* file: as the scene gives it, for messages */
    double mesh_size;             /* file: h0 (0: the file's own sizes), size h0 / level */
    int file_element;             /* file: the element type asked for, -1 the file's */
    int line_file;                /* file: the line of key 'file' */
    double gap_h;                 /* masonry: settlement gap g as a fraction of H */

    /* [material] */
    cx_material mat;
    double body_force[3];

    /* [traction NAME] and [support NAME] sections */
    int ntractions;
    cx_scene_traction tractions[CX_SCENE_MAX_LOADS];
    int nsupports;
    cx_scene_support supports[CX_SCENE_MAX_LOADS];

    /* [material NAME] (regions), [pressure NAME], [force NAME] */
    int nmaterials;
    cx_scene_material materials[CX_SCENE_MAX_LOADS];
    int npressures;
    cx_scene_pressure pressures[CX_SCENE_MAX_LOADS];
    int nforces;
    cx_scene_force forces[CX_SCENE_MAX_LOADS];
    /* the physical groups named (file meshes) */
    int nrefs;
    cx_scene_ref refs[CX_SCENE_MAX_REFS];

    /* [contact] and [contact NAME]: every contact in contacts[]; the fields
     * below repeat the first one (its friction law is the scene's) */
    int ncontacts;
    cx_scene_contact contacts[CX_SCENE_MAX_LOADS];
    char contact_boundary[CX_SCENE_NAMELEN];
    char contact_master[CX_SCENE_NAMELEN];  /* two bodies: the master boundary ("" = obstacle) */
    cx_obstacle obstacle;
    cx_friction friction;         /* default law */
    double slip_bound;            /* Tresca bound (traction) */
    double F;                     /* Coulomb coefficient */
    unsigned laws;                /* the laws it allows: bit (1u << cx_friction) each */

    /* [methods] */
    int nmethods;
    char methods[CX_SCENE_MAX_METHODS][CX_SCENE_NAMELEN];  /* suited, first = default */

    /* [units] (optional): unit names for labels, "" = not declared */
    char unit_length[16];         /* e.g. "mm" */
    char unit_stress[16];         /* e.g. "MPa" (stresses, tractions, E) */

    /* [hertz] analytical reference: 2D load per unit length P on the cylinder of
     * radius R; 3D load P on the whole ball of radius R */
    int has_hertz;
    double hertz_P, hertz_R;

    /* the lines of the [mesh], [material] and [contact] headers, for the
     * messages of cx_scene_build */
    int line_mesh, line_material, line_contact;
} cx_scene;

/* Read and check a scene file: a regular file or a pipe of at most 1 MiB
 * (CX_EINVAL beyond), read whole. CX_EIO if it cannot be read (or is a
 * device or a directory), CX_EINVAL with "file:line: ..." for any bad
 * content (the first error only): NUL bytes and control characters but
 * tabs, junk after a section header, unknown keys, values out of range
 * (reals within +-1e30, positive scales from 1e-30). Sets inih's option
 * globals (Debian): not to be called from two threads at once. */
int cx_scene_load(cx_scene *s, const char *path, cx_diag *d);

/* The same for a scene held in memory: len bytes of text (not
 * NUL-terminated; a NUL among them is refused), named path in messages. */
int cx_scene_parse(cx_scene *s, const char *path, const char *text, size_t len, cx_diag *d);

/* Resolve a scene id (or a path to an .ini) to a path; CX_EINVAL
 * "unknown scene 'x' (see 'signorini list')". */
int cx_scene_resolve(const char *id_or_path, char *path, size_t len, cx_diag *d);

/* Resolve and load: a scene id or a path to an .ini. */
int cx_scene_open(const char *id_or_path, cx_scene *s, cx_diag *d);

/* The ids of all scenes found (sorted, distinct); *ids is an array of
 * CX_SCENE_NAMELEN strings (cx_free). */
int cx_scene_list(char (**ids)[CX_SCENE_NAMELEN], int *count, cx_diag *d);

/* Mesh cell counts of a level: level_rule linear: L * cells; sqrt2:
 * ceil(cells * 2^(L/2)) (exact for even L). */
void cx_scene_cells(const cx_scene *s, int level, int cells[3]);
/* twoblocks: the lower body's cell counts of a level (level x cells_lower). */
void cx_scene_cells_lower(const cx_scene *s, int level, int cells[3]);

/* The obstacle the solver uses at a level (level <= 0: the scene's
 * default): the scene's, except masonry's plane lowered by the settlement
 * gap g = gap_h H (H = 1 / courses). */
void cx_scene_obstacle(const cx_scene *s, int level, cx_obstacle *ob);
/* Every rigid obstacle of the scene's contacts (those without a master
 * boundary), in the order of its sections, where the solver has them (as
 * cx_scene_obstacle): at most max of them in ob; returns their count. */
int cx_scene_obstacles(const cx_scene *s, int level, cx_obstacle *ob, int max);

/* Generate the mesh, assemble, apply supports and loads, build contact:
 * the problem at a level (level <= 0: the scene's default), and beside it
 * the scene's friction defaults in *fr (may be NULL; its law, slip bound
 * and F, no per-point values), for cx_session_set_friction. The contact
 * points are those with a free normal dof (p->contact.nclamped counts the
 * others). A NaN or Inf in the mesh, K, f, the gap or the rows is
 * CX_EINVAL "file:line: section [...]: ..." naming the section it comes
 * from (the loader's ranges keep a scene's values from getting there). */
int cx_scene_build(const cx_scene *s, int level, cx_problem **p, cx_friction_state *fr,
                   cx_diag *d);

/* cx_scene_build with flags: CX_SCENE_BUILD_NO_K builds no serial K, for
 * a caller that assembles its own (the PETSc backend, from p->mesh): p->K
 * is then empty (0 x 0, as cx_csc_clear leaves it), everything else the
 * same, bitwise: f with the prescribed displacements' part and the
 * stiffness scale p->kscale come from the element matrices, summed in the
 * order the assembly sums them. What needs K (a direct method, a
 * session's factorisation, an energy norm, the baseline) must not get
 * such a problem. It saves K and the assembly's pattern, not the element
 * work (hertz 1024, 2.1M dofs: scene built in 0.60 s instead of 1.10 s, and
 * 0.35 GB less at the peak of a one-rank PETSc run, 2.56 GB). */
#define CX_SCENE_BUILD_NO_K 0x1u
int cx_scene_build_flags(const cx_scene *s, int level, unsigned flags, cx_problem **p,
                         cx_friction_state *fr, cx_diag *d);

/* Hertz pressure p(x) = 2P/(pi b^2) sqrt(b^2 - x^2) of the scene (0 if
 * none) and the half-width b. */
double cx_scene_hertz_halfwidth(const cx_scene *s);
double cx_scene_hertz_pressure(const cx_scene *s, double x);

/* 3D: the contact radius of a solution, from a least-squares fit of
 * Hertz's p^2 = k (a^2 - r^2) over the points in contact (0 if none or 2D). */
double cx_scene_contact_radius(const cx_scene *s, const cx_problem *p, const double *lN);

/* 3D scenes (an eighth of a ball, symmetry planes x = 0 and y = 0):
 * cx_scene_hertz_halfwidth is the contact radius a, the pressure is
 * p(r), r = hypot(x, y), and the error is over the contact boundary.
 * L2 error on the x axis of the contact pressure (nodal force lN over
 * lumped length) against Hertz's, absolute and relative to ||p||.
 * CX_EUNSUPPORTED if the scene has no [hertz] section. */
int cx_scene_pressure_error(const cx_scene *s, const cx_problem *p, const double *lN,
                            double *abs_err, double *rel_err);

/* --method auto: the method for a scene under a friction law. A shipped
 * scene at its default level takes the choice measured for it (the table
 * in scene/auto.c: the method fastest to the default tolerance among those
 * that support the scene); any other scene or level a rule from the
 * problem's properties (dimension, law, floating bodies, multibody). p is
 * the built problem (may be NULL: the scene's properties then). Returns
 * the method id; *params the method's parameters ("key=value ...", "" for
 * its defaults; never NULL). Constant strings. */
const char *cx_scene_auto_method(const cx_scene *sc, int level, const cx_problem *p, cx_friction law,
                                 const char **params);

#endif
