/* SPDX-License-Identifier: GPL-3.0-or-later */
/* signorini list [--json]: scenes and methods, with what each supports and
 * each method's parameters (from the registry and the parameter tables). */
#include "cli/cli.h"
#include "out/out.h"

#include <stdio.h>
#include <string.h>

static const char list_usage[] =
    "usage: signorini list [--json]\n"
    "\n"
    "Lists the scenes (id, dimension, element, default level, friction, suited\n"
    "methods) and the methods (id, source, what each supports, parameters).\n";

typedef struct {
    int json;
} list_args;

static const cx_opt list_opts[] = {
    {"json", 0, CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "one JSON object on stdout instead of the text",
     offsetof(list_args, json), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

static void list_text(char (*ids)[CX_SCENE_NAMELEN], int nids)
{
    printf("scenes:\n");
    int w = 12;   /* the longest id (twoblocks-paper) sets the column */
    for (int k = 0; k < nids; k++)
        if ((int)strlen(ids[k]) > w)
            w = (int)strlen(ids[k]);
    for (int k = 0; k < nids; k++) {
        cx_scene sc;
        cx_diag d;
        if (cx_scene_open(ids[k], &sc, &d) != CX_OK) {
            printf("  %-*s (cannot load: %s)\n", w, ids[k], d.msg);
            continue;
        }
        printf("  %-*s %dD %-5s level %-3d friction %-7s %s\n", w, sc.id, sc.dim, cx_elem_name(sc.element),
               sc.level, cx_friction_name(sc.friction), sc.title);
    }
    printf("\nmethods:\n");
    for (int k = 0; k < cx_method_count(); k++) {
        const cx_method *m = cx_method_at(k);
        char buf[128];
        cx_list_supports(m->supports, buf, sizeof buf);
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
    list_args a = {0};
    cx_opt_group groups[] = {{list_opts, &a}, {NULL, NULL}};
    cx_diag d;
    int parsed = cx_opt_parse(groups, argc, argv, NULL, 0, NULL, &d);
    if (parsed == CX_OPT_HELP) {
        const cx_opt *const tables[] = {list_opts, NULL};
        cli_help(list_usage, tables, stdout);
        return CX_EXIT_OK;
    }
    if (parsed)
        return cli_usage("list", d.msg);
    int json = a.json;
    char (*ids)[CX_SCENE_NAMELEN] = NULL;
    int nids = 0;
    if (cx_scene_list(&ids, &nids, &d))
        return cli_fail("list", d.msg);
    if (json)
        cx_list_write_json(ids, nids, stdout);
    else
        list_text(ids, nids);
    cx_free(ids);
    /* a list lost on a full disk is an error */
    if (cx_outfile_close_stdout(&d))
        return cli_fail("list", d.msg);
    return CX_EXIT_OK;
}
