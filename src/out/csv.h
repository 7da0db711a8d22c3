/* SPDX-License-Identifier: GPL-3.0-or-later */
/* out/csv.h: the one CSV writer (RFC 4180 quoting), for the bench's tables
 * and the explorer's export. Header lines "# key: value" may come first;
 * readers skip lines that start with '#'. A number that is not finite is
 * an empty cell (never "nan"). Writes go to a FILE the caller opened (an
 * out/outfile.h file); errors stay in the stream (ferror), checked when it
 * is closed. */
#ifndef CX_OUT_CSV_H
#define CX_OUT_CSV_H

#include <stdio.h>

typedef struct cx_csv {
    FILE *out;
    int col;           /* cells written in the current row */
} cx_csv;

void cx_csv_init(cx_csv *c, FILE *out);
/* "# key: value" (before the first row). */
void cx_csv_comment(cx_csv *c, const char *key, const char *value);
/* One cell: text (quoted when it holds a comma, quote or line break), a
 * number with %.17g (or fmt, e.g. "%.10g"), an integer, an empty cell. */
void cx_csv_str(cx_csv *c, const char *s);
void cx_csv_num(cx_csv *c, double v);
void cx_csv_numf(cx_csv *c, const char *fmt, double v);
void cx_csv_int(cx_csv *c, long v);
void cx_csv_empty(cx_csv *c);
void cx_csv_end_row(cx_csv *c);

#endif
