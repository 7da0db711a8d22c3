/* SPDX-License-Identifier: GPL-3.0-or-later */
/* mesh/: meshes and their generators, one generator per geometry. A mesh is
 * nodes, elements of one type, an optional body id and material id per
 * element, and named boundaries (lists of boundary facets). It knows
 * nothing of elasticity: a material id is an index into a table its user
 * keeps.
 * Generators return a new mesh the caller owns (cx_mesh_destroy). */
#ifndef CX_MESH_H
#define CX_MESH_H

#include "base/base.h"

typedef enum cx_elem_type {
    CX_EL_TRI3,   /* P1 triangle, 3 nodes counter-clockwise */
    CX_EL_TRI6,   /* P2 triangle: vertices 0,1,2 ccw, then mid-edges 01, 12, 20 */
    CX_EL_QUAD4,  /* Q1 quadrilateral, 4 nodes counter-clockwise */
    CX_EL_HEX8,   /* Q1 hexahedron: bottom face 0-3 ccw seen from +z, top 4-7 above them */
    CX_EL_TET4    /* P1 tetrahedron with positive volume */
} cx_elem_type;

/* Facets of the boundary: 2D edges (2 nodes, or 3 for P2: ends then middle),
 * 3D faces (4 nodes of a hex face, or 3 of a tet face), ordered so that the
 * outward normal follows the right-hand rule in 3D and lies to the right of
 * the edge direction in 2D (the body is on the left). */
typedef struct cx_boundary {
    char name[24];
    int nfacets;
    int npf;          /* nodes per facet */
    int *facets;      /* npf * nfacets node ids */
} cx_boundary;

typedef struct cx_mesh {
    int dim;                  /* 2 or 3 */
    int nnodes;
    double *x;                /* dim * nnodes coordinates */
    cx_elem_type etype;
    int npe;                  /* nodes per element */
    int nelems;
    int *conn;                /* npe * nelems */
    int nbodies;              /* >= 1 */
    int *body;                /* nelems body ids in [0, nbodies), or NULL if one body */
    int nmats;                /* material ids when mat is set (else unused) */
    int *mat;                 /* nelems material ids in [0, nmats), set where the material
                                 is per region (a body may hold several), or NULL: each
                                 body is one material, its id the body id */
    int nbounds;
    cx_boundary *bounds;      /* nbounds named boundaries */
} cx_mesh;

/* The material id of element e (mat, else body, else 0), and the size
 * of a material table for m: one entry per id (nmats, else nbodies). */
static inline int cx_mesh_elem_mat(const cx_mesh *m, int e)
{
    return m->mat ? m->mat[e] : m->body ? m->body[e] : 0;
}
static inline int cx_mesh_nmats(const cx_mesh *m) { return m->mat ? m->nmats : m->nbodies; }

/* Nodes per element of a type, and the space dimension of a type. */
int cx_elem_npe(cx_elem_type t);
int cx_elem_dim(cx_elem_type t);
const char *cx_elem_name(cx_elem_type t);      /* "tri3", "tri6", "quad4", "hex8", "tet4" */
int cx_elem_from_name(const char *name);       /* -1 if unknown */

void cx_mesh_destroy(cx_mesh **m);

/* The boundary called name, or NULL. */
const cx_boundary *cx_mesh_boundary(const cx_mesh *m, const char *name);

/* The distinct nodes of a boundary, ascending; *nodes is allocated
 * (cx_free), *count set. */
int cx_boundary_nodes(const cx_boundary *b, int **nodes, int *count);

/* Rectangle [x0,x1] x [y0,y1] with nx x ny cells: TRI3 (two triangles per
 * cell, diagonal (i,j)-(i+1,j+1)), TRI6 (the same, P2) or QUAD4. Node
 * (i, j) of the (q nx + 1) x (q ny + 1) lattice (q = 2 for TRI6, else 1) is
 * j (q nx + 1) + i. Boundaries "left", "right", "bottom", "top".
 * CX_EINVAL (with d) for bad sizes or a non-2D element type. */
int cx_mesh_rectangle(cx_mesh **m, double x0, double y0, double x1, double y1,
                      int nx, int ny, cx_elem_type t, cx_diag *d);

/* The Hertz quarter disc of radius R (centre (0, R)), level N: the unit
 * square (u, v) = (i/N, j/N) mapped by x = R u sqrt(1 - v^2/2),
 * y = R - R v sqrt(1 - u^2/2), two TRI3 per cell (or TRI6 / QUAD4; TRI6
 * maps the 2N lattice, so its mid-edge nodes lie on the curved map). Node
 * (i, j) is j (qN + 1) + i as for the rectangle; (0, N) is the origin.
 * Boundaries "top" (v = 0, the cut y = R), "axis" (u = 0, x = 0),
 * "arc" (v = 1, the lower arc from the origin to 45 degrees: the contact
 * candidates) and "side" (u = 1, the arc from 45 degrees up to (R, R));
 * "quarter" is arc then side, the whole quarter arc (paper 002's Gc).
 * CX_EINVAL (with d) for R <= 0, N < 1 or a non-2D element type. */
int cx_mesh_hertz(cx_mesh **m, double R, int N, cx_elem_type t, cx_diag *d);

/* Brick [x0,x1] x [y0,y1] x [z0,z1] with nx x ny x nz cells: HEX8, or TET4
 * (each cell split into 6 tetrahedra around its main diagonal, conforming
 * across cells). Node (i, j, k) is (k (ny+1) + j) (nx+1) + i. Boundaries
 * "xmin", "xmax", "ymin", "ymax", "zmin", "zmax". CX_EINVAL as above. */
int cx_mesh_brick(cx_mesh **m, const double lo[3], const double hi[3],
                  int nx, int ny, int nz, cx_elem_type t, cx_diag *d);

/* Two blocks stacked along y as one mesh of two bodies (paper 000 §7):
 * body 0 (Omega^1) is the rectangle [x0,x1] x [ym,y1] with cells_upper
 * (x, y) cells, body 1 (Omega^2) is [x0,x1] x [y0,ym] with cells_lower
 * cells; the counts may differ (non-matching interface). Nodes of body 0
 * come first, with the rectangle's numbering; the interface nodes exist
 * once per body. Boundaries "left1", "right1", "bottom1", "top1" of body 0
 * and "left2", ..., "top2" of body 1 (bottom1 and top2 face each other).
 * CX_EINVAL (with d) unless y0 < ym < y1, or as cx_mesh_rectangle. */
int cx_mesh_twoblocks(cx_mesh **m, double x0, double y0, double ym, double x1, double y1,
                      const int cells_upper[2], const int cells_lower[2], cx_elem_type t,
                      cx_diag *d);

/* Masonry walls on the unit square (paper 003 §5): N courses of height
 * H = 1/N built of separate bodies, each meshed with TRI6 of size h = H
 * (two triangles per H x H cell) with its own nodes, so that neighbouring
 * bodies have coincident nodes on their common edges. Stack bond: H x H
 * squares; running bond: 2H x H bricks with H x H half bricks closing the
 * courses (even N: a course of N/2 bricks, then half + N/2-1 bricks + half;
 * odd N: (N-1)/2 bricks and a half brick at the right end, then at the
 * left); laminae: 1 x H strips. Boundaries: "left", "right", "top",
 * "settle" (bottom edges ending at x <= 1/2: the Signorini part),
 * "base" (the other bottom edges), and "joints" (every edge shared by two
 * bodies, once from each side). body[e] numbers the bodies course by course
 * from the bottom left. CX_EINVAL for N < 1 or an unknown bond. */
typedef enum cx_bond {
    CX_BOND_STACK,
    CX_BOND_RUNNING,
    CX_BOND_LAMINAE
} cx_bond;

int cx_mesh_masonry(cx_mesh **m, cx_bond bond, int N, cx_diag *d);
/* Number of bodies of a wall: N^2, N(N+1)/2, N. */
long cx_masonry_bodies(cx_bond bond, int N);

/* ---- facets and the surface (surface.c) ---------------------------------- */

/* The facets of an element type in local node numbers, -1 padded: 2D the
 * edges (end, end, and for TRI6 the mid node), 3D the faces (3 or 4
 * corners, outward by the right-hand rule for a right-handed element).
 * Returns their count; *npf is the corners per facet (2, 3 or 4). */
int cx_elem_facets(cx_elem_type t, const int (**local)[4], int *npf);

/* Facets of a mesh, each once (matched by their corner nodes, so two bodies
 * that repeat their interface nodes keep both sides). */
typedef struct cx_facets {
    int n;
    int npf;         /* corners per facet: 2 (2D), 3 (TET4), 4 (HEX8) */
    int *nodes;      /* npf n corners, ordered as in the first element that has the facet */
    int *mid;        /* n mid-edge nodes of TRI6 edges, NULL for other types */
    int *uses;       /* n: elements that share the facet (1 on the surface) */
} cx_facets;

/* Every facet of m (surface = 0) or only those of one element, the
 * surface (surface = 1): 2D the boundary edges, 3D the boundary faces. In
 * the order of the elements, so the result depends only on the mesh.
 * Fills *f (cx_facets_clear frees it); CX_ENOMEM. */
int cx_mesh_facets(const cx_mesh *m, int surface, cx_facets *f);
void cx_facets_clear(cx_facets *f);

/* The outline: the distinct edges of the surface facets as node pairs
 * (smaller id first, sorted); 2D TRI6 edges split at their mid node.
 * *pairs (2 count ints) is allocated (cx_free). CX_ENOMEM. */
int cx_mesh_outline(const cx_mesh *m, int **pairs, int *count);

/* ---- meshes from Gmsh files (gmsh.c) ------------------------------------- */

/* A physical group of a Gmsh file: dim == mesh dim a region (items: its
 * elements), dim 0 a point (items: its nodes), dim == mesh dim - 1 a
 * boundary (in the mesh's bounds under the same name; items NULL). */
typedef struct cx_mesh_group {
    char name[24];
    int dim;
    int count;
    int *items;
} cx_mesh_group;

typedef struct cx_mesh_groups {
    int n;
    cx_mesh_group *g;
} cx_mesh_groups;

typedef struct cx_gmsh_options {
    int level;        /* a .geo is meshed at size h / level (h: its own sizes) */
    double size;      /* > 0: and at most size / level */
    int element;      /* the cx_elem_type asked for (TRI6: second order, QUAD4 and
                         HEX8: recombined), -1 for the file's (a .geo: TRI3/TET4) */
} cx_gmsh_options;

/* Is Gmsh built in (meson feature 'gmsh')? */
int cx_mesh_have_gmsh(void);

/* Read a .msh (format 4, ASCII or binary) or mesh a .geo with Gmsh, in a
 * helper process (signorini-mesh; $SIGNORINI_MESHER names another): the
 * elements of the model's dimension, which must be of one type (TRI3,
 * TRI6, QUAD4, TET4, HEX8), the nodes they use, bodies (the connected
 * parts), boundaries from the physical groups one dimension down (facets
 * oriented as in their elements), regions and points in *groups
 * (cx_mesh_groups_clear). Elements of an entity all turning the wrong way
 * are turned over; one turning against the rest, or flat, is an inverted
 * element. CX_EINVAL with "PATH: ..." for a file Gmsh cannot read or mesh,
 * an element type we do not have (naming the group and the type), an
 * inverted element; CX_EIO for an unreadable file; CX_EUNSUPPORTED in a
 * build without Gmsh. */
int cx_mesh_read_gmsh(cx_mesh **m, cx_mesh_groups *groups, const char *path,
                      const cx_gmsh_options *opt, cx_diag *d);
void cx_mesh_groups_clear(cx_mesh_groups *g);
/* The group called name, or NULL. */
const cx_mesh_group *cx_mesh_group_find(const cx_mesh_groups *g, const char *name);

#endif
