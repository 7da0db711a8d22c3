#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Geometry from Gmsh (issue 24): `[mesh] file = NAME.geo|NAME.msh`.

The shipped sphere at two levels: the mesh's node count is the helper's
(signorini-mesh run directly, its pipe header read here) and the VTU's,
the solve converges, the forces balance, and the 3D Hertz errors (contact
radius, pressure) fall with the level, below stated bounds at the finer
one. A render of the .geo scene is not blank (Gmsh and OSMesa in one
process give blank images: the helper process keeps them apart). Bad
inputs each give one `file:line: key` line and exit 1: a missing file, a
group the file lacks, a group of the wrong dimension, an element type we
do not have, an inverted element, a .geo Gmsh cannot read. A file path is
relative to the scene's folder, or to the working directory for a scene
read from a pipe."""
import json
import os
import re
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, exe, finish, one_line_error, png_read, run  # noqa: E402

SCENES = os.environ.get("SIGNORINI_SCENES", "")
MESHER = os.path.join(os.path.dirname(os.path.abspath(exe)), "src", "mesh", "signorini-mesh")


def helper_nodes(geo, level):
    """The nodes of the elements of the model's dimension in the helper's
    pipe (mesh/gmsh.c describes it): what the mesh keeps."""
    r = subprocess.run([MESHER, geo, str(level), "0", "1", "0"], capture_output=True, timeout=300)
    check(r.returncode == 0, f"signorini-mesh {geo} {level} exits 0 ({r.stderr!r})")
    data = r.stdout
    check(data[:8] == b"CXMESH01", "the pipe starts with its magic")
    dim, nnodes = struct.unpack("<iq", data[8:20])
    pos = 20 + 24 * nnodes
    (nblocks,) = struct.unpack("<i", data[pos:pos + 4])
    pos += 4
    used = set()
    for _ in range(nblocks):
        edim, _, _, npe, n = struct.unpack("<5i", data[pos:pos + 20])
        pos += 20
        conn = struct.unpack(f"<{npe * n}i", data[pos:pos + 4 * npe * n])
        pos += 4 * npe * n
        if edim == dim:
            used.update(conn)
    return len(used)


def vtu_points(path):
    with open(path, "rb") as f:
        head = f.read(1 << 16).decode("latin-1")
    m = re.search(r'NumberOfPoints="(\d+)"', head)
    return int(m.group(1)) if m else -1


def render_rows(scene):
    """The RGB rows of 'render SCENE --level 1' (it exits 0), or None in a
    build without the renderer."""
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, scene + ".png")
        code, out, err = run("render", scene, "--level", "1", "--png", path)
        if code == 1 and "render" in err and "not" in err:
            print("render: not in this build, skipped")
            return None
        check(code == 0, f"render {scene} exits 0 ({err.strip()})")
        if code != 0:
            return []
        png = png_read(path)
        check(png.channels == 3, f"{path}: 8-bit RGB")
        return png.rows


def solve_json(*args):
    code, out, err = run("solve", *args, "--json")
    check(code == 0, f"solve {' '.join(args)} exits 0 ({err.strip()})")
    return json.loads(out) if code == 0 else None


# ---- the sphere at two levels ----------------------------------------------
geo = os.path.join(SCENES, "sphere.geo")
results = {}
with tempfile.TemporaryDirectory() as tmp:
    for level in (1, 3):
        js = solve_json("sphere", "--level", str(level))
        if js is None:
            continue
        results[level] = js
        check(js["converged"], f"sphere level {level} converges")
        check(js["kkt_error"] <= 1e-10, f"level {level}: kkt {js['kkt_error']}")
        fa, fc = js["force"]["applied"], js["force"]["contact"]
        check(abs(fa[2] + fc[2]) <= 1e-8 * abs(fa[2]), f"level {level}: forces balance {fa} {fc}")
        check(140 < -fa[2] <= 150, f"level {level}: the eighth carries about P/4 = 150 ({fa[2]})")
        n = helper_nodes(geo, level)
        vtu = os.path.join(tmp, f"s{level}.vtu")
        code, out, err = run("solve", "sphere", "--level", str(level), "--vtu", vtu)
        check(code == 0, f"solve --vtu exits 0 ({err.strip()})")
        check(vtu_points(vtu) == n, f"level {level}: VTU points {vtu_points(vtu)} = Gmsh nodes {n}")
        # 3 dofs a node, less one per node of each symmetry plane
        check(js["dofs"] < 3 * n and js["dofs"] > 2 * n, f"level {level}: dofs {js['dofs']} of {n} nodes")
if 1 in results and 3 in results:
    h1, h3 = results[1]["contact_halfwidth"], results[3]["contact_halfwidth"]
    e1 = abs(h1["computed"] - h1["hertz"]) / h1["hertz"]
    e3 = abs(h3["computed"] - h3["hertz"]) / h3["hertz"]
    p1, p3 = results[1]["pressure_error_l2"]["rel"], results[3]["pressure_error_l2"]["rel"]
    print(f"sphere: a = {h1['hertz']:.4f}; level 1 radius {h1['computed']:.4f} ({100 * e1:.2f} %), "
          f"pressure {100 * p1:.1f} %; level 3 radius {h3['computed']:.4f} ({100 * e3:.2f} %), "
          f"pressure {100 * p3:.1f} %")
    check(abs(h1["hertz"] - 1.1789) < 1e-3, f"Hertz a = (3PR/4E*)^(1/3) = 1.1789 ({h1['hertz']})")
    check(e3 < e1, "the contact radius error falls with the level")
    check(p3 < p1, "the pressure error falls with the level")
    check(e3 < 0.02, f"level 3: contact radius within 2 % of Hertz ({100 * e3:.2f} %)")
    check(p3 < 0.10, f"level 3: pressure L2 error below 10 % ({100 * p3:.1f} %)")
code, out, err = run("solve", "sphere", "--level", "1")
check(re.search(r"contact radius [0-9.]+ computed, a = 1\.179 Hertz", out) is not None,
      "solve prints the contact radius beside Hertz's a")

# ---- ring (two obstacles, one body) and punch (two bodies, Coulomb) ----------
for scene, levels in (("ring", (1, 2)), ("punch", (1, 2))):
    for level in levels:
        js = solve_json(scene, "--level", str(level))
        if js is None:
            continue
        check(js["converged"] and js["method_auto"], f"{scene} level {level} converges with auto")
        n = helper_nodes(os.path.join(SCENES, scene + ".geo"), level)
        with tempfile.TemporaryDirectory() as tmp:
            vtu = os.path.join(tmp, "r.vtu")
            code, out, err = run("solve", scene, "--level", str(level), "--vtu", vtu)
            check(vtu_points(vtu) == n, f"{scene} level {level}: VTU points = Gmsh nodes {n}")
        fa, fc = js["force"]["applied"], js["force"]["contact"]
        if scene == "punch":
            fc = js["force"]["contact_bodies"][0]   # on the punch (body 1)
        if scene == "ring":
            # the pressure pushes the ring apart: the plates press back equally
            check(abs(fc[1]) <= 1e-8 and abs(fa[1]) <= 1e-8, f"ring: no net vertical force {fa} {fc}")
            check(js["active"] >= 2, f"ring level {level}: points in contact ({js['active']})")
        else:
            check(abs(fc[1] - 50) <= 1e-8 * 50, f"punch: the contact carries the punch's 50 ({fc})")
            check(js["stick"] > 0 and js["slip"] > 0,
                  f"punch level {level}: a stick zone and slip ({js['stick']} stick, {js['slip']} slip)")
            check(abs(fc[0]) <= 0.1 * fc[1], "punch: friction within F times the load")
    if scene == "punch":
        # the regions' materials count: the block as steel too changes the friction
        with tempfile.TemporaryDirectory() as tmp:
            text = open(os.path.join(SCENES, "punch.ini")).read()
            text = text.replace("E = 70000\nnu = 0.33", "E = 210000\nnu = 0.3")
            text = text.replace("file = punch.geo", "file = " + os.path.join(SCENES, "punch.geo"))
            same = os.path.join(tmp, "same.ini")
            open(same, "w").write(text)
            a, b = solve_json("punch"), solve_json(same)
            if a and b:
                fa, fb = a["force"]["contact_bodies"][0][0], b["force"]["contact_bodies"][0][0]
                print(f"punch: friction force {fa:.4f} (steel on aluminium), {fb:.4f} (steel on steel)")
                check(abs(fa - fb) > 0.03 * abs(fa), "the block's own material changes the result")
    # K is singular (held by contact alone): the dual methods refuse it
    code, out, err = run("solve", scene, "--method", "mprgp", "--friction", "none")
    one_line_error(code, err, "need K^-1", "not positive definite")
# ring: both plates carry the load (the VTU's contact points lie on both)
code, out, err = run("solve", "ring", "--json")
if code == 0:
    js = json.loads(out)
    check(js["contact_points"] > 20, "ring: the points of both contacts")

# ---- each contact its own F: a block on two feet, F = 0 on the left one --------
FEET_GEO = """h = 0.1;
Point(1) = {0, 0, 0, h}; Point(2) = {0.8, 0, 0, h}; Point(3) = {1.2, 0, 0, h};
Point(4) = {2, 0, 0, h}; Point(5) = {2, 1, 0, h}; Point(6) = {0, 1, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6}; Plane Surface(1) = {1};
Physical Curve("left_foot") = {1}; Physical Curve("right_foot") = {3};
Physical Curve("top") = {5}; Physical Curve("left") = {6}; Physical Surface("block") = {1};
"""
FEET = """[scene]
id = feet
dim = 2

[mesh]
file = feet.geo

[material]
E = 1000
nu = 0.3

[traction top]
boundary = top
t = 0.2 -1

[support left]
boundary = left
fix = x

[contact left]
boundary = left_foot
obstacle = plane
point = 0 0
normal = 0 1
friction = coulomb
F = 0

[contact right]
boundary = right_foot
obstacle = plane
point = 0 0
normal = 0 1
F = 1
"""
with tempfile.TemporaryDirectory() as tmp:
    open(os.path.join(tmp, "feet.geo"), "w").write(FEET_GEO)
    feet = os.path.join(tmp, "feet.ini")
    open(feet, "w").write(FEET)
    own, all1, all0 = solve_json(feet), solve_json(feet, "--F", "1"), solve_json(feet, "--F", "0")
    if own and all1 and all0:
        print(f"feet: own F {own['stick']} stick {own['slip']} slip; --F 1 {all1['stick']}/{all1['slip']}; "
              f"--F 0 {all0['stick']}/{all0['slip']}")
        # 9 points a foot; the left foot's corner node is held in x by the support
        check(own["slip"] == 8 and own["stick"] == 10, "own F: the left foot slips (F = 0), the right sticks")
        check(all1["slip"] == 0, "--F 1 acts on every contact: all stick")
        check(all0["slip"] == 17, "--F 0 acts on every contact: all slip but the held corner")
        check(all0["force"]["contact"][0] == 0, "--F 0: no friction force")

# ---- a pressure is a traction along the inward normal (on a generator's mesh too)
with tempfile.TemporaryDirectory() as tmp:
    text = open(os.path.join(SCENES, "hertz.ini")).read()
    check("[traction top]\nboundary = top\nt = 0 -100\n" in text, "hertz.ini loads its top by a traction")
    text = text.replace("[traction top]\nboundary = top\nt = 0 -100\n", "[pressure top]\nboundary = top\np = 100\n")
    p = os.path.join(tmp, "hertzp.ini")
    open(p, "w").write(text.replace("id = hertz", "id = hertzp"))
    a, b = solve_json("hertz", "--level", "8"), solve_json(p, "--level", "8")
    if a and b:
        check(b["force"]["applied"] == a["force"]["applied"], f"pressure 100 = traction (0, -100) ({b['force']})")
        check(abs(b["force"]["contact"][1] - a["force"]["contact"][1]) <= 1e-9 * 800, "the same contact force")
        check(b["iterations"] == a["iterations"], "the same run")

# ---- a render of a .geo scene is not blank -----------------------------------
rows = render_rows("sphere")
if rows is not None:
    check(len(rows) > 0, "the PNG decodes")
    # blank renders are one flat colour: count saturated (coloured) pixels
    coloured = sum(max(r[i:i + 3]) - min(r[i:i + 3]) > 40 for r in rows for i in range(0, len(r), 3))
    check(coloured > 2000, f"the render is not blank ({coloured} coloured pixels)")

# ---- the ring's two plates are both drawn -------------------------------------
# The obstacle's fill (0.86, 0.84, 0.80: 220 215 204 as cairo rounds) must appear above the
# ring and below it: the plate at y = 1 and the plate at y = -1.
rows = render_rows("ring")
if rows is not None:
    fill = bytes((220, 215, 204))
    hit = [y for y, r in enumerate(rows) if r.count(fill) > 100]
    h = len(rows)
    check(any(y < h // 4 for y in hit), f"the upper plate is drawn (rows with its fill: {hit[:3]}...)")
    check(any(y > h // 2 for y in hit), f"the lower plate is drawn (rows with its fill: {hit[-3:]})")

# ---- bad inputs: one line each, exit 1 ---------------------------------------
SCENE = """[scene]
id = t
dim = {dim}

[mesh]
file = {file}

[material]
E = 1000
nu = 0.3

[support base]
boundary = {support}
fix = all

[contact]
boundary = {contact}
obstacle = plane
point = {point}
normal = {normal}
"""

SQUARE = """SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 1, 1};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Curve("right") = {2};
Physical Surface("body") = {1};
Physical Point("corner") = {3};
"""

PRISMS = """Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5}; Point(3) = {0, 1, 0, 0.5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};
out[] = Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; };
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
Physical Volume("body") = {out[1]};
"""

# a bow tie: its curve loop crosses itself, Gmsh cannot mesh it
SELFX = """Point(1) = {0, 0, 0, 0.1}; Point(2) = {1, 1, 0, 0.1}; Point(3) = {1, 0, 0, 0.1};
Point(4) = {0, 1, 0, 0.1};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Curve("bottom") = {2}; Physical Curve("top") = {4}; Physical Surface("body") = {1};
"""

# two triangles of one surface, the second turned the other way
INVERTED = """$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
1 1 "bottom"
2 2 "body"
$EndPhysicalNames
$Entities
0 1 1 0
1 0 0 0 1 0 0 1 1 0
1 0 0 0 1 1 0 1 2 0
$EndEntities
$Nodes
2 4 1 4
1 1 0 2
1
2
0 0 0
1 0 0
2 1 0 2
3
4
1 1 0
0 1 0
$EndNodes
$Elements
2 3 1 3
1 1 1 1
1 1 2
2 1 2 2
2 1 2 3
3 1 4 3
$EndElements
"""


def scene_file(tmp, name, dim=2, file="m.geo", support="top", contact="bottom", extra=""):
    point, normal = ("0 -1", "0 1") if dim == 2 else ("0 0 -1", "0 0 1")
    text = SCENE.format(dim=dim, file=file, support=support, contact=contact, point=point,
                        normal=normal) + extra
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def line_of(path, key):
    """The line of the last key of that name."""
    found = 0
    with open(path) as f:
        for k, line in enumerate(f, 1):
            if line.split("=")[0].strip() == key:
                found = k
    return found


with tempfile.TemporaryDirectory() as tmp:
    for name, text in (("m.geo", SQUARE), ("prisms.geo", PRISMS), ("inv.msh", INVERTED),
                       ("broken.geo", "Point(1) = {0, 0, 0;\nLine(1) = {1, 7};\n"),
                       ("selfx.geo", SELFX)):
        with open(os.path.join(tmp, name), "w") as f:
            f.write(text)

    # a good 2D scene from the same file: it builds and solves
    good = scene_file(tmp, "good.ini")
    code, out, err = run("solve", good)
    check(code == 0, f"a .geo square solves ({err.strip()})")
    # from a pipe the path is relative to the working directory
    r = subprocess.run([os.path.abspath(exe), "solve", "/dev/stdin"], input=open(good).read(), capture_output=True,
                       text=True, cwd=tmp, timeout=300)
    check(r.returncode == 0, f"a piped scene finds m.geo in the working directory ({r.stderr.strip()})")
    with open(good) as f:   # standard input redirected from a file: the same rule
        r = subprocess.run([os.path.abspath(exe), "solve", "/dev/stdin"], stdin=f, capture_output=True,
                           text=True, cwd=tmp, timeout=300)
    check(r.returncode == 0, f"/dev/stdin from a file: m.geo in the working directory ({r.stderr.strip()})")
    r = subprocess.run([os.path.abspath(exe), "solve", "/dev/stdin"], input=open(good).read(), capture_output=True,
                       text=True, cwd="/", timeout=300)
    one_line_error(r.returncode, r.stderr, "/dev/stdin:6: key 'file'", "cannot read 'm.geo'")

    # a force on a physical point and a region's body force reach the load
    p = scene_file(tmp, "loads.ini", extra="\n[force push]\npoint = corner\nF = 0.5 -1\n\n"
                                           "[material heavy]\nregion = body\nE = 1000\nnu = 0.3\n"
                                           "body_force = 0 -2\n")
    js = solve_json(p)
    if js:
        fa = js["force"]["applied"]
        check(abs(fa[0] - 0.5) <= 1e-12 and abs(fa[1] + 3) <= 1e-12,
              f"point force (0.5, -1) + body force (0, -2) on the unit square = (0.5, -3): {fa}")

    p = scene_file(tmp, "missing.ini", file="nothere.geo")
    code, out, err = run("solve", p)
    one_line_error(code, err, f"{p}:6: key 'file'", "nothere.geo")

    p = scene_file(tmp, "nogroup.ini", contact="floor")
    code, out, err = run("solve", p)
    one_line_error(code, err, f"{p}:{line_of(p, 'boundary') + 0}", "key 'boundary'",
                   "no physical group 'floor'", "bottom (1D)")

    p = scene_file(tmp, "wrongdim.ini", support="body")
    code, out, err = run("solve", p)
    one_line_error(code, err, f"{p}:13: key 'boundary'", "'body'", "dimension 2",
                   "a boundary needs dimension 1")

    p = scene_file(tmp, "prisms.ini", dim=3, file="prisms.geo")
    code, out, err = run("solve", p)
    one_line_error(code, err, f"{p}:6: key 'file'", "physical group 'body'", "PRISM6",
                   "we have TRI3, TRI6, QUAD4, TET4, HEX8")

    p = scene_file(tmp, "inv.ini", file="inv.msh", support="bottom")
    code, out, err = run("solve", p)
    one_line_error(code, err, f"{p}:6: key 'file'", "inverted element", "'body'")

    p = scene_file(tmp, "broken.ini", file="broken.geo")
    code, out, err = run("solve", p)
    one_line_error(code, err, f"{p}:6: key 'file'", "broken.geo", "gmsh cannot read the file",
                   "line 1: syntax error")

    p = scene_file(tmp, "selfx.ini", file="selfx.geo")
    code, out, err = run("solve", p)
    one_line_error(code, err, f"{p}:6: key 'file'", "selfx.geo", "gmsh failed to mesh the geometry")

    p = scene_file(tmp, "badpoint.ini", extra="\n[force push]\npoint = top\nF = 0 -1\n")
    code, out, err = run("solve", p)
    one_line_error(code, err, "key 'point'", "'top'", "dimension 1", "a point needs dimension 0")

    p = scene_file(tmp, "region.ini", file="m.geo",
                   extra="\n[material steel]\nregion = bottom\nE = 1\nnu = 0.3\n")
    code, out, err = run("solve", p)
    one_line_error(code, err, "key 'region'", "a region needs dimension 2")

# ---- scene keys of user geometry ----------------------------------------------
with tempfile.TemporaryDirectory() as tmp:
    with open(os.path.join(tmp, "m.geo"), "w") as f:
        f.write(SQUARE)
    # a generator's keys with 'file'
    p = scene_file(tmp, "gen.ini")
    text = open(p).read().replace("file = m.geo", "file = m.geo\ncells = 4 4")
    open(p, "w").write(text)
    code, out, err = run("solve", p)
    one_line_error(code, err, f"{p}:7: key 'cells'", "not used with 'file'")
    # not a .geo or .msh
    p = scene_file(tmp, "ext.ini", file="m.stl")
    code, out, err = run("solve", p)
    one_line_error(code, err, f"{p}:6: key 'file'", "expected NAME.geo or NAME.msh")
    # regions need a Gmsh mesh
    p = os.path.join(tmp, "regiongen.ini")
    open(p, "w").write("[scene]\nid = t\ndim = 2\n\n[mesh]\ngenerator = rectangle\nlo = 0 0\n"
                       "hi = 1 1\n\n[material a]\nregion = body\nE = 1\nnu = 0.3\n\n"
                       "[contact]\nboundary = bottom\nobstacle = plane\npoint = 0 -1\nnormal = 0 1\n")
    code, out, err = run("solve", p)
    one_line_error(code, err, f"{p}:11: key 'region'", "physical groups of a Gmsh mesh")
    # one friction law per scene
    p = scene_file(tmp, "laws.ini", support="top", contact="bottom",
                   extra="friction = tresca\n\n[contact other]\nboundary = top\nobstacle = plane\n"
                         "point = 0 2\nnormal = 0 -1\nfriction = coulomb\n")
    code, out, err = run("solve", p)
    one_line_error(code, err, "key 'friction'", "one friction law per scene")
    # a 3D pair of bodies is refused
    p = scene_file(tmp, "pair3d.ini", dim=3, file="m.geo")
    text = open(p).read().replace("obstacle = plane\npoint = 0 0 -1\nnormal = 0 0 1\n", "master = top\n")
    open(p, "w").write(text)
    code, out, err = run("solve", p)
    one_line_error(code, err, "key 'master'", "contact between two bodies needs dim 2",
                   "3D two-body contact is not supported")
    # two contacts meeting at a node: the corner (1, 0) of bottom and right
    p = scene_file(tmp, "meet.ini", extra="\n[contact side]\nboundary = right\nobstacle = plane\n"
                                          "point = 2 0\nnormal = -1 0\n")
    code, out, err = run("solve", p)
    one_line_error(code, err, "[contact side]", "node", "at (1, 0)", "a point of one contact only")

finish("cli_gmsh")
