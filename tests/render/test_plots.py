#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""'render --plot convergence|work' honour --method and --set: the methods
drawn are the ones named (read back from the PNG's text chunks, "methods"
and "Series"), several --method give one series each, a Coulomb
convergence plot is drawn, the series differ by (colour, marker), and the
pixels are not blank (decoded by tests/clicheck.py)."""
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, png_read, run, usage_error  # noqa: E402


def png_rgb(path):
    """(width, height, rows of RGB bytes, {tEXt key: value}) of an 8-bit
    RGB PNG."""
    png = png_read(path)
    check(png.channels == 3, f"{path}: 8-bit RGB")
    return png.width, png.height, png.rows, png.text


def coloured_pixels(rows):
    """Pixels that are neither white nor grey: the series' ink."""
    n = 0
    for row in rows:
        for i in range(0, len(row), 3):
            r, g, b = row[i], row[i + 1], row[i + 2]
            n += max(r, g, b) - min(r, g, b) > 40
    return n


def series(text):
    """[(label, colour, marker)] from the "Series" chunk."""
    out = []
    for line in text.get("Series", "").splitlines():
        label, c, m = line.split("\t")
        out.append((label, c.split("=")[1], m.split("=")[1]))
    return out


def plot(tmp, name, *args):
    p = os.path.join(tmp, name)
    code, out, err = run("render", *args, "--quiet", "--size", "400x300", "--png", p)
    return code, err, p


with tempfile.TemporaryDirectory() as tmp:
    # one named method: that method is drawn, not the scene's list (slider's
    # list is ssn-tresca; before, mprgp was asked and ssn-tresca drawn)
    code, err, p = plot(tmp, "mprgp.png", "slider", "--method", "mprgp", "--plot", "convergence")
    check(code in (0, 3) and os.path.exists(p), f"--method mprgp convergence plot ({code}: {err})")
    if os.path.exists(p):
        w, h, rows, text = png_rgb(p)
        s = series(text)
        check([x[0] for x in s] == ["mprgp"], f"the series is mprgp alone: {s}")
        check("ssn-tresca" not in text.get("methods", "x"), f"no ssn-tresca: {text.get('methods')}")
        check(coloured_pixels(rows) > 200, "the mprgp curve is drawn")

    # --set reaches the run and its legend
    code, err, p = plot(tmp, "rho.png", "hertz", "--level", "8", "--method", "ssn-tresca", "--set",
                        "rho=0.01", "--plot", "convergence")
    check(code == 0 and os.path.exists(p), f"--set rho convergence plot ({err})")
    if os.path.exists(p):
        s = series(png_rgb(p)[3])
        check([x[0] for x in s] == ["ssn-tresca rho=0.01"], f"the legend names the parameter: {s}")

    # two --method: two series, each its own (colour, marker)
    code, err, p = plot(tmp, "two.png", "slider", "--method", "mprgp", "--method", "ssn-tresca",
                        "--plot", "convergence")
    check(code in (0, 3) and os.path.exists(p), f"two --method ({code}: {err})")
    if os.path.exists(p):
        s = series(png_rgb(p)[3])
        check([x[0] for x in s] == ["mprgp", "ssn-tresca"], f"two series in order: {s}")
        check(len({(c, m) for _, c, m in s}) == 2 and len({c for _, c, _ in s}) == 2
              and len({m for _, _, m in s}) == 2, f"distinct colours and markers: {s}")

    # several --method outside a comparison plot, a --set no method has
    code, out, err = run("render", "slider", "--method", "mprgp", "--method", "ssn-tresca", "--png",
                         os.path.join(tmp, "x.png"))
    usage_error(code, err, "--method given 2 times")
    code, out, err = run("render", "slider", "--method", "mprgp", "--method", "ssn-tresca", "--set",
                         "nokey=1", "--plot", "convergence", "--png", os.path.join(tmp, "x.png"))
    usage_error(code, err, "nokey")
    check(not os.path.exists(os.path.join(tmp, "x.png")), "no file after a usage error")

    # Coulomb: before, 'no point to draw' (hertz lists no Coulomb method)
    code, err, p = plot(tmp, "coulomb.png", "hertz", "--level", "8", "--friction", "coulomb",
                        "--plot", "convergence")
    check(code == 0 and os.path.exists(p), f"Coulomb convergence plot ({err})")
    if os.path.exists(p):
        w, h, rows, text = png_rgb(p)
        check((w, h) == (400, 300), "size")
        check(text.get("friction") == "coulomb" and len(series(text)) >= 1, f"Coulomb series: {text}")
        check(coloured_pixels(rows) > 100, "the Coulomb curve is drawn (not blank)")

    # work-precision of every method of a scene: (colour, marker) pairs differ
    code, err, p = plot(tmp, "work.png", "twoblocks", "--level", "4", "--plot", "work")
    check(code == 0 and os.path.exists(p), f"work plot ({err})")
    if os.path.exists(p):
        s = series(png_rgb(p)[3])
        check(len(s) >= 3, f"several methods: {s}")
        check(len({(c, m) for _, c, m in s}) == len(s), f"distinct (colour, marker): {s}")
        check(len({m for _, _, m in s}) == len(s), f"distinct markers: {s}")

    # 3D pressure: a map of the contact face seen from the obstacle (the
    # contact view of the pressure field, with axes and colour bar), no
    # longer a profile along one line
    code, err, p = plot(tmp, "p3d.png", "block3d", "--level", "2", "--plot", "pressure")
    check(code == 0 and os.path.exists(p), f"3D pressure plot ({err})")
    if os.path.exists(p):
        w, h, rows, text = png_rgb(p)
        check(text.get("field") == "pressure", f"the pressure field: {text.get('field')}")
        check(text.get("camera", "").startswith("contact view"), f"the contact view: {text.get('camera')}")
        check("profile" not in text, "no profile chunk")
        check(coloured_pixels(rows) > 2000, "the face is coloured")

finish("render_plots")
