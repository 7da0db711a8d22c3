/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "base/sort.h"

#include <stdlib.h>

static int sort_cmp(const void *pa, const void *pb)
{
    const cx_sort_key *a = pa, *b = pb;
    for (int k = 0; k < CX_SORT_MAXKEY; k++) {
        if (a->key[k] < b->key[k])
            return -1;
        if (a->key[k] > b->key[k])
            return 1;
    }
    return (a->id > b->id) - (a->id < b->id);
}

void cx_sort_keys(cx_sort_key *a, size_t n)
{
    if (n > 1)
        qsort(a, n, sizeof *a, sort_cmp);
}
