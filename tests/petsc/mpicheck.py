# SPDX-License-Identifier: GPL-3.0-or-later
"""Shared by the PETSc backend's end-to-end tests: the program (argv[1])
run alone or under mpirun -n N, checks that count and print the run's
output when they fail, and the exit with the count."""
import os
import shutil
import subprocess
import sys

exe = sys.argv[1]
_failed = 0


def run(args, mpi=0, env=None):
    """The program with args, under mpirun -n mpi when mpi > 0, with the
    variables of env added to the environment."""
    cmd = ([shutil.which("mpirun"), "-n", str(mpi)] if mpi else []) + [exe] + args
    return subprocess.run(cmd, capture_output=True, text=True, timeout=500,
                          env=dict(os.environ, **env) if env else None)


def check(cond, what, r=None):
    """Count a check; on failure print it and the tail of run r's output."""
    global _failed
    if not cond:
        _failed += 1
        print(f"FAIL: {what}")
        if r is not None:
            print(r.stdout[-3000:], r.stderr[-3000:])
    else:
        print(f"ok: {what}")


def finish(name):
    print(f"{name}: {_failed} failed")
    sys.exit(1 if _failed else 0)
