/* Reading "--name value" options (see args.h). */
#include "base/args.h"

#include <string.h>

#include "base/parse.h"

int cx_arg_option(int argc, char **argv, int *i, const char *name, const char **value, cx_diag *d)
{
    const char *a = argv[*i];
    size_t len = strlen(name);
    if (strncmp(a, name, len) != 0)
        return 0;
    if (a[len] == '=') {
        *value = a + len + 1;
        return 1;
    }
    if (a[len] != '\0')
        return 0;
    if (*i + 1 >= argc) {
        cx_diag_set(d, CX_EINVAL, "option '%s' needs a value", name);
        return -1;
    }
    *value = argv[++*i];
    return 1;
}

int cx_arg_level(const char *v, int *level, cx_diag *d)
{
    long n;
    if (cx_parse_int(v, 1, 1 << 20, &n))
        return cx_diag_set(d, CX_EINVAL, "--level '%s': expected a positive integer", v);
    *level = (int)n;
    return CX_OK;
}
