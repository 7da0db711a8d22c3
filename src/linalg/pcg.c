/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Preconditioned conjugate gradients (Jacobi). The tests are written so
 * that a NaN anywhere ends the iteration as a failure, never as success. */
#include "linalg/linalg.h"

#include <string.h>

int cx_pcg(int n, cx_apply_fn apply, void *ctx, const double *inv_diag, const double *b, double *x,
           double rtol, int maxit, int *iters, double *work, cx_diag *d)
{
    return cx_pcg_stop(n, apply, ctx, inv_diag, b, x, rtol, maxit, NULL, NULL, iters, work, d);
}

int cx_pcg_stop(int n, cx_apply_fn apply, void *ctx, const double *inv_diag, const double *b,
                double *x, double rtol, int maxit, cx_stop_fn stop, void *stop_ctx, int *iters,
                double *work, cx_diag *d)
{
    double *r = work, *z = work + n, *p = work + 2 * n, *q = work + 3 * n;
    double nb = cx_vec_norm2(n, b);
    *iters = 0;
    if (nb == 0) {   /* ||r|| <= rtol * 0: only x = 0 */
        memset(x, 0, sizeof(double) * (size_t)n);
        return CX_OK;
    }
    double target = rtol * nb;
    apply(ctx, x, q);
    for (int i = 0; i < n; i++) {
        r[i] = b[i] - q[i];
        z[i] = inv_diag ? inv_diag[i] * r[i] : r[i];
    }
    memcpy(p, z, sizeof(double) * (size_t)n);
    double rz = cx_vec_dot(n, r, z), rn = cx_vec_norm2(n, r);
    int k = 0;
    for (; k < maxit && !(rn <= target); k++) {
        if (stop && k > 0 && k % CX_PCG_CHECK_INTERVAL == 0 && stop(stop_ctx)) {
            *iters = k;
            return cx_diag_set(d, CX_ENUMERIC, "pcg: interrupted at iteration %d", k);
        }
        apply(ctx, p, q);
        double pq = cx_vec_dot(n, p, q);
        if (!(pq > 0)) {
            *iters = k;
            return cx_diag_set(d, CX_ENUMERIC, "pcg: breakdown at iteration %d (p'Ap = %g)", k, pq);
        }
        double alpha = rz / pq;
        cx_vec_axpy(n, alpha, p, x);
        cx_vec_axpy(n, -alpha, q, r);
        for (int i = 0; i < n; i++)
            z[i] = inv_diag ? inv_diag[i] * r[i] : r[i];
        double rz1 = cx_vec_dot(n, r, z), beta = rz1 / rz;
        rz = rz1;
        for (int i = 0; i < n; i++)
            p[i] = z[i] + beta * p[i];
        rn = cx_vec_norm2(n, r);
    }
    *iters = k;
    if (!(rn <= target))
        return cx_diag_set(d, CX_ENUMERIC, "pcg: no convergence in %d iterations (residual %g, target %g)", k,
                           rn, target);
    return CX_OK;
}
