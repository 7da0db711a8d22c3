/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Cell counts of a mesh level: level L refines the scene's base cells
 * along each direction the generator has (hertz: one count; the rectangle
 * two; the brick three); the other entries are 1. The linear rule takes
 * L * cells; the sqrt2 rule (paper 001, Table 1) ceil(cells * 2^(L/2)),
 * with the power of two exact for even L. */
#include "scene/scene.h"

#include <limits.h>
#include <string.h>
#include <math.h>

static long long cells_of(const cx_scene *s, int level, int base)
{
    if (s->level_rule == CX_LEVEL_LINEAR)
        return (long long)level * base;
    if (level >= 2 * 62)
        return LLONG_MAX;
    /* base * 2^(L/2): exact integer part, times sqrt(2) for odd L */
    double c = ldexp((double)base, level / 2);
    if (level % 2)
        c = ceil(c * sqrt(2.0));
    return c >= (double)INT_MAX ? LLONG_MAX : (long long)c;
}

void cx_scene_cells(const cx_scene *s, int level, int cells[3])
{
    int used = s->generator == CX_GEN_HERTZ ? 1 : s->dim;
    if (level <= 0)
        level = s->level;
    for (int k = 0; k < 3; k++) {
        long long c = k < used ? cells_of(s, level, s->cells[k] > 0 ? s->cells[k] : 1) : 1;
        cells[k] = c > INT_MAX ? INT_MAX : (int)c;
    }
}

void cx_scene_cells_lower(const cx_scene *s, int level, int cells[3])
{
    cx_scene tmp = *s;
    memcpy(tmp.cells, s->cells_lower, sizeof tmp.cells);
    cx_scene_cells(&tmp, level, cells);
}
