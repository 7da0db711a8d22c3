/* SPDX-License-Identifier: GPL-3.0-or-later */
/* base/args.h: the option tables. Parsing of every type, ranges with open
 * and closed ends, --name=value, missing values, unknown options,
 * repeatable options, positional arguments, and a help that holds every
 * option with its range. */
#include "base/base.h"
#include "base/args.h"
#include "base/opt_solve.h"
#include "check.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    int verbose, count, mode;
    double ratio, gain;
    const char *out;
    cx_opt_list sets;
} args_t;

static int check_not_x(const char *text, cx_diag *d)
{
    return strcmp(text, "x") == 0 ? cx_diag_set(d, CX_EINVAL, "--out: 'x' is not a file name") : CX_OK;
}

static const cx_opt table[] = {
    {"verbose", 'v', CX_OPT_FLAG, 0, 0, 0, NULL, NULL, "say more", offsetof(args_t, verbose), NULL},
    {"count", 'n', CX_OPT_INT, 1, 10, 0, NULL, "N", "how many", offsetof(args_t, count), NULL},
    {"mode", 0, CX_OPT_CHOICE, 0, 0, 0, "fast|slow|exact", "M", "how", offsetof(args_t, mode), NULL},
    {"ratio", 0, CX_OPT_REAL, 0, 1, CX_OPT_MIN_OPEN | CX_OPT_MAX_OPEN, NULL, "R", "open both ends",
     offsetof(args_t, ratio), NULL},
    {"gain", 0, CX_OPT_REAL, 0, 2, CX_OPT_MAX_OPEN, NULL, "G", "closed below, open above",
     offsetof(args_t, gain), NULL},
    {"out", 'o', CX_OPT_STRING, 0, 0, 0, NULL, "FILE", "where\nthe output goes", offsetof(args_t, out),
     check_not_x},
    {"set", 0, CX_OPT_LIST, 0, 0, 0, NULL, "K=V", "repeatable", offsetof(args_t, sets), NULL},
    {NULL, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL}
};

/* Parse the words of line (space separated; argv[0] = "prog"). */
static int parse(const char *line, args_t *a, const char **pos, int maxpos, int *npos, cx_diag *d)
{
    static char buf[1024];
    static char *argv[128];
    snprintf(buf, sizeof buf, "prog %s", line);
    int argc = 0;
    for (char *save = NULL, *w = strtok_r(buf, " ", &save); w && argc < 128; w = strtok_r(NULL, " ", &save))
        argv[argc++] = w;
    memset(a, 0, sizeof *a);
    a->count = 3;
    a->ratio = 0.5;
    cx_opt_group groups[] = {{table, a}, {NULL, NULL}};
    cx_diag_clear(d);
    return cx_opt_parse(groups, argc, argv, pos, maxpos, npos, d);
}

int main(void)
{
    args_t a;
    cx_diag d;
    const char *pos[4];
    int npos;

    /* every type, both spellings of a value, short names, positionals */
    CX_CHECK_OK(parse("in.ini -v --count 7 --mode=slow --ratio 0.25 --gain=0 -o out.txt --set a=1 --set b=2 "
                      "more",
                      &a, pos, 4, &npos, &d));
    CX_CHECK(a.verbose == 1 && a.count == 7 && a.mode == 1);
    CX_CHECK_NEAR(a.ratio, 0.25, 0, 0);
    CX_CHECK_NEAR(a.gain, 0, 0, 0);
    CX_CHECK(a.out && strcmp(a.out, "out.txt") == 0);
    CX_CHECK(a.sets.n == 2 && strcmp(a.sets.v[0], "a=1") == 0 && strcmp(a.sets.v[1], "b=2") == 0);
    CX_CHECK(npos == 2 && strcmp(pos[0], "in.ini") == 0 && strcmp(pos[1], "more") == 0);
    /* what is not given keeps the caller's value; "-" alone is positional */
    CX_CHECK_OK(parse("-n 2 -", &a, pos, 4, &npos, &d));
    CX_CHECK(a.count == 2 && a.verbose == 0 && a.ratio == 0.5 && npos == 1 && strcmp(pos[0], "-") == 0);
    /* after "--" everything is positional */
    CX_CHECK_OK(parse("-- --count", &a, pos, 4, &npos, &d));
    CX_CHECK(npos == 1 && strcmp(pos[0], "--count") == 0 && a.count == 3);
    /* a value that starts with '-' is still the value */
    CX_CHECK(parse("--gain -1", &a, pos, 4, &npos, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "--gain '-1'") != NULL);

    /* ranges: closed ends take the end, open ends refuse it */
    CX_CHECK_OK(parse("--count 1", &a, pos, 0, NULL, &d));
    CX_CHECK_OK(parse("--count 10", &a, pos, 0, NULL, &d));
    CX_CHECK(parse("--count 11", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "--count '11': expected an integer in [1, 10]") != NULL);
    CX_CHECK(parse("--count 2.5", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK(parse("--ratio 0", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "--ratio '0': expected a number in (0, 1)") != NULL);
    CX_CHECK(parse("--ratio 1", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK_OK(parse("--ratio 1e-300", &a, pos, 0, NULL, &d));
    CX_CHECK_OK(parse("--gain 0", &a, pos, 0, NULL, &d));
    CX_CHECK(parse("--gain 2", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "[0, 2)") != NULL);
    CX_CHECK(parse("--gain nan", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK(parse("--ratio 0.5x", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK(parse("--mode quick", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "--mode 'quick': expected fast, slow or exact") != NULL);

    /* malformed lines: one line naming the culprit */
    CX_CHECK(parse("--count", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "option '--count' needs a value") != NULL);
    CX_CHECK(parse("-n", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK(parse("--bogus", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "unknown option '--bogus'") != NULL);
    CX_CHECK(parse("--countx 3", &a, pos, 0, NULL, &d) == CX_EINVAL);   /* no prefix matching */
    CX_CHECK(parse("-q", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK(parse("--verbose=1", &a, pos, 0, NULL, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "takes no value") != NULL);
    CX_CHECK(parse("a b", &a, pos, 1, &npos, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "unexpected argument 'b'") != NULL);
    CX_CHECK(parse("-o x", &a, pos, 0, NULL, &d) == CX_EINVAL);   /* the row's own check */
    CX_CHECK(strstr(d.msg, "'x' is not a file name") != NULL);
    CX_CHECK(!strchr(d.msg, '\n'));
    /* repeatable, up to its limit */
    {
        char line[(CX_OPT_LIST_MAX + 1) * sizeof "--set k=1 " + 1] = "";
        for (int k = 0; k <= CX_OPT_LIST_MAX; k++)
            strcat(line, "--set k=1 ");
        CX_CHECK(parse(line, &a, pos, 0, NULL, &d) == CX_EINVAL);
        CX_CHECK(a.sets.n == CX_OPT_LIST_MAX);
    }
    /* help wins over everything else on the line */
    CX_CHECK(parse("--bogus -h", &a, pos, 0, NULL, &d) == CX_OPT_HELP);
    CX_CHECK(parse("x --help", &a, pos, 0, NULL, &d) == CX_OPT_HELP);
    CX_CHECK(parse("-- --help", &a, pos, 1, &npos, &d) == CX_OK);

    /* the help: every option, its value's name, its range, its lines */
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    cx_opt_help(table, f);
    fclose(f);
    CX_CHECK(text != NULL);
    if (text) {
        for (const cx_opt *o = table; o->name; o++) {
            char want[64];
            snprintf(want, sizeof want, "--%s", o->name);
            CX_CHECK(strstr(text, want) != NULL);
        }
        CX_CHECK(strstr(text, "  -v, --verbose ") != NULL);
        CX_CHECK(strstr(text, "--count N") != NULL);
        CX_CHECK(strstr(text, "an integer in [1, 10]") != NULL);
        CX_CHECK(strstr(text, "a number in (0, 1)") != NULL);
        CX_CHECK(strstr(text, "a number in [0, 2)") != NULL);
        CX_CHECK(strstr(text, "\n                       the output goes") != NULL);
        int lines = 0;
        for (const char *c = text; *c; c++)
            lines += *c == '\n';
        CX_CHECK(lines == 8);   /* 7 rows, one of two lines */
        free(text);
    }

    /* the solve table: one range per option, as the explorer reads it */
    const cx_opt *tol = cx_opt_find(cx_solve_opts, "tol"), *maxit = cx_opt_find(cx_solve_opts, "max-iter");
    CX_CHECK(tol && maxit && !cx_opt_find(cx_solve_opts, "nope"));
    /* every row the explorer's value entry reads (tui/actions.c) */
    CX_CHECK(cx_opt_find(cx_solve_opts, "level") && cx_opt_find(cx_solve_opts, "F") &&
             cx_opt_find(cx_solve_opts, "slip"));
    {
        double x;
        const cx_opt *F = cx_opt_find(cx_solve_opts, "F");
        CX_CHECK(F && cx_opt_value(F, "0", &x, &d) == CX_OK && cx_opt_value(F, "-0.1", &x, &d) == CX_EINVAL);
        CX_CHECK(strstr(d.msg, "[0, inf)") != NULL);
    }
    if (tol && maxit) {
        CX_CHECK(!cx_opt_in_range(tol, 0) && !cx_opt_in_range(tol, 1) && cx_opt_in_range(tol, 1e-10));
        CX_CHECK(cx_opt_in_range(maxit, 1) && cx_opt_in_range(maxit, 1e8) && !cx_opt_in_range(maxit, 1e8 + 1));
        CX_CHECK(!cx_opt_in_range(maxit, 2.5));
        double x;
        CX_CHECK(cx_opt_value(tol, "1", &x, &d) == CX_EINVAL && strstr(d.msg, "(0, 1)"));
        CX_CHECK(cx_opt_value(maxit, "100000000", &x, &d) == CX_OK && x == 1e8);
    }
    cx_solve_args sa;
    cx_solve_args_default(&sa, 1e-10, 500, 1, 0);
    const char *scene = NULL;
    char *argv[] = {"solve", "--friction", "coulomb", "--stop", "kkt", "--F=0.3", "--set", "rho=1", "hertz",
                    NULL};
    cx_opt_group g[] = {{cx_solve_opts, &sa}, {NULL, NULL}};
    CX_CHECK_OK(cx_opt_parse(g, 9, argv, &scene, 1, &npos, &d));
    CX_CHECK(sa.friction == 2 && sa.own_stop == 0 && sa.F == 0.3 && isnan(sa.slip) && sa.sets.n == 1);
    CX_CHECK(scene && strcmp(scene, "hertz") == 0 && sa.tol == 1e-10 && sa.max_iter == 500);
    char *bad[] = {"solve", "--set", "rho", NULL};
    CX_CHECK(cx_opt_parse(g, 3, bad, &scene, 1, &npos, &d) == CX_EINVAL && strstr(d.msg, "key=value"));
    return check_finish("base_opt");
}
