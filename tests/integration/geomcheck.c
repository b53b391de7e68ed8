/* SPDX-License-Identifier: GPL-3.0-or-later
 * geomcheck.c -- compares the 2-D pressure mesh with OpenFOAM's own geometry.
 *
 *   geomcheck <case> <time>
 *
 * Reads <case>/constant/polyMesh with our reader, builds the 2-D mesh, and
 * reads <case>/<time>/C and V as written by
 *   postProcess -func writeCellCentres / writeCellVolumes (writePrecision 17)
 * with our field reader. Our centroid (mapped to 3-D on the mid-plane) must
 * equal C, and our area x thickness must equal V, to 1e-10 relative (C
 * relative to the domain size, V relative to itself). Exit 0 on agreement,
 * 1 on mismatch, 2 on read errors. Prints the worst errors either way.
 */
#include "umppm/fieldio.h"
#include "umppm/mesh2d.h"
#include "umppm/polymesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: geomcheck <case> <time>\n");
        return 2;
    }
    char dir[4096], path[4200];
    snprintf(dir, sizeof dir, "%s/constant/polyMesh", argv[1]);
    ump_err err;
    pmesh *pm = NULL;
    mesh2d *m = NULL;
    fld_field *C = NULL, *V = NULL;
    if (pmesh_read(dir, &pm, &err) != UMP_OK || mesh_build(pm, &m, &err) != UMP_OK) {
        fprintf(stderr, "geomcheck: %s\n", err.msg);
        return 2;
    }
    snprintf(path, sizeof path, "%s/%s/C", argv[1], argv[2]);
    if (fio_read_field(path, pm, 3, &C, &err) != UMP_OK) {
        fprintf(stderr, "geomcheck: %s\n", err.msg);
        return 2;
    }
    snprintf(path, sizeof path, "%s/%s/V", argv[1], argv[2]);
    if (fio_read_field(path, pm, 1, &V, &err) != UMP_OK) {
        fprintf(stderr, "geomcheck: %s\n", err.msg);
        return 2;
    }
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (ump_idx i = 0; i < pm->npoints; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], pm->points[3 * (size_t)i + k]);
            hi[k] = fmax(hi[k], pm->points[3 * (size_t)i + k]);
        }
    double L = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                    (hi[2] - lo[2]) * (hi[2] - lo[2]));
    double thick = m->zmax - m->zmin, ec = 0, ev = 0;
    ump_idx wc = 0, wv = 0;
    for (ump_idx c = 0; c < m->ncells; c++) {
        double x[3];
        mesh_to3d(m, m->cx[c], m->cy[c], x);
        const double *of = C->internal + 3 * (size_t)c;
        double d = sqrt((x[0] - of[0]) * (x[0] - of[0]) + (x[1] - of[1]) * (x[1] - of[1]) +
                        (x[2] - of[2]) * (x[2] - of[2])) / L;
        if (d > ec) { ec = d; wc = c; }
        double v = fabs(m->area[c] * thick - V->internal[c]) / fabs(V->internal[c]);
        if (v > ev || isnan(v)) { ev = v; wv = c; }
    }
    int ncyc = 0;
    for (ump_idx f = pm->ninternal; f < m->ninternal; f++)
        ncyc++;
    printf("cells %ld (%s), cyclic pairs %d: max centroid error %.3g (cell %ld), max volume error %.3g (cell %ld)\n",
           (long)m->ncells, m->normal == 2 ? "normal z" : m->normal == 1 ? "normal y" : "normal x",
           ncyc, ec, (long)wc, ev, (long)wv);
    int ok = ec <= 1e-10 && ev <= 1e-10;
    fld_free(&C);
    fld_free(&V);
    mesh_free(&m);
    pmesh_free(&pm);
    return ok ? 0 : 1;
}
