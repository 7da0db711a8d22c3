# SPDX-License-Identifier: GPL-3.0-or-later
"""The command line of every subcommand comes from its option table:
--help lists exactly the options the table has (and the parser knows each
of them), an unknown option and an out-of-range value are usage errors
(exit 2, one line), -V / --version print the version."""
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, run, usage_error  # noqa: E402

SOLVE = {"method", "friction", "F", "slip", "level", "tol", "max-iter", "stop", "time-limit", "set",
         "json", "baseline", "quiet", "backend", "vtu-series", "problem",
         "png", "field", "scale", "font-scale", "cmap", "range", "title", "no-title", "size", "view", "edges", "vtu", "vtu-ascii", "plot", "timing"}
SOLVE |= {"camera", "crop", "mirror"}   # render's camera and framing (issue 22)
SOLVE |= {"svg", "pdf", "log", "frames", "gif", "every"}   # render/: vector files, log scale, animation
BENCH = {"methods", "friction", "slip", "F", "max-iter", "time-limit", "repeat", "threads", "csv", "json",
         "png", "cache"}

# command, its options (today's names), an out-of-range value and what the message names
COMMANDS = [
    (["solve"], SOLVE, ["hertz", "--tol", "1"], "(0, 1)"),
    (["render"], SOLVE, ["hertz", "--png", "x.png", "--max-iter", "0"], "[1, 100000000]"),
    (["list"], {"json"}, None, None),
    (["export"], {"format", "friction", "F", "slip", "level"}, ["hertz", "--level", "0"], "[1, 1048576]"),
    (["version"], set(), None, None),
    (["tui"], {"level", "method", "friction", "mono", "ascii", "export-dir", "keys", "frames", "stats", "present",
              "backend"},
     ["--frames", "0"], "--frames '0'"),
    (["bench", "wp"], BENCH | {"level", "tols", "sweep"}, ["hertz", "--repeat", "0"], "[1, 1000]"),
    (["bench", "scaling"], BENCH | {"levels", "tol", "no-reference", "backend", "set"}, ["hertz", "--levels", "4", "--tol", "0"],
     "(0, 1)"),
    (["bench", "stress"], BENCH | {"level", "cases"}, ["--threads", "0"], "[1, 1024]"),
    (["bench", "paper", "000"], {"rows", "all", "first", "slip", "slip-nodal", "abar", "scene", "repeat"}, ["--rows", "22"], "[1, 21]"),
    (["bench", "paper", "001"], {"levels", "repeat", "no-solves", "gamma", "set"}, ["--repeat", "16"], "[1, 15]"),
    (["bench", "paper", "002"], {"quick", "tables"}, ["--tables", "9"], "--tables '9'"),
    (["bench", "paper", "003"], {"max-level", "small", "time-limit", "tables", "geometry", "gap"},
     ["--gap", "1"], "(0, 1)"),
]

OPTION_LINE = re.compile(r"^  (?:-(\w), )?--([A-Za-z][\w-]*)(\s|$)")


def help_options(out):
    """The long names of the option rows of a help text, and their short names."""
    names, shorts = [], {}
    for line in out.splitlines():
        m = OPTION_LINE.match(line)
        if m:
            names.append(m.group(2))
            if m.group(1):
                shorts[m.group(2)] = m.group(1)
    return names, shorts


for cmd, options, out_of_range, needle in COMMANDS:
    name = " ".join(cmd)
    for h in ("--help", "-h"):
        code, out, err = run(*cmd, h)
        check(code == 0 and err == "" and out.startswith("usage: signorini"), f"{name} {h}: {code} {err!r}")
    code, out, err = run(*cmd, "--help")
    names, shorts = help_options(out)
    check(len(names) == len(set(names)), f"{name}: each option once in the help: {names}")
    check(set(names) == options | {"help"}, f"{name}: the help lists {sorted(set(names) ^ (options | {'help'}))} "
                                            "beyond or short of the table")
    check(shorts.get("help") == "h", f"{name}: -h, --help")
    # the parser knows every option the help lists (and asks for a value where it takes one)
    for opt in names:
        if opt == "help":
            continue
        takes_value = re.search(r"^  --" + re.escape(opt) + r" \S", out, re.M) is not None
        code, _, err = run(*cmd, f"--{opt}" if takes_value else f"--{opt}=1")
        want = "needs a value" if takes_value else "takes no value"
        check(code == 2 and want in err and len(err.strip().splitlines()) == 1,
              f"{name} --{opt}: {want} (exit 2), got {code} {err!r}")
    # ranges are written from the table
    for opt in ("tol", "max-iter", "level"):
        if opt in options:
            line = next((l for l in out.splitlines() if l.startswith(f"  --{opt} ")), "")
            check("in " in out[out.find(line):out.find(line) + 300], f"{name}: --{opt} shows its range")
    # an unknown option: exit 2, one line naming it and the help
    code, out, err = run(*cmd, "--no-such-option")
    usage_error(code, err, "unknown option '--no-such-option'", f"signorini {name}")
    if out_of_range:
        code, out, err = run(*cmd, *out_of_range)
        usage_error(code, err, needle)

# one range per option everywhere: tol and max-iter read the same rows in solve and bench
for cmd in (["solve", "hertz"], ["bench", "scaling", "hertz", "--levels", "4"]):
    usage_error(*run(*cmd, "--tol", "0")[::2], "--tol '0'", "(0, 1)")
for cmd in (["solve", "hertz"], ["bench", "wp", "hertz"]):
    usage_error(*run(*cmd, "--max-iter", "100000001")[::2], "[1, 100000000]")
usage_error(*run("solve", "hertz", "--time-limit=0")[::2], "--time-limit '0'", "(0, inf)")
usage_error(*run("solve", "hertz", "--json", "--vtu", "-")[::2], "only one")   # options that exclude each other

# the top level: -V / --version / version, help, unknown command or option
out_v = run("version")[1]
check(re.fullmatch(r"signorini \d+\.\d+\.\d+\S*\n", out_v) is not None, f"version: {out_v!r}")
for v in ("-V", "--version"):
    code, out, err = run(v)
    check(code == 0 and out == out_v and err == "", f"{v}: {code} {out!r}")
code, out, err = run("--help")
check(code == 0 and "-V, --version" in out and "-h, --help" in out and "2 a malformed command line" in out,
      "signorini --help names -V and the exit status 2")
usage_error(*run("frobnicate")[::2], "unknown command 'frobnicate'")
usage_error(*run("--frobnicate")[::2], "unknown option '--frobnicate'")
code, out, err = run("bench")
check(code == 2 and "usage: signorini bench" in err and out == "", f"bench with no kind: usage on stderr, exit 2 "
                                                                     f"({code})")
usage_error(*run("bench", "nokind")[::2], "unknown kind 'nokind'")
usage_error(*run("bench", "paper", "999")[::2], "unknown paper '999'")
code, out, err = run("bench", "paper", "-h")
check(code == 0 and all(p in out for p in ("000", "001", "002", "003")), f"bench paper -h lists the papers: {err!r}")
# errors of the run stay 1
code, out, err = run("solve", "nosuchscene")
check(code == 1, f"an unknown scene is an error of the run (1), got {code}")

finish("usage")
