/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fem/: linear elasticity by finite elements. Element kernels (pure
 * functions of element coordinates and material) apart from the global
 * assembly; Dirichlet elimination as a separate step with expansion back;
 * nodal stresses computed only when asked. Dof numbering of the full
 * ("all") system: node k, component c -> dim * k + c. */
#ifndef CX_FEM_H
#define CX_FEM_H

#include "base/base.h"
#include "linalg/linalg.h"
#include "mesh/mesh.h"

typedef enum cx_model {
    CX_PLANE_STRAIN,
    CX_PLANE_STRESS,
    CX_SOLID        /* 3D */
} cx_model;

typedef struct cx_material {
    double E, nu;     /* Young's modulus, Poisson's ratio (nu < 0.5) */
    cx_model model;
} cx_material;

/* Number of stress components: 3 in 2D (xx, yy, xy) [4 with zz for plane
 * strain is not stored], 6 in 3D (xx, yy, zz, yz, xz, xy) — Voigt order. */
int cx_fem_nstress(int dim);

/* The elasticity matrix D (nstress x nstress, row-major) of a material. */
void cx_fem_elasticity(const cx_material *mat, double *D);

/* ---- element kernels -------------------------------------------------- */

/* Ke = int_e B' D B dx (ndof = dim * npe, row-major, dof order node-major:
 * (node 0 x, node 0 y, node 1 x, ...)). xe: dim * npe coordinates.
 * CX_ENUMERIC if the element is degenerate or inverted. */
int cx_fem_element_stiffness(cx_elem_type t, const double *xe, const double *D, double *Ke);

/* fe = int_e N' b dx for a constant body force b (dim values per volume). */
int cx_fem_element_body_force(cx_elem_type t, const double *xe, const double *b, double *fe);

/* An affine surface traction t(x) = t0 + G x (force per area/length),
 * G row-major dim x dim: t_i = t0_i + sum_k G[i*dim+k] x_k. */
typedef struct cx_traction {
    double t0[3];
    double G[9];
} cx_traction;

/* fe = int_facet N' t(x) ds for a boundary facet with npf nodes (2D: 2 or 3
 * nodes; 3D: 3 or 4). Exact for the affine traction on straight facets. */
int cx_fem_facet_traction(int dim, int npf, const double *xf, const cx_traction *t, double *fe);

/* Lumped facet measure: weights w[a] (npf values) with sum = facet
 * length/area, w[a] = int N_a ds (Simpson-like for P2 edges: 1/6, 1/6,
 * 4/6 in facet order). Writes nothing for an unsupported (dim, npf). */
void cx_fem_facet_lumped(int dim, int npf, const double *xf, double *w);

/* ---- assembly ---------------------------------------------------------- */

/* K over all dim * nnodes dofs, symmetric, full storage. mats: one per
 * material id of the mesh (cx_mesh_nmats entries: per body unless the mesh
 * has material ids per element). The pattern: every dof pair of two nodes that
 * share an element (explicit zeros kept), nothing else. K must be empty and
 * is left empty on failure: CX_EINVAL (bad material, body, material or node id, or
 * more than INT_MAX entries), CX_ENUMERIC (names the degenerate element),
 * CX_ENOMEM. */
int cx_fem_assemble_stiffness(const cx_mesh *m, const cx_material *mats, cx_csc *K, cx_diag *d);
/* f += traction on the facets of boundary b. CX_EINVAL for facets the
 * kernels do not know. */
int cx_fem_add_traction(const cx_mesh *m, const cx_boundary *b, const cx_traction *t, double *f);
/* f += body force b (dim values) over all elements. CX_ENUMERIC for a
 * degenerate element. */
int cx_fem_add_body_force(const cx_mesh *m, const double *b, double *f);
/* f += pressure p normal to the facets of b (positive pushes into the body:
 * the traction -p n, n the outward normal of the straight facet through
 * its corners) (loads.c). CX_EINVAL for unknown facets, CX_ENUMERIC for a
 * facet of no length or area. */
int cx_fem_add_pressure(const cx_mesh *m, const cx_boundary *b, double p, double *f);
/* f += body force b over the elements elems[0..count) (a region). */
int cx_fem_add_body_force_on(const cx_mesh *m, const int *elems, int count, const double *b,
                             double *f);

/* ---- Dirichlet elimination --------------------------------------------- */

/* Which dofs are prescribed, and to what. */
typedef struct cx_dofmap {
    int nall;          /* dim * nnodes */
    int nfree;
    int *free_of;      /* nall: free index of an all-dof, or -1 if prescribed */
    int *all_of;       /* nfree: the all-dof of a free index */
    double *value;     /* nall: prescribed value (0 for free dofs) */
} cx_dofmap;

/* All dofs free. */
int cx_dofmap_init(cx_dofmap *map, int nall);
void cx_dofmap_clear(cx_dofmap *map);
/* Prescribe component c (0..dim-1) of every node of boundary b to value
 * (a whole node: call once per component; a symmetry line: one component).
 * nfree is -1 until the next cx_dofmap_finish. CX_EINVAL for a bad c. */
int cx_dofmap_fix(cx_dofmap *map, const cx_mesh *m, const cx_boundary *b, int c, double value);
/* Renumber the free dofs after the last fix (ascending all-dof order). */
int cx_dofmap_finish(cx_dofmap *map);

/* K = Kall(free, free), f = fall(free) - Kall(free, fixed) * value.
 * K must be empty; f has nfree entries. CX_EINVAL if the map is not
 * finished or does not fit Kall, CX_ENOMEM (K left empty). */
int cx_fem_reduce(const cx_csc *Kall, const double *fall, const cx_dofmap *map,
                  cx_csc *K, double *f);
/* As cx_fem_reduce, or, when Kall is over the free dofs already (nfree x
 * nfree: cx_fem_assemble_free, or no dof prescribed), its arrays move
 * into K (Kall left empty) and f = fall(free): the prescribed values'
 * part of f is then the caller's (cx_fem_assemble_free's fd). */
int cx_fem_reduce_move(cx_csc *Kall, const double *fall, const cx_dofmap *map, cx_csc *K, double *f);
/* K = Kall(free, free) and fd -= Kall(free, fixed) * value (nfree
 * entries) as cx_fem_reduce gives them from cx_fem_assemble_stiffness (K
 * bitwise), assembled straight onto the free dofs of the finished map:
 * no matrix over all dofs (assemble.c). fd may be NULL when every
 * prescribed value is 0. Failures as cx_fem_assemble_stiffness; CX_EINVAL
 * also for a map not finished or not of this mesh. */
int cx_fem_assemble_free(const cx_mesh *m, const cx_material *mats, const cx_dofmap *map, cx_csc *K,
                         double *fd, cx_diag *d);
/* uall = u on free dofs and the prescribed values elsewhere. */
void cx_fem_expand(const cx_dofmap *map, const double *u, double *uall);

/* ---- stresses ------------------------------------------------------------ */

/* Nodal stresses (mats as for cx_fem_assemble_stiffness): element stresses at the nodes (P1: the constant; others:
 * at the node's reference position), averaged over the elements of each
 * node. sig: nstress * nnodes, node-major. uall: dim * nnodes. */
int cx_fem_nodal_stress(const cx_mesh *m, const cx_material *mats, const double *uall, double *sig);
/* Von Mises stress of one Voigt stress vector (plane strain includes
 * szz = nu (sxx + syy); plane stress szz = 0). */
double cx_fem_von_mises(const cx_material *mat, const double *sig);

#endif
