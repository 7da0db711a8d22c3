/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The scene reader (src/scene): every scene of the scene directories loads
 * (cx_scene_list + cx_scene_resolve) and the Hertz scene's fields are the
 * file's; the test scenes of good/ (defaults, normalised directions,
 * gradients, comments); the catalogue of bad files (bad/, one mistake per
 * file: one line of diagnostic starting with the path, the exact line, the
 * key or section); Hertz's half-width and pressure against the hand formula;
 * the search order of the scene directories. Runs in tests/scene (meson
 * workdir), with SIGNORINI_SCENES set to the source tree's scenes/. */
#include "scene/scene.h"
#include "check.h"

#include "cx_config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- scenes that load ---------------------------------------------------- */

static void check_all_scenes(void)
{
    char (*ids)[CX_SCENE_NAMELEN] = NULL;
    int n = 0, found = 0;
    cx_diag d;
    CX_CHECK_OK(cx_scene_list(&ids, &n, &d));
    CX_CHECK(n >= 3);
    for (int k = 0; k < n; k++) {
        char path[1024];
        cx_scene s;
        int st = cx_scene_resolve(ids[k], path, sizeof path, &d);
        if (!st)
            st = cx_scene_load(&s, path, &d);
        CX_CHECK_OK(st);
        if (st) {
            fprintf(stderr, "  scene '%s': %s\n", ids[k], d.msg);
            continue;
        }
        /* the id in the file is the file's name */
        CX_CHECK(strcmp(s.id, ids[k]) == 0);
        CX_CHECK(s.title[0] != '\0');
        CX_CHECK(s.nmethods >= 1);
        found += !strcmp(ids[k], "hertz") + !strcmp(ids[k], "slider") + !strcmp(ids[k], "block3d");
    }
    CX_CHECK(found == 3);
    cx_free(ids);
}

static void check_hertz(void)
{
    char path[1024];
    cx_scene s;
    cx_diag d;
    int cells[3];
    CX_CHECK_OK(cx_scene_resolve("hertz", path, sizeof path, &d));
    CX_CHECK_OK(cx_scene_load(&s, path, &d));
    CX_CHECK(strcmp(s.path, path) == 0);
    CX_CHECK(strcmp(s.id, "hertz") == 0);
    CX_CHECK(strcmp(s.title, "Hertz: elastic cylinder on a rigid line (quarter model)") == 0);
    CX_CHECK(s.dim == 2);
    CX_CHECK(s.generator == CX_GEN_HERTZ);
    CX_CHECK(s.element == CX_EL_TRI3);
    CX_CHECK_NEAR(s.radius, 8, 0, 0);
    CX_CHECK(s.cells[0] == 1);
    CX_CHECK(s.level == 32 && s.level_max == 2048);
    CX_CHECK(s.mat.model == CX_PLANE_STRAIN);
    CX_CHECK_NEAR(s.mat.E, 2000, 0, 0);
    CX_CHECK_NEAR(s.mat.nu, 0.3, 0, 0);
    CX_CHECK(s.body_force[0] == 0 && s.body_force[1] == 0);

    CX_CHECK(s.ntractions == 1);
    CX_CHECK(strcmp(s.tractions[0].boundary, "top") == 0);
    CX_CHECK_NEAR(s.tractions[0].t.t0[0], 0, 0, 0);
    CX_CHECK_NEAR(s.tractions[0].t.t0[1], -100, 0, 0);
    for (int k = 0; k < 9; k++)
        CX_CHECK(s.tractions[0].t.G[k] == 0);
    /* the quarter carries half the load on the cut of length R */
    CX_CHECK_NEAR(-s.tractions[0].t.t0[1] * s.radius, s.hertz_P / 2, 1e-15, 0);

    CX_CHECK(s.nsupports == 1);
    CX_CHECK(strcmp(s.supports[0].boundary, "axis") == 0);
    CX_CHECK(s.supports[0].comps == 1u);
    CX_CHECK(s.supports[0].value[0] == 0);

    CX_CHECK(strcmp(s.contact_boundary, "arc") == 0);
    CX_CHECK(s.obstacle.kind == CX_OBST_PLANE);
    CX_CHECK(s.obstacle.point[0] == 0 && s.obstacle.point[1] == 0);
    CX_CHECK(s.obstacle.normal[0] == 0 && s.obstacle.normal[1] == 1);
    CX_CHECK(s.obstacle.direction[0] == 0 && s.obstacle.direction[1] == 0);
    CX_CHECK(s.friction == CX_FRICTION_NONE);
    CX_CHECK_NEAR(s.slip_bound, 20, 0, 0);
    CX_CHECK_NEAR(s.F, 0.3, 0, 0);

    CX_CHECK(s.has_hertz);
    CX_CHECK_NEAR(s.hertz_P, 1600, 0, 0);
    CX_CHECK_NEAR(s.hertz_R, 8, 0, 0);
    CX_CHECK(s.nmethods == 1 && strcmp(s.methods[0], "ssn-tresca") == 0);

    cx_scene_cells(&s, 5, cells);
    CX_CHECK(cells[0] == 5 && cells[1] == 1 && cells[2] == 1);
    cx_scene_cells(&s, 0, cells);   /* the default level */
    CX_CHECK(cells[0] == 32);
}

static void check_slider_block(void)
{
    char path[1024];
    cx_scene s;
    cx_diag d;
    int cells[3];
    CX_CHECK_OK(cx_scene_resolve("slider", path, sizeof path, &d));
    CX_CHECK_OK(cx_scene_load(&s, path, &d));
    CX_CHECK(s.generator == CX_GEN_RECTANGLE && s.element == CX_EL_QUAD4);
    CX_CHECK(s.cells[0] == 8 && s.cells[1] == 2 && s.level == 4 && s.level_max == 256);
    CX_CHECK(s.lo[0] == -2 && s.lo[1] == 0 && s.hi[0] == 2 && s.hi[1] == 1);
    CX_CHECK(s.nsupports == 1 && s.supports[0].comps == 3u);
    CX_CHECK_NEAR(s.supports[0].value[0], 0.004, 0, 0);
    CX_CHECK_NEAR(s.supports[0].value[1], -0.01, 0, 0);
    CX_CHECK(s.friction == CX_FRICTION_TRESCA);
    CX_CHECK_NEAR(s.slip_bound, 1.5, 0, 0);
    CX_CHECK(!s.has_hertz);
    cx_scene_cells(&s, 0, cells);
    CX_CHECK(cells[0] == 32 && cells[1] == 8 && cells[2] == 1);

    CX_CHECK_OK(cx_scene_resolve("block3d", path, sizeof path, &d));
    CX_CHECK_OK(cx_scene_load(&s, path, &d));
    CX_CHECK(s.dim == 3 && s.generator == CX_GEN_BRICK && s.element == CX_EL_HEX8);
    CX_CHECK(s.mat.model == CX_SOLID);
    CX_CHECK(s.cells[0] == 2 && s.cells[1] == 2 && s.cells[2] == 1 && s.level == 4 && s.level_max == 64);
    CX_CHECK(s.hi[0] == 1 && s.hi[1] == 1 && s.hi[2] == 0.5);
    CX_CHECK(s.nsupports == 2 && s.supports[0].comps == 1u && s.supports[1].comps == 2u);
    CX_CHECK(s.ntractions == 1 && s.tractions[0].t.t0[2] == -10);
    CX_CHECK(s.obstacle.normal[2] == 1);
    cx_scene_cells(&s, 3, cells);
    CX_CHECK(cells[0] == 6 && cells[1] == 6 && cells[2] == 3);
}

static void check_good(void)
{
    cx_scene s;
    cx_diag d;

    /* defaults */
    CX_CHECK_OK(cx_scene_load(&s, "good/minimal.ini", &d));
    CX_CHECK(s.title[0] == '\0');
    CX_CHECK(s.element == CX_EL_TRI3 && s.mat.model == CX_PLANE_STRAIN);
    CX_CHECK(s.cells[0] == 1 && s.cells[1] == 1 && s.level == 1 && s.level_max == 4096);
    CX_CHECK(s.ntractions == 0 && s.nsupports == 0 && s.nmethods == 0 && !s.has_hertz);
    CX_CHECK(s.friction == CX_FRICTION_NONE && s.slip_bound == 0 && s.F == 0.3);
    CX_CHECK(s.obstacle.point[0] == 0 && s.obstacle.point[1] == 0);

    CX_CHECK_OK(cx_scene_load(&s, "good/features.ini", &d));
    CX_CHECK(strcmp(s.id, "features_2") == 0 && s.dim == 2);
    CX_CHECK(s.element == CX_EL_TRI6 && s.cells[0] == 3 && s.cells[1] == 5 && s.level == 2);
    CX_CHECK(s.mat.model == CX_PLANE_STRESS);
    CX_CHECK_NEAR(s.mat.E, 2500, 0, 0);
    CX_CHECK_NEAR(s.mat.nu, -0.2, 0, 0);
    CX_CHECK_NEAR(s.body_force[1], -9.81, 0, 0);
    CX_CHECK(s.ntractions == 2);
    CX_CHECK(strcmp(s.tractions[0].boundary, "right") == 0 && strcmp(s.tractions[1].boundary, "left") == 0);
    /* G row-major dim x dim: t_y = 0.5 x */
    CX_CHECK(s.tractions[0].t.G[0] == 0 && s.tractions[0].t.G[1] == 0);
    CX_CHECK(s.tractions[0].t.G[2] == 0.5 && s.tractions[0].t.G[3] == 0);
    CX_CHECK(s.nsupports == 2);
    CX_CHECK(s.supports[0].comps == 3u && s.supports[0].value[0] == 0.1 && s.supports[0].value[1] == -0.2);
    /* only the fixed components keep their value */
    CX_CHECK(s.supports[1].comps == 2u && s.supports[1].value[0] == 0 && s.supports[1].value[1] == 0.5);
    CX_CHECK(s.obstacle.kind == CX_OBST_DISC && s.obstacle.radius == 3);
    CX_CHECK(s.obstacle.point[1] == -3);
    CX_CHECK(s.obstacle.direction[0] == 0 && s.obstacle.direction[1] == -1);
    CX_CHECK(s.friction == CX_FRICTION_COULOMB && s.F == 0.5);

    CX_CHECK_OK(cx_scene_load(&s, "good/solid.ini", &d));
    CX_CHECK(s.dim == 3 && s.element == CX_EL_TET4 && s.mat.model == CX_SOLID);
    CX_CHECK(s.mat.nu == 0 && s.mat.E == 1);
    CX_CHECK(s.supports[0].comps == 5u);
    CX_CHECK(s.obstacle.kind == CX_OBST_CYLINDER && s.obstacle.radius == 1);
    CX_CHECK(s.obstacle.normal[0] == 0 && s.obstacle.normal[1] == 1 && s.obstacle.normal[2] == 0);
    CX_CHECK(s.friction == CX_FRICTION_TRESCA && s.slip_bound == 2);
}

/* ---- bad scene files ----------------------------------------------------- */

typedef struct bad_case {
    const char *file;      /* in bad/; NULL: the directory itself */
    int status;
    int line;
    const char *says;      /* a substring of the message */
} bad_case;

static const bad_case bad_cases[] = {
    {"missing_key.ini", CX_EINVAL, 11, "section [material]: missing key 'E'"},
    {"negative_e.ini", CX_EINVAL, 12, "key 'E': expected a positive number"},
    {"nu_half.ini", CX_EINVAL, 13, "key 'nu': expected a number in (-1, 0.5)"},
    {"nu_large.ini", CX_EINVAL, 13, "key 'nu': expected a number in (-1, 0.5)"},
    {"unknown_key.ini", CX_EINVAL, 10, "unknown key 'colour' in section [mesh]"},
    {"malformed_number.ini", CX_EINVAL, 12, "key 'E': expected a positive number"},
    {"unknown_generator.ini", CX_EINVAL, 7, "key 'generator': expected rectangle|hertz|brick"},
    {"empty.ini", CX_EINVAL, 1, "empty scene file"},
    {"only_comments.ini", CX_EINVAL, 1, "empty scene file"},
    {"unknown_section.ini", CX_EINVAL, 11, "unknown section [materials]"},
    {"duplicate_key.ini", CX_EINVAL, 14, "key 'E' given twice"},
    {"vector_length.ini", CX_EINVAL, 8, "key 'lo': expected 2 numbers"},
    {"unknown_boundary.ini", CX_EINVAL, 16, "key 'boundary': unknown boundary 'floor' of generator rectangle"},
    {"unknown_method.ini", CX_EINVAL, 21, "key 'list': unknown method 'magic' (see 'signorini list')"},
    {"section_before_scene.ini", CX_EINVAL, 3, "section [scene] must come first"},
    {"missing_section.ini", CX_EINVAL, 1, "missing section [contact]"},
    {"syntax_error.ini", CX_EINVAL, 4, "syntax error"},
    {"syntax_before_value.ini", CX_EINVAL, 4, "syntax error"},
    {"key_outside_section.ini", CX_EINVAL, 1, "key 'id' outside any section"},
    {"duplicate_section.ini", CX_EINVAL, 20, "section [mesh] given twice (first on line 6)"},
    {"fix_z_in_2d.ini", CX_EINVAL, 22, "key 'fix': expected x|y|xy|all"},
    {"generator_dim.ini", CX_EINVAL, 7, "key 'generator': generator 'brick' needs dim 3"},
    {"hi_not_above_lo.ini", CX_EINVAL, 9, "key 'hi': expected hi > lo"},
    {"missing_radius.ini", CX_EINVAL, 6, "section [mesh]: missing key 'radius'"},
    {"traction_without_name.ini", CX_EINVAL, 20, "section [traction] needs a name"},
    {"element_dim.ini", CX_EINVAL, 10, "key 'element': expected tri3|tri6|quad4"},
    {"zero_normal.ini", CX_EINVAL, 18, "key 'normal': expected 2 numbers, not all zero"},
    {"level_max_below_level.ini", CX_EINVAL, 11, "key 'level_max': expected an integer >= level (8)"},
    {"dim_four.ini", CX_EINVAL, 4, "key 'dim': expected 2 or 3"},
    {"bad_id.ini", CX_EINVAL, 3, "key 'id'"},
    {"missing_key_last_section.ini", CX_EINVAL, 15, "section [contact]: missing key 'obstacle'"},
    {"boundary_before_mesh.ini", CX_EINVAL, 7, "unknown boundary 'roof'"},
    {"obstacle_dim.ini", CX_EINVAL, 17, "key 'obstacle': expected plane|disc"},
    {"hertz_missing_r.ini", CX_EINVAL, 20, "section [hertz]: missing key 'R'"},
    {"body_force_length.ini", CX_EINVAL, 14, "key 'body_force': expected 2 numbers"},
    {"master_with_obstacle.ini", CX_EINVAL, 19, "key 'obstacle': not used with 'master'"},
    {"interface_outside.ini", CX_EINVAL, 10, "key 'interface': expected a number strictly between"},
    {"unknown_master.ini", CX_EINVAL, 18, "unknown boundary 'roof' of generator twoblocks"},
    /* input bytes and ranges (issue 20) */
    {"nul_in_value.ini", CX_EINVAL, 12, "key 'E': NUL byte in column 7"},
    {"nul_line_start.ini", CX_EINVAL, 12, "NUL byte in column 1"},
    {"control_in_key.ini", CX_EINVAL, 12, "control character 0x1b in column 2"},
    {"cr_inside.ini", CX_EINVAL, 13, "key 'nu': control character 0x0d in column 9"},
    {"c1_in_key.ini", CX_EINVAL, 12, "unknown key 'E\\xc2\\x9b2J' in section [material]"},
    {"junk_after_header.ini", CX_EINVAL, 11, "junk after the section header [material]: 'junk E = 5'"},
    {"e_overflow.ini", CX_EINVAL, 12, "key 'E': 1e+308 is out of range"},
    {"e_underflow.ini", CX_EINVAL, 12, "key 'E': 1e-300 is out of range"},
    {"lo_overflow.ini", CX_EINVAL, 8, "key 'lo': -1e+308 is out of range"},
    {"hi_overflow.ini", CX_EINVAL, 9, "key 'hi': 1e+308 is out of range"},
    {"coord_overflow.ini", CX_EINVAL, 9, "key 'hi': 1e+300 is out of range"},
    {"load_overflow.ini", CX_EINVAL, 22, "key 't': -1e+308 is out of range"},
    {"no_such_file.ini", CX_EIO, 0, "cannot open: No such file or directory"},
    {NULL, CX_EIO, 0, "cannot read"},
};

static void check_case(const bad_case *c)
{
    char path[1024], head[1100];
    cx_scene s;
    cx_diag d;
    if (c->file)
        snprintf(path, sizeof path, "bad/%s", c->file);
    else
        snprintf(path, sizeof path, "bad");
    cx_diag_clear(&d);
    int st = cx_scene_load(&s, path, &d);
    int ok = st == c->status && d.status == st;
    for (const char *q = d.msg; *q; q++)   /* one printable line: input bytes escaped */
        ok = ok && (unsigned char)*q >= 0x20 && *q != 0x7f;
    if (c->line > 0)
        snprintf(head, sizeof head, "%s:%d: ", path, c->line);
    else
        snprintf(head, sizeof head, "%s: ", path);
    ok = ok && strncmp(d.msg, head, strlen(head)) == 0 && strstr(d.msg, c->says);
    CX_CHECK(ok);
    if (!ok)
        fprintf(stderr, "  %s: status %d (expected %d), message \"%s\"; expected \"%s...%s\"\n",
                c->file ? c->file : "(directory)", st, c->status, d.msg, head, c->says);
}

static void check_bad(void)
{
    for (size_t k = 0; k < sizeof bad_cases / sizeof bad_cases[0]; k++)
        check_case(&bad_cases[k]);

    /* the good twin of the catalogue loads, and a NULL diag is fine */
    cx_scene s;
    CX_CHECK_OK(cx_scene_load(&s, "good/minimal.ini", NULL));
    CX_CHECK(cx_scene_load(&s, "bad/negative_e.ini", NULL) == CX_EINVAL);
}

/* ---- Hertz's formula ------------------------------------------------------ */

static void check_hertz_formula(void)
{
    cx_scene s;
    memset(&s, 0, sizeof s);
    s.dim = 2;
    s.mat.E = 2000;
    s.mat.nu = 0.3;
    s.mat.model = CX_PLANE_STRAIN;
    s.hertz_P = 1600;
    s.hertz_R = 8;

    /* no [hertz] section: nothing */
    CX_CHECK(cx_scene_hertz_halfwidth(&s) == 0);
    CX_CHECK(cx_scene_hertz_pressure(&s, 0) == 0);
    s.has_hertz = 1;

    double b = cx_scene_hertz_halfwidth(&s);
    double b_hand = 2 * sqrt(1600 * 8 * 0.91 / (CX_PI * 2000));
    CX_CHECK_NEAR(b, b_hand, 1e-12, 0);
    CX_CHECK_NEAR(b, 2.7231, 0, 1e-4);   /* by hand: 2 sqrt(1.8539...) */
    CX_CHECK_NEAR(cx_scene_hertz_pressure(&s, 0), 2 * 1600 / (CX_PI * b), 1e-12, 0);
    CX_CHECK_NEAR(cx_scene_hertz_pressure(&s, 0.5 * b), 2 * 1600 / (CX_PI * b) * sqrt(0.75), 1e-12, 0);
    CX_CHECK_NEAR(cx_scene_hertz_pressure(&s, -0.3), cx_scene_hertz_pressure(&s, 0.3), 1e-15, 0);
    CX_CHECK(cx_scene_hertz_pressure(&s, b) == 0);
    CX_CHECK(cx_scene_hertz_pressure(&s, -b) == 0);
    CX_CHECK(cx_scene_hertz_pressure(&s, 1.0001 * b) == 0);
    CX_CHECK(cx_scene_hertz_pressure(&s, 100) == 0);

    /* the resultant is P: midpoint rule, error O(h^1.5) at the ends */
    int n = 200000;
    double h = 2 * b / n, sum = 0;
    for (int i = 0; i < n; i++)
        sum += h * cx_scene_hertz_pressure(&s, -b + (i + 0.5) * h);
    CX_CHECK_NEAR(sum, 1600, 1e-6, 0);

    /* plane stress: E* = E */
    s.mat.model = CX_PLANE_STRESS;
    CX_CHECK_NEAR(cx_scene_hertz_halfwidth(&s), 2 * sqrt(1600 * 8 / (CX_PI * 2000)), 1e-12, 0);
}

/* ---- finding scenes (changes SIGNORINI_SCENES: last) ---------------------- */

static void write_file(const char *dir, const char *name, const char *text)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    CX_CHECK(f != NULL);
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static void remove_file(const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    remove(path);
}

static int has_id(char (*ids)[CX_SCENE_NAMELEN], int n, const char *id)
{
    int c = 0;
    for (int k = 0; k < n; k++)
        c += strcmp(ids[k], id) == 0;
    return c;
}

static void check_find(void)
{
    char dir[] = "/tmp/cx-scene-find-XXXXXX";
    char path[1024], want[1100];
    cx_diag d;
    CX_CHECK(mkdtemp(dir) != NULL);
    write_file(dir, "zz-extra.ini", "; listed\n");
    write_file(dir, "hertz.ini", "; found before the source tree's hertz\n");
    write_file(dir, "Upper.ini", "; not an id: skipped\n");
    write_file(dir, "notes.txt", "not a scene\n");
    write_file(dir, "old.ini.bak", "not a scene\n");
    snprintf(path, sizeof path, "%s/dir.ini", dir);
    CX_CHECK(mkdir(path, 0700) == 0);
    /* a missing directory in the list is skipped */
    snprintf(want, sizeof want, "/nonexistent/cx-scenes:%s", dir);
    CX_CHECK(setenv("SIGNORINI_SCENES", want, 1) == 0);

    /* resolve: $SIGNORINI_SCENES first */
    CX_CHECK_OK(cx_scene_resolve("hertz", path, sizeof path, &d));
    snprintf(want, sizeof want, "%s/hertz.ini", dir);
    CX_CHECK(strcmp(path, want) == 0);
    CX_CHECK_OK(cx_scene_resolve("slider", path, sizeof path, &d));
    CX_CHECK(strcmp(path, CX_SCENE_DIR_BUILD "/slider.ini") == 0);

    /* paths are taken as they are */
    CX_CHECK_OK(cx_scene_resolve("some/dir/x", path, sizeof path, &d));
    CX_CHECK(strcmp(path, "some/dir/x") == 0);
    CX_CHECK_OK(cx_scene_resolve("x.ini", path, sizeof path, &d));
    CX_CHECK(strcmp(path, "x.ini") == 0);
    CX_CHECK(cx_scene_resolve("a/long/path.ini", path, 8, &d) == CX_EINVAL);

    /* unknown ids, and names that are not ids */
    const char *unknown[] = {"nope", "Upper", "dir", "notes", ""};
    for (int k = 0; k < 5; k++) {
        char msg[128];
        cx_diag_clear(&d);
        CX_CHECK(cx_scene_resolve(unknown[k], path, sizeof path, &d) == CX_EINVAL);
        snprintf(msg, sizeof msg, "unknown scene '%s' (see 'signorini list')", unknown[k]);
        CX_CHECK(strcmp(d.msg, msg) == 0);
    }
    /* a buffer too small for any directory: not found */
    CX_CHECK(cx_scene_resolve("hertz", path, 4, &d) == CX_EINVAL);

    /* list: sorted, distinct, ids only */
    char (*ids)[CX_SCENE_NAMELEN] = NULL;
    int n = 0;
    CX_CHECK_OK(cx_scene_list(&ids, &n, &d));
    CX_CHECK(has_id(ids, n, "zz-extra") == 1);
    CX_CHECK(has_id(ids, n, "hertz") == 1);
    CX_CHECK(has_id(ids, n, "slider") == 1 && has_id(ids, n, "block3d") == 1);
    CX_CHECK(!has_id(ids, n, "Upper") && !has_id(ids, n, "dir") && !has_id(ids, n, "notes"));
    for (int k = 0; k + 1 < n; k++)
        CX_CHECK(strcmp(ids[k], ids[k + 1]) < 0);
    cx_free(ids);

    /* allocation failures: CX_ENOMEM and nothing left behind */
    long live = cx_alloc_live();
    cx_alloc_fail_after(0);
    CX_CHECK(cx_scene_list(&ids, &n, &d) == CX_ENOMEM);
    cx_alloc_fail_after(-1);
    CX_CHECK(ids == NULL && n == 0);
    CX_CHECK(cx_alloc_live() == live);

    /* an empty scene directory list still finds the source tree */
    CX_CHECK(unsetenv("SIGNORINI_SCENES") == 0);
    CX_CHECK_OK(cx_scene_resolve("hertz", path, sizeof path, &d));
    CX_CHECK(strcmp(path, CX_SCENE_DIR_BUILD "/hertz.ini") == 0);

    remove_file(dir, "zz-extra.ini");
    remove_file(dir, "hertz.ini");
    remove_file(dir, "Upper.ini");
    remove_file(dir, "notes.txt");
    remove_file(dir, "old.ini.bak");
    remove_file(dir, "dir.ini");
    remove(dir);
}

int main(void)
{
    check_all_scenes();
    check_hertz();
    check_slider_block();
    check_good();
    check_bad();
    check_hertz_formula();
    check_find();
    return check_finish("scene_load");
}
