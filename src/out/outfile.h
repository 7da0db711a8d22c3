/* SPDX-License-Identifier: GPL-3.0-or-later */
/* out/outfile.h: the one way every program writes an output file (VTU,
 * PNG, CSV, JSON, reference caches). A regular file (or a new one) is
 * written under a temporary name beside it and renamed into place when
 * complete, so that a failure or an interrupt never leaves a partial file
 * under the real name. The path's symbolic links are followed first: the
 * temporary goes beside the link's final target and is renamed onto it, so
 * the link stays a link. A target that exists and is not a regular file (a
 * device, a FIFO, a socket, /dev/stdout) is written in place, never
 * replaced. "-" is standard output.
 *
 * Ctrl-C: the library installs no signal handler. A temporary being written
 * is registered (a few lock-free slots, so two threads may write at once);
 * a program's SIGINT handler calls cx_outfile_abandon_pending(), which is
 * async-signal-safe, to remove it before it exits.
 *
 * Errors are one line in the diag: CX_EINVAL (empty or too long a name),
 * CX_EIO "PATH: cannot write: reason". */
#ifndef CX_OUT_OUTFILE_H
#define CX_OUT_OUTFILE_H

#include <stdio.h>

#include "base/base.h"

#define CX_OUTFILE_PATHLEN 4096

typedef enum cx_outfile_mode {
    CX_OUTFILE_RENAME,   /* temporary beside the target, renamed onto it */
    CX_OUTFILE_INPLACE,  /* an existing non-regular file, written directly */
    CX_OUTFILE_STDOUT    /* "-" */
} cx_outfile_mode;

typedef struct cx_outfile {
    FILE *f;                        /* write here between open and close */
    const char *path;               /* as given (borrowed; for messages) */
    cx_outfile_mode mode;
    int slot;                       /* pending-temporary slot, or -1 */
    char target[CX_OUTFILE_PATHLEN];/* the file that will hold the data */
    char tmp[CX_OUTFILE_PATHLEN];   /* RENAME: "TARGET.tmpPID" */
} cx_outfile;

/* 1 if path names standard output ("-"). */
int cx_outfile_is_stdout(const char *path);

/* Open path for writing (see above). A directory is refused. */
int cx_outfile_open(cx_outfile *o, const char *path, cx_diag *d);
/* Finish: flush and close (standard output is flushed, not closed); if ok
 * and no write failed, rename the temporary onto the target, else remove
 * it. CX_OK or CX_EIO "PATH: cannot write: reason"; when !ok it removes
 * what it must and returns CX_OK with d untouched (the caller reports). */
int cx_outfile_close(cx_outfile *o, int ok, cx_diag *d);

/* Remove every temporary file still being written. Async-signal-safe (for
 * a SIGINT handler that then calls _exit); the writers' later close
 * finds its temporary gone and fails. */
void cx_outfile_abandon_pending(void);

/* The end of a program that wrote to standard output: flush it, check
 * that no write failed, and close it. CX_EIO "standard output: reason".
 * Nothing may be written to stdout afterwards. */
int cx_outfile_close_stdout(cx_diag *d);

#endif
