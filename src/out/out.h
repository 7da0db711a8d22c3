/* SPDX-License-Identifier: GPL-3.0-or-later */
/* out/: the solution snapshot (out/result.h) and every output format that
 * needs no GL — VTU for ParaView, the JSON of 'solve' and 'list', CSV
 * (out/csv.h), the JSON writer (out/json.h) — and the one safe way to
 * write a file (out/outfile.h: temporary + rename, links kept, devices
 * written in place, "-" for standard output). render/ draws from the same
 * cx_result. Nothing here prints; errors are one line in a cx_diag. */
#ifndef CX_OUT_H
#define CX_OUT_H

#include <stdio.h>

#include "out/csv.h"
#include "out/json.h"
#include "out/outfile.h"
#include "out/result.h"

/* Write the mesh (undeformed coordinates) with point data "displacement"
 * (3 components, z = 0 in 2D), "stress" (Voigt: 3 in 2D, 6 in 3D),
 * "von_mises", "contact_pressure", "contact_status" (-1 away from the
 * contact points) and cell data "body", as a VTK XML UnstructuredGrid
 * (ascii = 1: ASCII; 0: base64 binary) through out/outfile.h. CX_EIO,
 * CX_ENOMEM, CX_ENUMERIC (stresses), each with "PATH: reason". */
int cx_vtu_write(cx_result *r, const char *path, int ascii, cx_diag *d);

/* The JSON object of 'signorini solve --json' (doc/design.md, "Output")
 * for r. CX_EIO if a write to out failed. */
int cx_result_write_json(const cx_result *r, FILE *out);

/* The iterations of a run as the observer saw them (the "history" array of
 * 'solve --json'): kkt error, the method's own criterion, the contact
 * counts, inner iterations, the work counters and the time so far. */
typedef struct cx_history_row {
    int iter;
    double kkt, own;             /* own: NaN if the method has none */
    int ncontact, nstick, nslip, nchanged;
    long inner;
    long factorizations, solves, matvecs;
    double time;                 /* seconds of the run so far */
} cx_history_row;
typedef struct cx_history {
    cx_history_row *rows;
    int n, cap;
} cx_history;
/* Append the iterate it (CX_ENOMEM); cx_history_clear frees the rows. A
 * zeroed cx_history is empty. */
int cx_history_add(cx_history *h, const cx_iterate *it);
void cx_history_clear(cx_history *h);
/* The history as the array member "history" of the object j is in (a
 * non-finite kkt or own criterion is null). */
void cx_history_write_json(cx_json *j, const cx_history *h);
/* cx_result_write_json with the history (h may be NULL: none). */
int cx_result_write_json_history(const cx_result *r, const cx_history *h, FILE *out);

/* The JSON of 'signorini list --json': the scenes ids[nids] (each opened
 * for its details; one that cannot be read gets "error") and every
 * registered method with its parameters. CX_EIO if a write failed. */
int cx_list_write_json(char (*ids)[CX_SCENE_NAMELEN], int nids, FILE *out);
/* "frictionless tresca 2d ..." for a method's supports flags. */
void cx_list_supports(unsigned flags, char *buf, size_t len);

#endif
