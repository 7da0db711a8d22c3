/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The progress hook of long steps (linalg.h): one per thread, so that a
 * program draws the steps of the run it started and an explorer's worker
 * thread, or a library user's thread, sees nothing it did not ask for. */
#include "linalg/linalg.h"

static _Thread_local const cx_progress *progress_hook;

const cx_progress *cx_progress_set(const cx_progress *p)
{
    const cx_progress *old = progress_hook;
    progress_hook = p;
    return old;
}

void cx_progress_step(const char *what, double size)
{
    const cx_progress *p = progress_hook;
    if (p && p->step)
        p->step(p->ctx, what, size);
}
