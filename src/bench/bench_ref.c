/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The reference solution of doc/design.md §3: computed once per scene, level,
 * friction law and value (and stress variant) by the most robust method to
 * kkt < 1e-12, stored on disk under a hash of the parsed scene and those
 * values (bench_ref_key), and read back by the next benchmark run.
 *
 * File: one text line "CXREF 1 n m nt kkt iterations method", then the
 * doubles u (n), lN (m), lT (nt) in the machine's byte order. A file that
 * does not match the problem's sizes is recomputed. */
#include "bench/bench.h"
#include "out/outfile.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The reference method per friction law, most robust first. Add a row when
 * a more robust method lands; a law without a registered row falls back to
 * any registered method that supports the problem. */
static const struct {
    cx_friction law;
    const char *id;
} ref_table[] = {
    {CX_FRICTION_NONE, "ssn-tresca"},
    {CX_FRICTION_TRESCA, "ssn-tresca"},
    {CX_FRICTION_COULOMB, "ssn-coulomb"},
};

#define REF_TOL 1e-12
/* accepted, and flagged in the header, when no method gets below REF_TOL:
 * on fine meshes the round-off floor of the kkt error lies near 1e-11 */
#define REF_TOL_FLOOR 1e-9

/* Candidates in order: the table's rows for the law, then the registry. */
static int ref_candidates(const cx_problem *p, cx_friction law, const cx_method **out, int max)
{
    int n = 0;
    for (size_t k = 0; k < sizeof ref_table / sizeof ref_table[0] && n < max; k++) {
        const cx_method *m = cx_method_find(ref_table[k].id);
        if (ref_table[k].law == law && m && cx_method_check(m, p, law, NULL) == CX_OK)
            out[n++] = m;
    }
    for (int k = 0; k < cx_method_count() && n < max; k++) {
        const cx_method *m = cx_method_at(k);
        int seen = 0;
        for (int j = 0; j < n; j++)
            seen |= out[j] == m;
        if (!seen && cx_method_check(m, p, law, NULL) == CX_OK)
            out[n++] = m;
    }
    return n;
}

const cx_method *bench_ref_method(const cx_problem *p, cx_friction law)
{
    const cx_method *m[1];
    return ref_candidates(p, law, m, 1) ? m[0] : NULL;
}

/* ---- the key: a canonical serialisation of the parsed scene ----------
 *
 * The key is computed from what was parsed, never from the file by its
 * path: a scene read from a pipe (/dev/stdin) has no bytes left to re-read,
 * and a scene changed in memory (bench stress) is not the file. Each field
 * that changes the problem goes into FNV-1a in a fixed order: integers and
 * enums as 64-bit values, doubles by their bit pattern, strings up to and
 * with their NUL, arrays after their count; never pointers or padding, so
 * equal scenes give equal keys whatever the memory held. Left out: the
 * path, id and title, the default and largest level (the level of the run
 * is part of the key), the suited methods and the analytical Hertz data
 * (they change no matrix). */

#define FNV_OFFSET 14695981039346656037ull
#define FNV_PRIME 1099511628211ull

static void key_bytes(uint64_t *h, const void *data, size_t len)
{
    const unsigned char *c = data;
    for (size_t k = 0; k < len; k++) {
        *h ^= c[k];
        *h *= FNV_PRIME;
    }
}

/* little-endian whatever the machine, so a key names the same scene
 * everywhere */
static void key_u64(uint64_t *h, uint64_t v)
{
    unsigned char b[8];
    for (int k = 0; k < 8; k++)
        b[k] = (unsigned char)(v >> (8 * k));
    key_bytes(h, b, sizeof b);
}

static void key_int(uint64_t *h, long long v) { key_u64(h, (uint64_t)v); }

static void key_double(uint64_t *h, double v)
{
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    key_u64(h, bits);
}

static void key_doubles(uint64_t *h, const double *v, int n)
{
    for (int k = 0; k < n; k++)
        key_double(h, v[k]);
}

static void key_ints(uint64_t *h, const int *v, int n)
{
    for (int k = 0; k < n; k++)
        key_int(h, v[k]);
}

static void key_str(uint64_t *h, const char *s, size_t cap)
{
    key_bytes(h, s, strnlen(s, cap));
    key_bytes(h, "", 1);
}

/* A Gmsh scene, pressures or several contacts (issue 24): the mesh file's
 * bytes (an edited .geo is another problem) and the sections only such
 * scenes have; the other scenes keep their keys. */
static void key_scene_file(uint64_t *h, const cx_scene *s)
{
    FILE *f = s->generator == CX_GEN_FILE ? fopen(s->mesh_file, "rb") : NULL;
    unsigned char buf[4096];
    size_t n;
    key_str(h, "mesh file", 16);
    while (f && (n = fread(buf, 1, sizeof buf, f)) > 0)
        key_bytes(h, buf, n);
    if (f)
        fclose(f);
    key_double(h, s->mesh_size);
    key_int(h, s->file_element);
    for (int k = 0; k < s->nmaterials && k < CX_SCENE_MAX_LOADS; k++) {
        key_str(h, s->materials[k].region, CX_SCENE_NAMELEN);
        key_double(h, s->materials[k].mat.E);
        key_double(h, s->materials[k].mat.nu);
        key_int(h, s->materials[k].mat.model);
        key_doubles(h, s->materials[k].body_force, 3);
    }
    for (int k = 0; k < s->npressures && k < CX_SCENE_MAX_LOADS; k++) {
        key_str(h, s->pressures[k].boundary, CX_SCENE_NAMELEN);
        key_double(h, s->pressures[k].p);
    }
    for (int k = 0; k < s->nforces && k < CX_SCENE_MAX_LOADS; k++) {
        key_str(h, s->forces[k].point, CX_SCENE_NAMELEN);
        key_doubles(h, s->forces[k].F, 3);
    }
    for (int k = 1; k < s->ncontacts && k < CX_SCENE_MAX_LOADS; k++) {
        const cx_scene_contact *c = &s->contacts[k];
        key_str(h, c->boundary, CX_SCENE_NAMELEN);
        key_str(h, c->master, CX_SCENE_NAMELEN);
        key_int(h, c->obstacle.kind);
        key_doubles(h, c->obstacle.point, 3);
        key_doubles(h, c->obstacle.normal, 3);
        key_double(h, c->obstacle.radius);
        key_doubles(h, c->obstacle.direction, 3);
        key_double(h, c->slip_bound);
        key_double(h, c->F);
    }
}

static void key_scene(uint64_t *h, const cx_scene *s)
{
    key_str(h, "cx_scene 1", 16);   /* the layout below: change it when fields join */
    key_int(h, s->dim);
    /* [mesh] */
    key_int(h, s->generator);
    key_int(h, s->element);
    key_doubles(h, s->lo, 3);
    key_doubles(h, s->hi, 3);
    key_double(h, s->radius);
    key_ints(h, s->cells, 3);
    key_double(h, s->interface);
    key_ints(h, s->cells_lower, 3);
    key_int(h, s->level_rule);
    key_int(h, s->bond);
    key_double(h, s->gap_h);
    /* [material] */
    key_double(h, s->mat.E);
    key_double(h, s->mat.nu);
    key_int(h, s->mat.model);
    key_doubles(h, s->body_force, 3);
    /* loads and supports */
    int nt = s->ntractions < CX_SCENE_MAX_LOADS ? s->ntractions : CX_SCENE_MAX_LOADS;
    key_int(h, nt);
    for (int k = 0; k < nt; k++) {
        key_str(h, s->tractions[k].boundary, CX_SCENE_NAMELEN);
        key_doubles(h, s->tractions[k].t.t0, 3);
        key_doubles(h, s->tractions[k].t.G, 9);
    }
    int ns = s->nsupports < CX_SCENE_MAX_LOADS ? s->nsupports : CX_SCENE_MAX_LOADS;
    key_int(h, ns);
    for (int k = 0; k < ns; k++) {
        key_str(h, s->supports[k].boundary, CX_SCENE_NAMELEN);
        key_int(h, s->supports[k].comps);
        key_doubles(h, s->supports[k].value, 3);
    }
    /* [contact]: the scene's own law and values too, since the build
     * starts from them before the case sets its own */
    key_str(h, s->contact_boundary, CX_SCENE_NAMELEN);
    key_str(h, s->contact_master, CX_SCENE_NAMELEN);
    key_int(h, s->obstacle.kind);
    key_doubles(h, s->obstacle.point, 3);
    key_doubles(h, s->obstacle.normal, 3);
    key_double(h, s->obstacle.radius);
    key_doubles(h, s->obstacle.direction, 3);
    key_int(h, s->friction);
    key_double(h, s->slip_bound);
    key_double(h, s->F);
    if (s->generator == CX_GEN_FILE || s->npressures > 0 || s->ncontacts > 1)
        key_scene_file(h, s);
}

uint64_t bench_scene_hash(const cx_scene *s)
{
    uint64_t h = FNV_OFFSET;
    key_scene(&h, s);
    return h;
}

uint64_t bench_ref_key(const bench_problem_spec *spec)
{
    uint64_t h = FNV_OFFSET;
    key_scene(&h, spec->scene);
    key_int(&h, spec->level > 0 ? spec->level : spec->scene->level);
    key_int(&h, spec->law);
    key_double(&h, spec->law == CX_FRICTION_NONE ? 0.0 : spec->value);
    key_str(&h, spec->variant ? spec->variant : "", 256);
    return h;
}

const char *bench_ref_origin(const bench_ref *r)
{
    return r->cached ? "cached" : r->kept ? "computed" : "computed, not kept";
}

void bench_ref_clear(bench_ref *r)
{
    free(r->u);
    free(r->lN);
    free(r->lT);
    memset(r, 0, sizeof *r);
}

static int ref_alloc(bench_ref *r, const cx_problem *p)
{
    r->n = p->n;
    r->m = p->m;
    r->nt = p->nt;
    r->u = calloc((size_t)p->n + 1, sizeof(double));
    r->lN = calloc((size_t)p->m + 1, sizeof(double));
    r->lT = calloc((size_t)p->nt + 1, sizeof(double));
    return r->u && r->lN && r->lT ? CX_OK : CX_ENOMEM;
}

/* mkdir -p, then check that dir is a directory we may write in (errno
 * set when not). */
static int ref_mkdir(const char *dir)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", dir);
    for (char *c = buf + 1;; c++) {
        if (*c == '/' || *c == '\0') {
            char keep = *c;
            *c = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return CX_EIO;
            *c = keep;
            if (!keep)
                break;
        }
    }
    struct stat st;
    if (stat(dir, &st) != 0)
        return CX_EIO;
    if (!S_ISDIR(st.st_mode)) {
        errno = ENOTDIR;
        return CX_EIO;
    }
    return access(dir, W_OK | X_OK) == 0 ? CX_OK : CX_EIO;
}

/* The one warning of a cache that fails: the run goes on without it. */
static void ref_cache_off(bench_cache *cache, const char *why)
{
    if (cache->off)
        return;
    cache->off = 1;
    fprintf(stderr, "signorini bench: warning: reference cache %s: %s; references are not kept\n",
            cache->dir[0] ? cache->dir : "(none: neither $XDG_CACHE_HOME nor $HOME is set)", why);
}

static void ref_path(const char *dir, const bench_problem_spec *spec, uint64_t hash, char *path,
                     size_t len)
{
    int level = spec->level > 0 ? spec->level : spec->scene->level;
    snprintf(path, len, "%s/%s-L%d-%016llx.ref", dir, spec->scene->id, level,
             (unsigned long long)hash);
}

static int ref_read(const char *path, const cx_problem *p, bench_ref *r)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return CX_EIO;
    int n, m, nt, iters, ok = 0;
    double kkt;
    char method[CX_SCENE_NAMELEN];
    if (fscanf(f, "CXREF 1 %d %d %d %lg %d %31s", &n, &m, &nt, &kkt, &iters, method) == 6 &&
        fgetc(f) == '\n' && n == p->n && m == p->m && nt == p->nt && ref_alloc(r, p) == CX_OK &&
        fread(r->u, sizeof(double), (size_t)n, f) == (size_t)n &&
        fread(r->lN, sizeof(double), (size_t)m, f) == (size_t)m &&
        fread(r->lT, sizeof(double), (size_t)nt, f) == (size_t)nt && fgetc(f) == EOF &&
        cx_vec_finite(n, r->u) && cx_vec_finite(m, r->lN) && cx_vec_finite(nt, r->lT)) {
        ok = 1;
        r->kkt = kkt;
        r->iterations = iters;
        snprintf(r->method, sizeof r->method, "%s", method);
    }
    fclose(f);
    if (!ok)
        bench_ref_clear(r);
    return ok ? CX_OK : CX_EIO;
}

static int ref_write(const char *path, const bench_ref *r, cx_diag *d)
{
    cx_outfile o;
    CX_TRY(cx_outfile_open(&o, path, d));
    FILE *f = o.f;
    fprintf(f, "CXREF 1 %d %d %d %.17g %d %s\n", r->n, r->m, r->nt, r->kkt, r->iterations, r->method);
    fwrite(r->u, sizeof(double), (size_t)r->n, f);
    fwrite(r->lN, sizeof(double), (size_t)r->m, f);
    fwrite(r->lT, sizeof(double), (size_t)r->nt, f);
    return cx_outfile_close(&o, 1, d);
}

/* Solve p with the candidates in turn until one reaches REF_TOL; keep the
 * best run below REF_TOL_FLOOR otherwise (a run that stops on its own
 * criterion above REF_TOL goes on to the kkt tolerance, and one that then
 * stalls at the rounding floor is still good). */
static int ref_compute(const bench_problem_spec *spec, const cx_problem *p, double time_limit,
                       bench_ref *r, cx_diag *d)
{
    const cx_method *cand[16];
    int nc = ref_candidates(p, spec->law, cand, 16);
    if (nc == 0)
        return cx_diag_set(d, CX_EUNSUPPORTED, "no registered method solves %s friction here",
                           cx_friction_name(spec->law));
    cx_options opt;
    cx_options_default(&opt);
    opt.tol = REF_TOL;
    opt.max_iter = 2000;
    opt.time_limit = time_limit;
    double best = INFINITY;
    char why[CX_DIAG_LEN] = "";
    for (int k = 0; k < nc && best > REF_TOL && !bench_interrupted(); k++) {
        cx_session *s = NULL;
        cx_diag local;
        int st = bench_session(spec, &s, NULL, &local);
        if (st == CX_OK)
            st = cx_session_set_method(s, cand[k], NULL, &opt, &local);
        if (st == CX_OK)
            st = bench_solve_watched(s, bench_observer, NULL, &local);
        const cx_iterate *it = s ? cx_session_iterate(s) : NULL;
        if (st == CX_OK && it->reason == CX_STOPPED_OWN) {
            /* a loose own criterion (cf-fp's 1e-4): go on to the kkt tolerance */
            cx_options more = opt;
            more.own_stop = 0;
            cx_session_set_options(s, &more);
            st = bench_solve_watched(s, bench_observer, NULL, &local);
        }
        int usable = it && it->reason != CX_DIVERGED_NAN && it->reason != CX_DIVERGED_BREAKDOWN;
        if (st == CX_OK && usable && it->kkt < best && it->kkt <= REF_TOL_FLOOR) {
            bench_ref_clear(r);
            if (ref_alloc(r, p) != CX_OK) {
                cx_session_destroy(&s);
                return cx_diag_set(d, CX_ENOMEM, "out of memory");
            }
            memcpy(r->u, it->u, sizeof(double) * (size_t)p->n);
            memcpy(r->lN, it->lN, sizeof(double) * (size_t)p->m);
            memcpy(r->lT, it->lT, sizeof(double) * (size_t)p->nt);
            r->kkt = best = it->kkt;
            r->iterations = it->iter;
            r->work = it->counters;
            snprintf(r->method, sizeof r->method, "%s", cand[k]->id);
        } else if (!why[0]) {
            if (st != CX_OK)
                snprintf(why, sizeof why, "%s: %s", cand[k]->id, cx_diag_msg(&local, st));
            else {
                char outcome[CX_DIAG_LEN];
                snprintf(why, sizeof why, "%s: %s", cand[k]->id,
                         cx_session_outcome(s, outcome, sizeof outcome));
            }
        }
        cx_session_destroy(&s);
    }
    if (!isfinite(best))
        return cx_diag_set(d, CX_ENUMERIC, "no reference solution (%s)", why[0] ? why : "interrupted");
    return CX_OK;
}

int bench_ref_get(bench_cache *cache, const bench_problem_spec *spec, const cx_problem *p,
                  double time_limit, bench_ref *r, cx_diag *d)
{
    memset(r, 0, sizeof *r);
    char path[700]; /* dir (512) + name */
    uint64_t hash = bench_ref_key(spec);
    if (!cache->off && !cache->dir[0])
        ref_cache_off(cache, "no directory");
    if (!cache->off && ref_mkdir(cache->dir) != CX_OK)
        ref_cache_off(cache, strerror(errno));
    if (!cache->off) {
        ref_path(cache->dir, spec, hash, path, sizeof path);
        r->cached = ref_read(path, p, r) == CX_OK;
    }
    if (!r->cached) {
        CX_TRY(ref_compute(spec, p, time_limit, r, d));
        cx_diag wd;
        cx_diag_clear(&wd);
        if (!cache->off && ref_write(path, r, &wd) != CX_OK)
            ref_cache_off(cache, "cannot write in it");
    }
    r->kept = !cache->off;
    r->hash = hash;
    double *w = malloc(sizeof(double) * ((size_t)p->n + 1));
    if (!w) {
        bench_ref_clear(r);
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    }
    cx_csc_gemv(&p->K, 1.0, r->u, 0.0, w);
    double q = cx_vec_dot(p->n, r->u, w);
    free(w);
    r->uK = sqrt(q > 0 ? q : 0);
    double l2 = 0;
    for (int i = 0; i < p->m; i++)
        l2 += r->lN[i] * r->lN[i];
    for (int i = 0; spec->law != CX_FRICTION_NONE && i < p->nt; i++)
        l2 += r->lT[i] * r->lT[i];
    r->lnorm = sqrt(l2);
    return CX_OK;
}
