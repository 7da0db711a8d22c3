/* SPDX-License-Identifier: GPL-3.0-or-later */
/* libFuzzer harness for the scene reader (cx_scene_parse: the bytes of a
 * scene file in memory, checked line by line, then inih and the key
 * tables). Besides the sanitizers' findings, it aborts when the reader
 * breaks its contract: a failure must leave one printable line that names
 * the file; a success must leave a scene whose numbers are finite and
 * within the loader's ranges. Built by tests/fuzz/run.sh with clang
 * -fsanitize=fuzzer,address,undefined; without libFuzzer, replay.c runs it
 * over the seed corpus as a unit test. */
#include "scene/scene.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void fz_fail(const char *what, const char *msg)
{
    fprintf(stderr, "fuzz_scene: %s: \"%s\"\n", what, msg);
    abort();
}

static void fz_reals(const double *x, int n, double big)
{
    for (int k = 0; k < n; k++)
        if (!isfinite(x[k]) || fabs(x[k]) > big)
            fz_fail("a value out of the loader's range", "");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cx_scene s;
    cx_diag d;
    cx_diag_clear(&d);
    int st = cx_scene_parse(&s, "fuzz.ini", (const char *)data, size, &d);
    if (st != CX_OK) {
        if (strncmp(d.msg, "fuzz.ini:", 9) != 0)
            fz_fail("message without the file", d.msg);
        for (const unsigned char *c = (const unsigned char *)d.msg; *c; c++)
            if (*c < 0x20 || *c == 0x7f)
                fz_fail("unprintable message", d.msg);
        if (st != CX_EINVAL && st != CX_ENOMEM)
            fz_fail("unexpected status", d.msg);
        return 0;
    }
    if (s.dim != 2 && s.dim != 3)
        fz_fail("dim", s.id);
    fz_reals(s.lo, 3, 1e30);
    fz_reals(s.hi, 3, 1e30);
    fz_reals(&s.mat.E, 1, 1e30);
    fz_reals(s.body_force, 3, 1e30);
    fz_reals(s.obstacle.point, 3, 1e30);
    fz_reals(s.obstacle.normal, 3, 1.000001);
    fz_reals(&s.slip_bound, 1, 1e30);
    for (int k = 0; k < s.ntractions; k++) {
        fz_reals(s.tractions[k].t.t0, 3, 1e30);
        fz_reals(s.tractions[k].t.G, 9, 1e30);
    }
    if (s.mat.E < 1e-30 || !(s.mat.nu > -1 && s.mat.nu < 0.5))
        fz_fail("material out of range", s.id);
    int cells[3];
    cx_scene_cells(&s, s.level, cells);
    if (cells[0] < 1 || cells[1] < 1 || cells[2] < 1)
        fz_fail("cells", s.id);
    return 0;
}
