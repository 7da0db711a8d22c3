/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The history of runs: a fixed table of the last TUI_MAX_RUNS runs on the
 * current scene and level, each with its steps. No curses here. */
#include "tui/tui_impl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

tui_history *tui_history_create(void)
{
    tui_history *h = tui_xalloc(NULL, sizeof *h);
    memset(h, 0, sizeof *h);
    return h;
}

static void run_free(tui_run *r)
{
    free(r->steps);
    memset(r, 0, sizeof *r);
}

void tui_history_clear(tui_history *h)
{
    for (int i = 0; i < h->nruns; i++)
        run_free(&h->runs[i]);
    h->nruns = 0;
    h->next_serial = 0;
}

void tui_history_destroy(tui_history **h)
{
    if (!h || !*h)
        return;
    tui_history_clear(*h);
    free(*h);
    *h = NULL;
}

void tui_history_keep_current(tui_history *h)
{
    if (h->nruns > 1) {
        for (int i = 0; i < h->nruns - 1; i++)
            free(h->runs[i].steps);
        h->runs[0] = h->runs[h->nruns - 1];
        memset(&h->runs[h->nruns - 1], 0, sizeof h->runs[0]);
        h->nruns = 1;
    }
}

tui_run *tui_history_new_run(tui_history *h)
{
    /* an empty current run gives its number (and colour) to its successor;
     * one that ended without a step (a PETSc run refused or broken down at
     * its start) stays, with its outcome */
    if (h->nruns && h->runs[h->nruns - 1].nsteps == 0 && h->runs[h->nruns - 1].reason == CX_ITERATING) {
        run_free(&h->runs[--h->nruns]);
        h->next_serial--;
    }
    if (h->nruns == TUI_MAX_RUNS) {
        run_free(&h->runs[0]);
        memmove(h->runs, h->runs + 1, sizeof h->runs[0] * (TUI_MAX_RUNS - 1));
        memset(&h->runs[TUI_MAX_RUNS - 1], 0, sizeof h->runs[0]);
        h->nruns--;
    }
    tui_run *r = &h->runs[h->nruns++];
    memset(r, 0, sizeof *r);
    r->serial = h->next_serial++;
    return r;
}

void tui_history_append(tui_run *r, const cx_iterate *it)
{
    if (r->nsteps == r->cap) {
        r->cap = r->cap ? 2 * r->cap : 64;
        r->steps = tui_xalloc(r->steps, sizeof *r->steps * (size_t)r->cap);
    }
    tui_step *s = &r->steps[r->nsteps++];
    s->iter = it->iter;
    s->kkt = it->kkt;
    s->own = it->own;
    s->nfree = it->nfree;
    s->ncontact = it->ncontact;
    s->nstick = it->nstick;
    s->nslip = it->nslip;
    s->nchanged = it->nchanged;
    s->inner = it->inner;
    s->solves = it->counters.solves + r->probe.solves;
    s->time = it->time - it->init_time;
    s->step_time = it->step_time;
    r->reason = it->reason;
    r->setup = it->init_time;
    r->factorizations = it->counters.factorizations + r->probe.factorizations;
}

/* ---- the state's runs ------------------------------------------------------ */

int tui_state_nruns(const tui_state *st)
{
    return st->history ? st->history->nruns : 0;
}

const tui_run *tui_state_run_at(const tui_state *st, int i)
{
    return i >= 0 && i < tui_state_nruns(st) ? &st->history->runs[i] : NULL;
}

const tui_run *tui_state_run(const tui_state *st)
{
    return tui_state_run_at(st, tui_state_nruns(st) - 1);
}

int tui_state_nsteps(const tui_state *st, int i)
{
    const tui_run *r = tui_state_run_at(st, i);
    return r ? r->nsteps : 0;
}

double tui_state_step_time(const tui_state *st, int i, int k)
{
    const tui_run *r = tui_state_run_at(st, i);
    return r && k >= 0 && k < r->nsteps ? r->steps[k].step_time : 0;
}

int tui_run_colour(const tui_run *r)
{
    return r->serial % CX_PALETTE_NSERIES;
}

void tui_run_legend(const tui_run *r, char *buf, size_t len)
{
    snprintf(buf, len, "%s%s%s", r->method, r->changed[0] ? " " : "", r->changed);
}

int tui_run_cached(const tui_run *r)
{
    /* a PETSc run (state.c) factorises nothing: no cache served it */
    return r->nsteps > 0 && r->factorizations == 0 && strncmp(r->changed, "petsc", 5) != 0;
}
