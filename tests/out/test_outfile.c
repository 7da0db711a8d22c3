/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The safe-output helper (out/outfile.h): a new file and a replaced one
 * (permissions kept, no temporary left), a failed write leaves nothing, a
 * symbolic link stays a link and its target is written (also a dangling
 * link and a link to a link), a device node is written in place and stays
 * a device, "-" is standard output, a directory is refused, and
 * cx_outfile_abandon_pending removes a temporary being written. And the
 * one CSV writer's quoting. */
#define _GNU_SOURCE   /* mknod, makedev */
#include <dirent.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "out/out.h"

static char dir[] = "/tmp/cx_outfile_XXXXXX";

static const char *in_dir(const char *name)
{
    static char buf[4][512];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
    return buf[k];
}

static int write_text(const char *path, const char *text, cx_diag *d)
{
    cx_outfile o;
    int rc = cx_outfile_open(&o, path, d);
    if (rc != CX_OK)
        return rc;
    fputs(text, o.f);
    return cx_outfile_close(&o, 1, d);
}

static int file_is(const char *path, const char *text)
{
    char buf[256];
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return strcmp(buf, text) == 0;
}

/* Files in dir whose name holds ".tmp". */
static int temporaries(const char *where)
{
    int n = 0;
    DIR *dd = opendir(where);
    struct dirent *e;
    while (dd && (e = readdir(dd)))
        n += strstr(e->d_name, ".tmp") != NULL;
    if (dd)
        closedir(dd);
    return n;
}

static void test_regular(void)
{
    cx_diag d;
    const char *p = in_dir("a.txt");
    CX_CHECK_OK(write_text(p, "one\n", &d));
    CX_CHECK(file_is(p, "one\n"));
    CX_CHECK(chmod(p, 0640) == 0);
    CX_CHECK_OK(write_text(p, "two\n", &d));
    CX_CHECK(file_is(p, "two\n"));
    struct stat st;
    CX_CHECK(stat(p, &st) == 0 && (st.st_mode & 0777) == 0640);
    /* a failed write (ok = 0) leaves the old file and no temporary */
    cx_outfile o;
    CX_CHECK_OK(cx_outfile_open(&o, p, &d));
    fputs("half", o.f);
    CX_CHECK(o.mode == CX_OUTFILE_RENAME && strstr(o.tmp, ".tmp") != NULL);
    CX_CHECK_OK(cx_outfile_close(&o, 0, &d));
    CX_CHECK(file_is(p, "two\n"));
    CX_CHECK(temporaries(dir) == 0);
    /* a missing directory: one line naming the file, nothing created */
    CX_CHECK(write_text(in_dir("no/such/x.txt"), "x", &d) == CX_EIO);
    CX_CHECK(strstr(d.msg, "no/such/x.txt: cannot write") != NULL && !strchr(d.msg, '\n'));
    /* a directory is refused */
    CX_CHECK(write_text(dir, "x", &d) == CX_EIO);
    CX_CHECK(strstr(d.msg, "cannot write") != NULL);
    CX_CHECK(cx_outfile_open(&o, "", &d) == CX_EINVAL);
}

static void test_links(void)
{
    cx_diag d;
    struct stat st;
    CX_CHECK(mkdir(in_dir("sub"), 0700) == 0);
    CX_CHECK_OK(write_text(in_dir("sub/target.vtu"), "old", &d));
    /* relative link, and a link to that link */
    CX_CHECK(symlink("sub/target.vtu", in_dir("link.vtu")) == 0);
    CX_CHECK(symlink("link.vtu", in_dir("link2.vtu")) == 0);
    CX_CHECK_OK(write_text(in_dir("link.vtu"), "via link", &d));
    CX_CHECK(lstat(in_dir("link.vtu"), &st) == 0 && S_ISLNK(st.st_mode));
    CX_CHECK(lstat(in_dir("sub/target.vtu"), &st) == 0 && S_ISREG(st.st_mode));
    CX_CHECK(file_is(in_dir("sub/target.vtu"), "via link"));
    CX_CHECK_OK(write_text(in_dir("link2.vtu"), "via two links", &d));
    CX_CHECK(lstat(in_dir("link2.vtu"), &st) == 0 && S_ISLNK(st.st_mode));
    CX_CHECK(lstat(in_dir("link.vtu"), &st) == 0 && S_ISLNK(st.st_mode));
    CX_CHECK(file_is(in_dir("sub/target.vtu"), "via two links"));
    /* a dangling link: its target is created, the link stays */
    CX_CHECK(symlink("sub/new.vtu", in_dir("dangling.vtu")) == 0);
    CX_CHECK_OK(write_text(in_dir("dangling.vtu"), "new", &d));
    CX_CHECK(lstat(in_dir("dangling.vtu"), &st) == 0 && S_ISLNK(st.st_mode));
    CX_CHECK(file_is(in_dir("sub/new.vtu"), "new"));
    /* an absolute link */
    char abs[600];
    snprintf(abs, sizeof abs, "%s/sub/target.vtu", dir);
    CX_CHECK(symlink(abs, in_dir("abs.vtu")) == 0);
    CX_CHECK_OK(write_text(in_dir("abs.vtu"), "absolute", &d));
    CX_CHECK(lstat(in_dir("abs.vtu"), &st) == 0 && S_ISLNK(st.st_mode));
    CX_CHECK(file_is(abs, "absolute"));
    CX_CHECK(temporaries(dir) == 0 && temporaries(in_dir("sub")) == 0);
}

static void test_devices(void)
{
    cx_diag d;
    struct stat st;
    cx_outfile o;
    /* as root, a node of our own first (a regression destroys only it) */
    if (mknod(in_dir("null"), S_IFCHR | 0666, makedev(1, 3)) == 0) {
        CX_CHECK_OK(cx_outfile_open(&o, in_dir("null"), &d));
        CX_CHECK(o.mode == CX_OUTFILE_INPLACE);
        fputs("discarded", o.f);
        CX_CHECK_OK(cx_outfile_close(&o, 1, &d));
        CX_CHECK(lstat(in_dir("null"), &st) == 0 && S_ISCHR(st.st_mode));
    }
    if (lstat(in_dir("null"), &st) != 0 || S_ISCHR(st.st_mode)) {
        CX_CHECK_OK(write_text("/dev/null", "discarded", &d));
        CX_CHECK(lstat("/dev/null", &st) == 0 && S_ISCHR(st.st_mode));
    }
    /* a link to a device: written through, both stay */
    CX_CHECK(symlink("/dev/null", in_dir("tonull")) == 0);
    CX_CHECK_OK(write_text(in_dir("tonull"), "discarded", &d));
    CX_CHECK(lstat(in_dir("tonull"), &st) == 0 && S_ISLNK(st.st_mode));
    CX_CHECK(lstat("/dev/null", &st) == 0 && S_ISCHR(st.st_mode));
    /* a FIFO is written in place (a child reads it) */
    CX_CHECK(mkfifo(in_dir("fifo"), 0600) == 0);
    pid_t child = fork();
    if (child == 0) {
        char buf[64] = "";
        FILE *f = fopen(in_dir("fifo"), "r");
        size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
        _exit(n == 9 && memcmp(buf, "via fifo\n", 9) == 0 ? 0 : 1);
    }
    CX_CHECK_OK(write_text(in_dir("fifo"), "via fifo\n", &d));
    int status = -1;
    while (waitpid(child, &status, 0) < 0 && errno == EINTR)
        ;
    CX_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    CX_CHECK(lstat(in_dir("fifo"), &st) == 0 && S_ISFIFO(st.st_mode));
    /* "-" is standard output: flushed, not closed */
    CX_CHECK(cx_outfile_is_stdout("-") && !cx_outfile_is_stdout("-x") && !cx_outfile_is_stdout(NULL));
    CX_CHECK_OK(cx_outfile_open(&o, "-", &d));
    CX_CHECK(o.mode == CX_OUTFILE_STDOUT && o.f == stdout);
    fputs("outfile: a line on standard output\n", o.f);
    CX_CHECK_OK(cx_outfile_close(&o, 1, &d));
    CX_CHECK(fputs("", stdout) >= 0);
}

static void test_abandon(void)
{
    cx_diag d;
    cx_outfile a, b;
    const char *pa = in_dir("big.vtu"), *pb = in_dir("other.csv");
    CX_CHECK_OK(cx_outfile_open(&a, pa, &d));
    CX_CHECK_OK(cx_outfile_open(&b, pb, &d));
    CX_CHECK(a.slot >= 0 && b.slot >= 0 && a.slot != b.slot);
    fputs("partial", a.f);
    fflush(a.f);
    CX_CHECK(access(a.tmp, F_OK) == 0 && access(b.tmp, F_OK) == 0);
    cx_outfile_abandon_pending();
    CX_CHECK(access(a.tmp, F_OK) != 0 && access(b.tmp, F_OK) != 0);
    /* the writer's close finds its temporary gone: an error, no file */
    CX_CHECK(cx_outfile_close(&a, 1, &d) == CX_EIO);
    CX_CHECK_OK(cx_outfile_close(&b, 0, &d));
    CX_CHECK(access(pa, F_OK) != 0 && access(pb, F_OK) != 0);
    /* a finished file is not pending: abandon leaves it */
    CX_CHECK_OK(write_text(pa, "whole", &d));
    cx_outfile_abandon_pending();
    CX_CHECK(file_is(pa, "whole"));
    CX_CHECK(temporaries(dir) == 0);
}

static void test_csv(void)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    cx_csv c;
    cx_csv_init(&c, f);
    cx_csv_comment(&c, "program", "signorini");
    cx_csv_str(&c, "plain");
    cx_csv_str(&c, "a,b");
    cx_csv_str(&c, "say \"hi\"");
    cx_csv_num(&c, 0.1);
    cx_csv_num(&c, NAN);
    cx_csv_numf(&c, "%.3g", 2.0 / 3);
    cx_csv_int(&c, -7);
    cx_csv_empty(&c);
    cx_csv_end_row(&c);
    cx_csv_str(&c, "line\nbreak");
    cx_csv_end_row(&c);
    fclose(f);
    CX_CHECK(strcmp(buf, "# program: signorini\nplain,\"a,b\",\"say \"\"hi\"\"\",0.10000000000000001,,"
                         "0.667,-7,\n\"line\nbreak\"\n") == 0);
    free(buf);
}

int main(void)
{
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 2;
    }
    test_regular();
    test_links();
    test_devices();
    test_abandon();
    test_csv();
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
    return check_finish("out_outfile");
}
