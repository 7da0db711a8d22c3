# SPDX-License-Identifier: GPL-3.0-or-later
"""The program on bad input bytes and out-of-range values (issue 20): each
bad scene gives exit 1 and one printable line on stderr naming the file, the
line and the key, and nothing on stdout (so no NaN or Inf); /dev/zero, an
oversized file and an endless pipe end at once with one line; the prism
counts 40 contact points and 5 clamped, and pdas solves it. Runs in
tests/scene (the paths in the messages are relative to it)."""
import json
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, exe  # noqa: E402

exe = os.path.abspath(exe) if os.sep in exe else exe
SCENES = os.path.abspath(os.environ.get("SIGNORINI_SCENES", "scenes"))
os.chdir(os.path.dirname(os.path.abspath(__file__)))

# file, then what the one line says after "bad/FILE:LINE: "
CASES = [
    ("nul_in_value.ini", 12, "key 'E': NUL byte in column 7"),
    ("nul_line_start.ini", 12, "NUL byte in column 1"),
    ("control_in_key.ini", 12, "control character 0x1b in column 2"),
    ("cr_inside.ini", 13, "key 'nu': control character 0x0d"),
    ("c1_in_key.ini", 12, "unknown key 'E\\xc2\\x9b2J'"),
    ("junk_after_header.ini", 11, "junk after the section header [material]"),
    ("e_overflow.ini", 12, "key 'E': 1e+308 is out of range"),
    ("e_underflow.ini", 12, "key 'E': 1e-300 is out of range"),
    ("lo_overflow.ini", 8, "key 'lo': -1e+308 is out of range"),
    ("hi_overflow.ini", 9, "key 'hi': 1e+308 is out of range"),
    ("coord_overflow.ini", 9, "key 'hi': 1e+300 is out of range"),
    ("load_overflow.ini", 22, "key 't': -1e+308 is out of range"),
]

NONFINITE = re.compile(rb"\b(nan|inf|infinity)\b", re.I)


def run_bytes(args, stdin=None, timeout=60):
    r = subprocess.run([exe, *args], capture_output=True, timeout=timeout, stdin=stdin)
    return r.returncode, r.stdout, r.stderr


def one_printable_line(code, out, err, head, says, status=1):
    lines = err.rstrip(b"\n").split(b"\n")
    check(code == status, f"exit {status}, got {code}: {err!r}")
    check(len(lines) == 1, f"one line on stderr, got {lines!r}")
    check(all(0x20 <= b < 0x7f or b >= 0x80 for b in lines[0]), f"printable: {err!r}")
    check(b"\x1b" not in err and b"\x07" not in err and b"\xc2\x9b" not in err, f"no escape: {err!r}")
    text = err.decode("utf-8", "replace")
    check(text.startswith("signorini solve: " + head), f"{head!r} starts {text!r}")
    check(says in text, f"{says!r} in {text!r}")
    check(not NONFINITE.search(out), f"no NaN or Inf on stdout: {out!r}")


for name, line, says in CASES:
    for extra in ([], ["--json"]):
        code, out, err = run_bytes(["solve", f"bad/{name}", *extra])
        one_printable_line(code, out, err, f"bad/{name}:{line}: ", says)

# a device: at once (it used to hang), no line number
code, out, err = run_bytes(["solve", "/dev/zero"], timeout=20)
one_printable_line(code, out, err, "/dev/zero: ", "cannot read: not a regular file or a pipe")

# an oversized file, and an endless pipe on stdin (/dev/stdin)
with tempfile.NamedTemporaryFile(suffix=".ini") as big:
    big.write(b"; padding\n" * 110000)
    big.flush()
    code, out, err = run_bytes(["solve", big.name])
    one_printable_line(code, out, err, big.name + ": ", "too large: 1100000 bytes")
yes = subprocess.Popen(["yes", "; a comment"], stdout=subprocess.PIPE)
code, out, err = run_bytes(["solve", "/dev/stdin"], stdin=yes.stdout, timeout=20)
yes.kill()
yes.wait()
one_printable_line(code, out, err, "/dev/stdin: ", "too large: more than 1048576 bytes")

# a good scene through a pipe solves
with open(os.path.join(SCENES, "slider.ini"), "rb") as f:
    code, out, err = run_bytes(["solve", "/dev/stdin", "--json"], stdin=f)
check(code == 0 and b'"scene": "slider"' in out, f"slider through a pipe: {code} {err!r}")

# a terminal escape in an option value and in a path is echoed escaped
code, out, err = run_bytes(["solve", "slider", "--method", "\x1b[2J"])
# a malformed command line: usage status 2
one_printable_line(code, out, err, "--method: ", "unknown method '\\x1b[2J'", status=2)
code, out, err = run_bytes(["solve", "x\x1b]0;t\x07.ini"])
one_printable_line(code, out, err, "x\\x1b]0;t\\x07.ini: ", "cannot open")

# contact points are the points with a free dof (paper 001, Table 1: 40 at
# level 2); pdas, which needs a free dof in every contact row, solves it
code, out, err = run_bytes(["solve", "prism", "--level", "2"])
check(code == 0 and b"600 dofs, 40 contact points, 5 clamped;" in out, f"prism summary: {out[:200]!r}")
check(b"contact: 40 of 40 points" in out, f"prism contact line: {out!r}")
code, out, err = run_bytes(["solve", "prism", "--level", "2", "--method", "pdas", "--friction", "none",
                            "--json"])
r = json.loads(out) if code == 0 else {}
check(r.get("contact_points") == 40 and r.get("clamped_points") == 5 and r.get("converged") is True and r.get("kkt_error", 1) <= 1e-10,
      f"pdas on prism: {code} {err!r} {r.get('contact_points')} {r.get('kkt_error')}")

finish("scene_input_cli")
