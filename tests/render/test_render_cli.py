#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""'signorini render' and 'solve --png/--vtu' end to end: the PNG is written
(signature, size, text chunks), the VTU is well-formed XML with the right
counts and array sizes (ASCII and base64 binary, decoded), the plots are
written, and bad paths / options give one line and leave no file."""
import base64
import os
import struct
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, exe, finish, one_line_error, png_read, run, usage_error  # noqa: E402


def png_info(path):
    """(width, height, {tEXt key: value}) of a PNG, chunk by chunk (CRCs
    checked)."""
    png = png_read(path, pixels=False)
    return png.width, png.height, png.text


def vtu_arrays(path):
    """Parse the VTU; return (piece attributes, {name: list of values})."""
    root = ET.parse(path).getroot()
    check(root.tag == "VTKFile" and root.get("type") == "UnstructuredGrid", "VTKFile UnstructuredGrid")
    piece = root.find("UnstructuredGrid/Piece")
    arrays = {}
    fmt = {"Float64": "d", "Int64": "q", "Int32": "i", "UInt8": "B"}
    for da in piece.iter("DataArray"):
        name = da.get("Name") or "Points"
        t = da.get("type")
        if da.get("format") == "ascii":
            vals = [float(x) if t == "Float64" else int(x) for x in da.text.split()]
        else:
            raw = base64.b64decode(da.text.strip())
            nbytes = struct.unpack("<Q", raw[:8])[0]
            check(nbytes == len(raw) - 8, f"{name}: header {nbytes} = payload {len(raw) - 8}")
            vals = list(struct.unpack("<%d%s" % (nbytes // struct.calcsize(fmt[t]), fmt[t]), raw[8:]))
        arrays[name] = (int(da.get("NumberOfComponents", "1")), vals)
    return piece.attrib, arrays


REPO_SCENES = os.environ.get("SIGNORINI_SCENES", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes"))

with tempfile.TemporaryDirectory() as tmp:
    png = os.path.join(tmp, "h.png")
    vtu = os.path.join(tmp, "h.vtu")

    # render hertz: PNG with its text chunks
    code, out, err = run("render", "hertz", "--level", "8", "--png", png, "--size", "320x240",
                         "--field", "sxy", "--edges", "--quiet")
    check(code == 0, f"render hertz exit 0 ({err})")
    w, h, text = png_info(png)
    check((w, h) == (320, 240), f"size 320x240, got {w}x{h}")
    for key, want in [("scene", "hertz"), ("level", "8"), ("method", "ssn-tresca"),
                      ("friction", "none"), ("field", "sxy")]:
        check(text.get(key) == want, f"tEXt {key} = {want!r}, got {text.get(key)!r}")
    check(float(text.get("kkt error", "1")) < 1e-10, "tEXt kkt error")
    check(text.get("Software", "").startswith("signorini "), "tEXt Software")
    check("rho=" in text.get("parameters", ""), "tEXt parameters")

    # solve --vtu (binary and ASCII) and --png together
    for ascii_flag in ([], ["--vtu-ascii"]):
        code, out, err = run("solve", "hertz", "--level", "8", "--quiet", "--vtu", vtu, *ascii_flag)
        check(code == 0, f"solve --vtu exit 0 ({err})")
        attrs, arr = vtu_arrays(vtu)
        n, ne = int(attrs["NumberOfPoints"]), int(attrs["NumberOfCells"])
        check(n == 9 * 9 and ne == 2 * 8 * 8, f"hertz level 8: 81 points, 128 cells, got {n}, {ne}")
        for name, comps in [("displacement", 3), ("stress", 6), ("von_mises", 1),
                            ("contact_pressure", 1), ("contact_status", 1), ("Points", 3)]:
            c, vals = arr[name]
            check(c == comps and len(vals) == comps * n, f"{name}: {comps} x {n} values, got {c} x {len(vals)}")
        check(len(arr["connectivity"][1]) == 3 * ne and arr["offsets"][1][-1] == 3 * ne, "connectivity/offsets")
        check(set(arr["types"][1]) == {5}, "VTK_TRIANGLE cells")
        check(len(arr["body"][1]) == ne, "cell data body")
        # the contact force balances the load: sum of pressure x lumped length ~ 800
        status = arr["contact_status"][1]
        check(sum(1 for s in status if s >= 0) == 9, "9 contact points carry a status")
        check(min(arr["von_mises"][1]) >= 0, "von Mises >= 0")
        uy = arr["displacement"][1][1::3]
        # the origin touches the line (uy = 0, up to round-off); the rest moves down
        check(max(uy) < 1e-12 and min(uy) < -0.1, f"uy in [{min(uy)}, {max(uy)}]")

    # 3D: solve --png and --vtu at once, contact view
    code, out, err = run("solve", "block3d", "--level", "1", "--quiet", "--png", png, "--vtu", vtu,
                         "--view", "contact", "--field", "szz", "--size", "200x150")
    check(code == 0, f"block3d --png --vtu exit 0 ({err})")
    w, h, text = png_info(png)
    check((w, h) == (200, 150) and text.get("field") == "szz", "3D PNG")
    attrs, arr = vtu_arrays(vtu)
    check(arr["stress"][0] == 6 and set(arr["types"][1]) == {12}, "3D: 6 stresses, hexahedra")

    # plots
    for kind in ["pressure", "convergence", "work"]:
        p = os.path.join(tmp, kind + ".png")
        code, out, err = run("render", "hertz", "--level", "8", "--quiet", "--png", p, "--plot", kind,
                             "--size", "400x300")
        check(code == 0 and os.path.exists(p), f"--plot {kind} ({err})")
        w, h, text = png_info(p)
        check(text.get("scene") == "hertz", f"{kind} plot text")

    # '-': the PNG (image or plot) on standard output, the summary on stderr;
    # a link stays a link and its target gets the PNG
    for extra in ([], ["--plot", "pressure"]):
        r = subprocess.run([exe, "render", "hertz", "--level", "8", "--png", "-", "--size", "200x150", *extra],
                           capture_output=True, timeout=300)
        check(r.returncode == 0 and r.stdout[:8] == b"\x89PNG\r\n\x1a\n", f"--png - {extra}: a PNG on stdout")
        check(b"converged" in r.stderr, "the summary on stderr")
    os.symlink("h.png", os.path.join(tmp, "link.png"))
    code, out, err = run("render", "hertz", "--level", "8", "--quiet", "--png", os.path.join(tmp, "link.png"),
                         "--size", "200x150")
    check(code == 0 and os.path.islink(os.path.join(tmp, "link.png")), f"--png through a link ({err})")
    w, h, text = png_info(png)
    check((w, h) == (200, 150), "the link's target holds the new PNG")
    os.remove(os.path.join(tmp, "link.png"))

    # errors: one line, no file
    before = set(os.listdir(tmp))
    bad = os.path.join(tmp, "missing", "x.png")
    code, out, err = run("render", "hertz", "--level", "4", "--quiet", "--png", bad)
    one_line_error(code, err, bad)
    code, out, err = run("solve", "hertz", "--level", "4", "--quiet", "--vtu", os.path.join(tmp, "missing", "x.vtu"))
    one_line_error(code, err, "x.vtu")
    check(set(os.listdir(tmp)) == before, "no file or temporary left behind")
    code, out, err = run("render", "hertz", "--quiet")
    usage_error(code, err, "--png")
    code, out, err = run("render", "hertz", "--png", png, "--field", "nope")
    usage_error(code, err, "--field", "nope")
    code, out, err = run("render", "hertz", "--png", png, "--field", "szz")
    one_line_error(code, err, "szz", "3D")
    code, out, err = run("render", "hertz", "--png", png, "--size", "12x5")
    usage_error(code, err, "--size")
    code, out, err = run("render", "hertz", "--png", png, "--view", "contact")
    one_line_error(code, err, "--view")
    code, out, err = run("render", "hertz", "--png", png, "--scale", "-1")
    usage_error(code, err, "--scale")
    # camera and framing: bad values, 3D-only options on 2D, --mirror
    # without symmetry planes, and the scene key's own errors
    code, out, err = run("render", "halfball", "--png", png, "--camera", "35")
    usage_error(code, err, "--camera", "AZ,EL")
    code, out, err = run("render", "halfball", "--png", png, "--camera", "0,95")
    usage_error(code, err, "--camera")
    code, out, err = run("render", "hertz", "--png", png, "--view", "below")
    one_line_error(code, err, "--view below", "3D")
    code, out, err = run("render", "hertz", "--png", png, "--camera", "10,20")
    one_line_error(code, err, "--camera", "3D")
    code, out, err = run("render", "halfball", "--level", "4", "--png", png, "--mirror", "--quiet")
    one_line_error(code, err, "--mirror", "halfball", "symmetry")
    code, out, err = run("render", "hertz", "--png", png, "--crop", "body")
    usage_error(code, err, "--crop")
    with open(os.path.join(REPO_SCENES, "hertz.ini")) as f:
        hertz_ini = f.read()
    for bad, needle in (("x=0 x=1", "twice"), ("z=0", "symmetry"), ("x 0", "symmetry"), ("y=abc", "symmetry")):
        path = os.path.join(tmp, "sym.ini")
        with open(path, "w") as f:
            f.write(hertz_ini.replace("symmetry = x=0", "symmetry = " + bad))
        code, out, err = run("render", path, "--png", png)
        one_line_error(code, err, "sym.ini:", needle)
    code, out, err = run("render", "hertz", "--level", "8", "--quiet", "--png", png, "--mirror", "--crop",
                         "contact", "--size", "300x225")
    check(code == 0 and os.path.exists(png), f"--mirror --crop contact ({err})")
    code, out, err = run("render", "halfball", "--level", "4", "--quiet", "--png", png, "--camera", "-20,-60",
                         "--size", "300x225")
    check(code == 0 and os.path.exists(png), f"--camera -20,-60 ({err})")
    # 3D, two obstacles: block3d squeezed from its sides grows in z between
    # its plane and a rigid ball touching its top corner. Seen from below,
    # the plane (on the eye's side) is left out and the ball, above the
    # block, is drawn: its shaded warm grey fills much of the upper half
    # (before, only the first obstacle was drawn: none of it from below)
    with open(os.path.join(REPO_SCENES, "block3d.ini")) as f:
        block_ini = f.read()
    squeezed = os.path.join(tmp, "squeezed.ini")
    with open(squeezed, "w") as f:
        f.write(block_ini.replace("[traction top]\nboundary = zmax\nt = 0 0 -10",
                                  "[traction sx]\nboundary = xmax\nt = -10 0 0\n\n"
                                  "[traction sy]\nboundary = ymax\nt = 0 -10 0")
                .replace("[contact]", "[contact floor]")
                .replace("[methods]", "[contact ball]\nboundary = zmax\nobstacle = sphere\npoint = 0 0 1.5\n"
                                      "radius = 1\n\n[methods]"))
    code, out, err = run("render", squeezed, "--level", "2", "--view", "below", "--quiet", "--png", png,
                         "--size", "480x360")
    check(code == 0, f"render of a block between a plane and a ball ({err})")
    if code == 0:
        img = png_read(png)
        ball = [0, 0]   # obstacle-coloured pixels in the upper, lower half
        for y, row in enumerate(img.rows):
            for i in range(0, len(row), img.channels):
                r, g, b = row[i:i + 3]
                if r >= g >= b and 12 <= r - b <= 70 and 50 < r < 235:
                    ball[2 * y >= img.height] += 1
        check(ball[0] > 0.1 * img.width * img.height and ball[0] > 3 * ball[1],
              f"the second obstacle (the ball above) is drawn: {ball} pixels of its colour")
    code, out, err = run("render", "--help")
    check(code == 0 and "--field" in out, "render --help")

finish("render cli")
