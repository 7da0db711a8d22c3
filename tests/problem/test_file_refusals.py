#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A problem read back from a file (`solve --problem DIR|FILE.hdf5`) has no
mesh (issue 24):

* the methods that need K^-1 refuse an exported punch or ring (bodies held
  only by contact) with their reason, from the factorisation's zero pivot
  since there is no mesh to name the body: one line, exit 1, "K is
  singular", the pivot's column, "use ssn-tresca"; ssn-tresca and auto
  still solve the same files; on the ring at level 16 the roundoff pivot
  passes the factorisation's check, and inverse iteration finds the
  rigid motion instead; a supported problem (slider) is not refused;
* a damaged FCLIB file (truncated, not HDF5 at all) is one line and exit 1,
  never a stop inside libfclib (tests/problem/test_fclib_bad.c checks the
  deleted and resized datasets through the library).
Usage: test_file_refusals.py SIGNORINI HAVE_FCLIB"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, one_line_error, run  # noqa: E402

fclib = len(sys.argv) > 2 and sys.argv[2] == "1"

with tempfile.TemporaryDirectory() as tmp:
    files = []
    for scene in ("punch", "ring"):
        d = os.path.join(tmp, scene + "-mm")
        code, out, err = run("export", scene, "--friction", "none", "--format", "mm", d)
        check(code == 0, f"export {scene} mm ({err})")
        files.append(d)
        if fclib:
            h = os.path.join(tmp, scene + ".hdf5")
            code, out, err = run("export", scene, "--friction", "none", "--format", "fclib", h)
            check(code == 0, f"export {scene} fclib ({err})")
            files.append(h)
    for path in files:
        name = os.path.basename(path)
        for method in ("mprgp", "ssn-tresca-dual", "ssn-tresca-glob"):
            code, out, err = run("solve", "--problem", path, "--method", method, "--quiet")
            one_line_error(code, err, "need K^-1", "K is singular", "at column", "held only by contact",
                           "use ssn-tresca")
            check(out == "", f"{name} {method}: nothing on stdout ({out[:200]!r})")
        for method in ("ssn-tresca", "auto"):
            code, out, err = run("solve", "--problem", path, "--method", method, "--quiet")
            check(code == 0 and "converged" in out, f"{name} {method} converges ({code}: {err[-300:]})")

    fine = os.path.join(tmp, "ring16")
    code, out, err = run("export", "ring", "--level", "16", "--friction", "none", "--format", "mm", fine)
    check(code == 0, f"export ring --level 16 ({err})")
    code, out, err = run("solve", "--problem", fine, "--method", "mprgp", "--quiet")
    one_line_error(code, err, "need K^-1", "K is singular", "inverse iteration", "use ssn-tresca")
    slider = os.path.join(tmp, "slider")
    code, out, err = run("export", "slider", "--format", "mm", slider)
    check(code == 0, f"export slider ({err})")
    for method in ("mprgp", "ssn-tresca-dual"):
        code, out, err = run("solve", "--problem", slider, "--method", method, "--quiet")
        code2, out2, err2 = run("solve", "slider", "--method", method, "--quiet")
        check(code == code2 and "singular" not in err and out.splitlines()[:1] == out2.splitlines()[:1],
              f"slider {method}: the file solves as the scene ({code} {err.strip()} / {code2})")

    if fclib:
        good = os.path.join(tmp, "punch.hdf5")
        with open(good, "rb") as f:
            data = f.read()
        for frac in (0.5, 0.9):
            cut = os.path.join(tmp, f"cut{int(frac * 100)}.hdf5")
            with open(cut, "wb") as f:
                f.write(data[:int(len(data) * frac)])
            code, out, err = run("solve", "--problem", cut, "--method", "ssn-tresca")
            one_line_error(code, err, cut, "truncated or damaged")
        text = os.path.join(tmp, "text.hdf5")
        with open(text, "w") as f:
            f.write("K = 1\n")
        code, out, err = run("solve", "--problem", text)
        one_line_error(code, err, text, "not a problem directory or an HDF5 file")

finish("problem_file_refusals")
