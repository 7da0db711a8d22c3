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
 * UInt8) taken from data (the matching C type). */
static int vtu_array(vtu_out *o, const char *type, const char *name, int ncomp, const void *data,
                     size_t n)
{
    fprintf(o->f, "        <DataArray type=\"%s\"", type);
    if (name)
        fprintf(o->f, " Name=\"%s\"", name);
    if (ncomp > 1)
        fprintf(o->f, " NumberOfComponents=\"%d\"", ncomp);
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
    int rc = CX_ENOMEM;
    if (!x3 || !u3 || !pr || !stv || !status || !body || !conn || !off || !types)
        goto done;
    cx_result_nodal_pressure(r, pr);
    cx_result_nodal_status(r, stv);
    for (int i = 0; i < nn; i++) {
        for (int k = 0; k < dim; k++) {
            x3[3 * i + k] = m->x[dim * i + k];
            u3[3 * i + k] = r->u[dim * i + k];
        }
        status[i] = (int32_t)stv[i];
    }
    for (size_t i = 0; i < nc; i++)
        conn[i] = m->conn[i];
    for (int e = 0; e < ne; e++) {
        off[e] = (int64_t)m->npe * (e + 1);
        types[e] = (uint8_t)vtu_celltype(m->etype);
        body[e] = m->body ? m->body[e] : 0;
    }
    FILE *f = o->f;
    uint16_t one = 1;
    fprintf(f, "<?xml version=\"1.0\"?>\n");
    fprintf(f, "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"%s\" header_type=\"UInt64\">\n",
            *(const unsigned char *)&one ? "LittleEndian" : "BigEndian");
    fprintf(f, "  <!-- signorini: scene %s, level %d, method %s, kkt error %.6e -->\n",
            r->run.scene, r->run.level, r->run.method, r->run.kkt);
    fprintf(f, "  <UnstructuredGrid>\n");
    fprintf(f, "    <Piece NumberOfPoints=\"%d\" NumberOfCells=\"%d\">\n", nn, ne);
    fprintf(f, "      <PointData Vectors=\"displacement\" Scalars=\"von_mises\">\n");
    if ((rc = vtu_array(o, "Float64", "displacement", 3, u3, 3 * (size_t)nn)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Float64", "stress", ns, sig, (size_t)ns * nn)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Float64", "von_mises", 1, vm, (size_t)nn)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Float64", "contact_pressure", 1, pr, (size_t)nn)) != CX_OK)
        goto done;
    if ((rc = vtu_array(o, "Int32", "contact_status", 1, status, (size_t)nn)) != CX_OK)
        goto done;
    fprintf(f, "      </PointData>\n      <CellData Scalars=\"body\">\n");
    if ((rc = vtu_array(o, "Int32", "body", 1, body, (size_t)ne)) != CX_OK)
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
