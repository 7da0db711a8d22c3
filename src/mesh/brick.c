/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The brick [lo, hi] with nx x ny x nz cells: trilinear hexahedra, or six
 * tetrahedra per cell by the Kuhn (Freudenthal) split: one tetrahedron per
 * monotone lattice path from the cell's lowest corner to its highest, i.e.
 * per order in which x, y and z are stepped. Every cell is split the same
 * way, and each face of a cell is then cut along its diagonal from its
 * lowest to its highest corner, the same diagonal for both cells that
 * share it: the mesh is conforming. */
#include "mesh/mesh_impl.h"

#include <math.h>

typedef struct lattice {
    int n[3];   /* cells per axis */
} lattice;

static int lat_node(const lattice *L, const int p[3])
{
    return (p[2] * (L->n[1] + 1) + p[1]) * (L->n[0] + 1) + p[0];
}

static double lerp(double a, double b, int k, int n)
{
    return k == n ? b : a + (b - a) * ((double)k / n);
}

/* The 6 Kuhn tetrahedra of the cell at corner c: for each permutation of
 * the axes, the path c, c + e_a, c + e_a + e_b, c + (1,1,1). Odd
 * permutations give a negative volume: their middle nodes are swapped. */
static int put_kuhn(const lattice *L, const int c[3], int *conn)
{
    static const int perm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    for (int k = 0; k < 6; k++) {
        int p[3] = {c[0], c[1], c[2]}, v[4];
        v[0] = lat_node(L, p);
        for (int s = 0; s < 3; s++) {
            p[perm[k][s]]++;
            v[s + 1] = lat_node(L, p);
        }
        if (k >= 3) {
            int t = v[1];
            v[1] = v[2];
            v[2] = t;
        }
        for (int s = 0; s < 4; s++)
            conn[4 * k + s] = v[s];
    }
    return 24;
}

/* Face side (0 min, 1 max) of axis a: the quadrilaterals (or their two
 * triangles along the lowest-to-highest diagonal) ordered q0, q1, q2, q3
 * around the axes (b, c) that follow a cyclically, whose right-hand normal
 * is e_b x e_c = e_a: reversed on the min side to point out. */
static void put_faces(const lattice *L, cx_boundary *bd, int a, int side, int tets)
{
    int b = (a + 1) % 3, c = (a + 2) % 3, *f = bd->facets;
    for (int jc = 0; jc < L->n[c]; jc++)
        for (int jb = 0; jb < L->n[b]; jb++) {
            int q[4], p[3];
            static const int db[4] = {0, 1, 1, 0}, dc[4] = {0, 0, 1, 1};
            for (int s = 0; s < 4; s++) {
                p[a] = side ? L->n[a] : 0;
                p[b] = jb + db[s];
                p[c] = jc + dc[s];
                q[s] = lat_node(L, p);
            }
            if (!side) {
                int t = q[1];
                q[1] = q[3];
                q[3] = t;
            }
            if (tets) {
                f[0] = q[0], f[1] = q[1], f[2] = q[2];
                f[3] = q[0], f[4] = q[2], f[5] = q[3];
                f += 6;
            } else {
                f[0] = q[0], f[1] = q[1], f[2] = q[2], f[3] = q[3];
                f += 4;
            }
        }
}

int cx_mesh_brick(cx_mesh **m, const double lo[3], const double hi[3],
                  int nx, int ny, int nz, cx_elem_type t, cx_diag *d)
{
    static const char *const names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
    *m = NULL;
    if (t != CX_EL_HEX8 && t != CX_EL_TET4)
        return cx_diag_set(d, CX_EINVAL, "brick: element '%s' is not a 3D element (hex8 or tet4)",
                           cx_elem_name(t));
    for (int k = 0; k < 3; k++)
        if (!isfinite(lo[k]) || !isfinite(hi[k]) || !(hi[k] > lo[k]))
            return cx_diag_set(d, CX_EINVAL, "brick: need lo < hi on axis %c (got %g, %g)",
                               "xyz"[k], lo[k], hi[k]);
    if (nx < 1 || ny < 1 || nz < 1)
        return cx_diag_set(d, CX_EINVAL, "brick: cells %d x %d x %d: need at least 1 x 1 x 1",
                           nx, ny, nz);
    int tets = t == CX_EL_TET4, per_cell = tets ? 6 : 1;
    CX_TRY(cx_mesh_check_size(((double)nx + 1) * ((double)ny + 1) * ((double)nz + 1), "nodes", d));
    CX_TRY(cx_mesh_check_size((double)nx * ny * nz * per_cell * cx_elem_npe(t), "element node slots", d));
    CX_TRY(cx_mesh_check_size(2.0 * ((double)nx * ny + (double)ny * nz + (double)nz * nx) * 6,
                              "boundary facet node slots", d));

    lattice L = {{nx, ny, nz}};
    cx_mesh *p;
    if (cx_mesh_alloc(&p, 3, (nx + 1) * (ny + 1) * (nz + 1), t, per_cell * nx * ny * nz, 6))
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    for (int k = 0; k <= nz; k++)
        for (int j = 0; j <= ny; j++)
            for (int i = 0; i <= nx; i++) {
                int c[3] = {i, j, k};
                double *x = p->x + 3 * lat_node(&L, c);
                for (int s = 0; s < 3; s++)
                    x[s] = lerp(lo[s], hi[s], c[s], L.n[s]);
            }
    int *conn = p->conn;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++) {
                int c[3] = {i, j, k};
                if (tets) {
                    conn += put_kuhn(&L, c, conn);
                } else {
                    /* bottom face counter-clockwise seen from +z, then the top */
                    static const int di[8] = {0, 1, 1, 0, 0, 1, 1, 0}, dj[8] = {0, 0, 1, 1, 0, 0, 1, 1},
                                     dk[8] = {0, 0, 0, 0, 1, 1, 1, 1};
                    for (int s = 0; s < 8; s++) {
                        int q[3] = {i + di[s], j + dj[s], k + dk[s]};
                        conn[s] = lat_node(&L, q);
                    }
                    conn += 8;
                }
            }
    for (int a = 0; a < 3; a++)
        for (int side = 0; side < 2; side++) {
            cx_boundary *bd = &p->bounds[2 * a + side];
            int nf = L.n[(a + 1) % 3] * L.n[(a + 2) % 3] * (tets ? 2 : 1);
            if (cx_mesh_alloc_boundary(bd, names[a][side], nf, tets ? 3 : 4)) {
                cx_mesh_destroy(&p);
                return cx_diag_set(d, CX_ENOMEM, "out of memory");
            }
            put_faces(&L, bd, a, side, tets);
        }
    *m = p;
    return CX_OK;
}
