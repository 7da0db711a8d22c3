/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini export SCENE --format mm|fclib OUT: the discrete problem of a
 * scene at a level, with its friction law and per-point values, for
 * another solver (out/export.h; README, "The discrete problem"). */
#include "cli/cli.h"
#include "out/export.h"
#include "out/outfile.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char export_usage[] =
    "usage: signorini export SCENE --format mm|fclib OUT [options]\n"
    "\n"
    "Writes the discrete problem of SCENE (K, f, N, T, g and the friction\n"
    "values per contact point) for another solver: --format mm makes the\n"
    "directory OUT of MatrixMarket files with a manifest problem.json;\n"
    "--format fclib the FCLIB global problem OUT (HDF5; Coulomb or\n"
    "frictionless: Tresca has no FCLIB form). 'signorini solve --problem OUT'\n"
    "reads either back. The sign conventions are in problem.json and the\n"
    "README (\"The discrete problem\").\n"
    "\n"
    "Exit status: 0 written, 1 error, 2 usage.\n";

typedef struct {
    int format;      /* 0 mm, 1 fclib */
    int friction;    /* -1: the scene's */
    double F, slip;
    int level;
} export_args;

static const cx_opt export_opts[] = {
    {"format", 0, CX_OPT_CHOICE, 0, 0, 0, "mm|fclib", "mm|fclib",
     "mm: a directory of MatrixMarket files and problem.json;\n"
     "fclib: an FCLIB global problem in one HDF5 file", offsetof(export_args, format), NULL},
    CX_OPT_ROW_FRICTION(export_args, friction),
    CX_OPT_ROW_F(export_args, F),
    CX_OPT_ROW_SLIP(export_args, slip),
    CX_OPT_ROW_LEVEL(export_args, level),
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

int cli_export(int argc, char **argv)
{
    const char *cmd = "export";
    export_args a = {-1, -1, NAN, NAN, 0};
    cx_opt_group groups[] = {{export_opts, &a}, {NULL, NULL}};
    const char *pos[2] = {NULL, NULL};
    int npos = 0;
    cx_diag d;
    cx_diag_clear(&d);
    int parsed = cx_opt_parse(groups, argc, argv, pos, 2, &npos, &d);
    if (parsed == CX_OPT_HELP) {
        const cx_opt *const tables[] = {export_opts, NULL};
        cli_help(export_usage, tables, stdout);
        return CX_EXIT_OK;
    }
    if (parsed)
        return cli_usage(cmd, d.msg);
    if (npos < 1)
        return cli_usage(cmd, "missing SCENE");
    if (npos < 2)
        return cli_usage(cmd, "missing OUT (the directory or .hdf5 file to write)");
    if (a.format < 0)
        return cli_usage(cmd, "missing --format mm|fclib");
    if (cx_outfile_is_stdout(pos[1]))
        return cli_usage(cmd, "OUT '-': a directory (mm) or an HDF5 file (fclib), not standard output");

    cx_scene sc;
    if (cx_scene_open(pos[0], &sc, &d))
        return cli_fail(cmd, d.msg);
    int law = a.friction >= 0 ? a.friction : (int)sc.friction;
    if (!(sc.laws & (1u << law))) {
        cx_diag_set(&d, CX_EINVAL, "--friction %s: scene '%s' does not allow it (its 'laws')",
                    cx_friction_name((cx_friction)law), sc.id);
        return cli_fail(cmd, d.msg);
    }
    if (a.format == 1 && law == CX_FRICTION_TRESCA)
        return cli_fail(cmd, "--format fclib: Tresca friction has no FCLIB form (FCLIB's problems are "
                        "Coulomb's; use --friction coulomb or none, or --format mm)");
    cx_friction_state fr = {(cx_friction)law, isnan(a.slip) ? sc.slip_bound : a.slip, isnan(a.F) ? sc.F : a.F,
                            NULL, NULL};
    cx_problem *p = NULL;
    if (cx_scene_build(&sc, a.level, &p, NULL, &d))
        return cli_fail(cmd, d.msg);
    /* a scene's several contacts keep their own values unless --F / --slip
     * set them all (as solve does) */
    if (isnan(a.F))
        fr.Fi = p->contact.Fpt;
    if (isnan(a.slip))
        fr.s = p->contact.spt;
    /* the session computes the per-point values (s_i = bound x weight_i) */
    cx_session *s = NULL;
    int code = CX_EXIT_OK;
    if (cx_session_create(&s, &p, &d) || cx_session_set_friction(s, &fr, &d)) {
        cx_problem_destroy(&p);
        code = cli_fail(cmd, d.msg);
    } else {
        const cx_problem *cp = cx_session_problem(s);
        int level = a.level > 0 ? a.level : sc.level;
        int st = a.format == 0 ? cx_export_mm(cp, cx_session_friction(s), pos[1], sc.id, level, &d)
                               : cx_export_fclib(cp, cx_session_friction(s), pos[1], sc.id, level, &d);
        if (st)
            code = cli_fail(cmd, d.msg);
        else
            printf("%s level %d: %dD, %d unknowns, %d contact points, friction %s -> %s (%s)\n", sc.id, level,
                   cp->dim, cp->n, cp->m, cx_friction_name((cx_friction)law), pos[1],
                   a.format == 0 ? "MatrixMarket" : "FCLIB");
    }
    cx_session_destroy(&s);
    if (code == CX_EXIT_OK && cx_outfile_close_stdout(&d))
        code = cli_fail(cmd, d.msg);
    return code;
}
