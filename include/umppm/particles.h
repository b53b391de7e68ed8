/* SPDX-License-Identifier: GPL-3.0-or-later
 * particles.h -- fluid and boundary particles on the pressure mesh (module
 * prefix part_), docs/METHOD.md section 4 and Section 3.2.2.2 of Ng, Sheu &
 * Hwang (2016) [NSH16].
 *
 * Struct-of-arrays storage with one grow function. Each fluid particle knows
 * its cell; after every move the particle is re-located by walking from its
 * previous cell across the face it leaves through (a global search over
 * cells is the fall-back), and the set is re-binned per cell (counting sort,
 * O(N)). Neighbour search = the particles of {P} and N2(P) of the particle's
 * cell P (mesh2d stencils) plus the boundary particles of those cells: no
 * all-pairs loop anywhere. Across cyclic faces a particle's position wraps
 * by the face separation, and neighbours carry the stencil shift.
 *
 * Boundary particles sit at the centres of the boundary faces (Step 2) and
 * never move; their values are the boundary data.
 */
#ifndef UMPPM_PARTICLES_H
#define UMPPM_PARTICLES_H

#include <stddef.h>
#include <stdint.h>
#include "umppm/mesh2d.h"

/* Dimension of the particle arrays (pos[d], vel[d]); the kernels of the
 * 2-D solver are specialised for it at compile time. */
#define PART_DIM 2

typedef struct part_set {
    size_t n, cap;
    /* position (in-plane coordinates of mesh2d) and velocity, by name or
     * by dimension (pos[d], vel[d]: the same arrays, no cost at run time;
     * a 3-D solver extends PART_DIM instead of adding names) */
    union {
        struct { double *x, *y; };
        double *pos[PART_DIM];
    };
    union {
        struct { double *u, *v; };
        double *vel[PART_DIM];
    };
    double *T;         /* temperature (always allocated; unused if isothermal) */
    ump_idx *cell;     /* containing cell */
    int64_t *id;       /* persistent id (origId in the lagrangian cloud) */
    int64_t next_id;
} part_set;

ump_status part_create(size_t cap, part_set **out, ump_err *err);
void part_free(part_set **s);
/* Make room for at least cap particles (amortised doubling). */
ump_status part_reserve(part_set *s, size_t cap, ump_err *err);
/* Append one particle with a fresh id (next_id++); returns its index in *idx
 * (idx may be NULL). */
ump_status part_add(part_set *s, double x, double y, double u, double v, double T, ump_idx cell,
                    size_t *idx, ump_err *err);
/* Remove particles with keep[i] == 0 (order of the rest preserved). */
void part_compact(part_set *s, const unsigned char *keep);
/* One particle at every cell centroid (Step 2), values from cell arrays
 * u, v, T [ncells] (T may be NULL: T = 0). Appends to the set (cell c's
 * particle gets index n_before + c). */
ump_status part_seed_centroids(part_set *s, const mesh2d *m, const double *u, const double *v,
                               const double *T, ump_err *err);

/* Result of moving a particle. */
typedef enum {
    PART_INSIDE = 0,   /* found; cell updated (position wrapped across cyclics) */
    PART_LEFT = 1,     /* crossed a boundary face (*face set): to be removed */
    PART_LOST = 2      /* not found anywhere (should not happen) */
} part_where;

/* Locate point (*x, *y) starting from cell `start`: walk cell to cell across
 * the faces the point lies beyond; crossing a cyclic face wraps *x, *y by
 * the separation (owner -> neighbour: += sep, neighbour -> owner: -= sep);
 * crossing a boundary face returns PART_LEFT with that face.
 * Falls back to a search over all cells if the walk exceeds its budget or
 * cycles (or start is not a cell).
 *   PART_INSIDE: *cell = containing cell, *face = -1, *x, *y wrapped.
 *   PART_LEFT:   *face = boundary face crossed, *cell = its owner, *x, *y
 *                as walked (not moved back into the domain). Returned when
 *                the point is beyond boundary faces only, by at most d_c,
 *                and in no cell of N2 (round a domain corner); farther
 *                beyond, the global search decides and, if it finds no
 *                cell, the nearest boundary face is reported.
 *   PART_LOST:   non-finite point, or no cell and no boundary face (fully
 *                periodic mesh, point outside the periodic box); *cell =
 *                *face = -1.
 * A point on an edge or vertex (within 1e-10 d_c) belongs to the first cell
 * of the walk that contains it (boundary-inclusive cells). */
part_where part_locate(const mesh2d *m, ump_idx start, double *x, double *y, ump_idx *cell,
                       ump_idx *face);
/* Is (x, y) inside cell c (polygon test, boundary inclusive)? */
int part_in_cell(const mesh2d *m, ump_idx c, double x, double y);

/* Particles binned per cell: particles of cell c are idx[off[c] .. off[c+1]-1],
 * in increasing particle index. Zero-initialise (part_bins b = {0}) before
 * the first build; later builds reuse the storage (amortised growth).
 * Particles with cell < 0 (marked as left) are not binned. */
typedef struct part_bins {
    ump_idx ncells;
    ump_idx *off;      /* [ncells+1] */
    size_t *idx;       /* [cap] */
    size_t cap;
    void *work;        /* scratch of part_manage (owned here, grown amortised) */
    size_t work_bytes;
} part_bins;


/* UMP_ERR_INPUT if a particle's cell is >= ncells (bins then invalid).
 */
ump_status part_bins_build(part_bins *b, const mesh2d *m, const part_set *s, ump_err *err);
/* Reorder the particles by cell (stable: by index within a cell), an O(N)
 * gather from the bins, so that neighbours in the mesh are neighbours in
 * memory and the particles of a cell are consecutive; the bins are left
 * current (identity order). Every particle must have a cell >= 0. Ids
 * travel with the particles. */
ump_status part_sort_by_cell(part_set *s, part_bins *b, const mesh2d *m, ump_err *err);
void part_bins_free(part_bins *b);

/* Boundary particles: one per boundary face (faces ninternal..nfaces-1). */
typedef struct part_boundary {
    ump_idx n;          /* = m->nfaces - m->ninternal */
    union {             /* face centres, by name or dimension */
        struct { double *x, *y; };
        double *pos[PART_DIM];
    };
    union {             /* boundary velocity, set by the solver each step */
        struct { double *u, *v; };
        double *vel[PART_DIM];
    };
    double *T;          /* boundary temperature */
    ump_idx *face;      /* 2-D face index */
    ump_idx *off, *idx; /* per cell (owner) CSR of boundary particles [ncells+1] */
} part_boundary;

/* Fills *b (values u, v, T set to 0); part_boundary_free releases it. */
ump_status part_boundary_create(part_boundary *b, const mesh2d *m, ump_err *err);
void part_boundary_free(part_boundary *b);

/* A neighbour of a point: fluid particle (is_boundary 0, index into the
 * part_set) or boundary particle (is_boundary 1, index into part_boundary),
 * with its offset from the point (shift across cyclics applied). */
typedef struct part_nbr {
    size_t index;
    int is_boundary;
    double dx, dy;
} part_nbr;

/* Neighbours of point (x, y) in cell c: fluid and boundary particles of
 * {c} and N2(c). Writes at most max entries into out (the count is returned;
 * a return > max means out was too small). `exclude` is a fluid particle
 * index to leave out (the point itself) or SIZE_MAX. Order: cell c, then
 * N2(c) in stencil order; per cell its fluid particles (bin order), then its
 * boundary particles. bp may be NULL (fluid particles only). The bins must
 * be current. */
size_t part_neighbours(const mesh2d *m, const part_set *s, const part_bins *b,
                       const part_boundary *bp, ump_idx c, double x, double y, size_t exclude,
                       part_nbr *out, size_t max);

/* Particle management (Section 3.2.2.2). */
typedef enum { PART_UMPPM, PART_UMPPM_STAR } part_variant;

typedef struct part_manage_stats {
    size_t deleted_close;   /* UMPPM: particles deleted, each closer than
                               sqrt(alpha) d_c to a kept one */
    size_t deleted_extra;   /* UMPPM*: all but the one nearest the centroid */
    size_t added;           /* empty cells refilled at the centroid */
    size_t removed_left;    /* particles with cell < 0 (left the domain) removed */
} part_manage_stats;

/* UMPPM: delete one of any two particles in the same cell or in N1
 * neighbouring cells closer than sqrt(alpha)*d_c (d_c of the cell of the
 * particle kept); UMPPM*: keep only the particle nearest each centroid.
 * Then add a particle at the centroid of every empty cell with velocity
 * (uc, vc) and temperature Tc [ncells] (Eq. 36; Tc may be NULL: T = 0).
 * Particles with cell < 0 are removed first. Which particle of a close pair
 * is kept: the one nearer its own cell centroid (greedy, in increasing
 * distance to the own centroid, ties by lower index), so every surviving
 * pair is at least sqrt(alpha)*d_c apart, d_c of the cell of the member
 * nearer its centroid (refilled centroid particles, added after the
 * deletion as in the paper, may be closer). UMPPM* ties: lower index kept. Survivors keep their
 * order and ids; new particles are appended. Bins are built on entry (need
 * not be current) and rebuilt on exit. alpha is used by UMPPM only (> 0). */
ump_status part_manage(part_set *s, part_bins *b, const mesh2d *m, part_variant variant, double alpha,
                       const double *uc, const double *vc, const double *Tc, part_manage_stats *st,
                       ump_err *err);

/* part_manage with a refill function: after the deletion is decided and
 * before it is carried out (the bins, built on entry, still hold every
 * particle), refill(ctx, alive) is called with alive[i] != 0 for the
 * particles that stay; it may set uc, vc, Tc (the caller's arrays, passed
 * again here) of the cells that no surviving particle occupies, which
 * are then refilled with them. NULL: as part_manage. */
typedef ump_status (*part_refill_fn)(void *ctx, const unsigned char *alive, ump_err *err);
ump_status part_manage_refill(part_set *s, part_bins *b, const mesh2d *m, part_variant variant, double alpha,
                              part_refill_fn refill, void *ctx, const double *uc, const double *vc,
                              const double *Tc, part_manage_stats *st, ump_err *err);

#endif
