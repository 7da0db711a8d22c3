/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Damaged FCLIB files read back (scene/problem_fclib.c): libfclib stops
 * the process when an HDF5 call fails, so each file is checked with the
 * HDF5 API first. From an exported hertz problem: a file that is not
 * HDF5, a truncated copy, a dataset deleted (the vector mu, the matrix
 * M's x, the group vectors), a dataset of the wrong length, an impossible
 * nz, a string where fclib reads an int, H's columns not a multiple of
 * spacedim, an HDF5 file without /fclib_global. Each gives CX_EINVAL (or
 * CX_EUNSUPPORTED) with one line naming the file and what is wrong, and
 * this process lives on to check the next; the intact file still reads. */
#include "out/export.h"
#include "scene/problem_file.h"
#include "scene/scene.h"
#include "check.h"

#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char good[512];

static void copy_file(const char *from, const char *to, long keep)
{
    FILE *a = fopen(from, "rb"), *b = fopen(to, "wb");
    CX_CHECK(a && b);
    char buf[4096];
    size_t n;
    long total = 0;
    while (a && b && (n = fread(buf, 1, sizeof buf, a)) > 0) {
        if (keep >= 0 && total + (long)n > keep)
            n = (size_t)(keep - total);
        fwrite(buf, 1, n, b);
        total += (long)n;
        if (keep >= 0 && total >= keep)
            break;
    }
    if (a)
        fclose(a);
    if (b)
        fclose(b);
}

static long file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fclose(f);
    return n;
}

/* Read path: status want, message holding every needle and path, one line. */
static void expect(const char *path, int want, const char *n1, const char *n2)
{
    cx_problem_file pf;
    cx_diag d = {0};
    memset(&pf, 0, sizeof pf);
    int st = cx_problem_read(path, &pf, &d);
    if (st != want || (want && !strstr(d.msg, path)) || (n1 && !strstr(d.msg, n1)) ||
        (n2 && !strstr(d.msg, n2)))
        fprintf(stderr, "%s: status %d (want %d): %s\n", path, st, want, d.msg);
    CX_CHECK(st == want);
    if (want)
        CX_CHECK(strstr(d.msg, path) != NULL);
    CX_CHECK(strchr(d.msg, '\n') == NULL);
    if (n1)
        CX_CHECK(strstr(d.msg, n1) != NULL);
    if (n2)
        CX_CHECK(strstr(d.msg, n2) != NULL);
    if (st == CX_OK)
        cx_problem_file_clear(&pf);
}

/* A copy of the good file, opened for writing (H5Fclose it). */
static hid_t edit(const char *path)
{
    copy_file(good, path, -1);
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    CX_CHECK(f >= 0);
    return f;
}

static void put_ints(hid_t f, const char *name, const int *v, hsize_t n)
{
    H5Ldelete(f, name, H5P_DEFAULT);
    hid_t sp = H5Screate_simple(1, &n, NULL);
    hid_t ds = H5Dcreate2(f, name, H5T_NATIVE_INT, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    CX_CHECK(ds >= 0 && H5Dwrite(ds, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0);
    H5Dclose(ds);
    H5Sclose(sp);
}

static void put_doubles(hid_t f, const char *name, const double *v, hsize_t n)
{
    H5Ldelete(f, name, H5P_DEFAULT);
    hid_t sp = H5Screate_simple(1, &n, NULL);
    hid_t ds = H5Dcreate2(f, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    CX_CHECK(ds >= 0 && H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0);
    H5Dclose(ds);
    H5Sclose(sp);
}

static void put_string(hid_t f, const char *name, const char *text)
{
    H5Ldelete(f, name, H5P_DEFAULT);
    hid_t ty = H5Tcopy(H5T_C_S1);
    H5Tset_size(ty, strlen(text) + 1);
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t ds = H5Dcreate2(f, name, ty, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    CX_CHECK(ds >= 0 && H5Dwrite(ds, ty, H5S_ALL, H5S_ALL, H5P_DEFAULT, text) >= 0);
    H5Dclose(ds);
    H5Sclose(sp);
    H5Tclose(ty);
}

int main(void)
{
    char tmp[] = "/tmp/cx_fclib_bad_XXXXXX";
    if (!mkdtemp(tmp))
        return 1;
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);   /* our edits delete what may not be there */
    cx_diag d;
    cx_scene sc;
    cx_problem *p = NULL;
    cx_friction_state fr;
    cx_session *s = NULL;
    CX_CHECK_OK(cx_scene_open("hertz", &sc, &d));
    CX_CHECK_OK(cx_scene_build(&sc, 4, &p, &fr, &d));
    CX_CHECK_OK(cx_session_create(&s, &p, &d));
    CX_CHECK_OK(cx_session_set_friction(s, &fr, &d));
    snprintf(good, sizeof good, "%s/hertz.hdf5", tmp);
    CX_CHECK_OK(cx_export_fclib(cx_session_problem(s), cx_session_friction(s), good, "hertz", 4, &d));
    int n = cx_session_problem(s)->n, m = cx_session_problem(s)->m;
    cx_session_destroy(&s);
    expect(good, CX_OK, NULL, NULL);

    char path[600];
    snprintf(path, sizeof path, "%s/text.hdf5", tmp);
    FILE *f = fopen(path, "w");
    CX_CHECK(f != NULL);
    if (f) {
        fputs("not an HDF5 file\n", f);
        fclose(f);
    }
    expect(path, CX_EINVAL, "not a problem directory or an HDF5 file", NULL);

    long size = file_size(good);
    CX_CHECK(size > 4096);
    long cuts[3] = {size / 2, size - 100, 1000};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "%s/cut%d.hdf5", tmp, k);
        copy_file(good, path, cuts[k]);
        expect(path, CX_EINVAL, "truncated or damaged", NULL);
    }

    static const char *const gone[3] = {"/fclib_global/vectors/mu", "/fclib_global/M/x",
                                        "/fclib_global/vectors"};
    static const char *const said[3] = {"/fclib_global/vectors/mu is missing",
                                        "/fclib_global/M/x is missing",
                                        "/fclib_global/vectors/f is missing"};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "%s/gone%d.hdf5", tmp, k);
        hid_t h = edit(path);
        CX_CHECK(H5Ldelete(h, gone[k], H5P_DEFAULT) >= 0);
        H5Fclose(h);
        expect(path, CX_EINVAL, said[k], NULL);
    }

    /* f one short: fclib would read it into n doubles, leaving one unset */
    double *v = calloc((size_t)n, sizeof *v);
    snprintf(path, sizeof path, "%s/short.hdf5", tmp);
    hid_t h = edit(path);
    put_doubles(h, "/fclib_global/vectors/f", v, (hsize_t)n - 1);
    H5Fclose(h);
    char want[96];
    snprintf(want, sizeof want, "has %d values, expected %d", n - 1, n);
    expect(path, CX_EINVAL, "/fclib_global/vectors/f", want);
    /* mu one longer: fclib would write past its buffer */
    snprintf(path, sizeof path, "%s/long.hdf5", tmp);
    h = edit(path);
    put_doubles(h, "/fclib_global/vectors/mu", v, (hsize_t)m + 1);
    H5Fclose(h);
    expect(path, CX_EINVAL, "/fclib_global/vectors/mu", "values, expected");
    free(v);

    int bad = -7;
    snprintf(path, sizeof path, "%s/nz.hdf5", tmp);
    h = edit(path);
    put_ints(h, "/fclib_global/M/nz", &bad, 1);
    H5Fclose(h);
    expect(path, CX_EINVAL, "/fclib_global/M", "nz = -7");

    snprintf(path, sizeof path, "%s/string.hdf5", tmp);
    h = edit(path);
    put_string(h, "/fclib_global/H/m", "many");
    H5Fclose(h);
    expect(path, CX_EINVAL, "/fclib_global/H/m", "is not numeric");

    /* spacedim 3 on a 2D problem: H's 2m columns are not a multiple of 3
     * (m odd: hertz at level 4 has 5 contact points) */
    int three = 3;
    snprintf(path, sizeof path, "%s/dim.hdf5", tmp);
    h = edit(path);
    put_ints(h, "/fclib_global/spacedim", &three, 1);
    H5Fclose(h);
    CX_CHECK(m % 3 != 0);
    expect(path, CX_EINVAL, "not a multiple of spacedim 3", NULL);

    snprintf(path, sizeof path, "%s/empty.hdf5", tmp);
    h = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    CX_CHECK(h >= 0);
    H5Fclose(h);
    expect(path, CX_EINVAL, "no FCLIB global problem", NULL);

    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
    if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", tmp);
    return check_finish("problem_fclib_bad");
}
