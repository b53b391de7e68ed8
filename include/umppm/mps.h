/* SPDX-License-Identifier: GPL-3.0-or-later
 * mps.h -- free-surface flow on particles alone by the fully implicit
 * moving particle semi-implicit (MPS) method (module prefix mps_); the
 * numerics of meshlessFoam with `method MPS` (docs/METHOD.md section 9).
 *
 * Source: the "full implicit MPS method" (viscosity and pressure implicit,
 * free surface by number density, for high viscosity, 1-10 m^2/s, at large
 * time steps), after Koshizuka & Oka, "Moving-particle semi-implicit method
 * for fragmentation of incompressible fluid", Nucl. Sci. Eng. 123 (1996)
 * 421-434. Equation numbers in comments are those of that description:
 *   kernel w(r) = r_e/r - 1 (r < r_e), 0 beyond           Eq. 3
 *   gradient <grad f>_i = d/n0 sum (f_j - f_i) r_ij/|r_ij|^2 w   Eq. 4
 *   number density n_i = sum_{j != i} w(|r_ij|)            Eq. 5
 *   Laplacian <lap f>_i = 2d/(lambda n0) sum (f_j - f_i) w  Eq. 6
 *   lambda = sum |r_ij|^2 w / sum w (initial lattice)      Eq. 7
 *   implicit viscosity (u* - u^n)/dt = nu lap u* + g        Eqs. 11-14
 *   r* = r^n + dt u*                                        Eq. 10
 *   PPE <lap p>_i = -rho/dt^2 (n*_i - n0)/n0               Eqs. 16-18
 *   free surface n*_i < beta n0: p = 0                      (beta 0.98)
 *   u^{n+1} = u* - dt/rho <grad p>, r^{n+1} = r* + dt u'    Eq. 20
 *
 * Particles: one part_set (particles.h) holds them all, the fixed solid
 * particles first ([0, nsolid): wall particles, which take part in the
 * pressure equation, then dummy particles, which only complete the number
 * density of the wall particles), the moving fluid particles after them
 * ([nsolid, n)). Wall and dummy particles have zero velocity (no-slip
 * walls); fluid particles carry a persistent id and their mesh cell (kept by
 * the caller, which locates them on the mesh for output).
 *
 * Neighbours: a linked-list search on a square grid of spacing r_e
 * (the largest radius), rebuilt by counting sort after every move: O(N)
 * per step, no all-pairs loop. Rows of every sum run over neighbours in
 * increasing particle index, so the result does not depend on the number
 * of threads (a test checks 1 against 2 threads bit for bit).
 *
 * Where the description is silent (docs/METHOD.md section 9 gives the
 * reasons): the pressure gradient subtracts the local minimum pressure
 * p^_i = min(p_i, p_j) instead of p_i (Koshizuka, Nobe & Oka 1998), so the
 * gradient term is always repulsive; negative pressures are kept in the
 * Poisson solution; the source term can mix the velocity divergence with
 * the density deviation (Tanaka & Masunaga, J. Comput. Phys. 229 (2010)
 * 4279-4290) to reduce the pressure noise; a collision model (Lee et al.,
 * Comput. Methods Appl. Mech. Engrg. 200 (2011) 1113-1125) keeps
 * particles from coming closer than a fraction of l0.
 */
#ifndef UMPPM_MPS_H
#define UMPPM_MPS_H

#include <stddef.h>
#include <stdint.h>

#include "umppm/lsolve.h"
#include "umppm/particles.h"
#include "umppm/ump.h"

/* Kind of a particle. MPS_HIDDEN: a solid particle covered by a moving
 * wall (mps_hide): in no row, nobody's neighbour. */
enum { MPS_FLUID = 0, MPS_WALL = 1, MPS_DUMMY = 2, MPS_HIDDEN = 3 };

/* Source term of the pressure equation. */
typedef enum {
    MPS_SOURCE_DENSITY, /* Eq. 18: -(rho/dt^2)(n* - n0)/n0 */
    MPS_SOURCE_MIXED    /* (rho/dt) div u* - gamma (rho/dt^2)(n* - n0)/n0 */
} mps_source;

typedef struct mps_params {
    double l0;          /* initial particle spacing [m] */
    double re_n;        /* r_e of number density, gradient, divergence / l0 (2.1) */
    double re_lap;      /* r_e of the Laplacian / l0 (4.0) */
    double beta;        /* free surface: n* < beta n0 (0.98) */
    double lambda;      /* Laplacian parameter [m^2]; 0: Eq. 7 on the lattice */
    double rho, nu;     /* the liquid's density [kg/m^3], kinematic viscosity [m^2/s] */
    double g[2];        /* gravity in the plane [m/s^2] */
    mps_source source;
    double gamma;       /* weight of the density deviation in the mixed source */
    double collision;   /* collision distance / l0; 0: no collision model */
    double restitution; /* coefficient of restitution of the collision model */
    double p_tol;       /* CG tolerance of the pressure equation */
    double u_tol;       /* CG tolerance of the viscous step */
    int maxit;          /* CG iteration limit */
} mps_params;

/* Statistics of one step, for the log. */
typedef struct mps_stats {
    lsolve_stats visc[2];   /* viscous step, per component (iterations 0: nu = 0) */
    lsolve_stats pres;      /* pressure equation */
    size_t nfluid, nsurface, nunknowns; /* particles, free-surface ones, PPE unknowns */
    size_t collisions;      /* pairs the collision model separated */
    double n_min, n_max;    /* number density of fluid particles / n0 */
    double p_min, p_max;    /* pressure of the fluid particles [Pa] */
    double cpu[4], wall[4]; /* per stage: neighbours, viscosity, pressure, update */
} mps_stats;

typedef struct mps mps;

/* Create the solver around the particles s (borrowed; the first nsolid are
 * solid, kinds [nsolid] gives MPS_WALL or MPS_DUMMY for each). n0 and
 * lambda are computed on the square lattice of spacing l0 (Eqs. 5, 7).
 * UMP_ERR_INPUT for parameters out of range. */
ump_status mps_create(const mps_params *prm, part_set *s, size_t nsolid, const unsigned char *kinds, mps **out,
                      ump_err *err);
void mps_free(mps **m);

/* One time step of length dt (Eqs. 10-20). The caller then locates the
 * fluid particles on its mesh (their new positions are in the part_set).
 * Fails (UMP_ERR_SINGULAR) when a linear solve breaks down, naming it. */
ump_status mps_step(mps *m, double dt, mps_stats *st, ump_err *err);

/* Gravity for the coming steps (a moving container solved in its own
 * frame: g - a(t), mlapp.c). */
void mps_set_gravity(mps *m, const double g[2]);

/* Number of solid particles ([0, nsolid) of the part_set). */
size_t mps_nsolid(const mps *m);

/* Hide the solid particles i < nsolid with hidden[i] != 0 (covered by a
 * moving wall: a static wall's particles that a piston has passed over),
 * show the others again; takes effect at the next step. */
void mps_hide(mps *m, const unsigned char *hidden);
/* Tell the solver that fluid particles were removed or reordered by the
 * caller (part_compact on the part_set): its per-particle arrays follow
 * keep[] (indices of the part_set before compaction, solid ones always 1). */
void mps_compact(mps *m, const unsigned char *keep, size_t n_before);

/* Per-particle results of the last step ([n] of the part_set): pressure
 * [Pa], number density / n0, free-surface flag (1: p = 0 there). */
const double *mps_pressure(const mps *m);
const double *mps_density(const mps *m);
const unsigned char *mps_surface(const mps *m);
/* Number densities of the full lattice (Eq. 5) for r_e = re_n l0 and
 * re_lap l0, and lambda (Eq. 7 or as given). */
void mps_constants(const mps *m, double *n0_n, double *n0_lap, double *lambda);

/* Kernel of Eq. 3: r_e/r - 1 for 0 < r < r_e, else 0. */
static inline double mps_weight(double r, double re) { return r > 0 && r < re ? re / r - 1.0 : 0.0; }

/* Sum of w over a square lattice of spacing l0 without its origin, and
 * sum of |r|^2 w (for Eq. 7); re in units of l0. */
void mps_lattice_sums(double re, double *sum_w, double *sum_r2w);

#endif
