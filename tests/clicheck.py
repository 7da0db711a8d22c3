# SPDX-License-Identifier: GPL-3.0-or-later
"""Shared by the end-to-end tests of the program (tests/*/test_*.py): the
program under test (argv[1]), checks that count, running it, the
one-line error every bad input must give, and a reader of the PNGs it
writes."""
import collections
import os
import struct
import subprocess
import sys
import zlib

# a path (not a name looked up in PATH) made absolute: runs with cwd= find it
exe = os.path.abspath(sys.argv[1]) if os.sep in sys.argv[1] else sys.argv[1]
_count = {"checks": 0, "failures": 0}


def check(cond, what):
    _count["checks"] += 1
    if not cond:
        _count["failures"] += 1
        print(f"FAIL: {what}")


def run(*args, cwd=None, env=None, stdin=None):
    """(exit status, stdout, stderr) of the program with args; env: variables
    added to the environment."""
    r = subprocess.run([exe, *args], capture_output=True, text=True, timeout=300, cwd=cwd,
                       env=None if env is None else {**os.environ, **env}, stdin=stdin)
    return r.returncode, r.stdout, r.stderr


def one_line_error(code, err, *needles, status=1):
    """An error of the run (status 1) or, with status=2, a malformed
    command line: one line on stderr holding every needle."""
    lines = err.strip().splitlines()
    check(code == status, f"exit {status} for an error, got {code}: {err!r}")
    check(len(lines) == 1, f"one line on stderr, got {lines!r}")
    for n in needles:
        check(n in err, f"{n!r} in {err!r}")


def usage_error(code, err, *needles):
    """A malformed command line: exit 2, one line."""
    one_line_error(code, err, *needles, status=2)


Png = collections.namedtuple("Png", "width height channels text rows")


def _unfilter(raw, w, h, ch, path):
    """The rows of an image's IDAT data (decompressed) without the PNG row
    filters (none, sub, up, average, Paeth)."""
    stride, rows, prev = w * ch, [], bytearray(w * ch)
    check(len(raw) == h * (stride + 1), f"{path}: {len(raw)} bytes of rows for {h} of {stride} + 1")
    bad = []
    for y in range(h):
        start = y * (stride + 1)
        ft, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        if ft > 4:
            bad.append((y, ft))
        if ft == 1:
            for i in range(ch, stride):
                line[i] = (line[i] + line[i - ch]) & 255
        elif ft == 2:
            line = bytearray((x + up) & 255 for x, up in zip(line, prev))
        elif ft == 3:
            for i in range(stride):
                line[i] = (line[i] + ((line[i - ch] if i >= ch else 0) + prev[i]) // 2) & 255
        elif ft == 4:
            for i in range(stride):
                a = line[i - ch] if i >= ch else 0
                b, c = prev[i], prev[i - ch] if i >= ch else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    check(not bad, f"{path}: unknown row filters (row, filter): {bad[:5]}")
    return rows


def png_read(path, pixels=True):
    """The 8-bit RGB or RGBA PNG at path, chunk by chunk, its signature and
    every chunk's CRC checked: a Png of width, height, channels (3 or 4),
    text ({tEXt key: value}) and, with pixels, rows (each row's bytes, the
    row filters undone; else [])."""
    with open(path, "rb") as f:
        data = f.read()
    check(data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: PNG signature")
    pos, text, idat, w, h, depth, ctype, bad = 8, {}, b"", 0, 0, 0, 0, []
    while pos + 8 <= len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        crc = data[pos + 8 + n:pos + 12 + n]
        if len(crc) != 4 or zlib.crc32(kind + body) != struct.unpack(">I", crc)[0]:
            bad.append(kind)
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            idat += body
        elif kind == b"tEXt":
            k, v = body.split(b"\0", 1)
            text[k.decode("latin-1")] = v.decode("latin-1")
        pos += 12 + n
    check(not bad, f"{path}: the CRC of every chunk (wrong: {bad})")
    ok = depth == 8 and ctype in (2, 6)
    check(ok, f"{path}: 8-bit RGB(A) expected, got depth {depth} type {ctype}")
    ch = 4 if ctype == 6 else 3
    rows = _unfilter(zlib.decompress(idat), w, h, ch, path) if pixels and ok else []
    return Png(w, h, ch, text, rows)


def finish(name):
    """Print the count and exit non-zero on any failure."""
    print(f"{name}: {_count['checks']} checks, {_count['failures']} failed")
    sys.exit(1 if _count["failures"] else 0)
