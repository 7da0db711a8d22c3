# SPDX-License-Identifier: GPL-3.0-or-later
"""signorini export and solve --problem end to end: the exported files and
manifest, the solve of the files against the scene's (same iterations and
kkt error), and malformed files refused with one line naming the file and
the first bad entry (wrong sizes, a non-symmetric K, NaN values, a negative
gap, a missing manifest), outputs that need the mesh refused."""
import json
import os
import re
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, one_line_error, run, usage_error  # noqa: E402

HAVE_FCLIB = sys.argv[2] == "1"
tmp = tempfile.mkdtemp(prefix="cx_problem_cli_")


def summary(out):
    """(iterations, kkt) of solve's first line."""
    m = re.match(r"converged in (\d+) iterations: kkt error (\S+) <=", out)
    return (int(m.group(1)), float(m.group(2))) if m else None


def same_solve(scene, args, path, method):
    code, a, err = run("solve", scene, "--quiet", "--method", method, *args)
    code2, b, err2 = run("solve", "--problem", path, "--quiet", "--method", method)
    check(code == 0 and code2 == 0, f"{scene} {method}: both converge ({err.strip()} {err2.strip()})")
    check(summary(a) is not None and summary(a) == summary(b),
          f"{scene} {method}: the same iterations and kkt: {a.splitlines()[:1]} {b.splitlines()[:1]}")
    check(a.splitlines()[1] == b.splitlines()[1], f"{scene} {method}: the same contact line")


# ---- export, then solve the files as the scene ----------------------------
for scene, args, methods in [("hertz", [], ["ssn-tresca", "pdas", "graves"]),
                             ("hertz", ["--friction", "coulomb"], ["ssn-coulomb", "auto"]),
                             ("slider", [], ["ssn-tresca", "ssn-tresca-dual"]),
                             ("block3d", ["--friction", "tresca"], ["ssn-tresca", "ssstar"])]:
    d = os.path.join(tmp, scene + "-" + "-".join(args).strip("-"))
    code, out, err = run("export", scene, "--format", "mm", d, *args)
    check(code == 0, f"export {scene} {args}: {err}")
    check(out.startswith(scene + " level "), f"export prints what it wrote: {out!r}")
    man = json.load(open(os.path.join(d, "problem.json")))
    check(man["format"] == "signorini-problem" and man["version"] == 1, "manifest format")
    law = args[1] if args else ("tresca" if scene == "slider" else "none")
    check(man["friction"] == law, f"manifest friction {man['friction']} = {law}")
    check("N u - g <= 0" in man["conventions"]["contact"], "manifest states the contact convention")
    for f in man["files"].values():
        check(os.path.exists(os.path.join(d, f)), f"{f} written")
    k = open(os.path.join(d, "K.mtx")).readline()
    check(k.startswith("%%MatrixMarket matrix coordinate real symmetric"), f"K.mtx is symmetric: {k!r}")
    dims = open(os.path.join(d, "f.mtx")).read().split("\n")[1].split()
    check(dims == [str(man["n"]), "1"], f"f.mtx is n x 1: {dims}")
    for method in methods:
        same_solve(scene, args, d, method)

hz = os.path.join(tmp, "hertz-")
code, out, err = run("solve", "--problem", hz)
check(code == 0 and "problem " + hz in out and "(auto)" in out, f"--method auto on a problem: {out[:200]}")
code, out, err = run("solve", "--problem", hz, "--json")
j = json.loads(out)
check(j["converged"] is True and j["dofs"] > 1000 and j["contact_points"] == 33, "solve --problem --json")
check(len(j["history"]) == j["iterations"] and j["history"][-1]["kkt"] == j["kkt"], "--json history")

# ---- what needs the mesh, and usage -----------------------------------------
code, out, err = run("solve", "--problem", hz, "--png", os.path.join(tmp, "x.png"))
one_line_error(code, err, "--problem", "need the mesh")
code, out, err = run("solve", "--problem", hz, "--vtu", os.path.join(tmp, "x.vtu"))
one_line_error(code, err, "need the mesh")
code, out, err = run("solve", "hertz", "--problem", hz)
usage_error(code, err, "a SCENE and --problem")
code, out, err = run("export", "hertz", os.path.join(tmp, "nofmt"))
usage_error(code, err, "missing --format")
code, out, err = run("export", "hertz", "--format", "mm", "-")
usage_error(code, err, "not standard output")
# several bodies (node-to-segment rows): the same run from the files
tb = os.path.join(tmp, "twoblocks")
code, out, err = run("export", "twoblocks", "--format", "mm", tb)
check(code == 0, f"export twoblocks: {err}")
same_solve("twoblocks", [], tb, "ssn-tresca")
code, out, err = run("export", "slider", "--format", "fclib", os.path.join(tmp, "slider.hdf5"))
one_line_error(code, err, "Tresca friction has no FCLIB form")
check(not os.path.exists(os.path.join(tmp, "slider.hdf5")), "no file for a refused FCLIB export")

# ---- FCLIB --------------------------------------------------------------------
if HAVE_FCLIB:
    # auto: the scene's choice with its parameters (block3d Coulomb: cf-fp, tight), the scene
    # named in the FCLIB title
    for scene, args, method in [("hertz", ["--friction", "coulomb"], "ssn-coulomb"),
                                ("block3d", [], "ssn-tresca"),
                                ("block3d", ["--friction", "coulomb"], "auto")]:
        h5 = os.path.join(tmp, scene + "-".join(args) + ".hdf5")
        code, out, err = run("export", scene, "--format", "fclib", h5, *args)
        check(code == 0 and "FCLIB" in out, f"export {scene} fclib: {err}")
        check(open(h5, "rb").read(8) == b"\x89HDF\r\n\x1a\n", "an HDF5 file")
        same_solve(scene, args, h5, method)
    code, out, err = run("solve", "--problem", os.path.join(tmp, "hertz-", "K.mtx"))
    one_line_error(code, err, "K.mtx", "not a problem directory or an HDF5 file")


# ---- malformed files ------------------------------------------------------------
def broken(name, edit):
    """A copy of the hertz export with one file edited."""
    d = os.path.join(tmp, "bad-" + name)
    shutil.copytree(hz, d)
    edit(d)
    return d


def rewrite(d, f, fn):
    p = os.path.join(d, f)
    lines = open(p).read().split("\n")
    open(p, "w").write("\n".join(fn(lines)))


def wrong_size(lines):
    """One column fewer: the entries of the last column dropped."""
    r, c, nz = lines[1].split()
    body = [ln for ln in lines[2:] if ln.strip() and ln.split()[1] != c]
    return [lines[0], f"{r} {int(c) - 1} {len(body)}"] + body


d = broken("size", lambda d: rewrite(d, "N.mtx", wrong_size))
code, out, err = run("solve", "--problem", d)
one_line_error(code, err, os.path.join(d, "N.mtx"), "33 x 2144, expected 33 x 2145")


def asymmetric(lines):
    # the symmetric file as a general one (both triangles), one entry changed
    head, body = lines[:2], [ln for ln in lines[2:] if ln.strip()]
    out = []
    for ln in body:
        i, j, x = ln.split()
        out.append(ln)
        if i != j:
            out.append(f"{j} {i} {x}")
    i, j, x = out[1].split()
    out[1] = f"{i} {j} {float(x) * 1.001!r}"
    n = head[1].split()
    return ["%%MatrixMarket matrix coordinate real general", f"{n[0]} {n[1]} {len(out)}"] + out


d = broken("asym", lambda d: rewrite(d, "K.mtx", asymmetric))
code, out, err = run("solve", "--problem", d)
one_line_error(code, err, os.path.join(d, "K.mtx"), "not symmetric: entry at row 2, column 1")


def nan_in(k):
    def edit(lines):
        lines[k] = " ".join(lines[k].split()[:-1] + ["nan"])
        return lines
    return edit


d = broken("nanK", lambda d: rewrite(d, "K.mtx", nan_in(3)))
code, out, err = run("solve", "--problem", d)
one_line_error(code, err, os.path.join(d, "K.mtx"), "entry at row 2, column 1 is nan")
d = broken("nanf", lambda d: rewrite(d, "f.mtx", nan_in(4)))
code, out, err = run("solve", "--problem", d)
one_line_error(code, err, os.path.join(d, "f.mtx"), "entry at row 3, column 1 is nan")
d = broken("gap", lambda d: rewrite(d, "g.mtx", lambda ls: ls[:2] + ["-0.5"] + ls[3:]))
code, out, err = run("solve", "--problem", d)
one_line_error(code, err, os.path.join(d, "g.mtx"), "entry at row 1, column 1 is -0.5: a gap must be >= 0")
d = broken("manifest", lambda d: os.remove(os.path.join(d, "problem.json")))
code, out, err = run("solve", "--problem", d)
one_line_error(code, err, "problem.json", "No such file")
d = broken("json", lambda d: open(os.path.join(d, "problem.json"), "w").write('{"format": "signorini-problem",'))
code, out, err = run("solve", "--problem", d)
one_line_error(code, err, "problem.json", "malformed JSON")
d = broken("garbage", lambda d: open(os.path.join(d, "T.mtx"), "w").write("not a matrix\n"))
code, out, err = run("solve", "--problem", d)
one_line_error(code, err, os.path.join(d, "T.mtx"), "not a MatrixMarket file")
# the banner in another case: CHOLMOD would look for it further down
d = broken("banner_case", lambda d: rewrite(d, "g.mtx", lambda ls: [ls[0].replace("MatrixMarket", "matrixmarket")]
                                               + ls[1:]))
code, out, err = run("solve", "--problem", d)
one_line_error(code, err, os.path.join(d, "g.mtx"), "not a MatrixMarket file")
# a second banner below the first
d = broken("banner_twice", lambda d: rewrite(d, "g.mtx", lambda ls: ls[:1] + ["%%MatrixMarket matrix array real general"]
                                                + ls[1:]))
code, out, err = run("solve", "--problem", d)
one_line_error(code, err, os.path.join(d, "g.mtx"), "line 2: a second '%%MatrixMarket' line")

shutil.rmtree(tmp)
finish("problem_cli")
