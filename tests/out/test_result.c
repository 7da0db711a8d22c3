/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The solution snapshot (out/result.h) and the formats written from it:
 * a result from a solved hertz session holds copies (it outlives the
 * session), the full displacement (prescribed dofs included), the contact
 * resultant equal to the applied load, stresses computed once; its JSON
 * parses back to the run's numbers; its VTU (written without any GL) has
 * the mesh's counts. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "out/out.h"

static cx_session *solve_hertz(cx_scene *sc, int level)
{
    cx_diag d;
    cx_problem *p = NULL;
    cx_session *s = NULL;
    cx_friction_state fr;
    if (cx_scene_open("hertz", sc, &d) || cx_scene_build(sc, level, &p, &fr, &d) ||
        cx_session_create(&s, &p, &d) || cx_session_set_friction(s, &fr, &d) ||
        cx_session_set_method(s, cx_method_find("ssn-tresca"), NULL, NULL, &d) ||
        cx_solver_solve(s, NULL, NULL, &d)) {
        fprintf(stderr, "hertz level %d: %s\n", level, d.msg);
        exit(2);
    }
    return s;
}

int main(void)
{
    cx_scene sc;
    cx_diag d;
    enum { LEVEL = 8 };
    cx_session *s = solve_hertz(&sc, LEVEL);
    const cx_problem *p = cx_session_problem(s);
    const cx_iterate *it = cx_session_iterate(s);
    cx_result *r = NULL;
    CX_CHECK_OK(cx_result_from_session(&r, s, &sc, 0, &d));
    if (!r)
        return check_finish("out_result");

    /* the run record */
    CX_CHECK(strcmp(r->run.scene, "hertz") == 0 && strcmp(r->run.method, "ssn-tresca") == 0);
    CX_CHECK(r->run.level == sc.level);   /* 0: the scene's level */
    CX_CHECK(r->run.converged && r->run.reason == it->reason && r->run.iterations == it->iter);
    CX_CHECK(r->run.kkt == it->kkt && r->run.counters.solves == it->counters.solves);
    CX_CHECK(strstr(r->run.params_text, "rho=") != NULL && r->run.params.n > 0);
    CX_CHECK(r->run.has_pressure_error && r->run.pressure_error_rel > 0 && r->run.hertz_halfwidth > 0);
    CX_CHECK(r->n == p->n && r->m == p->m && r->dim == 2 && r->has_obstacle);

    /* the full displacement: free dofs from u, prescribed ones their values */
    int nall = p->map.nall, nfixed = 0;
    for (int k = 0; k < nall; k++) {
        int fr = p->map.free_of[k];
        if (fr >= 0) {
            CX_CHECK(r->u[k] == it->u[fr]);
        } else {
            CX_CHECK(r->u[k] == p->map.value[k]);
            nfixed++;
        }
    }
    CX_CHECK(nfixed > 0 && nall == 2 * r->mesh->nnodes);
    /* equilibrium of the body: the contact carries the applied load */
    CX_CHECK_NEAR(r->f_contact[1], -r->f_applied[1], 1e-9, 0);
    CX_CHECK_NEAR(r->f_applied[1], -800, 1e-12, 0);

    /* copies: the session can go */
    int nnodes = p->mesh->nnodes, m = p->m;
    double lN0 = it->lN[0];
    cx_session_destroy(&s);
    CX_CHECK(r->mesh->nnodes == nnodes && r->contact.m == m && r->lN[0] == lN0);

    /* stresses once, kept */
    const double *sig1, *vm1, *sig2;
    CX_CHECK_OK(cx_result_stress(r, &sig1, &vm1, &d));
    CX_CHECK_OK(cx_result_stress(r, &sig2, NULL, &d));
    CX_CHECK(sig1 == sig2 && vm1 != NULL);
    double vmax = 0;
    for (int k = 0; k < nnodes; k++)
        vmax = vm1[k] > vmax ? vm1[k] : vmax;
    CX_CHECK(vmax > 0);
    double *pr = CX_NEW(double, nnodes), *stv = CX_NEW(double, nnodes);
    cx_result_nodal_pressure(r, pr);
    cx_result_nodal_status(r, stv);
    int active = 0, away = 0;
    for (int k = 0; k < nnodes; k++) {
        active += stv[k] > 0;
        away += stv[k] == -1 && pr[k] == 0;
    }
    CX_CHECK(active == r->run.ncontact && away == nnodes - m);
    cx_free(pr);
    cx_free(stv);

    /* JSON */
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    CX_CHECK_OK(cx_result_write_json(r, f));
    fclose(f);
    CX_CHECK(strstr(buf, "\"scene\": \"hertz\"") && strstr(buf, "\"converged\": true") &&
             strstr(buf, "\"pressure_error_l2\"") && strstr(buf, "\"params\": {"));
    char want[64];
    snprintf(want, sizeof want, "\"contact_points\": %d", m);
    CX_CHECK(strstr(buf, want) != NULL);
    free(buf);

    /* VTU: counts in the Piece, no temporary left */
    char path[] = "/tmp/cx_result_XXXXXX";
    CX_CHECK(mkdtemp(path) != NULL);
    char vtu[600];
    snprintf(vtu, sizeof vtu, "%s/r.vtu", path);
    CX_CHECK_OK(cx_vtu_write(r, vtu, 1, &d));
    f = fopen(vtu, "r");
    char head[4096] = "";
    size_t n = f ? fread(head, 1, sizeof head - 1, f) : 0;
    head[n] = '\0';
    if (f)
        fclose(f);
    snprintf(want, sizeof want, "NumberOfPoints=\"%d\" NumberOfCells=\"%d\"", nnodes, r->mesh->nelems);
    CX_CHECK(strstr(head, "<VTKFile type=\"UnstructuredGrid\"") && strstr(head, want));
    CX_CHECK(remove(vtu) == 0 && rmdir(path) == 0);   /* nothing else in the directory */

    cx_result_destroy(&r);
    cx_result_destroy(&r);
    CX_CHECK(r == NULL);
    return check_finish("out_result");
}
