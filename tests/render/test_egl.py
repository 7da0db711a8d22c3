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
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from clicheck import check, exe, finish, png_read, run  # noqa: E402

SRC = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


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
            ia, ib = png_read(a), png_read(b)
            wa, ha, ca, pa = ia.width, ia.height, ia.channels, b"".join(ia.rows)
            wb, hb, cb, pb = ib.width, ib.height, ib.channels, b"".join(ib.rows)
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
