#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The layer order of doc/design.md §1, checked on every #include of src/:
a layer includes only its own headers and those of the layers below it.
The program layers (cli/, tui/) sit on top and never include each other,
nor declare or call each other's functions (cli_*, tui_*) by hand. The
program itself, src/main.c, stands above them all and is the one file of
src/ outside a layer: it may include any layer. The library (base/ up to
render/) installs no signal handler: Ctrl-C belongs to the programs.
The PETSc backend (petsc/) sits above solve/ in its own library; no other
file includes a PETSc or MPI header, so that the core library and the
Python package pull in MPI only when asked."""
import os
import re
import sys

ORDER = ["base", "linalg", "mesh", "fem", "contact", "solve", "petsc", "scene", "out", "render", "bench"]
PROGRAM = ["tui", "cli"]

src = sys.argv[1]
rank = {name: i for i, name in enumerate(ORDER)}
for name in PROGRAM:
    rank[name] = len(ORDER)
MAIN = "main.c"   # the program: above every layer
include = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/[^"]+"')
# a function of the other program layer named in code (a call or a
# hand-written prototype), outside comments
call = {"cli": re.compile(r'\btui_[a-z0-9_]+\s*\('), "tui": re.compile(r'\bcli_[a-z0-9_]+\s*\(')}
comment = re.compile(r'/\*.*?\*/|//[^\n]*', re.S)
LIBRARY = ORDER[:ORDER.index("render") + 1]
handler = re.compile(r'\b(signal|sigaction)\s*\(')
external_mpi = re.compile(r'^\s*#\s*include\s+<(petsc[a-z]*\.h|mpi\.h)>')
bad = []
for layer in sorted(os.listdir(src)):
    path = os.path.join(src, layer)
    if not os.path.isdir(path):
        if layer == MAIN:
            with open(path, encoding="utf-8") as f:
                for lineno, line in enumerate(f, 1):
                    m = include.match(line)
                    if m and m.group(1) not in rank:
                        bad.append(f"src/{MAIN}:{lineno}: includes unknown layer '{m.group(1)}'")
        elif layer.endswith((".c", ".h")):
            bad.append(f"src/{layer}: only the program (src/{MAIN}) lives outside a layer")
        continue
    if layer not in rank:
        bad.append(f"src/{layer}/: not a known layer (add it to the order in {__file__})")
        continue
    for name in sorted(os.listdir(path)):
        if not name.endswith((".c", ".h")):
            continue
        with open(os.path.join(path, name), encoding="utf-8") as f:
            text = f.read()
        code = comment.sub(lambda m: "\n" * m.group(0).count("\n"), text)
        if layer in LIBRARY:
            for lineno, line in enumerate(code.splitlines(), 1):
                if handler.search(line):
                    bad.append(f"src/{layer}/{name}:{lineno}: the library installs no signal handler "
                               f"(the programs own Ctrl-C)")
        if layer in call:
            for lineno, line in enumerate(code.splitlines(), 1):
                for m in call[layer].finditer(line):
                    bad.append(f"src/{layer}/{name}:{lineno}: '{layer}' names '{m.group(0).rstrip('( ')}' "
                               f"of the other program layer (the program, src/{MAIN}, joins them)")
        for lineno, line in enumerate(text.splitlines(), 1):
            if layer != "petsc" and external_mpi.match(line):
                bad.append(f"src/{layer}/{name}:{lineno}: only src/petsc/ includes PETSc or MPI headers")
            m = include.match(line)
            if not m or m.group(1) == layer:
                continue
            dep = m.group(1)
            if dep not in rank:
                bad.append(f"src/{layer}/{name}:{lineno}: includes unknown layer '{dep}'")
            elif rank[dep] > rank[layer] or (dep in PROGRAM and layer in PROGRAM):
                bad.append(f"src/{layer}/{name}:{lineno}: '{layer}' must not include the higher layer '{dep}'")
if not os.path.isfile(os.path.join(src, MAIN)):
    bad.append(f"src/{MAIN}: missing (the program's entry point lives there, above cli/ and tui/)")
for b in bad:
    print(b)
print(f"layers: {len(bad)} violations")
sys.exit(1 if bad else 0)
