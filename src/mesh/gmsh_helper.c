/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini-mesh: the one program that loads Gmsh. It opens a .geo or a
 * .msh, meshes a .geo at the size the arguments give, and writes the mesh
 * on its standard output in the plain form mesh/gmsh.c reads (described
 * there, "the pipe"). It runs apart from the program that renders because
 * Debian's libgmsh links libGL (through FLTK): in a process that draws
 * through OSMesa the two GL libraries meet and images come out blank with
 * no error. A process of its own also gives every mesh a fresh copy of
 * Gmsh's one global model, so two sessions on two threads cannot share it.
 *
 * Usage: signorini-mesh FILE LEVEL SIZE ORDER RECOMBINE
 *   LEVEL >= 1: a .geo is meshed with every size divided by LEVEL (the
 *   file's own sizes scaled by 1/LEVEL, and at most SIZE/LEVEL if SIZE > 0);
 *   ORDER 1 or 2 (2: TRI6); RECOMBINE 1: quadrilaterals in 2D. A .msh is
 *   read as it is (the other arguments are ignored).
 * Errors: one line on stderr, exit status 1 (2 for a bad usage). */
#include <gmshc.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static FILE *out;


static void die(const char *what)
{
    char *err = NULL;
    int ierr = 0;
    gmshLoggerGetLastError(&err, &ierr);
    if (err && err[0])
        fprintf(stderr, "%s: %s\n", what, err);
    else
        fprintf(stderr, "%s\n", what);
    exit(1);
}

/* The first error Gmsh logged since the logger started, if any: a .geo
 * with a syntax error or a surface that fails to mesh is only logged, the
 * call itself returns no error. */
static void die_on_logged_error(const char *what)
{
    char **log = NULL;
    size_t n = 0;
    int ierr = 0;
    gmshLoggerGet(&log, &n, &ierr);
    for (size_t k = 0; k < n; k++)
        if (strncmp(log[k], "Error", 5) == 0) {
            const char *msg = log[k] + 5;
            while (*msg == ':' || *msg == ' ')
                msg++;
            fprintf(stderr, "%s: %s\n", what, msg);
            exit(1);
        }
    for (size_t k = 0; k < n; k++)
        gmshFree(log[k]);
    gmshFree(log);
}

static void put_i32(int32_t v) { fwrite(&v, sizeof v, 1, out); }
static void put_i64(int64_t v) { fwrite(&v, sizeof v, 1, out); }

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcmp(s + n - k, suffix) == 0;
}

int main(int argc, char **argv)
{
    int ierr = 0;
    if (argc != 6) {
        fprintf(stderr, "usage: signorini-mesh FILE LEVEL SIZE ORDER RECOMBINE\n");
        return 2;
    }
    const char *path = argv[1];
    int level = atoi(argv[2]), order = atoi(argv[4]), recombine = atoi(argv[5]);
    double size = atof(argv[3]);
    if (level < 1 || (order != 1 && order != 2)) {
        fprintf(stderr, "signorini-mesh: bad level or order\n");
        return 2;
    }
    /* the mesh goes to the pipe on fd 1; whatever Gmsh prints goes to stderr */
    int fd = dup(1);
    if (fd < 0 || dup2(2, 1) < 0 || !(out = fdopen(fd, "wb"))) {
        fprintf(stderr, "signorini-mesh: cannot set up the output\n");
        return 1;
    }

    gmshInitialize(0, NULL, 0, &ierr);
    if (ierr)
        die("gmsh: cannot initialise");
    gmshOptionSetNumber("General.Terminal", 0, &ierr);
    gmshOptionSetNumber("General.AbortOnError", 0, &ierr);
    gmshLoggerStart(&ierr);
    int geo = ends_with(path, ".geo");
    if (geo) {
        gmshOptionSetNumber("Mesh.MeshSizeFactor", 1.0 / level, &ierr);
        if (size > 0)
            gmshOptionSetNumber("Mesh.MeshSizeMax", size / level, &ierr);
        gmshOptionSetNumber("Mesh.ElementOrder", order, &ierr);
        if (recombine)
            gmshOptionSetNumber("Mesh.RecombineAll", 1, &ierr);
    }
    gmshOpen(path, &ierr);
    if (ierr)
        die("gmsh cannot read the file");
    die_on_logged_error("gmsh cannot read the file");
    int dim = gmshModelGetDimension(&ierr);
    if (geo) {
        gmshModelMeshGenerate(dim, &ierr);
        if (ierr)
            die("gmsh failed to mesh the geometry");
        die_on_logged_error("gmsh failed to mesh the geometry");
    }

    /* nodes, renumbered 0 .. n-1 in Gmsh's order */
    size_t *tags = NULL, ntags = 0, ncoord = 0, npar = 0;
    double *coord = NULL, *par = NULL;
    gmshModelMeshGetNodes(&tags, &ntags, &coord, &ncoord, &par, &npar, -1, -1, 0, 0, &ierr);
    if (ierr)
        die("gmsh: cannot get the nodes");
    if (ntags == 0) {
        fprintf(stderr, "the file holds no mesh (no nodes)\n");
        return 1;
    }
    size_t maxtag = 0;
    for (size_t k = 0; k < ntags; k++)
        if (tags[k] > maxtag)
            maxtag = tags[k];
    int32_t *index = calloc(maxtag + 1, sizeof *index);
    if (!index) {
        fprintf(stderr, "signorini-mesh: out of memory\n");
        return 1;
    }
    for (size_t k = 0; k <= maxtag; k++)
        index[k] = -1;
    for (size_t k = 0; k < ntags; k++)
        index[tags[k]] = (int32_t)k;

    fwrite("CXMESH01", 1, 8, out);
    put_i32(dim);
    put_i64((int64_t)ntags);
    fwrite(coord, sizeof *coord, 3 * ntags, out);

    /* element blocks of every entity of the model's dimension, one below, and
     * points (physical points name nodes) */
    int *dt = NULL;
    size_t ndt = 0;
    gmshModelGetEntities(&dt, &ndt, -1, &ierr);
    int32_t nblocks = 0;
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1)
            put_i32(nblocks);
        for (size_t k = 0; k < ndt / 2; k++) {
            int edim = dt[2 * k], etag = dt[2 * k + 1];
            if (edim != dim && edim != dim - 1 && edim != 0)
                continue;
            int *types = NULL;
            size_t ntypes = 0, **etags = NULL, *etags_n = NULL, etags_nn = 0, **ntg = NULL,
                   *ntg_n = NULL, ntg_nn = 0;
            gmshModelMeshGetElements(&types, &ntypes, &etags, &etags_n, &etags_nn, &ntg, &ntg_n,
                                     &ntg_nn, edim, etag, &ierr);
            if (ierr)
                die("gmsh: cannot get the elements");
            for (size_t t = 0; t < ntypes; t++) {
                if (etags_n[t] == 0)
                    continue;
                if (pass == 0) {
                    nblocks++;
                    continue;
                }
                int npe = (int)(ntg_n[t] / etags_n[t]);
                put_i32(edim);
                put_i32(etag);
                put_i32(types[t]);
                put_i32(npe);
                put_i32((int32_t)etags_n[t]);
                for (size_t q = 0; q < ntg_n[t]; q++)
                    put_i32(ntg[t][q] <= maxtag ? index[ntg[t][q]] : -1);
            }
            for (size_t t = 0; t < ntypes; t++) {
                gmshFree(etags[t]);
                gmshFree(ntg[t]);
            }
            gmshFree(types);
            gmshFree(etags);
            gmshFree(etags_n);
            gmshFree(ntg);
            gmshFree(ntg_n);
        }
    }

    /* physical groups: dimension, tag, name, entities */
    int *pg = NULL;
    size_t npg = 0;
    gmshModelGetPhysicalGroups(&pg, &npg, -1, &ierr);
    put_i32((int32_t)(npg / 2));
    for (size_t k = 0; k < npg / 2; k++) {
        char *name = NULL;
        int *ent = NULL;
        size_t nent = 0;
        gmshModelGetPhysicalName(pg[2 * k], pg[2 * k + 1], &name, &ierr);
        gmshModelGetEntitiesForPhysicalGroup(pg[2 * k], pg[2 * k + 1], &ent, &nent, &ierr);
        put_i32(pg[2 * k]);
        put_i32(pg[2 * k + 1]);
        int32_t len = name ? (int32_t)strlen(name) : 0;
        put_i32(len);
        fwrite(name ? name : "", 1, (size_t)len, out);
        put_i32((int32_t)nent);
        for (size_t e = 0; e < nent; e++)
            put_i32(ent[e]);
        gmshFree(name);
        gmshFree(ent);
    }
    fwrite("END\n", 1, 4, out);
    if (fflush(out) != 0 || ferror(out)) {
        fprintf(stderr, "signorini-mesh: cannot write the mesh\n");
        return 1;
    }
    gmshFree(pg);
    gmshFree(dt);
    gmshFree(tags);
    gmshFree(coord);
    gmshFree(par);
    free(index);
    gmshFinalize(&ierr);
    return 0;
}
