#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Every header of src/ compiles on its own (it includes what it uses)."""
import os
import subprocess
import sys
import tempfile

src, builddir = sys.argv[1], sys.argv[2]
cc = sys.argv[3:]
failed = 0
count = 0
with tempfile.TemporaryDirectory() as tmp:
    for layer in sorted(os.listdir(src)):
        d = os.path.join(src, layer)
        if not os.path.isdir(d):
            continue
        extra = []
        if layer == "petsc":   # the one layer built with PETSc and MPI (a build without them skips it)
            r = subprocess.run(["pkg-config", "--cflags", "PETSc", "mpi"], capture_output=True, text=True)
            if r.returncode != 0:
                continue
            extra = r.stdout.split()
        for name in sorted(os.listdir(d)):
            if not name.endswith(".h"):
                continue
            count += 1
            unit = os.path.join(tmp, "unit.c")
            with open(unit, "w") as f:
                f.write(f'#include "{layer}/{name}"\n#include "{layer}/{name}"\n')
            r = subprocess.run(cc + ["-std=c11", "-D_POSIX_C_SOURCE=200809L", "-Wall", "-Wextra",
                                     "-Werror", "-fsyntax-only", "-I", src, "-I", builddir,
                                     "-I/usr/include/suitesparse"] + extra + [unit],
                               capture_output=True, text=True)
            if r.returncode != 0:
                failed += 1
                print(f"src/{layer}/{name}: not self-contained\n{r.stderr}")
print(f"headers: {count} checked, {failed} failed")
sys.exit(1 if failed else 0)
