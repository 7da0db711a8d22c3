/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The data-directory search of base/data.h. The library finds itself with
 * dladdr on one of its own functions: in libsignorini.so that names the
 * shared library, in a statically linked program the program (glibc
 * then reports argv[0], so /proc/self/exe is read instead). */
#define _GNU_SOURCE 1
#include "base/data.h"

#include "cx_config.h"

#include <dlfcn.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int cx_data_self(char *path, size_t len, int *lib, int *in_build)
{
    Dl_info info;
    char raw[PATH_MAX];
    *lib = 0;
    *in_build = 0;
    if (dladdr((void *)&cx_data_self, &info) && info.dli_fname && strchr(info.dli_fname, '/') &&
        strstr(info.dli_fname, "libsignorini")) {
        snprintf(raw, sizeof raw, "%s", info.dli_fname);
        *lib = 1;
    } else {   /* a program (dladdr would give argv[0]) */
        ssize_t n = readlink("/proc/self/exe", raw, sizeof raw - 1);
        if (n <= 0)
            return 0;
        raw[n] = '\0';
    }
    char real[PATH_MAX], build[PATH_MAX];
    if (!realpath(raw, real) || strlen(real) >= len)
        return 0;
    snprintf(path, len, "%s", real);
    size_t n = realpath(CX_BUILD_ROOT, build) ? strlen(build) : 0;
    *in_build = n > 0 && strncmp(real, build, n) == 0 && real[n] == '/';
    return 1;
}

static int data_push(char dirs[CX_DATA_MAXDIRS][CX_DATA_PATHLEN], int n, const char *a, const char *b)
{
    if (n >= CX_DATA_MAXDIRS)
        return n;
    int w = snprintf(dirs[n], CX_DATA_PATHLEN, "%s%s%s", a, b ? "/" : "", b ? b : "");
    return w > 0 && w < CX_DATA_PATHLEN ? n + 1 : n;
}

int cx_data_dirs(const char *kind, const char *env_var, char dirs[CX_DATA_MAXDIRS][CX_DATA_PATHLEN])
{
    int n = 0;
    const char *env = env_var ? getenv(env_var) : NULL;
    while (env && *env && n < CX_DATA_MAXDIRS - 2) {
        size_t len = strcspn(env, ":");
        if (len > 0 && len < CX_DATA_PATHLEN) {
            memcpy(dirs[n], env, len);
            dirs[n++][len] = '\0';
        }
        env += len;
        if (*env == ':')
            env++;
    }
    const char *data = getenv("SIGNORINI_DATA");
    if (data && *data)
        n = data_push(dirs, n, data, kind);

    char self[PATH_MAX];
    int lib, in_build;
    if (!cx_data_self(self, sizeof self, &lib, &in_build))
        return n;
    if (in_build)
        return data_push(dirs, n, CX_SOURCE_ROOT, kind);
    /* installed: from the file's directory up to the prefix and down to
     * share/signorini (the relative paths are worked out by meson from
     * libdir, bindir and datadir) */
    char *slash = strrchr(self, '/');
    *slash = '\0';
    const char *rel = lib ? CX_DATA_FROM_LIBDIR : CX_DATA_FROM_BINDIR;
    if (rel[0] == '/')   /* a libdir or datadir outside the prefix */
        return data_push(dirs, n, rel, kind);
    char base[PATH_MAX + 64];
    snprintf(base, sizeof base, "%s/%s", self, rel);
    return data_push(dirs, n, base, kind);
}

void cx_data_describe(const char *kind, const char *env_var, char *buf, size_t len)
{
    char dirs[CX_DATA_MAXDIRS][CX_DATA_PATHLEN];
    int n = cx_data_dirs(kind, env_var, dirs);
    size_t used = 0;
    if (len == 0)
        return;
    buf[0] = '\0';
    for (int k = 0; k < n && used < len; k++) {
        int w = snprintf(buf + used, len - used, "%s%s", k ? ":" : "", dirs[k]);
        if (w < 0)
            break;
        used += (size_t)w;
    }
    if (n == 0)
        snprintf(buf, len, "(no directory: set SIGNORINI_DATA)");
}
