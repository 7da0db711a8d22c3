/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Sorting by keys without a comparator context. qsort's comparator gets no
 * user pointer (qsort_r is a GNU extension), and a file-scope static that
 * hands it the coordinates is shared by every thread: two sessions built
 * at once would sort by each other's meshes. Instead each element carries
 * its keys. */
#ifndef CX_SORT_H
#define CX_SORT_H

#include <stddef.h>

#define CX_SORT_MAXKEY 3

/* An id and the keys it is sorted by, most significant first (unused keys
 * left at 0). */
typedef struct cx_sort_key {
    double key[CX_SORT_MAXKEY];
    int id;
} cx_sort_key;

/* Sort a[0..n) by key[0], key[1], key[2], then by id: equal keys keep the
 * order of their ids, so the result does not depend on the qsort at hand.
 * Thread-safe. */
void cx_sort_keys(cx_sort_key *a, size_t n);

#endif
