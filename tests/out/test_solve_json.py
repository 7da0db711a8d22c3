#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""'solve --json' carries the run's per-iteration history: one row per
iteration, in order, whose last row is the result's kkt error, iteration
count and contact counts, with non-decreasing work counters and time; a
run stopped at its iteration limit has exactly that many rows."""
import json
import subprocess
import sys

exe = sys.argv[1]
failed = []


def check(cond, what):
    if not cond:
        failed.append(what)


def solve(*args):
    r = subprocess.run([exe, "solve", *args, "--json"], capture_output=True, text=True)
    return r.returncode, json.loads(r.stdout) if r.stdout else {}


for args in (["hertz"], ["slider", "--method", "ssn-tresca"], ["hertz", "--method", "pdas"]):
    code, j = solve(*args)
    h = j.get("history", [])
    name = " ".join(args)
    check(code == 0 and j.get("converged") is True, f"{name}: converged (exit {code})")
    check(len(h) == j.get("iterations") and len(h) > 0, f"{name}: {len(h)} rows for {j.get('iterations')} iterations")
    check([row["iter"] for row in h] == list(range(1, len(h) + 1)), f"{name}: rows 1..n in order")
    if h:
        last = h[-1]
        check(last["kkt"] == j["kkt_error"] and last["kkt"] <= j["tol"], f"{name}: last kkt {last['kkt']} is the result's")
        check(last["stick"] == j["stick"] and last["slip"] == j["slip"], f"{name}: last counts are the result's")
        check(last["contact"] == j["active"] and last["contact"] + j["free"] == j["contact_points"], f"{name}: contact = active")
        check(h[0]["kkt"] > last["kkt"], f"{name}: the error falls")
        for key in ("factorizations", "solves", "matvecs", "time"):
            vals = [row[key] for row in h]
            check(all(a <= b for a, b in zip(vals, vals[1:])), f"{name}: {key} non-decreasing {vals}")
        check(all(set(row) >= {"kkt", "own", "contact", "changed", "inner", "time"} for row in h), f"{name}: keys")

code, j = solve("hertz", "--method", "pdas", "--max-iter", "2", "--tol", "1e-300")
check(code == 3 and j.get("converged") is False, f"max-iter 2: not converged (exit {code})")
check(len(j.get("history", [])) == 2, f"max-iter 2: two rows, got {len(j.get('history', []))}")

# the text summary has no JSON and the plain JSON keys are unchanged
code, j = solve("hertz", "--quiet")
check("kkt_error" in j and "iterations" in j and "version" in j, "the other keys stay")

for f in failed:
    print("FAIL", f)
print(f"{len(failed)} failures")
sys.exit(1 if failed else 0)
