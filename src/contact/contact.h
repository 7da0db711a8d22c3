/* SPDX-License-Identifier: GPL-3.0-or-later */
/* contact/: contact constraints from a mesh and an obstacle, without K.
 * A contact set holds m contact points and, in the all-dof numbering of
 * fem/ (node k, component c -> dim k + c), the sparse rows
 *     N (m x nall):         (N u)_i = normal displacement of point i towards
 *                            the obstacle (closing the gap is positive),
 *     T (m(dim-1) x nall):  tangential displacements (one tangent in 2D, an
 *                            orthonormal pair in 3D, rows 2i and 2i+1),
 * and the initial gap g (m), so that non-penetration reads N u - g <= 0.
 * Rows are general sparse rows, so that two-body node-to-segment rows and
 * multibody node-to-node rows fit the same structure. An initial
 * penetration is an error (CX_EINVAL with the point), never clipped. */
#ifndef CX_CONTACT_H
#define CX_CONTACT_H

#include "base/base.h"
#include "linalg/linalg.h"
#include "mesh/mesh.h"
#include "fem/fem.h"

typedef enum cx_obstacle_kind {
    CX_OBST_PLANE,    /* half-space {x : (x - point) . normal <= 0}; normal points out of the obstacle */
    CX_OBST_DISC,     /* 2D disc (centre, radius): the body is outside it */
    CX_OBST_CYLINDER, /* 3D cylinder (centre, axis, radius): the body is outside */
    CX_OBST_SPHERE    /* 3D ball (centre, radius): the body is outside; a half-ball uses the same surface */
} cx_obstacle_kind;

typedef struct cx_obstacle {
    cx_obstacle_kind kind;
    double point[3];   /* PLANE: a point of the plane; DISC/CYLINDER/SPHERE: the centre */
    double normal[3];  /* PLANE: unit normal out of the obstacle; CYLINDER: unit axis */
    double radius;
    /* If set (unit vector), gaps and normals are measured along this fixed
     * direction (the body moves along it towards the obstacle), as in paper
     * 002's half-ball where the gap is measured along z. Zero: along the
     * closest-point normal. */
    double direction[3];
} cx_obstacle;

const char *cx_obstacle_name(cx_obstacle_kind k);   /* "plane", "disc", "cylinder", "sphere" */
int cx_obstacle_from_name(const char *name);        /* -1 if unknown */

typedef struct cx_contact_set {
    int dim;
    int m;               /* contact points: points with a free dof in the normal direction */
    int nclamped;        /* points of the contact boundary left out: their normal
                            displacement is prescribed (cx_contact_drop_clamped) */
    int nall;            /* columns of N and T */
    int *node;           /* m: mesh node of the point (the slave node) */
    double *x;           /* dim * m: its position */
    double *weight;      /* m: lumped length (2D) / area (3D) of the contact boundary */
    double *normal;      /* dim * m: unit normal towards the obstacle */
    double *tangent;     /* dim * (dim-1) * m: unit tangents (2D: normal rotated by +90 deg) */
    double *gap;         /* m: initial gap >= 0 */
    cx_triplet N;        /* m x nall */
    cx_triplet T;        /* m(dim-1) x nall */
    /* several contacts with their own friction values (cx_contact_append,
     * cx_contact_set_friction): per point, or NULL when one value holds */
    double *Fpt;         /* m: Coulomb coefficient */
    double *spt;         /* m: Tresca slip bound, a nodal force (bound x weight) */
} cx_contact_set;

/* Append the points and rows of src after those of dst (a scene's several
 * contacts; both over the same nall, dst zeroed or built); src is cleared.
 * CX_ENOMEM (dst unchanged), CX_EINVAL if the sizes differ. */
int cx_contact_append(cx_contact_set *dst, cx_contact_set *src);

/* The friction values of points [start, end): coefficient F and slip bound
 * (a traction, times each point's weight). Allocates Fpt and spt on first
 * use; call it for every range once all contacts are appended. CX_ENOMEM. */
int cx_contact_set_friction(cx_contact_set *cs, int start, int end, double F, double slip_bound);

/* Contact points at the nodes of boundary b against obstacle ob, ordered
 * along the boundary (by arc length from the first facet's first node in
 * 2D; by coordinates in 3D). cs must be zeroed or cleared. An initial
 * penetration deeper than 1e-12 times the body size is CX_EINVAL with a
 * message naming the point; smaller ones are rounding and set to 0. */
int cx_contact_from_obstacle(cx_contact_set *cs, const cx_mesh *m, const cx_boundary *b,
                             const cx_obstacle *ob, cx_diag *d);
void cx_contact_clear(cx_contact_set *cs);

/* Remove the clamped points of cs: those whose row of N touches no free
 * dof of map (a support prescribes their normal displacement, e.g. the
 * clamped face's edge on the contact face of paper 001's prism). They are
 * counted in cs->nclamped; the other points keep their order. CX_ENOMEM. */
int cx_contact_drop_clamped(cx_contact_set *cs, const cx_dofmap *map);

/* Two-body node-to-segment rows (paper 000 §3, 2D): one contact point
 * per node of the slave boundary that has a free dof in map (map may be
 * NULL: every node), in their order along the slave from its end of
 * smaller x (by x then y if it is not one open chain), paired by
 * projection with its closest point chi on the master boundary's segments
 * [x_p, x_q] (a 3-node edge counts as its two straight halves, on either
 * side); rows N = (nu, -(1-delta) nu,
 * -delta nu) and T likewise with t over the dofs of (x, x_p, x_q), gap
 * |chi - x|, nu = (chi - x)/gap or the slave's outward normal where the gap
 * is 0. CX_EINVAL if a node penetrates the master; CX_EUNSUPPORTED in 3D. */
int cx_contact_node_to_segment(cx_contact_set *cs, const cx_mesh *m, const cx_boundary *slave,
                               const cx_boundary *master, const cx_dofmap *map, cx_diag *d);

/* Signed distance-like gap and unit normal (towards the obstacle) of one
 * point x against ob; the gap is negative inside the obstacle. */
int cx_obstacle_gap(const cx_obstacle *ob, int dim, const double *x, double *gap, double *normal);

/* An orthonormal tangent basis of a unit normal: 2D one tangent (normal
 * rotated +90 deg), 3D two (t1 x t2 = n). */
void cx_tangent_basis(int dim, const double *n, double *t);

/* Paper 003: many bodies with matching nodes. The contact set of a masonry
 * wall: first the Signorini points, the nodes of boundary settle that are
 * not on boundary fixed (Dirichlet wins where the two meet), against the
 * obstacle ob; then one frictionless node-to-node row per pair of
 * coincident nodes on the joints (boundary joints holds every shared edge
 * once from each side): with n the outward normal of the body below or to
 * the left, (N u)_i = (u_k - u_l) . n closes the joint (gap 0), the point
 * is node k. Pairs are listed once, ordered by node. CX_EINVAL if a joint
 * edge has no partner edge with coincident nodes. */
int cx_contact_masonry(cx_contact_set *cs, const cx_mesh *m, const cx_boundary *settle,
                       const cx_boundary *fixed, const cx_boundary *joints,
                       const cx_obstacle *ob, cx_diag *d);

#endif
