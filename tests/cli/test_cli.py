#!/usr/bin/env python3
"""The command line end to end: the JSON of 'solve' field by field, 'list',
exit codes, and one-line errors for bad options and bad scenes."""
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, run, one_line_error  # noqa: E402


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
for t in ["assemble", "setup", "solve", "total", "linear_solve"]:
    check(t in j["time"] and j["time"][t] >= 0, f"time.{t}")
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
one_line_error(*run("solve", "hertz", "--method", "nope")[::2], "unknown method 'nope'")
one_line_error(*run("solve", "nosuchscene")[::2], "unknown scene 'nosuchscene'")
one_line_error(*run("solve", "hertz", "--level", "abc")[::2], "--level", "abc")
one_line_error(*run("solve", "hertz", "--tol", "-1")[::2], "--tol")
one_line_error(*run("solve", "hertz", "--friction", "sticky")[::2], "--friction", "sticky")
one_line_error(*run("solve", "hertz", "--method", "ssn-tresca", "--set", "rho=-3")[::2], "rho", "ssn-tresca")
one_line_error(*run("solve", "hertz", "--set", "zeta=1")[::2], "unknown parameter 'zeta'")
one_line_error(*run("solve", "hertz", "--bogus")[::2], "unknown option '--bogus'")
one_line_error(*run("solve", "hertz", "--F")[::2], "--F", "needs a value")
one_line_error(*run("solve", "hertz", "--method", "ssn-tresca", "--friction", "coulomb")[::2],
               "does not support Coulomb")
one_line_error(*run("solve")[::2], "missing SCENE")
one_line_error(*run("frobnicate")[::2], "unknown command")
one_line_error(*run("solve", "hertz", "--level", "999999")[::2], "level")
with tempfile.TemporaryDirectory() as tmp:
    bad = os.path.join(tmp, "bad.ini")
    with open(bad, "w") as f:
        f.write("[scene]\nid = bad\ndim = 2\n[mesh]\ngenerator = hertz\nradius = 8\n"
                "[material]\nE = -5\nnu = 0.3\n[contact]\nboundary = arc\nobstacle = plane\nnormal = 0 1\n")
    one_line_error(*run("solve", bad)[::2], bad + ":8:", "'E'")

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
