#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""solve's contact force per body (out/result.c): -(N'lN + T'lT) summed
over each body's nodes, so that a row between two bodies pushes both,
oppositely; force.contact is then the rigid obstacles' force alone. Checked
on twoblocks and punch (the bodies' forces are opposite), on stack bond
(every body free of supports balances its weight; the obstacle and the
ground rollers carry the wall) and on hertz (one body: unchanged)."""
import json
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, run  # noqa: E402


def solve_json(*args):
    code, out, err = run("solve", *args, "--json")
    check(code == 0, f"solve {' '.join(args)} --json exits 0 ({err.strip()})")
    return json.loads(out) if code == 0 else None


# ---- two bodies, node-to-segment: the upper body's force is minus the lower's
for scene, extra in (("twoblocks", ["--level", "10"]), ("punch", ["--level", "1"])):
    js = solve_json(scene, *extra)
    if js is None:
        continue
    f = js["force"]
    check(js["converged"], f"{scene} converges")
    check(f["bodies"] == 2 and len(f["contact_bodies"]) == 2, f"{scene}: two bodies ({f})")
    up, lo = f["contact_bodies"]
    scale = max(abs(v) for v in up)
    err = max(abs(a + b) for a, b in zip(up, lo)) / scale
    print(f"{scene}: on body 1 {up}, on body 2 {lo}; |f1 + f2| / |f1| = {err:.2e}")
    check(err <= 1e-10, f"{scene}: the contact on body 1 is minus that on body 2 (rel {err:.2e})")
    check(max(abs(v) for v in f["contact"]) <= 1e-10 * scale, f"{scene}: no rigid obstacle, no net contact force")
    check(f["bodies_on_obstacle"] == 0, f"{scene}: no body on a rigid obstacle")
    # the slave's points carry the whole of body 1's force (the master's share is on body 2)
    check(max(abs(a - b) for a, b in zip(f["points"], up)) <= 1e-10 * scale, f"{scene}: the points' sum is body 1's")
    # body 1's load goes into body 2 through the contact: it is not held otherwise in y
    check(up[1] > 0 and lo[1] < 0, f"{scene}: body 1 is pushed up, body 2 down")
    code, out, err = run("solve", scene, *extra)
    lines = re.findall(r"^ +contact on body (\d) x (\S+) y (\S+)$", out, re.M)
    check([int(b) for b, _, _ in lines] == [1, 2], f"{scene}: one text line per body ({lines})")
    check(all(abs(float(y) - v[1]) <= 1e-5 * scale for (_, _, y), v in zip(lines, (up, lo))),
          f"{scene}: the text lines carry the JSON's forces")
    check(re.search(r"^force: +applied .*;  from rigid obstacles x \S+ y \S+$", out, re.M) is not None,
          f"{scene}: the force line names the rigid obstacles' force")
js = solve_json("punch", "--level", "1")
if js:
    check(abs(js["force"]["contact_bodies"][0][1] - 50) <= 1e-8 * 50, "punch: the contact carries the punch's 50")

# ---- stack bond, level 5: 25 bodies of H = 0.2, course by course from the
# ground; sides on rollers in x, the ground's right half (x >= 1/2) in y, the
# left half on the settled plane. Weight of a body: H^2 (body force -1).
N, H = 5, 0.2
js = solve_json("stackbond", "--level", str(N))
if js:
    f = js["force"]
    bodies = f["contact_bodies"]
    check(f["bodies"] == N * N and len(bodies) == N * N, f"stackbond: {N * N} bodies ({f['bodies']})")
    w = H * H
    side = [b for b in range(N * N) if b % N in (0, N - 1)]
    roller = [2, 3, 4]          # bottom course, x in [0.4, 1]: over x >= 1/2
    errx = max(abs(bodies[b][0]) for b in range(N * N) if b not in side) / w
    erry = max(abs(bodies[b][1] - w) for b in range(N * N) if b not in roller) / w
    print(f"stackbond: bodies off the side rollers |fx| / w <= {errx:.2e}; off the ground rollers "
          f"|fy - w| / w <= {erry:.2e}")
    check(errx <= 1e-10, "stackbond: a body off the side rollers takes no net horizontal contact force")
    check(erry <= 1e-10, "stackbond: a body off the ground rollers is carried by the contact: f_y = its weight")
    tot = [sum(b[k] for b in bodies) for k in range(2)]
    check(max(abs(tot[k] - f["contact"][k]) for k in range(2)) <= 1e-10,
          f"stackbond: the bodies' forces sum to the obstacle's {f['contact']} ({tot})")
    # the ground rollers' reactions: what balances those bodies' weight and contact
    rollers = sum(-(-w + bodies[b][1]) for b in roller)
    bal = f["applied"][1] + f["contact"][1] + rollers
    print(f"stackbond: applied y {f['applied'][1]:.6g}, obstacle y {f['contact'][1]:.6g}, "
          f"rollers y {rollers:.6g}; sum {bal:.2e}")
    check(abs(f["applied"][1] + 1) <= 1e-12, "stackbond: the wall weighs 1")
    check(0 < f["contact"][1] < 1 and abs(bal) <= 1e-10, "stackbond: obstacle + rollers carry the wall")
    check(f["bodies_on_obstacle"] >= 2, f"stackbond: bodies on the plane ({f['bodies_on_obstacle']})")
    code, out, err = run("solve", "stackbond", "--level", str(N))
    m = re.search(r"^force: +applied x \S+ y (\S+);  from rigid obstacles x \S+ y (\S+) \(on (\d+) of (\d+) bodies\)$",
                  out, re.M)
    check(m is not None and int(m.group(4)) == N * N and int(m.group(3)) == f["bodies_on_obstacle"],
          f"stackbond: the text gives the obstacle's force and the body count ({m.group(0) if m else out})")
    check("contact on body" not in out, "stackbond: no line per body for 25 bodies")

# ---- one body: the output is as it was
js = solve_json("hertz", "--level", "8")
if js:
    f = js["force"]
    check(set(f) == {"applied", "contact"}, f"hertz: force has applied and contact only ({sorted(f)})")
    check(abs(f["contact"][1] + f["applied"][1]) <= 1e-9 * 800, "hertz: the contact balances the load")
    code, out, err = run("solve", "hertz", "--level", "8")
    check(re.search(r"^force: +applied x 0 y -800;  contact x \S+ y 800$", out, re.M) is not None,
          "hertz: the single-body force line")

finish("cli_body_forces")
