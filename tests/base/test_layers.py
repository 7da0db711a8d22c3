#!/usr/bin/env python3
"""The layer order of DESIGN.md §1, checked on every #include of src/:
a layer includes only its own headers and those of the layers below it.
The program layers (cli/, tui/) sit on top and never include each other."""
import os
import re
import sys

ORDER = ["base", "linalg", "mesh", "fem", "contact", "solve", "scene", "out", "render", "bench"]
PROGRAM = ["tui", "cli"]

src = sys.argv[1]
rank = {name: i for i, name in enumerate(ORDER)}
for name in PROGRAM:
    rank[name] = len(ORDER)
include = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/[^"]+"')
bad = []
for layer in sorted(os.listdir(src)):
    path = os.path.join(src, layer)
    if not os.path.isdir(path):
        continue
    if layer not in rank:
        bad.append(f"src/{layer}/: not a known layer (add it to the order in {__file__})")
        continue
    for name in sorted(os.listdir(path)):
        if not name.endswith((".c", ".h")):
            continue
        with open(os.path.join(path, name), encoding="utf-8") as f:
            for lineno, line in enumerate(f, 1):
                m = include.match(line)
                if not m or m.group(1) == layer:
                    continue
                dep = m.group(1)
                if dep not in rank:
                    bad.append(f"src/{layer}/{name}:{lineno}: includes unknown layer '{dep}'")
                elif rank[dep] > rank[layer] or (dep in PROGRAM and layer in PROGRAM):
                    bad.append(f"src/{layer}/{name}:{lineno}: '{layer}' must not include the higher layer '{dep}'")
for b in bad:
    print(b)
print(f"layers: {len(bad)} violations")
sys.exit(1 if bad else 0)
