/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The one list of methods. Adding a method: one file in solve/ with its
 * const cx_method descriptor, one line here. 'signorini list', --method,
 * the explorer and the conformance tests all read this table. */
#include "solve/solve.h"

#include <string.h>

extern const cx_method cx_method_ssn_tresca;
extern const cx_method cx_method_mprgp;
extern const cx_method cx_method_ssn_tresca_dual;
extern const cx_method cx_method_ssn_tresca_glob;
extern const cx_method cx_method_ssn_coulomb;
extern const cx_method cx_method_ubr_c;
extern const cx_method cx_method_ubr_tf;
extern const cx_method cx_method_cf_fp;
extern const cx_method cx_method_ssn_c;
extern const cx_method cx_method_ssstar;
extern const cx_method cx_method_pdas;
extern const cx_method cx_method_pdpc;
extern const cx_method cx_method_lssnn;
extern const cx_method cx_method_psor;
extern const cx_method cx_method_graves;

static const cx_method *const cx_methods[] = {
    &cx_method_ssn_tresca,
    &cx_method_mprgp,
    &cx_method_ssn_tresca_dual,
    &cx_method_ssn_tresca_glob,
    &cx_method_ssn_coulomb,
    &cx_method_ubr_c,
    &cx_method_ubr_tf,
    &cx_method_cf_fp,
    &cx_method_ssn_c,
    &cx_method_ssstar,
    &cx_method_pdas,
    &cx_method_pdpc,
    &cx_method_lssnn,
    &cx_method_psor,
    &cx_method_graves,
    NULL
};

int cx_method_count(void)
{
    return (int)(sizeof cx_methods / sizeof cx_methods[0]) - 1;
}

const cx_method *cx_method_at(int i)
{
    return i >= 0 && i < cx_method_count() ? cx_methods[i] : NULL;
}

const cx_method *cx_method_find(const char *id)
{
    for (int i = 0; cx_methods[i]; i++)
        if (strcmp(cx_methods[i]->id, id) == 0)
            return cx_methods[i];
    return NULL;
}

int cx_method_check(const cx_method *m, const cx_problem *p, cx_friction law, cx_diag *d)
{
    static const unsigned law_flag[] = {CX_FRICTIONLESS, CX_TRESCA, CX_COULOMB};
    static const char *const law_text[] = {"frictionless contact", "Tresca friction", "Coulomb friction"};
    if (!(m->supports & law_flag[law]))
        return cx_diag_set(d, CX_EUNSUPPORTED, "method '%s' does not support %s",
                           m->id, law_text[law]);
    if (!(m->supports & (p->dim == 2 ? CX_2D : CX_3D)))
        return cx_diag_set(d, CX_EUNSUPPORTED, "method '%s' does not support %dD problems", m->id, p->dim);
    if (p->mesh && p->mesh->nbodies > 1 && !(m->supports & CX_MULTIBODY))
        return cx_diag_set(d, CX_EUNSUPPORTED, "method '%s' does not support several bodies", m->id);
    return CX_OK;
}
