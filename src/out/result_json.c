/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The JSON object of 'signorini solve --json' (doc/design.md, "Output"),
 * with the run's per-iteration history when the program kept one. */
#include "out/out.h"
#include "cx_config.h"

#include <math.h>

#define RJ_MAX_BODIES 1000

int cx_history_add(cx_history *h, const cx_iterate *it)
{
    if (h->n == h->cap) {
        int ncap = h->cap ? 2 * h->cap : 64;
        void *grown = cx_realloc(h->rows, (size_t)ncap * sizeof *h->rows);
        if (!grown)
            return CX_ENOMEM;
        h->rows = grown;
        h->cap = ncap;
    }
    cx_history_row *row = &h->rows[h->n++];
    row->iter = it->iter;
    row->kkt = it->kkt;
    row->own = it->own;
    row->ncontact = it->ncontact + it->nstick + it->nslip;
    row->nstick = it->nstick;
    row->nslip = it->nslip;
    row->nchanged = it->nchanged;
    row->inner = it->inner;
    row->factorizations = it->counters.factorizations;
    row->solves = it->counters.solves;
    row->matvecs = it->counters.matvecs;
    row->time = it->time;
    return CX_OK;
}

void cx_history_clear(cx_history *h)
{
    cx_free(h->rows);
    h->rows = NULL;
    h->n = h->cap = 0;
}

void cx_history_write_json(cx_json *j, const cx_history *h)
{
    cx_json_array(j, "history");
    for (int k = 0; k < h->n; k++) {
        const cx_history_row *row = &h->rows[k];
        cx_json_object(j, NULL);
        cx_json_int(j, "iter", row->iter);
        cx_json_num(j, "kkt", row->kkt);   /* null when not finite */
        cx_json_num(j, "own", row->own);
        cx_json_int(j, "contact", row->ncontact);
        cx_json_int(j, "stick", row->nstick);
        cx_json_int(j, "slip", row->nslip);
        cx_json_int(j, "changed", row->nchanged);
        cx_json_int(j, "inner", row->inner);
        cx_json_int(j, "factorizations", row->factorizations);
        cx_json_int(j, "solves", row->solves);
        cx_json_int(j, "matvecs", row->matvecs);
        cx_json_num(j, "time", row->time);
        cx_json_end_object(j);
    }
    cx_json_end_array(j);
}

int cx_result_write_json(const cx_result *r, FILE *out)
{
    return cx_result_write_json_history(r, NULL, out);
}

int cx_result_write_json_history(const cx_result *r, const cx_history *h, FILE *out)
{
    const cx_run_record *run = &r->run;
    cx_json j;
    cx_json_init(&j, out);
    cx_json_object(&j, NULL);
    cx_json_str(&j, "scene", run->scene);
    cx_json_int(&j, "level", run->level);
    cx_json_str(&j, "method", run->method);
    cx_json_bool(&j, "method_auto", run->method_auto);
    cx_json_str(&j, "friction", cx_friction_name(run->friction));
    if (run->friction == CX_FRICTION_TRESCA)
        cx_json_num(&j, "slip_bound", run->slip_bound);
    if (run->friction == CX_FRICTION_COULOMB)
        cx_json_num(&j, "F", run->F);
    cx_json_int(&j, "dim", r->dim);
    cx_json_int(&j, "dofs", r->n);
    cx_json_int(&j, "contact_points", r->m);
    cx_json_int(&j, "clamped_points", r->contact.nclamped);   /* on the contact boundary, held by a support */
    cx_json_int(&j, "iterations", run->iterations);
    cx_json_bool(&j, "converged", run->converged);
    cx_json_str(&j, "reason", cx_reason_id(run->reason));
    char outcome[CX_DIAG_LEN + 160];
    cx_json_str(&j, "reason_text", cx_reason_format(run->reason, run->iterations, run->kkt, run->tol,
                                                    run->message, outcome, sizeof outcome));
    if (run->message[0])
        cx_json_str(&j, "message", run->message);
    cx_json_num(&j, "kkt_error", run->kkt);
    cx_json_object(&j, "kkt_parts");
    cx_json_num(&j, "equilibrium", run->kkt_parts.equilibrium);
    cx_json_num(&j, "contact", run->kkt_parts.contact);
    cx_json_num(&j, "friction", run->kkt_parts.friction);
    cx_json_end_object(&j);
    cx_json_num(&j, "own_criterion", run->own);
    cx_json_num(&j, "tol", run->tol);
    cx_json_object(&j, "time");
    cx_json_num(&j, "assemble", run->time.assemble);
    cx_json_num(&j, "setup", run->time.setup);
    cx_json_num(&j, "solve", run->time.solve);
    cx_json_num(&j, "total", run->time.total);
    if (run->has_baseline)
        cx_json_num(&j, "baseline", run->time.baseline);   /* the name bench uses */
    cx_json_end_object(&j);
    cx_json_object(&j, "counts");
    cx_json_int(&j, "factorizations", run->counters.factorizations);
    cx_json_int(&j, "dense_factorizations", run->counters.dense_factorizations);
    cx_json_int(&j, "solves", run->counters.solves);
    cx_json_int(&j, "matvecs", run->counters.matvecs);
    cx_json_int(&j, "dual_products", run->counters.dual_products);
    cx_json_int(&j, "inner_iterations", run->inner_total);
    cx_json_end_object(&j);
    cx_json_int(&j, "active", run->ncontact + run->nstick + run->nslip);
    cx_json_int(&j, "stick", run->nstick);
    cx_json_int(&j, "slip", run->nslip);
    cx_json_int(&j, "free", run->nfree);
    cx_json_object(&j, "force");
    cx_json_vec(&j, "applied", r->f_applied, r->dim);
    cx_json_vec(&j, "contact", r->f_contact, r->dim);
    if (r->nbodies > 1) {
        /* several bodies: "contact" is the rigid obstacles' force on them all;
         * each body's own up to RJ_MAX_BODIES bodies (a fine masonry wall has
         * tens of thousands: the totals only) */
        cx_json_vec(&j, "points", r->f_points, r->dim);
        cx_json_int(&j, "bodies", r->nbodies);
        cx_json_int(&j, "bodies_on_obstacle", r->nbodies_obstacle);
        if (r->nbodies <= RJ_MAX_BODIES) {
            cx_json_array(&j, "contact_bodies");
            for (int b = 0; b < r->nbodies; b++)
                cx_json_vec(&j, NULL, r->f_contact_body + (size_t)r->dim * b, r->dim);
            cx_json_end_array(&j);
        }
    }
    cx_json_end_object(&j);
    cx_json_object(&j, "params");
    const cx_param_values *pv = &run->params;
    for (int k = 0; k < pv->n; k++) {
        char buf[64];
        const cx_param *q = &pv->table[k];
        if (q->type == CX_PARAM_REAL && !isnan(pv->num[k]))
            cx_json_num(&j, q->key, pv->num[k]);
        else if (q->type == CX_PARAM_INT)
            cx_json_int(&j, q->key, (long)pv->num[k]);
        else if (q->type == CX_PARAM_BOOL)
            cx_json_bool(&j, q->key, pv->num[k] != 0);
        else {
            cx_param_format(pv, k, buf, sizeof buf);
            cx_json_str(&j, q->key, buf);
        }
    }
    cx_json_end_object(&j);
    if (run->has_pressure_error) {
        cx_json_object(&j, "pressure_error_l2");
        cx_json_num(&j, "abs", run->pressure_error_abs);
        cx_json_num(&j, "rel", run->pressure_error_rel);
        cx_json_end_object(&j);
        cx_json_object(&j, "contact_halfwidth");
        cx_json_num(&j, "computed", run->halfwidth);
        cx_json_num(&j, "hertz", run->hertz_halfwidth);
        cx_json_end_object(&j);
    }
    if (h)
        cx_history_write_json(&j, h);
    cx_json_str(&j, "version", CX_VERSION);
    cx_json_end_object(&j);
    return ferror(out) ? CX_EIO : CX_OK;
}
