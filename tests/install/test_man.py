#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A man page exists for the program and every command, and mentions every
option of the command's help (bench: of every kind and paper too); groff
reads each page without a warning; the bash and zsh completions name every
option too, and bash completes commands, options, scenes and methods."""
import os
import re
import shutil
import subprocess
import sys

exe, mandir, bashfile, zshfile = sys.argv[1:5]
commands = sys.argv[5:]
with open(bashfile, encoding="utf-8") as f:
    bash = f.read()
with open(zshfile, encoding="utf-8") as f:
    zsh = f.read()
failed = []


def helptext(*args):
    r = subprocess.run([exe, *args, "--help"], capture_output=True, text=True)
    if r.returncode != 0:
        failed.append(f"{' '.join(args)} --help: exit {r.returncode}")
    return r.stdout


def options(text):
    """The long options of the option rows ("  -x, --name ARG   help")."""
    names = []
    for line in text.splitlines():
        if line.startswith("  -"):
            names += re.findall(r"--([a-z0-9][a-z0-9-]*)", line.split("  ")[1])
    return names


def block_words(text, heading):
    m = re.search(r"^" + heading + r"\n((?:  .*\n)+)", text, re.M)
    return re.findall(r"^  ([a-z0-9]+)", m.group(1), re.M) if m else []


def page(name):
    path = os.path.join(mandir, name + ".1")
    if not os.path.isfile(path):
        failed.append(f"{name}.1: missing")
        return ""
    if shutil.which("groff"):
        r = subprocess.run(["groff", "-man", "-ww", "-z", path], capture_output=True, text=True)
        if r.stderr.strip():
            failed.append(f"{name}.1: groff: {r.stderr.strip()}")
    with open(path, encoding="utf-8") as f:
        return f.read()


top = page("signorini")
for c in commands:
    if f"signorini\\-{c}" not in top:
        failed.append(f"signorini.1: no SEE ALSO signorini-{c}")
    text = page("signorini-" + c)
    helps = [((c,), helptext(c))]
    if c == "bench":
        for k in block_words(helps[0][1], "kinds:"):
            helps.append(((c, k), helptext(c, k)))
        for p in block_words(helps[0][1], "papers:"):
            helps.append(((c, "paper", p), helptext(c, "paper", p)))
        if len(helps) < 5:
            failed.append(f"bench: only {len(helps)} helps found")
    count = 0
    for args, h in helps:
        opts = options(h)
        for o in opts:
            count += 1
            if "\\-\\-" + o.replace("-", "\\-") not in text:
                failed.append(f"signorini-{c}.1: no --{o} (of '{' '.join(args)} --help')")
            ctx = " ".join(args)
            bctx = re.search(r"^    '" + re.escape(ctx) + r"'\)\n        opts='([^']*)'", bash, re.M)
            if not bctx or "--" + o not in bctx.group(1).split():
                failed.append(f"bash completion: no --{o} in '{ctx}'")
            zctx = re.search(r"^  '" + re.escape(ctx) + r"'\)\n    _arguments -s \\\n((?:      .*\n)+)", zsh, re.M)
            if not zctx or f"'--{o}[" not in zctx.group(1):
                failed.append(f"zsh completion: no --{o} in '{ctx}'")
    if count == 0:
        failed.append(f"signorini-{c}.1: no options found in its helps")
    print(f"signorini-{c}.1: {count} options of {len(helps)} helps")

# bash: what a user gets for a few partial command lines
script = f""". '{bashfile}'
t() {{ COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); COMPREPLY=(); _signorini; echo "${{COMPREPLY[*]}}"; }}
t '{exe}' so
t '{exe}' solve he
t '{exe}' solve hertz --max
t '{exe}' solve hertz --method ssn-tresca-g
t '{exe}' bench st
t '{exe}' render hertz --view c
"""
want = ["solve", "hertz hertz-paper", "--max-iter", "ssn-tresca-glob", "stress", "contact"]
got = subprocess.run(["bash", "-c", script], capture_output=True, text=True).stdout.splitlines()
if got != want:
    failed.append(f"bash completion: got {got}, expected {want}")
if shutil.which("zsh"):
    r = subprocess.run(["zsh", "-n", zshfile], capture_output=True, text=True)
    if r.returncode:
        failed.append(f"zsh -n: {r.stderr.strip()}")

for f in failed:
    print("FAIL", f)
sys.exit(1 if failed else 0)
