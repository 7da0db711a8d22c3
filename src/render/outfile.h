/* render/outfile.h (internal): an output file written under a temporary
 * name in the target's directory and renamed into place when complete, so
 * that a failure never leaves a partial file (PNG and VTU alike). */
#ifndef CX_RENDER_OUTFILE_H
#define CX_RENDER_OUTFILE_H

#include <stdio.h>

#include "base/base.h"

typedef struct cx_outfile {
    FILE *f;
    const char *path;
    char tmp[4096];
} cx_outfile;

/* Open "PATH.tmpPID" for writing. CX_EINVAL (empty or too long a name),
 * CX_EIO "PATH: cannot write: reason". */
int cx_outfile_open(cx_outfile *o, const char *path, cx_diag *d);
/* Close; if ok and no write failed, rename onto the path, else remove the
 * temporary. Returns CX_OK or CX_EIO with "PATH: cannot write: reason"
 * (when !ok it returns CX_OK and leaves d alone: the caller reports). */
int cx_outfile_close(cx_outfile *o, int ok, cx_diag *d);

#endif
