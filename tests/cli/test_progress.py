#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The progress line (cli/progress.c): with stderr on a terminal (a pty)
'solve' draws the steps before the first iteration (assembling, ordering,
factorising, condensing: 'STEP N dofs... T s') and erases the line before
the iteration lines, the summary, an error or the baseline's result; with
stderr a pipe nothing of it appears. The results are the same both ways."""
import os
import pty
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, exe, finish, run  # noqa: E402

ERASE = "\r\x1b[K"
LINE = re.compile(r"\r\x1b\[K(assembling|ordering|factorising|condensing) ([0-9.]+[kM]?) dofs\.\.\. ([0-9.]+) s")


def run_tty(*args):
    """Run with stderr on a pty, stdout a pipe: (status, stdout, what the terminal got)."""
    master, slave = pty.openpty()
    p = subprocess.Popen([exe, *args], stdout=subprocess.PIPE, stderr=slave, stdin=subprocess.DEVNULL)
    os.close(slave)
    chunks = []
    while True:
        try:
            b = os.read(master, 65536)
        except OSError:   # EIO: the last writer closed the pty
            break
        if not b:
            break
        chunks.append(b)
    out = p.stdout.read()
    p.wait(timeout=300)
    os.close(master)
    return p.returncode, out.decode(), b"".join(chunks).decode(errors="replace")


def main():
    # hertz 128 (33k dofs): a condensed method, the baseline before it
    args = ("solve", "hertz", "--level", "128", "--method", "ssn-tresca", "--baseline")
    code, out, term = run_tty(*args)
    check(code == 0, f"solve on a terminal ({code}, {term[-300:]!r})")
    steps = LINE.findall(term)
    names = [s[0] for s in steps]
    for want in ("assembling", "ordering", "factorising", "condensing"):
        check(want in names, f"'{want}' on the progress line: {names}")
    check(all(s[1] == "33k" for s in steps if s[0] != "condensing"), f"sizes: the dofs (33k): {steps}")
    check(all(100 < int(s[1]) < 300 for s in steps if s[0] == "condensing"),
          f"condensing onto the contact dofs (129 points): {steps}")
    check(names and names[0] == "assembling", f"assembly first: {names[:3]}")
    # every drawn line is erased before the next output: the last thing
    # on the terminal before each result line is the erase sequence
    check(term.count(ERASE) >= len(steps) + 1, "the line is erased when the steps end")
    plain = re.sub(r"\r\x1b\[K[^\r\n]*?(?=\r\x1b\[K|$)", "", term)
    check("assembling" not in plain and "factorising" not in plain, f"no progress text left: {plain[:200]!r}")
    # the summary goes to stdout; an error to the terminal on a line of its own
    check("converged in" in out and "baseline (factorise + solve K)" in out, f"summary on stdout: {out[-300:]!r}")

    # stderr a pipe: no progress line, the same summary lines
    code2, out2, err2 = run(*args)
    check(code2 == 0, f"solve on pipes ({code2}, {err2})")
    check("\x1b[K" not in err2 and "dofs..." not in err2 and "\x1b[K" not in out2,
          f"no progress on a pipe: {err2[:200]!r}")
    strip = lambda s: [l for l in s.splitlines() if not l.startswith(("time:", "         baseline", "         contact-last ordering",
                                                                      "         reduction CPU"))
                       and "(s)" not in l and not re.match(r"^ +\d+ ", l)]
    check(strip(out) == strip(out2), "the same summary with and without the terminal")

    # an error after the line began: the message starts a line of its own
    code, out, term = run_tty("solve", "hertz", "--level", "64", "--method", "ssn-tresca", "--vtu-series",
                              "/nonexistent/dir/x")
    check(code == 1, f"a bad --vtu-series fails ({code})")
    msg = [l for l in term.replace(ERASE, "\n").splitlines() if l.startswith("signorini solve:")]
    check(len(msg) == 1 and "--vtu-series" in msg[0], f"one error line: {term[-300:]!r}")
    finish("test_progress")


main()
