/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Private to mesh/: the allocation of a mesh and the structured 2D grid
 * shared by the rectangle and Hertz generators (defined in mesh.c and
 * grid2d.c). */
#ifndef CX_MESH_IMPL_H
#define CX_MESH_IMPL_H

#include "mesh/mesh.h"

/* A new mesh with zeroed coordinates and connectivity, one body (body NULL)
 * and nbounds unnamed empty boundaries. CX_ENOMEM (nothing left behind). */
int cx_mesh_alloc(cx_mesh **m, int dim, int nnodes, cx_elem_type t, int nelems, int nbounds);

/* Name b and allocate its npf * nfacets facet array. CX_ENOMEM. */
int cx_mesh_alloc_boundary(cx_boundary *b, const char *name, int nfacets, int npf);

/* CX_EINVAL with a message unless count (a product of the generator's
 * sizes, computed in double) fits an int index. what names the count. */
int cx_mesh_check_size(double count, const char *what, cx_diag *d);

/* The connectivity and boundaries of an nx x ny grid of cells (TRI3: two
 * triangles per cell along the (i, j)-(i+1, j+1) diagonal; TRI6: the same
 * with mid-edge nodes; QUAD4). Nodes sit on a lattice of q nx + 1 by
 * q ny + 1 points, q = 2 for TRI6 and 1 otherwise; lattice point (I, J) is
 * node J (q nx + 1) + I, and the caller fills the coordinates. flip: the
 * caller's map (I, J) -> (x, y) reverses orientation, so elements and facets
 * are ordered the other way round. side[0..3] name the sides J = 0,
 * I = q nx, J = q ny, I = 0. CX_EINVAL (bad sizes or type), CX_ENOMEM. */
int cx_mesh_grid2d(cx_mesh **m, int nx, int ny, cx_elem_type t, int flip,
                   const char *const side[4], cx_diag *d);

#endif
