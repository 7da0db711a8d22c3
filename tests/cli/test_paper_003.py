#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""bench paper 003 (issue 23): the "ours" body count of a built mesh is
counted from the mesh (connected components of its elements), marked 'f'
where the mesh is not built and the closed formula stands in; the PDPC
tables say that the paper's PDPC has no projection and ours adds one."""
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, run  # noqa: E402

code, out, err = run("bench", "paper", "003", "--max-level", "10", "--tables", "0")
check(code == 0, f"bench paper 003 --tables 0 exits 0 ({err.strip()})")
# the paper's body counts (Table 1) at 1/5 and 1/10
want = {"stackbond": (25, 100), "runningbond": (15, 55), "laminae": (5, 10)}
for geo, (n5, n10) in want.items():
    sec = out.split(geo + " (Tables 1-2)")[1] if geo + " (Tables 1-2)" in out else ""
    check(sec != "", f"{geo}: its size table is printed")
    for N, nb in ((5, n5), (10, n10)):
        m = re.search(rf"^  1/{N}\s+(\d+)\s+(\d+)\s", sec, re.M)
        check(m is not None and int(m.group(1)) == nb and int(m.group(2)) == nb,
              f"{geo} 1/{N}: counted bodies {m.group(1) if m else None} = {nb}")
    m = re.search(r"^  1/15\s+(\d+)f\s", sec, re.M)
    check(m is not None, f"{geo} 1/15 (not built): the formula's count is marked f")
check("connected components of the built mesh" in out, "the rule of the count is stated")

code, out, err = run("bench", "paper", "003", "--max-level", "5", "--tables", "6", "--geometry", "laminae")
check(code == 0, f"bench paper 003 --tables 6 exits 0 ({err.strip()})")
check(out.count("the paper's PDPC has no projection") == 2, "both PDPC tables state the projection")
code, out, err = run("bench", "paper", "003", "--max-level", "5", "--tables", "5", "--geometry", "laminae")
check("the paper's PDPC has no projection" not in out, "the PDAS table does not carry the PDPC note")
finish("cli_paper_003")
