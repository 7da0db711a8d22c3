/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The discrete problem out of signorini, for other solvers (README, "The
 * discrete problem"): MatrixMarket files with a JSON manifest
 * (export_mm.c), and an FCLIB global frictional problem in HDF5
 * (export_fclib.c). The sign conventions are those of solve/problem.h:
 *     K u - f + N' lN + T' lT = 0,  N u - g <= 0,  lN >= 0,
 *     |lT_i| <= s_i (Tresca) or F_i lN_i (Coulomb), T u along lT when slipping.
 * The friction values written are the session's per-point ones (fr->s,
 * fr->Fi: cx_session_friction). */
#ifndef CX_OUT_EXPORT_H
#define CX_OUT_EXPORT_H

#include "solve/solve.h"

/* The manifest's name inside an exported directory. */
#define CX_PROBLEM_MANIFEST "problem.json"   /* = CX_PROBLEM_MANIFEST_NAME (scene/problem_file.h) */

/* Into directory dir (created if missing; files in it replaced): K.mtx
 * (symmetric, lower triangle), f.mtx, N.mtx, T.mtx, g.mtx, weight.mtx,
 * points.mtx (m x dim positions of the contact points), and by law mu.mtx
 * (Coulomb, F_i) or slip_bound.mtx (Tresca, s_i nodal forces); with a
 * mesh, dofs.mtx (n x 2: node, component of each unknown, 1-based) and
 * nodes.mtx (coordinates), point_nodes.mtx (m: the node of each point);
 * and problem.json. source: the scene's id (or path), level its level,
 * for the manifest. CX_EIO with the path, CX_ENOMEM. */
int cx_export_mm(const cx_problem *p, const cx_friction_state *fr, const char *dir, const char *source,
                 int level, cx_diag *d);

/* The same problem as an FCLIB global problem (M = K, H = -[N; T]' per
 * point (normal then tangents), f, w = (g_i, 0...), mu = F_i; frictionless:
 * mu = 0 with the T rows kept). Tresca has no FCLIB form: CX_EUNSUPPORTED.
 * A build without FCLIB: CX_EUNSUPPORTED. */
int cx_export_fclib(const cx_problem *p, const cx_friction_state *fr, const char *path, const char *source,
                    int level, cx_diag *d);

#endif
