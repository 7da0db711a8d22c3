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
# the verdict on the sizes: every built row within 20 % of the paper's, said once per geometry
for N, nb, pnb, n, pn, nc, pnc in re.findall(r"^  1/(\d+)\s+(\d+)\s+(\d+)\s+(\d+)\s+(\d+)\s+(\d+)\s+(\d+)", out, re.M):
    for a, b in ((nb, pnb), (n, pn), (nc, pnc)):
        check(abs(int(a) - int(b)) <= 0.2 * int(b), f"1/{N}: {a} within 20 % of the paper's {b}")
check(out.count("verdict: n_b, n and n_c within 20 % of the paper's") == 3, "each geometry's sizes carry the verdict")
check("  differs:" not in out, "no size differs")

code, out, err = run("bench", "paper", "003", "--max-level", "15", "--tables", "5", "--geometry", "laminae")
check(code == 0, f"bench paper 003 --tables 5 (PDAS to 1/15, plain PDAS to 1/25) exits 0 ({err.strip()})")
m = re.findall(r"^  laminae +differs in time \(the paper's: Matlab 7 .*\); growth 1/10 -> 1/(?:15|25): ours x([\d.]+), "
               r"the paper's x([\d.]+)$", out, re.M)
check(len(m) == 2, f"each PDAS table says why its times differ, with the growth of both ({len(m)})")

code, out, err = run("bench", "paper", "003", "--max-level", "5", "--tables", "6", "--geometry", "laminae")
check(code == 0, f"bench paper 003 --tables 6 exits 0 ({err.strip()})")
check(out.count("the paper's PDPC has no projection") == 2, "both PDPC tables state the projection")
code, out, err = run("bench", "paper", "003", "--max-level", "5", "--tables", "5", "--geometry", "laminae")
check("the paper's PDPC has no projection" not in out, "the PDAS table does not carry the PDPC note")
finish("cli_paper_003")
