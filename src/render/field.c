/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Field names and nodal values. */
#include "render/render.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const struct {
    const char *name, *label, *symbol;
    int dims;        /* bit 2: in 2D, bit 3: in 3D */
    int stress;      /* Voigt index + 1 of the component, or -1 for von Mises */
    int disp;        /* component + 1, or -1 for |u| */
    int is_signed;
} field_table[CX_FIELD_COUNT] = {
    [CX_FIELD_VON_MISES] = {"von-mises", "von Mises stress", "σ_vM", 12, -1, 0, 0},
    [CX_FIELD_SXX] = {"sxx", "stress σxx", "σ_xx", 12, 0, 0, 1},
    [CX_FIELD_SYY] = {"syy", "stress σyy", "σ_yy", 12, 0, 0, 1},
    [CX_FIELD_SZZ] = {"szz", "stress σzz", "σ_zz", 8, 0, 0, 1},
    [CX_FIELD_SYZ] = {"syz", "stress σyz", "σ_yz", 8, 0, 0, 1},
    [CX_FIELD_SXZ] = {"sxz", "stress σxz", "σ_xz", 8, 0, 0, 1},
    [CX_FIELD_SXY] = {"sxy", "stress σxy", "σ_xy", 12, 0, 0, 1},
    [CX_FIELD_UMAG] = {"u", "displacement |u|", "|u|", 12, 0, -1, 0},
    [CX_FIELD_UX] = {"ux", "displacement ux", "u_x", 12, 0, 1, 1},
    [CX_FIELD_UY] = {"uy", "displacement uy", "u_y", 12, 0, 2, 1},
    [CX_FIELD_UZ] = {"uz", "displacement uz", "u_z", 8, 0, 3, 1},
    [CX_FIELD_PRESSURE] = {"pressure", "contact pressure", "p", 12, 0, 0, 0},
    [CX_FIELD_STATUS] = {"status", "contact status", "", 12, 0, 0, 0},
};

const char *cx_field_name(int f)
{
    return f >= 0 && f < CX_FIELD_COUNT ? field_table[f].name : "?";
}

const char *cx_field_label(int f)
{
    return f >= 0 && f < CX_FIELD_COUNT ? field_table[f].label : "?";
}

int cx_field_from_name(const char *name)
{
    for (int f = 0; f < CX_FIELD_COUNT; f++)
        if (strcmp(name, field_table[f].name) == 0)
            return f;
    return -1;
}

int cx_field_is_stress(int f)
{
    return f >= CX_FIELD_VON_MISES && f <= CX_FIELD_SXY;
}

int cx_field_is_signed(int f)
{
    return f >= 0 && f < CX_FIELD_COUNT && field_table[f].is_signed;
}

int cx_field_check(int f, int dim, cx_diag *d)
{
    if (f < 0 || f >= CX_FIELD_COUNT)
        return cx_diag_set(d, CX_EINVAL, "--field: unknown field");
    if (!(field_table[f].dims & (1 << dim)))
        return cx_diag_set(d, CX_EINVAL, "--field %s: only in 3D", field_table[f].name);
    return CX_OK;
}

/* Voigt index of a stress field: 2D (xx, yy, xy), 3D (xx, yy, zz, yz, xz, xy). */
static int field_voigt(int f, int dim)
{
    switch (f) {
    case CX_FIELD_SXX: return 0;
    case CX_FIELD_SYY: return 1;
    case CX_FIELD_SZZ: return 2;
    case CX_FIELD_SYZ: return 3;
    case CX_FIELD_SXZ: return 4;
    case CX_FIELD_SXY: return dim == 2 ? 2 : 5;
    default: return -1;
    }
}

int cx_field_nodal(cx_result *r, int f, double *val, cx_diag *d)
{
    const cx_mesh *m = r->mesh;
    const double *uall = r->u;
    int dim = m->dim, nn = m->nnodes;
    if (cx_field_is_stress(f)) {
        int ns = cx_fem_nstress(dim), c = field_voigt(f, dim);
        const double *sig, *vm;
        CX_TRY(cx_result_stress(r, &sig, &vm, d));
        for (int k = 0; k < nn; k++)
            val[k] = c >= 0 ? sig[(size_t)ns * k + c] : vm[k];
        return CX_OK;
    }
    if (f == CX_FIELD_PRESSURE) {
        cx_result_nodal_pressure(r, val);
        return CX_OK;
    }
    if (f == CX_FIELD_STATUS) {
        cx_result_nodal_status(r, val);
        return CX_OK;
    }
    int c = field_table[f].disp;
    for (int k = 0; k < nn; k++) {
        if (c > 0) {
            val[k] = uall[dim * k + c - 1];
        } else {
            double s = 0;
            for (int j = 0; j < dim; j++)
                s += uall[dim * k + j] * uall[dim * k + j];
            val[k] = sqrt(s);
        }
    }
    return CX_OK;
}

char *cx_quantity_label(const cx_run_record *run, const char *what, int stress, char *buf,
                        size_t len)
{
    const char *unit = stress ? run->unit_stress : run->unit_length;
    if (unit[0])
        snprintf(buf, len, "%s [%s]", what, unit);
    else
        snprintf(buf, len, "%s (units of the scene)", what);
    return buf;
}

char *cx_field_axis_label(const cx_run_record *run, int f, char *buf, size_t len)
{
    if (f < 0 || f >= CX_FIELD_COUNT || f == CX_FIELD_STATUS) {
        snprintf(buf, len, "%s", cx_field_label(f));
        return buf;
    }
    char what[96];
    int disp = f >= CX_FIELD_UMAG && f <= CX_FIELD_UZ;
    /* the quantity's word, then its symbol: "stress σ_xx", not "stress σxx σ_xx" */
    const char *word = f == CX_FIELD_VON_MISES || f == CX_FIELD_PRESSURE ? field_table[f].label
                       : disp ? "displacement" : "stress";
    snprintf(what, sizeof what, "%s %s", word, field_table[f].symbol);
    return cx_quantity_label(run, what, !disp, buf, len);
}
