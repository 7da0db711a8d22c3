#include "base/alloc.h"

#include <stdint.h>
#include <stdlib.h>

/* Counters are plain globals: the library is single-threaded per session and
 * these exist for tests. */
static long alloc_live;
static long alloc_budget = -1;

static int alloc_should_fail(void)
{
    if (alloc_budget < 0)
        return 0;
    if (alloc_budget == 0)
        return 1;
    alloc_budget--;
    return 0;
}

void *cx_malloc(size_t size)
{
    if (alloc_should_fail())
        return NULL;
    void *p = malloc(size ? size : 1);
    if (p)
        alloc_live++;
    return p;
}

void *cx_calloc(size_t count, size_t size)
{
    if (size && count > SIZE_MAX / size)
        return NULL;
    if (alloc_should_fail())
        return NULL;
    void *p = calloc(count ? count : 1, size ? size : 1);
    if (p)
        alloc_live++;
    return p;
}

void *cx_realloc(void *p, size_t size)
{
    if (!p)
        return cx_malloc(size);
    if (alloc_should_fail())
        return NULL;
    return realloc(p, size ? size : 1);
}

void cx_free(void *p)
{
    if (p) {
        alloc_live--;
        free(p);
    }
}

void cx_alloc_fail_after(long n) { alloc_budget = n; }
long cx_alloc_live(void) { return alloc_live; }
