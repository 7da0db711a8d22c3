/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Actions: one table maps keys to functions that change the state and
 * return reactions (doc/style.md C12). Only scene and level changes raise
 * TUI_REASSEMBLE; method, parameter, friction and tolerance changes raise
 * TUI_RESOLVE, which the session serves from its operator cache. No
 * curses here. */
#include "tui/tui_impl.h"
#include "base/opt_solve.h"
#include "cx_config.h"

#if CX_HAVE_RENDER
#include "render/render.h"
#endif

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

/* ---- the picker rows ------------------------------------------------------
 * One descriptor per row (tui_row, tui_impl.h): its label, how its value
 * is shown, stepped with left/right, entered as text, and why it is grey.
 * Drawing (draw.c), the keys and the text entry all go through the table
 * at the end of this section. */

static int select_method(tui_state *st, int index)
{
    char reason[CX_DIAG_LEN];
    if (tui_state_method_reason(st, index, reason, sizeof reason)[0]) {
        /* greyed: the reason, and the selection and the session stay, so
         * the row never shows a method other than the one that runs */
        tui_msg(st, 1, "%s: %s", cx_method_at(index)->id, reason);
        return TUI_REDRAW;
    }
    st->sel_method = index;
    cx_param_default(&st->sel_params, cx_method_at(index)->params);
    st->msg[0] = '\0';
    return TUI_REDRAW | TUI_RESOLVE;
}

/* The next method from the selected one in direction dir that can run the
 * scene under the selected law (greyed ones skipped), -1 if none. */
static int next_method(const tui_state *st, int dir)
{
    int n = cx_method_count();
    char reason[CX_DIAG_LEN];
    for (int k = 1; k <= n; k++) {
        int i = ((st->sel_method + dir * k) % n + n) % n;
        if (!tui_state_method_reason(st, i, reason, sizeof reason)[0])
            return i;
    }
    return -1;
}

/* scene */

static void scene_format(const tui_state *st, int i, char *buf, size_t len)
{
    (void)i;
    snprintf(buf, len, "%s", st->scene_ids[st->sel_scene]);
}

static int scene_step(tui_state *st, int i, int dir)
{
    (void)i;
    st->sel_scene = ((st->sel_scene + dir) % st->nscenes + st->nscenes) % st->nscenes;
    return TUI_REDRAW | TUI_REASSEMBLE;
}

static int scene_enter(tui_state *st, int i, const char *text)
{
    (void)i;
    for (int k = 0; k < st->nscenes; k++)
        if (strcmp(st->scene_ids[k], text) == 0) {
            st->sel_scene = k;
            return TUI_REDRAW | TUI_REASSEMBLE;
        }
    tui_msg(st, 1, "unknown scene '%s' (see 'signorini list')", text);
    return TUI_REDRAW;
}

static void scene_describe(const tui_state *st, int i, char *buf, size_t len)
{
    (void)i;
    snprintf(buf, len, "%s", st->scene.title);
}

static int scene_count(const tui_state *st) { return st->nscenes; }
static int scene_current(const tui_state *st) { return st->sel_scene; }

static const char *scene_item(const tui_state *st, int k, char *why, size_t len)
{
    if (len)
        why[0] = '\0';
    return st->scene_ids[k];
}

/* level */

/* "12.3k" */
static void level_count(double n, char *buf, size_t len)
{
    if (n >= 1e6)
        snprintf(buf, len, "%.2gM", n / 1e6);
    else if (n >= 1e4)
        snprintf(buf, len, "%.0fk", n / 1e3);
    else if (n >= 1e3)
        snprintf(buf, len, "%.1fk", n / 1e3);
    else
        snprintf(buf, len, "%.0f", n);
}

/* "<0.1 s", "2.3 s", "40 s", "12 min" */
static void level_time(double t, char *buf, size_t len)
{
    if (t < 0.1)
        snprintf(buf, len, "<0.1 s");
    else if (t < 100)
        snprintf(buf, len, "%.2g s", t);
    else
        snprintf(buf, len, "%.0f min", t / 60);
}

/* The level and its dofs: the session's, or about so many for another. */
static void level_format(const tui_state *st, int i, char *buf, size_t len)
{
    (void)i;
    double n, b, t;
    char c[32];
    if (!tui_state_level_estimate(st, st->sel_level, &n, &b, &t)) {
        snprintf(buf, len, "%d", st->sel_level);
        return;
    }
    level_count(n, c, sizeof c);
    /* 11 columns at 80: the word goes first when they are short */
    int w = snprintf(buf, len, "%d %s%s dofs", st->sel_level, st->sel_level == st->level ? "" : "~", c);
    if (w > 11)
        snprintf(buf, len, "%d %s%s", st->sel_level, st->sel_level == st->level ? "" : "~", c);
}

/* A level whose estimate exceeds the free memory is refused with the
 * figures, before anything is built. */
static int level_refused(tui_state *st, int level)
{
    char msg[CX_DIAG_LEN];
    if (!tui_state_level_refused(st, level, tui_mem_available(), msg, sizeof msg))
        return 0;
    tui_msg(st, 1, "%s (%s)", msg, tui_mem_source());
    return 1;
}

/* The row of cx_solve_opts a typed or stepped value is checked against:
 * one range per option, the same as on the command line (base/opt_solve.h). */
static const cx_opt *actions_row(const char *name)
{
    const cx_opt *o = cx_opt_find(cx_solve_opts, name);
    assert(o);
    return o;
}

/* The value of text for option name, or a message in the status line. */
static int actions_value(tui_state *st, const char *name, const char *text, double *x)
{
    cx_diag d;
    cx_diag_clear(&d);
    if (cx_opt_value(actions_row(name), text, x, &d) == CX_OK)
        return CX_OK;
    tui_msg(st, 1, "%s", d.msg);
    return d.status;
}

static int level_step(tui_state *st, int i, int dir)
{
    (void)i;
    int l = dir > 0 ? st->sel_level * 2 : st->sel_level / 2;
    l = l < 1 ? 1 : l > st->scene.level_max ? st->scene.level_max : l;
    if (l == st->sel_level || level_refused(st, l))
        return TUI_REDRAW;
    st->sel_level = l;
    return TUI_REDRAW | TUI_REASSEMBLE;
}

static int level_enter(tui_state *st, int i, const char *text)
{
    (void)i;
    double x;
    if (actions_value(st, "level", text, &x))
        return TUI_REDRAW;
    if (x > st->scene.level_max) {
        tui_msg(st, 1, "level '%s': scene '%s' allows levels 1 to %d", text, st->scene.id, st->scene.level_max);
        return TUI_REDRAW;
    }
    if (level_refused(st, (int)x))
        return TUI_REDRAW;
    st->sel_level = (int)x;
    return TUI_REDRAW | TUI_REASSEMBLE;
}

/* The range, then what the next levels up and down would take. */
static void level_describe(const tui_state *st, int i, char *buf, size_t len)
{
    (void)i;
    size_t at = (size_t)snprintf(buf, len, "1 to %d; rebuilds\nEsc abandons a build.", st->scene.level_max);
    double avail = tui_mem_available();
    const int next[2] = {st->sel_level * 2, st->sel_level / 2};
    const char key[2] = {']', '['};
    for (int k = 0; k < 2 && at < len; k++) {
        int l = next[k];
        double n, b, t;
        if (l < 1 || l > st->scene.level_max || !tui_state_level_estimate(st, l, &n, &b, &t))
            continue;
        char c[32], mem[32], tm[32];
        level_count(n, c, sizeof c);
        tui_size_text(b, mem, sizeof mem);
        level_time(t, tm, sizeof tm);
        at += (size_t)snprintf(buf + at, len - at, " %c level %d: ~%s dofs, ~%s, ~%s%s.", key[k], l, c, mem, tm,
                               avail > 0 && b > avail ? ", refused: more than the free memory" : "");
    }
    if (avail > 0 && at < len) {
        char have[32];
        tui_size_text(avail, have, sizeof have);
        snprintf(buf + at, len - at, " %s free.", have);
    }
}

/* friction law */

static void friction_format(const tui_state *st, int i, char *buf, size_t len)
{
    (void)i;
    snprintf(buf, len, "%s", cx_friction_name(st->sel_law));
}

/* A law chosen: if the selected method cannot run it, the method
 * --method auto chooses for it (with its parameters), so that cycling the
 * laws never dead-ends on a refusal. */
static int select_law(tui_state *st, cx_friction law)
{
    st->sel_law = law;
    char reason[CX_DIAG_LEN];
    if (!tui_state_method_reason(st, st->sel_method, reason, sizeof reason)[0])
        return TUI_REDRAW | TUI_RESOLVE;
    const cx_method *was = tui_state_sel_method(st);
    tui_state_select_auto(st);
    if (tui_state_method_reason(st, st->sel_method, reason, sizeof reason)[0]) {
        st->sel_law = st->cur_law;
        st->sel_method = st->cur_method ? tui_method_index(st->cur_method->id) : st->sel_method;
        st->sel_params = st->cur_params;
        tui_msg(st, 1, "%s friction: %s", cx_friction_name(law), reason);
        return TUI_REDRAW;
    }
    tui_msg(st, 0, "%s does not support %s friction: switching to %s", was->id, cx_friction_name(law),
            tui_state_sel_method(st)->id);
    return TUI_REDRAW | TUI_RESOLVE;
}

static int friction_step(tui_state *st, int i, int dir)
{
    (void)i;
    /* the laws the scene allows (its 'laws' key), in order */
    unsigned laws = st->scene.laws ? st->scene.laws : CX_SCENE_ALL_LAWS;
    int law = (int)st->sel_law;
    for (int k = 0; k < 3; k++) {
        law = (law + dir + 3) % 3;
        if (laws & (1u << law))
            break;
    }
    if (law == (int)st->sel_law) {
        tui_msg(st, 0, "scene '%s' allows only %s friction", st->scene.id, cx_friction_name(st->sel_law));
        return TUI_REDRAW;
    }
    return select_law(st, (cx_friction)law);
}

static int friction_enter(tui_state *st, int i, const char *text)
{
    (void)i;
    int law = cx_friction_from_name(text);
    if (law < 0) {
        tui_msg(st, 1, "friction '%s': expected none, tresca or coulomb", text);
        return TUI_REDRAW;
    }
    unsigned laws = st->scene.laws ? st->scene.laws : CX_SCENE_ALL_LAWS;
    if (!(laws & (1u << law))) {
        tui_msg(st, 1, "friction '%s': scene '%s' does not allow it", text, st->scene.id);
        return TUI_REDRAW;
    }
    return select_law(st, (cx_friction)law);
}

/* the friction coefficient: Tresca slip bound or Coulomb F */

static const char *coef_label(const tui_state *st, int i)
{
    (void)i;
    return st->sel_law == CX_FRICTION_COULOMB ? "F" : st->sel_law == CX_FRICTION_TRESCA ? "slip s" : "F / s";
}

static void coef_format(const tui_state *st, int i, char *buf, size_t len)
{
    (void)i;
    if (st->sel_law == CX_FRICTION_NONE)
        snprintf(buf, len, "-");
    else
        snprintf(buf, len, "%.4g", st->sel_law == CX_FRICTION_COULOMB ? st->sel_F : st->sel_slip);
}

static const char *coef_greyed(const tui_state *st, int i, char *why, size_t len)
{
    (void)i;
    snprintf(why, len, "%s", st->sel_law == CX_FRICTION_NONE ? "no friction: choose Tresca or Coulomb first" : "");
    return why;
}

static int coef_step(tui_state *st, int i, int dir)
{
    char why[CX_DIAG_LEN];
    if (coef_greyed(st, i, why, sizeof why)[0]) {
        tui_msg(st, 1, "%s", why);
        return TUI_REDRAW;
    }
    if (st->sel_law == CX_FRICTION_COULOMB)
        st->sel_F = fmax(0, round((st->sel_F + 0.05 * dir) * 100) / 100);
    else
        st->sel_slip = dir > 0 ? st->sel_slip * 1.25 : st->sel_slip / 1.25;
    return TUI_REDRAW | TUI_RESOLVE;
}

static int coef_enter(tui_state *st, int i, const char *text)
{
    (void)i;
    double x;
    if (actions_value(st, st->sel_law == CX_FRICTION_COULOMB ? "F" : "slip", text, &x))
        return TUI_REDRAW;
    if (st->sel_law == CX_FRICTION_COULOMB)
        st->sel_F = x;
    else
        st->sel_slip = x;
    return TUI_REDRAW | TUI_RESOLVE;
}

static void coef_describe(const tui_state *st, int i, char *buf, size_t len)
{
    (void)i;
    snprintf(buf, len, "%s", st->sel_law == CX_FRICTION_COULOMB ? "Coulomb coefficient F"
                             : st->sel_law == CX_FRICTION_TRESCA ? "Tresca bound (traction)"
                                                                  : "no friction");
}

/* method */

/* On the PETSc backend ('b') the row shows and steps the backend's method
 * (the header names the backend): that is what s and r run, not the
 * direct path's selection. */
static void method_format(const tui_state *st, int i, char *buf, size_t len)
{
    (void)i;
    if (st->sel_backend)
        snprintf(buf, len, "%s", tui_backend_method(st->sel_backend - 1));
    else
        snprintf(buf, len, "%s", tui_state_sel_method(st)->id);
}

static int method_step(tui_state *st, int i, int dir)
{
    (void)i;
    if (st->sel_backend) {
        int n = 0;
        while (tui_backend_method(n))
            n++;
        st->sel_backend = (st->sel_backend - 1 + (dir > 0 ? 1 : n - 1)) % n + 1;
        tui_msg(st, 0, "backend petsc, method %s (1 rank); b: the next one, then the direct path",
                tui_backend_method(st->sel_backend - 1));
        return TUI_REDRAW;
    }
    int k = next_method(st, dir);
    if (k < 0 || k == st->sel_method) {
        tui_msg(st, 0, "%s is the only method that fits this scene", tui_state_sel_method(st)->id);
        return TUI_REDRAW;
    }
    return select_method(st, k);
}

static int method_enter(tui_state *st, int i, const char *text)
{
    (void)i;
    if (st->sel_backend) {
        for (int k = 0; tui_backend_method(k); k++)
            if (strcmp(tui_backend_method(k), text) == 0) {
                st->sel_backend = k + 1;
                tui_msg(st, 0, "backend petsc, method %s (1 rank)", text);
                return TUI_REDRAW;
            }
        tui_msg(st, 1, "the PETSc backend has no method '%s' (b: back to the direct path's methods)", text);
        return TUI_REDRAW;
    }
    const cx_method *m = cx_method_find(text);
    if (!m) {
        tui_msg(st, 1, "unknown method '%s' (see 'signorini list')", text);
        return TUI_REDRAW;
    }
    for (int k = 0; k < cx_method_count(); k++)
        if (cx_method_at(k) == m)
            return select_method(st, k);
    return TUI_REDRAW;
}

/* On the PETSc backend the list, the grey reasons and the description
 * are the backend's methods', whose parameters are PETSc options (no
 * parameter rows: tui_state_nfields). */
static const char *method_greyed(const tui_state *st, int i, char *why, size_t len)
{
    (void)i;
    if (st->sel_backend) {
        snprintf(why, len, "%s", tui_backend_refusal(st->sel_backend - 1, st->sel_law));
        return why;
    }
    return tui_state_method_reason(st, st->sel_method, why, len);
}

static void method_describe(const tui_state *st, int i, char *buf, size_t len)
{
    (void)i;
    if (st->sel_backend) {
        snprintf(buf, len, "PETSc, 1 rank: %s (PETSc options prefixed cx_, as PETSC_OPTIONS=-cx_pc_type gamg)",
                 tui_backend_summary(st->sel_backend - 1));
        return;
    }
    const cx_method *m = tui_state_sel_method(st);
    snprintf(buf, len, "%s (%s)", m->name, m->source);
}

static int method_count(const tui_state *st)
{
    int n = 0;
    if (st->sel_backend)
        while (tui_backend_method(n))
            n++;
    return st->sel_backend ? n : cx_method_count();
}

static int method_current(const tui_state *st) { return st->sel_backend ? st->sel_backend - 1 : st->sel_method; }

static const char *method_item(const tui_state *st, int k, char *why, size_t len)
{
    if (st->sel_backend) {
        snprintf(why, len, "%s", tui_backend_refusal(k, st->sel_law));
        return tui_backend_method(k);
    }
    tui_state_method_reason(st, k, why, len);
    return cx_method_at(k)->id;
}

/* tolerance and iteration limit */

static void tol_format(const tui_state *st, int i, char *buf, size_t len)
{
    (void)i;
    snprintf(buf, len, "%.0e", st->sel_opt.tol);
}

static int tol_step(tui_state *st, int i, int dir)
{
    (void)i;
    /* a step that would leave the option's range is not taken */
    double x = dir > 0 ? st->sel_opt.tol * 10 : st->sel_opt.tol / 10;
    if (!cx_opt_in_range(actions_row("tol"), x) || x < 1e-16)
        return TUI_REDRAW;
    st->sel_opt.tol = x;
    return TUI_REDRAW | TUI_RESOLVE;
}

static int tol_enter(tui_state *st, int i, const char *text)
{
    (void)i;
    double x;
    if (actions_value(st, "tol", text, &x))
        return TUI_REDRAW;
    st->sel_opt.tol = x;
    return TUI_REDRAW | TUI_RESOLVE;
}

static void maxit_format(const tui_state *st, int i, char *buf, size_t len)
{
    (void)i;
    snprintf(buf, len, "%d", st->sel_opt.max_iter);
}

static int maxit_step(tui_state *st, int i, int dir)
{
    (void)i;
    double x = dir > 0 ? st->sel_opt.max_iter * 2.0 : floor(st->sel_opt.max_iter / 2.0);
    if (!cx_opt_in_range(actions_row("max-iter"), x))
        return TUI_REDRAW;
    st->sel_opt.max_iter = (int)x;
    return TUI_REDRAW | TUI_RESOLVE;
}

static int maxit_enter(tui_state *st, int i, const char *text)
{
    (void)i;
    double x;
    if (actions_value(st, "max-iter", text, &x))
        return TUI_REDRAW;
    st->sel_opt.max_iter = (int)x;
    return TUI_REDRAW | TUI_RESOLVE;
}

/* a parameter of the selected method */

static const char *param_label(const tui_state *st, int i)
{
    return i < st->sel_params.n ? st->sel_params.table[i].key : "?";
}

static void param_format(const tui_state *st, int i, char *buf, size_t len)
{
    cx_param_format(&st->sel_params, i, buf, len);
}

static int param_step(tui_state *st, int i, int dir)
{
    cx_param_values *v = &st->sel_params;
    const cx_param *p = &v->table[i];
    char text[CX_PARAM_STRLEN];
    double x = v->num[i];
    switch (p->type) {
    case CX_PARAM_REAL:
        if (isnan(x))
            x = p->def;
        else if (x == 0)
            x = dir > 0 ? fmin(p->max, 1e-3) : fmax(p->min, -1e-3);
        else
            x = dir > 0 ? x * 2 : x / 2;
        x = fmax(p->min, fmin(p->max, x));
        snprintf(text, sizeof text, "%.6g", x);
        break;
    case CX_PARAM_INT:
        snprintf(text, sizeof text, "%.0f", fmax(p->min, fmin(p->max, x + dir)));
        break;
    case CX_PARAM_BOOL:
        snprintf(text, sizeof text, "%s", x != 0 ? "false" : "true");
        break;
    case CX_PARAM_CHOICE: {
        int n = 1;
        for (const char *c = p->choices; c && *c; c++)
            n += *c == '|';
        int k = (((int)x + dir) % n + n) % n;
        const char *c = p->choices;
        for (int j = 0; j < k; j++)
            c = strchr(c, '|') + 1;
        size_t len = strcspn(c, "|");
        snprintf(text, sizeof text, "%.*s", (int)len, c);
        break;
    }
    default: {
        /* free text, in practice the id of an inner method: cycle the registry */
        int k = 0, n = cx_method_count();
        for (int j = 0; j < n; j++)
            if (strcmp(cx_method_at(j)->id, v->str[i]) == 0)
                k = j;
        snprintf(text, sizeof text, "%s", cx_method_at(((k + dir) % n + n) % n)->id);
        break;
    }
    }
    cx_diag d;
    cx_diag_clear(&d);
    char owner[64];
    snprintf(owner, sizeof owner, "method '%s'", tui_state_sel_method(st)->id);
    if (cx_param_set(v, p->key, text, owner, &d) != CX_OK) {
        tui_msg(st, 1, "%s", d.msg);
        return TUI_REDRAW;
    }
    return TUI_REDRAW | TUI_RESOLVE;
}

static int param_enter(tui_state *st, int i, const char *text)
{
    cx_diag d;
    cx_diag_clear(&d);
    char owner[64];
    snprintf(owner, sizeof owner, "method '%s'", tui_state_sel_method(st)->id);
    const cx_param *p = &st->sel_params.table[i];
    if (cx_param_set(&st->sel_params, p->key, text, owner, &d) != CX_OK) {
        tui_msg(st, 1, "%s", d.msg);
        return TUI_REDRAW;
    }
    return TUI_REDRAW | TUI_RESOLVE;
}

/* "range R", then the help */
static void param_describe(const tui_state *st, int i, char *buf, size_t len)
{
    const cx_param *p = &st->sel_params.table[i];
    char range[96];
    cx_param_range(p, range, sizeof range);
    snprintf(buf, len, "%s: range %s\n%s", p->key, range, p->help ? p->help : "");
}

static const tui_row tui_rows[] = {
    [TUI_F_SCENE] = {"scene", TUI_ROW_LIST, NULL, scene_format, scene_step, scene_enter, NULL, scene_describe,
                     scene_count, scene_current, scene_item},
    [TUI_F_LEVEL] = {"level", TUI_ROW_NUMBER, NULL, level_format, level_step, level_enter, NULL, level_describe,
                     NULL, NULL, NULL},
    [TUI_F_FRICTION] = {"friction", TUI_ROW_CHOICE, NULL, friction_format, friction_step, friction_enter, NULL,
                        NULL, NULL, NULL, NULL},
    [TUI_F_COEF] = {NULL, TUI_ROW_NUMBER, coef_label, coef_format, coef_step, coef_enter, coef_greyed,
                    coef_describe, NULL, NULL, NULL},
    [TUI_F_METHOD] = {"method", TUI_ROW_LIST, NULL, method_format, method_step, method_enter, method_greyed,
                      method_describe, method_count, method_current, method_item},
    [TUI_F_TOL] = {"tol", TUI_ROW_NUMBER, NULL, tol_format, tol_step, tol_enter, NULL, NULL, NULL, NULL, NULL},
    [TUI_F_MAXIT] = {"max iter", TUI_ROW_NUMBER, NULL, maxit_format, maxit_step, maxit_enter, NULL, NULL, NULL,
                     NULL, NULL},
    [TUI_F_PARAM0] = {NULL, TUI_ROW_NUMBER, param_label, param_format, param_step, param_enter, NULL,
                      param_describe, NULL, NULL, NULL},
};

int tui_state_nfields(const tui_state *st)
{
    return TUI_F_PARAM0 + (st->sel_backend ? 0 : st->sel_params.n);
}

const tui_row *tui_row_at(const tui_state *st, int f, int *i)
{
    (void)st;
    *i = f >= TUI_F_PARAM0 ? f - TUI_F_PARAM0 : 0;
    return &tui_rows[f >= TUI_F_PARAM0 ? TUI_F_PARAM0 : f];
}

const char *tui_field_label(const tui_state *st, int f)
{
    int i;
    const tui_row *r = tui_row_at(st, f, &i);
    return r->label ? r->label : r->label_of(st, i);
}

void tui_field_value(const tui_state *st, int f, char *buf, size_t len)
{
    int i;
    tui_row_at(st, f, &i)->format(st, i, buf, len);
}

/* Left (-1) or right (+1) on the row under the cursor. */
static int change_field(tui_state *st, int dir)
{
    int i;
    return tui_row_at(st, st->field, &i)->step(st, i, dir);
}

/* Enter on a row: the typed text. */
static int commit_edit(tui_state *st, const char *text)
{
    int i;
    return tui_row_at(st, st->field, &i)->enter(st, i, text);
}

static int edit_key(tui_state *st, int key)
{
    if (key == TUI_KEY_ESC || key == TUI_KEY_CTRL_C) {
        st->editing = 0;
        return TUI_REDRAW;
    }
    if (key == TUI_KEY_ENTER) {
        st->editing = 0;
        st->edit[st->edit_len] = '\0';
        st->msg[0] = '\0';
        return commit_edit(st, st->edit);
    }
    if (key == TUI_KEY_BACKSPACE) {
        if (st->edit_len > 0)
            st->edit_len--;
        return TUI_REDRAW;
    }
    if (key >= 32 && key < 127 && st->edit_len + 1 < (int)sizeof st->edit)
        st->edit[st->edit_len++] = (char)key;
    return TUI_REDRAW;
}

/* ---- actions ------------------------------------------------------------------ */

static int act_step(tui_state *st)
{
    st->running = 0;
    if (tui_state_busy(st)) {
        /* typed ahead: done in order when the job ends */
        if (st->queued_steps < 1000)
            st->queued_steps++;
        return TUI_REDRAW;
    }
    st->msg[0] = '\0';
    tui_state_step(st);
    return TUI_REDRAW;
}

static int act_run(tui_state *st)
{
    if (st->running) {
        st->running = 0;
        tui_msg(st, 0, "paused (r runs on)");
        return TUI_REDRAW;
    }
    /* typed during a switch or a build (or with one waiting): the run it
     * asks for is the one that job opens, not the ended one on screen */
    int switching = (tui_state_busy(st) && st->job.kind != TUI_JOB_STEP && st->job.kind != TUI_JOB_PETSC) ||
                    st->pending;
    if (switching) {
        st->running = 1;
        tui_msg(st, 0, "runs when the switch ends");
        return TUI_REDRAW;
    }
    const tui_run *run = tui_state_run(st);
    if (tui_state_run_ended(st)) {
        tui_msg(st, run->reason < 0, "run ended (%s); x starts again", cx_reason_str(run->reason));
        return TUI_REDRAW;
    }
    st->running = 1;
    st->msg[0] = '\0';
    return TUI_REDRAW;
}

/* Esc: stop what is going on. A step in progress is cancelled through the
 * session's cancel flag (the method stops at its next check; the UI does
 * not wait); a paced or running run pauses; queued steps are dropped. A
 * build is abandoned: the UI goes back to the level it had at once, the
 * build finishes on its own thread and frees its memory when it ends. */
static int act_cancel(tui_state *st)
{
    int had = st->running || st->queued_steps;
    st->running = 0;
    st->queued_steps = 0;
    if (tui_state_busy(st) && st->job.kind == TUI_JOB_STEP && st->session) {
        cx_session_cancel(st->session);
        tui_msg(st, 0, "cancelling the step in progress");
    } else if (tui_state_busy(st) && st->job.kind == TUI_JOB_PETSC) {
        tui_backend_cancel(st);
        tui_msg(st, 0, "stopping the PETSc run at its next step");
    } else if (tui_state_busy(st) && st->job.kind == TUI_JOB_BUILD && st->job.box) {
        tui_state_abandon_build(st);
    } else if (tui_state_busy(st))
        tui_msg(st, 2, "a switch cannot be cancelled before it ends; q quits");
    else if (had)
        tui_msg(st, 0, "paused (r runs on)");
    return TUI_REDRAW;
}

/* 'b': the direct path, then each method of the PETSc backend in turn. */
static int act_backend(tui_state *st)
{
    if (!tui_backend_available()) {
        tui_msg(st, 1, "this build has no PETSc backend (meson setup -Dpetsc=enabled)");
        return TUI_REDRAW;
    }
    int n = 0;
    while (tui_backend_method(n))
        n++;
    st->sel_backend = (st->sel_backend + 1) % (n + 1);
    if (st->field >= tui_state_nfields(st))   /* the direct method's parameter rows went */
        st->field = TUI_F_METHOD;
    if (st->sel_backend)
        tui_msg(st, 0, "backend petsc, method %s (1 rank): s or r runs it to the end; b changes",
                tui_backend_method(st->sel_backend - 1));
    else
        tui_msg(st, 0, "backend direct: the setup's method, step by step");
    return TUI_REDRAW;
}

static int act_reset(tui_state *st)
{
    tui_state_reset(st);
    return TUI_REDRAW;
}

static int act_up(tui_state *st)
{
    int n = tui_state_nfields(st);
    st->field = (st->field - 1 + n) % n;
    return TUI_REDRAW;
}

static int act_down(tui_state *st)
{
    st->field = (st->field + 1) % tui_state_nfields(st);
    return TUI_REDRAW;
}

static int act_left(tui_state *st) { return change_field(st, -1); }
static int act_right(tui_state *st) { return change_field(st, +1); }

static int act_edit(tui_state *st)
{
    st->editing = 1;
    char v[64];
    tui_field_value(st, st->field, v, sizeof v);
    v[strcspn(v, " ")] = '\0';   /* the value, not what follows it (the level's dofs) */
    if (strcmp(v, "-") == 0)
        v[0] = '\0';
    st->edit_len = snprintf(st->edit, sizeof st->edit, "%s", v);
    if (st->edit_len >= (int)sizeof st->edit)
        st->edit_len = (int)sizeof st->edit - 1;
    return TUI_REDRAW;
}

static int act_next_method(tui_state *st)
{
    /* the next method that can run this scene */
    st->field = TUI_F_METHOD;
    return method_step(st, 0, +1);
}

/* Shortcuts: move to a row and change it. */
static int act_row(tui_state *st, int field, int dir)
{
    st->field = field;
    return change_field(st, dir);
}

static int act_friction(tui_state *st) { return act_row(st, TUI_F_FRICTION, +1); }
static int act_coef_up(tui_state *st) { return act_row(st, TUI_F_COEF, +1); }
static int act_coef_down(tui_state *st) { return act_row(st, TUI_F_COEF, -1); }
static int act_level_up(tui_state *st) { return act_row(st, TUI_F_LEVEL, +1); }
static int act_level_down(tui_state *st) { return act_row(st, TUI_F_LEVEL, -1); }
static int act_next_scene(tui_state *st) { return act_row(st, TUI_F_SCENE, +1); }

static int act_view(tui_state *st)
{
    st->view = !st->view;
    return TUI_REDRAW;
}

static int act_scale_up(tui_state *st)
{
    st->disp_scale = 2 * (st->disp_scale > 0 ? st->disp_scale : tui_mesh_auto_scale(st));
    return TUI_REDRAW;
}

static int act_scale_down(tui_state *st)
{
    st->disp_scale = 0.5 * (st->disp_scale > 0 ? st->disp_scale : tui_mesh_auto_scale(st));
    return TUI_REDRAW;
}

static int act_scale_auto(tui_state *st)
{
    st->disp_scale = 0;
    return TUI_REDRAW;
}

static int act_clear_runs(tui_state *st)
{
    /* keep the current run, forget the earlier ones */
    tui_history_keep_current(st->history);
    tui_msg(st, 0, "earlier runs cleared");
    return TUI_REDRAW;
}

static int act_export(tui_state *st)
{
    char csv[512], json[512];
    cx_diag d;
    cx_diag_clear(&d);
    if (tui_export(st, st->export_dir, csv, json, sizeof csv, &d) != CX_OK)
        tui_msg(st, 1, "export: %s", d.msg);
    else
        tui_msg(st, 0, "runs written to %s and %s", csv, json);
    return TUI_REDRAW;
}

/* ==== RENDERING HOOK ========================================================
 * The one place the explorer renders: the session's current iterate, the
 * field von Mises, the mesh view's displacement scale, the scene's
 * supports, into the export directory as
 * signorini-SCENE-LLEVEL-METHOD-itN.png. Called on the main thread while
 * no job runs, so the session is not stepping meanwhile. */
int tui_render_png(const tui_state *st, char *file, size_t len, cx_diag *d)
{
    if (len)
        file[0] = '\0';
#if CX_HAVE_RENDER
    if (!st->session || !cx_session_method(st->session))
        return cx_diag_set(d, CX_EINVAL, "nothing to render yet");
    cx_result *res = NULL;
    CX_TRY(cx_result_from_session(&res, st->session, &st->scene, st->level, d));
    cx_render_opts o;
    cx_render_opts_default(&o);
    o.scale = st->disp_scale;
    o.scene = &st->scene;   /* its supports, as solve --png draws them */
    snprintf(file, len, "%s/signorini-%s-L%d-%s-it%d.png", st->export_dir, st->scene.id, st->level,
             res->run.method, res->run.iterations);
    int rc = cx_render_png(res, &o, file, NULL, d);
    cx_result_destroy(&res);
    return rc;
#else
    (void)st;
    return cx_diag_set(d, CX_EUNSUPPORTED, "rendering not available in this build");
#endif
}
/* ==== END OF RENDERING HOOK ================================================== */

static int act_render(tui_state *st)
{
    char file[512];
    cx_diag d;
    cx_diag_clear(&d);
    if (tui_state_busy(st) || !st->session)
        tui_msg(st, 0, "busy: render after the build");
    else if (tui_render_png(st, file, sizeof file, &d) != CX_OK)
        tui_msg(st, 1, "%s", d.msg);
    else
        tui_msg(st, 0, "rendered to %s", file);
    return TUI_REDRAW;
}

static int act_present(tui_state *st)
{
    st->present = !st->present;
    if (st->present)
        tui_msg(st, 0, "presentation mode: %.3g steps per second ({ slower, } faster); P leaves", st->pace);
    else
        tui_msg(st, 0, "presentation mode off: runs at full speed");
    return TUI_REDRAW;
}

/* The pace doubles or halves within [TUI_PACE_MIN, TUI_PACE_MAX]. */
static int pace_by(tui_state *st, double f)
{
    double p = st->pace * f;
    st->pace = p < TUI_PACE_MIN ? TUI_PACE_MIN : p > TUI_PACE_MAX ? TUI_PACE_MAX : p;
    tui_msg(st, 0, "%.3g steps per second%s", st->pace, st->present ? "" : " (in presentation mode, P)");
    return TUI_REDRAW;
}

static int act_pace_up(tui_state *st)
{
    return pace_by(st, 2);
}

static int act_pace_down(tui_state *st)
{
    return pace_by(st, 0.5);
}

static int act_help(tui_state *st)
{
    st->help = !st->help;
    return TUI_REDRAW;
}

static int act_quit(tui_state *st)
{
    (void)st;
    return TUI_QUIT;
}

static int act_resize(tui_state *st)
{
    (void)st;
    return TUI_REDRAW;
}

static const tui_binding tui_keys[] = {
    {'s', "s space", act_step, "one iteration of the method"},
    {' ', NULL, act_step, NULL},
    {'r', "r", act_run, "run to convergence / pause"},
    {'x', "x", act_reset, "start the method again"},
    {TUI_KEY_ESC, "Esc", act_cancel, "cancel a step, pause a run"},
    {TUI_KEY_UP, "up k", act_up, "previous setup row"},
    {'k', NULL, act_up, NULL},
    {TUI_KEY_DOWN, "down j", act_down, "next setup row"},
    {'j', NULL, act_down, NULL},
    {TUI_KEY_LEFT, "left h", act_left, "previous value of the row"},
    {'h', NULL, act_left, NULL},
    {TUI_KEY_RIGHT, "right l", act_right, "next value of the row"},
    {'l', NULL, act_right, NULL},
    {TUI_KEY_ENTER, "Enter", act_edit, "type a value for the row"},
    {'m', "m", act_next_method, "next method that fits"},
    {'b', "b", act_backend, "backend: direct or PETSc"},
    {'f', "f", act_friction, "friction none/Tresca/Coulomb"},
    {'+', "+ -", act_coef_up, "friction coefficient up/down"},
    {'-', NULL, act_coef_down, NULL},
    {']', "] [", act_level_up, "mesh level x2, /2 (rebuilds)"},
    {'[', NULL, act_level_down, NULL},
    {'n', "n", act_next_scene, "next scene (rebuilds)"},
    {'v', "v", act_view, "convergence plot / mesh view"},
    {'>', "> < =", act_scale_up, "mesh displacement x2,/2,auto"},
    {'<', NULL, act_scale_down, NULL},
    {'=', NULL, act_scale_auto, NULL},
    {'c', "c", act_clear_runs, "forget the earlier runs"},
    {'e', "e", act_export, "export runs as CSV and JSON"},
    {'p', "p", act_render, "render the state to PNG"},
    {'P', "P", act_present, "presentation mode on/off"},
    {'}', "} {", act_pace_up, "presentation pace x2, /2"},
    {'{', NULL, act_pace_down, NULL},
    {'?', "?", act_help, "this help"},
    {'q', "q ^C", act_quit, "quit"},
    {TUI_KEY_CTRL_C, NULL, act_quit, NULL},
    {TUI_KEY_RESIZE, NULL, act_resize, NULL},
    {0, NULL, NULL, NULL}
};

/* The help lists the rows with a key name. */
const tui_binding *tui_bindings(void)
{
    static tui_binding shown[sizeof tui_keys / sizeof tui_keys[0]];
    int n = 0;
    for (int k = 0; tui_keys[k].key; k++)
        if (tui_keys[k].keyname)
            shown[n++] = tui_keys[k];
    shown[n] = (tui_binding){0, NULL, NULL, NULL};
    return shown;
}

int tui_mouse(tui_state *st, int kind, int index, int what)
{
    if (st->editing || st->help)
        return 0;
    if (kind == TUI_HIT_FIELD && index >= 0 && index < tui_state_nfields(st)) {
        st->field = index;
        if (what == TUI_MOUSE_CLICK)
            return TUI_REDRAW;
        int i;
        const tui_row *row = tui_row_at(st, index, &i);
        return row->step ? TUI_REDRAW | row->step(st, i, what == TUI_MOUSE_WHEEL_UP ? +1 : -1) : TUI_REDRAW;
    }
    if (kind == TUI_HIT_RUN && what == TUI_MOUSE_CLICK && index >= 0 && index < tui_state_nruns(st)) {
        const tui_run *run = tui_state_run_at(st, index);
        st->highlight = st->highlight == run->serial + 1 ? 0 : run->serial + 1;
        char leg[96];
        tui_run_legend(run, leg, sizeof leg);
        if (st->highlight)
            tui_msg(st, 0, "run %d highlighted: %s (click again: none)", run->serial + 1, leg);
        else
            st->msg[0] = '\0';
        return TUI_REDRAW;
    }
    return 0;
}

int tui_key(tui_state *st, int key)
{
    if (key == TUI_KEY_NONE)
        return 0;
    if (st->editing)
        return edit_key(st, key);
    if (st->help && key != TUI_KEY_RESIZE && key != TUI_KEY_CTRL_C && key != 'q') {
        st->help = 0;
        return TUI_REDRAW;
    }
    for (int k = 0; tui_keys[k].key; k++)
        if (tui_keys[k].key == key)
            return tui_keys[k].action(st);
    return 0;
}
