# SPDX-License-Identifier: GPL-3.0-or-later
"""Three methods on the Hertz scene (frictionless): the kkt error per iteration."""
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import signorini

for method in ("ssn-tresca", "pdas", "ubr-c"):
    s = signorini.Session(signorini.Problem.scene("hertz"))
    s.set_method(method)
    print(f"{method:10s} {s.solve():11s} {s.iterations:3d} iterations, kkt {s.kkt:.2e}, "
          f"{s.counters['factorizations']} factorisations, {(s.status > 0).sum()} of {s.m} points in contact")
    plt.semilogy(range(1, s.iterations + 1), s.history["kkt"], "o-", label=method)
plt.xlabel("iteration"), plt.ylabel("kkt error"), plt.title("hertz"), plt.legend()
plt.savefig(sys.argv[1] if len(sys.argv) > 1 else "compare.png", dpi=100)
