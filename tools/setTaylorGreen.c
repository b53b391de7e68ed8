/* SPDX-License-Identifier: GPL-3.0-or-later
 * setTaylorGreen -- writes 0/U and 0/p of the Taylor-Green vortex of
 * Section 4.1 of Ng, Sheu & Hwang 2016 (Eqs. 38-40 at t = 0, U = 1, L = 1)
 * on the case's mesh, evaluated at the cell centroids, with cyclic (or
 * empty) patches.
 *   setTaylorGreen [-case DIR] [-U 1]
 */
#include "umppm/fieldio.h"
#include "umppm/mesh2d.h"
#include "umppm/polymesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    const char *c = ".";
    double U0 = 1;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-case") && i + 1 < argc) c = argv[++i];
        else if (!strcmp(argv[i], "-U") && i + 1 < argc) U0 = atof(argv[++i]);
        else { fprintf(stderr, "usage: setTaylorGreen [-case DIR] [-U 1]\n"); return 1; }
    }
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/constant/polyMesh", c);
    ump_err err;
    pmesh *pm = NULL;
    mesh2d *m = NULL;
    if (pmesh_read(dir, &pm, &err) != UMP_OK || mesh_build(pm, &m, &err) != UMP_OK) {
        fprintf(stderr, "setTaylorGreen: %s\n", err.msg);
        return 1;
    }
    ump_idx *sizes = calloc((size_t)pm->npatches, sizeof *sizes);
    for (int p = 0; p < pm->npatches; p++)
        sizes[p] = pm->patch[p].n;
    fld_field *U = NULL, *P = NULL;
    if (fld_create("U", 3, m->ncells, pm->npatches, sizes, &U, &err) != UMP_OK ||
        fld_create("p", 1, m->ncells, pm->npatches, sizes, &P, &err) != UMP_OK) {
        fprintf(stderr, "setTaylorGreen: %s\n", err.msg);
        return 1;
    }
    U->dims[1] = 1; U->dims[2] = -1;
    P->dims[1] = 2; P->dims[2] = -2;
    const double pi = 3.14159265358979323846;
    for (ump_idx k = 0; k < m->ncells; k++) {
        double x = m->cx[k], y = m->cy[k];
        double *u = U->internal + 3 * (size_t)k;
        u[m->normal] = 0;
        u[m->ax[0]] = -U0 * cos(2 * pi * x) * sin(2 * pi * y);             /* Eq. 38 */
        u[m->ax[1]] = U0 * sin(2 * pi * x) * cos(2 * pi * y);              /* Eq. 39 */
        P->internal[k] = -0.25 * U0 * U0 * (cos(4 * pi * x) + cos(4 * pi * y)); /* Eq. 40 */
    }
    for (int p = 0; p < pm->npatches; p++) {
        fld_bc_type t = pm->patch[p].kind == PMESH_CYCLIC ? FLD_BC_CYCLIC
                        : pm->patch[p].kind == PMESH_EMPTY ? FLD_BC_EMPTY : FLD_BC_ZEROGRADIENT;
        U->patch[p].type = P->patch[p].type = t;
    }
    snprintf(dir, sizeof dir, "%s/0", c);
    fio_format fmt = {0, 17, 0};
    if (fio_mkdir_p(dir, &err) != UMP_OK || fio_write_field(dir, "0", pm, U, &fmt, &err) != UMP_OK ||
        fio_write_field(dir, "0", pm, P, &fmt, &err) != UMP_OK) {
        fprintf(stderr, "setTaylorGreen: %s\n", err.msg);
        return 1;
    }
    printf("setTaylorGreen: 0/U and 0/p written for %ld cells\n", (long)m->ncells);
    fld_free(&U); fld_free(&P); free(sizes); mesh_free(&m); pmesh_free(&pm);
    return 0;
}
