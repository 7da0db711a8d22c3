/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The JSON of 'signorini list --json': scenes and methods, from the scene
 * files and the method registry with its parameter tables. */
#include "out/out.h"

#include <string.h>

void cx_list_supports(unsigned f, char *buf, size_t len)
{
    snprintf(buf, len, "%s%s%s%s%s%s", (f & CX_FRICTIONLESS) ? "frictionless " : "",
             (f & CX_TRESCA) ? "tresca " : "", (f & CX_COULOMB) ? "coulomb " : "",
             (f & CX_2D) ? "2d " : "", (f & CX_3D) ? "3d " : "", (f & CX_MULTIBODY) ? "multibody " : "");
    size_t l = strlen(buf);
    if (l && buf[l - 1] == ' ')
        buf[l - 1] = '\0';
}

static void list_scene(cx_json *j, const char *id)
{
    cx_scene sc;
    cx_diag d;
    cx_json_object(j, NULL);
    cx_json_str(j, "id", id);
    if (cx_scene_open(id, &sc, &d) == CX_OK) {
        cx_json_str(j, "title", sc.title);
        cx_json_int(j, "dim", sc.dim);
        cx_json_str(j, "element", cx_elem_name(sc.element));
        cx_json_int(j, "level", sc.level);
        cx_json_int(j, "level_max", sc.level_max);
        cx_json_str(j, "friction", cx_friction_name(sc.friction));
        cx_json_str(j, "obstacle", cx_obstacle_name(sc.obstacle.kind));
        cx_json_array(j, "methods");
        for (int q = 0; q < sc.nmethods; q++)
            cx_json_str(j, NULL, sc.methods[q]);
        cx_json_end_array(j);
    } else {
        cx_json_str(j, "error", d.msg);
    }
    cx_json_end_object(j);
}

static void list_method(cx_json *j, const cx_method *m)
{
    static const char *const types[] = {"real", "int", "bool", "choice", "string"};
    char buf[128];
    cx_json_object(j, NULL);
    cx_json_str(j, "id", m->id);
    cx_json_str(j, "name", m->name);
    cx_json_str(j, "source", m->source);
    cx_json_str(j, "summary", m->summary);
    cx_list_supports(m->supports, buf, sizeof buf);
    cx_json_str(j, "supports", buf);
    cx_json_array(j, "params");
    cx_param_values pv;
    cx_param_default(&pv, m->params);
    for (int q = 0; q < pv.n; q++) {
        cx_json_object(j, NULL);
        cx_json_str(j, "key", pv.table[q].key);
        cx_json_str(j, "type", types[pv.table[q].type]);
        cx_param_format(&pv, q, buf, sizeof buf);
        cx_json_str(j, "default", buf);
        cx_param_range(&pv.table[q], buf, sizeof buf);
        cx_json_str(j, "range", buf);
        cx_json_str(j, "help", pv.table[q].help);
        cx_json_end_object(j);
    }
    cx_json_end_array(j);
    cx_json_end_object(j);
}

int cx_list_write_json(char (*ids)[CX_SCENE_NAMELEN], int nids, FILE *out)
{
    cx_json j;
    cx_json_init(&j, out);
    cx_json_object(&j, NULL);
    cx_json_array(&j, "scenes");
    for (int k = 0; k < nids; k++)
        list_scene(&j, ids[k]);
    cx_json_end_array(&j);
    cx_json_array(&j, "methods");
    for (int k = 0; k < cx_method_count(); k++)
        list_method(&j, cx_method_at(k));
    cx_json_end_array(&j);
    cx_json_end_object(&j);
    return ferror(out) ? CX_EIO : CX_OK;
}
