/* Private to solve/: the session's fields, shared by session.c and
 * solver.c. */
#ifndef CX_SESSION_IMPL_H
#define CX_SESSION_IMPL_H

#include "solve/solve.h"

typedef struct cx_cache_entry {
    char key[CX_CACHE_KEYLEN];
    void *obj;
    cx_cache_destroy_fn destroy;
} cx_cache_entry;

struct cx_session {
    cx_problem *p;               /* owned */
    cx_schur *schur;             /* operator cache: K condensed onto p->cdofs, lazy */
    cx_cache_entry *entries;     /* operator cache: everything else, by key */
    int nentries, centries;
    cx_counters cache;           /* work of building the cache, all runs */
    cx_counters run;             /* work of the current run (linalg writes here) */
    const cx_method *method;     /* current method, or NULL */
    void *state;                 /* its private state (method->state_size bytes) */
    cx_param_values params;
    cx_options opt;
    cx_iterate it;
    double *work;                /* n + m + nt, for the kkt error */
    double best_kkt;             /* stall detection: best kkt so far ... */
    int best_iter;               /* ... and when it last halved */
    char reason_msg[CX_DIAG_LEN];/* why a run broke down */
};

#endif
