/* SPDX-License-Identifier: GPL-3.0-or-later
 * fpm.h -- free-surface flow on particles by the finite particle method
 * (module prefix fpm_); the numerics of meshlessFoam with `method FPM`
 * (docs/METHOD.md section 11).
 *
 * Source: Lu, Hu, Chang, Li & Wei, "Grid-free modelling based on the finite
 * particle method for incompressible viscous flow problems", Mathematical
 * Problems in Engineering 2019, 5623657 [LHC19]. Equation numbers in
 * comments are theirs:
 *   MLS fit and its full first and second derivatives     Eqs. 1-18 (mls_full)
 *   move  x^{n+1} = x^n + dt u^n                          Eq. 21
 *   predictor  u~ = u^n + dt (nu lap u^n + g)             Eq. 21
 *   correction u^{n+1} = u~ - dt/rho grad p^{n+1}          Eq. 22
 *   pressure Poisson equation lap p = rho/dt div u~        Eq. 24
 *   on walls dp/dn = rho n.(g - Du/Dt) + mu n.lap u        Eq. 25
 *   on the free surface p = 0
 *   time step dt <= 0.12 h0/|U|max, dt <= 0.24 sqrt(h0/|g|)  Eqs. 26-27
 *     (|U|max at least sqrt(|g| H), the celerity of the free surface's
 *     gravity waves: see fpm_max_dt)
 * All derivatives are MLS derivatives on the particles at x^{n+1}; the
 * pressure system is solved by BiCGSTAB (van der Vorst 1992) with ILU(0).
 *
 * Particles (one part_set): [0, nwall) boundary points ON the wall
 * surfaces, each with its outward unit normal (they carry the wall's
 * velocity and take part in the MLS stencils: no-slip, and the Neumann
 * rows of Eq. 25); [nwall, nsolid) ghost particles behind the walls, on
 * the fluid's lattice (mlseed.h), which only complete the number density
 * of the free-surface test near walls; [nsolid, n) fluid particles.
 *
 * Where the paper is silent (docs/METHOD.md section 11 gives the reasons):
 * the free surface is found by the number density of the MPS kernel,
 * n_i < beta n0 with r_s = 2.1 l0 over fluid and ghost particles, or the
 * weighted centroid of those neighbours off by more than shift l0 (a wall
 * point found so is dry: p = 0 there as well, and it is no MLS sample); a fluid particle
 * whose MLS fit falls back to the linear basis (too few neighbours) is a
 * free-surface particle; the explicit viscous term adds dt <= 0.1 l0^2/nu
 * to Eqs. 26-27; the Neumann rows are scaled by -l0 so that the matrix has
 * one sign on its diagonal (it changes nothing but ILU(0)'s pivots).
 */
#ifndef UMPPM_FPM_H
#define UMPPM_FPM_H

#include <stddef.h>

#include "umppm/lsolve.h"
#include "umppm/mls.h"
#include "umppm/particles.h"
#include "umppm/ump.h"

/* Kind of a particle. FPM_HIDDEN: a wall point or ghost covered by a
 * moving wall (fpm_hide): in no row, nobody's neighbour. */
enum { FPM_FLUID = 0, FPM_WALL = 1, FPM_GHOST = 2, FPM_HIDDEN = 3 };

typedef struct fpm_params {
    double l0;          /* particle spacing [m] */
    double h;           /* support radius h0 of the MLS weights [m] */
    mls_wfun weight;    /* Eq. 4 or Eq. 5 */
    double rho, nu;     /* the liquid's density, kinematic viscosity */
    double g[2];        /* gravity in the plane */
    double re_s;        /* radius of the free-surface number density / l0 */
    double beta;        /* free surface: n < beta n0 */
    double shift;       /* ... or the neighbours' centroid off by > shift l0 */
    double gamma;       /* weight of the density deviation in the PPE source (0: Eq. 24 alone) */
    double stab;        /* weight of the stabilising term of the PPE Laplacian (0: Eq. 24's MLS
                           Laplacian alone; fpm_laplacian_row) */
    double surf_damp;   /* damping of a free-surface particle's velocity towards its fluid
                           neighbours', nu_s = surf_damp l0 sqrt(|g| l0) (0: off; fpm_step) */
    double p_tol;       /* BiCGSTAB tolerance */
    int maxit;          /* BiCGSTAB iteration limit */
} fpm_params;

typedef struct fpm_stats {
    lsolve_stats pres;
    size_t nfluid, nsurface, nunknowns, nneumann; /* fluid, free-surface, PPE unknowns, wet wall points */
    size_t nlinear;                               /* rows whose MLS fit fell back to the linear basis */
    double n_min, n_max;                          /* number density / n0 of the fluid particles */
    double p_min, p_max;                          /* pressure of the fluid particles [Pa] */
    double cpu[4], wall[4]; /* neighbours + MLS, predictor, pressure, correction */
} fpm_stats;

typedef struct fpm fpm;

/* The solver around s (borrowed): [0, nwall) wall points with outward
 * normals (nx, ny) [nwall] (copied), [nwall, nsolid) ghosts, fluid after.
 * UMP_ERR_INPUT for parameters out of range. */
ump_status fpm_create(const fpm_params *prm, part_set *s, size_t nwall, size_t nsolid, const double *nx,
                      const double *ny, fpm **out, ump_err *err);
void fpm_free(fpm **f);

/* The acceleration of each wall point during the coming step [2 nwall]
 * (x, y interleaved; zeros unless the caller moves walls): the Du/Dt of
 * Eq. 25. The caller also sets the wall points' positions and velocities
 * (u, v of the part_set) for the end of the step before fpm_step. */
double *fpm_wall_accel(fpm *f);
/* The walls' normals [nwall] (the caller may rotate them). */
double *fpm_wall_normal(fpm *f, int comp);

/* One step of length dt (Eqs. 21-25). Fails (UMP_ERR_SINGULAR) when the
 * pressure solve breaks down, naming it. */
ump_status fpm_step(fpm *f, double dt, fpm_stats *st, ump_err *err);

/* The pressure equation alone (verification): rows and MLS fits at the
 * current positions, the classification of a step, then lap p = src_i on
 * the fluid particles inside, dp/dn = flux_i on the wet wall points,
 * p = pd_i (pd NULL: 0) on free-surface particles and dry wall points.
 * src, flux, pd [n] by particle; the result in fpm_pressure. */
ump_status fpm_poisson(fpm *f, const double *src, const double *flux, const double *pd, fpm_stats *st,
                       ump_err *err);

/* The Laplacian of a fluid particle's pressure row (docs/METHOD.md 11,
 * "Stabilised pressure Laplacian"; a departure from Eq. 24, which takes
 * the MLS Laplacian of Eqs. 16-18 alone):
 *   L p_i = lap_MLS p_i
 *         + eps sum_j c_j [p_j - p_i - d_j . grad p_i - d_j d_j : H p_i / 2],
 *   c_j = 4 w(|d_j| / h) / sum_k w(|d_k| / h) |d_k|^2   (2-D: L |d|^2 = 4),
 * grad p_i and the Hessian H p_i the MLS derivatives of the same fit. The
 * bracket is the residual of the particle's quadratic Taylor polynomial:
 * it vanishes for quadratics, so L stays exact for them (a hydrostatic
 * pressure is solved exactly); on a rough field the fit is smooth and the
 * term is a Laplacian with positive weights, which the MLS Laplacian is
 * not. Why it matters: with L, D, G the operators of Eqs. 24 and 22, each
 * step maps the last pressure to the next through I - L^-1 D G (the
 * divergence the last correction left behind is the next source), a map
 * independent of dt; with the MLS Laplacian alone its spectral radius on
 * irregular clouds exceeds 1 (test_fpm). In: the k offsets of the row
 * (index 0 the particle itself, at offset 0), the weight function and h
 * of the fit, its outputs cx, cy (d/dx, d/dy) and cxx, cxy, cyy (the
 * second derivatives; NULL or all zero for a linear fit). Out: lap[k]. */
void fpm_laplacian_row(const double *dx, const double *dy, int k, double h, mls_wfun wf, const double *cx,
                       const double *cy, const double *cxx, const double *cxy, const double *cyy, double eps,
                       double *lap);

/* The largest dt of Eqs. 26-27 (coefficients co, cg) and of the explicit
 * viscosity, for the current fluid velocities; Eq. 26 takes the speed
 * max(|U|max, u_wave), u_wave the celerity of gravity waves sqrt(|g| H)
 * (H the depth of the liquid). */
double fpm_max_dt(const fpm *f, double co, double cg, double u_wave);

/* Particle management (Section 4.1 of [LHC19]), after a step and after the
 * caller has located the particles; mg: its settings, in l0.
 *   walls   a fluid particle closer than d_wall to a wall face (signed
 *           distance to the nearest wall point's face) goes back to d_wall
 *           and loses its velocity into the wall (the paper is silent on
 *           fluid-wall pairs; without this they pile onto the wall points)
 *   merge   pairs of fluid particles closer than d_min become one at their
 *           midpoint, with the values interpolated there (the mean: linear
 *           interpolation at the midpoint of the pair)
 *   insert  at the largest Voronoi holes of the liquid (vor.h, qhull): the
 *           circumcentres of Delaunay triangles of inside fluid particles
 *           and wet wall points whose radius exceeds r_hole, inside their
 *           triangle, one per triangle and no two sharing a vertex per
 *           call; velocity and pressure by the MLS fit there (c0 of Eq. 1)
 *   repel   (d_rep > 0; before the walls and the merging) fluid pairs
 *           closer than d_rep: (a) a collision (MPS's model, Lee et al. 2011):
 *           the approaching part of the relative velocity is exchanged,
 *           restitution 0.2, and the particles move by dt times that
 *           change; (b) a repulsive shift dr_i = c_rep sum_j (d_rep - r_ij)
 *           e_ij over fluid and ghost neighbours within d_rep, at most
 *           0.2 l0, free-surface particles not shifted; velocity u +
 *           dr.grad u. Neither acts on a lattice (no pair closer than l0)
 * *keep [n before the call + inserted]: 0 for the particles merged away
 * (the caller compacts: part_compact, then fpm_compact); inserted
 * particles are appended to the part_set, their cell that of a neighbour
 * (a hint: the caller locates them). */
typedef struct fpm_manage_params {
    double d_wall, d_min, r_hole; /* / l0; 0 switches the action off */
    double shift;                 /* shifting coefficient A; 0: off */
    double d_rep, c_rep;          /* close-pair repulsion: radius / l0 (0: off), coefficient */
    int insert;                   /* search the holes (qhull) in this call */
} fpm_manage_params;
typedef struct fpm_manage_stats {
    size_t shifted, merged, inserted;
    double max_shift;             /* largest particle shift / l0 */
} fpm_manage_stats;
ump_status fpm_manage(fpm *f, const fpm_manage_params *mg, const unsigned char **keep, fpm_manage_stats *ms,
                      ump_err *err);

/* Gravity for the coming steps (a moving container solved in its own
 * frame: g - a(t), mlapp.c). */
void fpm_set_gravity(fpm *f, const double g[2]);

size_t fpm_nsolid(const fpm *f);
size_t fpm_nwall(const fpm *f);

/* Hide the wall points and ghosts i < nsolid with hidden[i] != 0
 * (covered by a moving wall), show the others again; takes effect at the
 * next step. */
void fpm_hide(fpm *f, const unsigned char *hidden);
/* Fluid particles removed or reordered by the caller (part_compact):
 * per-particle arrays follow keep[] (solid ones always kept). */
void fpm_compact(fpm *f, const unsigned char *keep, size_t n_before);

/* Per-particle results of the last step [n]: pressure [Pa], number
 * density / n0, free-surface flag (1: p = 0). */
const double *fpm_pressure(const fpm *f);
const double *fpm_density(const fpm *f);
const unsigned char *fpm_surface(const fpm *f);
/* n0 of the free-surface test (the full lattice). */
double fpm_n0(const fpm *f);

#endif
