#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""signorini solve --backend petsc as a user runs it: alone and under
mpirun -n 2 (rank 0 alone prints: one summary, a line per rank), the
refusals with their reasons (contact rows off the axes, Tresca for the
peers, options the backend has not), and the JSON and VTU it writes."""
import json
import os
import re
import shutil
import tempfile

from mpicheck import check, finish, run




# one rank, no mpirun: converges, prints the rank line
r = run(["solve", "hertz", "--level", "32", "--backend", "petsc"])
check(r.returncode == 0 and "converged" in r.stdout and "(petsc, 1 rank)" in r.stdout
      and re.search(r"rank 0: \d+ rows, 2048 elements assembled", r.stdout), "hertz 32 alone", r)
contact1 = re.search(r"contact x 0 y (\S+)", r.stdout)
# the summary names the preconditioner that ran: BoomerAMG in 2D where
# PETSc has hypre, else GAMG; -cx_pc_type gamg is named as it runs
pc2d = re.search(r"petsc: +1 rank; CG \+ (BoomerAMG|GAMG): \d+ Krylov iterations in \d+ solves", r.stdout)
check(pc2d is not None, "hertz 32: the summary names CG + BoomerAMG or CG + GAMG", r)
r = run(["solve", "hertz", "--level", "32", "--backend", "petsc"], env={"PETSC_OPTIONS": "-cx_pc_type gamg"})
check(r.returncode == 0 and "CG + GAMG: " in r.stdout, "hertz 32 with -cx_pc_type gamg: CG + GAMG named", r)
r = run(["solve", "block3d", "--level", "4", "--backend", "petsc"])
check(r.returncode == 0 and "CG + GAMG: " in r.stdout, "block3d 4: CG + GAMG named", r)

# two ranks: one summary (rank 0's), both ranks' lines, the elements split
if shutil.which("mpirun"):
    r = run(["solve", "hertz", "--level", "32", "--backend", "petsc"], mpi=2)
    elems = [int(x) for x in re.findall(r"rank \d: \d+ rows, (\d+) elements", r.stdout)]
    check(r.returncode == 0 and r.stdout.count("converged in") == 1 and "(petsc, 2 ranks)" in r.stdout
          and len(elems) == 2 and sum(elems) == 2048 and min(elems) > 0, "hertz 32 on 2 ranks", r)
    contact2 = re.search(r"contact x 0 y (\S+)", r.stdout)
    check(contact1 and contact2 and abs(float(contact1.group(1)) - float(contact2.group(1))) < 1e-6 * 800,
          "the same contact force on 1 and 2 ranks", r)

# solve --backend petsc builds the scene without the serial K (--baseline
# builds it, to factorise): the same run either way, bitwise, on 1 and 2
# ranks; slider prescribes non-zero displacements (their share of f comes
# from the element matrices without K), hertz none
def without_times(j):
    j = dict(j)
    j.pop("time", None)
    j["history"] = [{k: v for k, v in h.items() if k != "time"} for h in j.get("history", [])]
    return j


with tempfile.TemporaryDirectory() as tmp:
    for scene, level in (("slider", "2"), ("hertz", "32")):
        for mpi in (0, 2) if shutil.which("mpirun") else (0,):
            out = {}
            for flag in ("", "--baseline"):
                vtu = os.path.join(tmp, f"{scene}{mpi}{flag}.vtu")
                r = run(["solve", scene, "--level", level, "--backend", "petsc", "--json", "--vtu", vtu]
                        + ([flag] if flag else []), mpi=mpi)
                ok = r.returncode == 0
                out[flag] = (without_times(json.loads(r.stdout)) if ok else None,
                             open(vtu, "rb").read() if ok else None)
            a, b = out[""], out["--baseline"]
            check(a[0] is not None and a[0] == b[0] and a[1] == b[1] and a[0]["converged"],
                  f"{scene} {level} on {max(mpi, 1)} rank(s): the same result and VTU without the serial K", r)

# a tolerance below the roundoff floor of K u (hertz 32: about 2e-13): the
# run stops the step after it gets there (8 steps to 1e-10, then one that
# cannot halve the error), not at the stall window (50), and says why
r = run(["solve", "hertz", "--level", "32", "--backend", "petsc", "--tol", "1e-16"])
steps = [int(x) for x in re.findall(r"^\s+(\d+)\s+\d\.\d+e[-+]\d+\s", r.stdout, re.M)]
check(r.returncode != 0 and "stalled" in r.stdout and "roundoff floor of K u" in r.stdout and steps
      and steps[-1] <= 10, "hertz 32 to tol 1e-16: stopped at the roundoff floor, with the reason", r)

# a contact row off the axes (node to segment between two bodies): refused with the reason
r = run(["solve", "twoblocks", "--backend", "petsc"])
check(r.returncode == 1 and "acts on more than one dof" in r.stderr and "flat obstacles along an axis" in r.stderr,
      "twoblocks refused", r)
# the peers take no Tresca friction
r = run(["solve", "slider", "--backend", "petsc", "--method", "petsc-vi"])
check(r.returncode == 1 and "does not solve tresca friction" in r.stderr, "petsc-vi refuses Tresca", r)
r = run(["solve", "hertz", "--backend", "petsc", "--method", "pdas"])
check(r.returncode == 1 and "unknown method 'pdas'" in r.stderr, "a direct-path method refused", r)
r = run(["solve", "hertz", "--backend", "petsc", "--set", "rho=1"])
check(r.returncode == 2 and "--backend petsc" in r.stderr, "--set refused", r)
r = run(["render", "hertz", "--backend", "petsc", "--png", "x.png"])
check(r.returncode == 2, "render refuses the backend", r)

# JSON and VTU from rank 0
with tempfile.TemporaryDirectory() as tmp:
    vtu = os.path.join(tmp, "s.vtu")
    r = run(["solve", "block3d", "--level", "4", "--backend", "petsc", "--method", "petsc-tao", "--json",
             "--vtu", vtu], mpi=2 if shutil.which("mpirun") else 0)
    ok = r.returncode == 0
    if ok:
        j = json.loads(r.stdout)
        ok = j.get("method") == "petsc-tao" or j.get("run", {}).get("method") == "petsc-tao" or "petsc-tao" in r.stdout
        ok = ok and os.path.getsize(vtu) > 1000
    check(ok, "block3d 4 petsc-tao: JSON on stdout, a VTU file", r)

finish("petsc cli")
