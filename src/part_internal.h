/* SPDX-License-Identifier: GPL-3.0-or-later
 * part_internal.h -- internals of the particle module shared between its
 * files and exposed to tests/unit/test_particles.c (not part of the API).
 */
#ifndef UMPPM_PART_INTERNAL_H
#define UMPPM_PART_INTERNAL_H

#include "umppm/particles.h"

/* The walk of part_locate without its fall-backs: PART_INSIDE / PART_LEFT as
 * part_locate, PART_LOST when more than `budget` faces would be crossed, a
 * cycle is detected, or the point is beyond walls only by more than d_c
 * (the caller then searches globally). *nsteps (may be NULL) = faces
 * crossed. */
part_where part_walk(const mesh2d *m, ump_idx start, double *x, double *y, ump_idx *cell,
                     ump_idx *face, long budget, long *nsteps);

/* Tolerance for "on the edge" at (x, y) in cell c: 1e-10 d_c plus a few
 * ulps of the coordinates. */
double part_eps(const mesh2d *m, ump_idx c, double x, double y);

#endif
