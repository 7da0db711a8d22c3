#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""`solve hertz` prints the computed contact half-width beside Hertz's b
(issue 23): the computed one comes from the run's contact set (p^2
extrapolated linearly in x^2 through the last two points in contact, kept
between the last point in contact and its open neighbour), so it changes
with the level, lies within 2 % of b at level 256 and further away at a
coarse level; the text line and the JSON carry the same numbers."""
import json
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, run  # noqa: E402

LINE = re.compile(r"half-width ([0-9.]+) computed, b = ([0-9.]+) Hertz")


def halfwidth(level):
    code, out, err = run("solve", "hertz", "--level", str(level))
    check(code == 0, f"solve hertz --level {level} exits 0 ({err.strip()})")
    m = LINE.search(out)
    check(m is not None, f"level {level}: the half-width line is printed")
    if m is None:
        return None, None
    code, js, err = run("solve", "hertz", "--level", str(level), "--json")
    check(code == 0, f"solve hertz --level {level} --json exits 0")
    h = json.loads(js)["contact_halfwidth"]
    check(abs(h["computed"] - float(m.group(1))) <= 1e-3 * h["hertz"], "text and JSON agree (computed)")
    check(abs(h["hertz"] - float(m.group(2))) <= 1e-3 * h["hertz"], "text and JSON agree (Hertz)")
    return h["computed"], h["hertz"]


coarse, b = halfwidth(8)
fine, b2 = halfwidth(256)
if coarse is not None and fine is not None:
    print(f"half-width: level 8 {coarse:.4f}, level 256 {fine:.4f}, Hertz b {b:.4f}")
    check(b == b2, "b is the scene's constant")
    check(abs(fine - b) <= 0.02 * b, f"level 256 within 2 % of b ({fine} against {b})")
    check(abs(coarse - b) > abs(fine - b), f"level 8 is further from b ({coarse})")
    check(abs(coarse - b) > 0.02 * b, "level 8 is more than 2 % off (the rule reads the mesh)")
finish("cli_hertz_halfwidth")
