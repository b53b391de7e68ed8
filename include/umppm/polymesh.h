/* SPDX-License-Identifier: GPL-3.0-or-later
 * polymesh.h -- OpenFOAM constant/polyMesh reader (module prefix pmesh_).
 *
 * Reads points, faces (faceList or faceCompactList), owner, neighbour and
 * boundary, ascii or binary, plain or gzipped, into the 3-D polyMesh it
 * describes. pmesh_check() verifies the
 * topology (counts, index ranges, owner < neighbour on internal faces,
 * patch ranges contiguous and covering the boundary, duplicate faces,
 * repeated face points, every cell closed: edges used twice, area vectors
 * summing to zero: the only geometry computed here).
 */
#ifndef UMPPM_POLYMESH_H
#define UMPPM_POLYMESH_H

#include "umppm/ump.h"

typedef enum pmesh_patch_kind {
    PMESH_PATCH,          /* generic "patch" (inlets, outlets...) */
    PMESH_WALL,
    PMESH_EMPTY,
    PMESH_SYMMETRYPLANE,
    PMESH_SYMMETRY,
    PMESH_CYCLIC,
    PMESH_WEDGE,
    PMESH_OTHER           /* any other type word (processor, cyclicAMI...) */
} pmesh_patch_kind;

typedef struct pmesh_patch {
    char *name;
    char *type;              /* type word as written */
    pmesh_patch_kind kind;
    char **groups;           /* inGroups, ngroups entries */
    int ngroups;
    ump_idx start;           /* startFace */
    ump_idx n;               /* nFaces */
    /* cyclic only */
    char *neighbour_patch;   /* neighbourPatch, NULL if not cyclic */
    int nbr;                 /* index of neighbour patch (-1 if none) */
    char *transform;         /* "unknown", "translational", "rotational", "none"... or NULL */
    int has_separation;
    double separation[3];    /* separationVector (from this patch to its neighbour) */
} pmesh_patch;

typedef struct pmesh {
    char *dir;               /* the polyMesh directory read */
    ump_idx npoints, nfaces, ninternal, ncells;
    double *points;          /* [3*npoints] */
    ump_idx *face_off;       /* [nfaces+1] CSR offsets into face_pts */
    ump_idx *face_pts;       /* [face_off[nfaces]] point labels */
    ump_idx *owner;          /* [nfaces] */
    ump_idx *neighbour;      /* [ninternal] */
    pmesh_patch *patch;      /* [npatches] */
    int npatches;
} pmesh;

/* Read <dir>/points, faces, owner, neighbour, boundary and run pmesh_check. */
ump_status pmesh_read(const char *dir, pmesh **out, ump_err *err);
/* Topology checks (see top of file); messages name dir. */
ump_status pmesh_check(const pmesh *m, ump_err *err);
/* Index of patch by name, -1 when absent. */
int pmesh_patch_index(const pmesh *m, const char *name);
/* 1 if patch p lists group g in inGroups (or its type equals g, as
 * OpenFOAM's constraint types are implicit groups). */
int pmesh_patch_in_group(const pmesh_patch *p, const char *g);
void pmesh_free(pmesh **m);

/* Build a one-cell-thick polyMesh in memory by extruding 2-D polygons along
 * z from 0 to thickness (tests and mesh-making tools).
 *   xy [2*nv]            vertex coordinates
 *   poly_off [npoly+1], poly_v [poly_off[npoly]]  polygons, any orientation
 *   patch_of(x, y, ctx)  patch index (0..npatch-1) of the boundary edge whose
 *                        midpoint is (x, y)
 *   names/types [npatch] patch names and types; a last patch
 *                        "frontAndBack" of type empty is appended.
 * Internal faces are in upper-triangular order (by owner, then neighbour);
 * boundary faces of a patch are sorted by midpoint (x, then y), so faces k of
 * two opposite straight patches face each other (usable as cyclic pairs). */
/* Write m as an ascii OpenFOAM polyMesh into dir (points, faces, owner with
 * its nCells note, neighbour, boundary incl. inGroups and cyclic entries),
 * each file written to a temporary name and renamed into place. precision:
 * significant digits of the points. */
ump_status pmesh_write(const pmesh *m, const char *dir, int precision, ump_err *err);

/* Write dir/points alone (npoints points, [3*npoints]), the header's
 * location as given ("0.5/polyMesh": a moved mesh, as a dynamic-mesh
 * solver writes it into a time directory). */
ump_status pmesh_write_points(const double *points, ump_idx npoints, const char *dir, const char *location,
                              int precision, ump_err *err);

ump_status pmesh_extrude(const double *xy, ump_idx nv, const ump_idx *poly_off,
                         const ump_idx *poly_v, ump_idx npoly, double thickness,
                         int (*patch_of)(double x, double y, void *ctx), void *ctx,
                         const char *const *names, const char *const *types, int npatch,
                         pmesh **out, ump_err *err);

#endif
