/* Private to fem/: the reference elements (shape functions, node positions,
 * quadrature) shared by the element kernels (element.c), the nodal stresses
 * (stress.c) and the assembly. */
#ifndef CX_FEM_IMPL_H
#define CX_FEM_IMPL_H

#include "fem/fem.h"

#define CX_FEM_MAXNPE 8     /* nodes per element (HEX8) */
#define CX_FEM_MAXDOF 24    /* dofs per element */

/* Reference coordinates of the nodes of t (dim * npe values): where the
 * nodal stresses are evaluated. */
const double *cx_fem_ref_nodes(cx_elem_type t);

/* The volume quadrature rule of t (stiffness and body force): returns the
 * number of points, *xi (dim per point) and *w. */
int cx_fem_rule(cx_elem_type t, const double **xi, const double **w);

/* At reference point xi of element t with node coordinates xe: shape
 * values N (npe), physical gradients G (npe x dim, node-major) and det J.
 * CX_ENUMERIC if det J is not positive (relative to the element's size):
 * a degenerate or inverted element. */
int cx_fem_eval(cx_elem_type t, const double *xe, const double *xi, double *N, double *G,
                double *detJ);

/* The strain-displacement matrix B (nstress x dim npe, row-major, Voigt
 * order, engineering shear) from the gradients G. */
void cx_fem_strain_matrix(int dim, int npe, const double *G, double *B);

#endif
