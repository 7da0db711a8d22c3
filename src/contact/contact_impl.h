/* SPDX-License-Identifier: GPL-3.0-or-later */
/* contact/ internals shared by the three builders of a contact set (rigid
 * obstacle, node-to-segment, masonry): the allocation of a set and the
 * lumped weights of its points. */
#ifndef CX_CONTACT_IMPL_H
#define CX_CONTACT_IMPL_H

#include "contact/contact.h"

/* Allocate the arrays of m points (zeroed) and empty N (m rows) and T
 * (m(dim-1) rows) over nall columns with room for capN and capT entries.
 * CX_ENOMEM (the caller clears cs). */
int contact_alloc(cx_contact_set *cs, int dim, int m, int nall, size_t capN, size_t capT);

/* Add to weight[pos[k]] the lumped share (cx_fem_facet_lumped) of every
 * facet of b at its node k; nodes with pos[k] < 0 are not points. */
void contact_weights(double *weight, const cx_mesh *m, const cx_boundary *b, const int *pos);

/* The boundary nodes in their order along a 2D chain of facets, walked from
 * the facet whose first node ends no other facet, so that the contact strip
 * shows the points in boundary order (rigid.c; node-to-segment pairing too).
 * Returns the count placed: less than the node count when the boundary is
 * not one open chain (the caller then keeps its own order). facet_of and
 * seen: nnodes ints of workspace. */
int contact_order_2d_chain(const cx_boundary *b, int nnodes, int *order, int *facet_of, int *seen);

#endif
