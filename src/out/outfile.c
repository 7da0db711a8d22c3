/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The safe-output helper (see outfile.h). */
#include "out/outfile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The temporaries being written, for cx_outfile_abandon_pending. A slot is
 * 0 free, 1 being filled, 2 pending (its path names a file that may
 * exist). Lock-free atomics are safe both across threads and in a signal
 * handler; a plain flag would be neither. More writers at once than slots:
 * the extra temporaries are not registered (an interrupt may leave them). */
_Static_assert(ATOMIC_INT_LOCK_FREE == 2, "the pending-temporary slots need lock-free atomics");
enum { OUTFILE_SLOTS = 8 };
static atomic_int outfile_slot_state[OUTFILE_SLOTS];
static char outfile_slot_path[OUTFILE_SLOTS][CX_OUTFILE_PATHLEN];

static int outfile_register(const char *tmp)
{
    for (int k = 0; k < OUTFILE_SLOTS; k++) {
        int expect = 0;
        if (atomic_compare_exchange_strong(&outfile_slot_state[k], &expect, 1)) {
            memcpy(outfile_slot_path[k], tmp, strlen(tmp) + 1);
            atomic_store(&outfile_slot_state[k], 2);
            return k;
        }
    }
    return -1;
}

static void outfile_release(int slot)
{
    if (slot >= 0)
        atomic_store(&outfile_slot_state[slot], 0);
}

void cx_outfile_abandon_pending(void)
{
    for (int k = 0; k < OUTFILE_SLOTS; k++)
        if (atomic_load(&outfile_slot_state[k]) == 2)
            unlink(outfile_slot_path[k]);
}

int cx_outfile_is_stdout(const char *path)
{
    return path && strcmp(path, "-") == 0;
}

/* Follow the symbolic links of path (the last component, link after link)
 * to the name that holds the data, into out. Returns 0, 1 if the chain
 * enters /proc (a magic link such as /dev/stdout -> /proc/self/fd/1, whose
 * target is a descriptor, not a name to rename onto), or -1 with errno. */
static int outfile_resolve(const char *path, char *out, size_t len)
{
    char cur[CX_OUTFILE_PATHLEN], link[CX_OUTFILE_PATHLEN];
    if (strlen(path) >= sizeof cur)
        return errno = ENAMETOOLONG, -1;
    strcpy(cur, path);
    for (int hop = 0; hop < 40; hop++) {
        struct stat st;
        if (lstat(cur, &st) != 0 || !S_ISLNK(st.st_mode)) {
            if (strlen(cur) >= len)
                return errno = ENAMETOOLONG, -1;
            strcpy(out, cur);
            return 0;
        }
        ssize_t n = readlink(cur, link, sizeof link - 1);
        if (n < 0)
            return -1;
        link[n] = '\0';
        /* a relative target is relative to the link's directory */
        const char *slash = strrchr(cur, '/');
        if (link[0] != '/' && slash) {
            size_t dir = (size_t)(slash - cur) + 1;
            if (dir + (size_t)n >= sizeof cur)
                return errno = ENAMETOOLONG, -1;
            memmove(cur + dir, link, (size_t)n + 1);
        } else {
            memcpy(cur, link, (size_t)n + 1);
        }
        if (strncmp(cur, "/proc/", 6) == 0)
            return 1;
    }
    return errno = ELOOP, -1;
}

static int outfile_fail(const cx_outfile *o, int err, cx_diag *d)
{
    return cx_diag_set(d, CX_EIO, "%s: cannot write: %s", o->path, strerror(err));
}

static int outfile_open_inplace(cx_outfile *o, cx_diag *d)
{
    o->mode = CX_OUTFILE_INPLACE;
    snprintf(o->target, sizeof o->target, "%s", o->path);
    o->f = fopen(o->path, "wb");
    return o->f ? CX_OK : outfile_fail(o, errno, d);
}

int cx_outfile_open(cx_outfile *o, const char *path, cx_diag *d)
{
    memset(o, 0, sizeof *o);
    o->slot = -1;
    o->path = path;
    if (!path || !path[0])
        return cx_diag_set(d, CX_EINVAL, "output file: empty name");
    if (cx_outfile_is_stdout(path)) {
        o->mode = CX_OUTFILE_STDOUT;
        o->f = stdout;
        return CX_OK;
    }
    struct stat st;
    int exists = stat(path, &st) == 0;
    if (exists && S_ISDIR(st.st_mode))
        return outfile_fail(o, EISDIR, d);
    if (exists && !S_ISREG(st.st_mode))
        return outfile_open_inplace(o, d);
    int r = outfile_resolve(path, o->target, sizeof o->target);
    if (r < 0)
        return outfile_fail(o, errno, d);
    if (r == 1)
        return outfile_open_inplace(o, d);
    o->mode = CX_OUTFILE_RENAME;
    if (snprintf(o->tmp, sizeof o->tmp, "%s.tmp%ld", o->target, (long)getpid()) >= (int)sizeof o->tmp)
        return cx_diag_set(d, CX_EINVAL, "%s: file name too long", path);
    o->slot = outfile_register(o->tmp);
    /* O_NOFOLLOW: a link planted under the temporary's name is not followed */
    int fd = open(o->tmp, O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) {
        int e = errno;
        outfile_release(o->slot);
        return outfile_fail(o, e, d);
    }
    if (exists)   /* the new file keeps the old one's permissions */
        (void)fchmod(fd, st.st_mode & 07777);
    o->f = fdopen(fd, "wb");
    if (!o->f) {
        int e = errno;
        close(fd);
        unlink(o->tmp);
        outfile_release(o->slot);
        return outfile_fail(o, e, d);
    }
    return CX_OK;
}

int cx_outfile_close(cx_outfile *o, int ok, cx_diag *d)
{
    if (!o->f)
        return CX_OK;
    int e = 0;
    errno = 0;
    if (fflush(o->f) != 0 || ferror(o->f))
        e = errno ? errno : EIO;
    if (o->mode == CX_OUTFILE_STDOUT) {
        o->f = NULL;
        return ok && e ? cx_diag_set(d, CX_EIO, "standard output: cannot write: %s", strerror(e)) : CX_OK;
    }
    if (fclose(o->f) != 0 && !e)
        e = errno ? errno : EIO;
    o->f = NULL;
    if (o->mode == CX_OUTFILE_RENAME) {
        if (ok && !e && rename(o->tmp, o->target) != 0)
            e = errno;
        if (!ok || e)
            unlink(o->tmp);
        outfile_release(o->slot);
        o->slot = -1;
    }
    return ok && e ? outfile_fail(o, e, d) : CX_OK;
}

int cx_outfile_close_stdout(cx_diag *d)
{
    int e = 0;
    errno = 0;
    if (fflush(stdout) != 0 || ferror(stdout))
        e = errno ? errno : EIO;
    if (fclose(stdout) != 0 && !e)
        e = errno ? errno : EIO;
    return e ? cx_diag_set(d, CX_EIO, "standard output: %s", strerror(e)) : CX_OK;
}
