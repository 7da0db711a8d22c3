# SPDX-License-Identifier: GPL-3.0-or-later
"""The VTU read back by VTK's own XML reader (Debian python3-vtk9): the
stress as VTK's symmetric tensor (XX YY ZZ XY YZ XZ, named), hand-computed
homogeneous states in 2D (plane strain, with szz) and 3D, contact traction
vectors summing to solve --json's contact force, the slip, every contact
point of stackbond counted, and the run record in FieldData.
Usage: test_vtu.py SIGNORINI"""
import json
import math
import os
import subprocess
import sys
import tempfile

import vtk
from vtk.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, exe, finish  # noqa: E402


def solve(tmp, scene, name, *extra):
    vtu = os.path.join(tmp, name + ".vtu")
    r = subprocess.run([exe, "solve", scene, "--vtu", vtu, "--json", *extra], capture_output=True,
                       text=True, timeout=300, cwd=tmp)
    check(r.returncode == 0, f"solve {scene} exit 0 ({r.returncode}: {r.stderr[-300:]})")
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(vtu)
    reader.Update()
    return json.loads(r.stdout), reader.GetOutput()


def point(g, name):
    a = g.GetPointData().GetArray(name)
    check(a is not None, f"point array {name}")
    return vtk_to_numpy(a)


def field(g, name):
    a = g.GetFieldData().GetAbstractArray(name)
    check(a is not None, f"field data {name}")
    return a.GetValue(0) if a is not None else None


def near(a, b, tol):
    return abs(a - b) <= tol


PATCH2D = """[scene]
id = patch2d
title = Uniaxial patch, plane strain
dim = 2
[mesh]
generator = rectangle
element = quad4
lo = 0 0
hi = 2 1
cells = 2 1
level = 3
[material]
model = plane_strain
E = 1000
nu = 0.3
[traction top]
boundary = top
t = 0 -10
[support roll]
boundary = left
fix = x
[contact]
boundary = bottom
obstacle = plane
point = 0 0
normal = 0 1
friction = none
"""

with tempfile.TemporaryDirectory() as tmp:
    # ---- 2D plane strain: a block on a frictionless plane under a pressure
    # of 10 on top, a roller on its left side: sxx = 0, syy = -10, sxy = 0,
    # szz = nu (sxx + syy) = -3, von Mises sqrt(((0+10)^2 + (-10+3)^2 +
    # (-3-0)^2) / 2) = sqrt(79)
    path = os.path.join(tmp, "patch2d.ini")
    with open(path, "w") as f:
        f.write(PATCH2D)
    js, g = solve(tmp, path, "patch2d")
    s = g.GetPointData().GetArray("stress")
    check(s is not None and s.GetNumberOfComponents() == 6, "2D stress: a 6-component symmetric tensor")
    names = [s.GetComponentName(k) for k in range(6)] if s else []
    check(names == ["XX", "YY", "ZZ", "XY", "YZ", "XZ"], f"component names in VTK's order, got {names}")
    sig = vtk_to_numpy(s)
    want = [0, -10, -3, 0, 0, 0]
    err = max(abs(sig[:, k] - want[k]).max() for k in range(6))
    check(err < 1e-9, f"2D patch stress {want}: max error {err:.3e}")
    vm = point(g, "von_mises")
    check(abs(vm - math.sqrt(79)).max() < 1e-9, f"2D von Mises sqrt(79) = 8.888: got {vm.min()}..{vm.max()}")
    # von Mises consistent with the tensor written
    vmt = ((0.5 * ((sig[:, 0] - sig[:, 1]) ** 2 + (sig[:, 1] - sig[:, 2]) ** 2 + (sig[:, 2] - sig[:, 0]) ** 2)
            + 3 * (sig[:, 3] ** 2 + sig[:, 4] ** 2 + sig[:, 5] ** 2)) ** 0.5)
    check(abs(vm - vmt).max() < 1e-9, "von Mises is that of the tensor written")
    # traction: pressure 10 over the bottom, normal (0, -1) on the plane
    w = point(g, "contact_weight")
    tn = point(g, "contact_traction_normal")
    bottom = w > 0
    check(abs(tn[bottom, 1] - 10).max() < 1e-9, "normal traction 10 upwards on the body")
    check(near(w.sum(), 2, 1e-12), f"lumped weights cover the bottom (2), got {w.sum()}")

    # ---- 3D: block3d, uniaxial szz = -10 (rollers, frictionless plane)
    js, g = solve(tmp, "block3d", "block3d")
    sig = point(g, "stress")
    want = [0, 0, -10, 0, 0, 0]
    err = max(abs(sig[:, k] - want[k]).max() for k in range(6))
    check(err < 1e-9, f"block3d stress {want}: max error {err:.3e}")

    # ---- 3D shear order: halfball's shear components against the strain
    # of the written displacement (VTK's own gradient, G = E / 2(1 + nu));
    # each of XY, YZ, XZ must match its own strain, not another's (VTK
    # averages the tets' constant gradients at the nodes as fem/ averages the
    # stresses: equal to roundoff)
    js, g = solve(tmp, "halfball", "halfball", "--level", "4")
    grad = vtk.vtkGradientFilter()
    grad.SetInputData(g)
    grad.SetInputScalars(vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, "displacement")
    grad.SetResultArrayName("du")
    grad.Update()
    du = vtk_to_numpy(grad.GetOutput().GetPointData().GetArray("du")).reshape(-1, 3, 3)  # du[i, c, d] = d u_c / d x_d
    sig = point(g, "stress")
    with open(os.path.join(os.environ["SIGNORINI_SCENES"], "halfball.ini")) as f:
        mat = dict(map(str.strip, l.split("=", 1)) for l in f.read().split("[material]")[1].split("[")[0].splitlines()
                   if "=" in l and not l.startswith(";"))
    E, nu = float(mat["E"]), float(mat["nu"])
    G = E / (2 * (1 + nu))
    gam = {"XY": G * (du[:, 0, 1] + du[:, 1, 0]), "YZ": G * (du[:, 1, 2] + du[:, 2, 1]),
           "XZ": G * (du[:, 0, 2] + du[:, 2, 0])}
    for k, name in [(3, "XY"), (4, "YZ"), (5, "XZ")]:
        scale = (gam[name] ** 2).sum() ** 0.5
        errs = {o: ((sig[:, k] - gam[o]) ** 2).sum() ** 0.5 / scale for o in gam}
        best = min(errs, key=errs.get)
        check(best == name and errs[name] < 1e-9, f"stress {name} is the {name} shear: relative errors {errs}")

    # ---- traction vectors sum to the contact force; slip; run record
    for scene, extra in [("slider", []), ("stackbond", []), ("twoblocks", ["--level", "8"]),
                         ("hertz", ["--level", "16"])]:
        js, g = solve(tmp, scene, scene, *extra)
        w = point(g, "contact_weight")
        tn = point(g, "contact_traction_normal")
        tt = point(g, "contact_traction_tangential")
        f = (w[:, None] * (tn + tt)).sum(axis=0)
        fc = js["force"].get("points", js["force"]["contact"])   # several bodies: the points' sum
        scale = max(math.hypot(*fc), 1e-300)
        err = max(abs(f[k] - fc[k]) for k in range(len(fc))) / scale
        check(err <= 1e-8, f"{scene}: tractions x weights {list(f)} = force.contact {fc} (rel {err:.2e})")
        npts = point(g, "contact_points")
        st = point(g, "contact_status")
        check(int(npts.sum()) == js["contact_points"],
              f"{scene}: contact_points counts all {js['contact_points']} points, got {int(npts.sum())}")
        check(((npts > 0) == (st >= 0)).all(), f"{scene}: every node with a contact point has a status")
        nslip = js["slip"]
        check(int(((st == 3) | (st == 4)).sum()) <= nslip, f"{scene}: slip codes at most the slipping points")
        # FieldData: the run record
        check(field(g, "scene") == scene, f"{scene}: FieldData scene")
        check(field(g, "method") == js["method"], f"{scene}: FieldData method {js['method']}")
        check(field(g, "friction") == js["friction"], f"{scene}: FieldData friction")
        check(field(g, "iterations") == js["iterations"], f"{scene}: FieldData iterations")
        check(field(g, "converged") == int(js["converged"]), f"{scene}: FieldData converged")
        check(field(g, "reason") == js["reason"], f"{scene}: FieldData reason {js['reason']}")
        check(field(g, "kkt") == js["kkt_error"], f"{scene}: FieldData kkt {js['kkt_error']}")
        check(field(g, "tol") == js["tol"], f"{scene}: FieldData tol")
        if "slip_bound" in js:
            check(field(g, "slip_bound") == js["slip_bound"], f"{scene}: FieldData slip_bound")
        codes = field(g, "contact_status_codes")
        check(codes is not None and "2 stick" in codes and "-1 no contact" in codes,
              f"{scene}: status codes documented in FieldData")
        check(f"--method {js['method']}" in (field(g, "solve_args") or ""), f"{scene}: solve_args")
        if scene == "stackbond":
            # 126 points on 108 nodes: 18 joint nodes hold two points each
            check(js["contact_points"] == 126 and int((npts > 0).sum()) == 108 and int(npts.max()) == 2,
                  f"stackbond: 126 points on 108 nodes, got {int(npts.sum())} on {int((npts > 0).sum())}")
        if scene == "slider":
            # slipping points against the plane y = 0: slip = T u = u_x, along x
            u = point(g, "displacement")
            sl = point(g, "contact_slip")
            sl_nodes = (st == 3) | (st == 4)
            check(sl_nodes.sum() == nslip and nslip > 0, f"slider: {nslip} slipping nodes")
            check(abs(sl[sl_nodes, 0] - u[sl_nodes, 0]).max() < 1e-15 and abs(sl[:, 1]).max() == 0,
                  "slider: slip = tangential displacement at slipping points")
            check(abs(sl[~sl_nodes]).max() == 0, "slider: no slip elsewhere")
            check(abs(tt[sl_nodes, 0]).max() > 0, "slider: tangential traction at slipping points")
            # Tresca: |traction| = the bound at slipping points
            check(abs(abs(tt[sl_nodes, 0]) - js["slip_bound"]).max() < 1e-9,
                  f"slider: tangential traction = slip bound {js['slip_bound']} where slipping")

    # ---- --vtu-series: one VTU per iteration and a .pvd listing them
    series = os.path.join(tmp, "series")
    js, g = solve(tmp, "slider", "slider-final", "--vtu-series", series)
    import xml.etree.ElementTree as ET
    files = [ds.get("file") for ds in ET.parse(os.path.join(series, "series.pvd")).iter("DataSet")]
    check(len(files) == js["iterations"] and js["iterations"] > 1,
          f"series.pvd lists {js['iterations']} iterates, got {len(files)}")
    for k, name in enumerate(files, 1):
        reader = vtk.vtkXMLUnstructuredGridReader()
        reader.SetFileName(os.path.join(series, name))
        reader.Update()
        gk = reader.GetOutput()
        check(field(gk, "iterations") == k, f"series {name}: iterations {k}")
        if k == len(files):
            d = abs(point(gk, "displacement") - point(g, "displacement")).max()
            check(d == 0, f"the series' last iterate is the solution (max difference {d})")

finish("vtu")
