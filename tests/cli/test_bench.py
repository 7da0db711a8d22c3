#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""'signorini bench' machinery on tiny cases: CSV columns and one row per
run, the reference solution reused from the disk cache (checked through the
counters), where that cache lives ($XDG_CACHE_HOME/signorini, --cache, a
warning when it cannot be written), its key from the parsed scene (two
scenes through /dev/stdin), a stress case forced to fail gives a row and no
crash, unit scaling keeps kkt and iteration counts, Ctrl-C keeps what
finished and exits 130 without temporary files, scaling --set runs what
solve --set runs, and one-line errors for bad options. No timings are
asserted."""
import csv
import io
import json
import os
import pty
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, exe, finish, one_line_error, run  # noqa: E402


# Every run's default reference cache ($XDG_CACHE_HOME/signorini) goes to
# a temporary directory, never to the home directory of whoever runs the tests.
xdg_default = tempfile.mkdtemp(prefix="signorini-test-xdg-")
os.environ["XDG_CACHE_HOME"] = xdg_default
scenes = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes")


def read_csv(path):
    with open(path) as f:
        lines = f.read().splitlines()
    meta = {}
    for line in lines:
        if line.startswith("# "):
            k, _, v = line[2:].partition(": ")
            meta[k] = v
    rows = list(csv.DictReader(io.StringIO("\n".join(l for l in lines if not l.startswith("#")))))
    return meta, rows


def drain(master):
    """What is left to read on a pty's master side (the program has
    exited; EOF or EIO ends it); the master is closed."""
    out = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:
            break
        if not chunk:
            break
        out += chunk
    os.close(master)
    return out


methods = json.loads(run("list", "--json")[1])["methods"]
frictionless_2d = [m for m in methods if "frictionless" in m["supports"] and "2d" in m["supports"]]

with tempfile.TemporaryDirectory() as tmp:
    cache = os.path.join(tmp, "ref")

    # ---- wp: the CSV has the columns and one row per run ----
    out_csv = os.path.join(tmp, "wp.csv")
    code, out, err = run("bench", "wp", "hertz", "--level", "8", "--tols", "1e-4,1e-10",
                         "--sweep", "rho=1e-3,1e-2", "--csv", out_csv, "--cache", cache)
    check(code == 0, f"bench wp runs (exit {code}, {err})")
    check(err == "", f"no progress bar when stderr is not a terminal: {err!r}")
    meta, rows = read_csv(out_csv)
    for col in ["scene", "level", "friction", "method", "param", "value", "tol", "converged", "reason",
                "iterations", "time", "ratio", "setup", "solve", "factorizations", "solves", "kkt",
                "err_u", "err_l"]:
        check(rows and col in rows[0], f"wp CSV has column '{col}'")
    expected = sum(2 * (2 if any(p["key"] == "rho" for p in m["params"]) else 1) for m in frictionless_2d)
    check(len(rows) == expected, f"one row per run: {expected} expected, got {len(rows)}")
    for key in ["program", "machine", "blas", "scene hash", "baseline", "reference"]:
        check(key in meta, f"wp header has '{key}'")
    check("computed" in meta.get("reference", ""), f"first run computes the reference: {meta.get('reference')}")
    check(meta.get("program", "").startswith("signorini "), "program version in the header")
    check("cores" in meta.get("machine", ""), "cores in the header")
    ssn = [r for r in rows if r["method"] == "ssn-tresca"]
    check(len(ssn) == 4, "ssn-tresca: 2 values of rho x 2 tolerances")
    for r in ssn:
        check(r["converged"] == "yes" and float(r["kkt"]) <= float(r["tol"]), f"ssn row converged {r}")
        # the reference is ssn-tresca itself to kkt < 1e-12: the same active set, the same solution
        check(float(r["err_u"]) <= 1e-8 and float(r["err_l"]) <= 1e-8, f"errors against the reference {r}")
        check(int(r["factorizations"]) == 1, "one factorisation per run (fresh session)")
    refs = os.listdir(cache)
    check(len(refs) == 1 and refs[0].startswith("hertz-L8-") and refs[0].endswith(".ref"),
          f"one reference file in the cache: {refs}")
    check(not any(".tmp" in f for f in os.listdir(tmp)), "no temporary file left")

    # ---- the second run reads the reference from the cache ----
    code, out, err = run("bench", "wp", "hertz", "--level", "8", "--tols", "1e-10", "--methods",
                         "ssn-tresca", "--json", "--cache", cache)
    check(code == 0, f"second bench wp runs ({code}, {err})")
    j = json.loads(out)
    ref = j["meta"]["reference"]
    check("cached" in ref and "0 factorisations" in ref, f"reference reused, no work: {ref}")
    # typed JSON: seconds as a number (the sentence beside it), booleans for yes/no
    check(isinstance(j["meta"]["baseline"], float) and j["meta"]["baseline"] > 0
          and j["meta"]["baseline text"].startswith("%.4g s" % j["meta"]["baseline"]),
          f"baseline a number: {j['meta'].get('baseline')!r}")
    check(all(r["converged"] is True for r in j["rows"]), "converged is a boolean")
    check(len(j["rows"]) == 3 and [r["value"] for r in j["rows"]] == [0.0001, 0.001, 0.01],
          f"--methods ssn-tresca: the default sweep of rho (3 values) x 1 tolerance, got {len(j['rows'])}")
    check(all(r["err_u"] is not None and r["err_u"] <= 1e-8 for r in j["rows"]),
          "errors against the cached reference")
    check(len(os.listdir(cache)) == 1, "nothing recomputed")
    # another friction law is another reference
    code, out, err = run("bench", "wp", "hertz", "--level", "8", "--tols", "1e-10", "--friction",
                         "tresca", "--json", "--cache", cache)
    j = json.loads(out)
    check(code == 0 and "computed" in j["meta"]["reference"], f"Tresca: a new reference ({err})")
    check(len(os.listdir(cache)) == 2, "two references in the cache")

    # ---- scaling: one row per level and method ----
    sc_csv = os.path.join(tmp, "scaling.csv")
    code, out, err = run("bench", "scaling", "hertz", "--levels", "4..8", "--repeat", "1",
                         "--methods", "ssn-tresca", "--csv", sc_csv, "--cache", cache)
    check(code == 0, f"bench scaling runs ({code}, {err})")
    meta, rows = read_csv(sc_csv)
    check([int(r["level"]) for r in rows] == [4, 8], f"levels 4 and 8: {[r['level'] for r in rows]}")
    for r in rows:
        n = int(r["level"])
        check(int(r["dofs"]) == 2 * (n + 1) ** 2 - (n + 1) and int(r["contact"]) == n + 1,
              f"dofs and contact points at level {n}: {r['dofs']} {r['contact']}")
        for col in ["assembly", "baseline", "time", "ratio", "factor_mb", "peak_mb", "setup/baseline"]:
            check(r[col] != "" and float(r[col]) >= 0, f"scaling {col} at level {n}: {r[col]!r}")
        # medians of paired ratios: one run (--repeat 1) gives the plain quotients
        check(abs(float(r["setup/baseline"]) - float(r["setup"]) / float(r["baseline"]))
              <= 1e-3 * float(r["setup/baseline"]) + 1e-6, f"setup/baseline at level {n}: {r}")
        e2e = (float(r["assembly"]) + float(r["time"])) / float(r["baseline"])
        check(abs(float(r["end_to_end"]) - e2e) <= 1e-3 * e2e + 1e-6, f"end_to_end at level {n}: {r}")
        # the fill of the contact-last factor: at least K's upper triangle
        # (3 x 3 blocks per node pair in 2D: more than the dofs)
        check(r["ordering"] in ("camd", "amd", "metis") and float(r["fill_camd"]) > int(r["dofs"]),
              f"ordering and fill at level {n}: {r['ordering']!r} {r['fill_camd']!r}")
        check(r["converged"] == "yes" and float(r["err_u"]) <= 1e-8, f"scaling row {r}")
    check("slopes (log time / log dofs)" in meta, "slopes in the header")

    # ---- scaling --set: a method's parameters, as solve --set gives them ----
    # (PDAS on the running bond wall: the closed start takes 8 iterations
    # at 1/10, the paper's start 12; the bench runs what solve runs)
    for sets in ([], ["--set", "start=closed"]):
        code, out, err = run("solve", "runningbond", "--level", "10", "--method", "pdas", *sets, "--json")
        want = json.loads(out)["iterations"] if code == 0 else None
        code, out, err = run("bench", "scaling", "runningbond", "--levels", "10", "--methods", "pdas", *sets,
                             "--repeat", "1", "--no-reference", "--json")
        j = json.loads(out) if code == 0 else {"meta": {}, "rows": []}
        got = [r["iterations"] for r in j["rows"]]
        check(code == 0 and want is not None and got == [want], f"bench scaling {sets}: {got} against solve's {want}")
        check(("start=closed" in j["meta"].get("parameters", "")) == bool(sets), f"the parameters line {j['meta']}")
    code, out, err = run("bench", "scaling", "runningbond", "--levels", "10", "--set", "start=closed")
    one_line_error(code, err, "--set 'start=closed': name the methods", status=2)
    code, out, err = run("bench", "scaling", "runningbond", "--levels", "10", "--methods", "pdas,graves",
                         "--set", "nope=1")
    one_line_error(code, err, "none of --methods pdas,graves has that parameter", status=2)
    code, out, err = run("bench", "scaling", "runningbond", "--levels", "10", "--methods", "pdas",
                         "--set", "start=open")
    one_line_error(code, err, "'open' is not in paper|closed", status=2)

    # ---- stress: a case that cannot converge is a row, not a crash ----
    code, out, err = run("bench", "stress", "hertz", "--level", "16", "--cases", "load-1e-8",
                         "--max-iter", "2", "--json", "--cache", cache)
    check(code == 0, f"stress with 2 iterations runs ({code}, {err})")
    j = json.loads(out)
    rows = [r for r in j["rows"] if r["method"] == "ssn-tresca"]
    check([r["case"] for r in rows] == ["nominal", "load-1e-8"], f"cases {[r['case'] for r in rows]}")
    for r in rows:
        check(r["converged"] is False and r["reason"] == "max_iter" and r["iterations"] == 2,
              f"forced failure row {r}")
        check(r["nonfinite"] is False and r["kkt"] is not None and r["kkt"] > 1e-10, "a finite kkt, not small")

    # a duplicated contact point: a row with the reason, whatever it is
    code, out, err = run("bench", "stress", "hertz", "--level", "8", "--cases", "coincident", "--json",
                         "--cache", cache)
    j = json.loads(out)
    rows = [r for r in j["rows"] if r["case"] == "coincident"]
    check(code == 0 and len(rows) >= 1 and all(r["reason"] for r in rows), f"coincident rows {rows}")

    # the perturbations do what they say: contact points at the end
    code, out, err = run("bench", "stress", "hertz", "slider", "--level", "8", "--cases", "gap-1,load",
                         "--methods", "ssn-tresca", "--json", "--cache", cache)
    j = json.loads(out)
    act = {(r["scene"], r["case"]): r["active"] for r in j["rows"] if r["converged"] is True}
    check(code == 0 and len(act) == 14, f"14 converged rows (gap-1 is a prefix of gap-1e-*): {act}")
    # slider: a gap of the body size, the punch's 0.01 cannot close it
    check(act.get(("slider", "nominal")) == 65 and act.get(("slider", "gap-1")) == 0, f"slider {act}")
    # hertz: the rigid translation closes any gap, the same contact zone
    check(act.get(("hertz", "gap-1")) == act.get(("hertz", "nominal")) == 5, f"hertz gap {act}")
    # hertz: a tiny load touches at the lowest point only, a huge one closes the whole arc (9 points)
    check(act.get(("hertz", "load-1e-8")) == 1 and act.get(("hertz", "load-1e4")) == 9, f"hertz loads {act}")

    # ---- stress: unit scaling keeps kkt and iterations ----
    # (ssn-tresca only: a method whose parameters carry units would rightly show FAIL)
    code, out, err = run("bench", "stress", "hertz", "slider", "--level", "8", "--cases", "units",
                         "--methods", "ssn-tresca", "--json", "--cache", cache)
    check(code == 0, f"stress units runs ({code}, {err})")
    j = json.loads(out)
    units = [r for r in j["rows"] if r["case"] == "units" and r["converged"] is not None]
    check(len(units) >= 2, f"units rows on hertz and slider: {len(units)}")
    for r in units:
        nominal = [q for q in j["rows"] if q["case"] == "nominal" and q["scene"] == r["scene"]
                   and q["method"] == r["method"]][0]
        check(r["iterations"] == nominal["iterations"] == r["nominal_iterations"],
              f"{r['scene']} {r['method']}: iterations {r['iterations']} vs {nominal['iterations']}")
        check(abs(r["kkt"] - nominal["kkt"]) <= 1e-12 * max(1.0, nominal["kkt"]),
              f"{r['scene']}: kkt {r['kkt']} vs {nominal['kkt']}")
        check(r["scale_err"] is not None and r["scale_err"] <= 1e-8, f"results scale: {r['scale_err']}")
        check(r["check"] == "ok", f"units check {r['check']}")

    # ---- Ctrl-C stops cleanly and keeps what finished ----
    p = subprocess.Popen([exe, "bench", "wp", "hertz", "--level", "32", "--repeat", "200", "--json",
                          "--methods", "ssn-tresca", "--cache", cache], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.5)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=60)
    check(p.returncode == 130, f"exit 130 after Ctrl-C, got {p.returncode} ({err})")
    try:
        j = json.loads(out)
        check("interrupted" in j["meta"], "the header says it was interrupted")
        check(all(r["converged"] is True for r in j["rows"]), "only finished runs are kept")
    except json.JSONDecodeError:
        check(False, f"valid JSON after Ctrl-C: {out[:200]!r}")
    check("interrupted" in err, f"a note on stderr: {err!r}")

    # ---- the progress bar, on a terminal only ----
    master, slave = pty.openpty()
    r = subprocess.run([exe, "bench", "wp", "hertz", "--level", "4", "--tols", "1e-4,1e-8", "--methods",
                        "ssn-tresca", "--cache", cache], stdout=subprocess.PIPE, stderr=slave, timeout=60)
    os.close(slave)
    bar = b""
    bar += drain(master)
    check(r.returncode == 0 and b"] 1/6 ssn-tresca rho=0.0001 tol 1e-04" in bar and b"s left" in bar,
          f"a progress bar with the case and the time left: {bar[:200]!r}")

    # ---- where the reference cache lives ----
    small = ["bench", "wp", "--level", "4", "--tols", "1e-8", "--methods", "ssn-tresca"]

    def refs_in(d):
        return sorted(f for f in os.listdir(d) if f.endswith(".ref")) if os.path.isdir(d) else []

    # $XDG_CACHE_HOME/signorini by default, nothing in the working directory
    xdg, work = os.path.join(tmp, "xdg"), os.path.join(tmp, "work")
    os.makedirs(work)
    code, out, err = run(*small, "hertz", cwd=work, env={"XDG_CACHE_HOME": xdg})
    check(code == 0 and err == "", f"bench with the default cache ({code}, {err!r})")
    check(len(refs_in(os.path.join(xdg, "signorini"))) == 1, f"the reference in $XDG_CACHE_HOME/signorini: "
          f"{refs_in(os.path.join(xdg, 'signorini'))}")
    check(os.listdir(work) == [], f"nothing written in the working directory: {os.listdir(work)}")
    # without $XDG_CACHE_HOME: ~/.cache/signorini
    home = os.path.join(tmp, "home")
    code, out, err = run(*small, "hertz", cwd=work, env={"XDG_CACHE_HOME": "", "HOME": home})
    check(code == 0 and len(refs_in(os.path.join(home, ".cache", "signorini"))) == 1,
          f"the reference in ~/.cache/signorini ({code}, {err!r})")
    # --cache DIR overrides both
    mine, xdg2 = os.path.join(tmp, "mine"), os.path.join(tmp, "xdg2")
    code, out, err = run(*small, "hertz", "--cache", mine, cwd=work, env={"XDG_CACHE_HOME": xdg2})
    check(code == 0 and len(refs_in(mine)) == 1 and not os.path.exists(xdg2),
          f"--cache DIR overrides $XDG_CACHE_HOME ({code}, {err!r}, {refs_in(mine)})")
    check(os.listdir(work) == [], "still nothing in the working directory")
    # a cache that cannot be a directory (a file in the way; root ignores
    # permissions): one warning, the run goes on uncached, exit 0 and the table
    blocker = os.path.join(tmp, "a-file")
    open(blocker, "w").close()
    for how in (["--cache", blocker], ["--cache", os.path.join(blocker, "sub")]):
        code, out, err = run(*small, "hertz", *how, cwd=work)
        lines = err.strip().splitlines()
        check(code == 0, f"an unwritable cache is no error ({how}: {code}, {err!r})")
        check(len(lines) == 1 and "warning" in lines[0] and blocker in lines[0],
              f"one warning line naming the cache: {lines!r}")
        check("ssn-tresca" in out and "err_u" in out and "# reference: ssn-tresca" in out
              and "computed, not kept" in out,
              f"the table, with a reference computed for this run: {out[-300:]!r}")
    check(os.path.getsize(blocker) == 0, "the file in the way is untouched")

    # ---- the key is the parsed scene's, not the file's path ----
    with open(os.path.join(scenes, "hertz.ini")) as f:
        hertz_ini = f.read()
    stiffer = hertz_ini.replace("\nE = 2000\n", "\nE = 4000\n")
    check(stiffer != hertz_ini, "the second scene differs (E)")
    piped = os.path.join(tmp, "piped")
    keys, hashes = [], []
    for text in (hertz_ini, stiffer, hertz_ini):
        path = os.path.join(tmp, "scene.ini")
        with open(path, "w") as f:
            f.write(text)
        with open(path) as f:
            code, out, err = run(*small, "/dev/stdin", "--json", "--cache", piped, stdin=f)
        check(code == 0, f"bench wp on a scene from a pipe ({code}, {err!r})")
        j = json.loads(out) if code == 0 else {"meta": {}, "rows": []}
        keys.append(j["meta"].get("reference", "").split("key ")[-1].split(",")[0])
        hashes.append(j["meta"].get("scene hash", "").split(" ")[0])
        check(j["rows"] and all(r["err_u"] is not None and r["err_u"] <= 1e-8 for r in j["rows"]),
              f"errors against this scene's own reference: {[r['err_u'] for r in j['rows']]}")
    check(keys[0] != keys[1] and hashes[0] != hashes[1] and len(refs_in(piped)) == 2,
          f"two scenes through /dev/stdin, two keys: {keys} {hashes} {refs_in(piped)}")
    check(keys[0] == keys[2] and hashes[0] == hashes[2] and len(set(hashes[0])) > 1,
          f"the same scene again, the same key and a real hash: {keys} {hashes}")
    # and the scene read by its id has that same content hash
    code, out, err = run(*small, "hertz", "--json", "--cache", piped)
    check(code == 0 and json.loads(out)["meta"]["scene hash"].startswith(hashes[0] + " "),
          f"'hertz' by id hashes as its content through a pipe: {out[:300]!r}")

    # ---- Ctrl-C once a case has started: exit 130, no temporary file ----
    # (stderr on a terminal, so the progress bar says when the first case runs)
    ctrlc = os.path.join(tmp, "ctrlc")
    os.makedirs(ctrlc)
    ctrlc_csv = os.path.join(ctrlc, "wp.csv")
    master, slave = pty.openpty()
    p = subprocess.Popen([exe, "bench", "wp", "hertz", "--level", "16", "--repeat", "1000", "--methods",
                          "ssn-tresca", "--csv", ctrlc_csv, "--cache", os.path.join(ctrlc, "refs")],
                         stdout=subprocess.PIPE, stderr=slave, cwd=ctrlc)
    os.close(slave)
    bar, deadline = b"", time.time() + 60
    while b"] 1/" not in bar and time.time() < deadline:
        ready, _, _ = select.select([master], [], [], 1)
        if ready:
            try:
                bar += os.read(master, 4096)
            except OSError:
                break
    check(b"] 1/" in bar, f"the first case started: {bar[:200]!r}")
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=60)
    bar += drain(master)
    check(p.returncode == 130, f"exit 130 after Ctrl-C in a case, got {p.returncode} ({bar[-300:]!r})")
    check(b"interrupted" in bar, "the note on stderr")
    check(b"# interrupted: yes" in out, f"the table printed, marked interrupted: {out[-200:]!r}")
    meta, rows = read_csv(ctrlc_csv) if os.path.exists(ctrlc_csv) else ({}, [])
    check("interrupted" in meta, "the CSV written whole, marked interrupted")
    left = [os.path.join(r, f) for r, _, fs in os.walk(ctrlc) for f in fs if ".tmp" in f]
    check(left == [], f"no temporary file after Ctrl-C: {left}")

    # a paper driver too: Ctrl-C after its first level, the table of the
    # levels that finished, exit 130
    p = subprocess.Popen([exe, "bench", "paper", "001"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    err, deadline = b"", time.time() + 60
    while b"level 2 done" not in err and time.time() < deadline:
        ready, _, _ = select.select([p.stderr], [], [], 1)
        if ready:
            chunk = os.read(p.stderr.fileno(), 4096)
            if not chunk:
                break
            err += chunk
    p.send_signal(signal.SIGINT)
    out, rest = p.communicate(timeout=60)
    err += rest
    check(p.returncode == 130, f"paper 001: exit 130 after Ctrl-C, got {p.returncode} ({err[-300:]!r})")
    levels = [l.split()[0] for l in out.decode().splitlines() if l[:5].strip().isdigit()]
    check(levels[:2] == ["1", "2"] and b"interrupted" in err,
          f"paper 001: the levels that finished are printed: {levels}, {err[-200:]!r}")

    # ---- errors: one line, nothing written ----
    code, out, err = run("bench", "wp")
    one_line_error(code, err, "missing SCENE", status=2)
    code, out, err = run("bench", "wp", "hertz", "--level", "4", "--methods", "ssn-tresca,ubr-c",
                         "--png", os.path.join(tmp, "nodir", "x.png"))
    one_line_error(code, err, "nodir")
    check(not os.path.exists(os.path.join(tmp, "nodir")), "no PNG written")
    png = os.path.join(tmp, "wp.png")
    code, out, err = run("bench", "wp", "hertz", "--level", "4", "--methods", "ssn-tresca,ubr-c", "--png", png)
    data = open(png, "rb").read() if os.path.exists(png) else b""
    check(code == 0 and data[:8] == b"\x89PNG\r\n\x1a\n" and b"work-precision: hertz level 4" in data,
          f"the work-precision plot as a PNG with its title chunk: {code} {err!r} {len(data)} bytes")
    code, out, err = run("bench", "scaling", "hertz")
    one_line_error(code, err, "--levels", status=2)
    code, out, err = run("bench", "scaling", "hertz", "--levels", "8..4")
    one_line_error(code, err, "--levels '8..4'", status=2)
    code, out, err = run("bench", "wp", "hertz", "--methods", "nope")
    one_line_error(code, err, "unknown method 'nope'", status=2)
    code, out, err = run("bench", "stress", "hertz", "--time-limit", "0")
    one_line_error(code, err, "--time-limit", status=2)
    code, out, err = run("bench", "wp", "hertz", "--level", "8", "--csv", os.path.join(tmp, "no/such/dir.csv"),
                         "--cache", cache)
    one_line_error(code, err, "cannot write")

shutil.rmtree(xdg_default, ignore_errors=True)
finish("bench")
