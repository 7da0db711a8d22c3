#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""bench paper 001 (issue 23): the parameters the paper lost and we chose
(gamma of the approximation step, eps of the stopping rule) are printed
with the values the runs used; --gamma changes the runs and the line."""
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, run  # noqa: E402


def iters(out):
    rows = re.findall(r"^\s+([12])\s+\d+\s+\d+ \|.*\|\s+(\d+)\s+(\d+)\s*$", out, re.M)
    return {int(L): (int(a), int(b)) for L, a, b in rows}


code, out, err = run("bench", "paper", "001", "--levels", "1-2", "--no-solves", "--repeat", "1")
check(code == 0, f"bench paper 001 exits 0 ({err.strip()})")
check("chosen by us: gamma = 12" in out, "gamma = 12 is stated")
check("eps = 1e-12" in out, "eps = 1e-12 is stated")
check("tuned on this prism" in out, "how gamma was chosen is stated")
it = iters(out)
check(set(it) == {1, 2}, f"levels 1 and 2 are printed ({it})")
m = re.search(r"Our (\d+)-(\d+) steps against the paper's (\d+)-(\d+)", out)
check(m is not None, "the step ranges are compared")
if m and it:
    check(int(m.group(1)) == min(a for a, _ in it.values()) and int(m.group(2)) == max(a for a, _ in it.values()),
          "our range is the table's")
    check((int(m.group(3)), int(m.group(4))) == (5, 6), "the paper's range on levels 1-2 is 5-6")

# the verdict: every count more than 20 % off the paper's has a line with its reason
rows = re.findall(r"^\s+([12])\s+(\d+)\s+(\d+) \|.*\|\s+(\d+)\s+(\d+) \|.*\|\s+(\d+)\s+(\d+)\s*$", out, re.M)
lines = re.findall(r"^  differs: level (\d+), (nodes|contact nodes|Newton steps) (\d+) against the paper's (\d+) "
                   r"\([+-]\d+ %\): (.+)$", out, re.M)
check(out.count("  differs:") == len(lines) and len(lines) > 0, f"differs lines well formed ({len(lines)})")
named = {(int(L), w) for L, w, *_ in lines}
for L, w, a, b, why in lines:
    check(abs(int(a) - int(b)) > 0.2 * int(b) and len(why) > 20, f"level {L} {w}: {a} vs {b} off, with a reason")
for L, n, pn, c, pc, it, pit in rows:
    for w, a, b in (("nodes", n, pn), ("contact nodes", c, pc), ("Newton steps", it, pit)):
        if (int(L), w) not in named:
            check(abs(int(a) - int(b)) <= 0.2 * int(b), f"level {L} {w}: {a} within 20 % of {b}")
check((2, "nodes") not in named and (2, "contact nodes") not in named, "level 2's mesh is the paper's")

code, out2, err = run("bench", "paper", "001", "--levels", "1-2", "--no-solves", "--repeat", "1", "--gamma", "1")
check(code == 0, "bench paper 001 --gamma 1 exits 0")
check("gamma = 1," in out2 and "(--gamma" in out2, "the chosen gamma is stated")
it2 = iters(out2)
check(it2 != it and all(a > 20 for a, _ in it2.values()), f"gamma = 1 cycles (many steps: {it2})")

# --set passes a parameter to ssstar: the looser eps of the README's readings
# is stated and stops earlier (short of the solution); a bad one is a usage error
code, out3, err = run("bench", "paper", "001", "--levels", "1-2", "--no-solves", "--repeat", "1",
                      "--gamma", "16", "--set", "eps=1e-3")
check(code == 0, f"bench paper 001 --set eps=1e-3 exits 0 ({err.strip()})")
check("eps = 0.001, the relative residual" in out3 and "stop short of the solution" in out3,
      "the looser eps is stated with its consequence")
it3, it1 = iters(out3), iters(out)
check(set(it3) == {1, 2} == set(it1) and all(a < it1[L][0] for L, (a, _) in it3.items()),
      f"eps = 1e-3 takes fewer steps ({it3} against {it1})")
for bad in ("foo=1", "sweep=x"):
    code, _, err = run("bench", "paper", "001", "--levels", "1", "--set", bad)
    check(code == 2 and len(err.strip().splitlines()) == 1, f"--set {bad} is refused: {err!r}")
finish("cli_paper_001")
