#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""'render --plot convergence|work' honour --method and --set: the methods
drawn are the ones named (read back from the PNG's text chunks, "methods"
and "Series"), several --method give one series each, a Coulomb
convergence plot is drawn, the series differ by (colour, marker), and the
pixels are not blank (decoded here: zlib + PNG row filters)."""
import os
import struct
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, run, usage_error  # noqa: E402


def png_read(path):
    """(width, height, rows of RGB bytes, {tEXt key: value}) of an 8-bit
    RGB PNG."""
    with open(path, "rb") as f:
        data = f.read()
    check(data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: PNG signature")
    pos, text, idat, w, h = 8, {}, b"", 0, 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            check(depth == 8 and ctype == 2, f"{path}: 8-bit RGB")
        elif kind == b"IDAT":
            idat += body
        elif kind == b"tEXt":
            k, v = body.split(b"\0", 1)
            text[k.decode("latin-1")] = v.decode("latin-1")
        pos += 12 + n
    raw = zlib.decompress(idat)
    bpp, stride, rows, prev = 3, 3 * w, [], bytearray(3 * w)
    for y in range(h):
        ft = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if ft == 1:
                line[i] = (line[i] + a) & 255
            elif ft == 2:
                line[i] = (line[i] + b) & 255
            elif ft == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif ft == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, rows, text


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
        w, h, rows, text = png_read(p)
        s = series(text)
        check([x[0] for x in s] == ["mprgp"], f"the series is mprgp alone: {s}")
        check("ssn-tresca" not in text.get("methods", "x"), f"no ssn-tresca: {text.get('methods')}")
        check(coloured_pixels(rows) > 200, "the mprgp curve is drawn")

    # --set reaches the run and its legend
    code, err, p = plot(tmp, "rho.png", "hertz", "--level", "8", "--method", "ssn-tresca", "--set",
                        "rho=0.01", "--plot", "convergence")
    check(code == 0 and os.path.exists(p), f"--set rho convergence plot ({err})")
    if os.path.exists(p):
        s = series(png_read(p)[3])
        check([x[0] for x in s] == ["ssn-tresca rho=0.01"], f"the legend names the parameter: {s}")

    # two --method: two series, each its own (colour, marker)
    code, err, p = plot(tmp, "two.png", "slider", "--method", "mprgp", "--method", "ssn-tresca",
                        "--plot", "convergence")
    check(code in (0, 3) and os.path.exists(p), f"two --method ({code}: {err})")
    if os.path.exists(p):
        s = series(png_read(p)[3])
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
        w, h, rows, text = png_read(p)
        check((w, h) == (400, 300), "size")
        check(text.get("friction") == "coulomb" and len(series(text)) >= 1, f"Coulomb series: {text}")
        check(coloured_pixels(rows) > 100, "the Coulomb curve is drawn (not blank)")

    # work-precision of every method of a scene: (colour, marker) pairs differ
    code, err, p = plot(tmp, "work.png", "twoblocks", "--level", "4", "--plot", "work")
    check(code == 0 and os.path.exists(p), f"work plot ({err})")
    if os.path.exists(p):
        s = series(png_read(p)[3])
        check(len(s) >= 3, f"several methods: {s}")
        check(len({(c, m) for _, c, m in s}) == len(s), f"distinct (colour, marker): {s}")
        check(len({m for _, _, m in s}) == len(s), f"distinct markers: {s}")

    # 3D pressure: a map of the contact face seen from the obstacle (the
    # contact view of the pressure field, with axes and colour bar), no
    # longer a profile along one line
    code, err, p = plot(tmp, "p3d.png", "block3d", "--level", "2", "--plot", "pressure")
    check(code == 0 and os.path.exists(p), f"3D pressure plot ({err})")
    if os.path.exists(p):
        w, h, rows, text = png_read(p)
        check(text.get("field") == "pressure", f"the pressure field: {text.get('field')}")
        check(text.get("camera", "").startswith("contact view"), f"the contact view: {text.get('camera')}")
        check("profile" not in text, "no profile chunk")
        check(coloured_pixels(rows) > 2000, "the face is coloured")

finish("render_plots")
