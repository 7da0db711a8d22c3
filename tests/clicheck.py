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


def one_line_error(code, err, *needles):
    lines = err.strip().splitlines()
    check(code == 1, f"exit 1 for an error, got {code}: {err!r}")
    check(len(lines) == 1, f"one line on stderr, got {lines!r}")
    for n in needles:
        check(n in err, f"{n!r} in {err!r}")


def finish(name):
    """Print the count and exit non-zero on any failure."""
    print(f"{name}: {_count['checks']} checks, {_count['failures']} failed")
    sys.exit(1 if _count["failures"] else 0)
