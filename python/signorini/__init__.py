# SPDX-License-Identifier: GPL-3.0-or-later
"""signorini: elastic contact problems with and without friction, from
Python, over libsignorini.so (cffi, ABI mode).

    import signorini
    s = signorini.Session(signorini.Problem.scene("hertz"), friction="coulomb", F=0.3)
    s.set_method("ssn-coulomb", rho=1e-3)
    s.solve()
    s.u, s.lN, s.lT, s.status, s.history["kkt"], s.counters

A problem comes from a scene (Problem.scene), from scipy.sparse matrices
and numpy arrays (Problem.from_arrays) or from the files of 'signorini
export' (Problem.read), in the convention of the README's
"The discrete problem":
    K u - f + N' lN + T' lT = 0,  N u - g <= 0,  lN >= 0,
    |lT_i| <= s_i (Tresca) or F_i lN_i (Coulomb).
A session takes the problem (it cannot be given to a second one)."""
import numpy as np

from ._ffi import ffi, lib, lib_path

__all__ = ["Problem", "Session", "SignoriniError", "methods", "lib_path"]

FRICTION = {"none": 0, "tresca": 1, "coulomb": 2}
STATUS = {0: "free", 1: "contact", 2: "stick", 3: "slip+", 4: "slip-"}


class SignoriniError(RuntimeError):
    """A failed call: the library's one-line message."""


def _check(status, diag):
    if status != 0:
        raise SignoriniError(ffi.string(diag.msg).decode("utf-8", "replace") or
                             ffi.string(lib.cx_status_str(status)).decode())


def methods():
    """The registered methods: a list of dicts (id, name, source, summary)."""
    out = []
    for k in range(lib.cx_method_count()):
        m = lib.cx_method_at(k)
        out.append({key: ffi.string(getattr(m, key)).decode() for key in ("id", "name", "source", "summary")})
    return out


def _sparse(A, nrow, ncol, name, keep):
    """A scipy.sparse matrix (or anything with .tocsc()) as cx_sparse_data (CSC)."""
    import scipy.sparse as sp
    A = sp.csc_matrix(A, dtype=np.float64)
    if A.shape != (nrow, ncol):
        raise ValueError(f"{name}: shape {A.shape}, expected {(nrow, ncol)}")
    A.sort_indices()
    p = np.ascontiguousarray(A.indptr, dtype=np.int32)
    i = np.ascontiguousarray(A.indices, dtype=np.int32)
    x = np.ascontiguousarray(A.data, dtype=np.float64)
    keep += [p, i, x]
    s = ffi.new("cx_sparse_data *")
    s.form = 0
    s.nrow, s.ncol = nrow, ncol
    s.p = ffi.cast("const int *", ffi.from_buffer(p))
    s.i = ffi.cast("const int *", ffi.from_buffer(i))
    s.x = ffi.cast("const double *", ffi.from_buffer(x))
    return s[0]


def _vec(v, n, name, keep, default=None):
    if v is None:
        if default is None:
            return ffi.NULL
        v = np.full(n, default)
    a = np.ascontiguousarray(v, dtype=np.float64).ravel()
    if a.size != n:
        raise ValueError(f"{name}: {a.size} values, expected {n}")
    keep.append(a)
    return ffi.cast("const double *", ffi.from_buffer(a))


class Problem:
    """A discrete contact problem (owned until a Session takes it)."""

    def __init__(self, ptr, friction=None):
        self._pp = ptr            # cx_problem ** holding the problem
        self.friction = friction  # the scene's law and values (dict) or None

    @classmethod
    def scene(cls, scene, level=0):
        """The problem of a scene (id or .ini path) at a level (0: the scene's)."""
        pp = ffi.new("cx_problem **")
        fr = ffi.new("cx_friction_state *")
        d = ffi.new("cx_diag *")
        _check(lib.cx_problem_from_scene(scene.encode(), level, pp, fr, d), d)
        law = {v: k for k, v in FRICTION.items()}[fr.law]
        return cls(pp, {"law": law, "slip_bound": fr.slip_bound, "F": fr.F})

    @classmethod
    def read(cls, path):
        """The problem of 'signorini export': a directory of MatrixMarket
        files or an FCLIB .hdf5. Its friction law and per-point values are
        the session's defaults (friction: the law, F, slip, and per point
        'mu' or 'slip_points' as numpy arrays)."""
        pf = ffi.new("cx_problem_file *")
        d = ffi.new("cx_diag *")
        _check(lib.cx_problem_read(path.encode(), pf, d), d)
        m = pf.p.m
        law = {v: k for k, v in FRICTION.items()}[pf.fr.law]
        fr = {"law": law, "slip_bound": pf.fr.slip_bound, "F": pf.fr.F}
        if pf.Fi != ffi.NULL:
            fr["F"] = np.frombuffer(ffi.buffer(pf.Fi, 8 * m), dtype=np.float64).copy()
        if pf.s != ffi.NULL:
            fr["slip_bound"] = np.frombuffer(ffi.buffer(pf.s, 8 * m), dtype=np.float64).copy()
        pp = ffi.new("cx_problem **")
        pp[0] = pf.p            # the problem moves out of the file record
        pf.p = ffi.NULL
        lib.cx_problem_file_clear(pf)
        return cls(pp, fr)

    @classmethod
    def from_arrays(cls, K, f, N, T, g, dim, weight=None, x=None, E=0.0):
        """From scipy.sparse K (n x n, symmetric, both triangles), N (m x n),
        T (m (dim-1) x n) and numpy f (n), g (m); optional per-point weight
        (m, default 1), positions x (m x dim) and the stiffness scale E."""
        n = K.shape[0]
        m = N.shape[0]
        keep = []
        pd = ffi.new("cx_problem_data *")
        pd.dim, pd.n, pd.m = dim, n, m
        pd.K = _sparse(K, n, n, "K", keep)
        pd.K_lower = 0
        pd.f = _vec(f, n, "f", keep)
        pd.N = _sparse(N, m, n, "N", keep)
        pd.T = _sparse(T, (dim - 1) * m, n, "T", keep)
        pd.g = _vec(g, m, "g", keep)
        pd.weight = _vec(weight, m, "weight", keep)
        pd.x = _vec(None if x is None else np.asarray(x).ravel(), dim * m, "x", keep)
        pd.E = E
        pp = ffi.new("cx_problem **")
        d = ffi.new("cx_diag *")
        _check(lib.cx_problem_from_data(pp, pd, d), d)   # copies everything
        return cls(pp)

    def _dims(self):
        p = self._pp[0]
        if p == ffi.NULL:
            raise SignoriniError("this problem was given to a session")
        return p.dim, p.n, p.m

    @property
    def dim(self):
        return self._dims()[0]

    @property
    def n(self):
        return self._dims()[1]

    @property
    def m(self):
        return self._dims()[2]

    def __del__(self):
        if getattr(self, "_pp", None) is not None and self._pp[0] != ffi.NULL:
            lib.cx_problem_destroy(self._pp)


class Session:
    """A problem with a friction law and a method: step, solve, read the iterate.

    friction: "none", "tresca" or "coulomb" (default: the scene's, else none);
    F: the Coulomb coefficient (a number, or one per contact point);
    slip: the Tresca bound (a traction times each point's weight, or one
    nodal force per point)."""

    def __init__(self, problem, friction=None, F=None, slip=None):
        dims = problem._dims()
        self._s = ffi.new("cx_session **")
        d = ffi.new("cx_diag *")
        _check(lib.cx_session_create(self._s, problem._pp, d), d)   # takes the problem
        self.dim, self.n, self.m = dims
        self.history = {"kkt": np.empty(0), "own": np.empty(0), "time": np.empty(0)}
        self._rows = []
        sc = problem.friction or {"law": "none", "slip_bound": 0.0, "F": 0.0}
        self.set_friction(friction or sc["law"], sc["F"] if F is None else F,
                          sc["slip_bound"] if slip is None else slip)
        self.method = None

    def set_friction(self, law, F=0.0, slip=0.0):
        """The law and its values (scalars, or one value per point)."""
        keep = []
        fr = ffi.new("cx_friction_state *")
        fr.law = FRICTION[law]
        if np.ndim(F) == 0:
            fr.F = float(F)
        else:
            fr.Fi = _vec(F, self.m, "F", keep)
        if np.ndim(slip) == 0:
            fr.slip_bound = float(slip)
        else:
            fr.s = _vec(slip, self.m, "slip", keep)
        d = ffi.new("cx_diag *")
        _check(lib.cx_session_set_friction(self._s[0], fr, d), d)   # copies the values
        self._new_run()

    def set_method(self, method, tol=1e-10, max_iter=500, own_stop=True, time_limit=0.0, **params):
        """Select a method (see methods()) with its parameters as keywords
        (rho=1e-3, r="auto", ...) and the stopping rules; a new run."""
        m = lib.cx_method_find(method.encode())
        if m == ffi.NULL:
            raise SignoriniError(f"unknown method '{method}'")
        pv = ffi.new("cx_param_values *")
        lib.cx_param_default(pv, m.params)
        d = ffi.new("cx_diag *")
        owner = f"method '{method}'".encode()
        for k, v in params.items():
            if isinstance(v, bool):
                v = "true" if v else "false"
            _check(lib.cx_param_set_pair(pv, f"{k}={v}".encode(), owner, d), d)
        opt = ffi.new("cx_options *")
        lib.cx_options_default(opt)
        opt.tol, opt.max_iter, opt.own_stop, opt.time_limit = tol, max_iter, int(own_stop), time_limit
        _check(lib.cx_session_set_method(self._s[0], m, pv, opt, d), d)
        self.method = method
        self._new_run()

    def reset(self):
        """Restart the current method from its initial guess."""
        d = ffi.new("cx_diag *")
        _check(lib.cx_session_reset(self._s[0], d), d)
        self._new_run()

    def _new_run(self):
        self._rows = []
        self._update_history()

    def _update_history(self):
        rows = np.array(self._rows, dtype=float).reshape(-1, 3)
        self.history = {"kkt": rows[:, 0], "own": rows[:, 1], "time": rows[:, 2]}

    def step(self):
        """One iteration; returns the outcome id ("iterating", "converged", ...)."""
        if self.method is None:
            raise SignoriniError("no method: call set_method first")
        d = ffi.new("cx_diag *")
        before = self._it.iter
        _check(lib.cx_solver_step(self._s[0], d), d)
        it = self._it
        if it.iter != before:
            self._rows.append((it.kkt, it.own, it.time))
            self._update_history()
        return self.reason

    def solve(self):
        """Step until the run ends; returns the outcome id."""
        while self.step() == "iterating":
            pass
        return self.reason

    @property
    def _it(self):
        return lib.cx_session_iterate(self._s[0])

    def _array(self, ptr, count, dtype=np.float64):
        if count == 0 or ptr == ffi.NULL:
            return np.zeros(0, dtype=dtype)
        size = ffi.sizeof("double") if dtype == np.float64 else 1
        return np.frombuffer(ffi.buffer(ptr, count * size), dtype=dtype).copy()

    @property
    def u(self):
        """The displacement (n), the whole iterate (completed if partial)."""
        d = ffi.new("cx_diag *")
        _check(lib.cx_session_complete_iterate(self._s[0], d), d)
        return self._array(self._it.u, self.n)

    @property
    def lN(self):
        return self._array(self._it.lN, self.m)

    @property
    def lT(self):
        return self._array(self._it.lT, (self.dim - 1) * self.m)

    @property
    def status(self):
        """Per contact point: 0 free, 1 contact, 2 stick, 3 slip+, 4 slip- (STATUS)."""
        return self._array(self._it.status, self.m, np.uint8)

    @property
    def kkt(self):
        return self._it.kkt

    @property
    def kkt_parts(self):
        k = self._it.kkt_parts
        return {"total": k.total, "equilibrium": k.equilibrium, "contact": k.contact, "friction": k.friction}

    @property
    def iterations(self):
        return self._it.iter

    @property
    def reason(self):
        return ffi.string(lib.cx_reason_id(self._it.reason)).decode()

    @property
    def converged(self):
        return self.reason == "converged"

    @property
    def outcome(self):
        buf = ffi.new("char[]", 1024)
        return ffi.string(lib.cx_session_outcome(self._s[0], buf, 1024)).decode()

    @property
    def counters(self):
        """The run's work: factorisations, solves, products with K, ..."""
        c = self._it.counters
        out = {k: getattr(c, k) for k in ("factorizations", "solves", "matvecs", "dual_products", "updates",
                                          "dense_factorizations")}
        out["time"] = self._it.time
        out["inner"] = self._it.inner_total
        return out

    @property
    def counts(self):
        it = self._it
        return {"free": it.nfree, "contact": it.ncontact, "stick": it.nstick, "slip": it.nslip,
                "changed": it.nchanged}

    def close(self):
        if getattr(self, "_s", None) is not None and self._s[0] != ffi.NULL:
            lib.cx_session_destroy(self._s)

    def __del__(self):
        self.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
