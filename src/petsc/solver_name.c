/* SPDX-License-Identifier: GPL-3.0-or-later */
/* What a Krylov solver and its preconditioner are called in the summaries
 * ("CG + BoomerAMG", "CG + GAMG"): read from the objects after their
 * options, so that a PETSC_OPTIONS change (-cx_pc_type gamg) is named as
 * it runs, not as the code first set it. */
#include "petsc/petsc_impl.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

void px_pc_name(PC pc, char *buf, size_t len)
{
    PCType t = NULL;
    if (!pc || PCGetType(pc, &t) != 0 || !t) {
        snprintf(buf, len, "no preconditioner");
        return;
    }
#ifdef PETSC_HAVE_HYPRE
    if (strcmp(t, PCHYPRE) == 0) {
        const char *h = NULL;
        if (PCHYPREGetType(pc, &h) != 0 || !h || strcmp(h, "boomeramg") == 0)
            snprintf(buf, len, "BoomerAMG");
        else
            snprintf(buf, len, "hypre %s", h);
        return;
    }
#endif
    if (strcmp(t, PCGAMG) == 0)
        snprintf(buf, len, "GAMG");
    else
        snprintf(buf, len, "%s", t);
}

void px_ksp_name(KSP ksp, char *buf, size_t len)
{
    KSPType t = NULL;
    PC pc = NULL;
    char kname[32] = "?", pname[48];
    if (ksp && KSPGetType(ksp, &t) == 0 && t) {
        size_t k = 0;
        for (; t[k] && k + 1 < sizeof kname; k++)
            kname[k] = (char)toupper((unsigned char)t[k]);
        kname[k] = 0;
    }
    if (!ksp || KSPGetPC(ksp, &pc) != 0)
        pc = NULL;
    px_pc_name(pc, pname, sizeof pname);
    snprintf(buf, len, "%s + %s", kname, pname);
}
