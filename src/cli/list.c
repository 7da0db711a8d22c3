/* signorini list [--json]: scenes and methods, with what each supports and
 * each method's parameters (from the registry and the parameter tables). */
#include "cli/cli.h"
#include "out/json.h"

#include <stdio.h>
#include <string.h>

static const char list_usage[] =
    "usage: signorini list [--json]\n"
    "\n"
    "Lists the scenes (id, dimension, element, default level, friction, suited\n"
    "methods) and the methods (id, source, what each supports, parameters).\n";

static void list_supports(unsigned f, char *buf, size_t len)
{
    snprintf(buf, len, "%s%s%s%s%s%s", (f & CX_FRICTIONLESS) ? "frictionless " : "",
             (f & CX_TRESCA) ? "tresca " : "", (f & CX_COULOMB) ? "coulomb " : "",
             (f & CX_2D) ? "2d " : "", (f & CX_3D) ? "3d " : "", (f & CX_MULTIBODY) ? "multibody " : "");
    size_t l = strlen(buf);
    if (l && buf[l - 1] == ' ')
        buf[l - 1] = '\0';
}

static void list_json(char (*ids)[CX_SCENE_NAMELEN], int nids)
{
    cx_json j;
    cx_json_init(&j, stdout);
    cx_json_object(&j, NULL);
    cx_json_array(&j, "scenes");
    for (int k = 0; k < nids; k++) {
        cx_scene sc;
        cx_diag d;
        cx_json_object(&j, NULL);
        cx_json_str(&j, "id", ids[k]);
        if (cx_scene_open(ids[k], &sc, &d) == CX_OK) {
            cx_json_str(&j, "title", sc.title);
            cx_json_int(&j, "dim", sc.dim);
            cx_json_str(&j, "element", cx_elem_name(sc.element));
            cx_json_int(&j, "level", sc.level);
            cx_json_int(&j, "level_max", sc.level_max);
            cx_json_str(&j, "friction", cx_friction_name(sc.friction));
            cx_json_str(&j, "obstacle", cx_obstacle_name(sc.obstacle.kind));
            cx_json_array(&j, "methods");
            for (int q = 0; q < sc.nmethods; q++)
                cx_json_str(&j, NULL, sc.methods[q]);
            cx_json_end_array(&j);
        } else {
            cx_json_str(&j, "error", d.msg);
        }
        cx_json_end_object(&j);
    }
    cx_json_end_array(&j);
    cx_json_array(&j, "methods");
    for (int k = 0; k < cx_method_count(); k++) {
        const cx_method *m = cx_method_at(k);
        char buf[128];
        cx_json_object(&j, NULL);
        cx_json_str(&j, "id", m->id);
        cx_json_str(&j, "name", m->name);
        cx_json_str(&j, "source", m->source);
        cx_json_str(&j, "summary", m->summary);
        list_supports(m->supports, buf, sizeof buf);
        cx_json_str(&j, "supports", buf);
        cx_json_array(&j, "params");
        cx_param_values pv;
        cx_param_default(&pv, m->params);
        for (int q = 0; q < pv.n; q++) {
            static const char *const types[] = {"real", "int", "bool", "choice", "string"};
            cx_json_object(&j, NULL);
            cx_json_str(&j, "key", pv.table[q].key);
            cx_json_str(&j, "type", types[pv.table[q].type]);
            cx_param_format(&pv, q, buf, sizeof buf);
            cx_json_str(&j, "default", buf);
            cx_param_range(&pv.table[q], buf, sizeof buf);
            cx_json_str(&j, "range", buf);
            cx_json_str(&j, "help", pv.table[q].help);
            cx_json_end_object(&j);
        }
        cx_json_end_array(&j);
        cx_json_end_object(&j);
    }
    cx_json_end_array(&j);
    cx_json_end_object(&j);
}

static void list_text(char (*ids)[CX_SCENE_NAMELEN], int nids)
{
    printf("scenes:\n");
    for (int k = 0; k < nids; k++) {
        cx_scene sc;
        cx_diag d;
        if (cx_scene_open(ids[k], &sc, &d) != CX_OK) {
            printf("  %-12s (cannot load: %s)\n", ids[k], d.msg);
            continue;
        }
        printf("  %-12s %dD %-5s level %-3d friction %-7s %s\n", sc.id, sc.dim, cx_elem_name(sc.element),
               sc.level, cx_friction_name(sc.friction), sc.title);
    }
    printf("\nmethods:\n");
    for (int k = 0; k < cx_method_count(); k++) {
        const cx_method *m = cx_method_at(k);
        char buf[128];
        list_supports(m->supports, buf, sizeof buf);
        printf("  %-12s %s (%s)\n  %-12s supports: %s\n", m->id, m->name, m->source, "", buf);
        cx_param_values pv;
        cx_param_default(&pv, m->params);
        for (int q = 0; q < pv.n; q++) {
            char def[64], range[96];
            cx_param_format(&pv, q, def, sizeof def);
            cx_param_range(&pv.table[q], range, sizeof range);
            printf("  %-12s --set %s=%s  %s; %s\n", "", pv.table[q].key, def, range, pv.table[q].help);
        }
    }
}

int cli_list(int argc, char **argv)
{
    int json = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--json") == 0)
            json = 1;
        else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            fputs(list_usage, stdout);
            return CX_EXIT_OK;
        } else {
            char msg[160];
            snprintf(msg, sizeof msg, "unknown option '%s' (see 'signorini list --help')", argv[i]);
            return cli_fail("list", msg);
        }
    }
    char (*ids)[CX_SCENE_NAMELEN] = NULL;
    int nids = 0;
    cx_diag d;
    if (cx_scene_list(&ids, &nids, &d))
        return cli_fail("list", d.msg);
    if (json)
        list_json(ids, nids);
    else
        list_text(ids, nids);
    cx_free(ids);
    return CX_EXIT_OK;
}
