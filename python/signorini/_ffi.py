# SPDX-License-Identifier: GPL-3.0-or-later
"""The C declarations the package uses (cffi ABI mode: no compiler at
import) and the loading of libsignorini.so.0.

The structs below are copies of the installed headers' (solve/solve.h,
solve/problem.h, base/diag.h, base/param.h); cffi lays them out as the C
compiler does. cx_problem is declared by its leading fields only: the
package reads those and never allocates one (tests/test_signorini.py
checks the sizes against the library's results)."""
import os

import cffi

CDEF = """
typedef struct cx_diag { int status; char msg[512]; } cx_diag;

typedef struct cx_counters {
    long factorizations, solves, matvecs, dual_products, updates, dense_factorizations;
} cx_counters;

typedef struct cx_kkt { double total, equilibrium, contact, friction; } cx_kkt;

typedef struct cx_problem { int dim; int n; int m; int nt; } cx_problem;   /* leading fields */

typedef struct cx_friction_state {
    int law; double slip_bound; double F; const double *s; const double *Fi;
} cx_friction_state;

typedef struct cx_sparse_data {
    int form; int nrow, ncol; size_t nnz; const int *p; const int *i; const int *j; const double *x;
} cx_sparse_data;

typedef struct cx_problem_data {
    int dim; int n; int m;
    cx_sparse_data K; int K_lower; const double *f;
    cx_sparse_data N; cx_sparse_data T; const double *g;
    const double *weight; const double *x; double E;
} cx_problem_data;

typedef struct cx_options {
    double tol; int max_iter; int own_stop; int stall_window; double time_limit;
} cx_options;

typedef struct cx_param {
    const char *key; int type; double def; double min, max; const char *choices; const char *help;
    unsigned flags;
} cx_param;

typedef struct cx_param_values {
    const cx_param *table; int n; double num[24]; char str[24][48];
} cx_param_values;

typedef struct cx_method {
    const char *id; const char *name; const char *source; const char *summary;
    unsigned supports; size_t state_size; const cx_param *params;
    void *init; void *step; void *destroy;
} cx_method;

typedef struct cx_iterate {
    int iter; int reason; double kkt; cx_kkt kkt_parts; double own; int own_done; int progress;
    double *u; int u_partial; double *lN; double *lT;
    unsigned char *status; unsigned char *changed;
    int nfree, ncontact, nstick, nslip, nchanged;
    long inner; long inner_total; cx_counters counters;
    double step_time; double time; double init_time;
} cx_iterate;

typedef struct cx_session cx_session;

typedef struct cx_problem_file {
    cx_problem *p; cx_friction_state fr; double *s, *Fi; char format[8]; char source[256]; int level;
} cx_problem_file;
int cx_problem_read(const char *path, cx_problem_file *pf, cx_diag *d);
void cx_problem_file_clear(cx_problem_file *pf);

int cx_problem_from_data(cx_problem **p, const cx_problem_data *data, cx_diag *d);
int cx_problem_from_scene(const char *id_or_path, int level, cx_problem **p, cx_friction_state *fr,
                          cx_diag *d);
void cx_problem_destroy(cx_problem **p);

int cx_method_count(void);
const cx_method *cx_method_at(int i);
const cx_method *cx_method_find(const char *id);
void cx_param_default(cx_param_values *v, const cx_param *table);
int cx_param_set_pair(cx_param_values *v, const char *pair, const char *owner, cx_diag *d);
void cx_options_default(cx_options *o);

int cx_session_create(cx_session **s, cx_problem **p, cx_diag *d);
void cx_session_destroy(cx_session **s);
const cx_problem *cx_session_problem(const cx_session *s);
const cx_friction_state *cx_session_friction(const cx_session *s);
int cx_session_set_friction(cx_session *s, const cx_friction_state *fr, cx_diag *d);
int cx_session_set_method(cx_session *s, const cx_method *m, const cx_param_values *params,
                          const cx_options *opt, cx_diag *d);
int cx_session_reset(cx_session *s, cx_diag *d);
int cx_solver_step(cx_session *s, cx_diag *d);
int cx_session_complete_iterate(cx_session *s, cx_diag *d);
const cx_iterate *cx_session_iterate(const cx_session *s);
const cx_counters *cx_session_cache_counters(const cx_session *s);
const char *cx_reason_id(int reason);
char *cx_session_outcome(const cx_session *s, char *buf, size_t len);
const char *cx_status_str(int status);
"""

ffi = cffi.FFI()
ffi.cdef(CDEF)


def _candidates():
    env = os.environ.get("SIGNORINI_LIB")
    if env:
        yield env
    here = os.path.dirname(os.path.abspath(__file__))
    try:
        from . import _config
        yield os.path.normpath(os.path.join(here, _config.LIBDIR_FROM_PACKAGE, "libsignorini.so.0"))
    except ImportError:
        pass
    yield "libsignorini.so.0"   # the dynamic loader's search path


def _load():
    errors = []
    for path in _candidates():
        if os.sep in path and not os.path.exists(path):
            errors.append(path + ": no such file")
            continue
        try:
            return ffi.dlopen(path), path
        except OSError as e:
            errors.append(str(e))
    raise ImportError("signorini: cannot load libsignorini.so.0 (set SIGNORINI_LIB): " + "; ".join(errors))


lib, lib_path = _load()
