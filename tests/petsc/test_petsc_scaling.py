#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""signorini bench scaling --backend direct,petsc (and petsc alone), on
small levels, alone and under mpirun -n 2: both backends' rows per level
with the columns the comparison needs, both converged to the tolerance,
the same solution as the reference, and a crossover line that says what
the printed times say (recomputed here from the rows: the logic, not the
timings). The table and the CSV are printed by rank 0 alone."""
import csv
import json
import math
import os
import re
import shutil
import tempfile

from mpicheck import check, finish, run
TOL = 1e-10




def crossover(rows, method):
    """What the crossover line must say: the first level of the last run of
    levels (up to the largest both finished) at which PETSc is faster."""
    best = {}
    for r in rows:
        if r["method"] != method or r["converged"] not in ("yes", True):
            continue
        t = best.setdefault(int(r["level"]), {})
        t[r["backend"]] = min(t.get(r["backend"], math.inf), float(r["time"]))
    both = sorted(lv for lv, t in best.items() if "direct" in t and "petsc" in t)
    first = len(both)
    while first > 0 and best[both[first - 1]]["petsc"] < best[both[first - 1]]["direct"]:
        first -= 1
    return None if first == len(both) else both[first]


def check_table(j, levels, ranks, backends, what):
    rows, meta = j["rows"], j["meta"]
    for col in ("level", "backend", "ranks", "dofs", "method", "time", "peak_mb", "kkt", "iterations",
                "baseline", "ratio", "krylov"):
        check(all(col in r for r in rows), f"{what}: column {col}")
    for lv in levels:
        for be in backends:
            sel = [r for r in rows if r["level"] == lv and r["backend"] == be and r["method"] == "ssn-tresca"]
            check(len(sel) == 1, f"{what}: level {lv} has one {be} row")
            if not sel:
                continue
            r = sel[0]
            check(r["converged"] in ("yes", True) and float(r["kkt"]) <= TOL,
                  f"{what}: level {lv} {be}: converged, kkt {r['kkt']} <= {TOL}")
            check(float(r["time"]) > 0 and float(r["peak_mb"]) > 0 and int(r["iterations"]) > 0,
                  f"{what}: level {lv} {be}: time, peak memory, iterations")
            check(int(r["ranks"]) == (ranks if be == "petsc" else 1), f"{what}: level {lv} {be}: ranks {r['ranks']}")
            if be == "petsc":
                check(int(r["krylov"]) > 0, f"{what}: level {lv}: Krylov iterations counted")
            if "direct" in backends:
                # the same solution as the direct path's reference
                check(float(r["err_u"]) <= 1e-8, f"{what}: level {lv} {be}: err_u {r['err_u']}")
                check(abs(float(r["ratio"]) - float(r["time"]) / float(r["baseline"])) <= 1e-3 * float(r["ratio"]),
                      f"{what}: level {lv} {be}: ratio = time / baseline")
    if "direct" in backends and "petsc" in backends:
        line = meta.get("crossover (ssn-tresca)")
        check(line is not None, f"{what}: the crossover line is printed")
        want = crossover(rows, "ssn-tresca")
        if line is not None:
            if want is None:
                check(line.startswith("not within the levels run"), f"{what}: crossover '{line}' (none expected)")
            else:
                check(line.startswith(f"level {want} "), f"{what}: crossover '{line}' (level {want} expected)")
    else:
        check(not any(k.startswith("crossover") for k in meta), f"{what}: no crossover line for one backend")


with tempfile.TemporaryDirectory() as tmp:
    cache = os.path.join(tmp, "cache")
    common = ["--repeat", "1", "--cache", cache, "--json"]
    # one rank, no mpirun: block3d 2 and 4 (3D), both backends
    r = run(["bench", "scaling", "block3d", "--levels", "2..4", "--backend", "direct,petsc"] + common)
    check(r.returncode == 0, "block3d 2..4, direct,petsc, alone", r)
    if r.returncode == 0:
        check_table(json.loads(r.stdout), [2, 4], 1, ["direct", "petsc"], "block3d alone")
    # the text table: both backends per level and the crossover line
    r = run(["bench", "scaling", "hertz", "--levels", "8,16", "--backend", "petsc,direct", "--repeat", "1",
             "--cache", cache])
    check(r.returncode == 0 and re.search(r"^# crossover \(ssn-tresca\): (level \d+|not within the levels run)",
                                          r.stdout, re.M)
          and len(re.findall(r"^hertz\s+(8|16)\s+none\s+(direct|petsc)\s", r.stdout, re.M)) == 4,
          "hertz 8,16 text table: four rows and the crossover line", r)
    head = re.search(r"^# (crossover \(ssn-tresca\): .*)$", r.stdout, re.M)
    check(r.returncode == 0 and head and r.stdout.rstrip().splitlines()[-1] == head.group(1),
          "the crossover line again at the end, under the table", r)
    # petsc alone: no baseline, no crossover
    r = run(["bench", "scaling", "hertz", "--levels", "8..16", "--backend", "petsc"] + common)
    check(r.returncode == 0, "hertz 8..16, petsc alone", r)
    if r.returncode == 0:
        j = json.loads(r.stdout)
        check_table(j, [8, 16], 1, ["petsc"], "petsc alone")
        check(all(row["backend"] == "petsc" and row["baseline"] in ("", None) for row in j["rows"]),
              "petsc alone: petsc rows only, no baseline")
    # a bad backend is a one-line usage error
    r = run(["bench", "scaling", "hertz", "--levels", "8", "--backend", "cuda"])
    check(r.returncode == 2 and "--backend 'cuda'" in r.stderr and len(r.stderr.strip().splitlines()) == 1,
          "--backend cuda refused in one line", r)
    # the PETSc peers are methods of --methods too
    r = run(["bench", "scaling", "block3d", "--levels", "2", "--backend", "direct,petsc", "--methods",
             "ssn-tresca,petsc-vi"] + common)
    check(r.returncode == 0 and any(row["method"] == "petsc-vi" and row["backend"] == "petsc"
                                    for row in json.loads(r.stdout)["rows"]), "--methods petsc-vi runs on petsc", r)

    if shutil.which("mpirun"):
        # two ranks: rank 0 alone prints one JSON document
        r = run(["bench", "scaling", "block3d", "--levels", "2..4", "--backend", "direct,petsc"] + common, mpi=2)
        check(r.returncode == 0, "block3d 2..4 on 2 ranks", r)
        if r.returncode == 0:
            check_table(json.loads(r.stdout), [2, 4], 2, ["direct", "petsc"], "block3d on 2 ranks")
        csvp = os.path.join(tmp, "s.csv")
        r = run(["bench", "scaling", "hertz", "--levels", "8", "--backend", "direct,petsc", "--repeat", "1",
                 "--cache", cache, "--csv", csvp], mpi=2)
        with open(csvp) as f:
            body = [row for row in csv.reader(line for line in f if not line.startswith("#"))]
        check(r.returncode == 0 and r.stdout.count("# program:") == 1 and len(body) == 3,
              "hertz 8 on 2 ranks: one table, one CSV with two rows", r)

finish("petsc bench scaling")
