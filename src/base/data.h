/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Where the data files (scenes/, shaders/) are: one home for the search
 * order, so that the program, a C client and the Python package find the
 * same files wherever the prefix was installed or moved to (doc/design.md,
 * "Install and data"). For KIND ("scenes", "shaders") the directories are,
 * in order:
 *   1. $ENV_VAR (SIGNORINI_SCENES, SIGNORINI_SHADERS), one directory or
 *      several separated by ':';
 *   2. $SIGNORINI_DATA/KIND;
 *   3. when the running code is the build tree's (library or program under
 *      the build directory): the source tree's KIND/, so that edits to
 *      scenes and shaders need no install;
 *   4. otherwise KIND under share/signorini relative to the file that
 *      holds this code (libsignorini.so in LIBDIR, or the program in
 *      BINDIR), found with dladdr.
 * Missing directories are left in the list; the callers skip them. */
#ifndef CX_DATA_H
#define CX_DATA_H

#include <stddef.h>

#define CX_DATA_MAXDIRS 16
#define CX_DATA_PATHLEN 1024

/* Fill dirs with the search directories for kind; returns their number
 * (at least 0, at most CX_DATA_MAXDIRS). */
int cx_data_dirs(const char *kind, const char *env_var, char dirs[CX_DATA_MAXDIRS][CX_DATA_PATHLEN]);

/* The real path of the file that holds this code (libsignorini.so, or the
 * program that links it statically) in path (len bytes); *lib: it is the
 * library; *in_build: it lies in the build tree. 0 if it cannot be told. */
int cx_data_self(char *path, size_t len, int *lib, int *in_build);

/* The directories of cx_data_dirs as one ':'-separated string (for
 * messages such as "no scenes found in ..."). */
void cx_data_describe(const char *kind, const char *env_var, char *buf, size_t len);

#endif
