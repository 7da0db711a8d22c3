/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The assembled K, bit for bit: any change to the kernels, the pattern or
 * the scatter (inlining, another optimisation level, a new loop order)
 * must leave every stored entry's bits as they were. The Hertz fan (N = 8:
 * 128 TRI3; N = 4 for TRI6 and QUAD4), the distorted meshes of every type
 * and a HEX8 / TET4 brick are assembled over all dofs and over the free
 * dofs of a Dirichlet map with non-zero prescribed values; a 64-bit hash
 * of K's p, i and x (and of fd) must equal the one the assembly gave
 * before the kernels moved into fem/element_impl.h (the hashes below,
 * printed by this test when they differ). The hash sees every bit: a
 * single flipped last bit of one entry changes it (checked too). */
#include "fem/fem.h"
#include "fem_fixture.h"
#include "check.h"

#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* FNV-1a over bytes, continued from h */
static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const unsigned char *b = data;
    for (size_t k = 0; k < n; k++) {
        h ^= b[k];
        h *= 0x100000001b3ull;
    }
    return h;
}

#define FNV0 0xcbf29ce484222325ull

static uint64_t hash_csc(const cx_csc *K)
{
    uint64_t h = fnv(FNV0, &K->nrow, sizeof K->nrow);
    h = fnv(h, K->p, sizeof(int) * (size_t)(K->ncol + 1));
    h = fnv(h, K->i, sizeof(int) * cx_csc_nnz(K));
    return fnv(h, K->x, sizeof(double) * cx_csc_nnz(K));
}

typedef struct expect {
    const char *name;
    uint64_t all, free, fd;
} expect;

/* Assemble m both ways (prescribing the components of the boundaries
 * named in fix: "name:c=value", whole nodes fixed by listing each c) and
 * compare the hashes with e. */
static void check_mesh(cx_mesh *m, cx_model model, const char *const *fix, int nfix, const expect *e)
{
    cx_material mat = fx_material(model);
    cx_material mats[2] = {mat, mat};
    mats[1].E = 70.0;   /* a second body, if any, of another material */
    cx_csc K = {0}, Kf = {0};
    cx_dofmap map = {0};
    cx_diag d = {0};
    int st = cx_fem_assemble_stiffness(m, mats, &K, &d);
    CX_CHECK(st == CX_OK);
    CX_CHECK(cx_dofmap_init(&map, m->dim * m->nnodes) == CX_OK);
    for (int k = 0; k < nfix; k++) {
        char bname[32];
        int c;
        double v;
        CX_CHECK(sscanf(fix[k], "%31[^:]:%d=%lf", bname, &c, &v) == 3);
        const cx_boundary *b = cx_mesh_boundary(m, bname);
        CX_CHECK(b != NULL);
        if (b)
            CX_CHECK(cx_dofmap_fix(&map, m, b, c, v) == CX_OK);
    }
    CX_CHECK(cx_dofmap_finish(&map) == CX_OK);
    double *fd = calloc((size_t)map.nfree + 1, sizeof(double));
    CX_CHECK(cx_fem_assemble_free(m, mats, &map, &Kf, fd, &d) == CX_OK);
    uint64_t h_all = st == CX_OK ? hash_csc(&K) : 0, h_free = hash_csc(&Kf);
    uint64_t h_fd = fnv(FNV0, fd, sizeof(double) * (size_t)map.nfree);
    int same = h_all == e->all && h_free == e->free && h_fd == e->fd;
    CX_CHECK(same);
    if (!same)
        fprintf(stderr, "    {\"%s\", 0x%016" PRIx64 "ull, 0x%016" PRIx64 "ull, 0x%016" PRIx64 "ull},\n",
                e->name, h_all, h_free, h_fd);
    /* the hash sees the last bit of one entry */
    if (cx_csc_nnz(&K) > 0) {
        size_t q = cx_csc_nnz(&K) / 2;
        uint64_t bits;
        memcpy(&bits, &K.x[q], sizeof bits);
        bits ^= 1;
        memcpy(&K.x[q], &bits, sizeof bits);
        CX_CHECK(hash_csc(&K) != h_all);
    }
    free(fd);
    cx_dofmap_clear(&map);
    cx_csc_clear(&K);
    cx_csc_clear(&Kf);
}

static const expect expected[] = {
    {"hertz tri3 8", 0xf9544517eb34f6e9ull, 0x5e135fdd90996ea8ull, 0xf680b98efed1927eull},
    {"hertz tri6 4", 0xda4eda1d0fa0840cull, 0x3c6d9cc4fe9efbb1ull, 0x0d14152abd76b1c9ull},
    {"hertz quad4 4", 0x71d83af69f20ab2bull, 0xee2efe8e165175e2ull, 0xe3f3afb99ac63511ull},
    {"distorted tri3", 0xd8932c0c2bcee3c8ull, 0x18d555a8a798cdbcull, 0xf42d4d8520af1055ull},
    {"distorted tri6", 0x4676992cba1a3970ull, 0x213863a86aa671f0ull, 0x26e959bd27423a7eull},
    {"distorted quad4", 0xc6bf56af2cd17344ull, 0xb9b818490a0227fcull, 0x2834ee2e40597dafull},
    {"distorted hex8", 0xb6c8accae0d81538ull, 0xc4c127cceb272edeull, 0x6886da4c4506b67dull},
    {"distorted tet4", 0x208c0537e1b62bf6ull, 0x93dcd316bbf2bbc5ull, 0x072615da1e891b3full},
    {"brick hex8", 0x5981c8f6011c7dd5ull, 0x94b19fc9d505ac29ull, 0x89f434b4a0fa0d41ull},
    {"brick tet4", 0xf126631410f0d1fbull, 0xb9744824f5813140ull, 0x28383c875e844be5ull},
};

int main(void)
{
    static const char *const fix_hertz[] = {"axis:0=0", "top:1=-0.01"};
    static const char *const fix_rect[] = {"left:0=0", "left:1=0", "right:0=0.03"};
    static const char *const fix_brick[] = {"zmin:0=0", "zmin:1=0", "zmin:2=0", "xmax:0=0.02",
                                            "zmax:2=-0.01"};
    const cx_elem_type t2[] = {CX_EL_TRI3, CX_EL_TRI6, CX_EL_QUAD4};
    const int n2[] = {8, 4, 4};
    int k = 0;
    for (int t = 0; t < 3; t++, k++) {
        cx_mesh *m = NULL;
        CX_CHECK(cx_mesh_hertz(&m, 8.0, n2[t], t2[t], NULL) == CX_OK);
        if (m)
            check_mesh(m, CX_PLANE_STRAIN, fix_hertz, 2, &expected[k]);
        cx_mesh_destroy(&m);
    }
    const cx_elem_type td[] = {CX_EL_TRI3, CX_EL_TRI6, CX_EL_QUAD4, CX_EL_HEX8, CX_EL_TET4};
    for (int t = 0; t < 5; t++, k++) {
        cx_mesh *m = fx_mesh(td[t], 0);
        CX_CHECK(m != NULL);
        int dim = cx_elem_dim(td[t]);
        if (m)
            check_mesh(m, dim == 3 ? CX_SOLID : CX_PLANE_STRESS, dim == 3 ? fix_brick : fix_rect,
                       dim == 3 ? 5 : 3, &expected[k]);
        cx_mesh_destroy(&m);
    }
    const cx_elem_type t3[] = {CX_EL_HEX8, CX_EL_TET4};
    for (int t = 0; t < 2; t++, k++) {
        cx_mesh *m = NULL;
        double lo[3] = {0, 0, 0}, hi[3] = {2, 1, 1.5};
        CX_CHECK(cx_mesh_brick(&m, lo, hi, 6, 4, 5, t3[t], NULL) == CX_OK);
        if (m)
            check_mesh(m, CX_SOLID, fix_brick, 5, &expected[k]);
        cx_mesh_destroy(&m);
    }
    return check_finish("fem_assemble_bits");
}
