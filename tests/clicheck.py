# SPDX-License-Identifier: GPL-3.0-or-later
"""Shared by the end-to-end tests of the program (tests/*/test_*.py): the
program under test (argv[1]), checks that count, running it, and the
one-line error every bad input must give."""
import subprocess
import sys

exe = sys.argv[1]
_count = {"checks": 0, "failures": 0}


def check(cond, what):
    _count["checks"] += 1
    if not cond:
        _count["failures"] += 1
        print(f"FAIL: {what}")


def run(*args, cwd=None):
    r = subprocess.run([exe, *args], capture_output=True, text=True, timeout=300, cwd=cwd)
    return r.returncode, r.stdout, r.stderr


def one_line_error(code, err, *needles, status=1):
    """An error of the run (status 1) or, with status=2, a malformed
    command line: one line on stderr holding every needle."""
    lines = err.strip().splitlines()
    check(code == status, f"exit {status} for an error, got {code}: {err!r}")
    check(len(lines) == 1, f"one line on stderr, got {lines!r}")
    for n in needles:
        check(n in err, f"{n!r} in {err!r}")


def usage_error(code, err, *needles):
    """A malformed command line: exit 2, one line."""
    one_line_error(code, err, *needles, status=2)


def finish(name):
    """Print the count and exit non-zero on any failure."""
    print(f"{name}: {_count['checks']} checks, {_count['failures']} failed")
    sys.exit(1 if _count["failures"] else 0)
