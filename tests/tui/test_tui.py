#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The explorer end to end in a real terminal: tmux on a private socket,
a fixed size, keys sent, the pane captured and polled (no fixed sleeps).
Checks: the scene name; N step keys give iteration N and a falling kkt;
a parameter or tolerance change on ssn-tresca keeps "factorised: 1",
a friction change builds the second reduction (onto every contact dof)
once: "factorised: 2"; a second round of 'm' through the methods factorises
nothing (the counter read after the first round stays); the contact strip
shows stick and slip on 'slider' with Tresca; '?' shows the help; a
resize to 40x12 says "terminal too small" and back redraws; 'q' exits 0
and Ctrl-C 130 with the terminal restored; an export under a comma-decimal
locale (fr_FR.UTF-8, built with localedef) writes '.' decimals; ASCII without a UTF-8 locale."""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

exe = os.path.abspath(sys.argv[1])
failures = 0
checks = 0
if not shutil.which("tmux"):
    print("tmux not found (scripts/bootstrap.sh installs it)")
    sys.exit(1)

# one private server per start: a new server on a socket whose server was
# just killed can fail with "server exited unexpectedly"
sock = None
nstarts = 0
conf = tempfile.NamedTemporaryFile("w", suffix=".conf", delete=False)
conf.write("set -g remain-on-exit on\nset -g status off\n")
conf.close()
workdir = tempfile.mkdtemp(prefix="signorini-tui-")


def tmux(*args, check=True):
    r = subprocess.run(["tmux", "-L", sock, "-f", conf.name, *args], capture_output=True, text=True, timeout=30)
    if check and r.returncode != 0:
        raise RuntimeError(f"tmux {args}: {r.stderr}")
    return r.stdout


def check(cond, what):
    global failures, checks
    checks += 1
    if not cond:
        failures += 1
        print(f"FAIL: {what}")
        print(screen())


def screen():
    if not sock:
        return ""
    return tmux("capture-pane", "-t", "t", "-p", check=False)


def wait_for(pred, what, timeout=30.0):
    """Poll the pane until pred(text) holds; False after the timeout."""
    end = time.time() + timeout
    while time.time() < end:
        text = screen()
        if pred(text):
            return True
        time.sleep(0.05)
    state = tmux("display-message", "-p", "-t", "t",
                 "dead=#{pane_dead} status=#{pane_dead_status} signal=#{pane_dead_signal}", check=False)
    check(False, f"timed out waiting for {what} ({state.strip()})")
    return False


def has(s):
    return lambda text: s in text


def pane(fmt):
    return tmux("display-message", "-p", "-t", "t", fmt).strip()


def header():
    """(method, friction law, factorised count) read from the header line;
    None when the header is not there."""
    lines = screen().splitlines()
    m = re.search(r"│ (\S+) (none|tresca|coulomb)\s+│ factorised: (\d+)", lines[0] if lines else "")
    return (m.group(1), m.group(2), int(m.group(3))) if m else None


def status():
    """The status line: the last line that is not blank above the key bar."""
    lines = [l for l in screen().splitlines() if l.strip()]
    return lines[-2].strip() if len(lines) > 1 else ""


def status_block():
    """The status line with the lines above it (a long message wraps
    upwards), joined."""
    lines = [l.strip() for l in screen().splitlines() if l.strip()]
    return " ".join(lines[-5:-1])


def keybar():
    lines = [l for l in screen().splitlines() if l.strip()]
    return lines[-1] if lines else ""


def settled(what):
    """Wait until the explorer has read every key sent so far and the job
    they started has ended: keys are read in order, so the help opened by
    '?' shows that the keys before it were read; an unbound key ('z')
    closes it; then wait for the progress line to go."""
    keys("?")
    ok = wait_for(has("help: keys of the explorer"), f"the help (a barrier after {what})")
    keys("z")

    def calm(t):
        return "help: keys" not in t and "(keys still work)" not in t and header()

    # twice, 0.15 s apart: a capture can fall inside a redraw (the help
    # erased, the progress line not yet written), above all under ASan
    def calm_twice(t):
        if not calm(t):
            return False
        time.sleep(0.15)
        return calm(screen())
    return ok and wait_for(calm_twice, f"the job of {what} to end")


rcfile = os.path.join(workdir, "rc")


def start(cmd, lang="C.UTF-8", x=80, y=24, extra=""):
    """Run cmd in a new pane; its exit status goes to rcfile (tmux's own
    pane_dead_status is not always filled in when run under meson)."""
    global sock, nstarts
    if sock:
        tmux("kill-server", check=False)
    nstarts += 1
    sock = f"signorini-tui-{os.getpid()}-{nstarts}"
    if os.path.exists(rcfile):
        os.unlink(rcfile)
    env = f"LANG={lang} LC_ALL={lang} SIGNORINI_SCENES={os.environ.get('SIGNORINI_SCENES', '')} {extra}"
    tmux("new-session", "-d", "-s", "t", "-x", str(x), "-y", str(y), "-c", workdir,
         f"env {env} {cmd}; echo $? > {rcfile}.tmp && mv {rcfile}.tmp {rcfile}")


def keys(*k):
    tmux("send-keys", "-t", "t", *k)


def steps(text):
    """(iteration, kkt) of the rows of the step table."""
    rows = []
    for line in text.splitlines():
        m = re.match(r".{23}\s+(\d+) (\d\.\de[+-]\d\d) ", line)
        if m:
            rows.append((int(m.group(1)), float(m.group(2))))
    return rows


def exited_cleanly(how, want="0"):
    if wait_for(lambda t: os.path.exists(rcfile), f"the explorer to exit after {how}", 30):
        with open(rcfile) as f:
            rc = f.read().strip()
        check(rc == want, f"exit status {want} after {how}, got {rc}")
        check(pane("#{alternate_on}") == "0", f"the terminal left the alternate screen after {how}")


# ---- bad options: one line on stderr, before the screen opens; exit 2 for
# a malformed command line, 1 for an error of the run ----
for args, needle, want in [(["tui", "--nope"], "unknown option '--nope'", 2),
                             (["tui", "--level"], "'--level' needs a value", 2),
                             (["tui", "hertz", "--level", "99999"], "allows 1 to 2048", 1),
                             (["tui", "nope"], "unknown scene 'nope'", 1),
                             (["tui", "--method", "nope"], "unknown method 'nope'", 2),
                             (["tui", "--friction", "x"], "expected none, tresca or coulomb", 2)]:
    r = subprocess.run([exe, *args], capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == want and len(lines) == 1 and needle in r.stderr,
          f"{args}: {r.returncode} {r.stderr!r}")
# with no terminal, no argument prints the usage
r = subprocess.run([exe], capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL)
check(r.returncode == 0 and "usage:" in r.stdout, f"no argument without a terminal: {r.stdout!r}")

try:
    # ---- 'signorini' alone: the explorer on hertz --------------------------
    start(exe)
    wait_for(lambda t: "hertz L32" in t and "built in" in t, "hertz to be built")
    check(header() is not None and header()[2] == 1, f"factorised: 1 after the build: {header()}")
    keys("q")
    exited_cleanly("q after 'signorini' alone")

    # ---- the first run has solve's numbers ---------------------------------
    import json
    for scene in ("hertz", "slider", "laminae"):
        r = subprocess.run([exe, "solve", scene, "--method", "auto", "--json"], capture_output=True, text=True,
                           timeout=120, stdin=subprocess.DEVNULL)
        ref = json.loads(r.stdout)
        start(f"{exe} tui {scene}")
        wait_for(lambda t: "built in" in t, f"{scene} to be built")
        keys("r")
        wait_for(lambda t: "converged" in status(), f"the {scene} run to converge")
        runs = [l for l in screen().splitlines() if re.search(re.escape(ref["method"][:10]) + r"\s+(none|tresca|coulomb) ", l)]
        check(any(re.search(f"{ref['friction']} .* {ref['iterations']} .*  converged", l) for l in runs),
              f"{scene}: the runs table shows the law and the outcome in words: {runs}")
        keys("e")
        wait_for(has("runs written to"), f"the {scene} export")
        with open(os.path.join(workdir, f"signorini-{scene}-L{ref['level']}-runs.json")) as f:
            run = json.load(f)["runs"][0]
        last = run["steps"][-1]
        got = (run["method"], last["iter"], f"{last['kkt']:.3e}", run["factorizations"], last["solves"])
        want = (ref["method"], ref["iterations"], f"{ref['kkt_error']:.3e}", ref["counts"]["factorizations"],
                ref["counts"]["solves"])
        print(f"{scene}: explorer {got} solve {want}")
        check(got == want, f"{scene}: the first run (method, iterations, kkt, factorisations, solves) "
                           f"{got} equals solve --json's {want}")
        keys("q")
        exited_cleanly(f"q on {scene}")

    # ---- a refused switch changes nothing; 'f' visits every law -------------
    start(f"{exe} tui hertz --method ssn-tresca")
    wait_for(lambda t: "hertz L32" in t and "built in" in t, "hertz to be built")
    keys("r")
    wait_for(lambda t: "converged" in status(), "the run to converge")

    def strip_line(text):
        return [l for l in text.splitlines() if "pts" in l and "dofs" not in l]

    before = screen()
    # the dual methods are greyed from the build on (hertz's body has no
    # support in y: K is singular, known before any factorisation); 'm'
    # skips them, and typing one is refused at once with the reason
    check("factorised: 1" in before, "the screening of the methods factorised nothing (ssn-tresca's one)")
    keys("Enter", *["BSpace"] * 20)
    keys("-l", "ssn-tresca-dual")
    keys("Enter")
    wait_for(lambda t: "no support in y (held only by contact); use ssn-tresca" in status_block(),
             "the refusal in the status line, wrapped at whole words")
    check("factorised: 1" in screen(), "the refused switch factorised nothing")
    check(all(k in keybar() for k in ("m method", "f friction", "n scene", "v view", "e export", "p png")),
          f"the key bar stays and lists m f n v e p: {keybar()!r}")
    keys("r", "s", "p")
    wait_for(lambda t: "rendered to" in t or "rendering not available" in t, "'p' after the refusal")
    after = screen()
    check(steps(after) == steps(before) and steps(before), f"iterations and kkt unchanged: {steps(before)} / {steps(after)}")
    check(strip_line(after) == strip_line(before), f"the strip unchanged: {strip_line(before)} / {strip_line(after)}")
    png = re.search(r"-it(\d+)\.png", after)
    check(png is None or int(png.group(1)) == max(i for i, _ in steps(before)),
          f"'p' renders the converged iterate: {png and png.group(0)}")
    laws = []
    for _ in range(4):
        was = header()
        keys("f")
        settled("'f'")
        # the header names the law the session runs once the switch ended
        wait_for(lambda t: header() and was and header()[1] != was[1], "the header to show the new law")
        h = header()
        laws.append(h[1] if h else None)
        keys("r")
        # the status message, not a runs table row ("converged in N
        # iterations: kkt ..." only there; it may wrap, behind a 'cached' label)
        wait_for(lambda t: re.search(r"converged in \d+ iterations: kkt", status_block()) and header() is not None,
                 f"a run under {laws[-1]} to converge")
    check(laws == ["tresca", "coulomb", "none", "tresca"], f"'f' x4 visits the three laws and comes back: {laws}")
    keys("q")
    exited_cleanly("q after the laws")

    # ---- hertz on ssn-tresca -----------------------------------------------------
    start(f"{exe} tui hertz --method ssn-tresca")
    wait_for(lambda t: "hertz L32" in t and "built in" in t, "hertz to be built")
    check(header() == ("ssn-tresca", "none", 1), f"ssn-tresca, no friction, factorised: 1 after the build: {header()}")

    # ---- N step keys: iteration N, the kkt falls ---------------------------
    for _ in range(5):
        keys("s")
    wait_for(lambda t: any(i == 5 for i, _ in steps(t)), "iteration 5")
    rows = dict(steps(screen()))
    check(max(rows) == 5, f"iteration counter 5: {sorted(rows)}")
    check(rows.get(5, 1) < rows.get(1, 0), f"kkt falls from step 1 to 5: {rows}")

    # ---- parameter, friction, tolerance on ssn-tresca: once per reduction ------
    # (frictionless condenses onto the normal dofs, Tresca onto every
    # contact dof: the law change builds the second reduction, once)
    keys("Down", "Down", "Down", "Right")   # method -> tol -> max iter -> rho, x2
    wait_for(lambda t: re.search(r"rho\s+.0\.002", t) is not None, "rho 0.002")
    settled("the rho change")
    check(header() == ("ssn-tresca", "none", 1), f"factorised: 1 after the rho change: {header()}")
    keys("f")                     # Tresca; the cursor goes to the friction row
    wait_for(lambda t: header() is not None and header()[1] == "tresca", "Tresca in the header")
    settled("the friction change")
    check(header() == ("ssn-tresca", "tresca", 2), f"factorised: 2 after the friction change: {header()}")
    keys("Down", "Down", "Down", "Right")   # friction -> slip s -> method -> tol, x10
    wait_for(has("tolerance 1e-09"), "the tolerance 1e-09")
    check(re.search(r"tol\s+.1e-09", screen()) is not None, "tol 1e-09 in the setup")
    keys("r")
    wait_for(has("converged"), "the Tresca run to converge")
    check(header() == ("ssn-tresca", "tresca", 2),
          f"factorised: 2 after parameter, friction and tolerance changes: {header()}")

    # ---- 'm' round the methods twice: the second round factorises nothing ---------
    def round_of_methods(n):
        """Press 'm' until ssn-tresca is the session's method again (not a
        refusal that leaves it there); the (method, counter, status) seen."""
        seen = []
        for _ in range(60):
            keys("m")
            if not settled(f"'m' in round {n}"):
                break
            h, msg = header(), status()
            seen.append((h[0], h[2], msg))
            if h[0] == "ssn-tresca" and msg == "ssn-tresca ready (nothing reassembled)":
                return seen
        check(False, f"ssn-tresca back after round {n} of 'm': {seen}")
        return seen

    first = round_of_methods(1)
    nfact = header()[2] if header() else -1
    others = [m for m, _, msg in first if m != "ssn-tresca" and msg == f"{m} ready (nothing reassembled)"]
    check(others, f"round 1 of 'm' switched to other methods: {first}")
    counts = [f for _, f, _ in first]
    check(counts == sorted(counts) and counts[0] >= 1, f"the counter never goes down in round 1: {first}")
    second = round_of_methods(2)
    for n, seen in ((1, first), (2, second)):
        print(f"round {n} of 'm':", ", ".join(f"{m} [{f}]" + ("" if msg.startswith(m + " ready") else f" ({msg})")
                                            for m, f, msg in seen))
    check([m for m, _, _ in second] == others + ["ssn-tresca"],
          f"round 2 visits the methods round 1 switched to, skipping the refused ones: {first} / {second}")
    check(all(f == nfact for _, f, _ in second), f"factorised: {nfact} all through round 2: {second}")
    check(header() == ("ssn-tresca", "tresca", nfact), f"factorised: {nfact} after round 2: {header()}")

    # ---- help ----------------------------------------------------------------
    keys("?")
    wait_for(has("help: keys of the explorer"), "the help overlay")
    check("quit" in screen() and "one iteration" in screen(), "the help lists the keys")
    keys("Escape")
    wait_for(lambda t: "help: keys" not in t, "the help to close")

    # ---- resize down and back -------------------------------------------------
    tmux("resize-window", "-t", "t", "-x", "40", "-y", "12")
    wait_for(has("terminal too small"), "'terminal too small' at 40x12")
    tmux("resize-window", "-t", "t", "-x", "30", "-y", "10")
    wait_for(lambda t: "terminal too small: 30x10," in t and "needs 60x16; q quits" in t,
             "the whole size message at 30x10")
    tmux("resize-window", "-t", "t", "-x", "80", "-y", "24")
    wait_for(lambda t: f"factorised: {nfact}" in t and "─ runs ─" in t, "the full screen back at 80x24")
    check(pane("#{pane_dead}") == "0", "alive after the resizes")

    # ---- export ----------------------------------------------------------------
    keys("e")
    wait_for(has("runs written to"), "the export")
    check(os.path.exists(os.path.join(workdir, "signorini-hertz-L32-runs.csv")), "the CSV is written")
    check(os.path.exists(os.path.join(workdir, "signorini-hertz-L32-runs.json")), "the JSON is written")

    # ---- slider with Tresca: stick and slip in the strip --------------------------
    keys("q")
    exited_cleanly("q on hertz")
    start(f"{exe} tui slider --friction tresca")
    wait_for(lambda t: "slider L4" in t and "built in" in t, "slider to be built")
    check(header() == ("ssn-tresca", "tresca", 1), f"slider on ssn-tresca with Tresca: {header()}")
    keys("r")
    wait_for(has("converged"), "the slider run to converge")
    strip = [l for l in screen().splitlines() if "pts" in l and "dofs" not in l]
    check(len(strip) == 1 and "●" in strip[0] and ("▶" in strip[0] or "◀" in strip[0]),
          f"stick and slip symbols in the strip: {strip}")

    # ---- q: exit 0, terminal restored -------------------------------------------
    keys("q")
    exited_cleanly("q")

    # ---- Ctrl-C on a large terminal, monochrome ---------------------------------------
    start(f"{exe} tui slider --mono", x=160, y=48)
    wait_for(has("built in"), "slider at 160x48")
    check("deformed mesh" in screen(), "the mesh view beside the plot on a wide terminal")
    keys("C-c")
    exited_cleanly("Ctrl-C", "130")   # as the other subcommands: 128 + SIGINT

    # ---- presentation mode: paced, the source in the header, Esc pauses ----------
    start(f"{exe} tui hertz --present")
    wait_for(has("built in"), "hertz --present")
    check("000 §4.2" in screen() and "elastic cylinder" in screen(),
          "presentation: the scene's description and the method's source in the header")
    check("{ } pace" in keybar(), f"presentation: the pace keys in the key bar: {keybar()!r}")
    keys("r")
    # at 2 steps a second the class sees the iterations one by one: the
    # newest row of the table takes several values before convergence
    seen = set()
    wait_for(lambda t: (seen.add(max((i for i, _ in steps(t)), default=0)) or "run ended" in t
                        or "converged" in t), "the paced run to converge")
    check(len(seen - {0}) >= 3, f"presentation: the run paced, newest iterations seen {sorted(seen)}")
    keys("x", "r")
    wait_for(lambda t: steps(t) and steps(t)[-1][0] >= 1, "a second paced run to start")
    keys("Escape")
    wait_for(has("paused"), "Esc to pause the paced run")
    keys("q")
    exited_cleanly("q in presentation mode")

    # ---- Ctrl-Z suspends to the shell, fg restores the screen ---------------------
    start("bash --norc --noprofile -i", extra="PS1='sh$ '")
    wait_for(has("sh$"), "an interactive shell")
    keys(f"{exe} tui hertz", "Enter")
    wait_for(has("built in"), "the explorer under a shell")
    keys("s")
    wait_for(lambda t: steps(t) and steps(t)[-1][0] == 1, "one step before Ctrl-Z")
    keys("C-z")
    wait_for(lambda t: "Stopped" in t and "factorised" not in t, "Ctrl-Z to stop the explorer")
    keys("fg", "Enter")
    wait_for(lambda t: "factorised" in t and steps(t) and steps(t)[-1][0] == 1, "fg to restore the screen")
    keys("s")
    check(wait_for(lambda t: steps(t) and steps(t)[-1][0] == 2, "a step after fg"), "keys work after fg")
    keys("q")
    wait_for(has("sh$"), "the shell after q")
    keys("exit", "Enter")
    exited_cleanly("exit from the shell")

    # ---- quitting mid-build still prints --stats ----------------------------------
    statsfile = os.path.join(workdir, "stats")
    start(f"{exe} tui hertz --level 1024 --stats 2>{statsfile}")
    # the status line names the level being built; which phase it shows
    # (building, factorising) depends on how loaded the machine is
    wait_for(lambda t: "building" in t or "level 1024:" in t, "a large build to start")
    keys("q")
    exited_cleanly("q during a build")
    with open(statsfile) as f:
        st = f.read()
    check("explorer:" in st and "redraws" in st, f"--stats printed when quitting mid-build: {st!r}")

    # ---- the mouse (SGR 1006 reports): click a row, wheel a value, click a run ----
    start(f"{exe} tui hertz --method ssn-tresca")
    wait_for(lambda t: "hertz L32" in t and "built in" in t, "hertz to be built")
    keys("r")
    wait_for(lambda t: re.search(r"converged in \d+ iterations: kkt", status_block()), "the first run to converge")

    def sgr(button, x, y):
        """A press at column x, row y (1-based), as a terminal reports it."""
        keys("-l", f"\x1b[<{button};{x};{y}M")

    def row_of(text, what):
        return next((i for i, l in enumerate(text.splitlines()) if what in l), None)

    sgr(0, 3, row_of(screen(), "tol ") + 1)
    wait_for(lambda t: re.search(r"tol\s+.1e-10", t) and "◂1e-10" in t, "a click on the tol row selects it")
    sgr(64, 3, row_of(screen(), "friction") + 1)   # the wheel up: the next law
    wait_for(lambda t: header() and header()[1] == "tresca", "the wheel on the friction row to choose tresca")
    keys("r")   # Tresca builds its reduction (onto every contact dof) once
    wait_for(lambda t: re.search(r"converged in \d+ iterations: kkt", status_block()) and header()[2] == 2,
             "the Tresca run to converge")
    sgr(65, 3, row_of(screen(), "friction") + 1)   # the wheel down: back to none
    wait_for(lambda t: header() and header()[1] == "none", "the wheel on the friction row to choose none again")
    keys("r")
    wait_for(lambda t: re.search(r"cached \(0 fact\.\): converged in \d+ iterations: kkt", status_block()),
             "the third run to converge, said to be served by the cache")
    t = screen()
    check(any("■ ssn-tresca none" in l and "cached" in l for l in t.splitlines()),
          "the runs table labels the later run cached")
    check("cached: 0 fact." in t, "the session block says the run factorised nothing")
    check(header()[2] == 2, f"factorised stays 2: {header()}")
    y = row_of(t, "■ ssn-tresca tresca")
    sgr(0, t.splitlines()[y].index("■ ssn-tresca tresca") + 4, y + 1)
    wait_for(lambda t: "run 2 highlighted: ssn-tresca" in status_block(), "a click on the Tresca run highlights it")
    keys("q")
    exited_cleanly("q after the mouse")

    # ---- Esc abandons a build: the UI is back at once, on the level it had -------
    start(f"{exe} tui block3d --stats 2>{statsfile}", x=100, y=30)
    wait_for(lambda t: "block3d L4" in t and "built in" in t, "block3d to be built")
    keys("]")
    wait_for(lambda t: "block3d L8" in t and "built in" in t, "block3d level 8 to be built")
    check(re.search(r"level\s+.8 7\.5k dofs", screen()) is not None, "the level row shows the dofs")
    keys("]", "Escape")
    wait_for(lambda t: "abandoned" in status_block(), "Esc to abandon the build of level 16", timeout=5)
    check("block3d level 8 kept" in status_block() and "block3d L8" in screen(),
          f"the level built before is kept: {status_block()!r}")
    keys("s")
    wait_for(lambda t: steps(t), "a step on level 8 after the abandoned build")
    keys("q")
    exited_cleanly("q after an abandoned build")
    with open(statsfile) as f:
        check("explorer:" in f.read(), "--stats printed after an abandoned build")

    # ---- the level on the command line: the scene's default level is built
    # first and measures it; one that does not fit in the free memory
    # (SIGNORINI_MEMAVAILABLE stands in for /proc/meminfo) is refused with the
    # estimate, and the UI goes on on the level built ----
    start(f"{exe} tui block3d --level 16", x=100, y=30, extra="SIGNORINI_MEMAVAILABLE=100e6")
    wait_for(lambda t: "refused" in status_block(), "level 16 to be refused")
    msg = status_block()
    m = re.search(r"level 16 refused: about ([\d.e+]+) dofs need about (\d+) MB, and 100 MB of memory is "
                  r"available \(SIGNORINI_MEMAVAILABLE\); block3d level 4, built to measure it, is open", msg)
    check(m is not None, f"the refusal gives the estimate and the memory available: {msg!r}")
    if m:
        # block3d 16 has 54 417 dofs; its build peaks near 600 MB (README)
        check(27e3 < float(m.group(1)) < 110e3 and 300 < int(m.group(2)) < 1200, f"the estimate: {m.groups()}")
    check("block3d L4" in screen(), "level 4 is open")
    keys("s")
    wait_for(lambda t: steps(t), "a step on level 4 after the refusal")
    keys("q")
    exited_cleanly("q after a refused first level")

    # a level that fits is built after the measuring one, without a key
    start(f"{exe} tui block3d --level 8", x=100, y=30, extra="SIGNORINI_MEMAVAILABLE=100e9")
    wait_for(lambda t: "block3d L8" in t and "built in" in status_block(), "block3d level 8 to be built")
    check(re.search(r"level\s+.8 7\.5k dofs", screen()) is not None, "the level row shows level 8's dofs")
    keys("q")
    exited_cleanly("q after level 8")

    # ---- scripted sessions end by themselves ------------------------------------
    start(f"{exe} tui slider --keys rq")
    exited_cleanly("the scripted keys 'rq'")
    start(f"{exe} tui slider --frames 3")
    exited_cleanly("--frames 3")

    # ---- a comma-decimal locale: numbers stay in the C locale -------------------
    # fr_FR.UTF-8 is built into a private directory (LOCPATH): no root needed;
    # localedef and the locale sources come with Debian's 'locales'
    locdir = os.path.join(workdir, "locales")
    os.makedirs(locdir)
    lr = subprocess.run(["localedef", "-i", "fr_FR", "-f", "UTF-8", os.path.join(locdir, "fr_FR.UTF-8")],
                        capture_output=True, text=True, timeout=120)
    check(os.path.isdir(os.path.join(locdir, "fr_FR.UTF-8")), f"localedef builds fr_FR.UTF-8: {lr.stderr[-300:]}")
    probe = subprocess.run(["/usr/bin/python3", "-c", "import locale; locale.setlocale(locale.LC_ALL, ''); "
                            "print(locale.localeconv()['decimal_point'])"], capture_output=True, text=True,
                           env={**os.environ, "LOCPATH": locdir, "LC_ALL": "fr_FR.UTF-8"})
    check(probe.stdout.strip() == ",", f"the locale's decimal point is a comma: {probe.stdout!r}")
    expdir = os.path.join(workdir, "fr")
    os.makedirs(expdir)
    start(f"{exe} tui laminae --friction tresca --export-dir {expdir}", lang="fr_FR.UTF-8", extra=f"LOCPATH={locdir}")
    wait_for(lambda t: "built in" in t, "laminae under fr_FR.UTF-8")
    keys("r")
    wait_for(lambda t: "converged" in status(), "the run under fr_FR.UTF-8")
    keys("e")
    wait_for(has("runs written to"), "the export under fr_FR.UTF-8")
    keys("n")   # the next scene file is read under the same locale
    wait_for(lambda t: "built in" in t and "laminae L" not in t, "the next scene under fr_FR.UTF-8")
    check("expected a number" not in screen(), "the next scene reads under fr_FR.UTF-8")
    keys("C-c")
    exited_cleanly("Ctrl-C under fr_FR.UTF-8", "130")
    import csv as csvmod
    base = os.path.join(expdir, "signorini-laminae-L5-runs")
    try:
        with open(base + ".json") as f:
            data = json.load(f)
        run = data["runs"][-1]
        check(isinstance(run["coef"], (int, float)) and isinstance(run["steps"][-1]["kkt"], float)
              and run["steps"][-1]["kkt"] < 1e-10 and "," not in run["params"],
              f"the JSON parses with numbers: coef {run['coef']!r}, params {run['params']!r}")
        with open(base + ".csv") as f:
            rows = list(csvmod.DictReader(f))
        check(rows and all("," not in v for r in rows for k, v in r.items() if k in ("coef", "kkt", "time_s")),
              f"the CSV's numbers have '.' decimals: {rows[:1]}")
        check(float(rows[-1]["kkt"]) == run["steps"][-1]["kkt"] or abs(float(rows[-1]["kkt"]) - run["steps"][-1]["kkt"]) < 1e-20,
              "CSV and JSON agree")
    except (OSError, ValueError, KeyError) as e:
        check(False, f"the export under fr_FR.UTF-8 reads back: {e}")

    # ---- no UTF-8 locale: ASCII -------------------------------------------------
    start(f"{exe} tui slider", lang="C")
    wait_for(has("built in"), "slider in the C locale")
    keys("r")
    wait_for(has("converged"), "the run in ASCII")
    text = screen()
    strip = [l for l in text.splitlines() if "pts" in l and "dofs" not in l]
    check(len(strip) == 1 and "o" in strip[0] and (">" in strip[0] or "<" in strip[0]),
          f"ASCII stick and slip symbols: {strip}")
    check(all(ord(c) < 128 for c in text), "only ASCII on the screen")
    keys("q")
    exited_cleanly("q in ASCII")
finally:
    if sock:
        tmux("kill-server", check=False)
    os.unlink(conf.name)
    shutil.rmtree(workdir, ignore_errors=True)

print(f"tui: {checks} checks, {failures} failed")
sys.exit(1 if failures else 0)
