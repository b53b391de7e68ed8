/* SPDX-License-Identifier: GPL-3.0-or-later
 * mesh2d.h -- the UMPPM pressure mesh (docs/METHOD.md section 3.1; module
 * prefix mesh_).
 *
 * A 2-D OpenFOAM case is a one-cell-thick 3-D mesh whose flat front and back
 * sides are `empty` patches. mesh_build() makes a 2-D *view* of that polyMesh
 * (the pmesh stays the master description; a later 3-D solver uses it
 * directly):
 *   - 2-D cell   = the cell's face on the back (min-coordinate) empty side;
 *                  any polygon: triangles, quads, polygons, mixed (hybrid);
 *   - 2-D vertex = a point of the back side;
 *   - 2-D face   = every non-empty polyMesh face (an edge in 2-D);
 *   - cyclic pairs become internal faces carrying a separation vector.
 * In-plane coordinates are (X,Y) = (axis ax[0], axis ax[1]) with the normal
 * axis `normal` and ax = ((normal+1)%3, (normal+2)%3): right-handed, so a
 * z-normal mesh uses (x,y), an x-normal mesh (y,z), a y-normal mesh (z,x).
 *
 * Face numbering: internal faces first (polyMesh internal faces in order,
 * then one face per cyclic pair), then boundary faces grouped by patch in
 * polyMesh patch order (empty and cyclic patches contribute none).
 *
 * Stencils (Figs. 1, 3, 4, 5 of Ng, Sheu & Hwang 2016 [NSH16]):
 * N1(P) = cells sharing a vertex with P (P excluded); N2(P) = cells within
 * two vertex-rings of P (P excluded, N1(P) included, so N2 is the whole
 * search stencil besides P). Across cyclic
 * boundaries vertices are identified, and each stencil entry carries the
 * shift that brings the neighbour next to P (zero without cyclics).
 *
 * Refused with a message naming the polyMesh directory: 3-D meshes (no
 * empty patch), wedge patches, empty sides that are not planes normal to x, y
 * or z, cells without exactly two empty faces, non-translational cyclics,
 * unmatched cyclic faces, zero or negative areas, and NaN/inf coordinates.
 */
#ifndef UMPPM_MESH2D_H
#define UMPPM_MESH2D_H

#include "umppm/ump.h"
#include "umppm/polymesh.h"

typedef struct mesh_patch {
    int pm_patch;        /* index into pmesh patches */
    ump_idx start, n;    /* range of 2-D faces (boundary patches; n = 0 for
                            empty and cyclic patches) */
} mesh_patch;

typedef struct mesh2d {
    const pmesh *pm;     /* borrowed: must outlive the mesh2d */
    int normal;          /* 0,1,2: axis normal to the empty sides */
    int ax[2];           /* in-plane axes */
    double zmin, zmax;   /* extent along the normal; thickness = zmax - zmin */

    ump_idx ncells, nfaces, ninternal, nverts;

    /* vertices */
    double *vx, *vy;            /* [nverts] */
    ump_idx *vert_pm;           /* [nverts] polyMesh point of each vertex */
    ump_idx *vert_id;           /* [nverts] representative after cyclic
                                   identification (== self without cyclics) */

    /* cells */
    ump_idx *cell_off, *cell_verts; /* CSR [ncells+1], counter-clockwise vertices */
    double *cx, *cy;            /* [ncells] centroid */
    double *area;               /* [ncells] */
    double *dx, *dy, *dc;       /* [ncells] bounding-box extents, sqrt(dx^2+dy^2) */
    ump_idx *cell_face_off, *cell_faces; /* CSR: 2-D faces of each cell */

    /* faces */
    ump_idx *owner;             /* [nfaces] */
    ump_idx *neigh;             /* [ninternal] */
    ump_idx *fv0, *fv1;         /* [nfaces] end vertices of the edge */
    double *fx, *fy;            /* [nfaces] face centre (edge midpoint) */
    double *nx, *ny;            /* [nfaces] unit normal, owner -> neighbour / outwards */
    double *len;                /* [nfaces] edge length (|A_f| per unit thickness) */
    double *sepx, *sepy;        /* [ninternal] or NULL: neighbour seen from the
                                   owner is at (x_N - sep); zero for ordinary faces */
    ump_idx *face_pm;           /* [nfaces] polyMesh face (the owner-side face for
                                   cyclic pairs) */
    ump_idx *face_pm2;          /* [ninternal] partner polyMesh face of a cyclic
                                   pair, -1 otherwise */
    ump_idx *pmface_to_face;    /* [pm->nfaces] 2-D face of a polyMesh face, -1 for
                                   empty faces */
    int *face_patch;            /* [nfaces] pmesh patch index of boundary faces,
                                   -1 for internal faces */

    mesh_patch *patch;          /* [pm->npatches] */
    int npatches;
    int has_cyclic;

    /* stencils (CSR over cells, entries sorted by cell index) */
    ump_idx *n1_off, *n1;       /* first neighbours */
    ump_idx *n2_off, *n2;       /* first + second neighbours */
    double *n1_sx, *n1_sy;      /* [n1_off[ncells]] shift or NULL (no cyclics) */
    double *n2_sx, *n2_sy;      /* [n2_off[ncells]] shift or NULL */
} mesh2d;

/* Build the 2-D view of pm (see top). */
ump_status mesh_build(const pmesh *pm, mesh2d **out, ump_err *err);
void mesh_free(mesh2d **m);

/* Statistics for umppmFoam -checkMesh. */
typedef struct mesh_stats {
    ump_idx ntri, nquad, npoly;      /* cells by polygon type (npoly: >4 sides) */
    ump_idx nsides_max;
    double area_min, area_max, area_mean, area_total;
    double nonorth_max, nonorth_mean; /* degrees, interior faces */
    double skew_max;                  /* OpenFOAM-style skewness (interior+boundary) */
    double len_min, len_max;
    ump_idx n1_min, n1_max, n2_min, n2_max;
    double n1_mean, n2_mean;
} mesh_stats;

void mesh_compute_stats(const mesh2d *m, mesh_stats *s);

/* Total 3-D face area of the boundary faces of pmesh patch p (length x
 * thickness, OpenFOAM's gSum(magSf); 0 for empty and cyclic patches), and,
 * when nrm [3*n] is not NULL, the outward unit normal of each of its n
 * faces in the polyMesh's 3-D axes (polyMesh face order; zero for faces that
 * are not 2-D boundary faces). */
double mesh_patch_area(const mesh2d *m, int p, double *nrm);

/* 3-D coordinates of 2-D point (X,Y) on the mid-plane. */
void mesh_to3d(const mesh2d *m, double X, double Y, double out[3]);

#endif
