/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The library's allocator. Every allocation of the library goes through
 * these, so that tests can count live blocks and make the N-th allocation
 * fail (cx_alloc_fail_after) to check that constructors clean up. All of
 * it may be used from several threads at once. */
#ifndef CX_ALLOC_H
#define CX_ALLOC_H

#include <stddef.h>

void *cx_malloc(size_t size);
void *cx_calloc(size_t count, size_t size);   /* overflow-checked */
void *cx_realloc(void *p, size_t size);
void cx_free(void *p);                        /* NULL is fine */

/* Allocate count elements of type T; NULL on failure. */
#define CX_NEW(T, count) ((T *)cx_calloc((size_t)(count), sizeof(T)))

/* Test hooks, safe to call from any thread.
 * cx_alloc_fail_after: the calling thread's next n allocations succeed,
 * every one after them fails (n < 0 turns failures off); other threads'
 * allocations are not affected.
 * cx_alloc_live: live blocks of the whole process.
 * cx_alloc_live_thread: blocks allocated minus blocks freed by the calling
 * thread (negative if it frees what another thread made): a thread that
 * checks its own work for leaks while others allocate compares this one. */
void cx_alloc_fail_after(long n);
long cx_alloc_live(void);
long cx_alloc_live_thread(void);

#endif
