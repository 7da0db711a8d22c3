/* SPDX-License-Identifier: GPL-3.0-or-later */
/* dirichlet.c: the dof map (init, fix by boundary and component, finish),
 * the reduction K(free, free), f(free) - K(free, fixed) value against a
 * dense computation on an assembled K (sorted CSC columns), the expansion
 * back, refusal of an unfinished map and of bad components, and allocation
 * failures of init and reduce. */
#include "fem/fem.h"
#include "fem_fixture.h"
#include "check.h"

static void test_map(void)
{
    cx_mesh *m = NULL;
    cx_dofmap map;
    CX_CHECK_OK(cx_mesh_rectangle(&m, 0, 0, 2, 1, 2, 1, CX_EL_QUAD4, NULL));
    /* nodes 0 1 2 / 3 4 5; "left" = {0, 3}, "bottom" = {0, 1, 2} */
    CX_CHECK_OK(cx_dofmap_init(&map, 12));
    CX_CHECK(map.nall == 12 && map.nfree == 12);
    for (int k = 0; k < 12; k++)
        CX_CHECK(map.free_of[k] == k && map.all_of[k] == k && map.value[k] == 0);
    CX_CHECK_OK(cx_dofmap_fix(&map, m, cx_mesh_boundary(m, "left"), 0, 0.25));
    CX_CHECK_OK(cx_dofmap_fix(&map, m, cx_mesh_boundary(m, "bottom"), 1, -0.5));
    CX_CHECK(map.nfree == -1);
    CX_CHECK(cx_dofmap_fix(&map, m, cx_mesh_boundary(m, "top"), 2, 1) == CX_EINVAL);
    CX_CHECK(cx_dofmap_fix(&map, m, cx_mesh_boundary(m, "top"), -1, 1) == CX_EINVAL);
    CX_CHECK_OK(cx_dofmap_finish(&map));
    /* prescribed: 0 (0x), 6 (3x), 1 (0y), 3 (1y), 5 (2y) */
    int fixed[12] = {1, 1, 0, 1, 0, 1, 1, 0, 0, 0, 0, 0};
    CX_CHECK(map.nfree == 7);
    for (int k = 0, n = 0; k < 12; k++) {
        if (fixed[k]) {
            CX_CHECK(map.free_of[k] == -1);
        } else {
            CX_CHECK(map.free_of[k] == n && map.all_of[n] == k);
            n++;
        }
    }
    CX_CHECK(map.value[0] == 0.25 && map.value[6] == 0.25 && map.value[1] == -0.5 && map.value[5] == -0.5);
    double u[7] = {1, 2, 3, 4, 5, 6, 7}, uall[12];
    cx_fem_expand(&map, u, uall);
    double want[12] = {0.25, -0.5, 1, -0.5, 2, -0.5, 0.25, 3, 4, 5, 6, 7};
    for (int k = 0; k < 12; k++)
        CX_CHECK(uall[k] == want[k]);
    cx_dofmap_clear(&map);
    CX_CHECK(map.free_of == NULL && map.nall == 0);
    cx_dofmap_clear(&map);   /* twice is fine */
    cx_mesh_destroy(&m);
}

static void test_reduce(void)
{
    cx_mesh *m = fx_mesh(CX_EL_TRI6, 0);
    cx_material mat = fx_material(CX_PLANE_STRAIN);
    cx_csc Kall = {0}, K = {0};
    cx_dofmap map;
    int nall = 2 * m->nnodes;
    CX_CHECK_OK(cx_fem_assemble_stiffness(m, &mat, &Kall, NULL));
    CX_CHECK_OK(cx_dofmap_init(&map, nall));
    CX_CHECK_OK(cx_dofmap_fix(&map, m, cx_mesh_boundary(m, "left"), 0, 0.1));
    CX_CHECK_OK(cx_dofmap_fix(&map, m, cx_mesh_boundary(m, "left"), 1, 0));
    CX_CHECK_OK(cx_dofmap_fix(&map, m, cx_mesh_boundary(m, "right"), 1, -0.2));
    double *fall = malloc(sizeof(double) * (size_t)nall), *f = malloc(sizeof(double) * (size_t)nall);
    for (int k = 0; k < nall; k++)
        fall[k] = fx_rand();
    CX_CHECK(cx_fem_reduce(&Kall, fall, &map, &K, f) == CX_EINVAL);   /* not finished */
    CX_CHECK_OK(cx_dofmap_finish(&map));
    CX_CHECK_OK(cx_fem_reduce(&Kall, fall, &map, &K, f));
    int n = map.nfree;
    CX_CHECK(K.nrow == n && K.ncol == n && n == nall - 7 - 7 - 7);

    double err = 0, ferr = 0, scale = fx_maxabs(&Kall);
    int unsorted = 0;
    for (int j = 0; j < n; j++)
        for (int q = K.p[j] + 1; q < K.p[j + 1]; q++)
            unsorted += K.i[q] <= K.i[q - 1];
    for (int i = 0; i < n; i++) {
        double fi = fall[map.all_of[i]];
        for (int j = 0; j < nall; j++)
            if (map.free_of[j] < 0)
                fi -= cx_csc_get(&Kall, map.all_of[i], j) * map.value[j];
        ferr = fmax(ferr, fabs(f[i] - fi));
        for (int j = 0; j < n; j++)
            err = fmax(err, fabs(cx_csc_get(&K, i, j) - cx_csc_get(&Kall, map.all_of[i], map.all_of[j])));
    }
    CX_CHECK(unsorted == 0);
    CX_CHECK_NEAR(err, 0, 0, 0);
    CX_CHECK_NEAR(ferr, 0, 0, 1e-13 * scale);
    /* every stored entry of Kall(free, free) is kept, no more */
    size_t kept = 0;
    for (int j = 0; j < nall; j++)
        for (int q = Kall.p[j]; q < Kall.p[j + 1]; q++)
            kept += map.free_of[j] >= 0 && map.free_of[Kall.i[q]] >= 0;
    CX_CHECK(cx_csc_nnz(&K) == kept);

    /* allocation failures */
    int points = 0, ok = 0;
    for (long k = 0; k < 100 && !ok; k++) {
        cx_csc K2 = {0};
        long live = cx_alloc_live();
        cx_alloc_fail_after(k);
        int st = cx_fem_reduce(&Kall, fall, &map, &K2, f);
        cx_alloc_fail_after(-1);
        if (st == CX_OK) {
            ok = 1;
            CX_CHECK(cx_csc_nnz(&K2) == kept);
        } else {
            CX_CHECK(st == CX_ENOMEM && K2.p == NULL);
            points++;
        }
        cx_csc_clear(&K2);
        CX_CHECK(cx_alloc_live() == live);
    }
    CX_CHECK(ok && points >= 3);
    cx_dofmap map2;
    cx_alloc_fail_after(1);
    CX_CHECK(cx_dofmap_init(&map2, 10) == CX_ENOMEM);
    cx_alloc_fail_after(-1);
    CX_CHECK(map2.free_of == NULL && map2.all_of == NULL && map2.value == NULL);

    free(fall);
    free(f);
    cx_csc_clear(&Kall);
    cx_csc_clear(&K);
    cx_dofmap_clear(&map);
    cx_mesh_destroy(&m);
}

int main(void)
{
    long live = cx_alloc_live();
    test_map();
    test_reduce();
    CX_CHECK(cx_alloc_live() == live);
    return check_finish("fem_dirichlet");
}
