/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Private to fem/: the reference element of a type (shape values and
 * reference gradients at the quadrature points and at the nodes, computed
 * once and then used for every element of a mesh) and the kernels that take
 * it, shared by the public single-element kernels (element.c), the
 * assembly (assemble.c) and the nodal stresses (stress.c). */
#ifndef CX_FEM_IMPL_H
#define CX_FEM_IMPL_H

#include "fem/fem.h"

#define CX_FEM_MAXNPE 8     /* nodes per element (HEX8) */
#define CX_FEM_MAXDOF 24    /* dofs per element */
#define CX_FEM_MAXQ 8       /* volume quadrature points (HEX8) */

typedef struct cx_fem_ref {
    cx_elem_type t;
    int dim, npe, nq;
    int affine;                                 /* TRI3, TET4: J constant on the element */
    double w[CX_FEM_MAXQ];                      /* quadrature weights */
    double Nq[CX_FEM_MAXQ][CX_FEM_MAXNPE];      /* shape values at the points */
    double dNq[CX_FEM_MAXQ][3 * CX_FEM_MAXNPE]; /* reference gradients there, node-major (a, k) */
    double dNn[CX_FEM_MAXNPE][3 * CX_FEM_MAXNPE]; /* reference gradients at the nodes */
} cx_fem_ref;

/* The reference element of t. CX_EINVAL for an unknown type. */
int cx_fem_ref_init(cx_fem_ref *r, cx_elem_type t);

/* Ke and fe as cx_fem_element_stiffness and cx_fem_element_body_force
 * state, for an element of r's type. */
int cx_fem_ref_stiffness(const cx_fem_ref *r, const double *xe, const double *D, double *Ke);
int cx_fem_ref_body_force(const cx_fem_ref *r, const double *xe, const double *b, double *fe);

/* Physical gradients G (npe x dim, node-major) at node a of the element
 * with coordinates xe. CX_ENUMERIC if det J is not positive there
 * (relative to the element's size). */
int cx_fem_ref_node_gradients(const cx_fem_ref *r, const double *xe, int a, double *G);

/* The strain-displacement matrix B (nstress x dim npe, row-major, Voigt
 * order, engineering shear) from the gradients G. */
void cx_fem_strain_matrix(int dim, int npe, const double *G, double *B);

#endif
