#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The command line end to end: the JSON of 'solve' field by field, 'list',
exit codes, one-line errors for bad options and bad scenes, and the output
files: a write error on standard output is an error, '-' is standard
output, links and devices are kept, Ctrl-C leaves no temporary."""
import json
import re
import os
import signal
import stat
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, exe, finish, run, one_line_error, usage_error  # noqa: E402


# ---- solve --json on hertz ----
code, out, err = run("solve", "hertz", "--level", "16", "--json", "--baseline")
check(code == 0, f"hertz converges (exit {code}, {err})")
j = json.loads(out)
for key in ["scene", "method", "dim", "dofs", "contact_points", "iterations", "converged", "reason",
            "kkt_error", "time", "counts", "active", "stick", "slip", "force", "params",
            "pressure_error_l2"]:
    check(key in j, f"JSON has '{key}'")
check(j["scene"] == "hertz" and j["method"] == "ssn-tresca" and j["dim"] == 2, "scene, method, dim")
check(j["contact_points"] == 17, f"17 arc nodes at level 16, got {j['contact_points']}")
# 17 x 17 nodes, 2 dofs each, u_x = 0 on the 17 axis nodes
check(j["dofs"] == 2 * 17 * 17 - 17, f"dofs = 561, got {j['dofs']}")
check(j["converged"] is True and j["reason"] == "converged", "converged on the kkt error")
check(j["reason_text"].startswith("converged in "), f"the outcome's sentence: {j['reason_text']}")
check(0 < j["kkt_error"] < 1e-12, f"kkt {j['kkt_error']}")
check(2 <= j["iterations"] <= 12, f"iterations {j['iterations']}")
for t in ["assemble", "setup", "solve", "total", "baseline"]:
    check(t in j["time"] and j["time"][t] >= 0, f"time.{t}")

# ---- solve --baseline, text: the baseline, the orderings' fills and where
# the reduction's CPU time went, one line each ----
code, out, err = run("solve", "hertz", "--level", "64", "--baseline")
check(code == 0, f"solve --baseline ({code}, {err})")
base = re.search(r"^ +baseline \(factorise \+ solve K\) ([0-9.e+-]+) s; \(setup \+ solve\) / baseline = ([0-9.]+)$",
                 out, re.M)
check(base is not None and float(base.group(1)) > 0, f"the baseline's line: {out[-600:]!r}")
check(re.search(r"^ +contact-last ordering: CAMD( \(chosen\))? [0-9.e+]+ nnz\(L\)", out, re.M) is not None,
      "the orderings' line")
red = re.search(r"^ +reduction CPU \(all threads\): orderings ([0-9.]+) s, analysis ([0-9.]+) s, "
                r"factorisation ([0-9.]+) s, S ([0-9.]+) s$", out, re.M)
check(red is not None, f"the reduction's CPU line: {out[-400:]!r}")
# the reduction's phases were timed (hertz 64 takes a few tens of ms), not left at 0
check(red is not None and sum(float(v) for v in red.groups()) > 0, f"the reduction's CPU time: {red and red.groups()}")
check(j["counts"]["factorizations"] == 1, "one factorisation")
# ssn-tresca works on the condensed system: f is condensed once and u
# expanded once, when the run ends; the kkt error of the other iterations
# is evaluated on the condensed system, with no product with K
check(j["counts"]["solves"] == 2, f"two solves (condense f, expand u), got {j['counts']['solves']}")
check(j["counts"]["matvecs"] == 1, f"one product with K (the last kkt), got {j['counts']['matvecs']}")
check(j["active"] > 0 and j["stick"] == 0 and j["slip"] == 0, "frictionless: active, no stick/slip")
fa, fc = j["force"]["applied"], j["force"]["contact"]
check(abs(fa[1] + 800) < 1e-9 and abs(fc[1] - 800) < 1e-6, f"forces {fa} {fc}")
check(abs(fa[0]) < 1e-12, "no horizontal load")
check(j["params"]["rho"] == 1e-3, "parameters echoed")
pe = j["pressure_error_l2"]
check(pe["abs"] > 0 and 0 < pe["rel"] < 0.2, f"pressure error {pe}")

# Tresca on slider: stick and slip
code, out, err = run("solve", "slider", "--json")
j = json.loads(out)
check(code == 0 and j["friction"] == "tresca", f"slider tresca ({code}, {err})")
check(j["stick"] > 0 and j["slip"] > 0, f"stick {j['stick']} slip {j['slip']}")
check("pressure_error_l2" not in j, "no Hertz error without an analytical pressure")

# --set, --tol, --friction echo
code, out, err = run("solve", "hertz", "--level", "8", "--json", "--set", "rho=0.01", "--tol", "1e-6",
                     "--friction", "tresca", "--slip", "20")
j = json.loads(out)
check(code == 0 and j["params"]["rho"] == 0.01 and j["friction"] == "tresca" and j["slip_bound"] == 20,
      "options reach the run")

# not converging is a result: exit 3
code, out, err = run("solve", "hertz", "--level", "16", "--json", "--max-iter", "1")
j = json.loads(out)
check(code == 3 and j["converged"] is False and j["reason"] == "max_iter", f"max-iter 1: {code} {j['reason']}")
check(j["kkt_error"] is not None, "kkt reported even when not converged")

# text summary
code, out, err = run("solve", "hertz", "--level", "8")
check(code == 0 and "converged" in out and "pressure vs Hertz" in out, "text summary")

# ---- bad options: one line, exit 1 ----
usage_error(*run("solve", "hertz", "--method", "nope")[::2], "unknown method 'nope'")
one_line_error(*run("solve", "nosuchscene")[::2], "unknown scene 'nosuchscene'")
usage_error(*run("solve", "hertz", "--level", "abc")[::2], "--level", "abc")
usage_error(*run("solve", "hertz", "--tol", "-1")[::2], "--tol")
usage_error(*run("solve", "hertz", "--friction", "sticky")[::2], "--friction", "sticky")
usage_error(*run("solve", "hertz", "--method", "ssn-tresca", "--set", "rho=-3")[::2], "rho", "ssn-tresca")
usage_error(*run("solve", "hertz", "--set", "zeta=1")[::2], "unknown parameter 'zeta'")
usage_error(*run("solve", "hertz", "--bogus")[::2], "unknown option '--bogus'")
usage_error(*run("solve", "hertz", "--F")[::2], "--F", "needs a value")
one_line_error(*run("solve", "hertz", "--method", "ssn-tresca", "--friction", "coulomb")[::2],
               "does not support Coulomb")
usage_error(*run("solve")[::2], "missing SCENE")
usage_error(*run("frobnicate")[::2], "unknown command")
one_line_error(*run("solve", "hertz", "--level", "999999")[::2], "level")
with tempfile.TemporaryDirectory() as tmp:
    bad = os.path.join(tmp, "bad.ini")
    with open(bad, "w") as f:
        f.write("[scene]\nid = bad\ndim = 2\n[mesh]\ngenerator = hertz\nradius = 8\n"
                "[material]\nE = -5\nnu = 0.3\n[contact]\nboundary = arc\nobstacle = plane\nnormal = 0 1\n")
    one_line_error(*run("solve", bad)[::2], bad + ":8:", "'E'")

# ---- output: write errors, '-' for standard output, links and devices kept ----
# standard output on a full device: exit 1 with one line, for the summary,
# the JSON and the list (the output is lost: that is an error, not a result)
for args in (["solve", "hertz", "--level", "8"], ["solve", "hertz", "--level", "8", "--json"],
             ["list", "--json"], ["list"]):
    with open("/dev/full", "w") as full:
        r = subprocess.run([exe, *args], stdout=full, stderr=subprocess.PIPE, text=True, timeout=300)
    one_line_error(r.returncode, r.stderr, "standard output", "No space left on device")


def is_vtu(data):
    return data.lstrip().startswith(b"<?xml") and b'<VTKFile type="UnstructuredGrid"' in data


exe = os.path.abspath(exe)   # the runs below change directory
with tempfile.TemporaryDirectory() as tmp:
    # --vtu -: the VTU on standard output, the summary on stderr
    r = subprocess.run([exe, "solve", "hertz", "--level", "8", "--vtu", "-"], capture_output=True,
                       timeout=300, cwd=tmp)
    check(r.returncode == 0 and is_vtu(r.stdout) and r.stdout.rstrip().endswith(b"</VTKFile>"),
          f"--vtu - writes the VTU on stdout ({r.returncode}, {r.stderr!r})")
    # (the VTU's FieldData has an array named "converged": look for the summary's line)
    check(b"converged" in r.stderr and all(
          line not in r.stdout for line in r.stderr.splitlines() if b"converged" in line),
          "the summary goes to stderr")
    check(os.listdir(tmp) == [], f"no file for '-': {os.listdir(tmp)}")
    usage_error(*run("solve", "hertz", "--level", "8", "--json", "--vtu", "-")[::2], "standard output")
    # --csv -: the CSV on standard output
    code, out, err = run("bench", "wp", "hertz", "--level", "4", "--methods", "ssn-tresca",
                         "--csv", "-", "--cache", tmp)
    lines = out.splitlines()
    check(code == 0 and any(l.startswith("# program: signorini") for l in lines), f"--csv - ({code}, {err})")
    rows = [l for l in lines if not l.startswith("#")]
    check(len(rows) >= 2 and "method" in rows[0].split(",") and
          len({l.count(",") for l in rows}) == 1, f"stdout holds the CSV alone: {rows[:3]}")
    check("# program: signorini" in err, "the text table goes to stderr")
    check(not any(".tmp" in f for f in os.listdir(tmp)), "no temporary for '-'")

    # a link stays a link; its target is written
    os.mkdir(os.path.join(tmp, "real"))
    target = os.path.join(tmp, "real", "t.vtu")
    with open(target, "w") as f:
        f.write("old")
    os.chmod(target, 0o640)
    link = os.path.join(tmp, "link.vtu")
    os.symlink("real/t.vtu", link)
    code, out, err = run("solve", "hertz", "--level", "8", "--quiet", "--vtu", link)
    check(code == 0 and os.path.islink(link) and os.readlink(link) == "real/t.vtu", f"link kept ({err})")
    with open(target, "rb") as f:
        check(is_vtu(f.read()), "the link's target holds the VTU")
    check(os.stat(target).st_mode & 0o777 == 0o640, "the target keeps its permissions")
    csv_link = os.path.join(tmp, "link.csv")
    os.symlink(os.path.join(tmp, "real", "t.csv"), csv_link)
    code, out, err = run("bench", "wp", "hertz", "--level", "4", "--methods", "ssn-tresca",
                         "--csv", csv_link, "--cache", tmp)
    check(code == 0 and os.path.islink(csv_link) and os.path.isfile(os.path.join(tmp, "real", "t.csv")),
          f"--csv through a link ({code}, {err})")

    # a device is written in place and stays a device: a node of our own
    # first (as root), then /dev/null itself
    nodes = []
    try:
        os.mknod(os.path.join(tmp, "null"), 0o666 | stat.S_IFCHR, os.makedev(1, 3))
        nodes.append(os.path.join(tmp, "null"))
    except PermissionError:
        pass
    nodes.append("/dev/null")
    for node in nodes:
        if not stat.S_ISCHR(os.lstat(node).st_mode):
            break   # the first node was replaced: do not risk /dev/null
        for opt in (["--vtu", node], ["--vtu", node, "--vtu-ascii"]):
            code, out, err = run("solve", "hertz", "--level", "8", "--quiet", *opt)
            check(code == 0 and stat.S_ISCHR(os.lstat(node).st_mode), f"{opt}: still a character device ({err})")
        code, out, err = run("bench", "wp", "hertz", "--level", "4", "--methods", "ssn-tresca",
                             "--csv", node, "--cache", tmp)
        check(code == 0 and stat.S_ISCHR(os.lstat(node).st_mode), f"--csv {node}: still a device ({err})")
    check(not [f for f in os.listdir(tmp) if ".tmp" in f], "no temporary left")

    # the VTU read back with VTK (Debian's python3-vtk9, under /usr/bin/python3)
    # has the solve's points and displacement: the same numbers as the
    # ASCII file written by the same solve, u_x = 0 on the symmetry axis,
    # and as many contact points in contact as the JSON says
    vtk_read = (
        "import json, sys, vtk\n"
        "r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(sys.argv[1]); r.Update()\n"
        "g = r.GetOutput(); pd = g.GetPointData(); n = g.GetNumberOfPoints()\n"
        "u = pd.GetArray('displacement'); s = pd.GetArray('contact_status')\n"
        "print(json.dumps({'error': r.GetErrorCode(), 'points': n, 'cells': g.GetNumberOfCells(),\n"
        "                  'x': [g.GetPoint(i) for i in range(n)], 'u': [u.GetTuple3(i) for i in range(n)],\n"
        "                  'status': [s.GetTuple1(i) for i in range(n)]}))\n")
    bin_vtu, asc_vtu = os.path.join(tmp, "h.vtu"), os.path.join(tmp, "h_ascii.vtu")
    code, out, err = run("solve", "hertz", "--level", "16", "--json", "--vtu", bin_vtu)
    j = json.loads(out) if code == 0 else {}
    code2, _, err2 = run("solve", "hertz", "--level", "16", "--quiet", "--vtu", asc_vtu, "--vtu-ascii")
    check(code == 0 and code2 == 0, f"solve --vtu ({err}, {err2})")
    r = subprocess.run(["/usr/bin/python3", "-c", vtk_read, bin_vtu], capture_output=True, text=True,
                       timeout=300)
    check(r.returncode == 0, f"VTK reads the VTU (python3-vtk9 installed?): {r.stderr[-300:]}")
    if r.returncode == 0 and j:
        v = json.loads(r.stdout)
        check(v["error"] == 0 and v["points"] == 17 * 17, f"VTK: 289 points, got {v['points']}")
        check(j["dofs"] == 2 * v["points"] - 17, "the solve's dofs: 2 per point but u_x on the 17 axis nodes")
        da = ET.parse(asc_vtu).getroot().find(".//PointData/DataArray[@Name='displacement']")
        ua = [float(t) for t in da.text.split()]
        uv = [c for t in v["u"] for c in t]
        check(len(ua) == len(uv) and ua == uv, "VTK's displacement = the ASCII file's, exactly")
        axis = [i for i, x in enumerate(v["x"]) if x[0] == 0.0]
        check(len(axis) == 17 and all(v["u"][i][0] == 0.0 for i in axis), "u_x = 0 on the axis")
        check(max(abs(t[1]) for t in v["u"]) > 0, "the body moved")
        check(sum(1 for s in v["status"] if s > 0) == j["active"], "points in contact as in the JSON")

    # Ctrl-C while the VTU is written: status 130, no temporary left. The
    # process is stopped as soon as its temporary appears (so the signal
    # surely lands inside the write), then interrupted and continued; a run
    # that finishes before its temporary is seen is tried again.
    seen = False
    for attempt in range(4):
        work = os.path.join(tmp, f"sigint{attempt}")
        os.mkdir(work)
        p = subprocess.Popen([exe, "solve", "hertz", "--level", "256", "--quiet", "--vtu", "big.vtu",
                              "--vtu-ascii"], cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        while p.poll() is None:
            if any(".tmp" in f for f in os.listdir(work)):
                p.send_signal(signal.SIGSTOP)
                seen = any(".tmp" in f for f in os.listdir(work))
                p.send_signal(signal.SIGINT)
                p.send_signal(signal.SIGCONT)
                break
            time.sleep(0.002)
        p.communicate(timeout=300)
        if seen:
            check(p.returncode == 130, f"interrupted: exit 130, got {p.returncode}")
            left = os.listdir(work)
            check(left == [], f"no temporary or partial file after Ctrl-C: {left}")
            break
    check(seen, "the VTU's temporary was seen while it was written")

# ---- help and list ----
for cmd in (["--help"], ["solve", "--help"], ["list", "--help"]):
    code, out, err = run(*cmd)
    check(code == 0 and "usage:" in out, f"{cmd} prints usage")
code, out, err = run("list", "--json")
j = json.loads(out)
ids = [s["id"] for s in j["scenes"]]
check(all(s in ids for s in ["hertz", "slider", "block3d"]), f"scenes listed: {ids}")
ms = {m["id"]: m for m in j["methods"]}
check("ssn-tresca" in ms and ms["ssn-tresca"]["source"] == "000 §4.2", "method listed with its source")
check(any(p["key"] == "rho" for p in ms["ssn-tresca"]["params"]), "parameters listed")
code, out, err = run("list")
check(code == 0 and "hertz" in out and "ssn-tresca" in out, "text list")

finish("cli")
