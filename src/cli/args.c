/* Reporting a command-line failure (the parsing helpers are base/args.h). */
#include "cli/cli.h"

#include <stdio.h>
#include <string.h>

int cli_fail(const char *cmd, const char *msg)
{
    char safe[2048];   /* msg may quote input: print it escaped */
    fprintf(stderr, "signorini %s: %s\n", cmd, cx_escape(safe, sizeof safe, msg, strlen(msg)));
    return CX_EXIT_ERROR;
}
