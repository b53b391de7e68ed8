/* SPDX-License-Identifier: GPL-3.0-or-later
 * mlseed.h -- the initial particles of a meshless (free-surface) case
 * (module prefix mlseed_); docs/METHOD.md section 9.
 *
 * One square lattice of spacing l0 covers the container: points
 * (x0 + (i + 1/2) l0, y0 + (j + 1/2) l0) with (x0, y0) the lower-left corner
 * of the mesh's bounding box. A lattice point inside a mesh cell whose
 * liquid fraction is at least 1/2 becomes a fluid particle (the region
 * setFields marked); a point outside the mesh whose nearest boundary face
 * is a wall face, no farther than the solid thickness, becomes a solid
 * particle: a wall particle when it is within wall_depth of that face,
 * a dummy particle beyond. Fluid and solid particles thus form one
 * perfect lattice whatever the position of the walls (a wall that does
 * not fall between lattice lines is represented by the staircase of
 * lattice points on its far side), any polygonal container of wall
 * patches works -- obstacles, inclined walls, several boundaries -- and the
 * points above an open patch (the atmosphere) stay empty.
 *
 * Cost: each cell tests the lattice points of its bounding box; boundary
 * faces are binned on a grid of the solid thickness, so each point tests
 * the faces of one bin: O(cells + lattice points), once, at start-up.
 */
#ifndef UMPPM_MLSEED_H
#define UMPPM_MLSEED_H

#include "umppm/mesh2d.h"
#include "umppm/particles.h"
#include "umppm/ump.h"

/* What the seeding made. */
typedef struct mlseed_stats {
    size_t nfluid, nwall, ndummy;
    double x0, y0;            /* lattice origin (its points are at +1/2 l0) */
} mlseed_stats;

/* Half the median of sqrt(cell area): about four particles per cell. */
double mlseed_default_spacing(const mesh2d *m);

/* Distance from (px, py) to the segment (ax, ay)-(bx, by). */
double mlseed_seg_dist(double px, double py, double ax, double ay, double bx, double by);

/* Seed the empty part_set s: solid particles first (kinds[] gets
 * MPS_WALL or MPS_DUMMY for each, caller frees), then fluid ones with
 * velocity (u, v) [ncells] of their cell (NULL: at rest) and their cell.
 *   alpha [ncells]       liquid volume fraction per cell
 *   wall_patch [npatches of the polyMesh]  1 for patches of type wall
 *   wall_depth, thick    [m]: wall particles within wall_depth of the
 *                        wall, dummy ones up to thick
 * UMP_ERR_INPUT when no cell holds liquid or the lattice would exceed
 * 10^8 points (a spacing far too small for the mesh). */
ump_status mlseed_build(const mesh2d *m, const double *alpha, const double *u, const double *v,
                        const unsigned char *wall_patch, double l0, double wall_depth, double thick, part_set *s,
                        unsigned char **kinds, ump_idx **solid_face, mlseed_stats *st, ump_err *err);
/* solid_face (may be NULL): *solid_face gets, for each solid particle,
 * its nearest wall face (caller frees) -- the patch that carries it when
 * walls move. Particles are appended: s need not be empty. */

/* Points on the wall faces themselves (the boundary particles of the
 * finite particle method, fpm.h): a wall face of length L gets
 * k = ceil(L / l0) points at the centres of its k equal parts (spacing at
 * most l0; a corner is thus flanked by two points l0/2 or less from it),
 * each with the face's outward unit normal and its face index, velocity 0,
 * cell the face's owner. Appended to s; *nx, *ny, *face [*count] are
 * allocated (caller frees). */
ump_status mlseed_wall_points(const mesh2d *m, const unsigned char *wall_patch, double l0, part_set *s, double **nx,
                              double **ny, ump_idx **face, size_t *count, ump_err *err);

#endif
