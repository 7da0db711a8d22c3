#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Honest outcomes end to end (issue 20): 'converged' and exit 0 only when
the kkt error is at or below the tolerance; the words of the outcome in the
text summary and the JSON (reason id + reason_text); every shipped scene
converges with no options under every law it allows (--method auto);
--time-limit and Ctrl-C act inside a long step; no NaN or Inf is ever
printed as a result."""
import json
import math
import os
import re
import signal
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, exe, finish, run, one_line_error, usage_error  # noqa: E402

SCENES = os.environ.get("SIGNORINI_SCENES", os.path.join(os.path.dirname(__file__), "..", "..", "scenes"))
IDS = {"converged", "stopped_own", "stalled", "max_iter", "diverged", "breakdown", "refused",
       "cancelled", "time_limit", "nonfinite"}


def scene_variant(tmp, scene, name, edits):
    """A copy of a shipped scene with some 'key = value' lines replaced."""
    with open(os.path.join(SCENES, scene + ".ini")) as f:
        text = f.read()
    for old, new in edits:
        check(re.search(old, text, re.M) is not None, f"{scene}.ini has {old!r}")
        text = re.sub(old, new, text, count=1, flags=re.M)
    path = os.path.join(tmp, name + ".ini")
    with open(path, "w") as f:
        f.write(text)
    return path


def no_constant(c):
    check(False, f"a JSON number is {c}")
    return float("nan")


def solve_json(*args):
    code, out, err = run("solve", *args, "--json")
    if code == 1 and not out:
        return code, {}, err
    try:
        j = json.loads(out, parse_constant=no_constant)
    except ValueError:
        check(False, f"JSON from solve {args}: {out[:200]!r} {err!r}")
        j = {}
    return code, j, err


def all_numbers_finite(what, text):
    """Every number printed is finite: no 'nan'/'inf' word (but in the
    outcome's words, "overflow or NaN: NaN in u ..."), and every token that
    parses as a float is finite."""
    text = re.sub(r"overflow or NaN|NaN in |overflow: Inf in ", "", text)
    check(re.search(r"\b-?(nan|inf|infinity)\b", text, re.I) is None, f"no NaN/Inf word in {what}: {text[:300]!r}")
    for tok in re.findall(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?", text):
        check(math.isfinite(float(tok)), f"finite number {tok} in {what}")


def json_numbers_finite(what, j):
    if isinstance(j, dict):
        for v in j.values():
            json_numbers_finite(what, v)
    elif isinstance(j, list):
        for v in j:
            json_numbers_finite(what, v)
    elif isinstance(j, float):
        check(math.isfinite(j), f"finite JSON number in {what}: {j}")


with tempfile.TemporaryDirectory() as tmp:
    # ---- the far obstacle: its own criterion stops it, far from a solution ----
    far = scene_variant(tmp, "hertz", "far", [(r"^point = 0 0$", "point = 0 -1e14")])
    for method in ["ssn-tresca", "graves", "pdas"]:
        code, j, err = solve_json(far, "--level", "8", "--method", method)
        check(code == 3 and j.get("converged") is False, f"far obstacle {method}: exit {code}, {j.get('reason')}")
        check(j.get("reason") == "stopped_own" and j.get("kkt_error", 0) > j.get("tol", 1),
              f"far obstacle {method}: {j.get('reason_text')}")
        check("stopped by its own criterion" in j.get("reason_text", ""), f"the words: {j.get('reason_text')}")
    code, out, err = run("solve", far, "--level", "8", "--method", "ssn-tresca")
    check(code == 3 and "stopped by its own criterion at kkt error" in out and "not converged" in out,
          f"text summary of the far obstacle: {out[-400:]!r}")

    # ---- the cases: own criteria above the tolerance are not converged ----
    slider_e12 = scene_variant(tmp, "slider", "slider_e12", [(r"^E = .*$", "E = 1e12")])
    cases = [([slider_e12, "--method", "mprgp"], "mprgp on slider, E = 1e12"),
             (["hertz", "--method", "ubr-c"], "ubr-c on hertz (eps 1e-5)"),
             (["hertz", "--method", "ssn-c"], "ssn-c on hertz"),
             (["hertz", "--method", "cf-fp", "--friction", "coulomb", "--F", "0"], "cf-fp at F = 0")]
    for args, what in cases:
        code, j, err = solve_json(*args)
        check(code == 3 and j.get("converged") is False and j.get("reason") == "stopped_own",
              f"{what}: exit {code}, {j.get('reason_text')} {err}")
        check(j.get("kkt_error", 0) > j.get("tol", 1), f"{what}: kkt {j.get('kkt_error')} above tol")
    # --tol is enforced: the same run is converged under a tolerance above its kkt error
    code, j, err = solve_json("hertz", "--method", "ubr-c")
    loose = 2 * j["kkt_error"]
    code, j, err = solve_json("hertz", "--method", "ubr-c", "--tol", f"{loose:.3e}")
    check(code == 0 and j["converged"] is True and j["reason"] == "converged", f"ubr-c under --tol {loose:.1e}")

    # ---- every shipped scene, every law it allows, no options: converged ----
    code, out, err = run("list", "--json")
    scenes = [s["id"] for s in json.loads(out)["scenes"]]
    check(len(scenes) >= 9, f"scenes listed: {scenes}")
    allowed = 0
    for sc in scenes:
        for law in ["none", "tresca", "coulomb"]:
            code, j, err = solve_json(sc, "--friction", law)
            if code == 1 and "allows only" in err:
                continue   # a law the scene's 'laws' key excludes: one line, exit 1
            allowed += 1
            check(code == 0 and j.get("converged") is True and j.get("kkt_error", 1) <= j.get("tol", 0),
                  f"{sc} {law} with no options: exit {code}, {j.get('method')}: {j.get('reason_text')} {err}")
            check(j.get("reason") in IDS, f"reason id {j.get('reason')}")
    check(allowed >= 23, f"scene x law cases run: {allowed}")
    code, j, err = solve_json("halfball")
    check(code == 0 and j["method"] != "ubr-c" and j["method_auto"] is True,
          f"halfball converges by default ({j['method']})")
    code, j, err = solve_json("halfball", "--method", "ubr-c")
    check(code == 3 and j["method_auto"] is False and j["reason"] in ("stalled", "stopped_own"),
          f"halfball on ubr-c (the old default) is not converged: {j['reason_text']}")
    code, j, err = solve_json("twoblocks", "--friction", "coulomb")
    check(code == 0 and j["method"] == "ssn-coulomb", f"twoblocks Coulomb picks a Coulomb method: {j['method']}")
    one_line_error(*run("solve", "stackbond", "--friction", "tresca")[::2], "stackbond", "allows only none")

    # ---- time limit and Ctrl-C inside a long psor step ----
    slow = ["laminae", "--method", "psor", "--set", "sweeps=1000000", "--set", "omega=1e-5"]
    code, j, err = solve_json(*slow, "--time-limit", "0.3")
    check(code == 3 and j.get("reason") == "time_limit" and j.get("iterations") == 1,
          f"--time-limit cuts the first step: exit {code} {j.get('reason_text')}")
    check(j.get("counts", {}).get("inner_iterations", 10**6) < 10**6, "fewer sweeps than the step asked for")
    usage_error(*run("solve", "hertz", "--time-limit", "-1")[::2], "--time-limit")
    p = subprocess.Popen([exe, "solve", *slow], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    header = p.stdout.readline() + p.stdout.readline()   # printed (flushed) before the run starts
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=120)
    check(p.returncode == 130, f"Ctrl-C: exit {p.returncode} {err!r}")
    check("\ncancelled after 1 iterations" in "\n" + out, f"the partial result, as cancelled: {out[:300]!r}")
    all_numbers_finite("the cancelled run", header + out)

    # ---- no NaN or Inf printed, whatever the arithmetic gives ----
    e300 = scene_variant(tmp, "hertz", "e300", [(r"^E = .*$", "E = 1e-300")])
    l308 = scene_variant(tmp, "hertz", "l308", [(r"^t = 0 -100$", "t = 1e308 -1e308")])
    for path, what in [(e300, "E = 1e-300"), (l308, "loads 1e308")]:
        code, out, err = run("solve", path)
        check(code in (0, 1, 3), f"{what}: exit {code}")
        all_numbers_finite(f"text of {what}", out)
        code, out, err = run("solve", path, "--json")
        all_numbers_finite(f"JSON of {what}", out)
        if out.strip():
            j = json.loads(out, parse_constant=no_constant)
            json_numbers_finite(what, j)
            check(code != 0 or j["converged"] is True, f"{what}: exit 0 only if converged")
            if j["reason"] == "nonfinite":
                check("NaN" in j["reason_text"] or "overflow" in j["reason_text"], f"{what}: {j['reason_text']}")

finish("cli_outcomes")
