/* SPDX-License-Identifier: GPL-3.0-or-later */
/* VTK XML UnstructuredGrid (.vtu) output for ParaView: ASCII, or binary
 * data as base64 with a UInt64 byte-count header per array (uncompressed).
 * Written from a cx_result through out/outfile.h (no GL needed). */
#include "out/out.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

typedef struct vtu_out {
    FILE *f;
    int ascii;
} vtu_out;

static void vtu_base64(FILE *f, const unsigned char *b, size_t n)
{
    static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)b[i] << 16;
        if (i + 1 < n)
            v |= (unsigned)b[i + 1] << 8;
        if (i + 2 < n)
            v |= b[i + 2];
        char q[4] = {tab[(v >> 18) & 63], tab[(v >> 12) & 63], i + 1 < n ? tab[(v >> 6) & 63] : '=',
                     i + 2 < n ? tab[v & 63] : '='};
        fwrite(q, 1, 4, f);
    }
}

/* One DataArray of n values of the given VTK type (Float64, Int64, Int32,
 * UInt8) taken from data (the matching C type); cnames (NULL: none) names
 * the ncomp components, which ParaView shows instead of 0, 1, 2... */
static int vtu_array_named(vtu_out *o, const char *type, const char *name, int ncomp,
                           const char *const *cnames, const void *data, size_t n)
{
    fprintf(o->f, "        <DataArray type=\"%s\"", type);
    if (name)
        fprintf(o->f, " Name=\"%s\"", name);
    if (ncomp > 1)
        fprintf(o->f, " NumberOfComponents=\"%d\"", ncomp);
    for (int k = 0; cnames && k < ncomp; k++)
        fprintf(o->f, " ComponentName%d=\"%s\"", k, cnames[k]);
    fprintf(o->f, " format=\"%s\">\n", o->ascii ? "ascii" : "binary");
    size_t size = strcmp(type, "Float64") == 0 || strcmp(type, "Int64") == 0 ? 8
                  : strcmp(type, "Int32") == 0 ? 4 : 1;
    if (o->ascii) {
        for (size_t i = 0; i < n; i++) {
            const char *sep = (i + 1) % 9 == 0 || i + 1 == n ? "\n" : " ";
            if (size == 8 && type[0] == 'F')
                fprintf(o->f, "%.17g%s", ((const double *)data)[i], sep);
            else if (size == 8)
                fprintf(o->f, "%lld%s", (long long)((const int64_t *)data)[i], sep);
            else if (size == 4)
                fprintf(o->f, "%d%s", (int)((const int32_t *)data)[i], sep);
            else
                fprintf(o->f, "%u%s", (unsigned)((const uint8_t *)data)[i], sep);
        }
    } else {
        size_t bytes = n * size;
        unsigned char *buf = cx_malloc(8 + bytes);
        if (!buf)
            return CX_ENOMEM;
        uint64_t hdr = bytes;
        memcpy(buf, &hdr, 8);
        if (bytes)
            memcpy(buf + 8, data, bytes);
        vtu_base64(o->f, buf, 8 + bytes);
        fputc('\n', o->f);
        cx_free(buf);
    }
    fprintf(o->f, "        </DataArray>\n");
    return CX_OK;
}

static int vtu_array(vtu_out *o, const char *type, const char *name, int ncomp, const void *data,
                     size_t n)
{
    return vtu_array_named(o, type, name, ncomp, NULL, data, n);
}

/* A FieldData string (one tuple), always ASCII: VTK's XML form of a string
 * is its character codes, each string ended by a 0. Characters XML or the
 * reader would trip on are not expected (ids, numbers, messages). */
static void vtu_field_string(vtu_out *o, const char *name, const char *str)
{
    fprintf(o->f, "      <DataArray type=\"String\" Name=\"%s\" NumberOfTuples=\"1\" format=\"ascii\">\n        ",
            name);
    for (const unsigned char *c = (const unsigned char *)str; *c; c++)
        fprintf(o->f, "%u ", *c);
    fprintf(o->f, "0\n      </DataArray>\n");
}

static void vtu_field_double(vtu_out *o, const char *name, double v)
{
    fprintf(o->f, "      <DataArray type=\"Float64\" Name=\"%s\" NumberOfTuples=\"1\" format=\"ascii\">%.17g</DataArray>\n",
            name, v);
}

static void vtu_field_int(vtu_out *o, const char *name, long v)
{
    fprintf(o->f, "      <DataArray type=\"Int64\" Name=\"%s\" NumberOfTuples=\"1\" format=\"ascii\">%ld</DataArray>\n",
            name, v);
}

/* What contact_status holds at a node (the README's VTU paragraph says the same). */
static const char vtu_status_codes[] =
    "-1 no contact point at the node; 0 free (open gap); 1 in contact (frictionless); "
    "2 stick; 3 slip (2D: lT along +t; 3D: any slip); 4 slip (2D: lT along -t). "
    "A node holding several contact points (multibody joints) shows the largest code; "
    "contact_points counts them.";

/* The run record as FieldData: the numbers ParaView's Information panel
 * shows and a script can read (the XML comment is for a human with less). */
static void vtu_field_data(vtu_out *o, const cx_result *r)
{
    const cx_run_record *run = &r->run;
    char args[512];
    fprintf(o->f, "    <FieldData>\n");
    vtu_field_string(o, "scene", run->scene);
    vtu_field_int(o, "level", run->level);
    vtu_field_string(o, "method", run->method);
    vtu_field_string(o, "params", run->params_text);
    vtu_field_string(o, "friction", cx_friction_name(run->friction));
    vtu_field_double(o, "F", run->F);
    vtu_field_double(o, "slip_bound", run->slip_bound);
    vtu_field_double(o, "tol", run->tol);
    vtu_field_int(o, "iterations", run->iterations);
    vtu_field_int(o, "converged", run->converged);
    vtu_field_int(o, "reason_code", run->reason);
    vtu_field_string(o, "reason", run->method[0] ? cx_reason_id(run->reason) : "");
    vtu_field_double(o, "kkt", run->kkt);
    vtu_field_string(o, "solve_args", cx_run_record_solve_args(run, args, sizeof args));
    vtu_field_string(o, "unit_length", run->unit_length);
    vtu_field_string(o, "unit_stress", run->unit_stress);
    vtu_field_string(o, "contact_status_codes", vtu_status_codes);
    fprintf(o->f, "    </FieldData>\n");
}

static int vtu_celltype(cx_elem_type t)
{
    switch (t) {
    case CX_EL_TRI3: return 5;    /* VTK_TRIANGLE */
    case CX_EL_TRI6: return 22;   /* VTK_QUADRATIC_TRIANGLE: vertices, then mid-edges 01 12 20 */
    case CX_EL_QUAD4: return 9;   /* VTK_QUAD */
    case CX_EL_HEX8: return 12;   /* VTK_HEXAHEDRON: bottom face, then top */
    case CX_EL_TET4: return 10;   /* VTK_TETRA */
    }
    return 0;
}

static int vtu_body(vtu_out *o, cx_result *r, cx_diag *d)
{
    const cx_mesh *m = r->mesh;
    int dim = m->dim, nn = m->nnodes, ne = m->nelems, ns = cx_fem_nstress(dim);
    size_t nc = (size_t)m->npe * ne;
    const double *sig = NULL, *vm = NULL;
    CX_TRY(cx_result_stress(r, &sig, &vm, d));
    double *x3 = CX_NEW(double, 3 * (size_t)nn + 1), *u3 = CX_NEW(double, 3 * (size_t)nn + 1);
    double *pr = cx_malloc(sizeof(double) * (size_t)nn + 1), *stv = cx_malloc(sizeof(double) * (size_t)nn + 1);
    int32_t *status = cx_malloc(sizeof(int32_t) * (size_t)nn + 1), *body = cx_malloc(sizeof(int32_t) * (size_t)ne + 1);
    int64_t *conn = cx_malloc(sizeof(int64_t) * nc + 1), *off = cx_malloc(sizeof(int64_t) * (size_t)ne + 1);
    uint8_t *types = cx_malloc((size_t)ne + 1);
    /* the stress as VTK's symmetric tensor (XX YY ZZ XY YZ XZ), 2D included */
    double *s6 = CX_NEW(double, 6 * (size_t)nn + 1);
    /* per node, summed over the contact points at it: weight, the forces
     * on the body (normal, tangential), the slip; traction = force / weight */
    double *cw = CX_NEW(double, (size_t)nn + 1), *tn = CX_NEW(double, 3 * (size_t)nn + 1);
    double *tt = CX_NEW(double, 3 * (size_t)nn + 1), *sl = CX_NEW(double, 3 * (size_t)nn + 1);
    int32_t *npts = CX_NEW(int32_t, (size_t)nn + 1);
    /* per cell: its material id and that material's E and nu, so that a
     * body split between materials shows its regions */
    int32_t *matc = cx_malloc(sizeof(int32_t) * (size_t)ne + 1);
    double *Ec = cx_malloc(sizeof(double) * (size_t)ne + 1), *nuc = cx_malloc(sizeof(double) * (size_t)ne + 1);
    int rc = CX_ENOMEM;
    if (!x3 || !u3 || !pr || !stv || !status || !body || !conn || !off || !types || !s6 || !cw ||
        !tn || !tt || !sl || !npts || !matc || !Ec || !nuc)
        goto done;
    /* the material of a node: that of an element using it (as
     * cx_result_stress takes it for von Mises); npts is borrowed, reset below */
    for (int e = 0; e < ne; e++)
        for (int a = 0; a < m->npe; a++)
            npts[m->conn[m->npe * e + a]] = cx_mesh_elem_mat(m, e);
    for (int i = 0; i < nn; i++) {
        const double *v = sig + (size_t)ns * i;
        double *t = s6 + 6 * (size_t)i;
        if (dim == 3) {   /* Voigt xx yy zz yz xz xy */
            t[0] = v[0], t[1] = v[1], t[2] = v[2], t[3] = v[5], t[4] = v[3], t[5] = v[4];
        } else {          /* xx yy xy; szz of plane strain as cx_fem_von_mises has it */
            const cx_material *mat = &r->mats[npts[i]];
            t[0] = v[0], t[1] = v[1], t[3] = v[2], t[4] = t[5] = 0;
            t[2] = mat->model == CX_PLANE_STRAIN ? mat->nu * (v[0] + v[1]) : 0;
        }
    }
    memset(npts, 0, sizeof(int32_t) * (size_t)nn);
    const cx_contact_set *cs = &r->contact;
    int dt = dim - 1;
    for (int i = 0; i < cs->m; i++) {
        int k = cs->node[i], st = r->status[i];
        npts[k]++;
        cw[k] += cs->weight[i];
        status[k] = npts[k] == 1 || st > status[k] ? st : status[k];
        for (int c = 0; c < dim; c++) {
            tn[3 * k + c] -= r->lN[i] * cs->normal[dim * i + c];
            for (int q = 0; q < dt; q++) {
                const double *tq = cs->tangent + dim * (dt * i + q);
                if (r->run.friction != CX_FRICTION_NONE)
                    tt[3 * k + c] -= r->lT[dt * i + q] * tq[c];
                if (st == CX_PT_SLIP_POS || st == CX_PT_SLIP_NEG)
                    sl[3 * k + c] += r->tu[dt * i + q] * tq[c];
            }
        }
    }
    for (int k = 0; k < nn; k++) {
        for (int c = 0; c < 3; c++) {
            tn[3 * k + c] = cw[k] > 0 ? tn[3 * k + c] / cw[k] : 0;
            tt[3 * k + c] = cw[k] > 0 ? tt[3 * k + c] / cw[k] : 0;
        }
    }
    cx_result_nodal_pressure(r, pr);
    cx_result_nodal_status(r, stv);
    for (int i = 0; i < cs->m; i++) {   /* a shared node: the points' total over their weight */
        int k = cs->node[i];
        pr[k] = 0;
    }
    for (int i = 0; i < cs->m; i++) {
        int k = cs->node[i];
        pr[k] += cw[k] > 0 ? r->lN[i] / cw[k] : 0;
    }
    for (int i = 0; i < nn; i++) {
        for (int k = 0; k < dim; k++) {
            x3[3 * i + k] = m->x[dim * i + k];
            u3[3 * i + k] = r->u[dim * i + k];
        }
        if (npts[i] == 0)
            status[i] = (int32_t)stv[i];
    }
    for (size_t i = 0; i < nc; i++)
        conn[i] = m->conn[i];
    for (int e = 0; e < ne; e++) {
        off[e] = (int64_t)m->npe * (e + 1);
        types[e] = (uint8_t)vtu_celltype(m->etype);
        body[e] = m->body ? m->body[e] : 0;
        matc[e] = cx_mesh_elem_mat(m, e);
        Ec[e] = r->mats[matc[e]].E;
        nuc[e] = r->mats[matc[e]].nu;
    }
    FILE *f = o->f;
    uint16_t one = 1;
    fprintf(f, "<?xml version=\"1.0\"?>\n");
    fprintf(f, "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"%s\" header_type=\"UInt64\">\n",
            *(const unsigned char *)&one ? "LittleEndian" : "BigEndian");
    fprintf(f, "  <!-- signorini: scene %s, level %d, method %s, kkt error %.6e -->\n",
            r->run.scene, r->run.level, r->run.method, r->run.kkt);
    fprintf(f, "  <UnstructuredGrid>\n");
    vtu_field_data(o, r);
    fprintf(f, "    <Piece NumberOfPoints=\"%d\" NumberOfCells=\"%d\">\n", nn, ne);
    fprintf(f, "      <PointData Vectors=\"displacement\" Scalars=\"von_mises\">\n");
    if ((rc = vtu_array(o, "Float64", "displacement", 3, u3, 3 * (size_t)nn)) != CX_OK)
        goto done;
    static const char *const tensor_names[6] = {"XX", "YY", "ZZ", "XY", "YZ", "XZ"};
    if ((rc = vtu_array_named(o, "Float64", "stress", 6, tensor_names, s6, 6 * (size_t)nn)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Float64", "von_mises", 1, vm, (size_t)nn)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Float64", "contact_pressure", 1, pr, (size_t)nn)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Int32", "contact_status", 1, status, (size_t)nn)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Int32", "contact_points", 1, npts, (size_t)nn)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Float64", "contact_weight", 1, cw, (size_t)nn)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Float64", "contact_traction_normal", 3, tn, 3 * (size_t)nn)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Float64", "contact_traction_tangential", 3, tt, 3 * (size_t)nn)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Float64", "contact_slip", 3, sl, 3 * (size_t)nn)) != CX_OK)
        goto done;
    fprintf(f, "      </PointData>\n      <CellData Scalars=\"body\">\n");
    if ((rc = vtu_array(o, "Int32", "body", 1, body, (size_t)ne)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Int32", "material", 1, matc, (size_t)ne)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Float64", "young_modulus", 1, Ec, (size_t)ne)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Float64", "poisson_ratio", 1, nuc, (size_t)ne)) != CX_OK)
        goto done;
    fprintf(f, "      </CellData>\n      <Points>\n");
    if ((rc = vtu_array(o, "Float64", NULL, 3, x3, 3 * (size_t)nn)) != CX_OK)
        goto done;
    fprintf(f, "      </Points>\n      <Cells>\n");
    if ((rc = vtu_array(o, "Int64", "connectivity", 1, conn, nc)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Int64", "offsets", 1, off, (size_t)ne)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "UInt8", "types", 1, types, (size_t)ne)) != CX_OK)
        goto done;
    fprintf(f, "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    rc = CX_OK;
done:
    cx_free(x3);
    cx_free(u3);
    cx_free(pr);
    cx_free(stv);
    cx_free(status);
    cx_free(body);
    cx_free(conn);
    cx_free(off);
    cx_free(types);
    cx_free(s6);
    cx_free(cw);
    cx_free(tn);
    cx_free(tt);
    cx_free(sl);
    cx_free(npts);
    cx_free(matc);
    cx_free(Ec);
    cx_free(nuc);
    return rc == CX_OK ? CX_OK : cx_diag_set(d, rc, "%s", cx_status_str(rc));
}

int cx_vtu_write(cx_result *r, const char *path, int ascii, cx_diag *d)
{
    /* the stresses first: an error there leaves no file at all */
    CX_TRY(cx_result_stress(r, NULL, NULL, d));
    cx_outfile out;
    CX_TRY(cx_outfile_open(&out, path, d));
    vtu_out o = {out.f, ascii};
    int rc = vtu_body(&o, r, d);
    int rc2 = cx_outfile_close(&out, rc == CX_OK, d);
    if (rc != CX_OK) {
        cx_diag_prefix(d, "%s", path);
        return rc;
    }
    return rc2;
}
