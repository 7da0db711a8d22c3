/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The bytes of a scene file (issue 20): what the reader accepts (a regular
 * file, a pipe, CRLF line ends, UTF-8 in comments and titles) and what it
 * refuses with one line (a device such as /dev/zero, a file or a pipe
 * beyond 1 MiB, NUL bytes in a buffer); cx_escape on its own. The bad
 * files of the catalogue are in test_scene.c. Runs in tests/scene. */
#include "scene/scene.h"
#include "check.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static const char minimal[] =
    "[scene]\nid = bytes\ndim = 2\n[mesh]\ngenerator = rectangle\nlo = 0 0\nhi = 1 1\n"
    "[material]\nE = 1000\nnu = 0.3\n[contact]\nboundary = bottom\nobstacle = plane\n"
    "normal = 0 1\n";

static int printable(const char *msg)
{
    for (const unsigned char *q = (const unsigned char *)msg; *q; q++)
        if (*q < 0x20 || *q == 0x7f)
            return 0;
    return 1;
}

static void check_escape(void)
{
    char out[64];
    /* ESC ] 0 ; BEL ESC [ 2 J, C1 CSI (U+009B), an invalid byte, a tab */
    const char in[] = "k\x1b]0;t\x07\x1b[2J\xc2\x9b\xff\tx";
    cx_escape(out, sizeof out, in, sizeof in - 1);
    CX_CHECK(strcmp(out, "k\\x1b]0;t\\x07\\x1b[2J\\xc2\\x9b\\xff\\tx") == 0);
    /* valid UTF-8 passes; escaping twice changes nothing */
    const char utf[] = "E \xc2\xb5m \xe2\x80\x94 \xf0\x9f\x98\x80";
    cx_escape(out, sizeof out, utf, sizeof utf - 1);
    CX_CHECK(strcmp(out, utf) == 0);
    char twice[64];
    cx_escape(out, sizeof out, in, sizeof in - 1);
    cx_escape(twice, sizeof twice, out, strlen(out));
    CX_CHECK(strcmp(out, twice) == 0);
    /* overlong, surrogate, truncated sequences; NUL inside the length */
    cx_escape(out, sizeof out, "\xc0\xaf|\xed\xa0\x80|\xe2\x80|\0", 11);
    CX_CHECK(strcmp(out, "\\xc0\\xaf|\\xed\\xa0\\x80|\\xe2\\x80|\\x00") == 0);
    /* truncation keeps whole escapes */
    cx_escape(out, 6, "\x1b\x1b", 2);
    CX_CHECK(strcmp(out, "\\x1b") == 0);
    /* every diagnostic goes through it */
    cx_diag d;
    cx_diag_set(&d, CX_EINVAL, "key '%s'", "a\x1b[2Jb");
    CX_CHECK(strcmp(d.msg, "key 'a\\x1b[2Jb'") == 0);
}

static void check_memory(void)
{
    cx_scene s;
    cx_diag d;
    CX_CHECK_OK(cx_scene_parse(&s, "mem.ini", minimal, sizeof minimal - 1, &d));
    CX_CHECK(strcmp(s.id, "bytes") == 0 && s.mat.E == 1000);

    /* "E = 20\0 00" is not E = 20: the length, not the NUL, ends the text */
    char buf[sizeof minimal + 8];
    const char *e = strstr(minimal, "E = 1000");
    size_t at = (size_t)(e - minimal) + 6, n = sizeof minimal - 1;
    memcpy(buf, minimal, n);
    buf[at] = '\0';
    CX_CHECK(cx_scene_parse(&s, "mem.ini", buf, n, &d) == CX_EINVAL);
    CX_CHECK(strcmp(d.msg, "mem.ini:9: key 'E': NUL byte in column 7 (a scene file is text)") == 0);

    /* CRLF line ends, a UTF-8 title and comment, no newline at the end */
    const char crlf[] = "; \xc2\xb5m and \xe2\x80\x94\r\n[scene]\r\nid = crlf\r\ndim = 2\r\n"
                        "title = Stahl \xe2\x80\x94 \xc2\xb5m\r\n[mesh]\r\ngenerator = rectangle\r\n"
                        "lo = 0 0\r\nhi = 1 1\r\n[material]  ; comment after a header\r\nE = 1\r\n"
                        "nu = 0.3\r\n[contact]\r\nboundary = bottom\r\nobstacle = plane\r\n"
                        "normal = 0 1";
    CX_CHECK_OK(cx_scene_parse(&s, "crlf.ini", crlf, sizeof crlf - 1, &d));
    CX_CHECK(strcmp(s.title, "Stahl \xe2\x80\x94 \xc2\xb5m") == 0 && s.obstacle.normal[1] == 1);

    /* a DEL, a vertical tab, a form feed in a comment: refused too */
    const char *ctl[] = {"; a\x7f\n", "; a\x0b\n", "\x0c\n"};
    for (int k = 0; k < 3; k++) {
        CX_CHECK(cx_scene_parse(&s, "c.ini", ctl[k], strlen(ctl[k]), &d) == CX_EINVAL);
        CX_CHECK(strncmp(d.msg, "c.ini:1: control character 0x", 29) == 0 && printable(d.msg));
    }
}

/* A scene through a pipe: the writer is a child process. */
static int load_from_pipe(const char *text, size_t len, size_t repeat, cx_scene *s, cx_diag *d)
{
    int fd[2];
    if (pipe(fd) != 0)
        return -1;
    pid_t pid = fork();
    if (pid == 0) {
        close(fd[0]);
        for (size_t r = 0; r < repeat; r++)
            if (write(fd[1], text, len) != (ssize_t)len)
                _exit(0);   /* the reader stopped: the pipe is closed */
        _exit(0);
    }
    close(fd[1]);
    char path[64];
    snprintf(path, sizeof path, "/dev/fd/%d", fd[0]);
    int st = cx_scene_load(s, path, d);
    close(fd[0]);
    int ws;
    waitpid(pid, &ws, 0);
    return st;
}

static void check_files(void)
{
    cx_scene s;
    cx_diag d;
    signal(SIGPIPE, SIG_IGN);

    /* a device: refused before reading (it used to hang) */
    CX_CHECK(cx_scene_load(&s, "/dev/zero", &d) == CX_EIO);
    CX_CHECK(strcmp(d.msg, "/dev/zero: cannot read: not a regular file or a pipe") == 0);

    /* a pipe is read whole; an endless one stops at the limit */
    CX_CHECK_OK(load_from_pipe(minimal, sizeof minimal - 1, 1, &s, &d));
    CX_CHECK(strcmp(s.id, "bytes") == 0);
    const char comment[] = "; a comment line repeated for ever ...............................\n";
    CX_CHECK(load_from_pipe(comment, sizeof comment - 1, 100000, &s, &d) == CX_EINVAL);
    CX_CHECK(strstr(d.msg, ": too large: more than 1048576 bytes (a scene file has at most 1048576)") != NULL);

    /* a regular file above 1 MiB: one line, nothing parsed */
    char path[] = "/tmp/cx-scene-big-XXXXXX";
    int fd = mkstemp(path);
    CX_CHECK(fd >= 0);
    if (fd >= 0) {
        CX_CHECK(write(fd, minimal, sizeof minimal - 1) == (ssize_t)(sizeof minimal - 1));
        CX_CHECK(ftruncate(fd, (1 << 20) + 1) == 0);
        close(fd);
        CX_CHECK(cx_scene_load(&s, path, &d) == CX_EINVAL);
        char want[128];
        snprintf(want, sizeof want, "%s: too large: 1048577 bytes (a scene file has at most 1048576)",
                 path);
        CX_CHECK(strcmp(d.msg, want) == 0);
        if (strcmp(d.msg, want) != 0)
            fprintf(stderr, "  got: %s\n", d.msg);
        /* exactly 1 MiB is read (and fails on its NUL padding, line 15) */
        CX_CHECK(truncate(path, 1 << 20) == 0);
        CX_CHECK(cx_scene_load(&s, path, &d) == CX_EINVAL);
        snprintf(want, sizeof want, "%s:15: NUL byte in column 1", path);
        CX_CHECK(strncmp(d.msg, want, strlen(want)) == 0);
        unlink(path);
    }
    /* no leak on any of these paths */
    long live = cx_alloc_live();
    cx_scene_load(&s, "/dev/zero", &d);
    cx_scene_load(&s, "bad/nul_in_value.ini", &d);
    CX_CHECK(cx_alloc_live() == live);
}

/* The build's backstop: values the loader would refuse, set directly,
 * give "file:line: section [...]" instead of an Inf or a NaN in K or f. */
static void check_build_overflow(void)
{
    cx_scene s;
    cx_problem *p = NULL;
    cx_diag d;
    CX_CHECK_OK(cx_scene_load(&s, "good/minimal.ini", &d));
    CX_CHECK(s.line_mesh == 6 && s.line_material == 11 && s.line_contact == 15);
    CX_CHECK_OK(cx_scene_build(&s, 1, &p, NULL, &d));
    cx_problem_destroy(&p);

    cx_scene big = s;
    big.mat.E = 1.7e308;   /* lambda + 2 mu overflows */
    CX_CHECK(cx_scene_build(&big, 1, &p, NULL, &d) == CX_EINVAL && !p);
    CX_CHECK(strncmp(d.msg, "good/minimal.ini:11: section [material]: E = 1.7e+308", 53) == 0);
    cx_problem_destroy(&p);

    big = s;
    big.hi[0] = 1e10;   /* a traction of 1e308 on an edge of length 1e10 */
    big.ntractions = 1;
    memset(&big.tractions[0], 0, sizeof big.tractions[0]);
    strcpy(big.tractions[0].boundary, "top");
    strcpy(big.tractions[0].name, "press");
    big.tractions[0].line = 21;
    big.tractions[0].t.t0[1] = -1e308;
    CX_CHECK(cx_scene_build(&big, 1, &p, NULL, &d) == CX_EINVAL && !p);
    CX_CHECK(strcmp(d.msg, "good/minimal.ini:21: section [traction press]: the loads (overflow: "
                           "Inf or NaN; rescale the units)") == 0);

    big = s;
    big.lo[0] = -1e308, big.hi[0] = 1e308;   /* hi - lo = Inf */
    CX_CHECK(cx_scene_build(&big, 1, &p, NULL, &d) == CX_EINVAL && !p);
    CX_CHECK(strcmp(d.msg, "good/minimal.ini:6: section [mesh]: the node coordinates (overflow: "
                           "Inf or NaN; rescale the units)") == 0);
}

int main(void)
{
    check_escape();
    check_memory();
    check_files();
    check_build_overflow();
    return check_finish("scene_input");
}
