/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Strict parsing of numbers and words, shared by the scene reader, the
 * parameter tables and the command line: the whole text must be consumed,
 * numbers must be finite. */
#ifndef CX_PARSE_H
#define CX_PARSE_H

/* 0 on success; -1 if text is not one finite number. */
int cx_parse_double(const char *text, double *out);

/* 0 on success; -1 if text is not one integer within [min, max]. */
int cx_parse_int(const char *text, long min, long max, long *out);

/* Parse up to max whitespace-separated numbers; returns how many were read,
 * or -1 if a word is not a finite number or there are more than max. */
int cx_parse_doubles(const char *text, double *out, int max);

/* Index of word in "a|b|c", or -1. */
int cx_parse_choice(const char *text, const char *choices);

#endif
