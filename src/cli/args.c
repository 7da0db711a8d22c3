/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Reporting a command-line failure and writing a command's help (the
 * option tables and their parser are base/args.h). */
#include "cli/cli.h"
#include "cli/progress.h"

#include <stdio.h>
#include <string.h>

int cli_fail(const char *cmd, const char *msg)
{
    cli_progress_stop();   /* the message on a line of its own */
    return cx_arg_report(stderr, cmd, msg, CX_EXIT_ERROR);
}

int cli_usage(const char *cmd, const char *msg)
{
    cli_progress_stop();
    return cx_arg_report(stderr, cmd, msg, CX_EXIT_USAGE);
}

void cli_help(const char *usage, const cx_opt *const *tables, FILE *out)
{
    fputs(usage, out);
    fputs("\n  -h, --help           this help\n", out);
    for (int k = 0; tables[k]; k++)
        cx_opt_help(tables[k], out);
}
