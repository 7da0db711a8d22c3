/* SPDX-License-Identifier: GPL-3.0-or-later */
/* --method auto: which method solves a scene by default.
 *
 * The table holds, for each shipped scene at its default level and each
 * law it allows, the method that was fastest to the default tolerance
 * (kkt 1e-10) among the methods that support it: `signorini bench wp SCENE
 * --friction LAW --tols 1e-10 --repeat 5 --threads 1` (medians; a tie
 * within 10 % goes to ssn-tresca, the most general method), then checked
 * to converge under the default `--stop own` (cf-fp's own criteria are
 * tightened for that: its defaults stop at kkt ~1e-5). The README lists
 * the measurements. A test runs every scene and law with no options and
 * asserts convergence, so a method change that breaks a default shows.
 *
 * Anything else (a user's scene, another level, where the dense methods
 * of the table may not scale) takes a rule from the problem: Coulomb by
 * ssn-coulomb in 2D and cf-fp in 3D; bodies with no support (a singular
 * K: masonry) by pdas, which regularises and projects (start=closed on
 * the masonry walls, where few joints open); the rest by
 * ssn-tresca, which takes every other case. */
#include "scene/scene.h"

#include <string.h>

typedef struct {
    const char *scene;
    cx_friction law;
    const char *method;
    const char *params;
} auto_choice;

/* cf-fp to kkt 1e-10 under its own criteria: the fixed point and the inner
 * tolerance's floor below the tolerance */
#define AUTO_CFFP_TIGHT "eps_fp=1e-12 eps_min=1e-12"

static const auto_choice auto_table[] = {
    {"block3d", CX_FRICTION_NONE, "ubr-c", ""},
    {"block3d", CX_FRICTION_TRESCA, "ssn-tresca", ""},
    {"block3d", CX_FRICTION_COULOMB, "cf-fp", AUTO_CFFP_TIGHT},
    {"halfball", CX_FRICTION_NONE, "graves", ""},
    {"halfball", CX_FRICTION_TRESCA, "ssn-tresca", ""},
    {"halfball", CX_FRICTION_COULOMB, "cf-fp", AUTO_CFFP_TIGHT},
    {"hertz", CX_FRICTION_NONE, "ssn-tresca", ""},   /* a tie with graves */
    {"hertz", CX_FRICTION_TRESCA, "ssn-tresca", ""},
    {"hertz", CX_FRICTION_COULOMB, "ssn-coulomb", ""},   /* since its condensation */
    {"laminae", CX_FRICTION_NONE, "graves", ""},
    {"laminae", CX_FRICTION_TRESCA, "ssn-tresca", ""},
    {"laminae", CX_FRICTION_COULOMB, "ssn-coulomb", ""},
    {"prism", CX_FRICTION_NONE, "ssn-tresca", ""},
    {"prism", CX_FRICTION_TRESCA, "ssstar", ""},
    {"prism", CX_FRICTION_COULOMB, "cf-fp", AUTO_CFFP_TIGHT},
    /* punch, ring, sphere (Gmsh scenes): setup + solve, median of 3 runs of
     * `solve SCENE --friction LAW --method M --json` at the default level */
    {"punch", CX_FRICTION_NONE, "pdas", ""},           /* 15 ms; graves 27, ssn-tresca 31 */
    {"punch", CX_FRICTION_TRESCA, "ssn-tresca", ""},
    {"punch", CX_FRICTION_COULOMB, "ssn-coulomb", ""}, /* cf-fp: one body only */
    {"ring", CX_FRICTION_NONE, "pdas", ""},            /* 30 ms; graves 39, ssn-tresca 45 */
    {"ring", CX_FRICTION_TRESCA, "ssn-tresca", ""},
    {"ring", CX_FRICTION_COULOMB, "ssn-coulomb", ""},  /* cf-fp stops short */
    {"runningbond", CX_FRICTION_NONE, "graves", ""},
    {"slider", CX_FRICTION_NONE, "ssn-tresca", ""},
    {"slider", CX_FRICTION_TRESCA, "ssn-tresca", ""},
    {"slider", CX_FRICTION_COULOMB, "ssn-coulomb", ""},  /* since its condensation */
    {"sphere", CX_FRICTION_NONE, "ssn-tresca", ""},    /* 0.11 s; graves 0.16, pdas 0.34 */
    {"sphere", CX_FRICTION_TRESCA, "ssn-tresca", ""},
    {"sphere", CX_FRICTION_COULOMB, "cf-fp", AUTO_CFFP_TIGHT},
    {"stackbond", CX_FRICTION_NONE, "graves", ""},
    {"twoblocks", CX_FRICTION_NONE, "ssn-tresca", ""},
    {"twoblocks", CX_FRICTION_TRESCA, "ssn-tresca", ""},
    {"twoblocks", CX_FRICTION_COULOMB, "ssn-coulomb", ""},
};

/* A body none of whose nodes has a prescribed dof: its rigid motions make
 * K singular. */
static int auto_floating(const cx_problem *p)
{
    const cx_mesh *mesh = p->mesh;
    if (!mesh || !p->map.free_of)
        return 0;
    int nb = mesh->nbodies > 0 ? mesh->nbodies : 1;
    int held[64] = {0};
    if (nb > 64)
        nb = 64;   /* beyond: judged on the first 64 bodies */
    for (int e = 0; e < mesh->nelems; e++) {
        int b = mesh->body ? mesh->body[e] : 0;
        if (b >= nb || held[b])
            continue;
        for (int k = 0; k < mesh->npe && !held[b]; k++) {
            int node = mesh->conn[mesh->npe * e + k];
            for (int c = 0; c < p->dim; c++)
                if (p->map.free_of[p->dim * node + c] < 0)
                    held[b] = 1;
        }
    }
    for (int b = 0; b < nb; b++)
        if (!held[b])
            return 1;
    return 0;
}

const char *cx_scene_auto_method(const cx_scene *sc, int level, const cx_problem *p, cx_friction law,
                                 const char **params)
{
    *params = "";
    if (sc && (level <= 0 || level == sc->level))
        for (size_t k = 0; k < sizeof auto_table / sizeof auto_table[0]; k++)
            if (auto_table[k].law == law && strcmp(auto_table[k].scene, sc->id) == 0) {
                *params = auto_table[k].params;
                return auto_table[k].method;
            }
    int dim = p ? p->dim : sc ? sc->dim : 2;
    if (law == CX_FRICTION_COULOMB) {
        if (dim == 2)
            return "ssn-coulomb";
        *params = AUTO_CFFP_TIGHT;
        return "cf-fp";
    }
    int floating = p ? auto_floating(p) : sc && sc->generator == CX_GEN_MASONRY;
    if (law == CX_FRICTION_NONE && floating) {
        /* the masonry walls: few joints end open, so from every joint
         * closed PDAS changes a few per step and its factor is updated, not
         * redone (1/100: 3-12 steps and 1-2 factorisations, against 12-22
         * and 7-16 from the paper's start) */
        if (sc && sc->generator == CX_GEN_MASONRY)
            *params = "start=closed";
        return "pdas";
    }
    return "ssn-tresca";
}
