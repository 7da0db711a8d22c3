/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Scene ids and paths. The scene directories are those of
 * cx_data_dirs("scenes", "SIGNORINI_SCENES") (base/data.h: the override,
 * $SIGNORINI_DATA, then the source tree for the build tree's code or
 * share/signorini beside the installed library); the first NAME.ini found
 * wins. Missing directories are skipped. */
#include "scene/scene.h"

#include "base/data.h"

#include <ctype.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define FIND_MAXDIRS CX_DATA_MAXDIRS
#define FIND_PATHLEN CX_DATA_PATHLEN

static int find_dirs(char dirs[FIND_MAXDIRS][FIND_PATHLEN])
{
    return cx_data_dirs("scenes", "SIGNORINI_SCENES", dirs);
}

/* A scene id: lower-case letters, digits, '_' and '-', as [scene] id. */
static int find_is_id(const char *t, size_t len)
{
    if (len == 0 || len >= CX_SCENE_NAMELEN)
        return 0;
    for (size_t k = 0; k < len; k++) {
        unsigned char c = (unsigned char)t[k];
        if (!(islower(c) || isdigit(c) || c == '_' || c == '-'))
            return 0;
    }
    return 1;
}

static int find_is_ini(const char *name, size_t len)
{
    return len > 4 && strcmp(name + len - 4, ".ini") == 0;
}

static int find_is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode) && access(path, R_OK) == 0;
}

int cx_scene_resolve(const char *id_or_path, char *path, size_t len, cx_diag *d)
{
    size_t n = strlen(id_or_path);
    if (strchr(id_or_path, '/') || find_is_ini(id_or_path, n)) {
        if (n >= len)
            return cx_diag_set(d, CX_EINVAL, "scene path too long: %.200s", id_or_path);
        memcpy(path, id_or_path, n + 1);
        return CX_OK;
    }
    if (find_is_id(id_or_path, n)) {
        char dirs[FIND_MAXDIRS][FIND_PATHLEN];
        int ndirs = find_dirs(dirs);
        for (int k = 0; k < ndirs; k++) {
            int w = snprintf(path, len, "%s/%s.ini", dirs[k], id_or_path);
            if (w > 0 && (size_t)w < len && find_is_file(path))
                return CX_OK;
        }
    }
    if (len > 0)
        path[0] = '\0';
    return cx_diag_set(d, CX_EINVAL, "unknown scene '%.64s' (see 'signorini list')", id_or_path);
}

static int find_cmp(const void *a, const void *b)
{
    return strcmp((const char *)a, (const char *)b);
}

int cx_scene_list(char (**ids)[CX_SCENE_NAMELEN], int *count, cx_diag *d)
{
    char dirs[FIND_MAXDIRS][FIND_PATHLEN];
    int ndirs = find_dirs(dirs), n = 0, cap = 0;
    char (*list)[CX_SCENE_NAMELEN] = NULL;

    *ids = NULL;
    *count = 0;
    for (int k = 0; k < ndirs; k++) {
        DIR *dir = opendir(dirs[k]);
        struct dirent *e;
        if (!dir)
            continue;
        while ((e = readdir(dir)) != NULL) {
            size_t len = strlen(e->d_name);
            char file[FIND_PATHLEN + 256];
            if (!find_is_ini(e->d_name, len) || !find_is_id(e->d_name, len - 4))
                continue;
            int w = snprintf(file, sizeof file, "%s/%s", dirs[k], e->d_name);
            if (w < 0 || (size_t)w >= sizeof file || !find_is_file(file))
                continue;
            int dup = 0;
            for (int q = 0; q < n && !dup; q++)
                dup = strncmp(list[q], e->d_name, len - 4) == 0 && list[q][len - 4] == '\0';
            if (dup)
                continue;
            if (n == cap) {
                int ncap = cap ? 2 * cap : 16;
                void *grown = cx_realloc(list, (size_t)ncap * sizeof *list);
                if (!grown) {
                    closedir(dir);
                    cx_free(list);
                    return cx_diag_set(d, CX_ENOMEM, "out of memory listing scenes");
                }
                list = grown;
                cap = ncap;
            }
            memcpy(list[n], e->d_name, len - 4);
            list[n++][len - 4] = '\0';
        }
        closedir(dir);
    }
    if (n == 0) {
        /* an empty list would look like a successful run with no scenes */
        char where[512];
        cx_data_describe("scenes", "SIGNORINI_SCENES", where, sizeof where);
        return cx_diag_set(d, CX_EIO, "no scenes found in %s (set SIGNORINI_DATA or SIGNORINI_SCENES)", where);
    }
    if (n > 1)
        qsort(list, (size_t)n, sizeof *list, find_cmp);
    *ids = list;
    *count = n;
    return CX_OK;
}

int cx_scene_open(const char *id_or_path, cx_scene *s, cx_diag *d)
{
    char path[512];
    CX_TRY(cx_scene_resolve(id_or_path, path, sizeof path, d));
    return cx_scene_load(s, path, d);
}
