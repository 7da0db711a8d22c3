/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A discrete problem read back from the files of 'signorini export' (or
 * written by another program in the same form, README "The discrete
 * problem"): a directory of MatrixMarket files with its problem.json, or
 * an FCLIB global problem (.hdf5). The problem has no mesh: the methods
 * that need only the algebra solve it; outputs that draw the mesh refuse
 * it. */
#ifndef CX_SCENE_PROBLEM_FILE_H
#define CX_SCENE_PROBLEM_FILE_H

#include "solve/solve.h"

/* The manifest's name inside a problem directory. */
#define CX_PROBLEM_MANIFEST_NAME "problem.json"

typedef struct cx_problem_file {
    cx_problem *p;          /* the problem; cx_session_create takes it */
    cx_friction_state fr;   /* the law and values written with it (s, Fi
                               point into the arrays below, or NULL) */
    double *s, *Fi;         /* m per-point slip bounds / coefficients */
    char format[8];         /* "mm" or "fclib" */
    char source[256];       /* the scene it was exported from ("" if unknown) */
    int level;              /* its level (0 if unknown) */
} cx_problem_file;

/* Read path: a directory (MatrixMarket, its problem.json) or an FCLIB
 * file. Every file is checked after it is read: sizes against the
 * manifest and each other, K symmetric, values finite, gaps, weights and
 * friction values >= 0; the first bad one is one line naming the file and
 * the entry's row and column (1-based, as in the file). CX_EIO, CX_EINVAL,
 * CX_EUNSUPPORTED (an FCLIB file in a build without FCLIB), CX_ENOMEM. */
int cx_problem_read(const char *path, cx_problem_file *pf, cx_diag *d);
void cx_problem_file_clear(cx_problem_file *pf);

/* A scene's problem in one call (cx_scene_open + cx_scene_build; level
 * <= 0: the scene's), with its friction defaults in *fr (may be NULL):
 * for bindings that do not hold a cx_scene. */
int cx_problem_from_scene(const char *id_or_path, int level, cx_problem **p, cx_friction_state *fr,
                          cx_diag *d);

/* An FCLIB global problem (problem_fclib.c). */
int cx_problem_read_fclib(const char *path, cx_problem_file *pf, cx_diag *d);

/* The manifest alone (problem.json's text, len bytes, named name): the
 * fields the reader uses, for tests and fuzzing. */
typedef struct cx_problem_manifest {
    int dim, n, m, level, version;
    cx_friction law;
    double F, slip_bound, E;
    char source[256];
    char file[10][64];      /* by key: see problem_file.c's manifest_keys */
} cx_problem_manifest;
int cx_problem_manifest_parse(const char *text, size_t len, const char *name, cx_problem_manifest *mf,
                              cx_diag *d);

#endif
