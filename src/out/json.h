/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A small streaming JSON writer for --json output: keys in order, commas
 * managed, NaN/Inf written as null (JSON has no NaN). */
#ifndef CX_OUT_JSON_H
#define CX_OUT_JSON_H

#include <stdio.h>

typedef struct cx_json {
    FILE *out;
    int depth;
    int count[32];     /* members written at each depth */
} cx_json;

void cx_json_init(cx_json *j, FILE *out);     /* writes nothing yet */
/* key is NULL inside arrays and for the top-level value */
void cx_json_object(cx_json *j, const char *key);
void cx_json_array(cx_json *j, const char *key);
void cx_json_end_object(cx_json *j);
void cx_json_end_array(cx_json *j);
void cx_json_num(cx_json *j, const char *key, double v);
void cx_json_int(cx_json *j, const char *key, long v);
void cx_json_bool(cx_json *j, const char *key, int v);
void cx_json_str(cx_json *j, const char *key, const char *v);
void cx_json_null(cx_json *j, const char *key);
void cx_json_vec(cx_json *j, const char *key, const double *v, int n);

#endif
