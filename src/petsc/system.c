/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The distributed system: K assembled element by element on the ranks,
 * the prescribed dofs, the rigid-body near null space, the contact rows as
 * one dof each. The mesh is every rank's (replicated): a rank reads all of
 * it to find its elements and its rows' pattern, and stores only its rows
 * of K. */
#include "petsc/petsc_impl.h"

#include <math.h>
#include <string.h>

/* The rank owning node k when nodes are split in size contiguous ranges. */
static int sys_node_owner(int nnodes, int size, int k)
{
    int r = (int)(((long long)k * size) / nnodes);
    /* the ranges are [nnodes r / size, nnodes (r + 1) / size) */
    while (r > 0 && k < (int)(((long long)nnodes * r) / size))
        r--;
    while (r + 1 < size && k >= (int)(((long long)nnodes * (r + 1)) / size))
        r++;
    return r;
}

/* An element is assembled by the owner of its first node (in the mesh's
 * generators, nodes and elements run in the same lattice order, so most
 * of an element's rows are its assembler's own). */
static int sys_elem_owner(const cx_mesh *m, int size, int e)
{
    return sys_node_owner(m->nnodes, size, m->conn[(size_t)m->npe * e]);
}

/* Preallocation of the owned rows: the nodes sharing an element with each
 * owned node, on this rank's range (d) or off it (o), times dim. */
static int sys_prealloc(const cx_mesh *m, int nstart, int nend, PetscInt *dnz, PetscInt *onz)
{
    int nn = m->nnodes, npe = m->npe, dim = m->dim;
    int *cnt = CX_NEW(int, nn + 1), *stamp = CX_NEW(int, nn);
    int *inc = NULL;
    if (!cnt || !stamp)
        goto nomem;
    /* node -> elements (CSR), for the owned nodes only */
    for (int e = 0; e < m->nelems; e++)
        for (int a = 0; a < npe; a++) {
            int k = m->conn[(size_t)npe * e + a];
            if (k >= nstart && k < nend)
                cnt[k + 1]++;
        }
    for (int k = 0; k < nn; k++)
        cnt[k + 1] += cnt[k];
    inc = CX_NEW(int, cnt[nn] > 0 ? cnt[nn] : 1);
    if (!inc)
        goto nomem;
    for (int e = 0; e < m->nelems; e++)
        for (int a = 0; a < npe; a++) {
            int k = m->conn[(size_t)npe * e + a];
            if (k >= nstart && k < nend)
                inc[cnt[k]++] = e;
        }
    for (int k = nn; k > 0; k--)
        cnt[k] = cnt[k - 1];
    cnt[0] = 0;
    for (int k = 0; k < nn; k++)
        stamp[k] = -1;
    for (int k = nstart; k < nend; k++) {
        int dl = 0, ol = 0;
        for (int q = cnt[k]; q < cnt[k + 1]; q++) {
            const int *c = m->conn + (size_t)npe * inc[q];
            for (int b = 0; b < npe; b++) {
                if (stamp[c[b]] == k)
                    continue;
                stamp[c[b]] = k;
                if (c[b] >= nstart && c[b] < nend)
                    dl++;
                else
                    ol++;
            }
        }
        if (dl == 0)   /* a node of no element: its own diagonal */
            dl = 1;
        for (int c = 0; c < dim; c++) {
            dnz[dim * (k - nstart) + c] = dim * dl;
            onz[dim * (k - nstart) + c] = dim * ol;
        }
    }
    cx_free(cnt);
    cx_free(stamp);
    cx_free(inc);
    return CX_OK;
nomem:
    cx_free(cnt);
    cx_free(stamp);
    cx_free(inc);
    return CX_ENOMEM;
}

/* The contact rows as one (dof, value) each; CX_EUNSUPPORTED with the
 * reason otherwise. */
static int sys_rows(px_system *sys, const cx_problem *p, int tangential, cx_diag *d)
{
    int m = p->m, nt = p->nt;
    const cx_csc *B[2] = {&p->N, &p->T};
    int nrow[2] = {m, tangential ? nt : 0};
    int *dof[2] = {sys->ndof, sys->tdof};
    double *val[2] = {sys->nval, sys->tval};
    int *seen = CX_NEW(int, p->n > 0 ? p->n : 1);
    if (!seen)
        return cx_diag_set(d, CX_ENOMEM, "out of memory");
    for (int b = 0; b < 2; b++)
        for (int r = 0; r < (b ? nt : m); r++)
            dof[b][r] = -1;
    int status = CX_OK;
    for (int b = 0; b < 2 && status == CX_OK; b++) {
        for (int j = 0; j < B[b]->ncol && status == CX_OK; j++)
            for (int q = B[b]->p[j]; q < B[b]->p[j + 1]; q++) {
                int r = B[b]->i[q];
                if (r >= nrow[b] || B[b]->x[q] == 0)
                    continue;
                if (dof[b][r] >= 0) {
                    status = cx_diag_set(d, CX_EUNSUPPORTED,
                                         "--backend petsc: contact point %d: its %s row acts on more than "
                                         "one dof (a contact direction off the coordinate axes, or between "
                                         "two bodies); the backend takes only flat obstacles along an axis",
                                         b ? r / (p->dim - 1) : r, b ? "tangential" : "normal");
                    break;
                }
                if (seen[j]) {
                    status = cx_diag_set(d, CX_EUNSUPPORTED,
                                         "--backend petsc: free dof %d is in two contact rows", j);
                    break;
                }
                seen[j] = 1;
                dof[b][r] = p->map.all_of[j];
                val[b][r] = B[b]->x[q];
            }
    }
    for (int i = 0; status == CX_OK && i < m; i++)
        if (sys->ndof[i] < 0)
            status = cx_diag_set(d, CX_EUNSUPPORTED, "--backend petsc: contact point %d: no free normal dof", i);
    cx_free(seen);
    return status;
}

int cx_petsc_check(const cx_problem *p, const char *method, cx_friction law, cx_diag *d)
{
    const cx_petsc_method *pm = cx_petsc_method_find(method);
    if (!pm)
        return cx_diag_set(d, CX_EINVAL, "--backend petsc: unknown method '%s' (ssn-tresca, petsc-vi, petsc-tao)",
                           method);
    unsigned need = law == CX_FRICTION_NONE ? CX_FRICTIONLESS : law == CX_FRICTION_TRESCA ? CX_TRESCA : 0u;
    if (!(pm->supports & need))
        return cx_diag_set(d, CX_EUNSUPPORTED, "--backend petsc: method '%s' does not solve %s friction%s",
                           method, cx_friction_name(law),
                           law == CX_FRICTION_TRESCA ? " (a Tresca bound is on the multiplier, not a bound on u)"
                                                     : "");
    px_system sys = {0};
    sys.ndof = CX_NEW(int, p->m + 1);
    sys.nval = CX_NEW(double, p->m + 1);
    sys.tdof = CX_NEW(int, p->nt + 1);
    sys.tval = CX_NEW(double, p->nt + 1);
    int status = !sys.ndof || !sys.nval || !sys.tdof || !sys.tval
                     ? cx_diag_set(d, CX_ENOMEM, "out of memory")
                     : sys_rows(&sys, p, law == CX_FRICTION_TRESCA, d);
    cx_free(sys.ndof);
    cx_free(sys.nval);
    cx_free(sys.tdof);
    cx_free(sys.tval);
    return status;
}

int px_system_create(px_system *sys, const cx_problem *p, int tangential, cx_diag *d)
{
    int status = CX_OK;
    double t0 = cx_clock_now();
    const cx_mesh *m = p->mesh;
    memset(sys, 0, sizeof *sys);
    sys->p = p;
    sys->comm = PETSC_COMM_WORLD;
    MPI_Comm_rank(sys->comm, &sys->rank);
    MPI_Comm_size(sys->comm, &sys->size);
    sys->dim = m->dim;
    sys->nall = m->dim * m->nnodes;
    sys->kscale = p->kscale > 0 ? p->kscale : 1;
    int dim = m->dim, npe = m->npe, nd = dim * npe;
    int nstart = (int)(((long long)m->nnodes * sys->rank) / sys->size);
    int nend = (int)(((long long)m->nnodes * (sys->rank + 1)) / sys->size);
    int nloc = dim * (nend - nstart);
    PetscInt *dnz = CX_NEW(PetscInt, nloc + 1), *onz = CX_NEW(PetscInt, nloc + 1);
    PetscInt *idx = CX_NEW(PetscInt, nd), *fixed = NULL;
    double *Ke = CX_NEW(double, (size_t)nd * nd), *xe = CX_NEW(double, nd);
    double *D = CX_NEW(double, 36 * (size_t)(cx_mesh_nmats(m) > 0 ? cx_mesh_nmats(m) : 1));
    sys->ndof = CX_NEW(int, p->m + 1);
    sys->nval = CX_NEW(double, p->m + 1);
    sys->tdof = CX_NEW(int, p->nt + 1);
    sys->tval = CX_NEW(double, p->nt + 1);
    if (!dnz || !onz || !idx || !Ke || !xe || !D || !sys->ndof || !sys->nval || !sys->tdof || !sys->tval) {
        status = cx_diag_set(d, CX_ENOMEM, "out of memory");
        goto fail;
    }
    if ((status = sys_rows(sys, p, tangential, d)) != CX_OK)
        goto fail;
    if ((status = sys_prealloc(m, nstart, nend, dnz, onz)) != CX_OK) {
        status = cx_diag_set(d, status, "out of memory");
        goto fail;
    }
    for (int b = 0; b < cx_mesh_nmats(m); b++)
        cx_fem_elasticity(&p->mats[b], D + 36 * b);

    PX(MatCreate(sys->comm, &sys->K));
    PX(MatSetSizes(sys->K, nloc, nloc, sys->nall, sys->nall));
    PX(MatSetType(sys->K, MATAIJ));
    PX(MatSetBlockSize(sys->K, dim));
    PX(MatSeqAIJSetPreallocation(sys->K, 0, dnz));
    PX(MatMPIAIJSetPreallocation(sys->K, 0, dnz, 0, onz));
    PX(MatSetOption(sys->K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    PX(MatGetOwnershipRange(sys->K, &sys->rstart, &sys->rend));

    /* the elements this rank owns, added where their rows are (another
     * rank's rows travel at the assembly) */
    for (int e = 0; e < m->nelems; e++) {
        if (sys_elem_owner(m, sys->size, e) != sys->rank)
            continue;
        const int *c = m->conn + (size_t)npe * e;
        for (int a = 0; a < npe; a++)
            for (int k = 0; k < dim; k++) {
                xe[dim * a + k] = m->x[(size_t)dim * c[a] + k];
                idx[dim * a + k] = (PetscInt)dim * c[a] + k;
            }
        if (cx_fem_element_stiffness(m->etype, xe, D + 36 * cx_mesh_elem_mat(m, e), Ke) != CX_OK) {
            status = cx_diag_set(d, CX_ENUMERIC, "element %d is degenerate or inverted", e);
            goto fail;
        }
        PX(MatSetValues(sys->K, nd, idx, nd, idx, Ke, ADD_VALUES));   /* Ke is row-major, as PETSc's */
        sys->nelems++;
    }
    for (int k = nstart; k < nend; k++)   /* a node of no element keeps a diagonal */
        for (int c = 0; c < dim; c++) {
            PetscInt r = (PetscInt)dim * k + c;
            PX(MatSetValue(sys->K, r, r, 0.0, ADD_VALUES));
        }
    PX(MatAssemblyBegin(sys->K, MAT_FINAL_ASSEMBLY));
    PX(MatAssemblyEnd(sys->K, MAT_FINAL_ASSEMBLY));

    /* the prescribed dofs: identity rows and columns (their values are
     * folded into p->f already), so the free block is p->K */
    PX(MatCreateVecs(sys->K, &sys->f, NULL));
    fixed = CX_NEW(PetscInt, nloc + 1);
    if (!fixed) {
        status = cx_diag_set(d, CX_ENOMEM, "out of memory");
        goto fail;
    }
    int nfixed = 0;
    PetscScalar *fv;
    PX(VecGetArray(sys->f, &fv));
    for (PetscInt r = sys->rstart; r < sys->rend; r++) {
        int j = p->map.free_of[r];
        if (j < 0)
            fixed[nfixed++] = r;
        fv[r - sys->rstart] = j < 0 ? 0.0 : p->f[j];
    }
    PX(VecRestoreArray(sys->f, &fv));
    PX(MatSetOption(sys->K, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));   /* the methods' copies share it */
    PX(MatZeroRowsColumns(sys->K, nfixed, fixed, sys->kscale, NULL, NULL));
    PX(MatSetOption(sys->K, MAT_SYMMETRIC, PETSC_TRUE));
    PX(MatSetOption(sys->K, MAT_SPD, PETSC_TRUE));

    /* the rigid-body modes from the coordinates of the owned nodes */
    {
        Vec xv;
        MatNullSpace nsp;
        PX(VecCreateMPI(sys->comm, nloc, sys->nall, &xv));
        PX(VecSetBlockSize(xv, dim));
        PetscScalar *xa;
        PX(VecGetArray(xv, &xa));
        memcpy(xa, m->x + (size_t)dim * nstart, sizeof(double) * (size_t)nloc);
        PX(VecRestoreArray(xv, &xa));
        PX(MatNullSpaceCreateRigidBody(xv, &nsp));
        PX(MatSetNearNullSpace(sys->K, nsp));
        PX(MatNullSpaceDestroy(&nsp));
        PX(VecDestroy(&xv));
    }
    PX(VecScatterCreateToAll(sys->f, &sys->all, &sys->whole));
    sys->setup_time = cx_clock_now() - t0;
    cx_free(dnz);
    cx_free(onz);
    cx_free(idx);
    cx_free(fixed);
    cx_free(Ke);
    cx_free(xe);
    cx_free(D);
    return CX_OK;
fail:
    cx_free(dnz);
    cx_free(onz);
    cx_free(idx);
    cx_free(fixed);
    cx_free(Ke);
    cx_free(xe);
    cx_free(D);
    px_system_destroy(sys);
    return status;
}

void px_system_destroy(px_system *sys)
{
    if (sys->K)
        MatDestroy(&sys->K);
    if (sys->f)
        VecDestroy(&sys->f);
    if (sys->all)
        VecScatterDestroy(&sys->all);
    if (sys->whole)
        VecDestroy(&sys->whole);
    cx_free(sys->ndof);
    cx_free(sys->nval);
    cx_free(sys->tdof);
    cx_free(sys->tval);
    memset(sys, 0, sizeof *sys);
}

int px_system_gather(px_system *sys, Vec v, double *u, cx_diag *d)
{
    int status = CX_OK;
    PX(VecScatterBegin(sys->all, v, sys->whole, INSERT_VALUES, SCATTER_FORWARD));
    PX(VecScatterEnd(sys->all, v, sys->whole, INSERT_VALUES, SCATTER_FORWARD));
    if (u) {
        const PetscScalar *w;
        PX(VecGetArrayRead(sys->whole, &w));
        const cx_problem *p = sys->p;
        for (int j = 0; j < p->n; j++)
            u[j] = w[p->map.all_of[j]];
        PX(VecRestoreArrayRead(sys->whole, &w));
    }
    return CX_OK;
fail:
    return status;
}

void px_multipliers_from_residual(const px_system *sys, const double *r, double *lN, double *lT)
{
    const cx_problem *p = sys->p;
    for (int i = 0; i < p->m; i++)
        lN[i] = r[sys->ndof[i]] / sys->nval[i];
    for (int t = 0; lT && t < p->nt; t++)
        lT[t] = sys->tdof[t] >= 0 ? r[sys->tdof[t]] / sys->tval[t] : 0.0;
}
