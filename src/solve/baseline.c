/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The floor every contact solve is measured against (doc/design.md §5): one
 * analysis, factorisation and solve of K with CHOLMOD's default ordering.
 * Springs diag(K) on the contact dofs make K definite when only the contact
 * holds the body (as on 'hertz'); they change values, not the cost. */
#include "solve/solve.h"

int cx_problem_baseline(const cx_problem *p, double *seconds, cx_diag *d)
{
    cx_csc A = {0};
    cx_fact *F = NULL;
    double *x = NULL;
    int st = cx_csc_copy(&A, &p->K);
    if (st)
        return cx_diag_set(d, st, "out of memory");
    for (int k = 0; k < p->nc; k++) {
        int j = p->cdofs[k];
        for (int q = A.p[j]; q < A.p[j + 1]; q++)
            if (A.i[q] == j)
                A.x[q] *= 2;
    }
    x = CX_NEW(double, p->n);
    if (!x) {
        st = cx_diag_set(d, CX_ENOMEM, "out of memory");
        goto done;
    }
    double t0 = cx_clock_now();
    if ((st = cx_fact_create(&F, CX_FACT_CHOLESKY, NULL, d)) ||
        (st = cx_fact_analyze(F, &A, d)) ||
        (st = cx_fact_factorize(F, &A, d)) ||
        (st = cx_fact_solve(F, p->f, x, d)))
        goto done;
    *seconds = cx_clock_now() - t0;
done:
    cx_fact_destroy(&F);
    cx_free(x);
    cx_csc_clear(&A);
    return st;
}
