/* SPDX-License-Identifier: GPL-3.0-or-later */
/* base/: parameter tables, strict parsing, diagnostics and the allocator. */
#include "base/base.h"
#include "check.h"

#include <string.h>

static const cx_param table[] = {
    {"rho", CX_PARAM_REAL, 1.0, 1e-6, 1e6, NULL, "a real", 0},
    {"r", CX_PARAM_REAL, 0.11, 1e-12, 1e12, NULL, "real or auto", CX_PARAM_AUTO},
    {"restart", CX_PARAM_INT, 20, 1, 1000, NULL, "an int", 0},
    {"adaptive", CX_PARAM_BOOL, 0, 0, 1, NULL, "a bool", 0},
    {"precision", CX_PARAM_CHOICE, 1, 0, 0, "fixed|adaptive", "a choice", 0},
    {"inner", CX_PARAM_STRING, 0, 0, 0, "ubr-tf", "a string", 0},
    {NULL, 0, 0, 0, 0, NULL, NULL, 0}
};

int main(void)
{
    cx_param_values v;
    cx_diag d;
    char buf[64];
    cx_param_default(&v, table);
    CX_CHECK(v.n == 6);
    CX_CHECK_NEAR(cx_param_get(&v, "rho"), 1.0, 0, 0);
    CX_CHECK(strcmp(cx_param_get_str(&v, "inner"), "ubr-tf") == 0);
    cx_param_format(&v, 4, buf, sizeof buf);
    CX_CHECK(strcmp(buf, "adaptive") == 0);

    CX_CHECK_OK(cx_param_set(&v, "rho", "2.5e3", "method 'x'", &d));
    CX_CHECK_NEAR(cx_param_get(&v, "rho"), 2500.0, 0, 0);
    CX_CHECK_OK(cx_param_set_pair(&v, "restart=30", "method 'x'", &d));
    CX_CHECK_NEAR(cx_param_get(&v, "restart"), 30, 0, 0);
    CX_CHECK_OK(cx_param_set(&v, "adaptive", "yes", "method 'x'", &d));
    CX_CHECK_NEAR(cx_param_get(&v, "adaptive"), 1, 0, 0);
    CX_CHECK_OK(cx_param_set(&v, "precision", "fixed", "method 'x'", &d));
    CX_CHECK_NEAR(cx_param_get(&v, "precision"), 0, 0, 0);
    CX_CHECK_OK(cx_param_set(&v, "r", "auto", "method 'x'", &d));
    cx_param_format(&v, 1, buf, sizeof buf);
    CX_CHECK(strcmp(buf, "auto") == 0);

    /* refusals name the key and the range, and leave the value */
    CX_CHECK(cx_param_set(&v, "rho", "-1", "method 'x'", &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "'rho'") && strstr(d.msg, "[1e-06, 1e+06]"));
    CX_CHECK_NEAR(cx_param_get(&v, "rho"), 2500.0, 0, 0);
    CX_CHECK(cx_param_set(&v, "rho", "abc", "method 'x'", &d) == CX_EINVAL);
    CX_CHECK(cx_param_set(&v, "rho", "nan", "method 'x'", &d) == CX_EINVAL);
    CX_CHECK(cx_param_set(&v, "restart", "2.5", "method 'x'", &d) == CX_EINVAL);
    CX_CHECK(cx_param_set(&v, "precision", "exact", "method 'x'", &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "fixed|adaptive") != NULL);
    CX_CHECK(cx_param_set(&v, "nope", "1", "method 'x'", &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, "unknown parameter 'nope' of method 'x'") != NULL);
    CX_CHECK(cx_param_set_pair(&v, "rho", "method 'x'", &d) == CX_EINVAL);

    /* strict numbers */
    double x;
    long k;
    CX_CHECK(cx_parse_double(" 1.5e3 ", &x) == 0 && x == 1500);
    CX_CHECK(cx_parse_double("2e3x", &x) != 0);
    CX_CHECK(cx_parse_double("", &x) != 0);
    CX_CHECK(cx_parse_double("inf", &x) != 0);
    CX_CHECK(cx_parse_int("12", 0, 20, &k) == 0 && k == 12);
    CX_CHECK(cx_parse_int("21", 0, 20, &k) != 0);
    double vec[3];
    CX_CHECK(cx_parse_doubles("1 -2.5 3", vec, 3) == 3 && vec[1] == -2.5);
    CX_CHECK(cx_parse_doubles("1 2 3 4", vec, 3) == -1);
    CX_CHECK(cx_parse_doubles("1 x", vec, 3) == -1);
    CX_CHECK(cx_parse_choice("b", "a|b|c") == 1 && cx_parse_choice("d", "a|b|c") == -1);

    /* status messages from the one list; diag is one line */
    CX_CHECK(strcmp(cx_status_str(CX_ENOMEM), "out of memory") == 0);
    CX_CHECK(cx_diag_set(&d, CX_EINVAL, "a\nb %d", 3) == CX_EINVAL);
    CX_CHECK(strcmp(d.msg, "a b 3") == 0);
    cx_diag_prefix(&d, "file.ini:%d", 4);
    CX_CHECK(strcmp(d.msg, "file.ini:4: a b 3") == 0);

    /* allocation failure injection */
    long live = cx_alloc_live();
    cx_alloc_fail_after(1);
    void *a = cx_malloc(8), *b = cx_malloc(8);
    cx_alloc_fail_after(-1);
    CX_CHECK(a != NULL && b == NULL);
    cx_free(a);
    CX_CHECK(cx_alloc_live() == live);
    return check_finish("base_param");
}
