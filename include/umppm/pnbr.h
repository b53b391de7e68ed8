/* SPDX-License-Identifier: GPL-3.0-or-later
 * pnbr.h -- neighbour rows of a particle set (module prefix pnbr_), shared
 * by the particle methods of meshlessFoam (mps.h, fpm.h).
 *
 * A linked-list search: the particles are binned on a square grid of the
 * search radius (counting sort, O(N)); a particle's neighbours are in the
 * 3 x 3 bins around its own. A row is the list of neighbours of one
 * particle within the radius (itself excluded), in increasing particle
 * index -- so every sum over a row is the same for any number of threads --
 * with the offset x_j - x_i and the distance of each.
 *
 * Rows are a Verlet list: built within radius + skin; while no particle
 * has moved by more than half the skin since the build, they still hold
 * every pair within the radius, and an update only recomputes offsets and
 * distances (one search per several steps instead of one per stage).
 */
#ifndef UMPPM_PNBR_H
#define UMPPM_PNBR_H

#include <stddef.h>

#include "umppm/particles.h"
#include "umppm/ump.h"

/* Rows (public, read-only for the callers) and the search's state. Start
 * from a zeroed struct; pnbr_free releases it. */
typedef struct pnbr {
    size_t *off;       /* [n + 1]: row of particle i = [off[i], off[i+1]); empty if not needed */
    size_t *j;         /* neighbour index */
    double *dx, *dy;   /* x_j - x_i */
    double *r;         /* |x_j - x_i| */
    /* private */
    size_t cap, rcap;  /* per-particle capacity, row-entry capacity */
    double *xb, *yb;   /* positions at the last build */
    size_t nb;         /* particle count at the last build; 0: none */
    double x0, y0, h;  /* grid */
    long nx, ny;
    size_t gcap;
    size_t *goff, *gcur, *gidx;
    long *gbin;
} pnbr;

void pnbr_free(pnbr *nb);

/* Rows within radius (m) for the particles i with need[kind[i]] > 0
 * (kind [n] of small integers, need indexed by them), neighbours of any
 * kind but the hidden ones: need[kind[i]] < 0 keeps particle i out of
 * every row (a solid covered by a moving wall); a caller that hides or
 * shows particles forces a new search. force, or a particle that moved by more than skin/2 since the last
 * build, or a different particle count: a new search within radius + skin;
 * otherwise the offsets and distances of the old rows at the current
 * positions. who names the caller in messages ("MPS"). Fails for a
 * non-finite position or more than 512 neighbours in one row (particles
 * collapsed onto each other: the run has diverged). */
ump_status pnbr_update(pnbr *nb, const part_set *s, const unsigned char *kind, const int *need, double radius,
                       double skin, int force, const char *who, ump_err *err);

#endif
