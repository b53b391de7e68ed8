/* SPDX-License-Identifier: GPL-3.0-or-later
 * foamCompare -- cell-by-cell differences between two OpenFOAM cases (or
 * two time directories) on the same mesh.
 *
 *   foamCompare <caseA> <timeA> <caseB> <timeB> [field ...]   (default: U p)
 *
 * The meshes must match (same cells, centroids equal to 1e-9 of the domain
 * size) or the tool exits 2 with "mesh mismatch". For each field it prints
 * the area-weighted L2 (rms) and the L-infinity norm of the difference
 * (vector fields: of |a - b|), both relative to the rms and max of the
 * second case's field, and the L2 relative to that field's range (max - min
 * of a scalar, max |v| of a vector): the useful scale for a temperature,
 * whose rms is dominated by its offset. Exit 0 after a successful comparison, 1 on read
 * errors, 2 on mesh mismatch.
 */
#include "umppm/fieldio.h"
#include "umppm/foam.h"
#include "umppm/mesh2d.h"
#include "umppm/polymesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int load(const char *c, pmesh **pm, mesh2d **m)
{
    char dir[4096];
    ump_err err;
    snprintf(dir, sizeof dir, "%s/constant/polyMesh", c);
    if (pmesh_read(dir, pm, &err) != UMP_OK || mesh_build(*pm, m, &err) != UMP_OK) {
        fprintf(stderr, "foamCompare: %s\n", err.msg);
        return 0;
    }
    return 1;
}

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: foamCompare <caseA> <timeA> <caseB> <timeB> [field ...]\n");
        return 1;
    }
    pmesh *pa = NULL, *pb = NULL;
    mesh2d *ma = NULL, *mb = NULL;
    int rc = 0;
    if (!load(argv[1], &pa, &ma) || !load(argv[3], &pb, &mb)) {
        rc = 1;
        goto done;
    }
    double L = 0;
    for (ump_idx c = 0; c < ma->ncells; c++)
        L = fmax(L, fmax(fabs(ma->cx[c]), fabs(ma->cy[c])));
    if (ma->ncells != mb->ncells) {
        fprintf(stderr, "foamCompare: mesh mismatch: %ld cells vs %ld cells\n", (long)ma->ncells,
                (long)mb->ncells);
        rc = 2;
        goto done;
    }
    for (ump_idx c = 0; c < ma->ncells; c++)
        if (hypot(ma->cx[c] - mb->cx[c], ma->cy[c] - mb->cy[c]) > 1e-9 * (L > 0 ? L : 1)) {
            fprintf(stderr, "foamCompare: mesh mismatch: cell %ld centroids differ\n", (long)c);
            rc = 2;
            goto done;
        }
    const char *deflt[] = {"U", "p"};
    int nf = argc > 5 ? argc - 5 : 2;
    const char **fields = argc > 5 ? (const char **)argv + 5 : deflt;
    printf("%-8s %14s %14s %12s %12s %12s\n", "field", "L2(diff)", "Linf(diff)", "L2 rel", "Linf rel",
           "L2/range");
    for (int i = 0; i < nf; i++) {
        char p1[4400], p2[4400];
        snprintf(p1, sizeof p1, "%s/%s/%s", argv[1], argv[2], fields[i]);
        snprintf(p2, sizeof p2, "%s/%s/%s", argv[3], argv[4], fields[i]);
        /* the class decides scalar or vector */
        foam_file *ff = NULL;
        ump_err err;
        if (foam_file_read(p2, &ff, &err) != UMP_OK) {
            fprintf(stderr, "foamCompare: %s\n", err.msg);
            rc = 1;
            continue;
        }
        int ncomp = strcmp(ff->class_name, "volVectorField") == 0 ? 3 : 1;
        foam_file_free(&ff);
        fld_field *a = NULL, *b = NULL;
        if (fio_read_field(p1, pa, ncomp, &a, &err) != UMP_OK || fio_read_field(p2, pb, ncomp, &b, &err) != UMP_OK) {
            fprintf(stderr, "foamCompare: %s\n", err.msg);
            fld_free(&a);
            rc = 1;
            continue;
        }
        double s2 = 0, smax = 0, r2 = 0, rmax = 0, atot = 0, bmin = INFINITY, bmax = -INFINITY;
        for (ump_idx c = 0; c < ma->ncells; c++) {
            double d = 0, r = 0;
            for (int k = 0; k < ncomp; k++) {
                double x = a->internal[(size_t)c * (size_t)ncomp + (size_t)k];
                double y = b->internal[(size_t)c * (size_t)ncomp + (size_t)k];
                d += (x - y) * (x - y);
                r += y * y;
            }
            double w = ma->area[c];
            s2 += w * d;
            r2 += w * r;
            atot += w;
            smax = fmax(smax, sqrt(d));
            rmax = fmax(rmax, sqrt(r));
            double bv = ncomp == 1 ? b->internal[c] : sqrt(r);
            bmin = fmin(bmin, ncomp == 1 ? bv : 0);
            bmax = fmax(bmax, bv);
        }
        double l2 = sqrt(s2 / atot), lr = sqrt(r2 / atot);
        double range = bmax - bmin;
        printf("%-8s %14.6g %14.6g %12.4g %12.4g %12.4g\n", fields[i], l2, smax, lr > 0 ? l2 / lr : 0,
               rmax > 0 ? smax / rmax : 0, range > 0 ? l2 / range : 0);
        fld_free(&a);
        fld_free(&b);
    }
done:
    mesh_free(&ma);
    mesh_free(&mb);
    pmesh_free(&pa);
    pmesh_free(&pb);
    return rc;
}
