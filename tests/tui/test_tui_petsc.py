#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The explorer on the PETSc backend, one rank, in a real terminal (tmux on
a private socket, the pane polled): 'signorini tui hertz --level 32
--backend petsc' runs ssn-tresca on PETSc with 'r', and the runs table and
the status line show the iteration count and the kkt error that
'signorini solve hertz --level 32 --backend petsc --json' gives on the
same problem; the header names the backend; 'b' goes through PETSc's
methods (the picker then lists the backend's methods, without the direct
method's parameter rows) to the direct path, whose run then opens a row of its own; an
Esc-free 'q' ends PETSc on its thread and exits 0."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

exe = os.path.abspath(sys.argv[1])
failures = 0
if not shutil.which("tmux"):
    print("tmux not found (scripts/bootstrap.sh installs it)")
    sys.exit(1)

sock = f"signorini-tui-petsc-{os.getpid()}"
conf = tempfile.NamedTemporaryFile("w", suffix=".conf", delete=False)
conf.write("set -g remain-on-exit on\nset -g status off\n")
conf.close()
workdir = tempfile.mkdtemp(prefix="signorini-tui-petsc-")
rcfile = os.path.join(workdir, "rc")


def tmux(*args, check=True):
    r = subprocess.run(["tmux", "-L", sock, "-f", conf.name, *args], capture_output=True, text=True, timeout=30)
    if check and r.returncode != 0:
        raise RuntimeError(f"tmux {args}: {r.stderr}")
    return r.stdout


def screen():
    return tmux("capture-pane", "-t", "t", "-p", check=False)


def check(cond, what):
    global failures
    if not cond:
        failures += 1
        print(f"FAIL: {what}")
        print(screen())
    else:
        print(f"ok: {what}")


def wait_for(pred, what, timeout=120.0):
    end = time.time() + timeout
    while time.time() < end:
        if pred(screen()):
            return True
        time.sleep(0.1)
    check(False, f"timed out waiting for {what}")
    return False


def keys(*k):
    tmux("send-keys", "-t", "t", *k)


def header():
    lines = screen().splitlines()
    return lines[0] if lines else ""


def runs_rows():
    """The runs table's rows: (method, law, iter, kkt text, the rest)."""
    return re.findall(r"■ (\S+)\s+(none|tresca|coulomb)\s+\S+\s+(\d+)\s+(\S+)\s+\d+\s+(.*)$", screen(), re.M)


# the reference: solve on the same problem, the same backend
LEVEL = "32"
r = subprocess.run([exe, "solve", "hertz", "--level", LEVEL, "--backend", "petsc", "--json"], capture_output=True,
                   text=True, timeout=300)
check(r.returncode == 0, f"solve --backend petsc --json ({r.stderr.strip()})")
ref = json.loads(r.stdout)
iters, kkt = ref["iterations"], ref["kkt_error"]
check(ref["converged"] and kkt <= 1e-10, f"solve converged: {iters} iterations, kkt {kkt:.3e}")

env = f"LANG=C.UTF-8 LC_ALL=C.UTF-8 SIGNORINI_SCENES={os.environ.get('SIGNORINI_SCENES', '')}"
tmux("new-session", "-d", "-s", "t", "-x", "120", "-y", "40", "-c", workdir,
     f"env {env} {exe} tui hertz --level {LEVEL} --backend petsc; echo $? > {rcfile}.tmp && mv {rcfile}.tmp {rcfile}")
try:
    wait_for(lambda t: "built in" in t, "the build")
    check("│ petsc ssn-tresca none" in header(), f"the header names the backend: {header()!r}")
    keys("r")
    wait_for(lambda t: any("petsc, 1 rank" in row[4] for row in runs_rows()), "the PETSc run's row")
    rows = [row for row in runs_rows() if "petsc, 1 rank" in row[4]]
    if rows:
        method, law, it, kkt_text, rest = rows[-1]
        check(method == "ssn-tresca" and law == "none", f"the row's method and law: {rows[-1]}")
        check(int(it) == iters, f"iterations on the screen {it} = solve --json's {iters}")
        check(kkt_text == f"{kkt:.1e}", f"kkt on the screen {kkt_text} = solve --json's {kkt:.1e}")
        check(rest.startswith("converged"), f"the outcome: {rest!r}")
    # the status line's sentence, with three digits of the kkt error
    text = " ".join(l.strip() for l in screen().splitlines()[-6:])
    m = re.search(r"converged in (\d+) iterations: kkt error (\S+) <= tol", text)
    check(m and int(m.group(1)) == iters and abs(float(m.group(2)) - kkt) <= 5e-3 * kkt,
          f"the status line: {m.group(0) if m else text!r} against kkt {kkt:.3e}")
    # the steps panel has every iteration of the run
    # (its row, not the runs table's, which has the marker and the outcome)
    last = [l for l in screen().splitlines() if re.search(rf"\s{iters}\s+{re.escape(f'{kkt:.1e}')}\s", l)
            and "■" not in l and "converged" not in l]
    check(len(last) == 1, f"the steps panel's last iteration: {last}")
    # 'b': petsc-vi, petsc-tao, then the direct path; 'r' runs it in a row of its own
    keys("b")
    wait_for(lambda t: "│ petsc petsc-vi none" in t.splitlines()[0], "b: petsc-vi")
    # the setup's method row shows what s and r run: the backend's method
    check(re.search(r"^method\s+◂?petsc-vi\b", screen(), re.M) is not None,
          "the method row shows petsc-vi")
    # with the cursor on that row, the list is the backend's methods with
    # its summary, and the direct method's parameter rows (rho) are gone
    listed = re.findall(r"^(▸ |  )(\S+)\s", screen(), re.M)
    names = [n for _, n in listed]
    check(names[:3] == ["ssn-tresca", "petsc-vi", "petsc-tao"] and "ssstar" not in names
          and ("▸ ", "petsc-vi") in listed, f"the picker lists PETSc's methods: {listed}")
    check("PETSc, 1 rank:" in screen() and re.search(r"^rho\s", screen(), re.M) is None,
          "the backend's summary, no parameter rows")
    keys("b")
    wait_for(lambda t: "│ petsc petsc-tao none" in t.splitlines()[0], "b: petsc-tao")
    keys("b")
    wait_for(lambda t: "backend direct" in t, "b: the direct path")
    keys("r")
    wait_for(lambda t: len(runs_rows()) >= 2 and runs_rows()[-1][4].startswith("converged")
             and "petsc" not in runs_rows()[-1][4], "the direct run's row")
    d = runs_rows()[-1]
    check(d[0] == "ssn-tresca" and float(d[3]) <= 1e-10, f"the direct run converged: {d}")
    keys("q")
    wait_for(lambda t: os.path.exists(rcfile), "the exit", timeout=60)
    with open(rcfile) as f:
        rc = int(f.read().strip() or -1)
    check(rc == 0, f"q exits 0 (PETSc ended on its thread): {rc}")
finally:
    tmux("kill-server", check=False)
    os.unlink(conf.name)

print("FAILED" if failures else "all passed")
sys.exit(1 if failures else 0)
