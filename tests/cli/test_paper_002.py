#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""bench paper 002 Table 4 (issue 23): the paper's CF-FP runs start cold,
so our cold-started run sits beside the paper's columns and our
warm-started one (the default) follows, both from real runs: the warm
start needs fewer Tresca iterations in all than the cold one."""
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, run  # noqa: E402

PAPER = {441: (9, 109), 1681: (8, 106), 6561: (13, 122)}   # Table 4, first three meshes
code, out, err = run("bench", "paper", "002", "--quick", "--tables", "4")
check(code == 0, f"bench paper 002 --quick --tables 4 exits 0 ({err.strip()})")
check("runs start cold" in out, "the table says the paper's runs start cold")
rows = re.findall(r"^\| (\d+) \| (\d+) \| (\d+)\*? \| (\d+) \| (\d+) \| (\d+) \| (\d+)\*? \| (\d+) \|", out, re.M)
check(len(rows) == 3, f"three levels printed ({len(rows)})")
for level, nodes, cfp, pfp, ctr, ptr, wfp, wtr in rows:
    nodes = int(nodes)
    check(nodes in PAPER and (int(pfp), int(ptr)) == PAPER[nodes],
          f"{nodes} nodes: the paper's fixed point / Tresca columns ({pfp}/{ptr})")
    check(int(wtr) < int(ctr), f"level {level}: warm start {wtr} Tresca iterations < cold {ctr}")
    check(3 <= int(cfp) <= 30, f"level {level}: cold fixed point iterations {cfp}")
finish("cli_paper_002")
