/* SPDX-License-Identifier: GPL-3.0-or-later
 * makeCrossedTriangleMesh -- writes constant/polyMesh of a periodic square
 * [0,L]x[0,L] meshed with crossed triangles: n x n squares, each cut into
 * four triangles by its diagonals (Fig. 7 of Ng, Sheu & Hwang 2016;
 * N_m = 4 n^2), one cell thick, cyclic left/right and bottom/top, empty
 * frontAndBack. This is the Taylor-Green mesh of Section 4.1.
 *
 *   makeCrossedTriangleMesh [-case DIR] -n N [-L 1] [-thickness 0.1]
 */
#include "umppm/polymesh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct sq { double L; } sq;

static int side(double x, double y, void *ctx)
{
    double L = ((sq *)ctx)->L, tol = 1e-9 * L;
    if (x < tol) return 0;         /* left */
    if (x > L - tol) return 1;     /* right */
    if (y < tol) return 2;         /* bottom */
    return 3;                      /* top */
    (void)y;
}

/* OpenFOAM wants face k of the second patch of a cyclic pair to start at the
 * image of the first vertex of face k of the first patch (checkMesh: "0th
 * vertex ... opposite their coupled equivalent"): rotate its point list. */
static void align_cyclic(pmesh *pm, int pa, int pb, const double sep[3])
{
    const pmesh_patch *A = &pm->patch[pa], *B = &pm->patch[pb];
    for (ump_idx k = 0; k < A->n; k++) {
        ump_idx fa = A->start + k, fb = B->start + k;
        const double *a0 = pm->points + 3 * (size_t)pm->face_pts[pm->face_off[fa]];
        ump_idx b = pm->face_off[fb], n = pm->face_off[fb + 1] - b, best = 0;
        double bd = 1e300;
        for (ump_idx i = 0; i < n; i++) {
            const double *q = pm->points + 3 * (size_t)pm->face_pts[b + i];
            double d = 0;
            for (int c = 0; c < 3; c++)
                d += (q[c] - a0[c] - sep[c]) * (q[c] - a0[c] - sep[c]);
            if (d < bd) {
                bd = d;
                best = i;
            }
        }
        ump_idx tmp[16];
        for (ump_idx i = 0; i < n && n <= 16; i++)
            tmp[i] = pm->face_pts[b + (best + i) % n];
        for (ump_idx i = 0; i < n && n <= 16; i++)
            pm->face_pts[b + i] = tmp[i];
    }
}

int main(int argc, char **argv)
{
    const char *dir = ".";
    long n = 0;
    double L = 1.0, th = 0.1;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-case") && i + 1 < argc) dir = argv[++i];
        else if (!strcmp(argv[i], "-n") && i + 1 < argc) n = atol(argv[++i]);
        else if (!strcmp(argv[i], "-L") && i + 1 < argc) L = atof(argv[++i]);
        else if (!strcmp(argv[i], "-thickness") && i + 1 < argc) th = atof(argv[++i]);
        else {
            fprintf(stderr, "usage: makeCrossedTriangleMesh [-case DIR] -n N [-L 1] [-thickness 0.1]\n");
            return 1;
        }
    }
    if (n < 1 || n > 4000 || !(L > 0) || !(th > 0)) {
        fprintf(stderr, "makeCrossedTriangleMesh: need -n in 1..4000, L > 0, thickness > 0\n");
        return 1;
    }
    /* vertices: (n+1)^2 lattice, then n^2 square centres */
    long nl = (n + 1) * (n + 1), nv = nl + n * n;
    double *xy = malloc(2 * sizeof(double) * (size_t)nv);
    ump_idx *off = malloc(sizeof(ump_idx) * (size_t)(4 * n * n + 1));
    ump_idx *pv = malloc(sizeof(ump_idx) * (size_t)(12 * n * n));
    if (!xy || !off || !pv) {
        fprintf(stderr, "makeCrossedTriangleMesh: out of memory\n");
        return 1;
    }
    double h = L / (double)n;
    for (long j = 0; j <= n; j++)
        for (long i = 0; i <= n; i++) {
            xy[2 * (j * (n + 1) + i)] = (double)i * h;
            xy[2 * (j * (n + 1) + i) + 1] = (double)j * h;
        }
    long c = 0;
    off[0] = 0;
    for (long j = 0; j < n; j++)
        for (long i = 0; i < n; i++) {
            long ctr = nl + j * n + i;
            xy[2 * ctr] = ((double)i + 0.5) * h;
            xy[2 * ctr + 1] = ((double)j + 0.5) * h;
            long a = j * (n + 1) + i, b = a + 1, d = a + n + 1, e = d + 1;
            long tri[4][2] = {{a, b}, {b, e}, {e, d}, {d, a}};
            for (int t = 0; t < 4; t++, c++) {
                pv[3 * c] = (ump_idx)tri[t][0];
                pv[3 * c + 1] = (ump_idx)tri[t][1];
                pv[3 * c + 2] = (ump_idx)ctr;
                off[c + 1] = (ump_idx)(3 * (c + 1));
            }
        }
    const char *names[] = {"left", "right", "bottom", "top"};
    const char *types[] = {"patch", "patch", "patch", "patch"};
    const char *nbr[] = {"right", "left", "top", "bottom"};
    double sepv[4][3] = {{L, 0, 0}, {-L, 0, 0}, {0, L, 0}, {0, -L, 0}};
    sq ctx = {L};
    pmesh *pm = NULL;
    ump_err err;
    if (pmesh_extrude(xy, (ump_idx)nv, off, pv, (ump_idx)c, th, side, &ctx, names, types, 4, &pm, &err) != UMP_OK) {
        fprintf(stderr, "makeCrossedTriangleMesh: %s\n", err.msg);
        return 1;
    }
    for (int p = 0; p < 4; p++) {
        pmesh_patch *pp = &pm->patch[p];
        free(pp->type);
        pp->type = strdup("cyclic");
        pp->kind = PMESH_CYCLIC;
        pp->neighbour_patch = strdup(nbr[p]);
        pp->transform = strdup("translational");
        pp->has_separation = 1;
        memcpy(pp->separation, sepv[p], sizeof sepv[p]);
        pp->nbr = pmesh_patch_index(pm, nbr[p]);
    }
    align_cyclic(pm, 0, 1, sepv[0]);
    align_cyclic(pm, 2, 3, sepv[2]);
    char pdir[4096];
    snprintf(pdir, sizeof pdir, "%s/constant/polyMesh", dir);
    if (pmesh_write(pm, pdir, 17, &err) != UMP_OK) {
        fprintf(stderr, "makeCrossedTriangleMesh: %s\n", err.msg);
        return 1;
    }
    printf("makeCrossedTriangleMesh: %ld triangles (n = %ld, L = %g) written to %s\n", c, n, L, pdir);
    pmesh_free(&pm);
    free(xy);
    free(off);
    free(pv);
    return 0;
}
