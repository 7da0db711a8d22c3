/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Reading a scene file (scene.h). inih splits the file into sections and
 * key = value pairs; every key is checked against the key table of its
 * section (ld_sections below) and the values fill a cx_scene.
 *
 * Debian's inih is built without INI_HANDLER_LINENO, so the handler gets no
 * line numbers: ld_read, the reader given to ini_parse_stream, counts lines
 * (inih calls the handler right after the reader returns the key's line).
 * The reader also spots the [section] headers itself, because inih reports
 * nothing for a header: that is how a section with no keys, a section given
 * twice and the header line of a missing key are known.
 *
 * The values of a section are kept until the section ends and then checked
 * together, since some depend on each other (generator and lo/hi, obstacle
 * and radius); boundary names are checked once the generator is known. The
 * first error wins and ends the stream (the reader returns EOF); inih's own
 * syntax errors are compared by line with ours.
 *
 * The file is read whole into memory first (a regular file or a pipe, at
 * most LD_MAXFILE bytes), so that a device such as /dev/zero or an endless
 * pipe ends at once; the reader then checks every byte of a line before
 * inih sees it: a NUL would end inih's line early and hide the rest (read
 * "E = 20\0 00" as E = 20, skip a line starting with one), and a control
 * character is never part of a scene. */
#include "scene/scene.h"

#include <ini.h>

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define LD_MAXFILE (1 << 20)     /* 1 MiB: a scene is a page or two of text */
#define LD_MAXLINE 4096          /* ini_max_line: longest line + 3 */
#define LD_MAXKEYS 16            /* keys of the largest section */
#define LD_VALLEN 1024           /* longest value + 1 */
#define LD_COUNT_MAX 1000000     /* largest level or cell count */
#define LD_LEVEL_MAX_DEFAULT 4096
/* Every real value lies within [-LD_BIG, LD_BIG], and the positive scales
 * (E, radii, P, R) at or above LD_TINY: far outside any physical range in
 * any units, and narrow enough that the products of a build (E h, t G x
 * area, |f| / E) stay finite, so that an absurd value is refused here with
 * its key rather than as an Inf or a NaN in K, f or the solution. */
#define LD_BIG 1e30
#define LD_TINY 1e-30

/* The choice lists below are read as indices into these enums. */
_Static_assert(CX_EL_TRI3 == 0 && CX_EL_TRI6 == 1 && CX_EL_QUAD4 == 2 && CX_EL_HEX8 == 3 &&
               CX_EL_TET4 == 4, "ld_elements follows cx_elem_type");
_Static_assert(CX_PLANE_STRAIN == 0 && CX_PLANE_STRESS == 1 && CX_SOLID == 2,
               "ld_models follows cx_model");
_Static_assert(CX_OBST_PLANE == 0 && CX_OBST_DISC == 1 && CX_OBST_CYLINDER == 2 &&
               CX_OBST_SPHERE == 3, "ld_obstacles follows cx_obstacle_kind");
_Static_assert(CX_FRICTION_NONE == 0 && CX_FRICTION_TRESCA == 1 && CX_FRICTION_COULOMB == 2,
               "ld_frictions follows cx_friction");
_Static_assert(CX_LEVEL_LINEAR == 0 && CX_LEVEL_SQRT2 == 1, "ld_level_rules follows cx_level_rule");
_Static_assert(CX_GEN_RECTANGLE == 0 && CX_GEN_HERTZ == 1 && CX_GEN_BRICK == 2 &&
               CX_GEN_TWOBLOCKS == 3 && CX_GEN_MASONRY == 4 && CX_GEN_FILE == 5,
               "ld_generators follows cx_scene_generator");

static const char ld_generators[] = "rectangle|hertz|brick|twoblocks|masonry";
static const char *const ld_generator_name[] = {"rectangle", "hertz", "brick", "twoblocks", "masonry",
                                               "file"};
static const int ld_generator_dim[] = {2, 2, 3, 2, 2, 0};
/* the boundary names of each generator's mesh (mesh.h) */
static const char *const ld_boundaries[] = {
    "left|right|bottom|top", "top|axis|arc|side|quarter", "xmin|xmax|ymin|ymax|zmin|zmax",
    "left1|right1|bottom1|top1|left2|right2|bottom2|top2",
    "left|right|top|settle|base|joints", ""};
static const char ld_bonds[] = "stack|running|laminae";
_Static_assert(CX_BOND_STACK == 0 && CX_BOND_RUNNING == 1 && CX_BOND_LAMINAE == 2,
               "ld_bonds follows cx_bond");
static const char ld_elements[] = "tri3|tri6|quad4|hex8|tet4";
static const char ld_models[] = "plane_strain|plane_stress|solid";
static const char ld_obstacles[] = "plane|disc|cylinder|sphere";
static const char ld_frictions[] = "none|tresca|coulomb";
static const char *ld_frictions_name(int k)
{
    static const char *const names[] = {"none", "tresca", "coulomb"};
    return k >= 0 && k < 3 ? names[k] : "?";
}
static const char ld_level_rules[] = "linear|sqrt2";
static const char ld_fixes[] = "x|y|z|xy|xz|yz|xyz|all";
static const unsigned ld_fix_comps[] = {1, 2, 4, 3, 5, 6, 7, 7};

typedef struct ld_state ld_state;

typedef struct ld_key {
    const char *name;
    int required;               /* always required (others may be, by context) */
} ld_key;

typedef struct ld_secdef {
    const char *name;
    int named;                  /* [traction NAME]: several, each named (2: the name is
                                   optional, [contact] and [contact NAME]) */
    int required;               /* every scene has it */
    const ld_key *keys;         /* terminated by a NULL name */
    int (*finish)(ld_state *L); /* check the values, fill the scene */
} ld_secdef;

/* The section being read: its values, kept until it ends. */
typedef struct ld_section {
    const ld_secdef *def;       /* NULL before the first header and after the last */
    char name[CX_SCENE_NAMELEN];/* NAME of [traction NAME] */
    int line;                   /* of the header */
    int key_line[LD_MAXKEYS];   /* per key of def->keys: its line, 0 if absent */
    char value[LD_MAXKEYS][LD_VALLEN];
} ld_section;

/* A boundary name given in the file, checked once the generator is known. */
typedef struct ld_bname {
    const char *name;           /* in the scene */
    int line;
    const char *key;
    cx_scene_ref_kind kind;     /* for a Gmsh mesh: what the group must be */
} ld_bname;

#define LD_NSECDEFS 11
#define LD_NBNAMES CX_SCENE_MAX_REFS

struct ld_state {
    cx_scene *s;
    const char *path;
    const char *text;           /* the whole file, len bytes */
    size_t len, pos;            /* pos: the next line's first byte */
    int line;                   /* lines read: the line inih is working on */
    int status;                 /* first error, CX_OK if none */
    int order;                  /* the line by which to compare it with inih's errors */
    char msg[CX_DIAG_LEN];
    ld_section sec;
    int nheaders;               /* section headers read */
    int nseen[LD_NSECDEFS];     /* sections of each kind read */
    char seen_name[LD_NSECDEFS][CX_SCENE_MAX_LOADS][CX_SCENE_NAMELEN];
    int seen_line[LD_NSECDEFS][CX_SCENE_MAX_LOADS];
    int has_generator;          /* [mesh] read: boundary names can be checked */
    int piped;                  /* read from a pipe: a mesh file is relative to the working
                                   directory, not to the scene's folder */
    int nbnames, nbchecked;
    ld_bname bnames[LD_NBNAMES];
};

/* ---- errors ---------------------------------------------------------------- */

#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static int ld_error(ld_state *L, int line, int order, const char *fmt, ...)
{
    if (L->status == CX_OK) {
        char text[CX_DIAG_LEN];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(text, sizeof text, fmt, ap);
        va_end(ap);
        snprintf(L->msg, sizeof L->msg, "%s:%d: %.*s", L->path, line, CX_DIAG_LEN / 2, text);
        L->status = CX_EINVAL;
        L->order = order;
    }
    return CX_EINVAL;
}

/* "[traction top]" or "[mesh]" */
static const char *ld_secname(const ld_state *L, char *buf, size_t len)
{
    if (L->sec.name[0])
        snprintf(buf, len, "[%s %s]", L->sec.def->name, L->sec.name);
    else
        snprintf(buf, len, "[%s]", L->sec.def->name);
    return buf;
}

/* ---- the values of the current section ------------------------------------ */

static int ld_index(const ld_state *L, const char *key)
{
    for (int i = 0; L->sec.def->keys[i].name; i++)
        if (strcmp(L->sec.def->keys[i].name, key) == 0)
            return i;
    return -1;
}

static const char *ld_value(const ld_state *L, const char *key)
{
    int i = ld_index(L, key);
    return i >= 0 && L->sec.key_line[i] ? L->sec.value[i] : NULL;
}

static int ld_key_line(const ld_state *L, const char *key)
{
    int i = ld_index(L, key);
    return i >= 0 ? L->sec.key_line[i] : 0;
}

/* An error about a given key: "PATH:LINE: key 'E': ..." */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static int ld_bad(ld_state *L, const char *key, const char *fmt, ...)
{
    char text[CX_DIAG_LEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    int line = ld_key_line(L, key);
    return ld_error(L, line, line, "key '%s': %.*s", key, CX_DIAG_LEN / 2, text);
}

/* A missing key is found when its section ends (at line L->line + 1 at
 * the latest), but is reported at the section's header. */
static int ld_require(ld_state *L, const char *key)
{
    if (ld_value(L, key))
        return CX_OK;
    char sec[80];
    return ld_error(L, L->sec.line, L->line + 1, "section %s: missing key '%s'",
                    ld_secname(L, sec, sizeof sec), key);
}

static int ld_unused(ld_state *L, const char *key, const char *what)
{
    if (!ld_value(L, key))
        return CX_OK;
    return ld_bad(L, key, "not used %s", what);
}

/* |x| <= LD_BIG, and x >= LD_TINY for a positive scale. */
static int ld_range(ld_state *L, const char *key, double x, int positive)
{
    if (fabs(x) > LD_BIG || (positive && x < LD_TINY))
        return ld_bad(L, key, "%g is out of range (expected %s%g to %g; rescale the units)", x,
                      positive ? "a value from " : "-", positive ? LD_TINY : LD_BIG, LD_BIG);
    return CX_OK;
}

/* A number in the interval (lo, hi) if open, else [lo, hi]. Absent keys
 * keep *out (its default). */
static int ld_real(ld_state *L, const char *key, double lo, double hi, int open,
                   const char *expect, double *out)
{
    const char *v = ld_value(L, key);
    double x;
    if (!v)
        return CX_OK;
    if (cx_parse_double(v, &x) != 0 || (open ? !(x > lo && x < hi) : !(x >= lo && x <= hi)))
        return ld_bad(L, key, "expected %s", expect);
    CX_TRY(ld_range(L, key, x, lo == 0 && open));
    *out = x;
    return CX_OK;
}

static int ld_positive(ld_state *L, const char *key, double *out)
{
    return ld_real(L, key, 0, INFINITY, 1, "a positive number", out);
}

static int ld_nonnegative(ld_state *L, const char *key, double *out)
{
    return ld_real(L, key, 0, INFINITY, 0, "a number >= 0", out);
}

/* Exactly n numbers (n <= 9); what says what they are (NULL: a vector). */
static int ld_vector(ld_state *L, const char *key, int n, const char *what, double *out)
{
    const char *v = ld_value(L, key);
    double x[9];
    if (!v)
        return CX_OK;
    if (cx_parse_doubles(v, x, n) != n) {
        if (what)
            return ld_bad(L, key, "expected %d numbers%s", n, what);
        return ld_bad(L, key, "expected %d numbers (dim %d)", n, L->s->dim);
    }
    for (int k = 0; k < n; k++)
        CX_TRY(ld_range(L, key, x[k], 0));
    memcpy(out, x, (size_t)n * sizeof *x);
    return CX_OK;
}

/* Exactly n integers in [min, max] (n <= 3). */
static int ld_ints(ld_state *L, const char *key, int n, long min, long max, const char *expect,
                   int *out)
{
    const char *v = ld_value(L, key);
    int x[3], k = 0;
    if (!v)
        return CX_OK;
    for (const char *p = v;;) {
        while (isspace((unsigned char)*p))
            p++;
        if (!*p)
            break;
        size_t len = strcspn(p, " \t\r\n");
        char word[32];
        long w;
        if (k == n || len >= sizeof word)
            return ld_bad(L, key, "expected %s", expect);
        memcpy(word, p, len);
        word[len] = '\0';
        if (cx_parse_int(word, min, max, &w) != 0)
            return ld_bad(L, key, "expected %s", expect);
        x[k++] = (int)w;
        p += len;
    }
    if (k != n)
        return ld_bad(L, key, "expected %s", expect);
    memcpy(out, x, (size_t)n * sizeof *x);
    return CX_OK;
}

static int ld_int(ld_state *L, const char *key, long min, long max, const char *expect, int *out)
{
    return ld_ints(L, key, 1, min, max, expect, out);
}

/* One word of choices whose index is in [first, last]. */
static int ld_choice(ld_state *L, const char *key, const char *choices, int first, int last,
                     const char *expect, int *out)
{
    const char *v = ld_value(L, key);
    if (!v)
        return CX_OK;
    int k = cx_parse_choice(v, choices);
    if (k < first || k > last)
        return ld_bad(L, key, "expected %s", expect);
    *out = k;
    return CX_OK;
}

/* Exactly dim numbers, not all zero, scaled to unit length. */
static int ld_direction(ld_state *L, const char *key, double *out)
{
    const char *v = ld_value(L, key);
    int dim = L->s->dim;
    double x[3] = {0, 0, 0}, n2 = 0;
    if (!v)
        return CX_OK;
    if (cx_parse_doubles(v, x, dim) != dim)
        return ld_bad(L, key, "expected %d numbers, not all zero", dim);
    for (int k = 0; k < dim; k++)
        CX_TRY(ld_range(L, key, x[k], 0));
    for (int k = 0; k < dim; k++)
        n2 += x[k] * x[k];
    if (!(n2 > 0) || !isfinite(n2))
        return ld_bad(L, key, "expected %d numbers, not all zero", dim);
    for (int k = 0; k < dim; k++)
        out[k] = x[k] / sqrt(n2);
    return CX_OK;
}

static int ld_is_word(const char *t, int lower_only)
{
    size_t n = 0;
    for (; t[n]; n++) {
        unsigned char c = (unsigned char)t[n];
        if (!(islower(c) || isdigit(c) || c == '_' || c == '-' || (!lower_only && isupper(c))))
            return 0;
    }
    return n > 0 && n < CX_SCENE_NAMELEN;
}

/* A name of a boundary (region, point) given by key, checked against the
 * generator later (ld_check_boundaries), or for a Gmsh mesh when it is
 * built (the scene's refs). */
static int ld_group(ld_state *L, const char *key, cx_scene_ref_kind kind, char *dst)
{
    const char *v = ld_value(L, key);
    if (strlen(v) >= CX_SCENE_NAMELEN)
        return ld_bad(L, key, "unknown %s '%.40s...'", kind == CX_REF_BOUNDARY ? "boundary"
                      : kind == CX_REF_REGION ? "region" : "point", v);
    if (L->nbnames == LD_NBNAMES)
        return ld_bad(L, key, "too many names of boundaries, regions and points (at most %d)",
                      LD_NBNAMES);
    strcpy(dst, v);
    L->bnames[L->nbnames] = (ld_bname){dst, ld_key_line(L, key), key, kind};
    L->nbnames++;
    return CX_OK;
}

static int ld_boundary(ld_state *L, char *dst)
{
    return ld_group(L, "boundary", CX_REF_BOUNDARY, dst);
}

static int ld_check_boundaries(ld_state *L)
{
    int g = L->s->generator;
    cx_scene *s = L->s;
    for (; L->nbchecked < L->nbnames; L->nbchecked++) {
        const ld_bname *b = &L->bnames[L->nbchecked];
        if (g == CX_GEN_FILE) {
            cx_scene_ref *r = &s->refs[s->nrefs++];
            snprintf(r->name, sizeof r->name, "%s", b->name);
            snprintf(r->key, sizeof r->key, "%s", b->key);
            r->line = b->line;
            r->kind = b->kind;
            continue;
        }
        if (b->kind != CX_REF_BOUNDARY)
            return ld_error(L, b->line, b->line, "key '%s': regions and points are physical "
                            "groups of a Gmsh mesh ([mesh] file = NAME.geo or NAME.msh)", b->key);
        if (cx_parse_choice(b->name, ld_boundaries[g]) < 0)
            return ld_error(L, b->line, b->line,
                            "key 'boundary': unknown boundary '%s' of generator %s (expected %s)",
                            b->name, ld_generator_name[g], ld_boundaries[g]);
    }
    return CX_OK;
}

/* ---- the sections ------------------------------------------------------------ */

/* symmetry = x=0 y=0: the planes across which the model is half or a
 * quarter of the body (render --mirror draws the whole); distinct axes of
 * the dimension. */
static int ld_symmetry(ld_state *L)
{
    cx_scene *s = L->s;
    const char *v = ld_value(L, "symmetry");
    static const char expect[] = "expected planes AXIS=VALUE of distinct axes, e.g. 'x=0 y=0'";
    for (const char *p = v; p;) {
        p += strspn(p, " \t,");
        if (!*p)
            break;
        const char *ax = strchr("xyz", *p);
        if (!ax || !*ax || ax - "xyz" >= s->dim || p[1] != '=' || s->nsymmetry == 3)
            return ld_bad(L, "symmetry", expect);
        char *end;
        double at = strtod(p + 2, &end);
        if (end == p + 2 || !isfinite(at) || fabs(at) > 1e30 || (*end && !strchr(" \t,", *end)))
            return ld_bad(L, "symmetry", expect);
        for (int k = 0; k < s->nsymmetry; k++)
            if (s->symmetry_axis[k] == ax - "xyz")
                return ld_bad(L, "symmetry", "%s ('%c' twice)", expect, *ax);
        s->symmetry_axis[s->nsymmetry] = (int)(ax - "xyz");
        s->symmetry_at[s->nsymmetry++] = at;
        p = end;
    }
    return CX_OK;
}

static int ld_finish_scene(ld_state *L)
{
    cx_scene *s = L->s;
    const char *id = ld_value(L, "id"), *title = ld_value(L, "title");
    if (!ld_is_word(id, 1))
        return ld_bad(L, "id", "expected lower-case letters, digits, '_' or '-' (at most %d)",
                      CX_SCENE_NAMELEN - 1);
    strcpy(s->id, id);
    if (title) {
        if (strlen(title) >= sizeof s->title)
            return ld_bad(L, "title", "expected at most %d characters", (int)sizeof s->title - 1);
        strcpy(s->title, title);
    }
    CX_TRY(ld_int(L, "dim", 2, 3, "2 or 3", &s->dim));
    return ld_symmetry(L);
}

/* twoblocks: the interface y strictly inside (lo, hi) and the lower
 * body's cells (default: the upper's); the keys belong to it alone. */
static int ld_finish_twoblocks(ld_state *L, int g)
{
    cx_scene *s = L->s;
    if (g != CX_GEN_TWOBLOCKS) {
        CX_TRY(ld_unused(L, "interface", "by this generator (only by twoblocks)"));
        return ld_unused(L, "cells_lower", "by this generator (only by twoblocks)");
    }
    CX_TRY(ld_require(L, "interface"));
    char expect[96];
    snprintf(expect, sizeof expect, "a number strictly between lo and hi in y (%g, %g)", s->lo[1], s->hi[1]);
    CX_TRY(ld_real(L, "interface", s->lo[1], s->hi[1], 1, expect, &s->interface));
    memcpy(s->cells_lower, s->cells, sizeof s->cells_lower);
    return ld_ints(L, "cells_lower", 2, 1, LD_COUNT_MAX, "2 positive integers (dim 2)", s->cells_lower);
}

/* [mesh] of generator masonry: bond, gap (a fraction of H), tri6 only,
 * no extents (the unit square). */
static int ld_masonry(ld_state *L)
{
    cx_scene *s = L->s;
    int bond = 0;
    CX_TRY(ld_require(L, "bond"));
    CX_TRY(ld_choice(L, "bond", ld_bonds, 0, 2, ld_bonds, &bond));
    s->bond = (cx_bond)bond;
    s->gap_h = 0.01;
    CX_TRY(ld_real(L, "gap", 0, 1, 1, "a number in (0, 1) (the gap g as a fraction of H)", &s->gap_h));
    if (s->element != CX_EL_TRI6)
        return ld_bad(L, "element", "expected tri6 (generator masonry)");
    CX_TRY(ld_unused(L, "lo", "by generator 'masonry' (the unit square)"));
    CX_TRY(ld_unused(L, "hi", "by generator 'masonry' (the unit square)"));
    return ld_unused(L, "radius", "by generator 'masonry' (the unit square)");
}

/* [mesh] file = NAME.geo | NAME.msh: the path relative to the scene's
 * folder (to the working directory for a scene read from a pipe), which
 * must be readable now; size h0 (optional); element (optional: the file's
 * type, TRI3/TET4 for a .geo); level and level_max. The generator keys
 * are not used. A build without Gmsh loads the scene (it is listed) and
 * refuses to build it (cx_mesh_read_gmsh). */
static int ld_mesh_file(ld_state *L)
{
    cx_scene *s = L->s;
    const char *v = ld_value(L, "file");
    static const char *const unused[] = {"generator", "lo", "hi", "radius", "cells", "interface",
                                         "cells_lower", "level_rule", "bond", "gap"};
    for (size_t k = 0; k < sizeof unused / sizeof unused[0]; k++)
        CX_TRY(ld_unused(L, unused[k], "with 'file' (the geometry is the file's)"));
    size_t n = strlen(v);
    if (n < 5 || (strcmp(v + n - 4, ".geo") != 0 && strcmp(v + n - 4, ".msh") != 0))
        return ld_bad(L, "file", "expected NAME.geo or NAME.msh");
    if (n >= sizeof s->mesh_file_key)
        return ld_bad(L, "file", "path too long");
    strcpy(s->mesh_file_key, v);
    const char *slash = strrchr(L->path, '/');
    if (v[0] == '/' || L->piped || !slash)
        snprintf(s->mesh_file, sizeof s->mesh_file, "%s", v);
    else if ((size_t)snprintf(s->mesh_file, sizeof s->mesh_file, "%.*s/%s", (int)(slash - L->path),
                              L->path, v) >= sizeof s->mesh_file)
        return ld_bad(L, "file", "path too long");
    if (access(s->mesh_file, R_OK) != 0)
        return ld_bad(L, "file", "cannot read '%s': %s", s->mesh_file, strerror(errno));
    s->generator = CX_GEN_FILE;
    s->line_file = ld_key_line(L, "file");
    s->file_element = -1;
    int dim = s->dim, el = -1;
    CX_TRY(ld_choice(L, "element", ld_elements, dim == 2 ? 0 : 3, dim == 2 ? 2 : 4,
                     dim == 2 ? "tri3|tri6|quad4 (dim 2)" : "hex8|tet4 (dim 3)", &el));
    s->file_element = el;
    s->element = el >= 0 ? (cx_elem_type)el : dim == 2 ? CX_EL_TRI3 : CX_EL_TET4;
    CX_TRY(ld_positive(L, "size", &s->mesh_size));
    CX_TRY(ld_int(L, "level", 1, LD_COUNT_MAX, "a positive integer", &s->level));
    if (ld_value(L, "level_max")) {
        char expect[64];
        snprintf(expect, sizeof expect, "an integer >= level (%d)", s->level);
        CX_TRY(ld_int(L, "level_max", s->level, LD_COUNT_MAX, expect, &s->level_max));
    } else if (s->level > s->level_max) {
        return ld_bad(L, "level", "expected a positive integer <= level_max (%d)", s->level_max);
    }
    L->has_generator = 1;
    return CX_OK;
}

static int ld_finish_mesh(ld_state *L)
{
    cx_scene *s = L->s;
    int dim = s->dim, g = 0, el = dim == 2 ? CX_EL_TRI3 : CX_EL_HEX8;

    s->line_mesh = L->sec.line;
    if (ld_value(L, "file"))
        return ld_mesh_file(L);
    CX_TRY(ld_unused(L, "size", "by a generator (only with 'file')"));
    if (!ld_value(L, "generator"))
        return ld_error(L, L->sec.line, L->line + 1, "section [mesh]: missing key 'generator' "
                        "(or 'file')");
    CX_TRY(ld_choice(L, "generator", ld_generators, 0, 4, ld_generators, &g));
    if (ld_generator_dim[g] != dim)
        return ld_bad(L, "generator", "generator '%s' needs dim %d (the scene has dim %d)",
                      ld_generator_name[g], ld_generator_dim[g], dim);
    s->generator = (cx_scene_generator)g;
    CX_TRY(ld_choice(L, "element", ld_elements, dim == 2 ? 0 : 3, dim == 2 ? 2 : 4,
                     dim == 2 ? "tri3|tri6|quad4 (dim 2)" : "hex8|tet4 (dim 3)", &el));
    s->element = (cx_elem_type)el;

    if (g == CX_GEN_MASONRY) {
        CX_TRY(ld_masonry(L));
    } else {
        CX_TRY(ld_unused(L, "bond", "by this generator (only by masonry)"));
        CX_TRY(ld_unused(L, "gap", "by this generator (only by masonry)"));
    }
    if (g == CX_GEN_MASONRY) {
        /* the unit square: no extents */
    } else if (g == CX_GEN_HERTZ) {
        CX_TRY(ld_require(L, "radius"));
        CX_TRY(ld_unused(L, "lo", "by generator 'hertz' (it takes radius)"));
        CX_TRY(ld_unused(L, "hi", "by generator 'hertz' (it takes radius)"));
        CX_TRY(ld_positive(L, "radius", &s->radius));
    } else {
        CX_TRY(ld_require(L, "lo"));
        CX_TRY(ld_require(L, "hi"));
        CX_TRY(ld_unused(L, "radius", "by this generator (it takes lo and hi)"));
        CX_TRY(ld_vector(L, "lo", dim, NULL, s->lo));
        CX_TRY(ld_vector(L, "hi", dim, NULL, s->hi));
        for (int k = 0; k < dim; k++)
            if (!(s->hi[k] > s->lo[k]))
                return ld_bad(L, "hi", "expected hi > lo in every component");
    }

    int ncells = g == CX_GEN_HERTZ || g == CX_GEN_MASONRY ? 1 : dim;
    CX_TRY(ld_ints(L, "cells", ncells, 1, LD_COUNT_MAX,
                   ncells == 1 ? "1 positive integer (generator hertz)"
                   : ncells == 2 ? "2 positive integers (dim 2)" : "3 positive integers (dim 3)",
                   s->cells));
    CX_TRY(ld_int(L, "level", 1, LD_COUNT_MAX, "a positive integer", &s->level));
    if (ld_value(L, "level_max")) {
        char expect[64];
        snprintf(expect, sizeof expect, "an integer >= level (%d)", s->level);
        CX_TRY(ld_int(L, "level_max", s->level, LD_COUNT_MAX, expect, &s->level_max));
    } else if (s->level > s->level_max) {
        return ld_bad(L, "level", "expected a positive integer <= level_max (%d)", s->level_max);
    }
    CX_TRY(ld_finish_twoblocks(L, g));
    int rule = CX_LEVEL_LINEAR;
    CX_TRY(ld_choice(L, "level_rule", ld_level_rules, 0, 1, ld_level_rules, &rule));
    s->level_rule = (cx_level_rule)rule;
    L->has_generator = 1;
    return CX_OK;
}

/* [material]: the scene's material; [material NAME] with region = GROUP:
 * a region's (Gmsh meshes). */
static int ld_finish_material(ld_state *L)
{
    cx_scene *s = L->s;
    int dim = s->dim, model = dim == 2 ? CX_PLANE_STRAIN : CX_SOLID;
    cx_material mat = {0};
    double bf[3] = {0, 0, 0};
    CX_TRY(ld_choice(L, "model", ld_models, dim == 2 ? 0 : 2, dim == 2 ? 1 : 2,
                     dim == 2 ? "plane_strain|plane_stress (dim 2)" : "solid (dim 3)", &model));
    mat.model = (cx_model)model;
    CX_TRY(ld_positive(L, "E", &mat.E));
    CX_TRY(ld_real(L, "nu", -1, 0.5, 1, "a number in (-1, 0.5)", &mat.nu));
    CX_TRY(ld_vector(L, "body_force", dim, NULL, bf));
    if (!L->sec.name[0]) {
        CX_TRY(ld_unused(L, "region", "by [material] (a region's material is [material NAME])"));
        s->line_material = L->sec.line;
        s->mat = mat;
        memcpy(s->body_force, bf, sizeof bf);
        return CX_OK;
    }
    cx_scene_material *r = &s->materials[s->nmaterials];
    memset(r, 0, sizeof *r);
    CX_TRY(ld_require(L, "region"));
    CX_TRY(ld_group(L, "region", CX_REF_REGION, r->region));
    strcpy(r->name, L->sec.name);
    r->line = L->sec.line;
    r->mat = mat;
    memcpy(r->body_force, bf, sizeof bf);
    s->nmaterials++;
    return CX_OK;
}

/* [pressure NAME]: p normal to a boundary. */
static int ld_finish_pressure(ld_state *L)
{
    cx_scene *s = L->s;
    cx_scene_pressure *q = &s->pressures[s->npressures];
    memset(q, 0, sizeof *q);
    strcpy(q->name, L->sec.name);
    q->line = L->sec.line;
    CX_TRY(ld_boundary(L, q->boundary));
    CX_TRY(ld_real(L, "p", -LD_BIG, LD_BIG, 0, "a number (positive pushes into the body)", &q->p));
    s->npressures++;
    return CX_OK;
}

/* [force NAME]: a force on a physical point. */
static int ld_finish_force(ld_state *L)
{
    cx_scene *s = L->s;
    cx_scene_force *f = &s->forces[s->nforces];
    memset(f, 0, sizeof *f);
    strcpy(f->name, L->sec.name);
    f->line = L->sec.line;
    CX_TRY(ld_group(L, "point", CX_REF_POINT, f->point));
    CX_TRY(ld_vector(L, "F", s->dim, NULL, f->F));
    s->nforces++;
    return CX_OK;
}

static int ld_finish_traction(ld_state *L)
{
    cx_scene *s = L->s;
    cx_scene_traction *t = &s->tractions[s->ntractions];
    int dim = s->dim;
    char what[64];
    memset(t, 0, sizeof *t);
    strcpy(t->name, L->sec.name);
    t->line = L->sec.line;
    CX_TRY(ld_boundary(L, t->boundary));
    CX_TRY(ld_vector(L, "t", dim, NULL, t->t.t0));
    snprintf(what, sizeof what, " (the %dx%d matrix G, row by row)", dim, dim);
    CX_TRY(ld_vector(L, "gradient", dim * dim, what, t->t.G));
    s->ntractions++;
    return CX_OK;
}

static int ld_finish_support(ld_state *L)
{
    cx_scene *s = L->s;
    cx_scene_support *sp = &s->supports[s->nsupports];
    int dim = s->dim, fix = 0;
    double value[3] = {0, 0, 0};
    memset(sp, 0, sizeof *sp);
    strcpy(sp->name, L->sec.name);
    sp->line = L->sec.line;
    CX_TRY(ld_boundary(L, sp->boundary));
    CX_TRY(ld_choice(L, "fix", ld_fixes, 0, 7, ld_fixes, &fix));
    unsigned comps = ld_fix_comps[fix] & ((1u << dim) - 1);
    if (comps != ld_fix_comps[fix] && fix != 7)
        return ld_bad(L, "fix", "expected x|y|xy|all (dim 2)");
    CX_TRY(ld_vector(L, "value", dim, NULL, value));
    sp->comps = comps;
    for (int c = 0; c < dim; c++)
        if ((comps >> c) & 1u)
            sp->value[c] = value[c];
    s->nsupports++;
    return CX_OK;
}

/* laws = none, tresca, coulomb: the friction laws the scene allows (all
 * three if absent); the default law must be one of them. */
static int ld_laws(ld_state *L)
{
    cx_scene *s = L->s;
    const char *v = ld_value(L, "laws");
    s->laws = CX_SCENE_ALL_LAWS;
    if (!v)
        return CX_OK;
    s->laws = 0;
    for (const char *p = v;;) {
        p += strspn(p, " \t,");
        if (!*p)
            break;
        size_t len = strcspn(p, " \t,");
        char word[16] = "";
        if (len < sizeof word)
            memcpy(word, p, len);
        int law = cx_parse_choice(word, ld_frictions);
        if (law < 0)
            return ld_bad(L, "laws", "expected a list of none, tresca, coulomb");
        s->laws |= 1u << law;
        p += len;
    }
    if (!s->laws)
        return ld_bad(L, "laws", "expected at least one of none, tresca, coulomb");
    if (!(s->laws & (1u << s->friction)))
        return ld_bad(L, "laws", "the default friction '%s' is not among the laws",
                      cx_friction_name(s->friction));
    return CX_OK;
}

/* friction, slip_bound, F and laws of a contact: the law is the scene's
 * (one per scene: a later contact may repeat it, not change it), the
 * values the contact's own (absent: those of the first contact). */
static int ld_friction(ld_state *L, cx_scene_contact *c, int first)
{
    cx_scene *s = L->s;
    int friction = first ? CX_FRICTION_NONE : (int)s->friction;
    CX_TRY(ld_choice(L, "friction", ld_frictions, 0, 2, ld_frictions, &friction));
    if (!first && friction != (int)s->friction)
        return ld_bad(L, "friction", "one friction law per scene: '%s' here, '%s' in the first "
                      "contact", ld_frictions_name(friction), cx_friction_name(s->friction));
    c->slip_bound = first ? 0 : s->contacts[0].slip_bound;
    c->F = first ? 0.3 : s->contacts[0].F;
    CX_TRY(ld_nonnegative(L, "slip_bound", &c->slip_bound));
    CX_TRY(ld_nonnegative(L, "F", &c->F));
    if (!first) {
        if (ld_value(L, "laws"))
            return ld_bad(L, "laws", "given in the first contact section only");
        return CX_OK;
    }
    s->friction = (cx_friction)friction;
    return ld_laws(L);
}

/* Contact between two bodies (paper 000): boundary is the slave, master
 * the master boundary; no obstacle keys. */
static int ld_finish_contact_bodies(ld_state *L, cx_scene_contact *c, int first)
{
    cx_scene *s = L->s;
    static const char *const obstacle_keys[] = {"obstacle", "point", "normal", "radius", "direction"};
    for (int k = 0; k < 5; k++)
        CX_TRY(ld_unused(L, obstacle_keys[k], "with 'master' (contact between two bodies)"));
    if (s->dim != 2)
        return ld_bad(L, "master", "contact between two bodies needs dim 2 (3D two-body contact "
                      "is not supported: use a rigid obstacle)");
    CX_TRY(ld_group(L, "master", CX_REF_BOUNDARY, c->master));
    if (strcmp(c->master, c->boundary) == 0)
        return ld_bad(L, "master", "expected a boundary other than the slave '%s'", c->boundary);
    return ld_friction(L, c, first);
}

static int ld_finish_contact(ld_state *L)
{
    cx_scene *s = L->s;
    int first = s->ncontacts == 0;
    cx_scene_contact *c = &s->contacts[s->ncontacts];
    cx_obstacle *ob = &c->obstacle;
    int dim = s->dim, kind = 0;

    memset(c, 0, sizeof *c);
    strcpy(c->name, L->sec.name);
    c->line = L->sec.line;
    if (first)
        s->line_contact = L->sec.line;
    CX_TRY(ld_boundary(L, c->boundary));
    if (ld_value(L, "master")) {
        CX_TRY(ld_finish_contact_bodies(L, c, first));
    } else {
        CX_TRY(ld_require(L, "obstacle"));
        CX_TRY(ld_choice(L, "obstacle", ld_obstacles, 0, 3,
                         dim == 2 ? "plane|disc (dim 2)" : "plane|cylinder|sphere (dim 3)", &kind));
        if (kind != CX_OBST_PLANE && (kind == CX_OBST_DISC) != (dim == 2))
            return ld_bad(L, "obstacle", "expected %s",
                          dim == 2 ? "plane|disc (dim 2)" : "plane|cylinder|sphere (dim 3)");
        ob->kind = (cx_obstacle_kind)kind;
        CX_TRY(ld_vector(L, "point", dim, NULL, ob->point));
        if (kind == CX_OBST_PLANE || kind == CX_OBST_CYLINDER) {
            CX_TRY(ld_require(L, "normal"));
            CX_TRY(ld_direction(L, "normal", ob->normal));
        } else {
            CX_TRY(ld_unused(L, "normal", "by this obstacle"));
        }
        if (kind == CX_OBST_PLANE) {
            CX_TRY(ld_unused(L, "radius", "by obstacle plane"));
        } else {
            CX_TRY(ld_require(L, "radius"));
            CX_TRY(ld_positive(L, "radius", &ob->radius));
        }
        CX_TRY(ld_direction(L, "direction", ob->direction));
        CX_TRY(ld_friction(L, c, first));
    }
    s->ncontacts++;
    if (first) {   /* the scalars every other layer reads: the first contact's */
        strcpy(s->contact_boundary, c->boundary);
        strcpy(s->contact_master, c->master);
        s->obstacle = c->obstacle;
        s->slip_bound = c->slip_bound;
        s->F = c->F;
    }
    return CX_OK;
}

static int ld_finish_hertz(ld_state *L)
{
    cx_scene *s = L->s;
    CX_TRY(ld_positive(L, "P", &s->hertz_P));
    CX_TRY(ld_positive(L, "R", &s->hertz_R));
    s->has_hertz = 1;
    return CX_OK;
}

/* [units]: names for the figures' labels ("mm", "MPa"); nothing is
 * converted. A name is 1..15 bytes without spaces. */
static int ld_unit(ld_state *L, const char *key, char *dst, size_t len)
{
    const char *v = ld_value(L, key);
    if (!v)
        return CX_OK;
    size_t n = strlen(v);
    if (n == 0 || n >= len || strpbrk(v, " \t"))
        return ld_bad(L, key, "'%s': expected a unit name of 1 to %d characters without spaces "
                      "(e.g. mm, MPa)", v, (int)len - 1);
    memcpy(dst, v, n + 1);
    return CX_OK;
}

static int ld_finish_units(ld_state *L)
{
    cx_scene *s = L->s;
    CX_TRY(ld_unit(L, "length", s->unit_length, sizeof s->unit_length));
    CX_TRY(ld_unit(L, "stress", s->unit_stress, sizeof s->unit_stress));
    if (!s->unit_length[0] && !s->unit_stress[0])
        return ld_error(L, L->sec.line, L->line + 1, "section [units]: expected 'length' or 'stress'");
    return CX_OK;
}

static int ld_finish_methods(ld_state *L)
{
    cx_scene *s = L->s;
    const char *p = ld_value(L, "list");
    for (;;) {
        while (isspace((unsigned char)*p))
            p++;
        if (!*p)
            break;
        size_t len = strcspn(p, " \t\r\n");
        char id[CX_SCENE_NAMELEN];
        if (len < sizeof id) {
            memcpy(id, p, len);
            id[len] = '\0';
        }
        if (len >= sizeof id || !cx_method_find(id))
            return ld_bad(L, "list", "unknown method '%.*s' (see 'signorini list')",
                          (int)(len < 64 ? len : 64), p);
        for (int k = 0; k < s->nmethods; k++)
            if (strcmp(s->methods[k], id) == 0)
                return ld_bad(L, "list", "method '%s' listed twice", id);
        if (s->nmethods == CX_SCENE_MAX_METHODS)
            return ld_bad(L, "list", "expected at most %d methods", CX_SCENE_MAX_METHODS);
        strcpy(s->methods[s->nmethods++], id);
        p += len;
    }
    if (s->nmethods == 0)
        return ld_bad(L, "list", "expected at least one method id (see 'signorini list')");
    return CX_OK;
}

static const ld_key ld_scene_keys[] = {{"id", 1}, {"title", 0}, {"dim", 1}, {"symmetry", 0}, {NULL, 0}};
static const ld_key ld_mesh_keys[] = {
    {"generator", 0}, {"file", 0}, {"size", 0}, {"element", 0}, {"lo", 0}, {"hi", 0}, {"radius", 0},
    {"cells", 0}, {"level", 0}, {"level_max", 0}, {"interface", 0}, {"cells_lower", 0},
    {"level_rule", 0}, {"bond", 0}, {"gap", 0}, {NULL, 0}};
static const ld_key ld_material_keys[] = {
    {"model", 0}, {"E", 1}, {"nu", 1}, {"body_force", 0}, {"region", 0}, {NULL, 0}};
static const ld_key ld_pressure_keys[] = {{"boundary", 1}, {"p", 1}, {NULL, 0}};
static const ld_key ld_force_keys[] = {{"point", 1}, {"F", 1}, {NULL, 0}};
static const ld_key ld_traction_keys[] = {
    {"boundary", 1}, {"t", 1}, {"gradient", 0}, {NULL, 0}};
static const ld_key ld_support_keys[] = {
    {"boundary", 1}, {"fix", 1}, {"value", 0}, {NULL, 0}};
static const ld_key ld_contact_keys[] = {
    {"boundary", 1}, {"obstacle", 0}, {"point", 0}, {"normal", 0}, {"radius", 0},
    {"direction", 0}, {"friction", 0}, {"slip_bound", 0}, {"F", 0}, {"master", 0}, {"laws", 0}, {NULL, 0}};
static const ld_key ld_hertz_keys[] = {{"P", 1}, {"R", 1}, {NULL, 0}};
static const ld_key ld_methods_keys[] = {{"list", 1}, {NULL, 0}};
static const ld_key ld_units_keys[] = {{"length", 0}, {"stress", 0}, {NULL, 0}};
_Static_assert(sizeof ld_contact_keys / sizeof ld_contact_keys[0] - 1 <= LD_MAXKEYS &&
               sizeof ld_mesh_keys / sizeof ld_mesh_keys[0] - 1 <= LD_MAXKEYS,
               "LD_MAXKEYS holds the largest section");

/* [scene] first: it gives dim, which the others need */
static const ld_secdef ld_sections[LD_NSECDEFS] = {
    {"scene", 0, 1, ld_scene_keys, ld_finish_scene},
    {"mesh", 0, 1, ld_mesh_keys, ld_finish_mesh},
    {"material", 2, 1, ld_material_keys, ld_finish_material},
    {"traction", 1, 0, ld_traction_keys, ld_finish_traction},
    {"support", 1, 0, ld_support_keys, ld_finish_support},
    {"contact", 2, 1, ld_contact_keys, ld_finish_contact},
    {"hertz", 0, 0, ld_hertz_keys, ld_finish_hertz},
    {"methods", 0, 0, ld_methods_keys, ld_finish_methods},
    {"units", 0, 0, ld_units_keys, ld_finish_units},
    {"pressure", 1, 0, ld_pressure_keys, ld_finish_pressure},
    {"force", 1, 0, ld_force_keys, ld_finish_force},
};

/* ---- sections open and close ------------------------------------------------- */

static int ld_close(ld_state *L)
{
    const ld_secdef *def = L->sec.def;
    int st = CX_OK;
    for (int i = 0; st == CX_OK && def->keys[i].name; i++)
        if (def->keys[i].required)
            st = ld_require(L, def->keys[i].name);
    if (st == CX_OK)
        st = def->finish(L);
    if (st == CX_OK && L->has_generator)
        st = ld_check_boundaries(L);
    L->sec.def = NULL;
    return st;
}

/* A header "[text]" on the current line: end the section before, check the
 * new one's name, place and count. */
static int ld_open(ld_state *L, const char *text, size_t len)
{
    char buf[128], word[3][64];
    int nwords = 0;

    if (L->sec.def)
        CX_TRY(ld_close(L));
    while (len > 0 && isspace((unsigned char)*text))
        text++, len--;
    while (len > 0 && isspace((unsigned char)text[len - 1]))
        len--;
    snprintf(buf, sizeof buf, "%.*s", (int)(len < 100 ? len : 100), text);
    for (const char *p = buf; nwords < 3;) {
        while (isspace((unsigned char)*p))
            p++;
        if (!*p)
            break;
        size_t wl = strcspn(p, " \t");
        snprintf(word[nwords++], sizeof word[0], "%.*s", (int)(wl < 63 ? wl : 63), p);
        p += wl;
    }

    int kind = -1;
    for (int k = 0; nwords > 0 && k < LD_NSECDEFS; k++)
        if (strcmp(word[0], ld_sections[k].name) == 0)
            kind = k;
    const ld_secdef *def = kind >= 0 ? &ld_sections[kind] : NULL;
    if (!def || nwords > 1 + (def->named > 0))
        return ld_error(L, L->line, L->line, "unknown section [%s]", buf);
    if (def->named == 1 && nwords < 2)
        return ld_error(L, L->line, L->line, "section [%s] needs a name: [%s NAME]", buf, buf);
    if (def->named && nwords > 1 && !ld_is_word(word[1], 0))
        return ld_error(L, L->line, L->line,
                        "section [%s]: expected a name of letters, digits, '_' or '-' (at most %d)",
                        buf, CX_SCENE_NAMELEN - 1);
    if (L->nheaders == 0 && kind != 0)
        return ld_error(L, L->line, L->line, "section [scene] must come first");

    const char *name = def->named && nwords > 1 ? word[1] : "";
    for (int k = 0; k < L->nseen[kind]; k++)
        if (strcmp(L->seen_name[kind][k], name) == 0)
            return ld_error(L, L->line, L->line, "section [%s] given twice (first on line %d)",
                            buf, L->seen_line[kind][k]);
    if (L->nseen[kind] == CX_SCENE_MAX_LOADS)
        return ld_error(L, L->line, L->line, "too many [%s] sections (at most %d)",
                        def->name, CX_SCENE_MAX_LOADS);
    strcpy(L->seen_name[kind][L->nseen[kind]], name);
    L->seen_line[kind][L->nseen[kind]] = L->line;
    L->nseen[kind]++;
    L->nheaders++;

    memset(L->sec.key_line, 0, sizeof L->sec.key_line);
    L->sec.def = def;
    L->sec.line = L->line;
    strcpy(L->sec.name, name);
    return CX_OK;
}

/* Is this line a section header for inih? Then open it. inih's rule: skip
 * a UTF-8 BOM on line 1 and leading blanks; the header ends at the first
 * ']' or at an inline ';' comment (after a blank), which is its error. */
static int ld_header(ld_state *L, const char *str)
{
    const unsigned char *p = (const unsigned char *)str;
    if (L->line == 1 && p[0] == 0xEF && p[1] == 0xBB && p[2] == 0xBF)
        p += 3;
    while (isspace(*p))
        p++;
    if (*p != '[')
        return CX_OK;
    const unsigned char *q = p + 1;
    while (*q && *q != ']' && !(*q == ';' && isspace(q[-1])))
        q++;
    if (*q != ']')
        return CX_OK;
    /* inih ignores what follows the ']': only blanks or a comment may */
    const unsigned char *r = q + 1;
    while (isspace(*r))
        r++;
    if (*r && *r != ';' && *r != '#') {
        size_t n = strcspn((const char *)r, "\r\n");
        return ld_error(L, L->line, L->line,
                        "junk after the section header [%.*s]: '%.*s' (expected the end of the "
                        "line or a ';' comment)", (int)(q - p - 1 < 64 ? q - p - 1 : 64), p + 1,
                        (int)(n < 64 ? n : 64), r);
    }
    return ld_open(L, (const char *)p + 1, (size_t)(q - p - 1));
}

/* ---- inih's callbacks ------------------------------------------------------- */

/* A line's bytes: a scene is text. Tabs, and a CR ending the line, are the
 * only control characters; a NUL anywhere is refused (see the top). The
 * key is named when the bad byte follows "key =". */
static int ld_check_bytes(ld_state *L, const char *line, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        unsigned char c = (unsigned char)line[k];
        if (c == '\t' || (c == '\r' && k + 1 == n) || (c >= 0x20 && c != 0x7f))
            continue;
        char what[48], key[72] = "";
        const char *eq = memchr(line, '=', k);
        if (eq) {
            const char *a = line, *b = eq;
            while (a < b && isspace((unsigned char)*a))
                a++;
            while (b > a && isspace((unsigned char)b[-1]))
                b--;
            if (b > a)
                snprintf(key, sizeof key, "key '%.*s': ", (int)(b - a < 48 ? b - a : 48), a);
        }
        if (c == 0)
            snprintf(what, sizeof what, "NUL byte");
        else
            snprintf(what, sizeof what, "control character 0x%02x", c);
        return ld_error(L, L->line, L->line, "%s%s in column %zu (a scene file is text)", key,
                        what, k + 1);
    }
    return CX_OK;
}

/* inih's reader: the next line of the text, checked, as a C string. */
static char *ld_read(char *str, int num, void *stream)
{
    ld_state *L = stream;
    if (L->status != CX_OK || L->pos >= L->len)
        return NULL;
    const char *line = L->text + L->pos;
    const char *nl = memchr(line, '\n', L->len - L->pos);
    size_t n = nl ? (size_t)(nl - line) : L->len - L->pos;   /* without the newline */
    L->pos += n + (nl != NULL);
    L->line++;
    if (ld_check_bytes(L, line, n) != CX_OK)
        return NULL;
    if (n + 3 > (size_t)num) {
        ld_error(L, L->line, L->line, "line too long (at most %d characters)", num - 3);
        return NULL;
    }
    memcpy(str, line, n);
    if (nl)
        str[n++] = '\n';
    str[n] = '\0';
    if (ld_header(L, str) != CX_OK)
        return NULL;
    return str;
}

static int ld_handler(void *user, const char *section, const char *key, const char *value)
{
    ld_state *L = user;
    char sec[80];
    (void)section;   /* the reader tracks sections, with their lines */
    if (L->status != CX_OK)
        return 1;
    if (!L->sec.def) {
        ld_error(L, L->line, L->line, "key '%s' outside any section (the file starts with [scene])",
                 key);
        return 1;
    }
    int i = ld_index(L, key);
    if (i < 0) {
        ld_error(L, L->line, L->line, "unknown key '%s' in section %s", key,
                 ld_secname(L, sec, sizeof sec));
    } else if (L->sec.key_line[i]) {
        ld_error(L, L->line, L->line, "key '%s' given twice", key);
    } else if (strlen(value) >= LD_VALLEN) {
        ld_error(L, L->line, L->line, "key '%s': value too long (at most %d characters)", key,
                 LD_VALLEN - 1);
    } else {
        strcpy(L->sec.value[i], value);
        L->sec.key_line[i] = L->line;
    }
    /* non-zero: inih's error line then means a syntax error only */
    return 1;
}

/* ---- the whole file ---------------------------------------------------------- */

static void ld_default(cx_scene *s, const char *path)
{
    memset(s, 0, sizeof *s);
    snprintf(s->path, sizeof s->path, "%s", path);
    s->cells[0] = s->cells[1] = s->cells[2] = 1;
    s->level = 1;
    s->level_max = LD_LEVEL_MAX_DEFAULT;
    s->F = 0.3;
    s->laws = CX_SCENE_ALL_LAWS;
}

/* After the last line: the sections every scene needs, then the boundary
 * names (the generator is known by then). */
static int ld_finish(ld_state *L)
{
    if (L->nheaders == 0)
        return ld_error(L, 1, 1, "empty scene file: expected sections [scene], [mesh], "
                                 "[material], [contact]");
    for (int k = 0; k < LD_NSECDEFS; k++)
        if (ld_sections[k].required && L->nseen[k] == 0)
            return ld_error(L, 1, L->line + 1, "missing section [%s]",
                            ld_sections[k].name);
    cx_scene *s = L->s;
    if (!s->line_material && s->nmaterials > 0) {   /* regions only: the first is the default */
        s->mat = s->materials[0].mat;
        s->line_material = s->materials[0].line;
    }
    return ld_check_boundaries(L);
}

static int ld_parse(cx_scene *s, const char *path, const char *text, size_t len, int piped,
                    cx_diag *d)
{
    ld_state L;

    memset(&L, 0, sizeof L);
    L.piped = piped;
    ld_default(s, path);
    L.s = s;
    L.path = path;
    L.text = text;
    L.len = len;

    /* Debian's inih: its compile-time options are globals (doc/toolchain.md §5.8),
     * so two scenes loaded on two threads take turns */
    static pthread_mutex_t ini_lock = PTHREAD_MUTEX_INITIALIZER;
    pthread_mutex_lock(&ini_lock);
    ini_max_line = LD_MAXLINE;
    ini_allow_multiline = false;   /* an indented line is not a continuation */
    int syntax = ini_parse_stream(ld_read, &L, ld_handler, &L);
    pthread_mutex_unlock(&ini_lock);
    if (syntax < 0)
        return cx_diag_set(d, CX_ENOMEM, "%s: out of memory", path);

    if (L.status == CX_OK && L.sec.def)
        ld_close(&L);
    if (syntax > 0 && (L.status == CX_OK || (L.status == CX_EINVAL && syntax < L.order)))
        return cx_diag_set(d, CX_EINVAL, "%s:%d: syntax error", path, syntax);
    if (L.status == CX_OK)
        ld_finish(&L);
    if (L.status != CX_OK)
        return cx_diag_set(d, L.status, "%s", L.msg);
    return CX_OK;
}

/* The whole of a regular file or a pipe, at most LD_MAXFILE bytes, into
 * *text (cx_free). Devices (/dev/zero), directories and sockets are
 * refused before anything is read; O_NONBLOCK keeps the open of a FIFO
 * without a writer from waiting (it then reads as empty). */
static int ld_slurp(const char *path, char **text, size_t *len, int *piped, cx_diag *d)
{
    struct stat sb;
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC), st = CX_OK;
    *text = NULL;
    *len = 0;
    if (fd < 0)
        return cx_diag_set(d, CX_EIO, "%s: cannot open: %s", path, strerror(errno));
    if (fstat(fd, &sb) != 0) {
        st = cx_diag_set(d, CX_EIO, "%s: cannot read: %s", path, strerror(errno));
    } else if (S_ISDIR(sb.st_mode)) {
        st = cx_diag_set(d, CX_EIO, "%s: cannot read: %s", path, strerror(EISDIR));
    } else if (!S_ISREG(sb.st_mode) && !S_ISFIFO(sb.st_mode)) {
        st = cx_diag_set(d, CX_EIO, "%s: cannot read: not a regular file or a pipe", path);
    } else if (S_ISREG(sb.st_mode) && sb.st_size > LD_MAXFILE) {
        st = cx_diag_set(d, CX_EINVAL, "%s: too large: %lld bytes (a scene file has at most %d)",
                         path, (long long)sb.st_size, LD_MAXFILE);
    }
    if (st) {
        close(fd);
        return st;
    }
    /* a pipe, or standard input named as a file (/dev/stdin, /dev/fd/0,
     * /proc/self/fd/0, whatever it is redirected from): no folder of its own */
    *piped = S_ISFIFO(sb.st_mode) || strncmp(path, "/dev/", 5) == 0 ||
             strncmp(path, "/proc/", 6) == 0;
    if (S_ISFIFO(sb.st_mode))
        (void)fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);

    size_t cap = S_ISREG(sb.st_mode) ? (size_t)sb.st_size + 1 : 65536, n = 0;
    char *buf = cx_malloc(cap);
    for (;;) {
        if (!buf) {
            st = cx_diag_set(d, CX_ENOMEM, "%s: out of memory", path);
            break;
        }
        if (n == cap) {   /* a pipe, or a file that grew: room for one byte past the limit */
            size_t want = cap * 2 > (size_t)LD_MAXFILE + 1 ? (size_t)LD_MAXFILE + 1 : cap * 2;
            char *more = want > cap ? cx_realloc(buf, want) : NULL;
            if (!more) {
                if (want > cap) {
                    st = cx_diag_set(d, CX_ENOMEM, "%s: out of memory", path);
                } else {
                    st = cx_diag_set(d, CX_EINVAL, "%s: too large: more than %d bytes (a scene file "
                                     "has at most %d)", path, LD_MAXFILE, LD_MAXFILE);
                }
                break;
            }
            buf = more, cap = want;
        }
        ssize_t r = read(fd, buf + n, cap - n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0) {
            st = cx_diag_set(d, CX_EIO, "%s: cannot read: %s", path, strerror(errno));
            break;
        }
        if (r == 0)
            break;
        n += (size_t)r;
    }
    close(fd);
    if (st) {
        cx_free(buf);
        return st;
    }
    *text = buf;
    *len = n;
    return CX_OK;
}

int cx_scene_load(cx_scene *s, const char *path, cx_diag *d)
{
    char *text;
    size_t len;
    int piped = 0;
    int st = ld_slurp(path, &text, &len, &piped, d);
    if (st) {
        ld_default(s, path);
        return st;
    }
    st = ld_parse(s, path, text, len, piped, d);
    cx_free(text);
    return st;
}

int cx_scene_parse(cx_scene *s, const char *path, const char *text, size_t len, cx_diag *d)
{
    return ld_parse(s, path, text, len, 0, d);
}
