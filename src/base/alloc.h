/* The library's allocator. Every allocation of the library goes through
 * these, so that tests can count live blocks and make the N-th allocation
 * fail (cx_alloc_fail_after) to check that constructors clean up. */
#ifndef CX_ALLOC_H
#define CX_ALLOC_H

#include <stddef.h>

void *cx_malloc(size_t size);
void *cx_calloc(size_t count, size_t size);   /* overflow-checked */
void *cx_realloc(void *p, size_t size);
void cx_free(void *p);                        /* NULL is fine */

/* Allocate count elements of type T; NULL on failure. */
#define CX_NEW(T, count) ((T *)cx_calloc((size_t)(count), sizeof(T)))

/* Test hooks: make every allocation after the next n succeed... fail
 * (n < 0 turns failures off), and the number of live blocks. */
void cx_alloc_fail_after(long n);
long cx_alloc_live(void);

#endif
