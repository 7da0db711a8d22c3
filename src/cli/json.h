/* A small streaming JSON writer for --json output: keys in order, commas
 * managed, NaN/Inf written as null (JSON has no NaN). */
#ifndef CLI_JSON_H
#define CLI_JSON_H

#include <stdio.h>

typedef struct cli_json {
    FILE *out;
    int depth;
    int count[32];     /* members written at each depth */
} cli_json;

void cli_json_init(cli_json *j, FILE *out);     /* writes nothing yet */
/* key is NULL inside arrays and for the top-level value */
void cli_json_object(cli_json *j, const char *key);
void cli_json_array(cli_json *j, const char *key);
void cli_json_end_object(cli_json *j);
void cli_json_end_array(cli_json *j);
void cli_json_num(cli_json *j, const char *key, double v);
void cli_json_int(cli_json *j, const char *key, long v);
void cli_json_bool(cli_json *j, const char *key, int v);
void cli_json_str(cli_json *j, const char *key, const char *v);
void cli_json_null(cli_json *j, const char *key);
void cli_json_vec(cli_json *j, const char *key, const double *v, int n);

#endif
