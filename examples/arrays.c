/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A problem from plain arrays (no scene, no mesh): a chain of M nodes in
 * the plane, joined by springs, each node pressed onto a rigid curved
 * ground below it with Coulomb friction, and pushed sideways. K comes as
 * triplets of its lower triangle, N and T as triplets, the friction
 * coefficient per point. Build it against an installed signorini with
 *   cc arrays.c $(pkg-config --cflags --libs signorini)
 * usage: arrays [M [METHOD]]   (default: 40 ssn-coulomb) */
#include <signorini.h>

#include <stdio.h>
#include <stdlib.h>

/* unknowns: node k has (ux, uy) at 2k, 2k+1 */
static void spring(int *I, int *J, double *X, size_t *nnz, int a, int b, double k)
{
    /* k (u_a - u_b)^2 / 2: lower triangle (row >= column) only */
    int lo = a < b ? a : b, hi = a < b ? b : a;
    I[*nnz] = a, J[*nnz] = a, X[(*nnz)++] = k;
    I[*nnz] = b, J[*nnz] = b, X[(*nnz)++] = k;
    I[*nnz] = hi, J[*nnz] = lo, X[(*nnz)++] = -k;
}

int main(int argc, char **argv)
{
    int M = argc > 1 ? atoi(argv[1]) : 40;
    const char *method = argc > 2 ? argv[2] : "ssn-coulomb";
    if (M < 2 || M > 100000) {
        fprintf(stderr, "arrays: M from 2 to 100000\n");
        return 2;
    }
    int n = 2 * M;
    size_t cap = 12 * (size_t)M;
    int *I = malloc(cap * sizeof *I), *J = malloc(cap * sizeof *J);
    double *X = malloc(cap * sizeof *X);
    int *Ni = malloc(M * sizeof *Ni), *Nj = malloc(M * sizeof *Nj), *Ti = malloc(M * sizeof *Ti),
        *Tj = malloc(M * sizeof *Tj);
    double *Nx = malloc(M * sizeof *Nx), *Tx = malloc(M * sizeof *Tx), *f = calloc(n, sizeof *f),
           *g = malloc(M * sizeof *g), *mu = malloc(M * sizeof *mu);
    size_t nnz = 0;
    for (int k = 0; k < M; k++) {
        if (k + 1 < M) {
            spring(I, J, X, &nnz, 2 * k, 2 * k + 2, 100.0);       /* axial */
            spring(I, J, X, &nnz, 2 * k + 1, 2 * k + 3, 50.0);    /* shear */
        }
        I[nnz] = J[nnz] = 2 * k, X[nnz++] = 1.0;                  /* soft anchors: K is definite */
        I[nnz] = J[nnz] = 2 * k + 1, X[nnz++] = 1.0;
        double x = (double)k / (M - 1) - 0.5;
        f[2 * k] = 0.25;                                          /* pushed along +x */
        f[2 * k + 1] = -1.0;                                      /* and down */
        g[k] = 0.2 + x * x;                                       /* the ground: a valley below */
        Ni[k] = k, Nj[k] = 2 * k + 1, Nx[k] = -1.0;               /* moving down closes the gap */
        Ti[k] = k, Tj[k] = 2 * k, Tx[k] = 1.0;                    /* the tangent: +x */
        mu[k] = k < M / 2 ? 0.3 : 0.6;                            /* rougher on the right */
    }
    cx_problem_data pd = {
        .dim = 2, .n = n, .m = M,
        .K = {CX_SPARSE_TRIPLET, n, n, nnz, NULL, I, J, X}, .K_lower = 1,
        .f = f,
        .N = {CX_SPARSE_TRIPLET, M, n, (size_t)M, NULL, Ni, Nj, Nx},
        .T = {CX_SPARSE_TRIPLET, M, n, (size_t)M, NULL, Ti, Tj, Tx},
        .g = g,
    };
    cx_diag d;
    cx_problem *p = NULL;
    cx_session *s = NULL;
    int code = 1, st;
    if ((st = cx_problem_from_data(&p, &pd, &d)) || (st = cx_session_create(&s, &p, &d))) {
        fprintf(stderr, "arrays: %s\n", cx_diag_msg(&d, st));
        goto done;
    }
    /* Coulomb with a coefficient per point (the session copies them) */
    cx_friction_state fr = {CX_FRICTION_COULOMB, 0, 0.3, NULL, mu};
    const cx_method *m = cx_method_find(method);
    if (!m) {
        fprintf(stderr, "arrays: unknown method '%s'\n", method);
        goto done;
    }
    if ((st = cx_session_set_friction(s, &fr, &d)) || (st = cx_session_set_method(s, m, NULL, NULL, &d)) ||
        (st = cx_solver_solve(s, NULL, NULL, &d))) {
        fprintf(stderr, "arrays: %s\n", cx_diag_msg(&d, st));
        goto done;
    }
    const cx_iterate *it = cx_session_iterate(s);
    double lsum = 0;
    for (int i = 0; i < M; i++)
        lsum += it->lN[i];
    printf("chain of %d nodes, method %s: %d unknowns, %d contact points\n", M, m->id, n, M);
    printf("contact %d stick %d slip %d, sum of lN %.6g (load %.6g)\n", it->ncontact + it->nstick + it->nslip,
           it->nstick, it->nslip, lsum, (double)M);
    printf("kkt %.3e iterations %d reason %s\n", it->kkt, it->iter, cx_reason_id(it->reason));
    code = it->reason == CX_CONVERGED_KKT ? 0 : 3;
done:
    cx_session_destroy(&s);
    cx_problem_destroy(&p);
    free(I), free(J), free(X), free(Ni), free(Nj), free(Ti), free(Tj);
    free(Nx), free(Tx), free(f), free(g), free(mu);
    return code;
}
