/* SPDX-License-Identifier: GPL-3.0-or-later */
/* libFuzzer harness for the MatrixMarket reader (cx_mm_read_file: CHOLMOD's
 * reader, then our checks of what it lets through). Besides the
 * sanitizers' findings, it aborts when the reader breaks its contract: a
 * failure must leave one printable line that names the file, with
 * CX_EINVAL or CX_ENOMEM; a success must hold finite values only, a dense
 * array of nrow x ncol, or a CSC matrix with sorted, distinct, in-range
 * rows. Inputs whose header declares more than 10^6 rows, columns or
 * entries are skipped: CHOLMOD would allocate for them before reading a
 * line (a real file that large is read, or fails with CX_ENOMEM). Built by
 * tests/fuzz/run.sh; without libFuzzer, replay.c runs it over the seeds
 * (tests/fuzz/mm) as a unit test. */
#include "linalg/linalg.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void fz_fail(const char *what, const char *msg)
{
    fprintf(stderr, "fuzz_mm: %s: \"%s\"\n", what, msg);
    abort();
}

/* The first line that is not a comment after the banner: its numbers
 * must be small (see above). Non-zero to skip the input. */
static int fz_too_big(const uint8_t *data, size_t size)
{
    char line[256];
    size_t k = 0;
    int lineno = 0;
    while (k < size) {
        size_t e = k;
        while (e < size && data[e] != '\n')
            e++;
        if (lineno++ > 0 && e > k && data[k] != '%') {
            size_t n = e - k < sizeof line - 1 ? e - k : sizeof line - 1;
            memcpy(line, data + k, n);
            line[n] = 0;
            char *p = line;
            for (int f = 0; f < 3; f++) {
                char *q;
                double v = strtod(p, &q);
                if (q == p)
                    break;
                if (!(fabs(v) <= 1e6))
                    return 1;
                p = q;
            }
            return 0;
        }
        k = e + 1;
    }
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0 || fz_too_big(data, size))
        return 0;
    FILE *f = fmemopen((void *)data, size, "r");
    if (!f)
        return 0;
    cx_mm mm;
    cx_diag d;
    cx_diag_clear(&d);
    int st = cx_mm_read_file(f, "fuzz.mtx", &mm, &d);
    fclose(f);
    if (st != CX_OK) {
        if (strncmp(d.msg, "fuzz.mtx:", 9) != 0)
            fz_fail("message without the file", d.msg);
        for (const unsigned char *c = (const unsigned char *)d.msg; *c; c++)
            if (*c < 0x20 || *c == 0x7f)
                fz_fail("unprintable message", d.msg);
        if (st != CX_EINVAL && st != CX_ENOMEM)
            fz_fail("unexpected status", d.msg);
        return 0;
    }
    if (mm.nrow < 0 || mm.ncol < 0)
        fz_fail("negative size", "");
    if (mm.dense) {
        for (size_t k = 0; k < (size_t)mm.nrow * (size_t)mm.ncol; k++)
            if (!isfinite(mm.x[k]))
                fz_fail("a value not finite", "");
    } else {
        const cx_csc *A = &mm.A;
        if (A->nrow != mm.nrow || A->ncol != mm.ncol || A->p[0] != 0)
            fz_fail("sizes", "");
        for (int j = 0; j < A->ncol; j++)
            for (int q = A->p[j]; q < A->p[j + 1]; q++) {
                if (A->i[q] < 0 || A->i[q] >= A->nrow || (q > A->p[j] && A->i[q] <= A->i[q - 1]))
                    fz_fail("rows out of range or order", "");
                if (!isfinite(A->x[q]))
                    fz_fail("a value not finite", "");
            }
    }
    cx_mm_clear(&mm);
    return 0;
}
