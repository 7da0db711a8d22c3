/* Cell counts of a mesh level: level L refines the scene's base cells L
 * times along each direction the generator has (hertz: one count; the
 * rectangle two; the brick three); the other entries are 1. */
#include "scene/scene.h"

#include <limits.h>
#include <string.h>

void cx_scene_cells(const cx_scene *s, int level, int cells[3])
{
    int used = s->generator == CX_GEN_HERTZ ? 1 : s->dim;
    if (level <= 0)
        level = s->level;
    for (int k = 0; k < 3; k++) {
        long long c = k < used ? (long long)level * (s->cells[k] > 0 ? s->cells[k] : 1) : 1;
        cells[k] = c > INT_MAX ? INT_MAX : (int)c;
    }
}

void cx_scene_cells_lower(const cx_scene *s, int level, int cells[3])
{
    cx_scene tmp = *s;
    memcpy(tmp.cells, s->cells_lower, sizeof tmp.cells);
    cx_scene_cells(&tmp, level, cells);
}
