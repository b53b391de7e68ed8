/* SPDX-License-Identifier: GPL-3.0-or-later
 * testmesh.h -- unit-square test meshes built in memory with pmesh_extrude:
 * quads, triangles, quad/triangle hybrids, optionally distorted by a smooth
 * map that keeps the boundary in place, optionally periodic (both pairs of
 * opposite sides turned into cyclic patches).
 *
 * Patches of the square: 0 bottom, 1 right, 2 top, 3 left (4 frontAndBack).
 */
#ifndef UMPPM_TESTMESH_H
#define UMPPM_TESTMESH_H

#include "testutil.h"
#include "umppm/mesh2d.h"
#include "umppm/polymesh.h"

typedef enum tm_kind {
    TM_QUAD,     /* n x n squares */
    TM_TRI,      /* every square split along a diagonal, alternating direction */
    TM_HYBRID    /* squares in the left half, triangles in the right half */
} tm_kind;

static int tm_square_patch(double x, double y, void *ctx)
{
    (void)ctx;
    if (y < 1e-12) return 0;
    if (x > 1 - 1e-12) return 1;
    if (y > 1 - 1e-12) return 2;
    return 3;
}

/* Smooth distortion, zero normal displacement on the boundary and periodic,
 * so it also suits cyclic meshes; amp = 0.05 gives skew up to ~30 degrees. */
static inline void tm_map(double amp, double x, double y, double *X, double *Y)
{
    *X = x + amp * sin(2 * UMP_PI * x) * sin(2 * UMP_PI * y);
    *Y = y + amp * sin(2 * UMP_PI * x) * sin(4 * UMP_PI * y) * 0.5;
}

/* Turn patches a and b of pm into a cyclic pair (no transform entry, as
 * "transform unknown": mesh_build finds the separation from the faces). */
static inline void tm_make_cyclic(pmesh *pm, int a, int b)
{
    int ends[2] = {a, b};
    for (int k = 0; k < 2; k++) {
        pmesh_patch *pp = &pm->patch[ends[k]];
        free(pp->type);
        pp->type = ump_strdup("cyclic");
        pp->kind = PMESH_CYCLIC;
        pp->neighbour_patch = ump_strdup(pm->patch[ends[1 - k]].name);
        pp->nbr = ends[1 - k];
    }
}

/* One-cell-thick polyMesh of the unit square: n x n squares split as kind
 * says, vertices moved by tm_map(amp); cyclic turns left/right and
 * bottom/top into cyclic pairs. Types: bottom/top "wall", left/right "patch". */
static inline pmesh *tm_pmesh(tm_kind kind, int n, double amp, int cyclic)
{
    static const char *const names[] = {"bottom", "right", "top", "left"};
    static const char *const types[] = {"wall", "patch", "wall", "patch"};
    int nv = (n + 1) * (n + 1);
    double *xy = malloc(2 * sizeof(double) * (size_t)nv);
    ump_idx *off = malloc(sizeof(ump_idx) * (size_t)(2 * n * n + 1));
    ump_idx *pv = malloc(sizeof(ump_idx) * 6 * (size_t)(n * n));
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            tm_map(amp, (double)i / n, (double)j / n, &xy[2 * (j * (n + 1) + i)],
                   &xy[2 * (j * (n + 1) + i) + 1]);
    int c = 0, k = 0;
    off[0] = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            ump_idx a = j * (n + 1) + i, b = a + 1, d = a + n + 1, e = a + n + 2;
            int split = kind == TM_TRI || (kind == TM_HYBRID && 2 * i >= n);
            if (!split) {
                pv[k++] = a; pv[k++] = b; pv[k++] = e; pv[k++] = d;
                off[++c] = k;
            } else if ((i + j) % 2 == 0) {
                pv[k++] = a; pv[k++] = b; pv[k++] = e; off[++c] = k;
                pv[k++] = a; pv[k++] = e; pv[k++] = d; off[++c] = k;
            } else {
                pv[k++] = a; pv[k++] = b; pv[k++] = d; off[++c] = k;
                pv[k++] = b; pv[k++] = e; pv[k++] = d; off[++c] = k;
            }
        }
    pmesh *pm = NULL;
    ump_err err;
    if (pmesh_extrude(xy, nv, off, pv, c, 0.1, tm_square_patch, NULL, names, types, 4, &pm, &err) !=
        UMP_OK)
        fail_msg("%s", err.msg);
    free(xy);
    free(off);
    free(pv);
    if (cyclic) {
        tm_make_cyclic(pm, 0, 2);
        tm_make_cyclic(pm, 1, 3);
    }
    return pm;
}

/* The mesh2d of tm_pmesh; *pm receives the polyMesh (free after the mesh). */
static inline mesh2d *tm_mesh(tm_kind kind, int n, double amp, int cyclic, pmesh **pm)
{
    *pm = tm_pmesh(kind, n, amp, cyclic);
    mesh2d *m = NULL;
    ump_err err;
    if (mesh_build(*pm, &m, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    return m;
}

static inline const char *tm_name(tm_kind kind, double amp)
{
    if (kind == TM_QUAD)
        return amp > 0 ? "distorted quads" : "quads";
    if (kind == TM_TRI)
        return amp > 0 ? "distorted triangles" : "triangles";
    return amp > 0 ? "distorted hybrid" : "hybrid";
}

#endif
