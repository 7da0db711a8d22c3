/* Temporary file + rename (see outfile.h). */
#include "render/outfile.h"

#include <errno.h>
#include <string.h>
#include <unistd.h>

int cx_outfile_open(cx_outfile *o, const char *path, cx_diag *d)
{
    memset(o, 0, sizeof *o);
    if (!path || !path[0])
        return cx_diag_set(d, CX_EINVAL, "output file: empty name");
    if (snprintf(o->tmp, sizeof o->tmp, "%s.tmp%ld", path, (long)getpid()) >= (int)sizeof o->tmp)
        return cx_diag_set(d, CX_EINVAL, "%s: file name too long", path);
    o->path = path;
    o->f = fopen(o->tmp, "wb");
    if (!o->f)
        return cx_diag_set(d, CX_EIO, "%s: cannot write: %s", path, strerror(errno));
    return CX_OK;
}

int cx_outfile_close(cx_outfile *o, int ok, cx_diag *d)
{
    if (!o->f)
        return CX_OK;
    int e = 0;
    if (fflush(o->f) != 0 || ferror(o->f))
        e = errno ? errno : EIO;
    if (fclose(o->f) != 0 && !e)
        e = errno ? errno : EIO;
    o->f = NULL;
    if (ok && !e && rename(o->tmp, o->path) != 0)
        e = errno;
    if (!ok || e) {
        remove(o->tmp);
        if (ok)
            return cx_diag_set(d, CX_EIO, "%s: cannot write: %s", o->path, strerror(e));
    }
    return CX_OK;
}
