/* Reporting a command-line failure (the parsing helpers are base/args.h). */
#include "cli/cli.h"

#include <stdio.h>

int cli_fail(const char *cmd, const char *msg)
{
    fprintf(stderr, "signorini %s: %s\n", cmd, msg);
    return CX_EXIT_ERROR;
}
