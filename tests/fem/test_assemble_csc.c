/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The stiffness assembled straight into its CSC pattern, for TRI3, TRI6,
 * QUAD4 (2D) and TET4, HEX8 (3D) on distorted meshes of two bodies, a
 * masonry wall (separate bodies with coincident nodes) and a mesh with a
 * node in no element (a node id out of range is refused):
 *  - equals a reference triplet assembly of the element matrices (the same
 *    pattern entry for entry, values to 1e-14 of max |K|);
 *  - its pattern is symmetric and K exactly symmetric, columns sorted with
 *    no duplicates, and an entry is stored exactly where two nodes share an
 *    element;
 *  - Dirichlet elimination (cx_fem_reduce) gives the same reduced K and f
 *    as from the reference, and K(free, free), f - K(free, fixed) value
 *    against a dense computation;
 *  - the elimination folded into the assembly (cx_fem_assemble_free, with
 *    whole nodes and single components prescribed to non-zero values)
 *    gives that reduced K bit for bit and f to 1e-14, and moves in
 *    (cx_fem_reduce_move); an unfinished map is refused.
 * And the element kernel against a dense sum of w det B'DB at the
 * quadrature points (Jacobians computed here) with a general, anisotropic
 * symmetric D, to 1e-14 of max |Ke|. */
#include "fem/fem.h"
#include "fem/fem_impl.h"
#include "fem_fixture.h"
#include "check.h"

#include <stdio.h>
#include <string.h>

/* The reference: every element matrix entry as a triplet, summed by the
 * conversion to CSC. */
static int triplet_assembly(const cx_mesh *m, const cx_material *mats, cx_csc *K)
{
    int dim = m->dim, npe = m->npe, nd = dim * npe;
    cx_triplet T;
    if (cx_triplet_init(&T, dim * m->nnodes, dim * m->nnodes, (size_t)m->nelems * (size_t)(nd * nd)))
        return CX_ENOMEM;
    for (int e = 0; e < m->nelems; e++) {
        const int *c = m->conn + npe * e;
        double xe[3 * CX_FEM_MAXNPE], Ke[CX_FEM_MAXDOF * CX_FEM_MAXDOF], D[36];
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++)
                xe[dim * a + i] = m->x[dim * c[a] + i];
        cx_fem_elasticity(&mats[m->body ? m->body[e] : 0], D);
        if (cx_fem_element_stiffness(m->etype, xe, D, Ke))
            return CX_ENUMERIC;
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++)
                for (int b = 0; b < npe; b++)
                    for (int j = 0; j < dim; j++)
                        if (cx_triplet_add(&T, dim * c[a] + i, dim * c[b] + j, Ke[nd * (dim * a + i) + dim * b + j]))
                            return CX_ENOMEM;
    }
    int st = cx_csc_from_triplet(K, &T);
    cx_triplet_clear(&T);
    return st;
}

/* Position of row i in column j, -1 if not stored. */
static int find(const cx_csc *A, int i, int j)
{
    for (int q = A->p[j]; q < A->p[j + 1]; q++)
        if (A->i[q] == i)
            return q;
    return -1;
}

/* Pattern and values of A and B the same: CX_CHECKs, and max |A - B|. */
static double compare(const cx_csc *A, const cx_csc *B)
{
    int same = A->nrow == B->nrow && A->ncol == B->ncol && cx_csc_nnz(A) == cx_csc_nnz(B);
    for (int j = 0; same && j <= A->ncol; j++)
        same = A->p[j] == B->p[j];
    for (size_t q = 0; same && q < cx_csc_nnz(A); q++)
        same = A->i[q] == B->i[q];
    CX_CHECK(same);
    double err = 0;
    for (size_t q = 0; same && q < cx_csc_nnz(A); q++)
        err = fmax(err, fabs(A->x[q] - B->x[q]));
    return same ? err : INFINITY;
}

/* Columns sorted without duplicates; the pattern symmetric and K exactly
 * symmetric; (dim a + i, dim b + j) stored iff nodes a and b share an
 * element. */
static void check_pattern(const cx_mesh *m, const cx_csc *K)
{
    int dim = m->dim, nn = m->nnodes, sorted = 1, sym = 1, exact = 1;
    for (int j = 0; j < K->ncol; j++)
        for (int q = K->p[j] + 1; q < K->p[j + 1]; q++)
            sorted &= K->i[q - 1] < K->i[q];
    CX_CHECK(sorted);
    for (int j = 0; j < K->ncol; j++)
        for (int q = K->p[j]; q < K->p[j + 1]; q++) {
            int t = find(K, j, K->i[q]);
            sym &= t >= 0;
            exact &= t >= 0 && K->x[t] == K->x[q];
        }
    CX_CHECK(sym);
    CX_CHECK(exact);
    /* node adjacency from the connectivity, densely */
    unsigned char *adj = calloc((size_t)nn * (size_t)nn, 1);
    for (int e = 0; e < m->nelems; e++)
        for (int a = 0; a < m->npe; a++)
            for (int b = 0; b < m->npe; b++)
                adj[(size_t)nn * m->conn[m->npe * e + a] + m->conn[m->npe * e + b]] = 1;
    size_t want = 0;
    int match = 1;
    for (int a = 0; a < nn; a++)
        for (int b = 0; b < nn; b++)
            if (adj[(size_t)nn * a + b]) {
                want += (size_t)(dim * dim);
                for (int i = 0; i < dim; i++)
                    for (int j = 0; j < dim; j++)
                        match &= find(K, dim * a + i, dim * b + j) >= 0;
            }
    CX_CHECK(match);
    CX_CHECK(cx_csc_nnz(K) == want);
    free(adj);
}

/* Reduce both, compare, and check K(free, free) and the load shift of the
 * prescribed values against K densely. */
static void check_reduce(const cx_mesh *m, const cx_material *mats, const cx_csc *K, const cx_csc *Kref,
                         const char *fixb, const char *fixc)
{
    int dim = m->dim, nall = dim * m->nnodes;
    cx_dofmap map;
    cx_csc R = {0}, Rref = {0};
    CX_CHECK_OK(cx_dofmap_init(&map, nall));
    for (int c = 0; c < dim; c++)
        CX_CHECK_OK(cx_dofmap_fix(&map, m, cx_mesh_boundary(m, fixb), c, 0.01 * (c + 1)));
    CX_CHECK_OK(cx_dofmap_fix(&map, m, cx_mesh_boundary(m, fixc), dim - 1, -0.02));
    CX_CHECK_OK(cx_dofmap_finish(&map));
    int n = map.nfree;
    CX_CHECK(n > 0 && n < nall);
    double *fall = calloc((size_t)nall, sizeof(double)), *f = calloc((size_t)n, sizeof(double)),
           *fref = calloc((size_t)n, sizeof(double));
    for (int k = 0; k < nall; k++)
        fall[k] = fx_rand();
    CX_CHECK_OK(cx_fem_reduce(K, fall, &map, &R, f));
    CX_CHECK_OK(cx_fem_reduce(Kref, fall, &map, &Rref, fref));
    double kmax = fx_maxabs(K);
    CX_CHECK_NEAR(compare(&R, &Rref), 0, 0, 1e-14 * kmax);
    double ferr = 0, derr = 0, fbig = 0;
    for (int r = 0; r < n; r++) {
        ferr = fmax(ferr, fabs(f[r] - fref[r]));
        /* f_r = fall_r - sum over prescribed s of K(r, s) value_s */
        int ar = map.all_of[r];
        double want = fall[ar];
        for (int s = 0; s < nall; s++)
            if (map.free_of[s] < 0)
                want -= cx_csc_get(K, ar, s) * map.value[s];
        derr = fmax(derr, fabs(f[r] - want));
        fbig = fmax(fbig, fabs(want));
    }
    CX_CHECK_NEAR(ferr, 0, 0, 1e-14 * fbig);
    CX_CHECK_NEAR(derr, 0, 0, 1e-13 * fbig);
    /* K(free, free): every entry of K between free dofs, and only those */
    size_t nfree_entries = 0;
    double kerr = 0;
    for (int j = 0; j < nall; j++)
        for (int q = K->p[j]; q < K->p[j + 1]; q++)
            if (map.free_of[j] >= 0 && map.free_of[K->i[q]] >= 0) {
                nfree_entries++;
                int t = find(&R, map.free_of[K->i[q]], map.free_of[j]);
                kerr = t < 0 ? INFINITY : fmax(kerr, fabs(R.x[t] - K->x[q]));
            }
    CX_CHECK(cx_csc_nnz(&R) == nfree_entries);
    CX_CHECK(kerr == 0);

    /* the elimination folded into the assembly: the same K to the last
     * bit, the same f to rounding; then moved (cx_fem_reduce_move) */
    cx_csc F = {0}, Fm = {0};
    double *fd = calloc((size_t)n, sizeof(double)), *fm = calloc((size_t)n, sizeof(double));
    cx_diag d;
    CX_CHECK_OK(cx_fem_assemble_free(m, mats, &map, &F, fd, &d));
    CX_CHECK(F.nrow == n && F.ncol == n && cx_csc_nnz(&F) == cx_csc_nnz(&R));
    if (F.ncol == n && cx_csc_nnz(&F) == cx_csc_nnz(&R)) {
        CX_CHECK(memcmp(F.p, R.p, sizeof(int) * (size_t)(n + 1)) == 0);
        CX_CHECK(memcmp(F.i, R.i, sizeof(int) * cx_csc_nnz(&R)) == 0);
        CX_CHECK(memcmp(F.x, R.x, sizeof(double) * cx_csc_nnz(&R)) == 0);
    }
    const int *fp = F.p;
    CX_CHECK_OK(cx_fem_reduce_move(&F, fall, &map, &Fm, fm));
    CX_CHECK(Fm.p == fp && F.p == NULL && F.x == NULL);
    double fderr = 0;
    for (int r = 0; r < n; r++)
        fderr = fmax(fderr, fabs(fm[r] + fd[r] - f[r]));
    CX_CHECK_NEAR(fderr, 0, 0, 1e-14 * fbig);
    /* an unfinished map is refused */
    CX_CHECK_OK(cx_dofmap_fix(&map, m, cx_mesh_boundary(m, fixc), 0, 0.0));
    CX_CHECK(cx_fem_assemble_free(m, mats, &map, &F, fd, &d) == CX_EINVAL);
    CX_CHECK(F.p == NULL);
    cx_csc_clear(&Fm);
    free(fd);
    free(fm);
    free(fall);
    free(f);
    free(fref);
    cx_csc_clear(&R);
    cx_csc_clear(&Rref);
    cx_dofmap_clear(&map);
}

static void run_case(const char *label, cx_mesh *m, const cx_material *mats, const char *fixb,
                     const char *fixc)
{
    cx_csc K = {0}, Kref = {0};
    cx_diag d;
    CX_CHECK(m != NULL);
    if (!m)
        return;
    CX_CHECK_OK(cx_fem_assemble_stiffness(m, mats, &K, &d));
    CX_CHECK_OK(triplet_assembly(m, mats, &Kref));
    double kmax = fx_maxabs(&Kref), err = compare(&K, &Kref);
    fprintf(stderr, "%s: %d elements, %d dofs, %zu entries, max |K - Kref| = %.3g of max |K| %.3g\n",
            label, m->nelems, K.ncol, cx_csc_nnz(&K), err, kmax);
    CX_CHECK_NEAR(err, 0, 0, 1e-14 * kmax);
    check_pattern(m, &K);
    if (fixb)
        check_reduce(m, mats, &K, &Kref, fixb, fixc);
    cx_csc_clear(&K);
    cx_csc_clear(&Kref);
}

/* Two bodies (even and odd elements) of different materials. */
static void test_types(void)
{
    cx_elem_type types[5] = {CX_EL_TRI3, CX_EL_TRI6, CX_EL_QUAD4, CX_EL_TET4, CX_EL_HEX8};
    for (int k = 0; k < 5; k++) {
        cx_mesh *m = fx_mesh(types[k], types[k] != CX_EL_TRI6);
        if (!m) {
            CX_CHECK(m != NULL);
            continue;
        }
        int three = m->dim == 3;
        cx_model model = three ? CX_SOLID : CX_PLANE_STRAIN;
        cx_material mats[2] = {fx_material(model), {.E = 3.5, .nu = 0.1, .model = model}};
        m->nbodies = 2;
        m->body = CX_NEW(int, m->nelems);
        for (int e = 0; e < m->nelems && m->body; e++)
            m->body[e] = e % 2;
        run_case(cx_elem_name(types[k]), m, mats, three ? "xmin" : "left", three ? "zmin" : "bottom");
        cx_mesh_destroy(&m);
    }
}

/* Separate bodies whose nodes coincide on the joints: no coupling across. */
static void test_masonry(void)
{
    cx_mesh *m = NULL;
    CX_CHECK_OK(cx_mesh_masonry(&m, CX_BOND_RUNNING, 3, NULL));
    if (!m)
        return;
    cx_material *mats = CX_NEW(cx_material, m->nbodies);
    for (int k = 0; k < m->nbodies; k++)
        mats[k] = (cx_material){.E = 1000 + 10 * k, .nu = 0.2, .model = CX_PLANE_STRESS};
    run_case("masonry running bond 3", m, mats, "base", "top");
    cx_free(mats);
    cx_mesh_destroy(&m);
}

/* A node in no element: its columns and rows stay empty. */
static void test_lonely_node(void)
{
    cx_mesh *m = NULL;
    CX_CHECK_OK(cx_mesh_rectangle(&m, 0, 0, 1, 1, 2, 2, CX_EL_TRI3, NULL));
    if (!m)
        return;
    double *x = cx_realloc(m->x, sizeof(double) * 2 * (size_t)(m->nnodes + 1));
    CX_CHECK(x != NULL);
    if (!x) {
        cx_mesh_destroy(&m);
        return;
    }
    m->x = x;
    x[2 * m->nnodes] = 5, x[2 * m->nnodes + 1] = 5;
    m->nnodes++;
    cx_material mat = fx_material(CX_PLANE_STRAIN);
    cx_csc K = {0};
    CX_CHECK_OK(cx_fem_assemble_stiffness(m, &mat, &K, NULL));
    int last = 2 * (m->nnodes - 1);
    CX_CHECK(K.ncol == 2 * m->nnodes);
    CX_CHECK(K.p[last] == K.p[last + 2]);
    run_case("tri3 with a node in no element", m, &mat, NULL, NULL);
    cx_csc_clear(&K);

    /* a node id out of range is refused, not written through */
    cx_diag d;
    m->conn[4] = m->nnodes;
    CX_CHECK(cx_fem_assemble_stiffness(m, &mat, &K, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "element 1: node") != NULL);
    CX_CHECK(K.p == NULL);
    cx_mesh_destroy(&m);
}

/* Ke against sum_q w_q det J_q B_q' D B_q with B dense (cx_fem_strain_matrix),
 * J and its inverse computed here, and D a general symmetric matrix. */
static void test_kernel(cx_elem_type t)
{
    cx_fem_ref r;
    CX_CHECK_OK(cx_fem_ref_init(&r, t));
    int dim = r.dim, npe = r.npe, nd = dim * npe, ns = cx_fem_nstress(dim);
    cx_mesh *m = fx_mesh(t, 0);
    if (!m) {
        CX_CHECK(m != NULL);
        return;
    }
    /* element 4: inside the mesh, distorted */
    double xe[3 * CX_FEM_MAXNPE], D[36], Ke[CX_FEM_MAXDOF * CX_FEM_MAXDOF] = {0},
           ref[CX_FEM_MAXDOF * CX_FEM_MAXDOF] = {0};
    for (int a = 0; a < npe; a++)
        for (int i = 0; i < dim; i++)
            xe[dim * a + i] = m->x[dim * m->conn[npe * 4 + a] + i];
    for (int i = 0; i < ns; i++)
        for (int j = 0; j <= i; j++)
            D[ns * i + j] = D[ns * j + i] = (i == j ? 4 : 0) + fx_rand();
    CX_CHECK_OK(cx_fem_element_stiffness(t, xe, D, Ke));
    for (int q = 0; q < r.nq; q++) {
        double J[9] = {0}, Ji[9], G[3 * CX_FEM_MAXNPE], B[6 * CX_FEM_MAXDOF], det;
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++)
                for (int k = 0; k < dim; k++)
                    J[dim * i + k] += xe[dim * a + i] * r.dNq[q][dim * a + k];
        if (dim == 2) {
            det = J[0] * J[3] - J[1] * J[2];
            Ji[0] = J[3] / det, Ji[1] = -J[1] / det, Ji[2] = -J[2] / det, Ji[3] = J[0] / det;
        } else {
            /* Ji = adj(J) / det, adj the transposed cofactors */
            for (int i = 0; i < 3; i++)
                for (int k = 0; k < 3; k++) {
                    int i1 = (i + 1) % 3, i2 = (i + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
                    Ji[3 * k + i] = J[3 * i1 + k1] * J[3 * i2 + k2] - J[3 * i1 + k2] * J[3 * i2 + k1];
                }
            det = J[0] * Ji[0] + J[1] * Ji[3] + J[2] * Ji[6];
            for (int k = 0; k < 9; k++)
                Ji[k] /= det;
        }
        for (int a = 0; a < npe; a++)
            for (int i = 0; i < dim; i++) {
                G[dim * a + i] = 0;
                for (int k = 0; k < dim; k++)
                    G[dim * a + i] += r.dNq[q][dim * a + k] * Ji[dim * k + i];
            }
        cx_fem_strain_matrix(dim, npe, G, B);
        for (int i = 0; i < nd; i++)
            for (int j = 0; j < nd; j++) {
                double v = 0;
                for (int k = 0; k < ns; k++)
                    for (int l = 0; l < ns; l++)
                        v += B[nd * k + i] * D[ns * k + l] * B[nd * l + j];
                ref[nd * i + j] += r.w[q] * det * v;
            }
    }
    double err = 0, big = 0, asym = 0;
    for (int k = 0; k < nd * nd; k++) {
        err = fmax(err, fabs(Ke[k] - ref[k]));
        big = fmax(big, fabs(ref[k]));
        asym = fmax(asym, fabs(Ke[k] - Ke[nd * (k % nd) + k / nd]));
    }
    fprintf(stderr, "%s kernel: max |Ke - dense B'DB| = %.3g of %.3g\n", cx_elem_name(t), err, big);
    CX_CHECK_NEAR(err, 0, 0, 1e-14 * big);
    CX_CHECK(asym == 0);
    cx_mesh_destroy(&m);
}

int main(void)
{
    long live = cx_alloc_live();
    test_types();
    test_masonry();
    test_lonely_node();
    cx_elem_type types[5] = {CX_EL_TRI3, CX_EL_TRI6, CX_EL_QUAD4, CX_EL_TET4, CX_EL_HEX8};
    for (int k = 0; k < 5; k++)
        test_kernel(types[k]);
    CX_CHECK(cx_alloc_live() == live);
    return check_finish("fem_assemble_csc");
}
