/* SPDX-License-Identifier: GPL-3.0-or-later
 * solver.h -- the UMPPM time step (module prefix sol_): Steps 5-12 of
 * Section 3.3 of Ng, Sheu & Hwang (2016) [NSH16], docs/METHOD.md section 5.
 *
 * Units are OpenFOAM's incompressible ones: kinematic pressure p = P/rho and
 * kinematic viscosity nu, so the results compare directly with icoFoam.
 * The solver never touches files: the application hands it the mesh, the
 * settings, and the initial/boundary data as fld_field structs, and reads
 * back cell fields and particles to write them.
 *
 * One step, given dt:
 *   6  implicit predictor on the particles (Eq. 14) with the chosen particle
 *      Laplacian (CPM by default, Eqs. 16-17); boundary particles are
 *      Dirichlet data;
 *   7  intermediate positions r* = r^n + dt u* (Eq. 9), re-located, re-binned;
 *   8  MLS u* at face centres and centroids (Eqs. 28-35, Eq. 32);
 *   9  PPE on the fixed mesh (Eqs. 20, 22-26), factorized once, one solve;
 *   10 u^{n+1} = u* - dt grad p (Eq. 10, MLS gradient Eqs. 33-34),
 *      r^{n+1} = r^n + dt u^{n+1} (Eq. 7); mesh velocity Eq. 36;
 *   11 particle management (UMPPM or UMPPM*), removal of particles that
 *      left through open boundaries (a move that crosses a wall is stopped
 *      at the wall instead).
 *
 * Buoyant (settings.buoyant): the Boussinesq source -beta (T - TRef) g
 * (Eq. 4, per unit mass, T^n of the particle) enters the predictor (with
 * settings.balanced less the gradient of the pressure pi_b that balances
 * it, solved first each step with the same matrix) and the
 * particle temperature is advanced implicitly with the same particle
 * Laplacian and thermal diffusivity kappa = nu/Pr (Eq. 37); the mesh
 * temperature T_P is the MLS value of the particle temperatures at the
 * centroid (Step 10). The pressure solved for is then pi with
 *   Du/Dt = -grad pi - beta (T - TRef) g + nu lap u,
 * i.e. pi = p - gh in buoyantBoussinesqPimpleFoam's terms (gh = g.x - ghRef,
 * rhok = 1 - beta (T - TRef)): p = pi + gh, p_rgh = p - rhok gh.
 */
#ifndef UMPPM_SOLVER_H
#define UMPPM_SOLVER_H

#include "umppm/field.h"
#include "umppm/laplacian.h"
#include "umppm/lsolve.h"
#include "umppm/mesh2d.h"
#include "umppm/particles.h"

/* Value of a particle added at the centroid of an empty cell (Step 11):
 * the mesh velocity u_P of Eq. 36 ([NSH16]), or the carried values of the
 * nearest particles moved there by the MLS increment (solver.c
 * refill_carried). */
typedef enum { SOL_REFILL_CENTROID = 0, SOL_REFILL_CARRIED = 1 } sol_refill;

/* faceSupport auto: the support of Step 8's face fits, in cell extents, at
 * a face beside a triangle in a flow driven by its walls alone
 * (docs/METHOD.md section 8, "Face fits on triangles") */
#define SOL_FACE_SUPPORT_TRI 3.0

typedef struct sol_settings {
    double nu;               /* kinematic viscosity */
    part_variant variant;    /* UMPPM (adaptive) or UMPPM* (default) */
    double alpha;            /* UMPPM deletion: sqrt(alpha) d_c (default 0.09) */
    lap_params lap;          /* particle Laplacian (default CPM) */
    lsolve_kind ppe_solver;  /* default LSOLVE_AUTO */
    lsolve_pc pred_pc;       /* predictor preconditioner (default ILU0) */
    double pred_tol;         /* predictor relative tolerance (default 1e-12) */
    int pred_maxit;          /* default 500 */
    ump_idx p_ref_cell;      /* pRefCell, used without pressure boundaries */
    double p_ref_value;
    /* Boussinesq buoyancy and energy (Eqs. 3, 4, 37); 0: isothermal */
    int buoyant;
    double g[3];             /* gravity in the polyMesh's 3-D axes */
    double gh_ref;           /* ghRef = -|g| hRef (OpenFOAM's readhRef.H) */
    double beta, t_ref;      /* expansion coefficient [1/K], TRef [K] */
    double kappa;            /* thermal diffusivity nu/Pr [m^2/s] */
    int sort_interval;       /* re-sort particles by cell every N steps (default 1; 0 never) */
    sol_refill refill;       /* value of a particle added to an empty cell (default carried;
                                umppmFoam's `refill auto` sets centroid with UMPPM) */
    int refill_k;            /* carried: particles whose values are moved to the centroid
                                (default 4, 1..16) */
    int refill_increment;    /* carried: weights by the modelled variance of each
                                estimate, its MLS increment squared plus a noise
                                growing with its distance (default 1, refillWeights
                                increment; 1/d^2 where anisotropic is on);
                                0: 1/d^2 (refillWeights distance) */
    double mls_support;      /* > 0: the MLS weight has a fixed support of that many
                                cell extents, continuous in the particle positions
                                (default 2; docs/METHOD.md section 8); 0: Eq. 35's
                                scales (farthest sample + cell extent) */
    double face_support;     /* support of Step 8's fits of u* at the faces in cell
                                extents (> 0; 0: Eq. 35's scales), at a face with
                                no triangle on either side (default 2) */
    double face_support_tri; /* the same at a face beside a triangle (default 2;
                                umppmFoam's faceSupport auto: SOL_FACE_SUPPORT_TRI
                                in a flow driven by its walls alone,
                                docs/METHOD.md section 8, "Face fits on
                                triangles") */
    double p_theta;          /* pressureTheta, 0..1/2: the share of the previous
                                step's pressure gradient applied at r^n, the rest
                                at r* (default 0: all at r*, [NSH16] Eq. 10; 1/2:
                                the trapezoidal rule along the path) */
    int positive;            /* positiveRows: a CPM row whose implicit row loses
                                its diagonal dominance (2 dt nu sum max(-a_j, 0)
                                > 1; with anisotropic, any row more than 1 %
                                negative) is blended into the closest
                                non-negative row (lap_positive_row; default 1;
                                0: [NSH16]'s CPM) */
    int anisotropic;         /* anisotropicCells: LS gradient weights 1/|d|^2,
                                CPM in the metric of the cell extents, the
                                particles' pressure gradient from the cell
                                gradients (default 0: Eq. 26, plain CPM,
                                Eqs. 33-34; the application turns it on for
                                meshes stretched beyond 20:1) */
    int q_transpose;         /* interpolationError transpose: the interpolation
                                error's pressure q (the potential of the
                                particles' face-fit error, part of Step 9's p)
                                given to the particles by the transpose of Step
                                8's face fits, the rest of p by Eq. 10
                                (docs/METHOD.md section 8, "Walls in the
                                correction" (f); README "The interpolation
                                error by the transpose of the fits"); 0: the
                                whole p by Eq. 10 ([NSH16]); -1 (default):
                                1 exactly where anisotropic applies its walls
                                (not with buoyancy source), 0 elsewhere */
    int bounded_fits;        /* boundedFits: an MLS value fit or a carried refill
                                is kept within the range of its samples widened
                                by SOL_FIT_MARGIN of it (default 1; docs/METHOD.md
                                section 8, "Bounded fits"); 0: the fits as they come */
    int balanced;            /* buoyant: the predictor carries b - grad pi_b (by the
                                reconstruction of its face residuals), pi_b the
                                pressure that balances the buoyancy b (solver.c
                                balance_buoyancy); 0: b alone, as [NSH16] Eq. 14 */
    double t_start;          /* start time: boundary conditions that are functions
                                of time and have no `value` start at their value
                                at t_start (default 0) */
} sol_settings;

void sol_default_settings(sol_settings *s);
/* q_transpose as a solver built with s has it (-1 resolved). */
int sol_q_transpose(const sol_settings *s);

/* Stages of a step, timed separately (sol_stats.stage_cpu/stage_wall). */
enum {
    SOL_STAGE_BOUNDARY, SOL_STAGE_BALANCE, SOL_STAGE_PWRITE, SOL_STAGE_ROWS, SOL_STAGE_SOLVE, SOL_STAGE_MOVE, SOL_STAGE_MLS,
    SOL_STAGE_PPE, SOL_STAGE_CORRECT, SOL_STAGE_MANAGE, SOL_STAGE_DIAG, SOL_NSTAGES
};
/* Name of a stage for logs ("predictor rows (Step 6)", ...). */
const char *sol_stage_name(int stage);
/* Threads the solver's parallel loops use (OpenMP: OMP_NUM_THREADS). */
int sol_threads(void);

typedef struct sol_stats {
    double co_mean, co_max;      /* Courant number of the new mesh velocity */
    size_t np;                   /* fluid particles after the step */
    size_t added, deleted, left; /* management; removals through open boundaries */
    size_t walled;               /* moves (Steps 7 and 10) stopped at a wall */
    lsolve_stats pred[3];        /* predictor solves (u, v; T if buoyant) */
    double p_res0, p_res;        /* PPE: OpenFOAM-normalised residual before and
                                    after the direct solve */
    const char *p_solver;        /* the direct solver's name (UMFPACK, ...) */
    int fields_written;          /* this step computed the fields written: the
                                    pressure (sol_cell_p) and the cell velocity
                                    of every cell (sol_cell_u) */
    int lap_fallbacks;           /* Laplacian rows that fell back to another
                                    form (a singular fit: CPM4 to CPM to MPS,
                                    images or d/dn rows); a particle can
                                    count twice */
    int mls_fallbacks;           /* MLS fits that fell back to linear/Shepard */
    int bounded_values;          /* boundedFits: fitted values limited */
    int positive_rows;           /* positiveRows: CPM rows blended into or
                                    replaced by positive rows (lap_positive_row) */
    double cont_local, cont_global, cont_max; /* continuity after correction:
                                    dt-weighted as icoFoam's continuityErrs,
                                    and the max |sum_f flux| / area */
    double stage_cpu[SOL_NSTAGES];  /* CPU seconds (all threads) per stage */
    double stage_wall[SOL_NSTAGES]; /* wall seconds per stage */
} sol_stats;

typedef struct sol sol; /* opaque */

/* Build the solver: LS gradient and PPE (assembled and factorized once),
 * boundary particles, and one fluid particle per centroid with the cell
 * values of U (and T). U and p give the boundary conditions (types and
 * values; U: fixedValue, noSlip, movingWallVelocity, uniformFixedValue,
 * flowRateInletVelocity, zeroGradient, inletOutlet, outletInlet,
 * pressureInletOutletVelocity, symmetryPlane, symmetry, slip, cyclic; p:
 * fixedValue, uniformFixedValue, totalPressure, zeroGradient,
 * fixedFluxPressure, symmetryPlane, symmetry, slip, cyclic; others, p
 * inletOutlet/outletInlet and a face with U and p both fixed are refused
 * with UMP_ERR_UNSUPPORTED/UMP_ERR_INPUT; U and p must stay alive for the
 * time-dependent ones, sol_set_time); for a buoyant case p is p_rgh (its fixed faces become
 * pi = p_rgh - beta (T - TRef) gh each step) and T (required then; NULL
 * otherwise) gives the temperature: fixedValue, zeroGradient, symmetry,
 * symmetryPlane or inletOutlet. mesh, U, p and T are borrowed for the
 * solver's lifetime. */
ump_status sol_create(const mesh2d *m, const sol_settings *s, const fld_field *U, const fld_field *p,
                      const fld_field *T, sol **out, ump_err *err);
void sol_free(sol **S);

/* Replace the particles (restart from a cloud): positions and velocities of
 * n particles (temperatures T [n], or NULL: the cell temperature); each is
 * located by a walk starting at its hint cell [n] (the cloud's celli; NULL
 * or -1: cell 0), so a restart costs O(N) when the hints are right;
 * particles outside the mesh are dropped (*dropped). */
ump_status sol_set_particles(sol *S, size_t n, const double *x, const double *y, const double *u,
                             const double *v, const double *T, const int64_t *id, const ump_idx *hint,
                             size_t *dropped, ump_err *err);
/* Set the cell pressure (restart) before the first step. */
void sol_set_pressure(sol *S, const double *p);
/* Whether the coming steps compute the fields written (default yes): the
 * pressure written, sol_cell_p (one more MLS pass over the faces and one
 * more solve per step), and the cell velocity u_P of Eq. 36 in every cell,
 * sol_cell_u (an MLS fit per cell). It changes nothing else. Without it
 * sol_cell_u is current only in the owners of boundary faces (what a
 * patch's face values read); a caller that writes the fields only at some
 * steps asks for them before those. */
void sol_want_fields(sol *S, int yes);

/* The new time t of the coming step: evaluates the boundary conditions that
 * are functions of time (uniformFixedValue of U or p, flowRateInletVelocity),
 * as OpenFOAM's updateCoeffs does at the time of the step. Call it before
 * each sol_step (after advancing the time); without it they keep their
 * start values. */
void sol_set_time(sol *S, double t);

/* Advance one step of size dt. */
ump_status sol_step(sol *S, double dt, sol_stats *st, ump_err *err);

/* Courant numbers of the current mesh velocity for a step dt (OpenFOAM's
 * 0.5 dt sum_f |phi_f| / V, per unit thickness). */
void sol_courant(const sol *S, double dt, double *mean, double *max);

/* Current fields: cell velocity (Eq. 36) and pressure [ncells], face values
 * for boundary faces (velocity per 2-D boundary face). Borrowed. The cell
 * velocity is current in every cell after a step that computed the fields
 * written (sol_want_fields), else only in the owners of boundary faces. */
const double *sol_cell_u(const sol *S);
const double *sol_cell_v(const sol *S);
/* The cells whose velocity (sol_cell_u) the last step computed: NULL if
 * every cell (a step that computed the fields written, refill centroid,
 * anisotropicCells, or no step yet), else a mask [ncells] of the owners
 * of boundary faces. */
const unsigned char *sol_cell_u_current(const sol *S);
/* The pressure written (kinematic): the solution of the PPE of the last
 * step that computed it (sol_want_fields; sol_stats.fields_written) less the
 * potential of the particle-to-mesh interpolation error (docs/METHOD.md
 * section 8, "The pressure written"); the first step after the start has
 * no previous corrected fluxes and writes the PPE's solution. */
const double *sol_cell_p(const sol *S);
/* The PPE's solution of the last step, the pressure whose gradient
 * corrected the particles and the mesh velocity (Eqs. 10 and 36). */
const double *sol_cell_p_projection(const sol *S);
/* Face fluxes u_f . A_f per unit thickness [nfaces] after the last step's
 * correction (Eq. 20 with the new pressure; zero before the first step),
 * oriented owner to neighbour, outwards on boundary faces. */
const double *sol_face_flux(const sol *S);
/* Boundary-face values for writing: velocity and pressure on 2-D face f
 * (f >= ninternal). */
void sol_face_values(const sol *S, ump_idx f, double *u, double *v, double *p);

/* Buoyant only. Cell temperature T_P [ncells] (NULL if isothermal). */
const double *sol_cell_T(const sol *S);
/* Temperature on boundary face f: the fixed value, or the zero-gradient
 * extrapolation T_P + grad T_P . d_t (d_t the tangential part of the
 * centroid-to-face vector) used for its boundary particle. */
double sol_face_T(const sol *S, ump_idx f);
/* buoyantBoussinesqPimpleFoam's p and p_rgh at cell c (f < 0) or on
 * boundary face f: p = pi + gh, p_rgh = p - rhok gh; without fixed-pressure
 * faces p is shifted so that p[pRefCell] = pRefValue (its pEqn.H). */
void sol_buoyant_pressure(const sol *S, ump_idx c, ump_idx f, double *p, double *p_rgh);

/* Wall-normal temperature gradient on boundary face f, along the outward
 * normal (into the wall): SOL_GRAD_SNGRAD (T_f - T_P) / (n . (x_f - x_P)),
 * as OpenFOAM's snGrad without correction; SOL_GRAD_MLS the quadratic MLS
 * derivative (Eqs. 33-34) of the particle temperatures, boundary particles
 * included, at the face centre. Local heat flux into the fluid
 * q = k dT/dn (Eq. 43). */
typedef enum { SOL_GRAD_MLS, SOL_GRAD_SNGRAD } sol_grad_method;
ump_status sol_wall_dTdn(sol *S, ump_idx f, sol_grad_method how, double *dTdn, ump_err *err);
const part_set *sol_particles(const sol *S);
/* Particle-distribution quality of [HNS16] for every fluid particle:
 * uN [2n] the artificial velocity of PS (Eq. 13), tau [3n] the effective
 * diffusivity of IPS (Eq. 22) as xx, xy, yy; both with r_e = re_factor
 * (settings; 0: 2.0) times the particle's sqrt(cell area), over the
 * neighbours the predictor uses. Particles whose IPS matrix is singular get
 * zeros and are counted in *nfail. */
ump_status sol_particle_quality(sol *S, double *uN, double *tau, size_t *nfail, ump_err *err);

#endif
