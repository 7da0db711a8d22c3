/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The explorer's state: scenes, selections, the session, taking a job's
 * result, and the snapshot panels draw from. The jobs are in job.c, the
 * runs in history.c, the mesh view's geometry in meshview.c. No curses
 * here. */
#include "tui/tui_impl.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void tui_msg(tui_state *st, int error, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(st->msg, sizeof st->msg, fmt, ap);
    va_end(ap);
    st->msg_error = error;
}

/* Fail fast on OOM in the explorer (doc/style.md C5) through the program's
 * hook, which restores the terminal first: the core never calls the loop. */
static void (*_Atomic state_oom_hook)(const char *msg);

void tui_on_oom(void (*hook)(const char *msg))
{
    state_oom_hook = hook;
}

_Noreturn void tui_oom(const char *msg)
{
    void (*hook)(const char *) = state_oom_hook;
    if (hook)
        hook(msg);
    abort();
}

void *tui_xalloc(void *p, size_t size)
{
    void *q = realloc(p, size ? size : 1);
    if (!q)
        tui_oom("out of memory");
    return q;
}

/* ---- selections ---------------------------------------------------------- */

const cx_method *tui_state_sel_method(const tui_state *st)
{
    return cx_method_at(st->sel_method);
}

const char *tui_state_method_reason(const tui_state *st, int index, char *buf, size_t len)
{
    buf[0] = '\0';
    const cx_method *m = cx_method_at(index);
    if (!m || !st->have_info)
        return buf;
    /* the law the pickers select, on the session's problem */
    cx_diag d;
    cx_diag_clear(&d);
    if (cx_method_check(m, st->info, st->sel_law, &d) != CX_OK)
        snprintf(buf, len, "%s", d.msg);
    else if (st->refused && st->refused[index][st->sel_law][0])
        snprintf(buf, len, "%s", st->refused[index][st->sel_law]);
    return buf;
}

int tui_method_index(const char *id)
{
    for (int i = 0; i < cx_method_count(); i++)
        if (strcmp(cx_method_at(i)->id, id) == 0)
            return i;
    return -1;
}

/* --method auto's choice for the selected scene, level and law, if it is
 * registered (else the selection stays). */
void tui_state_select_auto(tui_state *st)
{
    const char *sets;
    int i = tui_method_index(cx_scene_auto_method(&st->scene, st->sel_level, NULL, st->sel_law, &sets));
    if (i < 0)
        return;
    st->sel_method = i;
    cx_param_default(&st->sel_params, cx_method_at(i)->params);
    char buf[128];
    snprintf(buf, sizeof buf, "%s", sets);
    for (char *save = NULL, *tok = strtok_r(buf, " ", &save); tok; tok = strtok_r(NULL, " ", &save))
        cx_param_set_pair(&st->sel_params, tok, cx_method_at(i)->id, NULL);
}

/* The selections a freshly loaded scene starts from. */
static void state_select_scene_defaults(tui_state *st)
{
    st->sel_level = st->scene.level;
    st->sel_law = st->scene.friction;
    st->sel_slip = st->scene.slip_bound;
    st->sel_F = st->scene.F;
    st->sel_method = 0;
    for (int k = 0; k < st->scene.nmethods; k++) {
        int i = tui_method_index(st->scene.methods[k]);
        if (i >= 0) {
            st->sel_method = i;
            break;
        }
    }
    cx_param_default(&st->sel_params, cx_method_at(st->sel_method)->params);
    tui_state_select_auto(st);
}

static double state_sel_coef(const tui_state *st)
{
    return st->sel_law == CX_FRICTION_COULOMB ? st->sel_F : st->sel_slip;
}

/* ---- the size of a level -------------------------------------------------- */

/* What a build at another level will take, scaled from the level built:
 * dofs go with the nodes (the product of each direction's growth in
 * nodes; a masonry's bodies with the courses squared), the contact dofs
 * with the contact boundary (that product to the (dim-1)/dim; a
 * masonry's interfaces with its bodies). Memory and
 * time follow the operators the default methods build: the sparse
 * Cholesky factor of K (fill about n log2 n in 2D, n^(4/3) in 3D) and the
 * dense Schur complement onto the contact dofs (nc^2, kept with its
 * factor), which is built with nc solves with that factor and factorised
 * in nc^3. The constants are fitted to peak RSS and wall time of
 * 'signorini solve --max-iter 1' at hertz 64-512, block3d 8-16, laminae
 * 10-20 and halfball 12 (the README's explorer section has the table). A
 * build long enough to time (0.5 s) scales the time to this machine and
 * its load. */
static double state_fill(int dim, double n)
{
    return dim == 2 ? n * log2(n > 2 ? n : 2) : n * cbrt(n);
}

static void state_level_model(int dim, double n, double nc, double *bytes, double *secs)
{
    double fill = state_fill(dim, n);
    *bytes = (dim == 2 ? 90.0 : 160.0) * fill + 24.0 * nc * nc;
    *secs = (dim == 2 ? 9e-10 : 6e-10) * fill * nc + 3.5e-11 * nc * nc * nc;
}

int tui_state_level_estimate(const tui_state *st, int level, double *dofs, double *bytes, double *secs)
{
    const cx_problem *p = st->info;
    if (!st->session || !st->have_info || p->n <= 0 || tui_state_busy(st) || level < 1)
        return 0;
    const cx_scene *sc = &st->scene;
    int dim = p->dim;
    double r, rn, rc;
    if (sc->generator == CX_GEN_MASONRY) {
        r = (double)level / st->level;
        rn = rc = r * r;
    } else {
        /* nodes, not cells: from a small level (the first build's
         * calibration, state_build_target) r^dim overestimates by the
         * boundary's row of nodes (block3d 4 to 16: 72k for 54k dofs) */
        int c0[3], c1[3];
        cx_scene_cells(sc, st->level, c0);
        cx_scene_cells(sc, level, c1);
        r = c0[0] > 0 ? (c1[0] + 1.0) / (c0[0] + 1.0) : (double)level / st->level;
        rn = 1;
        for (int k = 0; k < dim; k++)   /* a direction not refined (hertz's second): as the first */
            rn *= c0[k] > 0 && c0[k] != c1[k] ? (c1[k] + 1.0) / (c0[k] + 1.0) : r;
        rc = pow(rn, (dim - 1.0) / dim);
    }
    double n = p->n * rn, nc = (p->nc > 0 ? p->nc : 2 * p->m) * rc;
    state_level_model(dim, n, nc, bytes, secs);
    if (st->build_time >= 0.5) {
        double b0, t0;
        state_level_model(dim, p->n, p->nc > 0 ? p->nc : 2 * p->m, &b0, &t0);
        double k = t0 > 0 ? st->build_time / t0 : 1;
        *secs *= k < 0.5 ? 0.5 : k > 4 ? 4 : k;
    }
    if (level == st->level)
        n = p->n;
    *dofs = n;
    return 1;
}

/* SIGNORINI_MEMAVAILABLE (bytes) stands in for MemAvailable, so that the
 * tests can make a refusal happen on any machine; not meant for users. */
static double state_mem_override(void)
{
    const char *env = getenv("SIGNORINI_MEMAVAILABLE");
    char *end;
    double x = env && *env ? strtod(env, &end) : -1;
    return env && *env && *end == '\0' && x > 0 && isfinite(x) ? x : -1;
}

const char *tui_mem_source(void)
{
    return state_mem_override() > 0 ? "SIGNORINI_MEMAVAILABLE" : "/proc/meminfo MemAvailable";
}

double tui_mem_available(void)
{
    double x = state_mem_override();
    if (x > 0)
        return x;
    FILE *f = fopen("/proc/meminfo", "r");
    if (!f)
        return -1;
    char line[128];
    double kb = -1;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "MemAvailable: %lf kB", &kb) == 1)
            break;
    fclose(f);
    return kb >= 0 ? kb * 1024 : -1;
}

void tui_size_text(double bytes, char *buf, size_t len)
{
    if (bytes >= 1e9)
        snprintf(buf, len, "%.1f GB", bytes / 1e9);
    else if (bytes >= 1e6)
        snprintf(buf, len, "%.0f MB", bytes / 1e6);
    else
        snprintf(buf, len, "%.0f kB", bytes / 1e3);
}

int tui_state_level_refused(const tui_state *st, int level, double avail, char *msg, size_t len)
{
    double dofs, bytes, secs;
    if (avail <= 0 || !tui_state_level_estimate(st, level, &dofs, &bytes, &secs) || bytes <= avail)
        return 0;
    char need[32], have[32];
    tui_size_text(bytes, need, sizeof need);
    tui_size_text(avail, have, sizeof have);
    snprintf(msg, len, "level %d refused: about %.3g dofs need about %s, and %s of memory is available", level,
             dofs, need, have);
    return 1;
}

/* ---- runs ---------------------------------------------------------------- */

/* A new run for the session's current method (history.c keeps the runs). */
static void state_new_run(tui_state *st)
{
    tui_run *r = tui_history_new_run(st->history);
    const cx_method *m = st->cur_method;
    snprintf(r->method, sizeof r->method, "%s", m ? m->id : "-");
    size_t at = 0;
    for (int i = 0; i < st->cur_params.n && at < sizeof r->params; i++) {
        char v[CX_PARAM_STRLEN];
        cx_param_format(&st->cur_params, i, v, sizeof v);
        int w = snprintf(r->params + at, sizeof r->params - at, "%s%s=%s", i ? " " : "",
                         st->cur_params.table[i].key, v);
        at += w > 0 ? (size_t)w : 0;
    }
    cx_param_values def;
    cx_param_default(&def, st->cur_params.table);
    at = 0;
    for (int i = 0; i < st->cur_params.n && at < sizeof r->changed; i++) {
        char v[CX_PARAM_STRLEN], v0[CX_PARAM_STRLEN];
        cx_param_format(&st->cur_params, i, v, sizeof v);
        cx_param_format(&def, i, v0, sizeof v0);
        if (strcmp(v, v0) == 0)
            continue;
        int w = snprintf(r->changed + at, sizeof r->changed - at, "%s%s=%s", at ? " " : "",
                         st->cur_params.table[i].key, v);
        at += w > 0 ? (size_t)w : 0;
    }
    r->law = st->cur_law;
    r->coef = st->cur_coef;
    r->tol = st->cur_opt.tol;
    r->reason = CX_ITERATING;
    if (st->flips && st->m > 0)
        memset(st->flips, 0, sizeof(int) * (size_t)st->m);
    memset(st->status_hash, 0, sizeof st->status_hash);
    st->cycle_iter = 0;
}

/* ---- snapshot ------------------------------------------------------------ */

/* Copy what the panels draw out of a solution (u on the free dofs, the
 * forces, the statuses; main thread, no job). */
static void state_snapshot_of(tui_state *st, const double *u, const double *lN, const double *lT,
                              const unsigned char *status, const unsigned char *changed)
{
    const cx_session *s = st->session;
    const cx_problem *p = cx_session_problem(s);
    const cx_contact_set *c = &p->contact;
    int m = p->m, dim = p->dim, nall = p->map.nall;
    if (m != st->m || !st->status) {
        st->m = m;
        st->status = tui_xalloc(st->status, (size_t)m + 1);
        st->changed = tui_xalloc(st->changed, (size_t)m + 1);
        st->pressure = tui_xalloc(st->pressure, sizeof(double) * ((size_t)m + 1));
        st->hertz = tui_xalloc(st->hertz, sizeof(double) * ((size_t)m + 1));
        st->slip_dir = tui_xalloc(st->slip_dir, sizeof(double) * (2 * (size_t)m + 1));
        st->flips = tui_xalloc(st->flips, sizeof(int) * ((size_t)m + 1));
        memset(st->flips, 0, sizeof(int) * ((size_t)m + 1));
    }
    st->uall = tui_xalloc(st->uall, sizeof(double) * ((size_t)nall + 1));
    for (int i = 0; i < m; i++) {
        st->status[i] = status[i];
        st->changed[i] = changed[i];
        st->pressure[i] = c->weight[i] > 0 ? lN[i] / c->weight[i] : 0;
        st->hertz[i] = st->scene.has_hertz && dim == 2 ? cx_scene_hertz_pressure(&st->scene, c->x[2 * i])
                                                       : NAN;
        /* the friction force on the body, -lT t, in the x, y plane */
        double fx = 0, fy = 0;
        if (cx_session_friction(s)->law != CX_FRICTION_NONE)
            for (int r = 0; r < dim - 1; r++) {
                const double *t = c->tangent + dim * ((dim - 1) * i + r);
                fx -= lT[(dim - 1) * i + r] * t[0];
                fy -= lT[(dim - 1) * i + r] * t[1];
            }
        st->slip_dir[2 * i] = fx;
        st->slip_dir[2 * i + 1] = fy;
    }
    for (int k = 0; k < nall; k++) {
        int f = p->map.free_of[k];
        st->uall[k] = f >= 0 ? u[f] : p->map.value[k];
    }
    st->cache = *cx_session_cache_counters(s);
    st->cache_size = cx_session_cache_size(s);
}

/* Copy what the panels draw out of the session's iterate. */
static void state_snapshot(tui_state *st)
{
    if (!st->session)
        return;
    const cx_iterate *it = cx_session_iterate(st->session);
    state_snapshot_of(st, it->u, it->lN, it->lT, it->status, it->changed);
}

/* After a job: what the session now is. */
static void state_take_session(tui_state *st)
{
    const cx_friction_state *fr = cx_session_friction(st->session);
    st->info = cx_session_problem(st->session);
    st->have_info = 1;
    st->cur_method = cx_session_method(st->session);
    st->cur_params = *cx_session_params(st->session);
    st->cur_opt = *cx_session_options(st->session);
    st->cur_law = fr->law;
    st->cur_coef = fr->law == CX_FRICTION_COULOMB ? fr->F : fr->slip_bound;
}

int tui_state_busy(const tui_state *st)
{
    return st->job.kind != TUI_JOB_NONE;
}

/* What arrived during a job: changes first, then typed-ahead steps. */
static void state_after_job(tui_state *st)
{
    if (st->pending) {
        int r = st->pending;
        st->pending = 0;
        tui_state_apply(st, r);
    }
    if (st->queued_steps > 0 && !tui_state_busy(st) && st->session) {
        st->queued_steps--;
        tui_state_step(st);
    }
}

/* The level asked for at start, once the scene's default level is built
 * and can measure it: built next if its estimate fits in the free memory,
 * else refused with both figures while the level built stays open. Not
 * if something else was asked for meanwhile. */
static void state_build_target(tui_state *st)
{
    int target = st->target_level;
    st->target_level = 0;
    if (!target || !st->session || st->level == target || (st->pending & TUI_REASSEMBLE))
        return;
    char msg[CX_DIAG_LEN];
    if (tui_state_level_refused(st, target, tui_mem_available(), msg, sizeof msg)) {
        tui_msg(st, 1, "%s (%s); %s level %d, built to measure it, is open", msg, tui_mem_source(),
                st->scene.id, st->level);
        return;
    }
    double dofs, bytes, secs;
    if (tui_state_level_estimate(st, target, &dofs, &bytes, &secs)) {
        char need[32];
        tui_size_text(bytes, need, sizeof need);
        tui_msg(st, 0, "level %d: about %.3g dofs, %s, %.2g s (scaled from level %d): building", target, dofs,
                need, secs, st->level);
    }
    st->sel_level = target;
    st->pending |= TUI_REASSEMBLE;
}

/* A PETSc run has ended (main thread): its outcome into the run, its
 * solution into the panels. */
static void state_after_petsc(tui_state *st)
{
    tui_job *j = &st->job;
    tui_run *run = &st->history->runs[st->history->nruns - 1];
    tui_backend_take(st, run, st->info->m);
    tui_backend_outcome o;
    cx_diag d;
    cx_diag_clear(&d);
    int status = j->status != CX_OK ? j->status : tui_backend_result(st, &o, &d);
    if (status != CX_OK) {
        const cx_diag *why = j->status != CX_OK ? &j->diag : &d;
        run->reason = CX_REFUSED;
        snprintf(run->outcome, sizeof run->outcome, "%s", cx_diag_msg(why, status));
        tui_msg(st, 1, "petsc: %s", cx_diag_msg(why, status));
        return;
    }
    run->reason = o.reason;
    run->setup = o.t_setup;
    snprintf(run->reason_msg, sizeof run->reason_msg, "%.150s", o.message);
    cx_reason_format(o.reason, o.iterations, o.kkt, st->sel_opt.tol, o.message, run->outcome, sizeof run->outcome);
    /* the Krylov work where the direct path's runs show their changed
     * parameters */
    snprintf(run->changed, sizeof run->changed, "petsc, %d rank%s, %ld Krylov it.", o.nranks, o.nranks > 1 ? "s" : "",
             o.krylov);
    const cx_problem *p = cx_session_problem(st->session);
    const cx_friction_state *fr = cx_session_friction(st->session);
    unsigned char *pts = tui_xalloc(NULL, (size_t)p->m + 1), *none = tui_xalloc(NULL, (size_t)p->m + 1);
    tui_backend_point_status(p, fr, o.lN, o.lT, pts);
    memset(none, 0, (size_t)p->m + 1);
    state_snapshot_of(st, o.u, o.lN, o.lT, pts, none);
    free(pts);
    free(none);
    tui_msg(st, o.reason < 0, "petsc %s (%d rank%s, %s: %ld Krylov iterations, peak %.0f MB): %s", run->method,
            o.nranks, o.nranks > 1 ? "s" : "", o.solver[0] ? o.solver : "no Krylov solver", o.krylov,
            o.mem_peak / 1048576.0, run->outcome);
}

int tui_state_poll(tui_state *st)
{
    tui_job *j = &st->job;
    /* a PETSc run's steps, as they come */
    int took = j->kind == TUI_JOB_PETSC && st->history->nruns > 0 &&
               tui_backend_take(st, &st->history->runs[st->history->nruns - 1], st->info->m) > 0;
    if (!tui_job_ended(st))
        return took;
    int kind = j->kind;
    j->kind = TUI_JOB_NONE;
    if (kind == TUI_JOB_PETSC) {
        state_after_petsc(st);
        state_after_job(st);
        return 1;
    }
    if (kind == TUI_JOB_STEP) {
        tui_state_after_step(st, j->status, &j->diag);
        state_after_job(st);
        return 1;
    }
    if (kind == TUI_JOB_BUILD) {
        if (j->status == CX_OK || j->session) {
            cx_session_destroy(&st->session);
            st->session = j->session;
            j->session = NULL;
            st->level = j->level;
            st->build_time = cx_clock_now() - j->t0;
            tui_history_clear(st->history);
            st->highlight = 0;
            /* what the new problem refuses up front (job.c), greyed before
             * anyone tries it */
            if (j->refused)
                memcpy(st->refused, j->refused, sizeof st->refused[0] * (size_t)cx_method_count());
            else
                memset(st->refused, 0, sizeof st->refused[0] * (size_t)cx_method_count());
            st->m = -1;
            st->info = cx_session_problem(st->session);
            tui_meshview_update(&st->mesh_view, st->info->mesh, &st->scene, st->level);
        } else if (st->session) {
            /* the build failed: the old session stays, and so does its scene */
            st->scene = st->prev_scene;
            for (int i = 0; i < st->nscenes; i++)
                if (strcmp(st->scene_ids[i], st->scene.id) == 0)
                    st->sel_scene = i;
            st->sel_level = st->level;
        }
    }
    if (st->session) {
        state_take_session(st);
        /* a refused switch leaves the session as it was: show that */
        int refused = j->status == CX_EUNSUPPORTED && kind == TUI_JOB_RESOLVE;
        int mi = refused ? tui_method_index(j->method->id) : -1;
        if (mi >= 0)
            snprintf(st->refused[mi][j->law], CX_DIAG_LEN, "%s", j->diag.msg);
        if (j->status != CX_OK && st->cur_method) {
            st->sel_method = tui_method_index(st->cur_method->id);
            st->sel_params = st->cur_params;
            st->sel_law = st->cur_law;
            if (st->cur_law == CX_FRICTION_COULOMB)
                st->sel_F = st->cur_coef;
            else if (st->cur_law == CX_FRICTION_TRESCA)
                st->sel_slip = st->cur_coef;
        }
        if (st->cur_method && (j->status == CX_OK || kind == TUI_JOB_BUILD)) {
            state_new_run(st);
            if (kind == TUI_JOB_RESOLVE)
            {
                tui_run *run = &st->history->runs[st->history->nruns - 1];
                run->probe = j->probe;
                run->factorizations = j->probe.factorizations;
            }
        }
        /* a refusal the probe caught left the session untouched: the
         * snapshot, the run and its steps stay as they were */
        if (!j->probed)
            state_snapshot(st);
        else
            st->cache = *cx_session_cache_counters(st->session);   /* the attempt's work */
    }
    /* a run asked for during a switch that failed is not the old one's */
    if (j->status != CX_OK)
        st->running = 0;
    if (j->status != CX_OK && kind == TUI_JOB_RESOLVE && j->method &&
        !strstr(cx_diag_msg(&j->diag, j->status), j->method->id))
        /* which switch was refused, and that nothing changed */
        tui_msg(st, 1, "%s refused, %s kept: %s", j->method->id, st->cur_method ? st->cur_method->id : "-",
                cx_diag_msg(&j->diag, j->status));
    else if (j->status != CX_OK)
        tui_msg(st, 1, "%s", cx_diag_msg(&j->diag, j->status));
    else if (kind == TUI_JOB_BUILD)
        tui_msg(st, 0, "%s level %d: %d dofs, %d contact points, built in %.2f s", st->scene.id,
                st->level, st->info->n, st->info->m, st->build_time);
    else
        tui_msg(st, 0, "%s ready (nothing reassembled)", st->cur_method ? st->cur_method->id : "-");
    if (kind == TUI_JOB_BUILD)
        state_build_target(st);
    state_after_job(st);
    return 1;
}

/* ---- apply --------------------------------------------------------------- */

static int state_load_scene(tui_state *st, int index, cx_diag *d)
{
    char path[512];
    cx_scene sc;
    CX_TRY(cx_scene_resolve(st->scene_ids[index], path, sizeof path, d));
    CX_TRY(cx_scene_load(&sc, path, d));
    st->scene = sc;
    st->sel_scene = index;
    return CX_OK;
}

static int params_equal(const cx_param_values *a, const cx_param_values *b)
{
    if (a->table != b->table || a->n != b->n)
        return 0;
    for (int i = 0; i < a->n; i++) {
        if (!(a->num[i] == b->num[i] || (isnan(a->num[i]) && isnan(b->num[i]))))
            return 0;
        if (strcmp(a->str[i], b->str[i]) != 0)
            return 0;
    }
    return 1;
}

void tui_state_apply(tui_state *st, int r)
{
    r &= TUI_RESOLVE | TUI_REASSEMBLE;
    if (!r)
        return;
    if (tui_state_busy(st)) {
        st->pending |= r;
        return;
    }
    if (r & TUI_REASSEMBLE) {
        st->prev_scene = st->scene;
        if (strcmp(st->scene.id, st->scene_ids[st->sel_scene]) != 0) {
            cx_diag d;
            cx_diag_clear(&d);
            int keep = st->sel_scene;
            if (state_load_scene(st, keep, &d) != CX_OK) {
                tui_msg(st, 1, "%s", d.msg);
                for (int i = 0; i < st->nscenes; i++)
                    if (strcmp(st->scene_ids[i], st->scene.id) == 0)
                        st->sel_scene = i;
                return;
            }
            state_select_scene_defaults(st);
        }
        tui_job_start(st, TUI_JOB_BUILD);
        return;
    }
    if (!st->session)
        return;
    double coef = state_sel_coef(st);
    int same_method = st->cur_method == tui_state_sel_method(st) &&
                      params_equal(&st->cur_params, &st->sel_params);
    int same_law = st->sel_law == st->cur_law && (st->sel_law == CX_FRICTION_NONE || coef == st->cur_coef);
    if (same_method && same_law) {
        /* only options: the run goes on under them */
        cx_session_set_options(st->session, &st->sel_opt);
        st->cur_opt = st->sel_opt;
        if (tui_state_nruns(st))
            st->history->runs[st->history->nruns - 1].tol = st->sel_opt.tol;
        tui_msg(st, 0, "tolerance %.3g, iteration limit %d (run kept)", st->sel_opt.tol, st->sel_opt.max_iter);
        return;
    }
    tui_job_start(st, TUI_JOB_RESOLVE);
}

/* ---- stepping ------------------------------------------------------------ */

/* A run of the PETSc backend says so where a direct run lists its
 * changed parameters ("petsc", then "petsc, 1 rank, ..." once ended). */
static int state_run_is_petsc(const tui_run *r)
{
    return strncmp(r->changed, "petsc", 5) == 0;
}

int tui_state_run_ended(const tui_state *st)
{
    const tui_run *cur = tui_state_run(st);
    if (!cur || cur->reason == CX_ITERATING)
        return 0;
    if (!st->sel_backend)
        return !state_run_is_petsc(cur);   /* after a PETSc run, the direct path opens its own */
    const char *id = tui_backend_method(st->sel_backend - 1);
    return state_run_is_petsc(cur) && id && strcmp(cur->method, id) == 0;
}

/* A step or a run on the PETSc backend: its whole run, as one job on the
 * backend's thread, in a run of its own in the table (the current run is
 * reused while it has no step). */
static void state_petsc_run(tui_state *st)
{
    const tui_run *cur = tui_state_run(st);
    const char *id = tui_backend_method(st->sel_backend - 1);
    /* the same method again needs x, as on the direct path; another ('b')
     * opens its own run */
    if (tui_state_run_ended(st)) {
        st->running = 0;
        st->queued_steps = 0;
        tui_msg(st, cur->reason < 0, "run ended (%s); x starts again", cx_reason_str(cur->reason));
        return;
    }
    if (!cur || cur->nsteps > 0 || cur->reason != CX_ITERATING)
        state_new_run(st);
    tui_run *run = &st->history->runs[st->history->nruns - 1];
    snprintf(run->method, sizeof run->method, "%s", id ? id : "-");
    run->params[0] = run->changed[0] = '\0';
    snprintf(run->changed, sizeof run->changed, "petsc");
    run->tol = st->sel_opt.tol;
    st->queued_steps = 0;
    tui_msg(st, 0, "petsc %s: running to the end on the PETSc backend (1 rank; Esc stops it)", run->method);
    /* the job is the whole run: r (or s) pressed during it asks for the
     * next one, with what 'b' selects by then */
    st->running = 0;
    tui_job_start(st, TUI_JOB_PETSC);
}

void tui_state_step(tui_state *st)
{
    if (tui_state_busy(st) || !st->session)
        return;
    if (!st->cur_method) {
        tui_msg(st, 1, "no method selected");
        st->running = 0;
        return;
    }
    if (st->sel_backend) {
        state_petsc_run(st);
        return;
    }
    const tui_run *cur = tui_state_run(st);
    if (cur && state_run_is_petsc(cur)) {
        /* back on the direct path after a PETSc run: a run of its own (r
         * goes on running it) */
        int running = st->running;
        tui_state_reset(st);
        st->running = running;
        if (!st->session || !st->cur_method)
            return;
    }
    const cx_iterate *it = cx_session_iterate(st->session);
    if (it->reason != CX_ITERATING) {
        st->running = 0;
        st->queued_steps = 0;
        tui_msg(st, it->reason < 0, "run ended (%s); x starts again", cx_reason_str(it->reason));
        return;
    }
    /* the step runs as a job: a slow method or a large level never
     * freezes the screen */
    tui_job_start(st, TUI_JOB_STEP);
}

/* Chattering (peers.md §4 item 4): count each point's status changes, and
 * flag a 2-cycle when a step repeats the step before last (same statuses,
 * same kkt to 1e-10) without repeating the last one: the iteration then
 * alternates between two iterates and will not converge by itself. */
static void state_watch_cycles(tui_state *st, const tui_run *run)
{
    unsigned long long h = 1469598103934665603ULL;    /* FNV-1a */
    for (int i = 0; i < st->m; i++) {
        st->flips[i] += st->changed[i] != 0;
        h = (h ^ st->status[i]) * 1099511628211ULL;
    }
    st->status_hash[2] = st->status_hash[1];
    st->status_hash[1] = st->status_hash[0];
    st->status_hash[0] = h;
    int n = run->nsteps;
    if (n < 4 || st->cycle_iter)
        return;
    double k0 = run->steps[n - 1].kkt, k1 = run->steps[n - 2].kkt, k2 = run->steps[n - 3].kkt;
    /* truly cycled: the set and the kkt error of iteration n-2 come back at
     * n, after a different error at n-1, and so does the method's own
     * criterion when it has one. An error that merely sits at a plateau
     * while the method makes headway is no cycle (lssnn on halfball sits
     * at kkt 1 for its first steps, its own criterion moving, then
     * converges in 85 as in solve) */
    double o0 = run->steps[n - 1].own, o2 = run->steps[n - 3].own;
    int own_repeats = (isnan(o0) && isnan(o2)) || fabs(o0 - o2) <= 1e-10 * fabs(o0);
    if (st->status_hash[0] == st->status_hash[2] && fabs(k0 - k2) <= 1e-10 * k0 && fabs(k0 - k1) > 1e-8 * k0 &&
        own_repeats)
        st->cycle_iter = run->steps[n - 1].iter;
}

/* After a step (main thread): the history, the snapshot, the outcome. */
void tui_state_after_step(tui_state *st, int status, const cx_diag *d)
{
    const cx_iterate *it = cx_session_iterate(st->session);
    tui_run *run = &st->history->runs[st->history->nruns - 1];
    tui_history_append(run, it);
    /* the step as solve saw it, before any expansion for drawing */
    const tui_job *j = &st->job;
    tui_step *last = &run->steps[run->nsteps - 1];
    if (it->reason == CX_ITERATING)
        last->kkt = j->kkt;
    last->solves = j->counters.solves + run->probe.solves;
    run->factorizations = j->counters.factorizations + run->probe.factorizations;
    run->draw.solves += j->draw.solves;
    run->draw.factorizations += j->draw.factorizations;
    run->draw.matvecs += j->draw.matvecs;
    state_snapshot(st);
    int seen = st->cycle_iter;
    state_watch_cycles(st, run);
    if (!seen && st->cycle_iter && it->reason == CX_ITERATING) {
        int flipping = 0;
        for (int i = 0; i < st->m; i++)
            flipping += st->flips[i] >= 3;
        st->running = 0;
        tui_msg(st, 2, "cycling: iteration %d repeats iteration %d, paused (kkt %.3g / %.3g, %d points flip 3+ times)",
                it->iter, it->iter - 2, run->steps[run->nsteps - 1].kkt, run->steps[run->nsteps - 2].kkt, flipping);
        return;
    }
    if (status != CX_OK) {
        st->running = 0;
        tui_msg(st, 1, "%s", cx_diag_msg(d, status));
        return;
    }
    if (it->reason != CX_ITERATING) {
        st->running = 0;
        const char *why = cx_session_reason_msg(st->session);
        snprintf(run->reason_msg, sizeof run->reason_msg, "%s", why);
        cx_session_outcome(st->session, run->outcome, sizeof run->outcome);
        char outcome[CX_DIAG_LEN + 128];
        cx_session_outcome(st->session, outcome, sizeof outcome);
        if (tui_run_cached(run))
            tui_msg(st, it->reason < 0, "cached (0 fact.): %s", outcome);
        else
            tui_msg(st, it->reason < 0, "%s", outcome);
    }
}

void tui_state_abandon_build(tui_state *st)
{
    int level = st->job.level;
    char id[CX_SCENE_NAMELEN];
    snprintf(id, sizeof id, "%s", st->scene.id);
    if (!tui_job_abandon(st))
        return;
    st->target_level = 0;
    st->pending = 0;
    st->queued_steps = 0;
    st->running = 0;
    if (st->session) {
        /* back to the scene and level of the session, as after a failed build */
        st->scene = st->prev_scene;
        for (int i = 0; i < st->nscenes; i++)
            if (strcmp(st->scene_ids[i], st->scene.id) == 0)
                st->sel_scene = i;
        st->sel_level = st->level;
        tui_msg(st, 2, "build of %s level %d abandoned (it ends on its own and frees its memory); %s level %d kept",
                id, level, st->scene.id, st->level);
    } else {
        tui_msg(st, 2, "build of %s level %d abandoned (it ends on its own and frees its memory); "
                "choose a smaller level", id, level);
    }
}

void tui_state_reset(tui_state *st)
{
    if (tui_state_busy(st)) {
        tui_msg(st, 0, "busy: reset when the job ends");
        return;
    }
    if (!st->session || !st->cur_method) {
        tui_msg(st, 0, "nothing to reset yet");
        return;
    }
    cx_diag d;
    cx_diag_clear(&d);
    st->running = 0;
    if (cx_session_reset(st->session, &d) != CX_OK) {
        tui_msg(st, 1, "%s", d.msg);
        return;
    }
    state_new_run(st);
    state_snapshot(st);
    tui_msg(st, 0, "%s starts again (nothing rebuilt)", st->cur_method->id);
}

/* ---- life ---------------------------------------------------------------- */

/* What the views read before the first build: no system (sizes zero). */
static const cx_problem state_no_problem;

int tui_state_init(tui_state *st, const char *scene, int level, const char *method, int law,
                   int sync, cx_diag *d)
{
    memset(st, 0, sizeof *st);
    st->info = &state_no_problem;
    st->sync = sync;
    st->history = tui_history_create();
    st->refused = tui_xalloc(NULL, sizeof st->refused[0] * (size_t)(cx_method_count() + 1));
    memset(st->refused, 0, sizeof st->refused[0] * (size_t)(cx_method_count() + 1));
    st->m = -1;
    st->pace = TUI_PACE_DEFAULT;
    snprintf(st->export_dir, sizeof st->export_dir, ".");
    cx_options_default(&st->sel_opt);
    st->cur_opt = st->sel_opt;
    CX_TRY(cx_scene_list(&st->scene_ids, &st->nscenes, d));
    /* a path to an .ini, or an id */
    char path[512];
    int status = cx_scene_resolve(scene, path, sizeof path, d);
    if (status == CX_OK)
        status = cx_scene_load(&st->scene, path, d);
    if (status != CX_OK) {
        tui_state_clear(st);
        return status;
    }
    st->sel_scene = -1;
    for (int i = 0; i < st->nscenes; i++)
        if (strcmp(st->scene_ids[i], st->scene.id) == 0)
            st->sel_scene = i;
    if (st->sel_scene < 0) {
        /* a scene file outside the scene directories: add it to the list */
        st->scene_ids = tui_xalloc(st->scene_ids, sizeof st->scene_ids[0] * (size_t)(st->nscenes + 1));
        snprintf(st->scene_ids[st->nscenes], CX_SCENE_NAMELEN, "%s", st->scene.id);
        st->sel_scene = st->nscenes++;
    }
    state_select_scene_defaults(st);
    if (level > 0) {
        if (level > st->scene.level_max) {
            cx_diag_set(d, CX_EINVAL, "--level %d: scene '%s' allows 1 to %d", level, st->scene.id,
                        st->scene.level_max);
            tui_state_clear(st);
            return CX_EINVAL;
        }
        st->sel_level = level;
    }
    if (law >= 0)
        st->sel_law = (cx_friction)law;
    if (method) {
        int i = tui_method_index(method);
        if (i < 0) {
            tui_state_clear(st);
            return cx_diag_set(d, CX_EINVAL, "unknown method '%s' (see 'signorini list')", method);
        }
        st->sel_method = i;
        cx_param_default(&st->sel_params, cx_method_at(i)->params);
    } else {
        tui_state_select_auto(st);   /* for the level and law asked for */
    }
    st->field = TUI_F_METHOD;
    /* a level above the scene's default is not built blind: the default
     * level (small, quick) is built first and its estimate decides
     * (state_build_target) */
    if (st->sel_level > st->scene.level) {
        st->target_level = st->sel_level;
        st->sel_level = st->scene.level;
        tui_msg(st, 0, "level %d first, to estimate level %d", st->sel_level, st->target_level);
    }
    tui_job_start(st, TUI_JOB_BUILD);
    return CX_OK;
}

void tui_state_clear(tui_state *st)
{
    tui_job_clear(st);
    tui_backend_stop(st);   /* PETSc ends on its thread */
    cx_session_destroy(&st->session);
    tui_history_destroy(&st->history);
    free(st->refused);
    tui_meshview_clear(&st->mesh_view);
    cx_free(st->scene_ids);
    free(st->status);
    free(st->changed);
    free(st->pressure);
    free(st->hertz);
    free(st->slip_dir);
    free(st->flips);
    free(st->uall);
    memset(st, 0, sizeof *st);
}

int tui_state_create(tui_state **st, const char *scene, int level, const char *method, int law,
                     int sync, cx_diag *d)
{
    *st = tui_xalloc(NULL, sizeof **st);
    int status = tui_state_init(*st, scene, level, method, law, sync, d);
    if (status != CX_OK) {
        free(*st);
        *st = NULL;
    }
    return status;
}

void tui_state_destroy(tui_state **st)
{
    if (!st || !*st)
        return;
    tui_state_clear(*st);
    free(*st);
    *st = NULL;
}

/* ---- what the loop asks ------------------------------------------------------ */

void tui_state_set_export_dir(tui_state *st, const char *dir)
{
    snprintf(st->export_dir, sizeof st->export_dir, "%s", dir);
}

void tui_state_set_present(tui_state *st, int on)
{
    st->present = on;
}

double tui_state_step_interval(const tui_state *st)
{
    return st->present ? 1.0 / st->pace : 0;
}

int tui_state_running(const tui_state *st)
{
    return st->running;
}

int tui_state_idle(const tui_state *st)
{
    return !tui_state_busy(st) && !st->running && !st->pending;
}

double tui_state_step_age(const tui_state *st, double now)
{
    return st->job.kind == TUI_JOB_STEP ? now - st->job.t0 : -1;
}
