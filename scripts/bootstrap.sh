#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Install what signorini needs on Debian 12 (when missing), then configure
# and build it in ./build. Safe to run again: it only does what is missing.
# clang and libclang-rt-14-dev (libclang_rt.fuzzer, and the sanitizer
# runtimes) are for CI's fuzzing (tests/fuzz/run.sh), not for the build.
# Gmsh (user geometry), PETSc with OpenMPI (the parallel backend; with
# --no-install-recommends petsc-dev does not bring mpirun: openmpi-bin),
# FCLIB (problem exchange), giflib (animations), EGL (headless GL where
# OSMesa is gone); cffi and pytest for the Python package and its tests;
# numpy and scipy (the package's arrays, the VTU and materials tests) and
# matplotlib (python/examples/compare.py), which a bare Debian 12 lacks.
set -eu
cd "$(dirname "$0")/.."

packages="build-essential meson ninja-build pkg-config python3 \
libsuitesparse-dev libopenblas0 liblapack-dev libinih-dev \
libncurses-dev libosmesa6-dev libpng-dev libcairo2-dev fonts-dejavu-core tmux \
python3-vtk9 clang libclang-rt-14-dev locales \
libgmsh-dev petsc-dev openmpi-bin libfclib-dev libgif-dev \
libegl-dev libopengl-dev python3-cffi python3-pytest \
python3-numpy python3-scipy python3-matplotlib"

missing=""
for p in $packages; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
    if [ "$(id -u)" != 0 ]; then
        echo "bootstrap: missing Debian packages:$missing (run as root, or apt-get install them)" >&2
        exit 1
    fi
    echo "bootstrap: installing$missing" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q >&2
    apt-get install -y -q --no-install-recommends $missing >&2
fi

builddir=${BUILDDIR:-build}
if [ ! -f "$builddir/build.ninja" ]; then
    meson setup "$builddir" ${MESON_ARGS:-} >&2
fi
ninja -C "$builddir" >&2
