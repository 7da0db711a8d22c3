/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Reporting a command-line failure and writing a command's help (the
 * option tables and their parser are base/args.h). */
#include "cli/cli.h"

#include <stdio.h>
#include <string.h>

int cli_fail(const char *cmd, const char *msg)
{
    char safe[2048];   /* msg may quote input: print it escaped */
    fprintf(stderr, "signorini %s: %s\n", cmd, cx_escape(safe, sizeof safe, msg, strlen(msg)));
    return CX_EXIT_ERROR;
}

int cli_usage(const char *cmd, const char *msg)
{
    /* a message that names where to look already is not given a second pointer */
    if (strstr(msg, "(see "))
        fprintf(stderr, "signorini %s: %s\n", cmd, msg);
    else
        fprintf(stderr, "signorini %s: %s (see 'signorini %s --help')\n", cmd, msg, cmd);
    return CX_EXIT_USAGE;
}

void cli_help(const char *usage, const cx_opt *const *tables, FILE *out)
{
    fputs(usage, out);
    fputs("\n  -h, --help           this help\n", out);
    for (int k = 0; tables[k]; k++)
        cx_opt_help(tables[k], out);
}
