/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Meshes from Gmsh files (mesh.h, cx_mesh_read_gmsh). Gmsh runs in a
 * process of its own, the helper signorini-mesh (gmsh_helper.c): Debian's
 * libgmsh links libGL, which must never be loaded beside OSMesa (the
 * renderer's images come out blank), and Gmsh keeps one global model,
 * which a process per mesh never shares. The helper writes the mesh on a
 * pipe; this file reads it and makes a cx_mesh of it.
 *
 * The pipe (native byte order, int32 i, int64 l, double d):
 *   "CXMESH01", i model dimension, l nodes, 3 l d coordinates,
 *   i blocks, per block: i entity dim, i entity tag, i Gmsh element type,
 *   i nodes per element, i elements, their node indices (from 0);
 *   i groups, per group: i dim, i tag, i name length, the name, i entities,
 *   their tags; "END\n".
 *
 * From it: the elements of the model's dimension (one type: TRI3, TRI6,
 * QUAD4, TET4 or HEX8), the nodes they use (renumbered in Gmsh's order),
 * bodies (the connected parts: elements sharing nodes), the boundaries
 * (physical groups one dimension down, each facet oriented as in its
 * element, so the outward normal follows) and the regions and points (the
 * other physical groups, in cx_mesh_groups). Gmsh orients a surface's
 * elements by the surface's normal: an entity whose elements all turn
 * clockwise is turned over; an element turning against the others of its
 * entity, or with no area, is an inverted element (an error). */
#define _GNU_SOURCE 1
#include "mesh/mesh_impl.h"
#include "base/data.h"

#include "cx_config.h"

#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

int cx_mesh_have_gmsh(void) { return CX_HAVE_GMSH; }

/* ---- Gmsh element types ------------------------------------------------------ */

static const char *gm_type_name(int t, char *buf, size_t len)
{
    static const struct { int t; const char *name; } names[] = {
        {1, "LINE2"}, {2, "TRI3"}, {3, "QUAD4"}, {4, "TET4"}, {5, "HEX8"}, {6, "PRISM6"},
        {7, "PYRAMID5"}, {8, "LINE3"}, {9, "TRI6"}, {10, "QUAD9"}, {11, "TET10"}, {12, "HEX27"},
        {13, "PRISM18"}, {14, "PYRAMID14"}, {15, "POINT"}, {16, "QUAD8"}, {17, "HEX20"},
        {18, "PRISM15"}, {19, "PYRAMID13"}, {20, "TRI9"}, {21, "TRI10"}, {26, "LINE4"},
        {29, "TET20"}};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (names[k].t == t)
            return names[k].name;
    snprintf(buf, len, "Gmsh type %d", t);
    return buf;
}

/* Our element type of a Gmsh type of dimension dim, or -1. */
static int gm_elem(int t)
{
    switch (t) {
    case 2: return CX_EL_TRI3;
    case 9: return CX_EL_TRI6;
    case 3: return CX_EL_QUAD4;
    case 4: return CX_EL_TET4;
    case 5: return CX_EL_HEX8;
    }
    return -1;
}

static const char *gm_entity_word(int dim)
{
    static const char *const w[] = {"point", "curve", "surface", "volume"};
    return dim >= 0 && dim <= 3 ? w[dim] : "entity";
}

/* ---- the raw mesh from the pipe ------------------------------------------------ */

typedef struct gm_block {
    int edim, etag, type, npe, n;
    const int32_t *conn;
} gm_block;

typedef struct gm_group {
    int dim, tag, nent;
    char name[64];
    const int32_t *ent;
} gm_group;

typedef struct gm_raw {
    int dim;
    int64_t nnodes;
    const double *xyz;
    int nblocks, ngroups;
    gm_block *blocks;
    gm_group *groups;
} gm_raw;

typedef struct gm_reader {
    const unsigned char *p, *end;
    int bad;
} gm_reader;

static const void *gm_take(gm_reader *r, size_t n)
{
    if (r->bad || (size_t)(r->end - r->p) < n) {
        r->bad = 1;
        return NULL;
    }
    const void *q = r->p;
    r->p += n;
    return q;
}

static int32_t gm_i32(gm_reader *r)
{
    int32_t v = 0;
    const void *q = gm_take(r, sizeof v);
    if (q)
        memcpy(&v, q, sizeof v);
    return v;
}

static int gm_parse(const unsigned char *buf, size_t len, gm_raw *raw)
{
    gm_reader r = {buf, buf + len, 0};
    memset(raw, 0, sizeof *raw);
    const char *magic = gm_take(&r, 8);
    if (!magic || memcmp(magic, "CXMESH01", 8) != 0)
        return CX_EIO;
    raw->dim = gm_i32(&r);
    const void *q = gm_take(&r, sizeof(int64_t));
    if (!q)
        return CX_EIO;
    memcpy(&raw->nnodes, q, sizeof raw->nnodes);
    if (raw->nnodes < 1 || raw->nnodes > INT_MAX / 3 ||
        (size_t)raw->nnodes * 3 * sizeof(double) > (size_t)(r.end - r.p))
        return CX_EIO;
    raw->xyz = gm_take(&r, (size_t)raw->nnodes * 3 * sizeof(double));
    /* doubles in a byte buffer: the buffer is malloc'ed and 8 + 4 + 8 bytes in */
    raw->nblocks = gm_i32(&r);
    if (r.bad || raw->nblocks < 0 || raw->nblocks > (1 << 24))
        return CX_EIO;
    raw->blocks = CX_NEW(gm_block, raw->nblocks > 0 ? raw->nblocks : 1);
    if (!raw->blocks)
        return CX_ENOMEM;
    for (int b = 0; b < raw->nblocks; b++) {
        gm_block *k = &raw->blocks[b];
        k->edim = gm_i32(&r), k->etag = gm_i32(&r), k->type = gm_i32(&r);
        k->npe = gm_i32(&r), k->n = gm_i32(&r);
        if (r.bad || k->npe < 1 || k->npe > 64 || k->n < 0 ||
            (size_t)k->n * (size_t)k->npe * 4 > (size_t)(r.end - r.p))
            return CX_EIO;
        k->conn = gm_take(&r, (size_t)k->n * (size_t)k->npe * 4);
        for (size_t a = 0; a < (size_t)k->n * (size_t)k->npe; a++) {
            int32_t v;
            memcpy(&v, (const unsigned char *)k->conn + 4 * a, 4);
            if (v < 0 || v >= raw->nnodes)
                return CX_EIO;
        }
    }
    raw->ngroups = gm_i32(&r);
    if (r.bad || raw->ngroups < 0 || raw->ngroups > (1 << 20))
        return CX_EIO;
    raw->groups = CX_NEW(gm_group, raw->ngroups > 0 ? raw->ngroups : 1);
    if (!raw->groups)
        return CX_ENOMEM;
    for (int g = 0; g < raw->ngroups; g++) {
        gm_group *k = &raw->groups[g];
        k->dim = gm_i32(&r), k->tag = gm_i32(&r);
        int len = gm_i32(&r);
        const char *name = len >= 0 ? gm_take(&r, (size_t)len) : NULL;
        if (!name)
            return CX_EIO;
        snprintf(k->name, sizeof k->name, "%.*s", len < 63 ? len : 63, name);
        k->nent = gm_i32(&r);
        if (r.bad || k->nent < 0 || (size_t)k->nent * 4 > (size_t)(r.end - r.p))
            return CX_EIO;
        k->ent = gm_take(&r, (size_t)k->nent * 4);
    }
    const char *end = gm_take(&r, 4);
    return end && memcmp(end, "END\n", 4) == 0 ? CX_OK : CX_EIO;
}

/* the pipe's doubles sit at any byte offset: read them with memcpy */
static double gm_coord(const gm_raw *raw, int64_t k, int c)
{
    double v;
    memcpy(&v, (const unsigned char *)raw->xyz + sizeof(double) * (size_t)(3 * k + c), sizeof v);
    return v;
}

static int32_t gm_at(const int32_t *a, size_t k)
{
    int32_t v;
    memcpy(&v, (const unsigned char *)a + 4 * k, 4);
    return v;
}

/* ---- running the helper ----------------------------------------------------- */

/* The helper: $SIGNORINI_MESHER; the build tree's for the build tree's
 * code; else libexec/signorini-mesh relative to the installed library or
 * program (as base/data.c finds share/), so a moved prefix finds it. */
static const char *gm_helper(char *buf, size_t len)
{
    const char *env = getenv("SIGNORINI_MESHER");
    if (env && *env)
        return env;
    char self[PATH_MAX];
    int lib, in_build;
    if (!cx_data_self(self, sizeof self, &lib, &in_build) || in_build)
        return CX_MESHER_BUILD;
    const char *rel = lib ? CX_MESHER_FROM_LIBDIR : CX_MESHER_FROM_BINDIR;
    if (rel[0] == '/')
        return rel;
    *strrchr(self, '/') = '\0';
    snprintf(buf, len, "%s/%s", self, rel);
    return buf;
}

typedef struct gm_buf {
    unsigned char *p;
    size_t n, cap;
} gm_buf;

static int gm_append(gm_buf *b, const unsigned char *src, size_t n)
{
    if (b->n + n > b->cap) {
        size_t cap = b->cap ? b->cap : 65536;
        while (cap < b->n + n)
            cap *= 2;
        unsigned char *q = cx_realloc(b->p, cap);
        if (!q)
            return CX_ENOMEM;
        b->p = q, b->cap = cap;
    }
    memcpy(b->p + b->n, src, n);
    b->n += n;
    return CX_OK;
}

/* Run the helper on path; its output in *out, its first error line in err. */
static int gm_run(const char *path, int level, double size, int order, int recombine,
                  gm_buf *out, char *err, size_t errlen, cx_diag *d)
{
    int po[2] = {-1, -1}, pe[2] = {-1, -1}, st = CX_OK;
    char a_level[32], a_size[64], a_order[8], a_rec[8];
    char where[PATH_MAX + 64];
    const char *helper = gm_helper(where, sizeof where);
    snprintf(a_level, sizeof a_level, "%d", level);
    snprintf(a_size, sizeof a_size, "%.17g", size);
    snprintf(a_order, sizeof a_order, "%d", order);
    snprintf(a_rec, sizeof a_rec, "%d", recombine);
    char *argv[] = {(char *)helper, (char *)path, a_level, a_size, a_order, a_rec, NULL};
    err[0] = '\0';
    if (pipe2(po, O_CLOEXEC) != 0 || pipe2(pe, O_CLOEXEC) != 0) {
        st = cx_diag_set(d, CX_EIO, "cannot run the mesher: %s", strerror(errno));
        goto done;
    }
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, po[1], 1);
    posix_spawn_file_actions_adddup2(&fa, pe[1], 2);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    pid_t pid;
    int e = posix_spawn(&pid, helper, &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    close(po[1]), close(pe[1]);
    po[1] = pe[1] = -1;
    if (e != 0) {
        st = cx_diag_set(d, CX_EIO, "cannot run the mesher %s: %s", helper, strerror(e));
        goto done;
    }
    size_t elen = 0;
    struct pollfd fds[2] = {{po[0], POLLIN, 0}, {pe[0], POLLIN, 0}};
    int open_fds = 2;
    unsigned char chunk[65536];
    while (open_fds > 0) {
        if (poll(fds, 2, -1) < 0) {
            if (errno == EINTR)
                continue;
            break;
        }
        for (int k = 0; k < 2; k++) {
            if (fds[k].fd < 0 || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR)))
                continue;
            ssize_t r = read(fds[k].fd, chunk, sizeof chunk);
            if (r < 0 && errno == EINTR)
                continue;
            if (r <= 0) {
                fds[k].fd = -1;
                open_fds--;
                continue;
            }
            if (k == 0) {
                if (st == CX_OK && gm_append(out, chunk, (size_t)r) != CX_OK)
                    st = CX_ENOMEM;   /* keep reading so the helper can end */
            } else {
                size_t take = (size_t)r < errlen - 1 - elen ? (size_t)r : errlen - 1 - elen;
                memcpy(err + elen, chunk, take);
                elen += take;
                err[elen] = '\0';
            }
        }
    }
    int ws = 0;
    while (waitpid(pid, &ws, 0) < 0 && errno == EINTR)
        ;
    err[strcspn(err, "\n")] = '\0';
    if (st == CX_ENOMEM) {
        cx_diag_set(d, CX_ENOMEM, "out of memory reading the mesh");
    } else if (WIFSIGNALED(ws)) {
        st = cx_diag_set(d, CX_EEXTERNAL, "the mesher %s ended by signal %d", helper,
                         WTERMSIG(ws));
    } else if (!WIFEXITED(ws) || WEXITSTATUS(ws) != 0) {
        st = CX_EINVAL;   /* the caller says it with err */
        if (!err[0])
            snprintf(err, errlen, "the mesher %.160s failed (exit %d)", helper,
                     WIFEXITED(ws) ? WEXITSTATUS(ws) : -1);
    }
done:
    for (int k = 0; k < 2; k++) {
        if (po[k] >= 0)
            close(po[k]);
        if (pe[k] >= 0)
            close(pe[k]);
    }
    return st;
}

/* ---- from the raw mesh to a cx_mesh -------------------------------------------- */

/* The group of an entity of dimension dim, "" if none. */
static const char *gm_entity_group(const gm_raw *raw, int dim, int tag)
{
    for (int g = 0; g < raw->ngroups; g++)
        if (raw->groups[g].dim == dim)
            for (int e = 0; e < raw->groups[g].nent; e++)
                if (gm_at(raw->groups[g].ent, (size_t)e) == tag)
                    return raw->groups[g].name;
    return "";
}

static int gm_where(const gm_raw *raw, int dim, int tag, char *buf, size_t len)
{
    const char *g = gm_entity_group(raw, dim, tag);
    if (g[0])
        return snprintf(buf, len, "physical group '%s' (%s %d)", g, gm_entity_word(dim), tag);
    return snprintf(buf, len, "%s %d", gm_entity_word(dim), tag);
}

/* Signed measure of an element's corners: 2D twice the area (the
 * shoelace over the corners), 3D six times the volume of the corner
 * tetrahedron at node 0 (for HEX8: nodes 0, 1, 3, 4). */
static double gm_orient(const double *x, int dim, cx_elem_type t, const int *c)
{
    if (dim == 2) {
        int nc = t == CX_EL_QUAD4 ? 4 : 3;
        double a = 0;
        for (int k = 0; k < nc; k++) {
            const double *p = x + 2 * c[k], *q = x + 2 * c[(k + 1) % nc];
            a += p[0] * q[1] - q[0] * p[1];
        }
        return a;
    }
    int i1 = 1, i2 = t == CX_EL_HEX8 ? 3 : 2, i3 = t == CX_EL_HEX8 ? 4 : 3;
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) {
        u[k] = x[3 * c[i1] + k] - x[3 * c[0] + k];
        v[k] = x[3 * c[i2] + k] - x[3 * c[0] + k];
        w[k] = x[3 * c[i3] + k] - x[3 * c[0] + k];
    }
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]);
}

/* Turn an element over: the permutation per type. */
static void gm_flip(cx_elem_type t, int *c)
{
    static const int tri3[] = {0, 2, 1}, tri6[] = {0, 2, 1, 5, 4, 3}, quad4[] = {0, 3, 2, 1},
                     tet4[] = {0, 2, 1, 3}, hex8[] = {0, 3, 2, 1, 4, 7, 6, 5};
    const int *p = t == CX_EL_TRI3 ? tri3 : t == CX_EL_TRI6 ? tri6 : t == CX_EL_QUAD4 ? quad4
                 : t == CX_EL_TET4 ? tet4 : hex8;
    int n = cx_elem_npe(t), tmp[8];
    for (int k = 0; k < n; k++)
        tmp[k] = c[p[k]];
    memcpy(c, tmp, sizeof(int) * (size_t)n);
}

static int gm_find(int *parent, int k)
{
    while (parent[k] != k)
        k = parent[k] = parent[parent[k]];
    return k;
}

/* Facet lookup: sorted corners -> the element facet (oriented) */
typedef struct gm_facet {
    int key[4];
    int nodes[4];   /* as in the element: corners, then the TRI6 mid node */
} gm_facet;

static int gm_facet_cmp(const void *a, const void *b)
{
    const gm_facet *x = a, *y = b;
    for (int k = 0; k < 4; k++)
        if (x->key[k] != y->key[k])
            return x->key[k] < y->key[k] ? -1 : 1;
    return 0;
}

static void gm_sort4(int *k)
{
    for (int i = 1; i < 4; i++)
        for (int j = i; j > 0 && k[j - 1] > k[j]; j--) {
            int t = k[j];
            k[j] = k[j - 1], k[j - 1] = t;
        }
}

/* The boundary groups (dimension dim - 1) into m->bounds, oriented by the
 * element facets. */
static int gm_boundaries(cx_mesh *m, const gm_raw *raw, const int *newnode, const char *path,
                         cx_diag *d)
{
    const int (*local)[4];
    int npf, nlf = cx_elem_facets(m->etype, &local, &npf), st = CX_OK;
    int nb = 0;
    for (int g = 0; g < raw->ngroups; g++)
        nb += raw->groups[g].dim == m->dim - 1;
    if (nb == 0)
        return CX_OK;
    size_t nf = (size_t)m->nelems * (size_t)nlf;
    gm_facet *all = CX_NEW(gm_facet, nf);
    cx_free(m->bounds);   /* cx_mesh_alloc's empty list */
    m->bounds = CX_NEW(cx_boundary, nb);
    if (!all || !m->bounds) {
        cx_free(all);
        return CX_ENOMEM;
    }
    int mid = m->etype == CX_EL_TRI6;
    for (int e = 0; e < m->nelems; e++)
        for (int f = 0; f < nlf; f++) {
            gm_facet *q = &all[(size_t)e * nlf + f];
            for (int a = 0; a < 4; a++) {
                int l = a < npf ? local[f][a] : -1;
                q->key[a] = l >= 0 ? m->conn[m->npe * e + l] : INT_MAX;
                q->nodes[a] = l >= 0 ? m->conn[m->npe * e + l] : -1;
            }
            if (mid)
                q->nodes[2] = m->conn[m->npe * e + local[f][2]];
            gm_sort4(q->key);
        }
    qsort(all, nf, sizeof *all, gm_facet_cmp);

    int bpf = mid ? 3 : npf;   /* nodes per boundary facet */
    for (int g = 0; g < raw->ngroups && st == CX_OK; g++) {
        const gm_group *gr = &raw->groups[g];
        if (gr->dim != m->dim - 1)
            continue;
        if (strlen(gr->name) >= sizeof m->bounds[0].name) {
            st = cx_diag_set(d, CX_EINVAL, "%s: physical group '%s': name too long (at most %d "
                             "characters)", path, gr->name, (int)sizeof m->bounds[0].name - 1);
            break;
        }
        int count = 0;
        for (int b = 0; b < raw->nblocks; b++)
            for (int e = 0; e < gr->nent; e++)
                if (raw->blocks[b].edim == gr->dim && raw->blocks[b].etag == gm_at(gr->ent, (size_t)e))
                    count += raw->blocks[b].n;
        cx_boundary *bd = &m->bounds[m->nbounds];
        if ((st = cx_mesh_alloc_boundary(bd, gr->name, count, bpf)))
            break;
        m->nbounds++;
        int w = 0;
        for (int b = 0; b < raw->nblocks && st == CX_OK; b++) {
            const gm_block *bl = &raw->blocks[b];
            int in = 0;
            for (int e = 0; e < gr->nent; e++)
                in |= bl->edim == gr->dim && bl->etag == gm_at(gr->ent, (size_t)e);
            if (!in)
                continue;
            for (int e = 0; e < bl->n && st == CX_OK; e++) {
                gm_facet key = {{INT_MAX, INT_MAX, INT_MAX, INT_MAX}, {0}};
                int ok = 1;
                for (int a = 0; a < npf && a < bl->npe; a++) {
                    int v = newnode[gm_at(bl->conn, (size_t)e * bl->npe + a)];
                    ok &= v >= 0;
                    key.key[a] = v;
                }
                gm_sort4(key.key);
                const gm_facet *hit = ok ? bsearch(&key, all, nf, sizeof *all, gm_facet_cmp) : NULL;
                if (!hit) {
                    char where[160], tb[32];
                    gm_where(raw, bl->edim, bl->etag, where, sizeof where);
                    st = cx_diag_set(d, CX_EINVAL, "%s: %s: a %s element is not a side of any %s "
                                     "element", path, where, gm_type_name(bl->type, tb, sizeof tb),
                                     cx_elem_name(m->etype));
                    break;
                }
                memcpy(bd->facets + (size_t)w * bpf, hit->nodes, sizeof(int) * (size_t)bpf);
                w++;
            }
        }
    }
    cx_free(all);
    return st;
}

/* The regions (dimension dim) and points (dimension 0) into groups. */
static int gm_groups(const cx_mesh *m, const gm_raw *raw, const int *elem_block_start,
                     const int *newnode, cx_mesh_groups *gs, const char *path, cx_diag *d)
{
    gs->n = 0;
    gs->g = CX_NEW(cx_mesh_group, raw->ngroups > 0 ? raw->ngroups : 1);
    if (!gs->g)
        return CX_ENOMEM;
    for (int g = 0; g < raw->ngroups; g++) {
        const gm_group *gr = &raw->groups[g];
        cx_mesh_group *o = &gs->g[gs->n];
        if (strlen(gr->name) >= sizeof o->name)
            return cx_diag_set(d, CX_EINVAL, "%s: physical group '%s': name too long (at most %d "
                               "characters)", path, gr->name, (int)sizeof o->name - 1);
        memcpy(o->name, gr->name, strlen(gr->name) + 1);   /* its length checked above */
        o->dim = gr->dim;
        gs->n++;
        if (gr->dim != m->dim && gr->dim != 0)
            continue;   /* boundaries: in m->bounds */
        int count = 0;
        for (int pass = 0; pass < 2; pass++) {
            if (pass == 1 && !(o->items = CX_NEW(int, count > 0 ? count : 1)))
                return CX_ENOMEM;
            count = 0;
            for (int b = 0; b < raw->nblocks; b++) {
                const gm_block *bl = &raw->blocks[b];
                int in = 0;
                for (int e = 0; e < gr->nent; e++)
                    in |= bl->edim == gr->dim && bl->etag == gm_at(gr->ent, (size_t)e);
                if (!in)
                    continue;
                for (int e = 0; e < bl->n; e++) {
                    if (pass == 1) {
                        if (gr->dim == 0) {
                            int v = newnode[gm_at(bl->conn, (size_t)e * bl->npe)];
                            if (v < 0)
                                return cx_diag_set(d, CX_EINVAL, "%s: physical point '%s' is "
                                                   "not a node of the mesh", path, gr->name);
                            o->items[count] = v;
                        } else {
                            o->items[count] = elem_block_start[b] + e;
                        }
                    }
                    count++;
                }
            }
        }
        o->count = count;
    }
    return CX_OK;
}

static int gm_build(const gm_raw *raw, const char *path, int want, cx_mesh **mp,
                    cx_mesh_groups *gs, cx_diag *d)
{
    int dim = raw->dim, st = CX_OK, type = -1, nelems = 0, gtype = -1;
    int *newnode = NULL, *start = NULL, *parent = NULL, *root = NULL;
    cx_mesh *m = NULL;
    char where[160], tb[32];
    if (dim != 2 && dim != 3)
        return cx_diag_set(d, CX_EINVAL, "%s: a %dD model (we have 2D and 3D meshes)", path, dim);
    /* one element type over the model's dimension */
    start = CX_NEW(int, raw->nblocks > 0 ? raw->nblocks : 1);
    if (!start)
        return CX_ENOMEM;
    for (int b = 0; b < raw->nblocks; b++) {
        const gm_block *bl = &raw->blocks[b];
        start[b] = -1;
        if (bl->edim != dim)
            continue;
        int t = gm_elem(bl->type);
        gm_where(raw, bl->edim, bl->etag, where, sizeof where);
        if (t < 0 || cx_elem_dim((cx_elem_type)t) != dim) {
            st = cx_diag_set(d, CX_EINVAL, "%s: %s has %s elements: we have TRI3, TRI6, QUAD4, "
                             "TET4, HEX8", path, where, gm_type_name(bl->type, tb, sizeof tb));
            goto fail;
        }
        if (type >= 0 && t != type) {
            char tb2[32];
            st = cx_diag_set(d, CX_EINVAL, "%s: %s has %s elements, others %s: a mesh has one "
                             "element type", path, where, gm_type_name(bl->type, tb, sizeof tb),
                             gm_type_name(gtype, tb2, sizeof tb2));
            goto fail;
        }
        type = t, gtype = bl->type;
        start[b] = nelems;
        nelems += bl->n;
    }
    if (nelems == 0) {
        st = cx_diag_set(d, CX_EINVAL, "%s: no %dD elements in the mesh", path, dim);
        goto fail;
    }
    if (want >= 0 && want != type) {
        st = cx_diag_set(d, CX_EINVAL, "%s: the mesh has %s elements, the scene asks for %s", path,
                         gm_type_name(gtype, tb, sizeof tb), cx_elem_name((cx_elem_type)want));
        goto fail;
    }

    /* the nodes the elements use, in Gmsh's order */
    newnode = CX_NEW(int, raw->nnodes);
    if (!newnode) {
        st = CX_ENOMEM;
        goto fail;
    }
    for (int64_t k = 0; k < raw->nnodes; k++)
        newnode[k] = -1;
    for (int b = 0; b < raw->nblocks; b++)
        if (start[b] >= 0)
            for (size_t a = 0; a < (size_t)raw->blocks[b].n * raw->blocks[b].npe; a++)
                newnode[gm_at(raw->blocks[b].conn, a)] = 0;
    int nn = 0;
    for (int64_t k = 0; k < raw->nnodes; k++)
        if (newnode[k] == 0)
            newnode[k] = nn++;
    if ((st = cx_mesh_alloc(&m, dim, nn, (cx_elem_type)type, nelems, 0)))
        goto fail;
    for (int64_t k = 0; k < raw->nnodes; k++) {
        if (newnode[k] < 0)
            continue;
        for (int c = 0; c < dim; c++)
            m->x[dim * newnode[k] + c] = gm_coord(raw, k, c);
        if (dim == 2 && gm_coord(raw, k, 2) != 0) {
            st = cx_diag_set(d, CX_EINVAL, "%s: a 2D mesh with a node off the plane z = 0 (z = %g)",
                             path, gm_coord(raw, k, 2));
            goto fail;
        }
    }
    /* connectivity, each entity turned to positive orientation */
    for (int b = 0; b < raw->nblocks; b++) {
        const gm_block *bl = &raw->blocks[b];
        if (start[b] < 0)
            continue;
        for (int e = 0; e < bl->n; e++)
            for (int a = 0; a < m->npe; a++)
                m->conn[m->npe * (start[b] + e) + a] = newnode[gm_at(bl->conn, (size_t)e * bl->npe + a)];
        int pos = 0, neg = 0;
        for (int e = 0; e < bl->n; e++) {
            double s = gm_orient(m->x, dim, m->etype, m->conn + m->npe * (start[b] + e));
            pos += s > 0, neg += s < 0;
        }
        int flip = neg > pos;
        for (int e = 0; e < bl->n; e++) {
            int *c = m->conn + m->npe * (start[b] + e);
            if (flip)
                gm_flip(m->etype, c);
            if (!(gm_orient(m->x, dim, m->etype, c) > 0)) {
                gm_where(raw, bl->edim, bl->etag, where, sizeof where);
                st = cx_diag_set(d, CX_EINVAL, "%s: %s: inverted element %d (nodes %d, %d, %d...: "
                                 "its orientation is opposite to its neighbours' or it has no %s)",
                                 path, where, e + 1, c[0] + 1, c[1] + 1, c[2] + 1,
                                 dim == 2 ? "area" : "volume");
                goto fail;
            }
        }
    }
    /* bodies: the connected parts */
    parent = CX_NEW(int, nn);
    root = CX_NEW(int, nn);
    m->body = CX_NEW(int, nelems);
    if (!parent || !root || !m->body) {
        st = CX_ENOMEM;
        goto fail;
    }
    for (int k = 0; k < nn; k++)
        parent[k] = k, root[k] = -1;
    for (int e = 0; e < nelems; e++)
        for (int a = 1; a < m->npe; a++) {
            int p = gm_find(parent, m->conn[m->npe * e]), q = gm_find(parent, m->conn[m->npe * e + a]);
            if (p != q)
                parent[p > q ? p : q] = p < q ? p : q;
        }
    m->nbodies = 0;
    for (int e = 0; e < nelems; e++) {
        int r = gm_find(parent, m->conn[m->npe * e]);
        if (root[r] < 0)
            root[r] = m->nbodies++;
        m->body[e] = root[r];
    }
    if (m->nbodies == 1) {
        cx_free(m->body);
        m->body = NULL;
    }
    if ((st = gm_boundaries(m, raw, newnode, path, d)) ||
        (st = gm_groups(m, raw, start, newnode, gs, path, d)))
        goto fail;
    cx_free(newnode);
    cx_free(start);
    cx_free(parent);
    cx_free(root);
    *mp = m;
    return CX_OK;
fail:
    cx_free(newnode);
    cx_free(start);
    cx_free(parent);
    cx_free(root);
    cx_mesh_destroy(&m);
    cx_mesh_groups_clear(gs);
    if (st == CX_ENOMEM)
        cx_diag_set(d, CX_ENOMEM, "out of memory reading the mesh %s", path);
    return st;
}

int cx_mesh_read_gmsh(cx_mesh **m, cx_mesh_groups *groups, const char *path,
                      const cx_gmsh_options *opt, cx_diag *d)
{
    *m = NULL;
    memset(groups, 0, sizeof *groups);
    if (!CX_HAVE_GMSH)
        return cx_diag_set(d, CX_EUNSUPPORTED, "%s: this build has no Gmsh (meson setup "
                           "-Dgmsh=enabled, with libgmsh-dev)", path);
    if (access(path, R_OK) != 0)
        return cx_diag_set(d, CX_EIO, "%s: cannot read: %s", path, strerror(errno));
    gm_buf out = {0};
    char err[CX_DIAG_LEN / 2];
    int want = opt->element;
    int order = want == CX_EL_TRI6 ? 2 : 1, recombine = want == CX_EL_QUAD4 || want == CX_EL_HEX8;
    int st = gm_run(path, opt->level > 0 ? opt->level : 1, opt->size, order, recombine, &out, err,
                    sizeof err, d);
    if (st == CX_EINVAL)
        st = cx_diag_set(d, CX_EINVAL, "%s: %s", path, err);
    if (st) {
        cx_free(out.p);
        return st;
    }
    gm_raw raw;
    st = gm_parse(out.p, out.n, &raw);
    if (st == CX_EIO)
        cx_diag_set(d, CX_EIO, "%s: the mesher's output is cut short or malformed", path);
    else if (st == CX_OK)
        st = gm_build(&raw, path, want, m, groups, d);
    cx_free(raw.blocks);
    cx_free(raw.groups);
    cx_free(out.p);
    return st;
}

void cx_mesh_groups_clear(cx_mesh_groups *g)
{
    if (g->g)
        for (int k = 0; k < g->n; k++)
            cx_free(g->g[k].items);
    cx_free(g->g);
    memset(g, 0, sizeof *g);
}

const cx_mesh_group *cx_mesh_group_find(const cx_mesh_groups *g, const char *name)
{
    for (int k = 0; k < g->n; k++)
        if (strcmp(g->g[k].name, name) == 0)
            return &g->g[k];
    return NULL;
}
