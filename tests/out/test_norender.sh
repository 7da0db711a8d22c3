#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# --vtu in a build without the renderer: configure a second build directory
# with -Drender=disabled -Dtests=false, build it, and check that
# 'signorini solve hertz --level 8 --vtu X.vtu' writes a VTU there (no GL
# is needed for VTU), while --png is refused with one line. A meson test
# registered only in such a build would never run in CI, hence this script.
#   usage: tests/out/test_norender.sh [BUILDDIR]   (default: build-norender)
set -eu
cd "$(dirname "$0")/../.."
builddir=${1:-build-norender}
if [ ! -f "$builddir/build.ninja" ]; then
    meson setup "$builddir" -Drender=disabled -Dtests=false >/dev/null
else
    meson configure "$builddir" -Drender=disabled -Dtests=false >/dev/null
fi
ninja -C "$builddir" >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export SIGNORINI_SCENES="$PWD/scenes"
fail=0
if ! "$builddir/signorini" solve hertz --level 8 --quiet --vtu "$tmp/X.vtu" >"$tmp/out" 2>"$tmp/err"; then
    echo "FAIL: solve --vtu exits non-zero without the renderer: $(cat "$tmp/err")"
    fail=1
fi
if ! head -c 200 "$tmp/X.vtu" 2>/dev/null | grep -q '<VTKFile type="UnstructuredGrid"' ||
   ! tail -c 20 "$tmp/X.vtu" | grep -q '</VTKFile>' ||
   ! grep -q 'NumberOfPoints="81" NumberOfCells="128"' "$tmp/X.vtu"; then
    echo "FAIL: $tmp/X.vtu is not the VTU of hertz level 8 (81 points, 128 triangles)"
    fail=1
fi
if ls "$tmp" | grep -q '\.tmp'; then
    echo "FAIL: a temporary file was left"
    fail=1
fi
code=0
"$builddir/signorini" solve hertz --level 8 --quiet --png "$tmp/X.png" >/dev/null 2>"$tmp/err" || code=$?
if [ "$code" != 1 ] || [ "$(wc -l <"$tmp/err")" != 1 ] || ! grep -q -- '--png' "$tmp/err" || [ -e "$tmp/X.png" ]; then
    echo "FAIL: --png without the renderer: exit $code, '$(cat "$tmp/err")' (expected 1 and one line)"
    fail=1
fi
if [ $fail = 0 ]; then
    echo "norender: --vtu works and --png is refused in a -Drender=disabled build"
fi
exit $fail
