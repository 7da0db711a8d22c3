# SPDX-License-Identifier: GPL-3.0-or-later
"""The Python package against the installed library (run by
tests/install/test_python.sh with /usr/bin/python3 -m pytest)."""
import numpy as np
import pytest
import scipy.sparse as sp

import signorini


def chain(M=30, mu=0.4):
    """The spring chain of examples/arrays.c as scipy matrices: node k has
    (ux, uy) at 2k, 2k+1, pushed along +x and down onto a valley."""
    n = 2 * M
    rows, cols, vals = [], [], []

    def spring(a, b, k):
        rows.extend([a, b, a, b]), cols.extend([a, b, b, a]), vals.extend([k, k, -k, -k])

    for k in range(M):
        if k + 1 < M:
            spring(2 * k, 2 * k + 2, 100.0)
            spring(2 * k + 1, 2 * k + 3, 50.0)
        rows.extend([2 * k, 2 * k + 1]), cols.extend([2 * k, 2 * k + 1]), vals.extend([1.0, 1.0])
    K = sp.coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsc()
    f = np.tile([0.4, -1.0], M)
    x = np.linspace(-0.5, 0.5, M)
    g = 0.2 + x ** 2
    N = sp.coo_matrix((-np.ones(M), (np.arange(M), 2 * np.arange(M) + 1)), shape=(M, n))
    T = sp.coo_matrix((np.ones(M), (np.arange(M), 2 * np.arange(M))), shape=(M, n))
    return K, f, N, T, g, np.full(M, mu)


def test_methods_listed():
    ids = [m["id"] for m in signorini.methods()]
    assert "ssn-tresca" in ids and "ssn-coulomb" in ids and "pdas" in ids
    assert signorini.lib_path


def test_scene_hertz():
    p = signorini.Problem.scene("hertz")
    assert (p.dim, p.m) == (2, 33) and p.n > 1000
    s = signorini.Session(p)
    s.set_method("ssn-tresca")
    assert s.solve() == "converged" and s.converged
    assert s.kkt <= 1e-10
    assert len(s.history["kkt"]) == s.iterations >= 2
    assert s.history["kkt"][-1] == s.kkt
    assert s.history["kkt"][0] > 1e3 * s.kkt      # it converged from far
    u, lN, st = s.u, s.lN, s.status
    assert u.shape == (s.n,) and lN.shape == (33,) and s.lT.shape == (33,)
    assert np.all(lN >= 0) and np.all(np.isfinite(u))
    assert set(np.unique(st)) <= {0, 1}             # frictionless: free or contact
    assert (st == 1).sum() == s.counts["contact"] == (lN > 0).sum()
    # Hertz's load 800 (quarter model) is carried by the contact forces
    assert abs(lN.sum() - 800) < 1e-6 * 800
    assert s.counters["factorizations"] >= 1 and s.counters["solves"] >= 1
    with pytest.raises(signorini.SignoriniError, match="given to a session"):
        p.n


def test_step_equals_solve():
    a = signorini.Session(signorini.Problem.scene("hertz"), friction="coulomb", F=0.3)
    a.set_method("ssn-coulomb")
    a.solve()
    b = signorini.Session(signorini.Problem.scene("hertz"), friction="coulomb", F=0.3)
    b.set_method("ssn-coulomb")
    reasons = [b.step() for _ in range(a.iterations)]
    assert reasons[-1] == "converged" and set(reasons[:-1]) <= {"iterating"}
    assert np.array_equal(a.u, b.u) and np.array_equal(a.history["kkt"], b.history["kkt"])
    assert np.any(b.status >= 2)                    # Coulomb: stick or slip points


def test_arrays_coulomb_kkt():
    K, f, N, T, g, mu = chain()
    s = signorini.Session(signorini.Problem.from_arrays(K, f, N, T, g, dim=2), friction="coulomb", F=mu)
    s.set_method("ssn-coulomb")
    assert s.solve() == "converged"
    u, lN, lT = s.u, s.lN, s.lT
    # the conditions of the README's "The discrete problem", checked here
    r = K @ u - f + N.T @ lN + T.T @ lT
    assert np.linalg.norm(r) <= 1e-8 * np.linalg.norm(f)
    assert np.all(N @ u - g <= 1e-10) and np.all(lN >= 0)
    assert np.all(np.abs(lT) <= mu * lN + 1e-10)
    slip = s.status >= 3
    assert slip.any() and np.all(lN[slip] > 0)
    assert np.allclose(np.abs(lT[slip]), mu[slip] * lN[slip], rtol=1e-8)
    # a point that slips moves along its friction force: (T u) lT >= 0
    assert np.all((T @ u)[slip] * lT[slip] >= 0)


def test_arrays_tresca_per_point_and_other_methods():
    K, f, N, T, g, _ = chain(20)
    bounds = np.linspace(0.05, 0.5, 20)
    results = {}
    for method in ("ssn-tresca", "ssn-tresca-dual", "ssn-tresca-glob"):
        s = signorini.Session(signorini.Problem.from_arrays(K, f, N, T, g, dim=2), friction="tresca", slip=bounds)
        s.set_method(method, tol=1e-11)
        assert s.solve() == "converged", (method, s.outcome)
        assert np.all(np.abs(s.lT) <= bounds + 1e-9)
        results[method] = s.u
    for m, u in results.items():
        assert np.linalg.norm(u - results["ssn-tresca"]) <= 1e-8 * np.linalg.norm(u), m


def test_parameters_and_errors():
    s = signorini.Session(signorini.Problem.scene("hertz"))
    with pytest.raises(signorini.SignoriniError, match="unknown method 'nope'"):
        s.set_method("nope")
    with pytest.raises(signorini.SignoriniError, match="rho"):
        s.set_method("ssn-tresca", rho=-1)
    s.set_method("ssn-tresca", rho=1e-2, max_iter=2, own_stop=False)
    assert s.solve() in ("converged", "max_iter") and s.iterations <= 2
    K, f, N, T, g, _ = chain(5)
    K = K.tolil()
    K[0, 2] += 1.0                                  # no longer symmetric
    with pytest.raises(signorini.SignoriniError, match="K: not symmetric at row 2, column 0"):
        signorini.Problem.from_arrays(K.tocsc(), f, N, T, g, dim=2)
    with pytest.raises(signorini.SignoriniError, match="g: entry 1 is -1"):
        signorini.Problem.from_arrays(chain(5)[0], f, N, T, np.array([0, -1, 0, 0, 0.0]), dim=2)


def test_read_exported(tmp_path):
    """A problem exported by the installed program, read back: the same run."""
    import os
    import subprocess
    exe = os.path.join(os.path.dirname(signorini.lib_path), "..", "..", "bin", "signorini")
    if not os.path.exists(exe):
        pytest.skip("no installed program beside the library")
    d = str(tmp_path / "hertz.mm")
    subprocess.run([exe, "export", "hertz", "--friction", "coulomb", "--F", "0.3", "--format", "mm", d],
                   check=True, capture_output=True)
    p = signorini.Problem.read(d)
    assert p.friction["law"] == "coulomb" and np.allclose(p.friction["F"], 0.3)
    a = signorini.Session(p)
    a.set_method("ssn-coulomb")
    b = signorini.Session(signorini.Problem.scene("hertz"), friction="coulomb", F=0.3)
    b.set_method("ssn-coulomb")
    assert a.solve() == b.solve() == "converged"
    assert a.iterations == b.iterations and np.array_equal(a.u, b.u)
    with pytest.raises(signorini.SignoriniError, match="problem.json"):
        signorini.Problem.read(str(tmp_path))
