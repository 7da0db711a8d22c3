/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "base/alloc.h"

#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>

/* Two sessions may run on two threads (the explorer runs library code on a
 * worker thread), so the counters are either atomic or per thread:
 *   alloc_live         live blocks of the whole process: a block may be
 *                      freed by another thread than the one that made it
 *                      (the explorer's results), so one shared count, atomic;
 *   alloc_live_thread  blocks made minus blocks freed by this thread;
 *   alloc_budget       the failure injection of this thread only, so that a
 *                      test forcing failures never fails another thread's
 *                      allocations.
 * Relaxed order is enough: the counts order nothing else. */
static atomic_long alloc_live;
static _Thread_local long alloc_live_thread;
static _Thread_local long alloc_budget = -1;

static int alloc_should_fail(void)
{
    if (alloc_budget < 0)
        return 0;
    if (alloc_budget == 0)
        return 1;
    alloc_budget--;
    return 0;
}

static void *alloc_counted(void *p)
{
    if (p) {
        atomic_fetch_add_explicit(&alloc_live, 1, memory_order_relaxed);
        alloc_live_thread++;
    }
    return p;
}

void *cx_malloc(size_t size)
{
    if (alloc_should_fail())
        return NULL;
    return alloc_counted(malloc(size ? size : 1));
}

void *cx_calloc(size_t count, size_t size)
{
    if (size && count > SIZE_MAX / size)
        return NULL;
    if (alloc_should_fail())
        return NULL;
    return alloc_counted(calloc(count ? count : 1, size ? size : 1));
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
        atomic_fetch_sub_explicit(&alloc_live, 1, memory_order_relaxed);
        alloc_live_thread--;
        free(p);
    }
}

void cx_alloc_fail_after(long n) { alloc_budget = n; }
long cx_alloc_live(void) { return atomic_load_explicit(&alloc_live, memory_order_relaxed); }
long cx_alloc_live_thread(void) { return alloc_live_thread; }
