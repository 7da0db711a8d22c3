/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Parameter tables: a method (or any component) declares its parameters once
 * in a static const cx_param table, terminated by an entry with key NULL.
 * The --set parser, the explorer's parameter panel, 'signorini list' and the
 * JSON echo all read the same table, so they cannot disagree. */
#ifndef CX_PARAM_H
#define CX_PARAM_H

#include "base/diag.h"

#include <stddef.h>

typedef enum cx_param_type {
    CX_PARAM_REAL,    /* a finite number in [min, max] */
    CX_PARAM_INT,     /* an integer in [min, max] */
    CX_PARAM_BOOL,    /* 0/1, true/false, yes/no, on/off */
    CX_PARAM_CHOICE,  /* one word of choices "a|b|c"; stored as its index */
    CX_PARAM_STRING   /* free text (e.g. the id of an inner method); default in choices */
} cx_param_type;

/* flags */
#define CX_PARAM_AUTO 1u      /* REAL that also accepts "auto" (stored as NaN) */
#define CX_PARAM_MIN_OPEN 2u  /* REAL: min itself is outside the range: (min, ... */
#define CX_PARAM_MAX_OPEN 4u  /* REAL: max itself is outside the range: ..., max) */

typedef struct cx_param {
    const char *key;      /* lower_snake */
    cx_param_type type;
    double def;           /* default (REAL/INT/BOOL; CHOICE: index) */
    double min, max;      /* range (REAL/INT): inclusive unless a *_OPEN flag says */
    const char *choices;  /* CHOICE: "a|b|c"; STRING: the default text */
    const char *help;     /* one line */
    unsigned flags;
} cx_param;

#define CX_PARAM_MAX 24
#define CX_PARAM_STRLEN 48

/* The values of one table. A plain struct the owner keeps by value. */
typedef struct cx_param_values {
    const cx_param *table;                  /* borrowed, static */
    int n;
    double num[CX_PARAM_MAX];               /* REAL/INT/BOOL/CHOICE; NaN = auto */
    char str[CX_PARAM_MAX][CX_PARAM_STRLEN];/* STRING */
} cx_param_values;

/* Number of entries of a table (up to the NULL key). */
int cx_param_count(const cx_param *table);

/* Fill v with the defaults of table (table may be NULL: no parameters). */
void cx_param_default(cx_param_values *v, const cx_param *table);

/* Index of key in v's table, or -1. */
int cx_param_find(const cx_param_values *v, const char *key);

/* Parse text for key and store it. CX_EINVAL with a message naming the key
 * and the allowed range/choices when the key is unknown or the value bad;
 * owner names what the table belongs to ("method 'pdas'"). */
int cx_param_set(cx_param_values *v, const char *key, const char *text,
                 const char *owner, cx_diag *d);

/* Parse text as a value of p (REAL/INT/BOOL/CHOICE) and check its range:
 * 0 and *x set, or -1. The one range check of parameters and options. */
int cx_param_value(const cx_param *p, const char *text, double *x);

/* Parse "key=value" (as given to --set). */
int cx_param_set_pair(cx_param_values *v, const char *pair,
                      const char *owner, cx_diag *d);

/* Value by key; NaN for an unknown key (a programming error: asserts). */
double cx_param_get(const cx_param_values *v, const char *key);
const char *cx_param_get_str(const cx_param_values *v, const char *key);

/* The value of entry i as text ("0.11", "auto", "true", "ubr-tf"). */
void cx_param_format(const cx_param_values *v, int i, char *buf, size_t len);

/* The allowed values of p as text ("[0.001, 1e+30]", "(0, 1)", "fixed|adaptive"). */
void cx_param_range(const cx_param *p, char *buf, size_t len);

#endif
