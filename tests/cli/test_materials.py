#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Materials per element (issue 24): a `[material NAME] region = GROUP` may
split one connected body between materials.

(a) The shipped coated block with both regions given the SAME material
    solves to the displacement of the scene with one [material], to 1e-12
    (relative to the largest displacement), with the same kkt error and
    iteration count.
(b) A bar of two materials in series (one body, the regions share the
    nodes of x = L1), plane stress, pulled by an axial traction s: the
    end displacement is s (L1/E1 + L2/E2); with nu_i / E_i equal on both
    sides the uniaxial state is exact for linear elements, so the FE
    value agrees to 1e-9 relative, and u_y on top is -nu_i s H / E_i.
(c) The VTU read back by VTK: the cell arrays material, young_modulus and
    poisson_ratio give each cell its region's values (the coating's
    cells above y = -t, the substrate's below), one body.
(d) The PETSc backend (when built) assembles the same split body: its
    displacement agrees with the direct path's.
(e) Elements in no region take [material]: the coating as its only
    [material NAME] and E = 100 as [material] solve to the coated scene's
    displacement to 1e-12; two regions of different materials that
    overlap are refused in one line, exit 1.
Usage: test_materials.py SIGNORINI"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import clicheck  # noqa: E402
from clicheck import check, finish, one_line_error, run  # noqa: E402

clicheck.exe = os.path.abspath(clicheck.exe)   # the runs below work in a temporary folder

SCENES = os.environ.get("SIGNORINI_SCENES", "")
COATED = os.path.join(SCENES, "coated.ini")


def read_vtu(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def solve(tmp, scene, name, *extra):
    vtu = os.path.join(tmp, name + ".vtu")
    code, out, err = run("solve", scene, "--vtu", vtu, "--json", "--quiet", *extra, cwd=tmp)
    check(code == 0, f"solve {name} exits 0 ({code}: {err[-400:]})")
    if code != 0:
        return None, None
    return json.loads(out), read_vtu(vtu)


def point(g, name):
    a = g.GetPointData().GetArray(name)
    check(a is not None, f"point array {name}")
    return vtk_to_numpy(a) if a is not None else None


def cell(g, name):
    a = g.GetCellData().GetArray(name)
    check(a is not None, f"cell array {name}")
    return vtk_to_numpy(a) if a is not None else None


def coated_text(mats):
    """The shipped coated.ini with its two [material NAME] sections replaced."""
    with open(COATED) as f:
        text = f.read()
    head, rest = text.split("[material coating]", 1)
    tail = rest.split("[support cut]", 1)[1]
    return head + mats + "\n[support cut]" + tail


with tempfile.TemporaryDirectory() as tmp:
    shutil.copy(os.path.join(SCENES, "coated.geo"), tmp)

    # (a) the same material in both regions = one [material]
    same = os.path.join(tmp, "same.ini")
    one = os.path.join(tmp, "one.ini")
    with open(same, "w") as f:
        f.write(coated_text("[material coating]\nregion = coating\nmodel = plane_strain\nE = 100\n"
                            "nu = 0.3\n\n[material substrate]\nregion = substrate\n"
                            "model = plane_strain\nE = 100\nnu = 0.3\n"))
    with open(one, "w") as f:
        f.write(coated_text("[material]\nmodel = plane_strain\nE = 100\nnu = 0.3\n"))
    for level in ("1", "2"):
        js, gs = solve(tmp, same, "same" + level, "--level", level, "--method", "ssn-tresca")
        jo, go = solve(tmp, one, "one" + level, "--level", level, "--method", "ssn-tresca")
        if gs is None or go is None:
            continue
        us, uo = point(gs, "displacement"), point(go, "displacement")
        scale = float(np.abs(uo).max())
        diff = float(np.abs(us - uo).max())
        check(us.shape == uo.shape and scale > 0 and diff <= 1e-12 * scale,
              f"level {level}: two regions of one material = one [material] "
              f"(max |du| {diff:.3e} of max |u| {scale:.3e})")
        check(js["iterations"] == jo["iterations"], f"level {level}: same iterations "
              f"({js['iterations']} vs {jo['iterations']})")
        check(js["kkt_error"] == jo["kkt_error"], f"level {level}: the same kkt error "
              f"({js['kkt_error']:.3e} vs {jo['kkt_error']:.3e})")
        mat = cell(gs, "material")
        check(mat is not None and set(mat.tolist()) == {0, 1}, "two material ids in the split scene")

    # (c) the shipped coated scene: the per-cell material fields
    jc, gc = solve(tmp, COATED, "coated", "--method", "ssn-tresca")
    if gc is not None:
        mat, E, nu = cell(gc, "material"), cell(gc, "young_modulus"), cell(gc, "poisson_ratio")
        body = cell(gc, "body")
        check(set(body.tolist()) == {0}, "coated is one body")
        centres = vtk.vtkCellCenters()
        centres.SetInputData(gc)
        centres.Update()
        yc = vtk_to_numpy(centres.GetOutput().GetPoints().GetData())[:, 1]
        top = yc > -0.1
        check(top.any() and (~top).any(), "cells on both sides of the interface")
        check(np.all(E[top] == 1000) and np.all(E[~top] == 100),
              "young_modulus: 1000 in the coating (y > -0.1), 100 below")
        check(np.all(mat[top] == 0) and np.all(mat[~top] == 1),
              "material: 0 (coating, its first [material NAME]) above, 1 below")
        check(np.all(nu == 0.3), "poisson_ratio 0.3 everywhere")
        # the stiff coating bridges: a narrower contact, a larger force than
        # on the bare substrate (one.ini: E = 100 everywhere) at one approach
        js1, _ = solve(tmp, one, "one1b", "--level", "1", "--method", "ssn-tresca")
        if js1 and jc:
            check(jc["active"] < js1["active"],
                  f"the coating narrows the contact ({jc['active']} < {js1['active']} points)")
            fc, fb = -jc["force"]["contact"][1], -js1["force"]["contact"][1]
            check(fc > 1.1 * fb, f"the coating takes a larger force ({fc:.4g} > 1.1 x {fb:.4g})")

    # (b) a two-material bar in series under axial traction
    L1, L2, H, s = 1.0, 2.0, 0.5, 2.0
    E1, nu1, E2, nu2 = 100.0, 0.1, 300.0, 0.3
    with open(os.path.join(tmp, "bar.geo"), "w") as f:
        f.write(f"""// two regions in series along x, sharing the line x = {L1}
h = 0.1;
Point(1) = {{0, 0, 0, h}};
Point(2) = {{{L1}, 0, 0, h}};
Point(3) = {{{L1 + L2}, 0, 0, h}};
Point(4) = {{{L1 + L2}, {H}, 0, h}};
Point(5) = {{{L1}, {H}, 0, h}};
Point(6) = {{0, {H}, 0, h}};
Line(1) = {{1, 2}}; Line(2) = {{2, 3}}; Line(3) = {{3, 4}}; Line(4) = {{4, 5}};
Line(5) = {{5, 6}}; Line(6) = {{6, 1}}; Line(7) = {{2, 5}};
Curve Loop(1) = {{1, 7, 5, 6}};
Plane Surface(1) = {{1}};
Curve Loop(2) = {{2, 3, 4, -7}};
Plane Surface(2) = {{2}};
Physical Curve("left") = {{6}};
Physical Curve("right") = {{3}};
Physical Curve("bottom") = {{1, 2}};
Physical Curve("top") = {{4, 5}};
Physical Surface("soft") = {{1}};
Physical Surface("stiff") = {{2}};
""")
    bar = os.path.join(tmp, "bar.ini")
    with open(bar, "w") as f:
        f.write(f"""[scene]
id = bar
title = Two materials in series
dim = 2

[mesh]
file = bar.geo
level = 1
level_max = 4

[material soft]
region = soft
model = plane_stress
E = {E1}
nu = {nu1}

[material stiff]
region = stiff
model = plane_stress
E = {E2}
nu = {nu2}

[traction pull]
boundary = right
t = {s} 0

[support left]
boundary = left
fix = x

[support bottom]
boundary = bottom
fix = y

; a plane far above the top: never reached
[contact]
boundary = top
obstacle = plane
point = 0 {H + 1}
normal = 0 -1
friction = none
""")
    for level in ("1", "2"):
        jb, gb = solve(tmp, bar, "bar" + level, "--level", level, "--method", "ssn-tresca")
        if gb is None:
            continue
        x = vtk_to_numpy(gb.GetPoints().GetData())
        u = point(gb, "displacement")
        want = s * (L1 / E1 + L2 / E2)
        end = np.abs(x[:, 0] - (L1 + L2)) < 1e-9
        got = u[end, 0]
        check(end.any() and np.all(np.abs(got - want) <= 1e-9 * want),
              f"level {level}: end displacement {got.min() if end.any() else 0:.12g} .. "
              f"{got.max() if end.any() else 0:.12g} = s (L1/E1 + L2/E2) = {want:.12g}")
        # everywhere: u_x = s x / E1 on the soft part, s (L1/E1 + (x-L1)/E2) beyond
        ux = np.where(x[:, 0] <= L1, s * x[:, 0] / E1, s * (L1 / E1 + (x[:, 0] - L1) / E2))
        uy = -nu1 * s * x[:, 1] / E1
        check(float(np.abs(u[:, 0] - ux).max()) <= 1e-9 * want,
              f"level {level}: u_x piecewise linear (max error {float(np.abs(u[:, 0] - ux).max()):.2e})")
        check(float(np.abs(u[:, 1] - uy).max()) <= 1e-9 * want,
              f"level {level}: u_y = -nu s y / E (max error {float(np.abs(u[:, 1] - uy).max()):.2e})")
        E = cell(gb, "young_modulus")
        check(sorted(set(E.tolist())) == [E1, E2], "the bar's cells carry E1 and E2")

    # (d) the PETSc backend on the split body
    code, out, err = run("solve", COATED, "--backend", "petsc", "--method", "ssn-tresca", "--json",
                         "--quiet", "--vtu", os.path.join(tmp, "petsc.vtu"), cwd=tmp)
    if code != 0 and "has no PETSc backend" in err:
        print("PETSc backend not built: (d) skipped")
    else:
        check(code == 0, f"coated --backend petsc exits 0 ({code}: {err[-300:]})")
        if code == 0 and gc is not None:
            up, ud = point(read_vtu(os.path.join(tmp, "petsc.vtu")), "displacement"), point(gc, "displacement")
            diff = float(np.abs(up - ud).max())
            check(diff <= 1e-5 * float(np.abs(ud).max()),
                  f"petsc and direct agree on the split body (max |du| {diff:.2e})")

    # (e) refusals
    rest = os.path.join(tmp, "rest.ini")
    with open(rest, "w") as f:
        f.write(coated_text("[material]\nmodel = plane_strain\nE = 100\nnu = 0.3\n\n"
                            "[material coating]\nregion = coating\nmodel = plane_strain\nE = 1000\n"
                            "nu = 0.3\n"))
    jr, gr = solve(tmp, rest, "rest", "--method", "ssn-tresca")
    if gr is not None and gc is not None:
        ur, uc = point(gr, "displacement"), point(gc, "displacement")
        diff = float(np.abs(ur - uc).max())
        check(diff <= 1e-12 * float(np.abs(uc).max()),
              f"[material] covers the elements in no region (max |du| {diff:.2e})")
        E = cell(gr, "young_modulus")
        check(sorted(set(E.tolist())) == [100.0, 1000.0], "rest: E 100 and 1000 by cell")
    overlap = os.path.join(tmp, "overlap.geo")
    with open(os.path.join(tmp, "coated.geo")) as f:
        geo = f.read()
    with open(overlap, "w") as f:
        f.write(geo + 'Physical Surface("all") = {1, 2};\n')
    ov = os.path.join(tmp, "overlap.ini")
    with open(ov, "w") as f:
        f.write(coated_text("[material coating]\nregion = coating\nmodel = plane_strain\nE = 1000\n"
                            "nu = 0.3\n\n[material all]\nregion = all\nmodel = plane_strain\nE = 100\n"
                            "nu = 0.3\n").replace("file = coated.geo", "file = overlap.geo"))
    code, out, err = run("solve", ov, cwd=tmp)
    one_line_error(code, err, "overlap.ini:", "[material all]", "overlap")

finish("cli_materials")
