#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Figure files besides the PNG: the animation of a run (--frames DIR,
--gif FILE: frame count = iterations + 1, every frame the same size, the
same global colour table and the same colour range, the bar's pixels the
same in the first and last frame), vector files (--svg parses as XML with
<text> for the tick labels and paths for the curves; --pdf is a PDF whose
text objects spell the axis label), and the log colour scale (--log; the
colour-bar labels never in C's 1e+09 form). Needs Debian's python3-pil
(run with /usr/bin/python3)."""
import os
import re
import sys
import tempfile
import struct
import xml.etree.ElementTree as ET
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, finish, one_line_error, png_read, run, usage_error  # noqa: E402

SVG = "{http://www.w3.org/2000/svg}"


def iterations(out):
    m = re.search(r"converged in (\d+) iterations", out)
    return int(m.group(1)) if m else -1


def lzw(min_size, data):
    """The colour indices of one GIF image (LZW, codes LSB first)."""
    clear, end = 1 << min_size, (1 << min_size) + 1
    size, table, out, prev = min_size + 1, None, bytearray(), None
    acc = nacc = pos = 0
    while True:
        while nacc < size and pos < len(data):
            acc |= data[pos] << nacc
            nacc += 8
            pos += 1
        if nacc < size:
            break
        code = acc & ((1 << size) - 1)
        acc >>= size
        nacc -= size
        if code == clear:
            table = [bytes([i]) for i in range(clear)] + [b"", b""]
            size, prev = min_size + 1, None
            continue
        if code == end:
            break
        if prev is None:
            entry = table[code]
        else:
            entry = table[code] if code < len(table) else prev + prev[:1]
            table.append(prev + entry[:1])
            if len(table) == 1 << size and size < 12:
                size += 1
        out += entry
        prev = entry
    return bytes(out)


def gif_read(path):
    """{"size", "table" (RGB triples), "local" (images with their own
    table), "comment", "loop", "frames": [(w, h, indices, delay)]}."""
    d = open(path, "rb").read()
    check(d[:6] == b"GIF89a", f"{path}: GIF89a")
    w, h, flags = struct.unpack("<HHB", d[6:11])
    gct = 3 * (1 << ((flags & 7) + 1)) if flags & 0x80 else 0
    g = {"size": (w, h), "table": [tuple(d[13 + i:16 + i]) for i in range(0, gct, 3)], "local": 0,
         "comment": b"", "loop": None, "frames": []}
    pos, delay = 13 + gct, 0

    def blocks(pos):
        data = bytearray()
        while d[pos] != 0:
            data += d[pos + 1:pos + 1 + d[pos]]
            pos += d[pos] + 1
        return bytes(data), pos + 1

    while pos < len(d) and d[pos] != 0x3B:
        if d[pos] == 0x21:
            label = d[pos + 1]
            data, pos = blocks(pos + 2)
            if label == 0xF9:
                delay = struct.unpack("<H", data[1:3])[0]
            elif label == 0xFE:
                g["comment"] += data
            elif label == 0xFF and data[:11] == b"NETSCAPE2.0":
                g["loop"] = struct.unpack("<H", data[12:14])[0]
        else:
            x, y, fw, fh, f = struct.unpack("<HHHHB", d[pos + 1:pos + 10])
            g["local"] += bool(f & 0x80)
            pos += 10 + (3 * (1 << ((f & 7) + 1)) if f & 0x80 else 0)
            min_size = d[pos]
            data, pos = blocks(pos + 1)
            g["frames"].append((fw, fh, lzw(min_size, data), delay))
    return g


def crop(frame, x0, y0, x1, y1):
    w, h, px, _ = frame
    return b"".join(px[y * w + x0:y * w + x1] for y in range(y0, y1))


def svg_texts(path):
    root = ET.parse(path).getroot()
    return root, ["".join(t.itertext()) for t in root.iter(SVG + "text")]


def pdf_strings(path):
    """The literal strings of the text objects (BT ... ET) of every
    content stream, one per text object, kerning gaps joined."""
    data = open(path, "rb").read()
    out = []
    for m in re.finditer(rb"stream\r?\n(.*?)\r?\nendstream", data, re.S):
        try:
            s = zlib.decompress(m.group(1))
        except zlib.error:
            continue
        for bt in re.finditer(rb"BT(.*?)ET", s, re.S):
            parts = re.findall(rb"\(((?:\\.|[^\\)])*)\)", bt.group(1))
            out.append(b"".join(parts).decode("latin-1"))
    return data, out


with tempfile.TemporaryDirectory() as tmp:
    # ---- the animation of a slider run ---------------------------------
    gif, frames = os.path.join(tmp, "slider.gif"), os.path.join(tmp, "frames")
    code, out, err = run("render", "slider", "--size", "400x300", "--gif", gif, "--frames", frames)
    n = iterations(out)
    check(code == 0 and n > 1, f"slider converges in more than one iteration ({code}, {n}): {err}")
    check(os.path.exists(gif), "the GIF is written")
    if os.path.exists(gif):
        g = gif_read(gif)
        fr = g["frames"]
        check(len(fr) == n + 1, f"GIF frames = iterations + 1: {len(fr)}, {n}")
        check(g["loop"] == 0, f"the GIF loops: {g['loop']}")
        m = re.search(rb"colour range ([-0-9.e+]+):([-0-9.e+]+)", g["comment"])
        check(m is not None and float(m.group(2)) > float(m.group(1)), f"comment: {g['comment']}")
        check(g["size"] == (400, 300) and all(f[0:2] == (400, 300) and len(f[2]) == 400 * 300 for f in fr),
              f"every frame 400x300, whole: {[(f[0], f[1], len(f[2])) for f in fr]}")
        check(len(g["table"]) == 256 and g["local"] == 0, f"one global table of 256 colours: {len(g['table'])}, {g['local']}")
        check([f[3] for f in fr] == [50] * n + [300], f"0.5 s a frame, the last 3 s: {[f[3] for f in fr]}")
        # the colour bar (right strip, below the title) is the same in the
        # first and the last frame (every frame has its band: start, still
        # running, the outcome)
        box = (int(0.85 * 400), int(0.3 * 300), 400, int(0.85 * 300))
        check(crop(fr[0], *box) == crop(fr[-1], *box), "colour bar identical in the first and last frame")
        check(fr[0][2] != fr[-1][2], "the run changes the picture")
        # a middle frame carries the banner (still running), the last not
        def banner(f):
            px = crop(f, 0, int(0.1 * 300), 400, int(0.2 * 300))
            return sum(1 for i in px if g["table"][i][0] > 140 and g["table"][i][1] < 80 and g["table"][i][2] < 30)
        check(banner(fr[1]) > 1000 and banner(fr[-1]) == 0, f"the banner in frame 1, not in the last: "
              f"{banner(fr[1])}, {banner(fr[-1])}")
        # the first and the last frame: a dark grey caption band (start,
        # converged) where the others have the warning
        def grey(f):
            px = crop(f, 0, int(0.1 * 300), 400, int(0.2 * 300))
            return sum(1 for i in px if g["table"][i] == (89, 89, 89))
        check(grey(fr[0]) > 1000 and grey(fr[-1]) > 1000 and grey(fr[1]) < 100,
              f"grey bands in the first and last frame: {grey(fr[0])}, {grey(fr[-1])}, {grey(fr[1])}")
    names = sorted(os.listdir(frames)) if os.path.isdir(frames) else []
    check(names == [f"frame_{k:04d}.png" for k in range(n + 1)], f"frames 0..{n}: {names}")
    ranges, iters = set(), []
    for k, name in enumerate(names):
        png = png_read(os.path.join(frames, name), pixels=False)
        w, h, text = png.width, png.height, png.text
        ranges.add(text.get("colour range"))
        iters.append(int(text.get("iterations", "-1")))
        check((w, h) == (400, 300) and text.get("frame") == str(k), f"{name}: size and frame chunk")
        if k == 0:
            check(text.get("outcome") == "start (iteration 0)", f"frame 0's outcome: {text.get('outcome')}")
    check(len(ranges) == 1, f"one colour range in every frame: {ranges}")
    check(iters == list(range(n + 1)), f"frame k is iteration k: {iters}")

    # the same run gives the same bytes
    gif2 = os.path.join(tmp, "again.gif")
    code, out, err = run("render", "slider", "--size", "400x300", "--gif", gif2)
    check(code == 0 and open(gif, "rb").read() == open(gif2, "rb").read(), "the GIF is reproducible")

    # --every 2: iterates 0, 2, 4, ... and the last
    frames2 = os.path.join(tmp, "every")
    code, out, err = run("render", "slider", "--size", "400x300", "--frames", frames2, "--every", "2")
    want = sorted(set(range(0, n + 1, 2)) | {n})
    got = [int(png_read(os.path.join(frames2, f), pixels=False).text.get("iterations", "-1")) for f in sorted(os.listdir(frames2))]
    check(code == 0 and got == want, f"--every 2 draws iterations {want}: {got}")

    # a GIF in a missing directory: one line, nothing left
    code, out, err = run("render", "slider", "--gif", os.path.join(tmp, "no", "x.gif"))
    one_line_error(code, err, "x.gif")
    # the frames directory is a file
    code, out, err = run("render", "slider", "--frames", gif)
    one_line_error(code, err, "--frames")

    # ---- vector plots -------------------------------------------------------
    svg, pdf = os.path.join(tmp, "conv.svg"), os.path.join(tmp, "conv.pdf")
    code, out, err = run("render", "hertz", "--level", "8", "--plot", "convergence", "--method", "ssn-tresca",
                         "--method", "pdas", "--svg", svg, "--pdf", pdf)
    check(code == 0 and os.path.exists(svg) and os.path.exists(pdf), f"--svg and --pdf ({err})")
    if os.path.exists(svg):
        root, texts = svg_texts(svg)
        check(root.tag == SVG + "svg" and root.get("width") == "600pt", f"an SVG of 600 pt: {root.attrib}")
        check("iteration" in texts and "kkt error" in texts, f"axis labels as <text>: {texts}")
        check(any(t.startswith("10") and len(t) > 2 for t in texts), f"decade tick labels as <text>: {texts}")
        check("ssn-tresca" in texts and "pdas" in texts, f"legend entries as <text>: {texts}")
        # the curves: stroked paths in the two series' colours
        strokes = {re.search(r"stroke:(rgb\([^)]*\))", p.get("style", "")).group(1)
                   for p in root.iter(SVG + "path") if "stroke:rgb" in p.get("style", "")}
        check(len(strokes) >= 4, f"paths for the grid, frame and two curves: {strokes}")
        check(not list(root.iter(SVG + "image")), "a plot embeds no bitmap")
    if os.path.exists(pdf):
        data, strings = pdf_strings(pdf)
        check(data.startswith(b"%PDF-") and data.rstrip().endswith(b"%%EOF"), "a whole PDF")
        check(any("iteration" in t for t in strings) and any("kkt error" in t for t in strings),
              f"PDF text: {strings}")

    # the same figure gives the same bytes (no date in the PDF)
    svg2, pdf2 = os.path.join(tmp, "again.svg"), os.path.join(tmp, "again.pdf")
    code, out, err = run("render", "hertz", "--level", "8", "--plot", "convergence", "--method", "ssn-tresca",
                         "--method", "pdas", "--svg", svg2, "--pdf", pdf2)
    check(open(svg, "rb").read() == open(svg2, "rb").read(), "the SVG is reproducible")
    check(open(pdf, "rb").read() == open(pdf2, "rb").read(), "the PDF is reproducible")

    # --svg - : the SVG on standard output, the summary on standard error
    code, out, err = run("render", "hertz", "--level", "4", "--plot", "pressure", "--svg", "-")
    check(code == 0 and out.startswith("<?xml") and out.rstrip().endswith("</svg>") and "converged" in err,
          f"--svg - ({code}): {err!r}")

    # ---- an image as SVG: the body embedded, text and bar as vectors -------
    code, out, err = run("render", "hertz", "--level", "8", "--svg", svg, "--pdf", pdf)
    check(code == 0, f"image --svg ({err})")
    if os.path.exists(svg):
        root, texts = svg_texts(svg)
        check(len(list(root.iter(SVG + "image"))) == 1, "the GL layer embedded once")
        check(any("von Mises" in t for t in texts), f"colour-bar title as <text>: {texts}")
        check(sum(bool(re.fullmatch(r"[0-9.]+", t)) for t in texts) >= 3, f"colour-bar ticks: {texts}")

    # ---- --log, and labels never in 1e+09 form ------------------------------
    png = os.path.join(tmp, "log.png")
    code, out, err = run("render", "twoblocks-paper", "--level", "4", "--log", "--png", png, "--svg", svg)
    check(code in (0, 3), f"--log ({err})")
    if os.path.exists(png):
        rng = png_read(png, pixels=False).text.get("colour range", "")
        check(rng.endswith("(log)"), f"the range is logarithmic: {rng}")
        lo, hi = (float(x) for x in rng.split()[0].split(":"))
        check(0 < lo < hi and hi / lo <= 1e6 * (1 + 1e-9), f"a positive range of at most 6 decades: {rng}")
        root, texts = svg_texts(svg)
        check(any(re.fullmatch(r"10[⁰¹²³⁴⁵⁶⁷⁸⁹⁻]+", t) for t in texts), f"decades on the bar: {texts}")
    code, out, err = run("render", "twoblocks-paper", "--level", "4", "--svg", svg)
    root, texts = svg_texts(svg)
    ticks = [t for t in texts if re.fullmatch(r"[-0-9.e+]+", t)]
    check(len(ticks) >= 3 and not any("e" in t for t in ticks), f"no 1e+09 bar labels: {ticks}")
    check(any("×10" in t for t in texts), f"the bar in units of 10ⁿ: {texts}")
    # a plot of large values: plain ticks, the power of ten after the label
    code, out, err = run("render", "twoblocks-paper", "--level", "4", "--plot", "pressure", "--svg", svg)
    root, texts = svg_texts(svg)
    check(any(t.startswith("contact pressure") and t.endswith("×10⁷") for t in texts), f"y label ×10ⁿ: {texts}")
    ticks = [t for t in texts if re.fullmatch(r"[-0-9.]+", t)]
    check(len(ticks) >= 6 and not any("×" in t for t in texts if len(t) < 8), f"plain ticks: {texts}")
    code, out, err = run("render", "hertz", "--level", "4", "--field", "sxx", "--log", "--png", png)
    one_line_error(code, err, "--log")
    code, out, err = run("render", "hertz", "--level", "4", "--log", "--range", "0:5", "--png", png)
    one_line_error(code, err, "--range")
    code, out, err = run("render", "hertz", "--level", "4")
    usage_error(code, err, "--png")

finish("render_figfiles")
