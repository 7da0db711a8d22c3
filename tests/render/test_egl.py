#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The EGL build (meson -Dgl=egl: Mesa's surfaceless platform) draws the
same images as the OSMesa build: 'render' of hertz (2D) and block3d (3D,
4x MSAA resolved by a blit into the pbuffer) by both programs, decoded here
and compared pixel by pixel. The bound: a mean absolute difference of at
most 0.5 of 255 per channel and at most 0.5 % of the pixels differing by
more than 8 in any channel (both draw with llvmpipe when there is no GPU;
measured: identical). argv[1] is the EGL program; the OSMesa one is
$SIGNORINI_OSMESA_PROGRAM, else build/signorini in the source tree (the
default build): without it the test is skipped (exit 77)."""
import os
import struct
import subprocess
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, exe, finish, run  # noqa: E402

SRC = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def png_pixels(path):
    """(width, height, channels, bytes) of an 8-bit RGB or RGBA PNG, unfiltered."""
    with open(path, "rb") as f:
        data = f.read()
    check(data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: PNG signature")
    pos, idat = 8, b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    if depth != 8 or ctype not in (2, 6):
        check(False, f"{path}: 8-bit RGB(A) expected, got depth {depth} type {ctype}")
        return w, h, 4, b""
    ch = 4 if ctype == 6 else 3
    raw = zlib.decompress(idat)
    stride = w * ch
    out = bytearray(h * stride)
    prev = bytearray(stride)
    for y in range(h):
        ft = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - ch] if x >= ch else 0
            b = prev[x]
            c = prev[x - ch] if x >= ch else 0
            if ft == 1:
                line[x] = (line[x] + a) & 255
            elif ft == 2:
                line[x] = (line[x] + b) & 255
            elif ft == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif ft == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[x] = (line[x] + pred) & 255
        out[y * stride:(y + 1) * stride] = line
        prev = line
    return w, h, ch, bytes(out)


def linked(program):
    r = subprocess.run(["ldd", program], capture_output=True, text=True)
    return r.stdout


def main():
    osmesa = os.environ.get("SIGNORINI_OSMESA_PROGRAM") or os.path.join(SRC, "build", "signorini")
    if not os.access(osmesa, os.X_OK):
        print(f"skipped: no OSMesa program at {osmesa} (build the default build first)")
        sys.exit(77)
    libs_egl, libs_osm = linked(exe), linked(osmesa)
    check("libEGL" in libs_egl and "libOSMesa" not in libs_egl, f"{exe} draws through EGL: {libs_egl}")
    check("libOSMesa" in libs_osm and "libEGL" not in libs_osm, f"{osmesa} draws through OSMesa: {libs_osm}")
    with tempfile.TemporaryDirectory() as tmp:
        for scene, extra in (("hertz", []), ("block3d", ["--level", "4", "--edges"])):
            a, b = os.path.join(tmp, scene + "-egl.png"), os.path.join(tmp, scene + "-osmesa.png")
            code, out, err = run("render", scene, "--png", a, "--size", "480x360", *extra)
            check(code == 0, f"EGL render {scene} ({code}, {err[-300:]})")
            r = subprocess.run([osmesa, "render", scene, "--png", b, "--size", "480x360", *extra],
                               capture_output=True, text=True, timeout=300)
            check(r.returncode == 0, f"OSMesa render {scene} ({r.returncode}, {r.stderr[-300:]})")
            if code or r.returncode:
                continue
            wa, ha, ca, pa = png_pixels(a)
            wb, hb, cb, pb = png_pixels(b)
            check((wa, ha, ca) == (wb, hb, cb) == (480, 360, ca), f"{scene}: sizes {wa}x{ha}x{ca} {wb}x{hb}x{cb}")
            if (wa, ha, ca) != (wb, hb, cb) or not pa:
                continue
            total = sum(abs(x - y) for x, y in zip(pa, pb))
            far = sum(1 for k in range(0, len(pa), ca)
                      if max(abs(pa[k + j] - pb[k + j]) for j in range(ca)) > 8)
            differ = sum(1 for k in range(0, len(pa), ca) if pa[k:k + ca] != pb[k:k + ca])
            mean = total / len(pa)
            print(f"{scene}: mean |difference| {mean:.4f} of 255 per channel; {differ} pixels differ, "
                  f"{far} by more than 8 (of {wa * ha})")
            check(mean <= 0.5, f"{scene}: mean difference {mean:.4f} <= 0.5")
            check(far <= 0.005 * wa * ha, f"{scene}: {far} pixels differ by more than 8 (<= 0.5 %)")
            # the images are drawings, not blanks: several colours
            check(len(set(pa[k:k + ca] for k in range(0, len(pa), ca * 97))) > 20, f"{scene}: a drawing")
    finish("test_egl")


main()
