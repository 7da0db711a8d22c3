#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Paper 000 from the command line: 'solve twoblocks' with the dual methods,
the refusal of Coulomb by mprgp, and 'bench paper 000' (first row: the
paper's n/m, our counts beside the paper's, bad options as one-line errors)."""
import json
import re
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, run  # noqa: E402


# ---- solve twoblocks with each paper-000 method ----
for method, friction in [("ssn-tresca-dual", "tresca"), ("ssn-tresca-glob", "tresca"), ("mprgp", "tresca"),
                         ("ssn-coulomb", "coulomb")]:
    code, out, err = run("solve", "twoblocks", "--level", "4", "--method", method, "--friction", friction,
                         "--json")
    check(code == 0, f"{method} converges on twoblocks (exit {code}, {err})")
    if code == 0:
        j = json.loads(out)
        check(j["dofs"] == 4 * 12 * 5 and j["contact_points"] == 12, f"{method}: n = 4m(m/3 + 1), m = 12")
        check(j["kkt_error"] < 1e-10, f"{method}: kkt {j['kkt_error']}")
        check(j["counts"]["factorizations"] >= 1, f"{method}: counts")

# ---- mprgp refuses Coulomb: one line, exit 1 ----
code, out, err = run("solve", "twoblocks", "--level", "2", "--method", "mprgp", "--friction", "coulomb")
check(code == 1 and len(err.strip().splitlines()) == 1 and "Coulomb" in err, f"mprgp refuses Coulomb: {err!r}")

# ---- bench paper 000 ----
code, out, err = run("bench", "paper", "000", "--help")
check(code == 0 and "--rows" in out, "bench paper 000 --help")
code, out, err = run("bench", "paper", "000", "--rows", "0")
check(code == 2 and len(err.strip().splitlines()) == 1 and "--rows" in err, f"--rows 0 is refused: {err!r}")
code, out, err = run("bench", "paper", "000", "--rows", "1")
check(code == 0, f"bench paper 000 --rows 1 (exit {code}, {err})")
row = [line for line in out.splitlines() if line.startswith("30600/150")]
check(len(row) == 1, f"one row 30600/150 in {out!r}")
if row:
    cells = row[0].split()
    # MPRGP nK(paper), SNM1 nK/kmax(paper), ...
    m = re.fullmatch(r"(\d+)\(181\)", cells[1])
    check(m is not None and 10 <= int(m.group(1)) <= 400, f"MPRGP cell {cells[1]}")
    m = re.fullmatch(r"(\d+)/(\d+)\(712/12\)", cells[2])
    check(m is not None and 2 <= int(m.group(2)) <= 15, f"SNM1 cell {cells[2]}")
    check("!" not in row[0], f"every method converged: {row[0]}")

finish("cli paper 000")
