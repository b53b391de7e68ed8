/* SPDX-License-Identifier: GPL-3.0-or-later
 * solver.c -- one UMPPM time step (Steps 6-11, Section 3.3 of Ng, Sheu &
 * Hwang 2016; Step 5, the time step, is runtime.c's, Step 12, the output,
 * app.c's). docs/METHOD.md section 5 maps each step to its equations.
 *
 * Data flow of a step (particles P, mesh M):
 *   P: u^n, r^n --(Eq. 14 implicit predictor, CPM Laplacian)--> u*   step6
 *      (pressureTheta > 0: with -th dt grad p^{n-1/2}, path_pressure_kick)
 *   P: r* = r^n + dt u*                                  (Eq. 9)    step7
 *   M: u*_f, u*_P by MLS from P at r*                    (Eqs. 28-35, 32) step8
 *   M: PPE sum_f grad p_f . A_f = (1/dt) sum_f u*_f . A_f (Eqs. 20, 25) step9
 *   P: u^{n+1} = u* - dt grad p (MLS over centroid p)    (Eqs. 10, 33-34) step10
 *   P: r^{n+1} = r^n + dt u^{n+1}                        (Eq. 7)
 *   M: u_P = u*_P - dt grad p_P (LS gradient)            (Eqs. 36, 26)
 *   P: delete/add particles (UMPPM or UMPPM*)            (Section 3.2.2.2) step11
 *
 * Data. Three kinds, kept apart:
 *   sol_setup  what never changes after sol_create: the mesh operators (LS
 *              gradient, the factorized PPE, the sorted particle stencils,
 *              the faces each cell owns), the boundary-condition tables, gh;
 *   sol_state  the state of the run: particles and their bins, boundary
 *              particle values, mesh fields, the predictor system;
 *   sol_work   one per thread: gathered neighbours, offsets, fit
 *              coefficients and that thread's fall-back counters. Every
 *              stage gets its work buffer as an argument; counters are
 *              summed over threads into sol_stats.
 * Sparse assembly (the predictor rows) is count -> prefix sum -> fill, each
 * row written by one thread, so no assembly reallocates inside a loop and
 * the matrix is the same for any thread count.
 *
 * Threads (OpenMP): every particle, face and cell loop of a step is split
 * over threads; each iteration writes only its own outputs, and every
 * floating-point reduction is either order-free (max) or done in a fixed
 * order (lsolve_rows.c's blocked dot products; the continuity sums run
 * serially over per-cell values), so 1 and N threads give bit-identical
 * results. Serial: the PPE's triangular solves (SuiteSparse), binning,
 * removal and refill, and the UMPPM deletion pass.
 *
 * Choices where the paper is silent (also in the README):
 *   - Boundary particles carry the prescribed velocity on fixedValue/noSlip/
 *     movingWallVelocity/uniformFixedValue/flowRateInletVelocity faces (the
 *     last two evaluated at the new time of the step, sol_set_time); on
 *     zeroGradient (outlet) faces the velocity of the owner cell (Eq. 36 of
 *     the previous step); on inletOutlet faces the inletValue where the last
 *     flux entered, else the owner cell velocity; on outletInlet faces the
 *     reverse (outletValue where the last flux left); on
 *     pressureInletOutletVelocity faces the owner cell velocity where the
 *     last flux left, and where it entered the owner cell's normal velocity
 *     plus the tangential part of tangentialVelocity (zero if not given);
 *     on symmetry planes and slip walls the owner cell velocity without its
 *     normal part. "The last flux" is the corrected face flux of the
 *     previous step, the phi OpenFOAM's boundary conditions look up.
 *   - totalPressure faces are fixed-pressure (Dirichlet) faces whose value
 *     is set before each PPE solve: p0 where the last flux left, p0 -
 *     |U_b|^2/2 where it entered, U_b the face's boundary-particle velocity
 *     of this step (v1912's p0 - 0.5 (1 - pos0(phi)) |U_p|^2, kinematic).
 *   - MLS at a face whose velocity is not prescribed leaves out that face's
 *     own boundary particle (its value is derived from the interior).
 *   - The pressure gradient at a particle (Eq. 10) is the MLS derivative of
 *     the centroid pressures of the particle's cell and its N2 stencil,
 *     evaluated at the intermediate position r* where the particle was
 *     binned for Step 8. A mesh-only alternative (the quadratic MLS fit
 *     centred at the cell centroid, built once, Taylor-expanded to the
 *     particle) was tried and measured worse: on the Re 100 cavity with 404
 *     triangles (test_solver_cavity.sh) v_rms against Ghia rose from 0.0102
 *     to 0.0117, so the per-particle fit (the paper's) stays.
 *   - A particle whose CPM moment matrix is singular (too few independent
 *     neighbours) gets the MPS Laplacian for that step (counted in stats).
 *   - A move (to r* or r^{n+1}) that crosses a wall (a face with a
 *     prescribed velocity that is not outflow, a symmetry plane, a slip
 *     wall) stops at the wall (wall_stop): the particle keeps its carried
 *     velocity instead of being deleted and re-seeded by interpolation.
 *     Particles that cross an open boundary face (outlets, pressure
 *     inlets) are removed at the end of the step; the empty-cell refill
 *     then repopulates.
 *   - A particle added to an empty cell (Step 11) takes, by default with
 *     UMPPM* (refill carried), the mean over the K nearest fluid particles of
 *     their carried values moved to the centroid by the MLS increment of
 *     the other samples (refill_carried), not the MLS mesh velocity u_P of
 *     Eq. 36 (refill centroid, the paper's): each refill by u_P replaced a
 *     carried value by a smoothed one (Taylor-Green at CFL 0.25: 2.5 % of
 *     the amplitude lost by t = 5). The K estimates are weighted by the
 *     inverse of a modelled variance, the square of the estimate's MLS
 *     increment plus a noise term growing with the distance
 *     (refillWeights increment), so that in a boundary layer the
 *     particles along the flow lend more than those across it; 1/d^2
 *     where anisotropicCells is on.
 *   - Particles are re-sorted by cell after the management of every step
 *     (sortInterval), an O(N) gather from the bins: the particles of a cell
 *     are consecutive, stencil neighbours are near in memory, and the
 *     predictor rows come out with increasing columns.
 *   - Buoyant: the energy equation (Eq. 37) uses the predictor's Laplacian
 *     rows (same particles at r^n, same coefficients a_j) scaled by
 *     dt kappa instead of dt nu. Temperature boundary particles carry the
 *     fixedValue; on zeroGradient (adiabatic) and symmetry faces they carry
 *     T_P + grad T_P . d_t of the owner cell, d_t the tangential part of
 *     x_f - x_P (the value a zero normal gradient gives, second order on
 *     smooth fields), so the implicit Laplacian sees no spurious flux there;
 *     inletOutlet: the inletValue where the last flux entered. T_P (Step 10)
 *     is the MLS value at the centroid of the particle temperatures after
 *     the move, before management, so refilled particles get T = T_P.
 */
#include "umppm/solver.h"
#include "umppm/lsq.h"
#include "umppm/mls.h"
#include "umppm/ppe.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* Velocity condition of a boundary face (boundary_velocity). */
enum { BU_FIXED = 0, BU_OUTLET, BU_INLETOUTLET, BU_SYMMETRY, BU_OUTLETINLET, BU_PRESSUREINLETOUTLET };
enum { BT_FIXED = 0, BT_ZEROGRADIENT, BT_INLETOUTLET };

typedef struct sol_setup {
    const mesh2d *m;
    sol_settings set;
    lsq_grad *g;
    lsq_grad *gw;              /* anisotropicCells: Eq. 26 with the walls (wall_faces_build) */
    ppe *pe;
    /* boundary conditions per boundary face b = f - ninternal */
    unsigned char *u_kind;
    unsigned char *p_dir;      /* [nfaces] fixed pressure */
    unsigned char *p_total;    /* [nb] totalPressure face */
    double *p0;                /* [nb] totalPressure: p0 */
    /* boundary conditions that are functions of time (uniformFixedValue,
     * flowRateInletVelocity), evaluated by sol_set_time */
    struct sol_timed {
        int patch;             /* pmesh patch */
        int is_p;              /* 0: U, 1: p (p_rgh when buoyant) */
        double area;           /* total 3-D face area of the patch */
        double *nrm;           /* [3*n] outward unit normals (3-D axes) */
        double *val;           /* [3*n] scratch for the face values */
    } *timed;
    int ntimed;
    int need_ref;              /* no fixed-pressure face: pRefCell fixes the level */
    unsigned char *t_kind;     /* buoyant: temperature condition per boundary face */
    double *tb;
    double *ghc, *ghf;         /* buoyant: gh at cells and faces */
    double *rinv;              /* buoyant: [3 ncells] (sum_f n_f n_f^T |A_f|)^-1 of
                                  each cell (xx, xy, yy), the reconstruction of a
                                  vector from its face fluxes (balance_buoyancy) */
    /* particle stencil of each cell: {c} u N2(c) in increasing cell order,
     * with the cyclic shift of each entry */
    ump_idx *st_off, *st_cell;
    double *st_sx, *st_sy;
    ump_idx st_max;            /* largest stencil (cells) */
    ump_idx pd_max;            /* most fixed-pressure faces of one stencil's cells */
    /* the same stencils as runs of consecutive cells with one shift: cells
     * ru_q0[r] .. ru_q1[r]-1, whose particles are consecutive in the bins */
    ump_idx *ru_off, *ru_q0, *ru_q1;
    double *ru_sx, *ru_sy;
    /* per cell: its stencil holds boundary particles (their set is fixed;
     * laplacian CPM4 keeps CPM there) */
    unsigned char *st_bnd;
    ump_idx *pd_off, *pd_face; /* per cell [ncells+1]: its fixed-pressure boundary faces */
    /* anisotropicCells: the boundary faces where the PPE's condition is
     * Neumann with a prescribed flux (velocity prescribed or symmetry, p
     * not fixed), flagged per boundary face and listed per cell */
    unsigned char *wall;       /* [nb] */
    ump_idx *wf_off, *wf_face;
    ump_idx wf_max;            /* most such faces of one stencil's cells */
    /* faces whose u* is interpolated (not fixed, not symmetry), by owner */
    ump_idx *of_off, *of_face;
    double *fsx, *fsy;         /* [nfaces] the scales of Step 8's face fits
                                  (face_scales_build, once) */
    /* [ncells] the owners of boundary faces: Step 8 fits their u*_P at
     * every step (the boundary particles and a patch's face values read
     * their u_P), not only at the steps that compute the fields written */
    unsigned char *uc_keep;
} sol_setup;

/* A gathered neighbour: fluid particle ref >= 0, boundary particle
 * ref = -1 - b. */
#define SOL_MAX_VALUES 3 /* quantities one MLS fit interpolates (u, v, T) */
/* positiveRows: a CPM row whose negative coefficients add up to more than
 * this share of its positive ones is blended into the positive row (fully
 * at twice the share; on uniform lattices about one row in 1 600 exceeds
 * it, on graded meshes one in five, on the stretched cavities most rows) */
#define SOL_POSITIVE_TAU 0.01
/* boundedFits: a fitted value may leave the range [lo, hi] of its samples
 * by this share of hi - lo (docs/METHOD.md section 8, "Bounded fits"): on
 * the 40^2 Re 1000 cavity no refill in 400 steps left it (7 left [lo, hi]
 * by more than 0.25 of the span, 649 left [lo, hi] itself, and limiting
 * those to [lo, hi] moved the cavity's RMS against Ghia from 0.0175 to
 * 0.0217); near the lid's corner of a cavity graded 1000:1 toward it,
 * refills of -30 to +26 times the lid speed, and the run diverged */
#define SOL_FIT_MARGIN 0.25
/* refillWeights increment: the noise of a carried estimate from distance d,
 * (d / l)^2 (kappa x the speed range of the stencil's samples)^2, l^2 the
 * empty cell's area (refill_value). kappa 0.15 by measurement (README,
 * "Refill weights by the increment"): 0.1 was best on the Re 1000 40^2
 * cavity's whole field but put the elbow's inlet-6 pressure 1.42x the
 * converged one, 0.2 let the cavity graded 10:1 toward its walls reach
 * 1.11x the lid speed */
#define SOL_REFILL_NOISE 0.15
/* The interpolation error's pressure by the transpose of the fits
 * (transpose_q): F of the 2 x 2 system sum_f |c_fj| n_f n_f^T + F I of a
 * particle, against the O(1) of a particle that enters its cell's face
 * fits fully; it caps the increment of one that hardly enters any (0.001
 * and 0.02 ... 0.5 measured alike on the 8x8 graded cavity, README) */
#define SOL_TQ_FLOOR 1.0e-3
typedef struct sol_work {
    size_t cap;
    union {                    /* gathered positions (stencil shift applied) */
        struct { double *px, *py; };
        double *gpos[PART_DIM];
    };
    ump_idx *ref;
    union {                    /* offsets from the target */
        struct { double *h, *k; };
        double *off[PART_DIM];
    };
    ump_idx *sref;             /* refs of the samples in h, k order */
    /* image_row: the samples with their images across zero-gradient
     * planes (offsets, coefficients, scratch, source sample), room icap */
    size_t icap;
    double *ih, *ik, *ia;
    int *isrc;
    double *c0, *cx, *cy;      /* MLS / Laplacian coefficients */
    double *pv;                /* stencil values (pressure gradient) */
    double *gv[SOL_MAX_VALUES]; /* gathered sample values (gather_values) */
    long lap_fallbacks, mls_fallbacks;
    long positive_rows;        /* positiveRows: CPM rows made positive */
    long bounded;              /* boundedFits: values limited */
    double fit_margin;         /* boundedFits: SOL_FIT_MARGIN, or < 0 (off) */
    ump_err err;               /* first error of this thread in a stage */
    ump_status rc;
} sol_work;

typedef struct sol_state {
    part_set *P;
    part_bins bins;
    part_bins bins_star;       /* the bins at r* of Step 8, kept through Step 11
                                  (refill_carried's u_P of a cell not fitted) */
    part_boundary bp;
    /* mesh fields */
    double *p, *uc, *vc, *usc, *vsc, *flux, *gflux, *gx, *gy, *div;
    double *pold;              /* [ncells] pressureTheta > 0: the previous step's
                                  pressure p^{n-1/2} (balanced buoyancy: pi_d),
                                  then the increment phi of this step */
    double *pf;                /* [nfaces] face pressure of fixed faces (pi) */
    double *pfprev, *pfphi;    /* [nfaces] pressureTheta > 0: pf of pold, of the increment */
    double *bpue, *bpve;       /* [nb] the boundary particles' values in the
                                  interpolation error's fit when shifted */
    double *pib, *fluxb, *pf0; /* buoyant (balanced): pi_b [ncells], its face fluxes
                                  [nfaces] (balance_buoyancy), and pi_d's fixed face
                                  values, zero [nfaces] (step_face_pressure) */
    double *hxx, *hxy, *hyy;   /* buoyant: the buoyancy's gradient -beta sym(g grad T_P)
                                  [ncells], pi_b's Hessian (balance_buoyancy) */
    double *rbx, *rby;         /* buoyant: [ncells] what pi_b leaves of the buoyancy,
                                  reconstructed from its face residuals (balance_buoyancy) */
    /* boundary values of this step per boundary face b = f - ninternal */
    double *ub, *vb;           /* prescribed velocity (fixed faces), inletValue,
                                  outletValue, or the tangential inflow velocity
                                  of pressureInletOutletVelocity */
    double *prgh_f;            /* [nfaces] buoyant: prescribed p_rgh */
    double *Tc, *gtx, *gty;    /* buoyant: mesh temperature T_P, its LS gradient */
    /* the pressure written (interpolation_error): p_d = p - q [ncells], the
       interpolation error eps_f [nfaces], its potential q [ncells], zero
       face values [nfaces] */
    double *pout, *fluxe, *q, *fz;
    int want_fields;           /* this step computes pout and u_P in every cell
                                  (sol_want_fields) */
    int uc_all;                /* the last Step 8 fitted u*_P in every cell */
    double *bpus, *bpvs;       /* [nb] the boundary particles' values in Step
                                  8's fit when shifted (bp_shifted; kept for
                                  refill_up) */
    int bp_shifted;
    int split;                 /* this step has computed q */
    /* anisotropicCells (transpose_q): p_d for the particles' Eq. 10
       [ncells], grad q . A_f [nfaces], and the face fits' coefficients of
       Step 8 per cell: slots tq_off[c] ... + tq_len[c] of (particle, face,
       coefficient) */
    double *pd, *gq;
    size_t *tq_off;
    ump_idx *tq_len;
    struct tq_entry { ump_idx ref, face; double c; } *tq;
    size_t tq_cap;
    int have_flux;             /* flux holds a corrected (divergence-free) phi^n */
    /* per particle */
    size_t wcap;
    double *x0, *y0, *us, *vs, *rhs_u, *rhs_v, *Ts, *rhs_T;
    double *xs, *ys;           /* r* of Step 8, kept through Step 11 (bins_star) */
    double *gpx, *gpy;         /* a pressure gradient at the particles */
    double *wdamp;             /* share of the correction a particle keeps next
                                  to a wall (step6_rows, walls_zero_gradient) */
    double *qa, *qb, *qc, *qx, *qy; /* transpose_q: the particle's 2 x 2 system
                                  (a b; b c) and right-hand side, then its
                                  increment in qx, qy */
    ump_idx *cell0;
    unsigned char *keep;
    /* predictor system I + dt nu L in rows */
    ump_idx *rp, *ci;
    double *av;
    double *avT;               /* [rowcap] rows of Eq. 37 when they differ from
                                  the predictor's (zero-gradient T faces), or NULL */
    unsigned char *uneu, *tneu; /* [nb] the boundary particle is a zero gradient of
                                  U, of T (buoyant) this step (set_boundary_particles) */
    ump_idx nneu;              /* how many are either */
    ump_idx ndiffer;           /* how many are one and not the other (buoyant) */
    int sepT;                  /* this step's rows for T are st->avT */
    int pold_pd;               /* pold holds the last step's pi_d (step10_correct) */
    size_t rowcap;
    ump_idx *cnt_cell;         /* [ncells] fluid particles in each cell's stencil */
    ump_idx *empty;            /* [ncells] the cells without a particle (refill_carried) */
    double *fu, *fv, *fT;      /* [ncells] refill values of those cells */
    lsolve_rows *kry;
    long steps;
} sol_state;

struct sol {
    sol_setup su;
    sol_state st;
    const fld_field *U, *pfld; /* borrowed: the boundary conditions of sol_set_time */
    int nthreads;
    sol_work *work;            /* [nthreads] */
};

void sol_default_settings(sol_settings *s)
{
    memset(s, 0, sizeof *s);
    s->nu = 0;
    s->variant = PART_UMPPM_STAR;
    s->alpha = 0.09;
    s->lap.model = LAP_CPM;
    s->lap.re_factor = 0; /* the model's default */
    s->ppe_solver = LSOLVE_AUTO;
    s->pred_pc = LSOLVE_PC_JACOBI;
    s->pred_tol = 1e-12;
    s->pred_maxit = 500;
    s->p_ref_cell = 0;
    s->p_ref_value = 0;
    s->sort_interval = 1;
    s->refill = SOL_REFILL_CARRIED;
    s->refill_k = 4;
    s->refill_increment = 1;
    s->mls_support = 2;
    s->face_support = 2;
    s->face_support_tri = 2;
    s->p_theta = 0;
    s->positive = 1;
    s->bounded_fits = 1;
    s->anisotropic = 0;
    s->q_transpose = -1;
    s->t_start = 0;
}

static int thread_id(void)
{
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

int sol_threads(void)
{
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Stage timer: CPU (all threads) and wall seconds since the last mark. */
typedef struct stage_clock {
    double cpu, wall;
} stage_clock;

static void stage_mark(stage_clock *c, sol_stats *st, int stage)
{
    double cpu = cpu_seconds(), wall = wall_seconds();
    if (st && stage >= 0) {
        st->stage_cpu[stage] += cpu - c->cpu;
        st->stage_wall[stage] += wall - c->wall;
    }
    c->cpu = cpu;
    c->wall = wall;
}

static const char *const STAGE_NAMES[SOL_NSTAGES] = {
    "boundary particles", "buoyancy balance, path kick", "interpolation error: MLS u^n faces",
    "predictor rows (Step 6)", "predictor solve (Step 6)", "move r* (Step 7)", "MLS u* faces/centroids (Step 8)", "PPE (Step 9)",
    "correct and move (Step 10)", "management (Step 11)", "continuity, Courant"};

const char *sol_stage_name(int stage)
{
    return stage >= 0 && stage < SOL_NSTAGES ? STAGE_NAMES[stage] : "?";
}

#define FREE(p) do { free(p); (p) = NULL; } while (0)

static void work_free(sol_work *w)
{
    void *arr[] = {w->px, w->py, w->ref, w->h, w->k, w->sref, w->c0, w->cx, w->cy, w->pv, w->gv[0], w->gv[1],
                   w->gv[2], w->ih, w->ik, w->ia, w->isrc};
    for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++)
        free(arr[i]);
    memset(w, 0, sizeof *w);
}

void sol_free(sol **pS)
{
    if (!pS || !*pS)
        return;
    sol *S = *pS;
    sol_setup *su = &S->su;
    sol_state *st = &S->st;
    part_free(&st->P);
    part_bins_free(&st->bins);
    part_bins_free(&st->bins_star);
    part_boundary_free(&st->bp);
    lsq_free(&su->g);
    lsq_free(&su->gw);
    ppe_free(&su->pe);
    lsolve_rows_free(&st->kry);
    for (int k = 0; su->timed && k < su->ntimed; k++) {
        free(su->timed[k].nrm);
        free(su->timed[k].val);
    }
    free(su->timed);
    void *arr[] = {su->u_kind, st->ub, st->vb, su->p_dir, su->p_total, su->p0, st->prgh_f, su->t_kind, su->tb, su->ghc, su->ghf, su->rinv, st->rbx, st->rby,
                   su->st_off, su->st_cell, su->st_sx, su->st_sy, su->ru_off, su->ru_q0, su->ru_q1,
                   su->ru_sx, su->ru_sy, su->st_bnd, su->of_off, su->of_face, su->fsx, su->fsy, st->p, st->pold, st->uc, st->vc, st->usc, st->vsc, st->flux, st->gflux, st->gx,
                   st->gy, st->div, st->pf, st->Tc, st->gtx, st->gty, st->x0, st->y0, st->us,
                   st->vs, st->rhs_u, st->rhs_v, st->Ts, st->rhs_T, st->cell0, st->keep, st->rp, st->ci,
                   st->av, st->avT, st->uneu, st->tneu, st->cnt_cell, st->pib, st->hxx, st->hxy, st->hyy, st->fluxb, st->pf0, st->gpx, st->gpy, st->wdamp, st->empty,
                   st->qa, st->qb, st->qc, st->qx, st->qy, st->pd, st->gq, st->tq_off, st->tq_len, st->tq,
                   st->fu, st->fv, st->fT, st->pout, st->fluxe, st->q, st->fz, st->pfprev, st->pfphi,
                   su->pd_off, su->pd_face, st->bpue, st->bpve, su->wall, su->wf_off, su->wf_face,
                   su->uc_keep, st->bpus, st->bpvs, st->xs, st->ys};
    for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++)
        free(arr[i]);
    if (S->work)
        for (int t = 0; t < S->nthreads; t++)
            work_free(&S->work[t]);
    free(S->work);
    free(S);
    *pS = NULL;
}

/* ---- per-thread work ----------------------------------------------------- */

/* Room for n gathered neighbours (amortised growth: a stencil grows only
 * when particles crowd into it, never per particle). */
static ump_status work_reserve(sol_work *w, size_t n, ump_err *err)
{
    if (n <= w->cap)
        return UMP_OK;
    size_t c = n + n / 2 + 64;
    double **d[] = {&w->px, &w->py, &w->h, &w->k, &w->c0, &w->cx, &w->cy, &w->pv, &w->gv[0], &w->gv[1],
                    &w->gv[2]};
    for (size_t i = 0; i < sizeof d / sizeof d[0]; i++) {
        double *q = ump_realloc_array(*d[i], c, sizeof(double));
        if (!q)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "neighbour list: out of memory (%zu)", c);
        *d[i] = q;
    }
    ump_idx **ix[] = {&w->ref, &w->sref};
    for (size_t i = 0; i < sizeof ix / sizeof ix[0]; i++) {
        ump_idx *q = ump_realloc_array(*ix[i], c, sizeof(ump_idx));
        if (!q)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "neighbour list: out of memory (%zu)", c);
        *ix[i] = q;
    }
    w->cap = c;
    return UMP_OK;
}

/* Record the first error of a thread inside a parallel stage. */
static void work_fail(sol_work *w, ump_status rc, const ump_err *e)
{
    if (w->rc == UMP_OK) {
        w->rc = rc;
        w->err = *e;
    }
}

/* After a parallel stage: the error of the lowest-numbered thread that
 * failed (deterministic message for a given thread count), counters
 * summed into st. */
static ump_status work_collect(sol *S, sol_stats *st, ump_err *err)
{
    ump_status rc = UMP_OK;
    for (int t = 0; t < S->nthreads; t++) {
        sol_work *w = &S->work[t];
        if (st) {
            st->lap_fallbacks += (int)w->lap_fallbacks;
            st->mls_fallbacks += (int)w->mls_fallbacks;
            st->positive_rows += (int)w->positive_rows;
            st->bounded_values += (int)w->bounded;
        }
        w->lap_fallbacks = w->mls_fallbacks = w->positive_rows = w->bounded = 0;
        if (w->rc != UMP_OK && rc == UMP_OK) {
            rc = w->rc;
            if (err)
                *err = w->err;
        }
        w->rc = UMP_OK;
    }
    return rc;
}

/* Gather the fluid and boundary particles of cell c's stencil (bins must be
 * current) into w->px, w->py, w->ref, run by run of the stencil (per run:
 * its fluid particles, then its boundary particles); returns the count.
 * gather_from: the fluid particles at (X, Y) in bins; gather_cell: the
 * particles and bins of the state. */
static inline __attribute__((always_inline)) ump_status gather_from(const sol_setup *su, const double *restrict X,
                                                                    const double *restrict Y, const part_bins *bins,
                                                                    const part_boundary *bp, sol_work *w, ump_idx c,
                                                                    size_t *n, ump_err *err)
{
    const double *restrict BX = bp->x, *restrict BY = bp->y;
    const ump_idx *boff = bins->off, *bpoff = bp->off, *bpidx = bp->idx;
    const size_t *bidx = bins->idx;
    size_t cnt = 0;
    ump_idx r0 = su->ru_off[c], r1 = su->ru_off[c + 1];
    size_t need = 0;
    for (ump_idx r = r0; r < r1; r++) {
        ump_idx q0 = su->ru_q0[r], q1 = su->ru_q1[r];
        need += (size_t)(boff[q1] - boff[q0]) + (size_t)(bpoff[q1] - bpoff[q0]);
    }
    if (need > w->cap)
        UMP_CALL(work_reserve(w, need, err));
    double *restrict px = w->px, *restrict py = w->py;
    ump_idx *restrict ref = w->ref;
    for (ump_idx r = r0; r < r1; r++) {
        ump_idx q0 = su->ru_q0[r], q1 = su->ru_q1[r];
        double sx = su->ru_sx ? su->ru_sx[r] : 0, sy = su->ru_sy ? su->ru_sy[r] : 0;
        /* the fluid particles of the run's cells, then their boundary
         * particles: each a contiguous range of the bins */
        for (ump_idx k = boff[q0]; k < boff[q1]; k++) {
            size_t j = bidx[k];
            px[cnt] = X[j] + sx;
            py[cnt] = Y[j] + sy;
            ref[cnt++] = (ump_idx)j;
        }
        for (ump_idx k = bpoff[q0]; k < bpoff[q1]; k++) {
            ump_idx j = bpidx[k];
            px[cnt] = BX[j] + sx;
            py[cnt] = BY[j] + sy;
            ref[cnt++] = -1 - j;
        }
    }
    *n = cnt;
    return UMP_OK;
}

static ump_status gather_cell(const sol_setup *su, const sol_state *st, sol_work *w, ump_idx c, size_t *n,
                              ump_err *err)
{
    return gather_from(su, st->P->x, st->P->y, &st->bins, &st->bp, w, c, n, err);
}

/* Offsets of the gathered samples from (x, y) into w->h, w->k, w->sref,
 * leaving out the boundary particle of face `skip_bface` (boundary index,
 * -1: none); returns the count. */
static int offsets(sol_work *w, size_t n, double x, double y, ump_idx skip_bface)
{
    /* refs are >= 0 (fluid) or -1 - b (boundary particle b); INT32_MIN is
     * no ref at all */
    ump_idx skip = skip_bface >= 0 ? -1 - skip_bface : INT32_MIN;
    const double *restrict px = w->px, *restrict py = w->py;
    const ump_idx *restrict ref = w->ref;
    double *restrict h = w->h, *restrict k = w->k;
    ump_idx *restrict sref = w->sref;
    if (n > MLS_MAX_SAMPLES)
        n = MLS_MAX_SAMPLES;
    int m = 0;
    for (size_t j = 0; j < n; j++) {
        ump_idx r = ref[j];
        h[m] = px[j] - x;
        k[m] = py[j] - y;
        sref[m] = r;
        m += r != skip; /* branch-free: a skipped sample is overwritten */
    }
    return m;
}

/* Offsets from fluid particle self at (x, y) of every gathered sample but
 * itself, into w->h, w->k (no sample cap: the Laplacian rows take all);
 * returns the count. */
static int offsets_but(sol_work *w, size_t n, ump_idx self, double x, double y)
{
    const double *restrict px = w->px, *restrict py = w->py;
    const ump_idx *restrict ref = w->ref;
    double *restrict h = w->h, *restrict k = w->k;
    int m = 0;
    for (size_t j = 0; j < n; j++) {
        h[m] = px[j] - x;
        k[m] = py[j] - y;
        m += ref[j] != self; /* branch-free: self is overwritten */
    }
    return m;
}

/* sum_j c_j value_j of a fluid quantity f and a boundary quantity g. */
static inline double apply(const double *restrict c, const ump_idx *restrict ref, int n,
                           const double *restrict f, const double *restrict g)
{
    double s = 0;
    for (int j = 0; j < n; j++) {
        ump_idx r = ref[j];
        s += c[j] * (r >= 0 ? f[r] : g[-1 - r]);
    }
    return s;
}

/* ---- boundary conditions -------------------------------------------------- */

/* The temperature a zero normal gradient gives on boundary face f:
 * T_P + grad T_P . d_t, d_t = (x_f - x_P) minus its normal part. */
static double zero_gradient_T(const sol_setup *su, const sol_state *st, ump_idx f)
{
    const mesh2d *m = su->m;
    ump_idx o = m->owner[f];
    double dx = m->fx[f] - m->cx[o], dy = m->fy[f] - m->cy[o];
    double dn = dx * m->nx[f] + dy * m->ny[f];
    dx -= dn * m->nx[f];
    dy -= dn * m->ny[f];
    return st->Tc[o] + st->gtx[o] * dx + st->gty[o] * dy;
}

/* The velocity of boundary face f (b = f - ninternal) from its condition,
 * the owner cell velocity (*u, *v on entry) and the last corrected flux
 * (see the choices at the top): the value of its boundary particle, and
 * the face value written. Inflow is flux < 0, as OpenFOAM's neg(phi). */
static void boundary_velocity(const sol_setup *su, const sol_state *st, ump_idx b, ump_idx f, double *u,
                              double *v)
{
    const mesh2d *m = su->m;
    double nx = m->nx[f], ny = m->ny[f], phi = st->flux[f];
    switch (su->u_kind[b]) {
    case BU_FIXED: /* fixedValue, noSlip, movingWallVelocity, uniformFixedValue,
                      flowRateInletVelocity */
        *u = st->ub[b];
        *v = st->vb[b];
        break;
    case BU_INLETOUTLET: /* inletValue in, zeroGradient out */
        if (phi < 0) {
            *u = st->ub[b];
            *v = st->vb[b];
        }
        break;
    case BU_OUTLETINLET: /* outletValue out (pos0(phi)), zeroGradient in */
        if (phi >= 0) {
            *u = st->ub[b];
            *v = st->vb[b];
        }
        break;
    case BU_PRESSUREINLETOUTLET: /* in: (n.u_P) n + tangential velocity; out: u_P */
        if (phi < 0) {
            double un = *u * nx + *v * ny;
            *u = un * nx + st->ub[b];
            *v = un * ny + st->vb[b];
        }
        break;
    case BU_SYMMETRY: { /* symmetryPlane, symmetry, slip: u_P without its normal part */
        double un = *u * nx + *v * ny;
        *u -= un * nx;
        *v -= un * ny;
        break;
    }
    default: /* zeroGradient, calculated */
        break;
    }
}

/* The velocity condition of boundary face f is a zero gradient this step:
 * zeroGradient (outlets), and inletOutlet, outletInlet and
 * pressureInletOutletVelocity on the side of the flux where they are. */
static int velocity_zero_gradient(const sol_setup *su, const sol_state *st, ump_idx b, ump_idx f)
{
    double phi = st->flux[f];
    switch (su->u_kind[b]) {
    case BU_OUTLET:
        return 1;
    case BU_INLETOUTLET:
    case BU_PRESSUREINLETOUTLET:
        return phi >= 0;
    case BU_OUTLETINLET:
        return phi < 0;
    default:
        return 0;
    }
}

/* Boundary particle values for this step (see the choices at the top), and
 * the totalPressure face values of this step's PPE. */
static void set_boundary_particles(const sol_setup *su, sol_state *st)
{
    const mesh2d *m = su->m;
    part_boundary *bp = &st->bp;
    /* the rows of Eqs. 14 and 37 take a zero-gradient boundary particle as
     * d/dn = 0 (CPM only; step6_rows) */
    int cpm = su->set.lap.model == LAP_CPM || su->set.lap.model == LAP_CPM4;
    st->nneu = st->ndiffer = 0;
    for (ump_idx b = 0; b < bp->n; b++) {
        ump_idx f = bp->face[b], o = m->owner[f];
        double u = st->uc[o], v = st->vc[o];
        boundary_velocity(su, st, b, f, &u, &v);
        bp->u[b] = u;
        bp->v[b] = v;
        st->uneu[b] = cpm && velocity_zero_gradient(su, st, b, f);
        if (su->p_total[b]) {
            /* totalPressureFvPatchScalarField::updateCoeffs, kinematic, psi
             * none: p0 - 0.5 (1 - pos0(phi)) |U_p|^2 */
            double pt = su->p0[b] - (st->flux[f] < 0 ? 0.5 * (u * u + v * v) : 0.0);
            if (su->set.buoyant)
                st->prgh_f[f] = pt; /* p_rgh: turned into pi below */
            else
                st->pf[f] = pt;
        }
    }
    if (!su->set.buoyant) {
        for (ump_idx b = 0; b < bp->n; b++)
            st->nneu += st->uneu[b];
        return;
    }
    lsq_gradient(su->g, st->Tc, st->gtx, st->gty);
    for (ump_idx b = 0; b < bp->n; b++) {
        ump_idx f = bp->face[b];
        double T = su->tb[b];
        st->tneu[b] = 0;
        if (su->t_kind[b] == BT_ZEROGRADIENT || (su->t_kind[b] == BT_INLETOUTLET && st->flux[f] >= 0)) {
            T = zero_gradient_T(su, st, f);
            st->tneu[b] = (unsigned char)cpm;
        }
        st->nneu += st->uneu[b] || st->tneu[b];
        st->ndiffer += st->uneu[b] != st->tneu[b];
        bp->T[b] = T;
        /* fixed p_rgh: pi = p_rgh - beta (T_f - TRef) gh_f (the buoyant p_rgh
         * relation of solver.h) */
        if (su->p_dir[f])
            st->pf[f] = st->prgh_f[f] - su->set.beta * (T - su->set.t_ref) * su->ghf[f];
    }
}

static ump_status read_bcs(sol_setup *su, sol_state *st, const fld_field *U, const fld_field *pf, ump_err *err)
{
    const mesh2d *m = su->m;
    const pmesh *pm = m->pm;
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pp = &pm->patch[p];
        const fld_patch *bu = &U->patch[p], *bpp = &pf->patch[p];
        for (ump_idx i = 0; i < pp->n; i++) {
            ump_idx f = m->pmface_to_face[pp->start + i];
            if (f < m->ninternal)
                continue; /* empty (f < 0) or cyclic: not a boundary in 2-D */
            ump_idx b = f - m->ninternal;
            const double *val = bu->value + 3 * (size_t)i;
            switch (bu->type) {
            case FLD_BC_FIXEDVALUE:
            case FLD_BC_NOSLIP:
            case FLD_BC_MOVINGWALLVELOCITY:
            case FLD_BC_UNIFORMFIXEDVALUE:     /* value: given, or at t_start (sol_create) */
            case FLD_BC_FLOWRATEINLETVELOCITY:
                su->u_kind[b] = BU_FIXED;
                st->ub[b] = val[m->ax[0]];
                st->vb[b] = val[m->ax[1]];
                break;
            case FLD_BC_ZEROGRADIENT:
                su->u_kind[b] = BU_OUTLET;
                break;
            case FLD_BC_CALCULATED: /* icoFoam stops on it too: a calculated patch cannot be solved for */
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "U: boundary condition 'calculated' on patch '%s' gives the solved velocity no "
                                "condition (OpenFOAM's icoFoam stops on it too); use fixedValue, noSlip, "
                                "zeroGradient, inletOutlet, ...", pp->name);
            case FLD_BC_INLETOUTLET:
            case FLD_BC_OUTLETINLET:
                su->u_kind[b] = bu->type == FLD_BC_INLETOUTLET ? BU_INLETOUTLET : BU_OUTLETINLET;
                st->ub[b] = bu->aux[3 * (size_t)i + (size_t)m->ax[0]]; /* inletValue / outletValue */
                st->vb[b] = bu->aux[3 * (size_t)i + (size_t)m->ax[1]];
                break;
            case FLD_BC_PRESSUREINLETOUTLETVELOCITY:
                /* refValue = tangentialVelocity - n (n . tangentialVelocity):
                 * its in-plane tangential part (zero when not given) */
                su->u_kind[b] = BU_PRESSUREINLETOUTLET;
                if (bu->aux) {
                    double tu = bu->aux[3 * (size_t)i + (size_t)m->ax[0]];
                    double tv = bu->aux[3 * (size_t)i + (size_t)m->ax[1]];
                    double tn = tu * m->nx[f] + tv * m->ny[f];
                    st->ub[b] = tu - tn * m->nx[f];
                    st->vb[b] = tv - tn * m->ny[f];
                }
                break;
            case FLD_BC_SYMMETRYPLANE:
            case FLD_BC_SYMMETRY:
            case FLD_BC_SLIP: /* slip: zero normal velocity, free tangential, as symmetry */
                su->u_kind[b] = BU_SYMMETRY;
                break;
            default:
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "U: boundary condition '%s' on patch '%s' is not supported for velocity",
                                fld_bc_name(bu->type), pp->name);
            }
            switch (bpp->type) {
            case FLD_BC_FIXEDVALUE:
            case FLD_BC_UNIFORMFIXEDVALUE: /* value: given, or at t_start (sol_create) */
            case FLD_BC_TOTALPRESSURE:     /* value: given, or p0; set each step */
                su->p_dir[f] = 1;
                st->pf[f] = bpp->value[i];
                if (st->prgh_f)
                    st->prgh_f[f] = bpp->value[i];
                if (bpp->type == FLD_BC_TOTALPRESSURE) {
                    su->p_total[b] = 1;
                    su->p0[b] = bpp->aux[i];
                }
                break;
            case FLD_BC_ZEROGRADIENT:
            case FLD_BC_FIXEDFLUXPRESSURE:
            case FLD_BC_SYMMETRYPLANE:
            case FLD_BC_SYMMETRY:
            case FLD_BC_SLIP: /* a scalar's slip is zeroGradient (basicSymmetry) */
                break;
            case FLD_BC_CALCULATED:
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "%s: boundary condition 'calculated' on patch '%s' gives the solved pressure no "
                                "condition (OpenFOAM's solvers stop on it too); use zeroGradient, fixedValue, "
                                "fixedFluxPressure, totalPressure, ...", st->prgh_f ? "p_rgh" : "p", pp->name);
            case FLD_BC_INLETOUTLET:
            case FLD_BC_OUTLETINLET:
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "p: boundary condition '%s' on patch '%s' is not supported for pressure: it switches "
                                "each face between a fixed value and zeroGradient with the flow direction, and "
                                "umppmFoam's pressure matrix is factorized once for a fixed set of fixed-pressure "
                                "faces; use fixedValue or totalPressure", fld_bc_name(bpp->type), pp->name);
            default:
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "p: boundary condition '%s' on patch '%s' is not supported for pressure",
                                fld_bc_name(bpp->type), pp->name);
            }
            if (su->p_dir[f] && su->u_kind[b] == BU_FIXED)
                return UMP_FAIL(err, UMP_ERR_INPUT,
                                "patch '%s': both U and p are fixed; fix one of them (inlet: fixedValue U "
                                "with zeroGradient p; outlet: zeroGradient/inletOutlet U with fixedValue p)",
                                pp->name);
        }
    }
    return UMP_OK;
}

/* Values at time t of the timed patches (all, or only those whose field
 * file gave no `value`) into the step's boundary values. Per face, serial:
 * a few operations per boundary face and step. */
static void timed_eval(sol *S, double t, const fld_field *U, const fld_field *pfld, int only_missing)
{
    sol_setup *su = &S->su;
    sol_state *st = &S->st;
    const mesh2d *m = su->m;
    const pmesh *pm = m->pm;
    for (int k = 0; k < su->ntimed; k++) {
        struct sol_timed *tp = &su->timed[k];
        const fld_patch *fp = tp->is_p ? &pfld->patch[tp->patch] : &U->patch[tp->patch];
        if (only_missing && fp->value_given)
            continue;
        fld_bc_eval(fp, tp->is_p ? 1 : 3, t, tp->nrm, tp->area, tp->val);
        const pmesh_patch *pp = &pm->patch[tp->patch];
        for (ump_idx i = 0; i < pp->n; i++) {
            ump_idx f = m->pmface_to_face[pp->start + i];
            if (f < m->ninternal)
                continue;
            if (tp->is_p) {
                if (st->prgh_f)
                    st->prgh_f[f] = tp->val[i]; /* p_rgh, turned into pi each step */
                else
                    st->pf[f] = tp->val[i];
            } else {
                st->ub[f - m->ninternal] = tp->val[3 * (size_t)i + (size_t)m->ax[0]];
                st->vb[f - m->ninternal] = tp->val[3 * (size_t)i + (size_t)m->ax[1]];
            }
        }
    }
}

/* The patches whose condition is a function of time (uniformFixedValue of
 * U or p, flowRateInletVelocity), with their normals and areas (mesh-only,
 * once); those without a `value` in the field file start at t_start (as
 * v1912 evaluates them when it reads them). */
static ump_status timed_build(sol *S, const fld_field *U, const fld_field *pfld, ump_err *err)
{
    sol_setup *su = &S->su;
    const mesh2d *m = su->m;
    const pmesh *pm = m->pm;
    for (int pass = 0; pass < 2; pass++) {
        int n = 0;
        for (int p = 0; p < pm->npatches; p++)
            for (int is_p = 0; is_p < 2; is_p++) {
                const fld_patch *fp = is_p ? &pfld->patch[p] : &U->patch[p];
                if (!fp->fn || (fp->type != FLD_BC_UNIFORMFIXEDVALUE && fp->type != FLD_BC_FLOWRATEINLETVELOCITY))
                    continue;
                if (pass == 1) {
                    struct sol_timed *tp = &su->timed[n];
                    const pmesh_patch *pp = &pm->patch[p];
                    tp->patch = p;
                    tp->is_p = is_p;
                    if (!(tp->nrm = ump_alloc_array(3 * (size_t)pp->n + 3, sizeof(double))) ||
                        !(tp->val = ump_alloc_array(3 * (size_t)pp->n + 3, sizeof(double))))
                        return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory");
                    tp->area = mesh_patch_area(m, p, tp->nrm); /* gSum(magSf), normals */
                    if (fp->type == FLD_BC_FLOWRATEINLETVELOCITY && !(tp->area > 0))
                        return UMP_FAIL(err, UMP_ERR_INPUT, "patch '%s': flowRateInletVelocity on a patch of "
                                        "zero area", pp->name);
                }
                n++;
            }
        if (pass == 0) {
            su->ntimed = n;
            if (n && !(su->timed = ump_alloc_array((size_t)n, sizeof *su->timed)))
                return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory");
        }
    }
    timed_eval(S, su->set.t_start, U, pfld, 1);
    S->U = U;
    S->pfld = pfld;
    return UMP_OK;
}

void sol_set_time(sol *S, double t)
{
    if (S->su.ntimed)
        timed_eval(S, t, S->U, S->pfld, 0);
}

/* Temperature boundary conditions (see the choices at the top). */
static ump_status read_t_bcs(sol_setup *su, const fld_field *T, ump_err *err)
{
    const mesh2d *m = su->m;
    const pmesh *pm = m->pm;
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pp = &pm->patch[p];
        const fld_patch *bt = &T->patch[p];
        for (ump_idx i = 0; i < pp->n; i++) {
            ump_idx f = m->pmface_to_face[pp->start + i];
            if (f < m->ninternal)
                continue;
            ump_idx b = f - m->ninternal;
            switch (bt->type) {
            case FLD_BC_FIXEDVALUE:
                su->t_kind[b] = BT_FIXED;
                su->tb[b] = bt->value[i];
                break;
            case FLD_BC_ZEROGRADIENT:
            case FLD_BC_SYMMETRYPLANE:
            case FLD_BC_SYMMETRY:
                su->t_kind[b] = BT_ZEROGRADIENT;
                break;
            case FLD_BC_INLETOUTLET:
                su->t_kind[b] = BT_INLETOUTLET;
                su->tb[b] = bt->aux[i];
                break;
            default:
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "T: boundary condition '%s' on patch '%s' is not supported for temperature "
                                "(fixedValue, zeroGradient, symmetry, symmetryPlane, inletOutlet)",
                                fld_bc_name(bt->type), pp->name);
            }
        }
    }
    return UMP_OK;
}

/* ---- mesh-only operators (Steps 1-4, once) -------------------------------- */

/* The particle stencil {c} u N2(c) of each cell, in increasing cell order
 * (N2 is sorted; c is inserted), with shifts. */
static ump_status stencil_build(sol_setup *su, ump_err *err)
{
    const mesh2d *m = su->m;
    ump_idx nc = m->ncells;
    size_t tot = (size_t)m->n2_off[nc] + (size_t)nc;
    UMP_CHECK(tot <= (size_t)UMP_IDX_MAX, err, UMP_ERR_INPUT,
              "solver: %zu particle stencil entries: more than the %d that 32-bit labels index", tot,
              UMP_IDX_MAX);
    if (!(su->st_off = ump_alloc_array((size_t)nc + 1, sizeof *su->st_off)) ||
        !(su->st_cell = ump_alloc_array(tot, sizeof *su->st_cell)))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory for the particle stencils");
    if (m->n2_sx && (!(su->st_sx = ump_alloc_array(tot, sizeof *su->st_sx)) ||
                     !(su->st_sy = ump_alloc_array(tot, sizeof *su->st_sy))))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory for the particle stencils");
    size_t k = 0;
    su->st_max = 0;
    for (ump_idx c = 0; c < nc; c++) {
        su->st_off[c] = (ump_idx)k;
        int placed = 0;
        for (ump_idx a = m->n2_off[c]; a <= m->n2_off[c + 1]; a++) {
            if (!placed && (a == m->n2_off[c + 1] || m->n2[a] > c)) {
                su->st_cell[k] = c;
                if (su->st_sx)
                    su->st_sx[k] = su->st_sy[k] = 0;
                k++;
                placed = 1;
            }
            if (a == m->n2_off[c + 1])
                break;
            su->st_cell[k] = m->n2[a];
            if (su->st_sx) {
                su->st_sx[k] = m->n2_sx[a];
                su->st_sy[k] = m->n2_sy[a];
            }
            k++;
        }
        su->st_max = UMP_MAX(su->st_max, (ump_idx)k - su->st_off[c]);
    }
    su->st_off[nc] = (ump_idx)k;
    /* runs: count -> prefix sum -> fill */
    if (!(su->ru_off = ump_alloc_array((size_t)nc + 1, sizeof *su->ru_off)))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory for the particle stencils");
    for (int pass = 0; pass < 2; pass++) {
        size_t nr = 0;
        for (ump_idx c = 0; c < nc; c++) {
            if (!pass)
                su->ru_off[c] = (ump_idx)nr;
            for (ump_idx a = su->st_off[c]; a < su->st_off[c + 1]; a++) {
                int joins = a > su->st_off[c] && su->st_cell[a] == su->st_cell[a - 1] + 1 &&
                            (!su->st_sx || (su->st_sx[a] == su->st_sx[a - 1] && su->st_sy[a] == su->st_sy[a - 1]));
                if (joins) {
                    if (pass)
                        su->ru_q1[nr - 1] = su->st_cell[a] + 1;
                    continue;
                }
                if (pass) {
                    su->ru_q0[nr] = su->st_cell[a];
                    su->ru_q1[nr] = su->st_cell[a] + 1;
                    if (su->ru_sx) {
                        su->ru_sx[nr] = su->st_sx[a];
                        su->ru_sy[nr] = su->st_sy[a];
                    }
                }
                nr++;
            }
        }
        if (!pass) {
            su->ru_off[nc] = (ump_idx)nr;
            if (!(su->ru_q0 = ump_alloc_array(nr + 1, sizeof *su->ru_q0)) ||
                !(su->ru_q1 = ump_alloc_array(nr + 1, sizeof *su->ru_q1)) ||
                (su->st_sx && (!(su->ru_sx = ump_alloc_array(nr + 1, sizeof *su->ru_sx)) ||
                               !(su->ru_sy = ump_alloc_array(nr + 1, sizeof *su->ru_sy)))))
                return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory for the particle stencils");
        }
    }
    return UMP_OK;
}

/* Faces whose u* is an MLS fit, grouped by owner, so that one gather per
 * cell serves its centroid and its faces. */
static ump_status owned_faces_build(sol_setup *su, ump_err *err)
{
    const mesh2d *m = su->m;
    ump_idx nc = m->ncells, nf = m->nfaces;
    if (!(su->of_off = ump_alloc_array((size_t)nc + 1, sizeof *su->of_off)) ||
        !(su->of_face = ump_alloc_array((size_t)nf + 1, sizeof *su->of_face)))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory for the face lists");
    /* count -> prefix sum -> fill */
    for (ump_idx f = 0; f < nf; f++) {
        int fitted = f < m->ninternal || (su->u_kind[f - m->ninternal] != BU_FIXED &&
                                          su->u_kind[f - m->ninternal] != BU_SYMMETRY);
        if (fitted)
            su->of_off[m->owner[f] + 1]++;
    }
    for (ump_idx c = 0; c < nc; c++)
        su->of_off[c + 1] += su->of_off[c];
    ump_idx *fill = ump_alloc_array((size_t)nc, sizeof *fill);
    if (!fill)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory for the face lists");
    for (ump_idx f = 0; f < nf; f++) {
        int fitted = f < m->ninternal || (su->u_kind[f - m->ninternal] != BU_FIXED &&
                                          su->u_kind[f - m->ninternal] != BU_SYMMETRY);
        if (fitted) {
            ump_idx o = m->owner[f];
            su->of_face[su->of_off[o] + fill[o]++] = f;
        }
    }
    free(fill);
    return UMP_OK;
}

/* The scales of Step 8's MLS fit at every face, for mls_weights (negative:
 * a fixed support, as mls_extent), once: the mean extents of the face's
 * two cells (the owner's at a boundary face; [NSH16] below Eq. 35) times
 * faceSupport, SOL_FACE_SUPPORT_TRI at a face beside a triangle by default
 * (docs/METHOD.md section 8, "Face fits on triangles"). On coarse
 * triangles the 2 extents of mlsSupport left the Re 1000 cavity's floor
 * and right wall layers too slow (944 cells: u at y = 0.055 -0.025 against
 * Ghia's -0.181, icoFoam -0.085) and its corner eddies too large; 3
 * extents for these fits alone gave -0.073 (README, "Face fits on
 * triangles"); on the 40^2 quadrilaterals 3 took v from 0.0110 to 0.0374
 * from Ghia. The interpolation error's transpose (transpose_q) uses the
 * same scales, as it must. */
static ump_status face_scales_build(sol_setup *su, ump_err *err)
{
    const mesh2d *m = su->m;
    ump_idx nf = m->nfaces;
    if (!(su->fsx = ump_alloc_array((size_t)nf + 1, sizeof *su->fsx)) ||
        !(su->fsy = ump_alloc_array((size_t)nf + 1, sizeof *su->fsy)))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory for the face fits' scales");
    for (ump_idx f = 0; f < nf; f++) {
        ump_idx c = m->owner[f];
        double mdx = m->dx[c], mdy = m->dy[c];
        int tri = m->cell_off[c + 1] - m->cell_off[c] == 3;
        if (f < m->ninternal) {
            ump_idx nb = m->neigh[f];
            mdx = 0.5 * (mdx + m->dx[nb]);
            mdy = 0.5 * (mdy + m->dy[nb]);
            tri |= m->cell_off[nb + 1] - m->cell_off[nb] == 3;
        }
        double sf = tri ? su->set.face_support_tri : su->set.face_support;
        su->fsx[f] = sf > 0 ? -sf * mdx : mdx;
        su->fsy[f] = sf > 0 ? -sf * mdy : mdy;
    }
    return UMP_OK;
}

/* ---- per-particle arrays ------------------------------------------------- */

static ump_status grow_particle_work(sol_state *st, size_t n, ump_err *err)
{
    if (n <= st->wcap)
        return UMP_OK;
    size_t c = n > 2 * st->wcap ? n : 2 * st->wcap;
    double **arr[] = {&st->x0, &st->y0, &st->us, &st->vs, &st->rhs_u, &st->rhs_v, &st->Ts, &st->rhs_T,
                      &st->gpx, &st->gpy, &st->wdamp, &st->qa, &st->qb, &st->qc, &st->qx, &st->qy,
                      &st->xs, &st->ys};
    for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++) {
        double *q = ump_realloc_array(*arr[i], c, sizeof(double));
        if (!q)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory (%zu)", c);
        *arr[i] = q;
    }
    ump_idx *cl = ump_realloc_array(st->cell0, c, sizeof *cl);
    if (!cl)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory (%zu)", c);
    st->cell0 = cl;
    unsigned char *kp = ump_realloc_array(st->keep, c, 1);
    if (!kp)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory (%zu)", c);
    st->keep = kp;
    ump_idx *rp = ump_realloc_array(st->rp, c + 1, sizeof *rp);
    if (!rp)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory (%zu)", c);
    st->rp = rp;
    st->wcap = c;
    return UMP_OK;
}

/* ---- creation -------------------------------------------------------------- */

/* Steps 1-4 beside the PPE: the particle stencils, the boundary particles
 * and the particles seeded at the centroids, sorted by cell. */
static ump_status particles_build(sol_setup *su, sol_state *st, ump_err *err)
{
    const mesh2d *m = su->m;
    UMP_CALL(stencil_build(su, err));
    UMP_CALL(owned_faces_build(su, err));
    UMP_CALL(face_scales_build(su, err));
    UMP_CALL(part_boundary_create(&st->bp, m, err));
    su->st_bnd = ump_alloc_array((size_t)m->ncells, sizeof *su->st_bnd);
    UMP_CHECK(su->st_bnd, err, UMP_ERR_NOMEM, "particle stencils: out of memory (%ld cells)", (long)m->ncells);
    for (ump_idx c = 0; c < m->ncells; c++) {
        su->st_bnd[c] = 0;
        for (ump_idx r = su->ru_off[c]; r < su->ru_off[c + 1]; r++)
            su->st_bnd[c] |= st->bp.off[su->ru_q1[r]] > st->bp.off[su->ru_q0[r]];
    }
    UMP_CALL(part_create((size_t)m->ncells * 2, &st->P, err));
    UMP_CALL(part_seed_centroids(st->P, m, st->uc, st->vc, st->Tc, err));
    UMP_CALL(part_sort_by_cell(st->P, &st->bins, m, err));
    return grow_particle_work(st, st->P->n, err);
}

/* Per cell, its boundary faces f with mask[f - ninternal] set (CSR, count
 * -> prefix sum -> fill, in the cell's face order), and the most of them
 * one particle stencil holds (the work arrays' size). */
static ump_status boundary_face_lists(sol_setup *su, const unsigned char *mask, ump_idx **off, ump_idx **face,
                                      ump_idx *max, const char *what, ump_err *err)
{
    const mesh2d *m = su->m;
    ump_idx nc = m->ncells, ni = m->ninternal;
    if (!(*off = ump_alloc_array((size_t)nc + 1, sizeof **off)))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory for the %s", what);
    for (int pass = 0; pass < 2; pass++) {
        ump_idx k = 0;
        for (ump_idx c = 0; c < nc; c++) {
            (*off)[c] = k;
            for (ump_idx a = m->cell_face_off[c]; a < m->cell_face_off[c + 1]; a++) {
                ump_idx f = m->cell_faces[a];
                if (f >= ni && mask[f - ni]) {
                    if (pass)
                        (*face)[k] = f;
                    k++;
                }
            }
        }
        (*off)[nc] = k;
        if (!pass && !(*face = ump_alloc_array((size_t)k + 1, sizeof **face)))
            return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory for the %s", what);
    }
    *max = 0;
    for (ump_idx c = 0; c < nc; c++) {
        ump_idx t = 0;
        for (ump_idx a = su->st_off[c]; a < su->st_off[c + 1]; a++)
            t += (*off)[su->st_cell[a] + 1] - (*off)[su->st_cell[a]];
        *max = UMP_MAX(*max, t);
    }
    return UMP_OK;
}

/* Per cell, its fixed-pressure boundary faces. */
static ump_status dirichlet_faces_build(sol_setup *su, ump_err *err)
{
    return boundary_face_lists(su, su->p_dir + su->m->ninternal, &su->pd_off, &su->pd_face, &su->pd_max,
                               "fixed-pressure faces", err);
}

/* anisotropicCells: the walls of the pressure correction (docs/METHOD.md
 * section 8, "Walls in the correction"): faces of `wall` patches with a
 * prescribed velocity, symmetry planes and slip walls, whose pressure is
 * not fixed: there the PPE (Eq. 25) holds the normal gradient of p at zero
 * and so does the flow. Not inlets (a prescribed velocity on a `patch`):
 * the PPE's condition is the same there, but the flow's pressure keeps its
 * gradient through them (a channel's pressure drop). Flagged, listed per
 * cell (count -> prefix sum -> fill), and Eq. 26 with them for the mesh
 * velocity of Eq. 36 (su->gw). */
static ump_status wall_faces_build(sol_setup *su, ump_err *err)
{
    const mesh2d *m = su->m;
    ump_idx ni = m->ninternal, nb = m->nfaces - ni;
    if (!(su->wall = ump_alloc_array((size_t)nb + 1, 1)))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory for the wall faces");
    for (ump_idx b = 0; b < nb; b++) {
        int pp = m->face_patch[ni + b];
        int wall_patch = m->pm && pp >= 0 && m->pm->patch[pp].kind == PMESH_WALL;
        su->wall[b] = !su->p_dir[ni + b] &&
                      (su->u_kind[b] == BU_SYMMETRY || (su->u_kind[b] == BU_FIXED && wall_patch));
    }
    ump_status rc = boundary_face_lists(su, su->wall, &su->wf_off, &su->wf_face, &su->wf_max, "wall faces", err);
    if (rc != UMP_OK)
        return rc;
    return lsq_build_walls(m, 1, su->wall, &su->gw, err);
}

ump_status sol_create(const mesh2d *m, const sol_settings *s, const fld_field *U, const fld_field *pfld,
                      const fld_field *T, sol **out, ump_err *err)
{
    *out = NULL;
    sol *S = ump_alloc_array(1, sizeof *S);
    if (!S)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory");
    sol_setup *su = &S->su;
    sol_state *st = &S->st;
    su->m = m;
    su->set = *s;
    su->set.q_transpose = sol_q_transpose(s);
    S->nthreads = sol_threads();
    st->want_fields = 1;
    st->uc_all = 1; /* u_P from the U field read */
    ump_idx nc = m->ncells, nf = m->nfaces, nb = nf - m->ninternal;
    ump_status rc;
    if (!(S->work = ump_alloc_array((size_t)S->nthreads, sizeof *S->work)))
        goto nomem;
    double **cellarr[] = {&st->p, &st->pold, &st->uc, &st->vc, &st->usc, &st->vsc, &st->gx, &st->gy, &st->div,
                          &st->fu, &st->fv, &st->fT, &st->pout, &st->q, &st->pd};
    for (size_t i = 0; i < sizeof cellarr / sizeof cellarr[0]; i++)
        if (!(*cellarr[i] = ump_alloc_array((size_t)nc, sizeof(double))))
            goto nomem;
    if (!(st->cnt_cell = ump_alloc_array((size_t)nc, sizeof(ump_idx))) ||
        !(st->empty = ump_alloc_array((size_t)nc, sizeof(ump_idx))) ||
        !(st->flux = ump_alloc_array((size_t)nf, sizeof(double))) ||
        !(st->gflux = ump_alloc_array((size_t)nf, sizeof(double))) ||
        !(st->fluxe = ump_alloc_array((size_t)nf, sizeof(double))) ||
        !(st->fz = ump_alloc_array((size_t)nf, sizeof(double))) ||
        !(st->gq = ump_alloc_array((size_t)nf, sizeof(double))) ||
        !(st->tq_off = ump_alloc_array((size_t)nc + 1, sizeof(size_t))) ||
        !(st->tq_len = ump_alloc_array((size_t)nc, sizeof(ump_idx))) ||
        !(st->pf = ump_alloc_array((size_t)nf, sizeof(double))) ||
        !(su->p_dir = ump_alloc_array((size_t)nf, 1)) || !(su->u_kind = ump_alloc_array((size_t)nb, 1)) ||
        !(su->p_total = ump_alloc_array((size_t)nb, 1)) || !(su->p0 = ump_alloc_array((size_t)nb, sizeof(double))) ||
        !(st->ub = ump_alloc_array((size_t)nb, sizeof(double))) ||
        !(st->bpue = ump_alloc_array((size_t)nb, sizeof(double))) ||
        !(st->bpve = ump_alloc_array((size_t)nb, sizeof(double))) ||
        !(st->vb = ump_alloc_array((size_t)nb, sizeof(double))))
        goto nomem;
    if (!(st->uneu = ump_alloc_array((size_t)nb > 0 ? (size_t)nb : 1, 1)) ||
        !(su->uc_keep = ump_alloc_array((size_t)nc, 1)) || !(st->bpus = ump_alloc_array((size_t)nb, sizeof(double))) ||
        !(st->bpvs = ump_alloc_array((size_t)nb, sizeof(double))))
        goto nomem;
    for (ump_idx f = m->ninternal; f < nf; f++)
        su->uc_keep[m->owner[f]] = 1;
    if (s->buoyant) {
        if (!T) {
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "solver: a buoyant case needs the temperature field T");
            goto fail;
        }
        double **carr[] = {&st->Tc, &st->gtx, &st->gty, &su->ghc, &st->pib, &st->hxx, &st->hxy, &st->hyy,
                           &st->rbx, &st->rby};
        for (size_t i = 0; i < sizeof carr / sizeof carr[0]; i++)
            if (!(*carr[i] = ump_alloc_array((size_t)nc, sizeof(double))))
                goto nomem;
        if (!(su->ghf = ump_alloc_array((size_t)nf, sizeof(double))) ||
            !(st->prgh_f = ump_alloc_array((size_t)nf, sizeof(double))) ||
            !(st->fluxb = ump_alloc_array((size_t)nf, sizeof(double))) ||
            !(st->pf0 = ump_alloc_array((size_t)nf, sizeof(double))) ||
            !(su->t_kind = ump_alloc_array((size_t)nb, 1)) || !(st->tneu = ump_alloc_array((size_t)nb, 1)) ||
            !(su->tb = ump_alloc_array((size_t)nb, sizeof(double))) ||
            !(su->rinv = ump_alloc_array(3 * (size_t)nc, sizeof(double))))
            goto nomem;
        /* the reconstruction of a cell vector from its face fluxes
         * (OpenFOAM's fvc::reconstruct): v = (sum_f n n^T |A_f|)^-1
         * sum_f n (v . n |A_f|), exact for a uniform v; mesh-only */
        for (ump_idx c = 0; c < nc; c++) {
            double axx = 0, axy = 0, ayy = 0;
            for (ump_idx k = m->cell_face_off[c]; k < m->cell_face_off[c + 1]; k++) {
                ump_idx f = m->cell_faces[k];
                axx += m->nx[f] * m->nx[f] * m->len[f];
                axy += m->nx[f] * m->ny[f] * m->len[f];
                ayy += m->ny[f] * m->ny[f] * m->len[f];
            }
            double det = axx * ayy - axy * axy;
            su->rinv[3 * (size_t)c] = ayy / det;
            su->rinv[3 * (size_t)c + 1] = -axy / det;
            su->rinv[3 * (size_t)c + 2] = axx / det;
        }
        /* gh = g . x - ghRef with the 3-D cell and face centres (gh.H) */
        double X[3];
        for (ump_idx c = 0; c < nc; c++) {
            mesh_to3d(m, m->cx[c], m->cy[c], X);
            su->ghc[c] = s->g[0] * X[0] + s->g[1] * X[1] + s->g[2] * X[2] - s->gh_ref;
            st->Tc[c] = T->internal[c];
        }
        for (ump_idx f = 0; f < nf; f++) {
            mesh_to3d(m, m->fx[f], m->fy[f], X);
            su->ghf[f] = s->g[0] * X[0] + s->g[1] * X[1] + s->g[2] * X[2] - s->gh_ref;
        }
        if ((rc = read_t_bcs(su, T, err)) != UMP_OK)
            goto fail;
    }
    for (ump_idx c = 0; c < nc; c++) {
        st->uc[c] = U->internal[3 * (size_t)c + (size_t)m->ax[0]];
        st->vc[c] = U->internal[3 * (size_t)c + (size_t)m->ax[1]];
        st->p[c] = pfld->internal[c];
    }
    if ((rc = read_bcs(su, st, U, pfld, err)) != UMP_OK || (rc = timed_build(S, U, pfld, err)) != UMP_OK)
        goto fail;
    su->need_ref = 1;
    for (ump_idx f = 0; f < nf; f++)
        su->need_ref &= !su->p_dir[f];
    /* No face fixes the pressure, yet fluid may cross a face whose velocity
     * is not fixed: icoFoam balances the flux by scaling the outflow there
     * (adjustPhi). umppmFoam cannot do that well: its open faces' fluxes
     * are MLS fits of the particles, and forcing them to the inflow (or
     * leaving the imbalance to the reference cell) gave a channel with a
     * zeroGradient outlet U 0.63 (0.98) from icoFoam's (README, "What is
     * refused"). Refused by name instead. */
    for (ump_idx b = 0; su->need_ref && b < nb; b++) {
        int k = su->u_kind[b];
        if (k == BU_OUTLET || k == BU_INLETOUTLET || k == BU_OUTLETINLET || k == BU_PRESSUREINLETOUTLET) {
            int pp = m->face_patch[m->ninternal + b];
            rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                          "patch '%s': fluid may cross it (its velocity is not fixed), but no patch fixes the "
                          "pressure; umppmFoam cannot then balance the flux through it (icoFoam scales the "
                          "outflow, adjustPhi; here that gave a channel with a zeroGradient outlet 0.6 from "
                          "icoFoam's U): fix the pressure where the fluid leaves (p fixedValue)",
                          pp >= 0 ? m->pm->patch[pp].name : "?");
            goto fail;
        }
    }
    if (s->p_theta > 0 && (!(st->pfprev = ump_alloc_array((size_t)nf, sizeof(double))) ||
                           !(st->pfphi = ump_alloc_array((size_t)nf, sizeof(double)))))
        goto nomem;
    if (s->p_theta > 0)
        memcpy(st->pfprev, s->buoyant && s->balanced ? st->pf0 : st->pf, (size_t)nf * sizeof *st->pf);
    if (s->buoyant) /* the initial p_rgh as pi (solver.h) */
        for (ump_idx c = 0; c < nc; c++)
            st->p[c] -= s->beta * (st->Tc[c] - s->t_ref) * su->ghc[c];
    /* Steps 1-4: mesh-only work, once */
    /* the quadratic fluxes only where balance_buoyancy uses them */
    ppe_opts po = {s->ppe_solver, s->p_ref_cell, s->p_ref_value, s->buoyant && s->balanced};
    if (s->p_ref_cell < 0 || s->p_ref_cell >= nc) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "system/fvSolution: pRefCell %ld is not a cell (0..%ld)",
                      (long)s->p_ref_cell, (long)nc - 1);
        goto fail;
    }
    if ((rc = lsq_build_weighted(m, s->anisotropic, &su->g, err)) != UMP_OK)
        goto fail;
    /* The PPE factorization (serial, the largest part of the set-up) beside
     * the particle stencils and the seeding, which do not need it; a
     * failure is reported as the serial order would (the PPE's first).
     * One thread: no OpenMP region at all -- inside an inactive one (a
     * false if clause) the supernodal factorization of the 320^2 cavity
     * took 3.4 s instead of 1.2 s (measured; the cause is in the BLAS). */
    ump_status rp = UMP_OK, rs = UMP_OK;
    ump_err ep, es;
    if (sol_threads() > 1) {
#pragma omp parallel sections num_threads(2)
        {
#pragma omp section
            rp = ppe_create(m, su->g, su->p_dir, &po, &su->pe, &ep);
#pragma omp section
            rs = particles_build(su, st, &es);
        }
    } else if ((rp = ppe_create(m, su->g, su->p_dir, &po, &su->pe, &ep)) == UMP_OK) {
        rs = particles_build(su, st, &es);
    }
    if (rp != UMP_OK || rs != UMP_OK) {
        rc = rp != UMP_OK ? rp : rs;
        if (err)
            *err = rp != UMP_OK ? ep : es;
        goto fail;
    }
    if ((rc = lsolve_rows_create(&st->kry, err)) != UMP_OK)
        goto fail;
    if ((rc = dirichlet_faces_build(su, err)) != UMP_OK)
        goto fail;
    if (s->anisotropic && (rc = wall_faces_build(su, err)) != UMP_OK)
        goto fail;
    for (int t = 0; t < S->nthreads; t++) {
        size_t room = 4 * (size_t)su->st_max + (size_t)su->pd_max + (size_t)su->wf_max + 64;
        if ((rc = work_reserve(&S->work[t], room, err)) != UMP_OK)
            goto fail;
        S->work[t].fit_margin = s->bounded_fits ? SOL_FIT_MARGIN : -1;
    }
    /* face fluxes of the initial cell velocities (linear interpolation), as
     * icoFoam's createPhi: the first Courant number and inletOutlet need them */
    for (ump_idx f = 0; f < m->nfaces; f++) {
        ump_idx o = m->owner[f];
        double u = st->uc[o], v = st->vc[o];
        if (f < m->ninternal) {
            u = 0.5 * (u + st->uc[m->neigh[f]]);
            v = 0.5 * (v + st->vc[m->neigh[f]]);
        } else if (su->u_kind[f - m->ninternal] == BU_FIXED) {
            u = st->ub[f - m->ninternal];
            v = st->vb[f - m->ninternal];
        } else if (su->u_kind[f - m->ninternal] == BU_SYMMETRY) {
            u = v = 0;
        }
        st->flux[f] = (u * m->nx[f] + v * m->ny[f]) * m->len[f];
    }
    set_boundary_particles(su, st);
    *out = S;
    return UMP_OK;
nomem:
    rc = UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory");
fail:
    sol_free(&S);
    return rc;
}

ump_status sol_set_particles(sol *S, size_t n, const double *x, const double *y, const double *u,
                             const double *v, const double *T, const int64_t *id, const ump_idx *hint,
                             size_t *dropped, ump_err *err)
{
    sol_state *st = &S->st;
    part_set *P = st->P;
    const mesh2d *m = S->su.m;
    P->n = 0;
    *dropped = 0;
    UMP_CALL(part_reserve(P, n, err));
    int64_t maxid = -1;
    for (size_t i = 0; i < n; i++) {
        double px = x[i], py = y[i];
        ump_idx cell, face;
        ump_idx start = hint && hint[i] >= 0 && hint[i] < m->ncells ? hint[i] : 0;
        if (part_locate(m, start, &px, &py, &cell, &face) != PART_INSIDE) {
            (*dropped)++;
            continue;
        }
        size_t idx;
        double Ti = T ? T[i] : st->Tc ? st->Tc[cell] : 0.0;
        UMP_CALL(part_add(P, px, py, u[i], v[i], Ti, cell, &idx, err));
        if (id) {
            P->id[idx] = id[i];
            if (id[i] > maxid)
                maxid = id[i];
        }
    }
    if (id && maxid + 1 > P->next_id)
        P->next_id = maxid + 1;
    UMP_CALL(part_sort_by_cell(P, &st->bins, m, err));
    return grow_particle_work(st, P->n, err);
}

void sol_set_pressure(sol *S, const double *p)
{
    memcpy(S->st.p, p, (size_t)S->su.m->ncells * sizeof *S->st.p);
    memcpy(S->st.pout, p, (size_t)S->su.m->ncells * sizeof *S->st.pout);
}

void sol_want_fields(sol *S, int yes) { S->st.want_fields = yes != 0; }

/* The mean cell extent e passed to the MLS fits as Eq. 35's Delta-bar, or,
 * with mlsSupport r > 0, the fixed support r e (passed negative, mls.h):
 * Eq. 35's x_m = max_j |dx_j| + Delta-bar jumps when a particle enters or
 * leaves the stencil, a fixed support does not (docs/METHOD.md section 8,
 * "MLS support"). */
static inline double mls_extent(const sol_setup *su, double e)
{
    return su->set.mls_support > 0 ? -su->set.mls_support * e : e;
}

/* The MLS value fit (Eq. 32) at (x, y) in cell c of the cell vectors
 * (vx, vy) [ncells] over the centroids of c's stencil into *ox, *oy
 * (scratch w->h, k, pv, cy, c0); with walls != 0 also a sample at each
 * wall face of the stencil's cells (su->wf_face): the owner's vector less
 * its normal component, the zero normal gradient the PPE holds there
 * (particle_pressure_gradient). Returns 1 if the fit fell back from the
 * quadratic basis. */
static int cell_vector_at(const sol_setup *su, sol_work *w, ump_idx c, double x, double y, const double *vx,
                          const double *vy, int walls, double *ox, double *oy)
{
    const mesh2d *m = su->m;
    int nn = 0;
    for (ump_idx a = su->st_off[c]; a < su->st_off[c + 1]; a++) {
        ump_idx q = su->st_cell[a];
        double sx = su->st_sx ? su->st_sx[a] : 0, sy = su->st_sy ? su->st_sy[a] : 0;
        w->h[nn] = m->cx[q] + sx - x;
        w->k[nn] = m->cy[q] + sy - y;
        w->pv[nn] = vx[q];
        w->cy[nn++] = vy[q];
        for (ump_idx d = walls ? su->wf_off[q] : 0; walls && d < su->wf_off[q + 1]; d++) {
            ump_idx f = su->wf_face[d];
            double vn = vx[q] * m->nx[f] + vy[q] * m->ny[f];
            w->h[nn] = m->fx[f] + sx - x;
            w->k[nn] = m->fy[f] + sy - y;
            w->pv[nn] = vx[q] - vn * m->nx[f]; /* n . grad p = 0 (Eq. 25) */
            w->cy[nn++] = vy[q] - vn * m->ny[f];
        }
    }
    double ex = mls_extent(su, m->dx[c]), ey = mls_extent(su, m->dy[c]);
    int fb = mls_weights(w->h, w->k, nn, ex, ey, w->c0, NULL, NULL, NULL) != MLS_QUADRATIC;
    double gx = 0, gy = 0;
    for (int j = 0; j < nn; j++) {
        gx += w->c0[j] * w->pv[j];
        gy += w->c0[j] * w->cy[j];
    }
    *ox = gx;
    *oy = gy;
    return fb;
}

/* grad p at every particle at its position (Eq. 10's gradient): the MLS
 * derivative (Eqs. 33-34) of the centroid pressures p of the particle's
 * cell and its N2 stencil, and of the prescribed pressures pfv at the
 * fixed-pressure boundary faces of those cells (docs/METHOD.md section 8,
 * "Fixed pressures in the particles' gradient"): the PPE's face gradient
 * at such a face is (p_f - p_A')/|A'f|, and a gradient from the centroids
 * alone extrapolates past the face and misses it, so the particles next
 * to an outlet were corrected by another pressure than the mesh.
 * anisotropicCells (docs/METHOD.md section 8, "Anisotropic cells"): the
 * MLS value (Eq. 32) at the particle of the cell gradients of Eq. 26 with
 * OpenFOAM's leastSquares weights 1/|d|^2 (the gradient of Eq. 36) over
 * the same stencil, without the face pressures (Eq. 26 is over the
 * centroids). On a stencil stretched 1000:1 the MLS derivative takes the
 * curvature of p across the thin direction into the derivative along it
 * (of order h_y^2/h_x): on the graded cavities |grad p| of 10^3 where p is
 * uniform along the row, and the particles next to the wall left at 5 m/s;
 * a value fit of weighted gradients does not divide by the short offsets.
 * With walls != 0 the fit also takes a sample at each wall face of the
 * stencil's cells (su->wf_face): the owner's gradient less its normal
 * component, the zero normal gradient the PPE holds there (docs/METHOD.md
 * section 8, "Walls in the correction"), so a particle at a wall is not
 * corrected through it or away from it; only for a p whose normal gradient
 * at walls is zero in the flow too (walls_zero_gradient). Its scratch is
 * st->gx, st->gy. Returns the count of fits that fell back from the
 * quadratic basis. */
static long particle_pressure_gradient(sol *S, const double *p, const double *pfv, double *gxo, double *gyo,
                                       int walls)
{
    const sol_setup *su = &S->su;
    const mesh2d *m = su->m;
    const part_set *P = S->st.P;
    size_t n = P->n;
    long fb = 0;
    int aniso = su->set.anisotropic;
    double *cgx = S->st.gx, *cgy = S->st.gy;
    if (aniso)
        lsq_gradient(su->g, p, cgx, cgy);
    /* pd: some stencil holds a fixed-pressure face; else the samples are
     * the centroids alone, in a loop without the face loop or the shift's
     * test (a quarter of a fit's cost with them) */
    int pd = su->pd_max > 0;
    const double *restrict cx = m->cx, *restrict cy = m->cy;
#pragma omp parallel num_threads(S->nthreads) reduction(+ : fb)
    {
        sol_work *w = &S->work[thread_id()];
#pragma omp for schedule(static)
        for (size_t i = 0; i < n; i++) {
            ump_idx c = P->cell[i];
            double x = P->x[i], y = P->y[i];
            if (aniso) { /* the MLS value of the cell gradients */
                fb += cell_vector_at(su, w, c, x, y, cgx, cgy, walls, &gxo[i], &gyo[i]);
                continue;
            }
            /* samples: (h, k) offsets, pv the pressures */
            int nn = 0;
            ump_idx a0 = su->st_off[c], a1 = su->st_off[c + 1];
            if (pd) {
                for (ump_idx a = a0; a < a1; a++) {
                    ump_idx q = su->st_cell[a];
                    double sx = su->st_sx ? su->st_sx[a] : 0, sy = su->st_sy ? su->st_sy[a] : 0;
                    w->h[nn] = m->cx[q] + sx - x;
                    w->k[nn] = m->cy[q] + sy - y;
                    w->pv[nn++] = p[q];
                    for (ump_idx d = su->pd_off[q]; d < su->pd_off[q + 1]; d++) {
                        ump_idx f = su->pd_face[d];
                        w->h[nn] = m->fx[f] + sx - x;
                        w->k[nn] = m->fy[f] + sy - y;
                        w->pv[nn++] = pfv[f];
                    }
                }
            } else { /* the centroids alone, the same offsets (no shift: + 0) */
                const ump_idx *restrict sc = su->st_cell + a0;
                const double *restrict ssx = su->st_sx ? su->st_sx + a0 : NULL;
                const double *restrict ssy = su->st_sy ? su->st_sy + a0 : NULL;
                double *restrict h = w->h, *restrict k = w->k, *restrict pv = w->pv;
                nn = (int)(a1 - a0);
                if (ssx)
                    for (int j = 0; j < nn; j++) {
                        h[j] = cx[sc[j]] + ssx[j] - x;
                        k[j] = cy[sc[j]] + ssy[j] - y;
                        pv[j] = p[sc[j]];
                    }
                else
                    for (int j = 0; j < nn; j++) {
                        h[j] = cx[sc[j]] - x;
                        k[j] = cy[sc[j]] - y;
                        pv[j] = p[sc[j]];
                    }
            }
            double ex = mls_extent(su, m->dx[c]), ey = mls_extent(su, m->dy[c]);
            if (mls_gradient(w->h, w->k, w->pv, nn, ex, ey, &gxo[i], &gyo[i], NULL) != MLS_QUADRATIC)
                fb++;
        }
    }
    return fb;
}

/* scale times cell_vector_at (no wall samples) at every particle of the
 * cell vectors (vx, vy) [ncells] into ox, oy [particles]. Returns the
 * count of fits that fell back from the quadratic basis. */
static long particle_cell_vector(sol *S, const double *vx, const double *vy, double *ox, double *oy, double scale)
{
    const sol_setup *su = &S->su;
    const part_set *P = S->st.P;
    size_t n = P->n;
    long fb = 0;
#pragma omp parallel num_threads(S->nthreads) reduction(+ : fb)
    {
        sol_work *w = &S->work[thread_id()];
#pragma omp for schedule(static)
        for (size_t i = 0; i < n; i++) {
            fb += cell_vector_at(su, w, P->cell[i], P->x[i], P->y[i], vx, vy, 0, &ox[i], &oy[i]);
            ox[i] *= scale;
            oy[i] *= scale;
        }
    }
    return fb;
}

/* The pressure of the correction has a zero normal gradient at walls in
 * the flow, not only in the PPE: without buoyancy, and with balanced
 * buoyancy (its pi_d; pi_b balances the buoyancy force, whose normal part
 * at a floor it carries). With the buoyancy source (Eq. 4 in the
 * predictor) p holds the hydrostatic gradient up to the walls. With
 * anisotropicCells only such a p takes the walls' samples. */
static int settings_walls_zero_gradient(const sol_settings *s)
{
    return s->anisotropic && (!s->buoyant || s->balanced);
}

static int walls_zero_gradient(const sol_setup *su) { return settings_walls_zero_gradient(&su->set); }

/* interpolationError auto: transpose where anisotropicCells is on, where it
 * was introduced (a particle of a large cell beside thin ones took the same
 * kick of -dt grad q step after step, README "Smaller steps on the 8x8
 * graded cavity"); gradient (Eq. 10 with the whole p, the paper's)
 * elsewhere. Measured on triangles (README, "The interpolation error by
 * the transpose of the fits"): the transpose halves the Re 1000 cavity's
 * error on 854 and 1 476 uniform triangles at small steps (1 476 at
 * deltaT 0.004, settled: 0.0326 / 0.0261 from Ghia against 0.0504 /
 * 0.0506; icoFoam 0.0566 / 0.0490), but loses on 3 552 triangles (0.0180 /
 * 0.0103 against 0.0160 / 0.0066 at 0.01), on the graded 3 588 (0.0131 /
 * 0.0162 against 0.0066 / 0.0059 at 0.005) and at the elbow's quarter
 * step (inlet pressures -0.11 / 1.00 against 0.44 / 2.04; converged 0.466
 * / 2.359), and on the 40^2 quads one step of the right wall's jet reached
 * 1.126 x the lid speed: so not by default. With buoyancy source the
 * anisotropic walls are off, and so is this (docs/METHOD.md section 8,
 * "Walls in the correction" (f)). */
int sol_q_transpose(const sol_settings *s)
{
    return s->q_transpose >= 0 ? s->q_transpose : settings_walls_zero_gradient(s);
}

/* positiveRows without anisotropicCells: the share of the positive row in a
 * CPM row a [n] by the diagonal dominance of the implicit row I - dnu L
 * (dnu = dt nu, the larger of dt nu and dt kappa): its off-diagonal sum
 * exceeds the diagonal where rho = 2 dnu sum_j max(-a_j, 0) > 1. 0 up to
 * rho = 1, 1 from rho = 2, linear between (continuous in the particle
 * positions). On uniform lattices rho stays below 1 except in a dozen rows
 * in 3 200 steps (40^2 cavity, Re 1000); a cavity graded 10:1 toward its
 * walls has about 30 such rows of 400 per step at dt 0.0005. */
static double dominance_weight(const double *a, int n, double dnu)
{
    double neg = 0;
    for (int j = 0; j < n; j++)
        neg -= a[j] < 0 ? a[j] : 0;
    double rho = 2 * dnu * neg;
    return rho <= 1 ? 0 : rho >= 2 ? 1 : rho - 1;
}

/* The row w->c0 [nn] (offsets w->h, w->k) blended by t in (0, 1] toward
 * lap_positive_row's positive row with share tau (t = 1: replaced);
 * w->cx keeps the row before. Returns 1 if the row was changed. */
static int positive_blend(sol_work *w, double *row, const double *nx, const double *ny, int nn, double sx,
                          double sy, double tau, double t)
{
    if (t < 1)
        memcpy(w->cx, row, (size_t)nn * sizeof *row);
    int r = nx ? lap_positive_row_neumann(w->h, w->k, nx, ny, nn, sx, sy, tau, row)
               : lap_positive_row(w->h, w->k, nn, sx, sy, tau, row);
    if (r && t < 1)
        for (int j = 0; j < nn; j++)
            row[j] = w->cx[j] + t * (row[j] - w->cx[j]);
    return r;
}

/* positiveRows on a row (docs/METHOD.md section 8, "Positive rows"; the
 * comment in step6_rows); returns 1 if it was changed */
static int positive_row(const sol_settings *set, sol_work *w, double *row, const double *nx, const double *ny,
                        int nn, double sx, double sy, double dmax)
{
    double th = set->anisotropic ? 1 : dominance_weight(row, nn, dmax);
    int made = th > 0 ? positive_blend(w, row, nx, ny, nn, sx, sy, SOL_POSITIVE_TAU, th) : 0;
    double td = set->anisotropic ? dominance_weight(row, nn, dmax) : 0;
    if (td > 0) /* tau 0: the positive row */
        made |= positive_blend(w, row, nx, ny, nn, sx, sy, 0, td);
    return made;
}

/* boundedFits (docs/METHOD.md section 8, "Bounded fits"): v limited to the
 * range of the n sample values s widened by margin times it (counted in
 * w->bounded; margin < 0: not limited); the MLS fits of [NSH16] Eqs. 28-35
 * and the carried refill are not bounded by their samples, and on stencils
 * whose cells differ in size by 1000:1 they returned tens of times the lid
 * speed. */
static double bound_fit(sol_work *w, const double *s, size_t n, double v, double margin)
{
    if (margin < 0 || n == 0)
        return v;
    double lo = s[0], hi = s[0];
#pragma omp simd reduction(min : lo) reduction(max : hi)
    for (size_t j = 1; j < n; j++) {
        lo = s[j] < lo ? s[j] : lo;
        hi = s[j] > hi ? s[j] : hi;
    }
    double e = margin * (hi - lo);
    if (v < lo - e) {
        w->bounded++;
        return lo - e;
    }
    if (v > hi + e) {
        w->bounded++;
        return hi + e;
    }
    return v;
}

/* ---- Step 6: the implicit predictor ------------------------------------------ */

/* The Laplacian row of a particle into a [nn] (offsets w->h, w->k, metric
 * sx, sy): with zero-gradient samples (*neu, normals nx, ny) CPM's row with
 * them as d/dn = 0 (lap_cpm_neumann); else, or if that fails (*neu = 0),
 * the model lp's row, CPM4 falling back to CPM, then MPS. Fall-backs are
 * counted in w->lap_fallbacks. */
static ump_status laplacian_row(sol_work *w, const lap_params *lp, int *neu, const double *nx, const double *ny,
                                int nn, double l0, double sx, double sy, double *a, ump_err *e)
{
    static const lap_params mps = {LAP_MPS, 3.1}, cpm = {LAP_CPM, 0};
    if (*neu && lap_cpm_neumann(w->h, w->k, nx, ny, nn, sx, sy, a, e) == UMP_OK)
        return UMP_OK;
    if (*neu)
        w->lap_fallbacks++; /* their values, as with another model */
    *neu = 0;
    if (lap_coeffs_metric(lp, w->h, w->k, nn, l0, sx, sy, a, e) == UMP_OK ||
        (lp->model == LAP_CPM4 && lap_coeffs_metric(&cpm, w->h, w->k, nn, l0, sx, sy, a, e) == UMP_OK))
        return UMP_OK;
    w->lap_fallbacks++;
    return lap_coeffs(&mps, w->h, w->k, nn, l0, a, e);
}

/* Zero-gradient boundaries by images (docs/METHOD.md section 8,
 * "Zero-gradient boundaries in the Laplacian"): the row of the samples
 * [nn] (offsets w->h, w->k) whose zero-gradient ones (normal nx, ny != 0)
 * lie on one plane, or on two perpendicular or parallel ones, is CPM's
 * row over the other samples, the particle itself (offset 0) and their
 * mirror images across those planes (and across both, at a corner of
 * two), each image carrying its source's value: the even extension of a
 * field with zero normal gradient, exact for its quadratics. An image
 * farther from the particle along a plane's normal than the farthest
 * sample (plus a quarter of the cell's extent ex, ey along it) is left
 * out, so next to a straight wall of a lattice the row is the interior
 * row, and a field of the wall-parallel coordinate alone stays one (a
 * stratification beside adiabatic walls: the CPM fit with d/dn = 0 rows,
 * lap_cpm_neumann, differed from the interior row in its higher moments,
 * and T varied along the wall by 1e-4 in the first seconds; README,
 * "Stratified rest while T changes"). The images' coefficients are summed
 * into their sources' a [nn]; the zero-gradient samples get 0 and the
 * particle's own images drop out of sum_j a_j (phi_j - phi_i).
 * positiveRows is the caller's (in the derivative form). Returns 1 with
 * the row made, 0 where images do not apply (more than two planes, two
 * oblique ones, the particle or a sample beyond a plane, a value sample on
 * one (a plane only partly zero-gradient), or the fit failed, counted as a
 * fall-back): the caller then takes lap_cpm_neumann; -1 out of memory. */
static int image_row(sol_work *w, const lap_params *lp, const double *nx, const double *ny, int nn, double l0,
                     double ex, double ey, double sx, double sy, double *a)
{
    /* the planes: normal (outward) and n . x of a point, offsets from the particle */
    double pn[2][2], pd[2];
    int np = 0;
    double tol = 1e-9 * l0;
    for (int j = 0; j < nn; j++) {
        if (nx[j] == 0 && ny[j] == 0)
            continue;
        double d = nx[j] * w->h[j] + ny[j] * w->k[j];
        int q = 0;
        while (q < np && !(pn[q][0] * nx[j] + pn[q][1] * ny[j] > 1 - 1e-12 && fabs(pd[q] - d) <= tol))
            q++;
        if (q == np) {
            if (np == 2 || d < -tol)
                return 0;
            pn[np][0] = nx[j], pn[np][1] = ny[j], pd[np++] = d;
        }
    }
    /* across two planes only if they are perpendicular (a corner) or
     * parallel (a channel): else the double image is a rotation */
    if (np == 2) {
        double c = pn[0][0] * pn[1][0] + pn[0][1] * pn[1][1];
        if (!(fabs(c) < 1e-9 || c < -1 + 1e-9))
            return 0;
    }
    /* the samples kept, every one on the inner side of each plane, and
     * their reach along each plane's normal from the particle */
    double reach[2] = {0, 0};
    int nk = 0;
    for (int j = 0; j < nn; j++) {
        if (nx[j] != 0 || ny[j] != 0)
            continue;
        for (int q = 0; q < np; q++) {
            double d = pn[q][0] * w->h[j] + pn[q][1] * w->k[j];
            if (d > pd[q] - tol) /* beyond the plane, or a value on it */
                return 0;
            reach[q] = fmax(reach[q], fabs(d));
        }
        nk++;
    }
    size_t need = (size_t)(nk + 1) * (np == 2 ? 4 : 2);
    if (need > w->icap) {
        size_t c = need + need / 2 + 64;
        double **d[] = {&w->ih, &w->ik, &w->ia};
        for (size_t i = 0; i < sizeof d / sizeof d[0]; i++) {
            double *q = ump_realloc_array(*d[i], c, sizeof(double));
            if (!q)
                return -1;
            *d[i] = q;
        }
        int *q = ump_realloc_array(w->isrc, c, sizeof(int));
        if (!q)
            return -1;
        w->isrc = q;
        w->icap = c;
    }
    /* sources (-1: the particle itself), then their images: across each
     * plane, and at a corner across both */
    int ne = 0;
    for (int j = -1; j < nn; j++) {
        if (j >= 0 && (nx[j] != 0 || ny[j] != 0))
            continue;
        w->ih[ne] = j < 0 ? 0 : w->h[j];
        w->ik[ne] = j < 0 ? 0 : w->k[j];
        w->isrc[ne++] = j;
    }
    int nsrc = ne;
    for (int m = 1; m < (np == 2 ? 4 : 2); m++) /* m: a bit per plane crossed */
        for (int e = 0; e < nsrc; e++) {
            double x = w->ih[e], y = w->ik[e];
            for (int q = 0; q < np; q++) {
                if (!(m & (1 << q)))
                    continue;
                double t = 2 * (pn[q][0] * x + pn[q][1] * y - pd[q]);
                x -= t * pn[q][0];
                y -= t * pn[q][1];
            }
            /* a quarter of the cell's extent along the normal spare, so a
             * lattice's row does not change as its particles jitter; an
             * image within a twentieth of the cell's extents of the
             * particle (its own, when it has come that close to the plane)
             * is left out: its weight 1/r^6 would swamp the fit */
            int in = 1;
            for (int q = 0; q < np; q++)
                in &= fabs(pn[q][0] * x + pn[q][1] * y) <=
                      reach[q] + 0.25 * (fabs(pn[q][0]) * ex + fabs(pn[q][1]) * ey);
            double u = x / ex, v = y / ey;
            if (!in || u * u + v * v < 0.05 * 0.05)
                continue;
            w->ih[ne] = x, w->ik[ne] = y;
            w->isrc[ne++] = w->isrc[e];
        }
    /* the particle itself is not a sample of the row: its images are */
    int off = 1;
    ump_err e;
    if (lap_coeffs_metric(lp, w->ih + off, w->ik + off, ne - off, l0, sx, sy, w->ia, &e) != UMP_OK) {
        w->lap_fallbacks++; /* the caller's lap_cpm_neumann instead */
        return 0;
    }
    for (int j = 0; j < nn; j++)
        a[j] = 0;
    for (int e2 = 0; e2 < ne - off; e2++) {
        int src = w->isrc[e2 + off];
        if (src >= 0)
            a[src] += w->ia[e2];
    }
    return 1;
}

/* Insertion sort of one row by column (only when particles are not sorted
 * by cell: sortInterval 0 or > 1). */
static void sort_row(ump_idx *ci, double *av, double *avT, ump_idx n)
{
    for (ump_idx a = 1; a < n; a++) {
        ump_idx c = ci[a];
        double v = av[a], vT = avT ? avT[a] : 0;
        ump_idx b = a;
        for (; b > 0 && ci[b - 1] > c; b--) {
            ci[b] = ci[b - 1];
            av[b] = av[b - 1];
            if (avT)
                avT[b] = avT[b - 1];
        }
        ci[b] = c;
        av[b] = v;
        if (avT)
            avT[b] = vT;
    }
}

/* The predictor's right-hand side carries -dt (gpx, gpy): the balanced
 * buoyancy's force (balance_buoyancy) and/or pressureTheta's kick
 * th grad p^{n-1/2} at r^n (step6_rows, step6_solve) */
static int rhs_kick(const sol_settings *set) { return (set->buoyant && set->balanced) || set->p_theta > 0; }

/* Rows of I + dt nu L (Eqs. 14, 16) and the right-hand sides, with the
 * Boussinesq source (Eq. 4) and, buoyant, the energy equation's (Eq. 37).
 * Count -> prefix sum -> fill: row i has one entry per fluid particle of
 * its cell's stencil (itself: the diagonal), boundary particles go to the
 * right-hand side. */

/* The fluid particles in cell c's stencil (its runs of consecutive cells
 * in the bins). */
static ump_idx stencil_particles(const sol_setup *su, const part_bins *bins, ump_idx c)
{
    ump_idx cnt = 0;
    for (ump_idx r = su->ru_off[c]; r < su->ru_off[c + 1]; r++)
        cnt += bins->off[su->ru_q1[r]] - bins->off[su->ru_q0[r]];
    return cnt;
}

static ump_status step6_rows(sol *S, double dt, ump_err *err)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    const mesh2d *m = su->m;
    const part_set *P = st->P;
    const sol_settings *set = &su->set;
    ump_idx nc = m->ncells;
    size_t n = P->n;
    /* count */
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
    for (ump_idx c = 0; c < nc; c++)
        st->cnt_cell[c] = stencil_particles(su, &st->bins, c);
    /* prefix sum */
    st->rp[0] = 0;
    for (size_t i = 0; i < n; i++) {
        size_t e = (size_t)st->rp[i] + (size_t)st->cnt_cell[P->cell[i]];
        UMP_CHECK(e < INT32_MAX, err, UMP_ERR_NOMEM, "predictor: %zu matrix entries overflow the index", e);
        st->rp[i + 1] = (ump_idx)e;
    }
    size_t nz = (size_t)st->rp[n];
    if (nz > st->rowcap || !st->ci || (st->ndiffer > 0 && !st->avT)) {
        size_t cap = nz + nz / 2 + 1024;
        ump_idx *ci = ump_realloc_array(st->ci, cap, sizeof *ci);
        if (!ci)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "predictor: out of memory (%zu entries)", cap);
        st->ci = ci;
        double *av = ump_realloc_array(st->av, cap, sizeof *av);
        if (!av)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "predictor: out of memory (%zu entries)", cap);
        st->av = av;
        if (st->ndiffer > 0 || st->avT) {
            double *aT = ump_realloc_array(st->avT, cap, sizeof *aT);
            if (!aT)
                return UMP_FAIL(err, UMP_ERR_NOMEM, "predictor: out of memory (%zu entries)", cap);
            st->avT = aT;
        }
        st->rowcap = cap;
    }
    /* fill */
    int buoyant = set->buoyant;
    double dnu = dt * set->nu, dkap = dt * set->kappa;
    double gx = buoyant ? set->g[m->ax[0]] : 0, gy = buoyant ? set->g[m->ax[1]] : 0;
    const lap_params cpm = {LAP_CPM, 0};
    const part_boundary *bp = &st->bp;
    int bal = buoyant && set->balanced;
    int kick = rhs_kick(set); /* gpx, gpy: -R (balance_buoyancy) and/or th grad p^{n-1/2} */
    int damp = walls_zero_gradient(su);  /* st->wdamp, for step10_correct */
    int sepT = buoyant && st->ndiffer > 0; /* rows of their own for T (st->avT) */
    st->sepT = sepT;
#pragma omp parallel num_threads(S->nthreads)
    {
        sol_work *w = &S->work[thread_id()];
        ump_idx gathered = -1; /* the cell whose stencil w holds (particles are sorted by cell) */
        size_t cnt = 0;
#pragma omp for schedule(dynamic, 256)
        for (size_t i = 0; i < n; i++) {
            if (w->rc != UMP_OK)
                continue;
            ump_idx c = P->cell[i];
            ump_err e;
            ump_status rc = c == gathered ? UMP_OK : gather_cell(su, st, w, c, &cnt, &e);
            if (rc != UMP_OK) {
                work_fail(w, rc, &e);
                continue;
            }
            gathered = c;
            int nn = offsets_but(w, cnt, (ump_idx)i, P->x[i], P->y[i]);
            double l0 = sqrt(m->area[c]);
            /* CPM4 only where the stencil is all fluid; next to a wall,
             * inlet or outlet the quartic fit to the boundary data
             * overshoots (docs/METHOD.md section 8, "CPM4"): CPM there */
            const lap_params *lp = set->lap.model == LAP_CPM4 && su->st_bnd[c] ? &cpm : &set->lap;
            /* anisotropicCells: CPM in the metric of the particle's cell,
             * distances in units of its extents dx, dy (docs/METHOD.md
             * section 8, "Anisotropic cells"); dx = dy is the plain row */
            double sx = set->anisotropic ? 1 / m->dx[c] : 1, sy = set->anisotropic ? 1 / m->dy[c] : 1;
            /* Zero-gradient boundaries in the Laplacian (docs/METHOD.md
             * section 8): a boundary particle whose condition is a zero
             * gradient this step (outlets for U, adiabatic walls for T)
             * enters the CPM fit as d/dn = 0 (lap_cpm_neumann) instead of
             * as its value, which is the previous step's: next to such a
             * boundary on a thin cell that value carried almost the whole
             * row and held the particle (README, "Zero-gradient walls in
             * the Laplacian"). Normals of U's such samples in w->pv,
             * w->cy, of T's in w->gv[1], w->gv[2] (zero: a value) */
            double *unx = w->pv, *uny = w->cy, *tnx = w->gv[1], *tny = w->gv[2];
            int anyu = 0, anyt = 0, differ = 0;
            if (st->nneu > 0 && lp->model == LAP_CPM) {
                int jj = 0;
                for (size_t j = 0; j < cnt; j++) {
                    ump_idx r = w->ref[j];
                    if (r == (ump_idx)i)
                        continue;
                    ump_idx b = r < 0 ? -1 - r : -1;
                    int fu = b >= 0 && st->uneu[b], ft = b >= 0 && buoyant && st->tneu[b];
                    double nx = b >= 0 ? m->nx[bp->face[b]] : 0, ny = b >= 0 ? m->ny[bp->face[b]] : 0;
                    unx[jj] = fu ? nx : 0;
                    uny[jj] = fu ? ny : 0;
                    tnx[jj] = ft ? nx : 0;
                    tny[jj++] = ft ? ny : 0;
                    anyu |= fu;
                    anyt |= ft;
                    differ |= fu != ft;
                }
            }
            /* the zero-gradient samples by images where they lie on one or
             * two planes (image_row; positiveRows below, in the derivative
             * form), else as
             * d/dn = 0 rows of the fit */
            int own = sepT && differ;
            int imu = anyu ? image_row(w, lp, unx, uny, nn, l0, m->dx[c], m->dy[c], sx, sy, w->c0) : 0;
            if (imu < 0) {
                work_fail(w, UMP_FAIL(&e, UMP_ERR_NOMEM, "out of memory for the image rows"), &e);
                continue;
            }
            if (!imu && (rc = laplacian_row(w, lp, &anyu, unx, uny, nn, l0, sx, sy, w->c0, &e)) != UMP_OK) {
                work_fail(w, rc, &e);
                continue;
            }
            /* T's row where its zero gradients are not U's: its own */
            double *aT = NULL;
            if (own) {
                aT = w->gv[0];
                int imt = anyt ? image_row(w, lp, tnx, tny, nn, l0, m->dx[c], m->dy[c], sx, sy, aT) : 0;
                if (imt < 0) {
                    work_fail(w, UMP_FAIL(&e, UMP_ERR_NOMEM, "out of memory for the image rows"), &e);
                    continue;
                }
                if (!imt && (rc = laplacian_row(w, lp, &anyt, tnx, tny, nn, l0, sx, sy, aT, &e)) != UMP_OK) {
                    work_fail(w, rc, &e);
                    continue;
                }
                if (set->positive)
                    w->positive_rows += positive_row(set, w, aT, anyt ? tnx : NULL, anyt ? tny : NULL, nn, sx, sy,
                                                     dkap);
            }
            /* positiveRows (docs/METHOD.md section 8, "Positive rows"): a
             * CPM row whose negative coefficients exceed SOL_POSITIVE_TAU
             * of its positive ones is replaced by the positive row closest
             * to it where they cost the implicit row I - dt nu L its
             * diagonal dominance, 2 dt nu sum_j max(-a_j, 0) > 1 (fully
             * from 2); with anisotropicCells wherever they exceed it. On
             * a cavity graded only 10:1 toward its walls, CPM's rows let
             * particles reach 84 times the lid speed at a small step; on
             * stretched stencils u* overshot the lid from rest. With
             * anisotropicCells a row kept (negatives below the share) is
             * then made positive too where it still costs the dominance
             * (blended by the same rule): near a wall dt nu/dx^2 reaches
             * 10^4, and a row 1 % negative turned u^n = 0.005 into u* =
             * 1.80 next to the lid's corner (README, "Graded toward the
             * lid's downstream corner"). Without a row of its own for T
             * this row is T's too (dominance at the larger of dt nu, dt
             * kappa). */
            if (set->positive && lp->model == LAP_CPM) {
                double dmax = own || dnu > dkap ? dnu : dkap;
                w->positive_rows += positive_row(set, w, w->c0, anyu ? unx : NULL, anyu ? uny : NULL, nn, sx, sy,
                                                 dmax);
            }
            /* L phi_i = sum_j a_j (phi_j - phi_i); boundary particles are
             * Dirichlet data (Eq. 14): their a_j phi_j moves to the RHS */
            ump_idx pos = st->rp[i], dpos = -1, *ci = st->ci;
            double *av = st->av, *avT = st->avT, suma = 0, bu = 0, bv = 0, bT = 0, swall = 0, sumT = 0;
            int jj = 0, sorted = 1;
            for (size_t j = 0; j < cnt; j++) {
                ump_idx r = w->ref[j];
                if (r == (ump_idx)i) {
                    dpos = pos++;
                    ci[dpos] = r;
                    continue;
                }
                double a = w->c0[jj], at = aT ? aT[jj] : a;
                jj++;
                suma += a;
                sumT += at;
                if (r < 0) {
                    if (damp) {
                        ump_idx fb = bp->face[-1 - r] - m->ninternal;
                        swall += su->wall[fb] && su->u_kind[fb] == BU_FIXED ? a : 0;
                    }
                    bu += a * bp->u[-1 - r];
                    bv += a * bp->v[-1 - r];
                    bT += at * bp->T[-1 - r];
                } else {
                    ci[pos] = r;
                    av[pos] = -dnu * a;
                    if (sepT)
                        avT[pos] = -dkap * at;
                    sorted &= pos == st->rp[i] || ci[pos - 1] < r;
                    pos++;
                }
            }
            av[dpos] = 1 + dnu * suma; /* I + dt nu L, Eq. 14 */
            if (sepT)
                avT[dpos] = 1 + dkap * sumT; /* I + dt kappa L, Eq. 37 */
            if (damp) {
                /* Walls in the correction (e) (docs/METHOD.md section 8):
                 * what this row leaves of an increment given to the fluid
                 * particles and not to the no-slip walls in it, the share
                 * of Eq. 10's correction the particle keeps
                 * (step10_correct); 1 without walls in the row */
                double k = (1 + dnu * (suma - swall)) / (1 + dnu * suma);
                st->wdamp[i] = k > 1 ? 1 : k > 0 ? k : 0;
            }
            if (dpos > st->rp[i])
                sorted &= ci[dpos - 1] < ci[dpos];
            if (dpos + 1 < pos)
                sorted &= ci[dpos + 1] > ci[dpos];
            if (!sorted)
                sort_row(ci + st->rp[i], av + st->rp[i], sepT ? avT + st->rp[i] : NULL, pos - st->rp[i]);
            /* Boussinesq source per unit mass, -beta (T^n - TRef) g (Eq. 4);
             * balanced buoyancy: what pi_b leaves of it, -gpx, -gpy
             * (balance_buoyancy) */
            double b = buoyant && !bal ? -set->beta * (P->T[i] - set->t_ref) : 0;
            double px = kick ? st->gpx[i] : 0, py = kick ? st->gpy[i] : 0;
            st->rhs_u[i] = P->u[i] + dnu * bu + dt * (b * gx - px);
            st->rhs_v[i] = P->v[i] + dnu * bv + dt * (b * gy - py);
            st->rhs_T[i] = P->T[i] + dkap * bT; /* Eq. 37 */
        }
    }
    return UMP_OK; /* errors and fall-back counts: work_collect in sol_step */
}

/* Solve the rows of step6_rows for u*, v* (and T^{n+1}), warm-started from
 * the particle values with the step's explicit forces applied: u and v
 * (and T when kappa = nu) in lockstep. */
static ump_status step6_solve(sol *S, double dt, sol_stats *stats, ump_err *err)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    part_set *P = st->P;
    const sol_settings *set = &su->set;
    size_t n = P->n;
    lsolve_csr A = {(ump_idx)n, st->rp, st->ci, st->av};
    if (rhs_kick(set)) {
        /* the start u^n - dt (gpx, gpy), the kick of pressureTheta and the
         * balanced buoyancy's force that the right-hand side holds: the
         * first residual is then the viscous change alone (with u^n the
         * kick was part of it: Taylor-Green 25 600, 13.3 -> 12.9 iterations) */
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
        for (size_t i = 0; i < n; i++) {
            st->us[i] = P->u[i] - dt * st->gpx[i];
            st->vs[i] = P->v[i] - dt * st->gpy[i];
        }
    } else {
        memcpy(st->us, P->u, n * sizeof *st->us);
        memcpy(st->vs, P->v, n * sizeof *st->vs);
    }
    if (set->buoyant)
        memcpy(st->Ts, P->T, n * sizeof *st->Ts);
    double dnu = dt * set->nu, dkap = dt * set->kappa;
    int together = set->buoyant && dkap == dnu && !st->sepT;
    const double *b[3] = {st->rhs_u, st->rhs_v, st->rhs_T};
    double *x[3] = {st->us, st->vs, st->Ts};
    UMP_CALL(lsolve_rows_setup(st->kry, &A, set->pred_pc, err));
    UMP_CALL(lsolve_rows_bicgstab(st->kry, &A, together ? 3 : 2, b, x, set->pred_tol, set->pred_maxit,
                                  stats->pred, err));
    if (set->buoyant && st->sepT) {
        /* Eq. 37 on its own rows (zero-gradient T faces, step6_rows) */
        lsolve_csr AT = {(ump_idx)n, st->rp, st->ci, st->avT};
        UMP_CALL(lsolve_rows_setup(st->kry, &AT, set->pred_pc, err));
        UMP_CALL(lsolve_rows_bicgstab(st->kry, &AT, 1, b + 2, x + 2, set->pred_tol, set->pred_maxit,
                                      stats->pred + 2, err));
    } else if (set->buoyant && !together) {
        /* Eq. 37: the same rows with dt kappa, I + (kappa/nu)(A - I) */
        double r = dkap / dnu;
        size_t nz = (size_t)st->rp[n];
        UMP_CHECK(dnu > 0 && isfinite(r), err, UMP_ERR_INPUT, "predictor: nu = %g, cannot scale to kappa",
                  set->nu);
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
        for (size_t k = 0; k < nz; k++)
            st->av[k] *= r;
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
        for (size_t i = 0; i < n; i++)
            for (ump_idx k = st->rp[i]; k < st->rp[i + 1]; k++)
                if (st->ci[k] == (ump_idx)i)
                    st->av[k] += 1 - r;
        UMP_CALL(lsolve_rows_setup(st->kry, &A, set->pred_pc, err));
        UMP_CALL(lsolve_rows_bicgstab(st->kry, &A, 1, b + 2, x + 2, set->pred_tol, set->pred_maxit,
                                      stats->pred + 2, err));
    }
    int ns = set->buoyant ? 3 : 2;
    for (int k = 0; k < ns; k++)
        if (stats->pred[k].converged < 0)
            return UMP_FAIL(err, UMP_ERR_SINGULAR, "predictor: BiCGSTAB broke down solving for %s "
                            "(residual %g)", k == 2 ? "T" : k ? "v" : "u", stats->pred[k].res);
    if (set->buoyant)
        memcpy(P->T, st->Ts, n * sizeof *P->T);
    return UMP_OK;
}

/* ---- Steps 7 and 10: moving particles ----------------------------------------- */

/* A boundary face that a particle may not leave through: the velocity is
 * prescribed there with no outward normal component (walls, moving walls,
 * inlets), or it is a symmetry plane or slip wall. */
static int is_wall_face(const sol_setup *su, const sol_state *st, ump_idx f)
{
    const mesh2d *m = su->m;
    ump_idx b = f - m->ninternal;
    if (su->u_kind[b] == BU_SYMMETRY)
        return 1;
    return su->u_kind[b] == BU_FIXED && st->ub[b] * m->nx[f] + st->vb[b] * m->ny[f] <= 0;
}

/* Wall stop (docs/METHOD.md section 8; the papers are silent): a move
 * that crosses a wall face f ends on the fluid side of f, at the crossing
 * point's projection onto f's line moved back by WALL_GAP of the owner
 * centroid's distance to that line (the tangential part of the move is
 * kept, the normal part stops at the wall). The gap keeps a stopped
 * particle off the boundary particle at the face centre. The caller
 * removes the velocity component into the wall and keeps the rest: the
 * carried velocity survives, where deletion replaced it by an
 * interpolated one. (Keeping the whole velocity was tried: a particle
 * stopped in a lid corner was pushed in again every step and the 20 x 20
 * Re 100 cavity with UMPPM diverged at t = 1.1.) At a corner the
 * projected point can lie beyond a second wall: it is projected again (at
 * most WALL_TRIES times), and failing that the particle stays at its
 * start. Returns the cell. */
#define WALL_GAP 0.1
#define WALL_TRIES 3
static ump_idx wall_stop(const sol_setup *su, const sol_state *st, ump_idx f, double *x, double *y,
                         double x0, double y0, ump_idx cell0)
{
    const mesh2d *m = su->m;
    for (int k = 0; k < WALL_TRIES; k++) {
        ump_idx c = m->owner[f];
        double d = (*x - m->fx[f]) * m->nx[f] + (*y - m->fy[f]) * m->ny[f];
        double dcf = (m->fx[f] - m->cx[c]) * m->nx[f] + (m->fy[f] - m->cy[c]) * m->ny[f];
        double s = (d > 0 ? d : 0) + WALL_GAP * dcf;
        double px = *x - s * m->nx[f], py = *y - s * m->ny[f];
        ump_idx cell, face;
        part_where r = part_locate(m, c, &px, &py, &cell, &face);
        if (r == PART_INSIDE) {
            *x = px;
            *y = py;
            return cell;
        }
        if (r != PART_LEFT || !is_wall_face(su, st, face))
            break;
        *x = px;
        *y = py;
        f = face;
    }
    *x = x0;
    *y = y0;
    return cell0;
}

/* Locate-and-keep, once for both moves: particle i goes to
 * (x0, y0) + dt (u, v), walking from cell0. A particle that crosses a wall
 * is stopped at it (wall_stop; counted in *walled) and loses the part of
 * (u, v) that points into the wall; one that leaves through
 * an open boundary (outlet, pressure inlet) is marked keep = 0 and stays
 * where it was for the rest of the step. */
static void move_particles(sol *S, double *u, double *v, double dt, size_t *walled)
{
    const sol_setup *su = &S->su;
    const mesh2d *m = su->m;
    sol_state *st = &S->st;
    part_set *P = st->P;
    size_t n = P->n, nw = 0;
#pragma omp parallel for schedule(static) num_threads(S->nthreads) reduction(+ : nw)
    for (size_t i = 0; i < n; i++) {
        double x = st->x0[i] + dt * u[i], y = st->y0[i] + dt * v[i];
        ump_idx cell, face;
        part_where r = part_locate(m, st->cell0[i], &x, &y, &cell, &face);
        if (r == PART_LEFT && is_wall_face(su, st, face)) {
            double un = u[i] * m->nx[face] + v[i] * m->ny[face];
            if (un > 0) {
                u[i] -= un * m->nx[face];
                v[i] -= un * m->ny[face];
            }
            cell = wall_stop(su, st, face, &x, &y, st->x0[i], st->y0[i], st->cell0[i]);
            r = PART_INSIDE;
            nw++;
        }
        if (r == PART_INSIDE) {
            P->x[i] = x;
            P->y[i] = y;
            P->cell[i] = cell;
        } else {
            st->keep[i] = 0;
        }
    }
    *walled += nw;
}

/* pressureTheta th > 0 (a departure from Eq. 10, docs/METHOD.md section 8
 * "Pressure along the path"): the predictor (Eq. 14) carries -th dt grad
 * p^{n-1/2}(r^n) in its right-hand side, with gpx/gpy (added to -R
 * under balanced buoyancy): the previous step's pressure (balanced
 * buoyancy: its pi_d part) by the MLS derivative of Eqs. 33-34 (the
 * gradient of Step 10). Implicit viscosity then balances it at walls, as
 * in icoFoam's momentum predictor. Step 9 then solves for
 * p^{n+1/2} and Step 10 applies the rest, (1 - th) of it, at r*: with th =
 * 1/2 the pressure impulse along the path is the trapezoidal rule
 * dt/2 (grad p(r^n) + grad p(r*)) instead of dt grad p(r*), whose velocity
 * loses the factor cos(dtheta) each step the path turns by dtheta. The
 * previous step's p^{n-1/2} (not an extrapolation) is applied, so the
 * pressure a step writes does not feed back into itself. */
static void path_pressure_kick(sol *S, sol_stats *stats)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    part_set *P = st->P;
    ump_idx nc = su->m->ncells;
    size_t n = P->n;
    double th = su->set.p_theta;
    int bal = su->set.buoyant && su->set.balanced;
    /* balanced: pold is the last step's pi_d (kept by step10_correct);
     * at the first step p less this step's pi_b */
    if (!bal || !st->pold_pd) {
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
        for (ump_idx c = 0; c < nc; c++)
            st->pold[c] = bal ? st->p[c] - st->pib[c] : st->p[c];
    }
    /* us, vs are free until the predictor solve */
    stats->mls_fallbacks +=
        (int)particle_pressure_gradient(S, st->pold, st->pfprev, st->us, st->vs, walls_zero_gradient(su));
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
    for (size_t i = 0; i < n; i++) {
        st->gpx[i] = (bal ? st->gpx[i] : 0.0) + th * st->us[i];
        st->gpy[i] = (bal ? st->gpy[i] : 0.0) + th * st->vs[i];
    }
}

/* Step 7: r* = r^n + dt u* (Eq. 9), re-located and re-binned. */
static ump_status step7_intermediate(sol *S, double dt, size_t *walled, ump_err *err)
{
    sol_state *st = &S->st;
    part_set *P = st->P;
    size_t n = P->n;
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
    for (size_t i = 0; i < n; i++) {
        st->x0[i] = P->x[i];
        st->y0[i] = P->y[i];
        st->cell0[i] = P->cell[i];
        st->keep[i] = 1;
    }
    move_particles(S, st->us, st->vs, dt, walled);
    return part_bins_build(&st->bins, S->su.m, P, err);
}

/* ---- Step 8: u* on the mesh ------------------------------------------------ */

/* MLS value (Eq. 32) at (x, y) of the gathered samples: fluid quantities
 * f[k], boundary quantities g[k], k < nv. */
/* The values of nv <= SOL_MAX_VALUES quantities at the gathered samples
 * (fluid f[q], boundary g[q]) into w->gv[q], once per gather. */
static void gather_values(sol_work *w, size_t cnt, int nv, const double *const *f, const double *const *g)
{
    for (int q = 0; q < nv; q++) {
        const double *restrict fq = f[q], *restrict gq = g[q];
        double *restrict v = w->gv[q];
        const ump_idx *restrict ref = w->ref;
        for (size_t j = 0; j < cnt; j++) {
            ump_idx r = ref[j];
            v[j] = r >= 0 ? fq[r] : gq[-1 - r];
        }
    }
}

/* Swap gathered samples a and b (position, ref and the nv values): the fits
 * leave a sample out by moving it to the end. */
static void sample_swap(sol_work *w, size_t a, size_t b, int nv)
{
    double t;
    t = w->px[a], w->px[a] = w->px[b], w->px[b] = t;
    t = w->py[a], w->py[a] = w->py[b], w->py[b] = t;
    ump_idx r = w->ref[a];
    w->ref[a] = w->ref[b], w->ref[b] = r;
    for (int q = 0; q < nv; q++)
        t = w->gv[q][a], w->gv[q][a] = w->gv[q][b], w->gv[q][b] = t;
}

/* MLS values (Eq. 32) at (x, y) from the gathered samples and their
 * gather_values, each limited by bound_fit with margin; the boundary
 * particle of face skip_bface (-1: none) is left out by moving it to the
 * end of the gathered arrays (the order of the samples is immaterial to
 * the fit). Contiguous arrays throughout, so the offset, weight and
 * dot-product loops vectorise. */
static void mls_fit_values(sol_work *w, size_t cnt, double x, double y, double mdx, double mdy,
                           ump_idx skip_bface, int nv, double margin, double *out)
{
    size_t n = cnt > MLS_MAX_SAMPLES ? MLS_MAX_SAMPLES : cnt;
    if (skip_bface >= 0) {
        ump_idx r = -1 - skip_bface;
        for (size_t j = 0; j < n; j++)
            if (w->ref[j] == r) {
                sample_swap(w, j, n - 1, nv);
                n--;
                break;
            }
    }
    const double *restrict px = w->px, *restrict py = w->py;
    double *restrict h = w->h, *restrict k = w->k;
#pragma omp simd
    for (size_t j = 0; j < n; j++) {
        h[j] = px[j] - x;
        k[j] = py[j] - y;
    }
    mls_info info;
    if (mls_weights(h, k, (int)n, mdx, mdy, w->c0, NULL, NULL, &info) != MLS_QUADRATIC)
        w->mls_fallbacks++;
    const double *restrict c0 = w->c0;
    for (int q = 0; q < nv; q++) {
        const double *restrict v = w->gv[q];
        double sum = 0;
#pragma omp simd reduction(+ : sum)
        for (size_t j = 0; j < n; j++)
            sum += c0[j] * v[j];
        out[q] = bound_fit(w, v, n, sum, margin);
    }
}

/* Open boundary face f whose velocity is zeroGradient at this step (the
 * boundary particle carries the owner's u_P, boundary_velocity): zeroGradient,
 * inletOutlet and pressureInletOutletVelocity while the last flux left,
 * outletInlet while it entered. */
static int open_zero_gradient(const sol_setup *su, const sol_state *st, ump_idx f)
{
    switch (su->u_kind[f - su->m->ninternal]) {
    case BU_OUTLET:
        return 1;
    case BU_INLETOUTLET:
    case BU_PRESSUREINLETOUTLET:
        return st->flux[f] >= 0;
    case BU_OUTLETINLET:
        return st->flux[f] < 0;
    default:
        return 0;
    }
}

/* Boundary face f's velocity is prescribed (fixed value, symmetry/slip):
 * Step 8 does not fit it. */
static inline int velocity_prescribed(const sol_setup *su, ump_idx f)
{
    int k = su->u_kind[f - su->m->ninternal];
    return k == BU_FIXED || k == BU_SYMMETRY;
}

/* u*_P of Eq. 36 at cell c's centroid (Eq. 32) from the gathered samples
 * and their gather_values (Step 8, and refill_up, which must give the same
 * bits). anisotropicCells: within its samples' range itself, not widened
 * by the margin (docs/METHOD.md section 8, "Walls in the correction" (d)):
 * next to the lid's corner of the graded cavities the fit sat at the
 * margin's -0.25 and 1.25 x the lid speed. Not on other meshes: the
 * elbow's outlets take u_P, and at deltaT/4 its p at t = 10 went from 0.70
 * to 5.5 against the converged flow. */
static void centroid_fit(const sol_setup *su, sol_work *w, size_t cnt, ump_idx c, double uv[2])
{
    const mesh2d *m = su->m;
    double cm = w->fit_margin < 0 || !su->set.anisotropic ? w->fit_margin : 0.0;
    mls_fit_values(w, cnt, m->cx[c], m->cy[c], mls_extent(su, m->dx[c]), mls_extent(su, m->dy[c]), -1, 2, cm,
                   uv);
}

/* MLS (Eq. 32) of the particle velocities (fu, fv) and the boundary
 * particles' (gu, gv) at the face centres, as fluxes u_f . A_f into flux[]
 * (faces whose velocity is prescribed excepted: the caller sets those), and,
 * when uc is given, at the centroids into uc, vc, in every cell or, when
 * only is given, in the cells it marks: one gather per cell serves its
 * centroid and the faces it owns. The centroid values are u*_P of Eq. 36,
 * which the step needs only in some cells (step8_mls_velocity): in every
 * cell at the steps that compute the fields written (they are the written
 * U), with refill u_P (the value of every refilled cell) and with
 * anisotropicCells (bound_cell_velocity); else in the owners of boundary
 * faces (su->uc_keep). A refill that falls back to u_P elsewhere fits it then,
 * from the particles at r* Step 8 had (refill_up). A centroid fit is a
 * third of this stage on quadrilaterals and two fifths on triangles (one
 * fit beside 2 and 1.5 owned faces). */
static void mls_to_mesh(sol *S, const double *fu, const double *fv, const double *gu, const double *gv,
                        double *flux, double *uc, double *vc, const unsigned char *only)
{
    const sol_setup *su = &S->su;
    const sol_state *st = &S->st;
    const mesh2d *m = su->m;
    ump_idx nc = m->ncells, ni = m->ninternal;
    const double *f[2] = {fu, fv}, *g[2] = {gu, gv};
#pragma omp parallel num_threads(S->nthreads)
    {
        sol_work *w = &S->work[thread_id()];
#pragma omp for schedule(dynamic, 64)
        for (ump_idx c = 0; c < nc; c++) {
            if (w->rc != UMP_OK)
                continue;
            size_t cnt;
            ump_err e;
            ump_status rc = gather_cell(su, st, w, c, &cnt, &e);
            if (rc != UMP_OK) {
                work_fail(w, rc, &e);
                continue;
            }
            double uv[2];
            gather_values(w, cnt, 2, f, g);
            if (uc && (!only || only[c])) {
                centroid_fit(su, w, cnt, c, uv);
                uc[c] = uv[0];
                vc[c] = uv[1];
            }
            for (ump_idx a = su->of_off[c]; a < su->of_off[c + 1]; a++) {
                ump_idx fa = su->of_face[a];
                if (fa >= ni && velocity_prescribed(su, fa))
                    continue;
                mls_fit_values(w, cnt, m->fx[fa], m->fy[fa], su->fsx[fa], su->fsy[fa], fa >= ni ? fa - ni : -1, 2,
                               w->fit_margin, uv);
                flux[fa] = (uv[0] * m->nx[fa] + uv[1] * m->ny[fa]) * m->len[fa]; /* u_f . A_f, Eq. 20 */
            }
        }
    }
}

/* Open faces whose velocity is zeroGradient at this step (Step 8 and the
 * interpolation error): their boundary particles take the mean increment
 * fu - u^n of the owner cell's particles, so they are at the level of the
 * particle field fu being fitted. If any face is such, returns 1 with the
 * boundary particles' values for that fit in gu, gv (the others' copied),
 * else 0 with gu, gv untouched: the fit takes bp's own. */
static int shift_open_boundary(const sol *S, const double *fu, const double *fv, double *gu, double *gv)
{
    const sol_setup *su = &S->su;
    const sol_state *st = &S->st;
    const mesh2d *m = su->m;
    const part_boundary *bp = &st->bp;
    int moved = 0;
    for (ump_idx b = 0; b < bp->n; b++) {
        ump_idx f = bp->face[b], o = m->owner[f];
        if (!open_zero_gradient(su, st, f))
            continue;
        if (!moved) { /* the first open face: the others keep their values */
            memcpy(gu, bp->u, (size_t)bp->n * sizeof *bp->u);
            memcpy(gv, bp->v, (size_t)bp->n * sizeof *bp->v);
            moved = 1;
        }
        double du = 0, dv = 0;
        ump_idx k0 = st->bins.off[o], k1 = st->bins.off[o + 1];
        for (ump_idx q = k0; q < k1; q++) {
            size_t i = st->bins.idx[q];
            du += fu[i] - st->P->u[i];
            dv += fv[i] - st->P->v[i];
        }
        if (k1 > k0) {
            gu[b] = bp->u[b] + du / (double)(k1 - k0);
            gv[b] = bp->v[b] + dv / (double)(k1 - k0);
        }
    }
    return moved;
}

/* u* at face centres (the fluxes u*_f . A_f of Eq. 20) and centroids, by
 * MLS from the particles at r*; faces whose velocity is prescribed take it
 * (symmetry planes and slip walls: no flux). */
static void step8_mls_velocity(sol *S)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    const mesh2d *m = su->m;
    ump_idx ni = m->ninternal;
    for (ump_idx fb = ni; fb < m->nfaces; fb++) {
        ump_idx b = fb - ni;
        if (su->u_kind[b] == BU_FIXED)
            st->flux[fb] = (st->ub[b] * m->nx[fb] + st->vb[b] * m->ny[fb]) * m->len[fb];
        else if (su->u_kind[b] == BU_SYMMETRY)
            st->flux[fb] = 0;
    }
    /* open faces whose velocity is zeroGradient at this step: their boundary
     * particles carry the owner's corrected u_P of the last step (set at the
     * start of the step), a value at the level of u^n; for this fit they
     * take the viscous increment u* - u^n of the owner cell's particles
     * too, so they are at the level of u* like the particles around them
     * (docs/METHOD.md section 8, "Open faces at the level of u*"). Without
     * it the flux out of a viscous channel lacked dt nu lap(u), and the PPE
     * left the last half cell before the outlet without its pressure drop
     * (Poiseuille, Re 10: p 0 instead of 0.06 in the last column). */
    st->bp_shifted = shift_open_boundary(S, st->us, st->vs, st->bpus, st->bpvs);
    /* u*_P in every cell, or only where the step needs it (mls_to_mesh) */
    st->uc_all = st->want_fields || su->set.refill != SOL_REFILL_CARRIED || su->set.anisotropic;
    mls_to_mesh(S, st->us, st->vs, st->bp_shifted ? st->bpus : st->bp.u, st->bp_shifted ? st->bpvs : st->bp.v,
                st->flux, st->usc, st->vsc, st->uc_all ? NULL : su->uc_keep);
}

/* The fixed face values of the pressure the step's PPE solves for: pi's
 * (st->pf), or with balanced buoyancy pi_d's, zero: pi_b takes pi's
 * (balance_buoyancy) */
static const double *step_face_pressure(const sol *S)
{
    return S->su.set.buoyant && S->su.set.balanced ? S->st.pf0 : S->st.pf;
}

/* The interpolation error of the particle-to-mesh map (docs/METHOD.md
 * section 8, "The pressure written"), for the pressure written: at the
 * start of the step, before the predictor, the particles at r^n carry u^n,
 * and the mesh has the corrected, divergence-free fluxes phi^n of the last
 * step. eps_f = MLS(u^n at r^n)_f - phi^n_f is what Step 8 would add to
 * the fluxes if nothing had changed: the MLS error, the values the last
 * management gave new particles, the MLS derivative of Eq. 10 that is not
 * the PPE's face gradient. Step 9's fluxes u*_f = phi^n_f + [MLS(u*, r*)
 * - MLS(u^n, r^n)]_f + eps_f, so its pressure is p = p_d + q, p_d from the
 * physical change of the step (advection and viscosity) and q the
 * potential of D eps / dt, which grows as 1/dt and is no pressure of the
 * flow. Faces whose velocity is prescribed: eps = 0 (their change of value
 * in time is physical).
 * pressureTheta th > 0: the particles start the predictor with u^n - th dt
 * grad p^{n-1/2} (path_pressure_kick; the MLS derivative, left in us, vs)
 * and Step 9 adds th dt G p^{n-1/2} to the fluxes (the PPE's face
 * gradient), so eps_f = MLS(u^n - th dt grad p^{n-1/2})_f - (phi^n_f - th
 * dt (G p^{n-1/2})_f). Without the kick's two gradients in eps their
 * difference stayed in the pressure written, and through p^{n-1/2} in
 * the next step's, growing it by 1/(1 - th): Taylor-Green on 1 600 cells,
 * pressure error 0.110 against 0.035 at th = 0 (README, "Settings for
 * flows without walls"). x0, y0 are scratch until Step 7, gflux until
 * Step 9. */
static void interpolation_error(sol *S, double dt)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    const mesh2d *m = su->m;
    part_set *P = st->P;
    ump_idx ni = m->ninternal;
    double th = su->set.p_theta;
    const double *fu = P->u, *fv = P->v;
    if (th > 0) {
        size_t n = P->n;
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
        for (size_t i = 0; i < n; i++) {
            st->x0[i] = P->u[i] - th * dt * st->us[i];
            st->y0[i] = P->v[i] - th * dt * st->vs[i];
        }
        fu = st->x0;
        fv = st->y0;
        ppe_face_gradient_flux(su->pe, st->pold, step_face_pressure(S), st->gflux);
    }
    /* open zero-gradient faces: their boundary particles with the kick, as
     * Step 8 gives them the increment of u* */
    int moved = th > 0 && shift_open_boundary(S, fu, fv, st->bpue, st->bpve);
    mls_to_mesh(S, fu, fv, moved ? st->bpue : st->bp.u, moved ? st->bpve : st->bp.v, st->fluxe, NULL, NULL, NULL);
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
    for (ump_idx f = 0; f < m->nfaces; f++) {
        double phi = th > 0 ? st->flux[f] - th * dt * st->gflux[f] : st->flux[f];
        st->fluxe[f] = f >= ni && velocity_prescribed(su, f) ? 0.0 : st->fluxe[f] - phi;
    }
}

/* Balanced buoyancy (docs/METHOD.md section 6; the paper puts the whole
 * Boussinesq source of Eq. 4 into the predictor). The pressure is split as
 * pi = pi_b + pi_d: pi_b is the part that balances the buoyancy b =
 * -beta (T^n - TRef) g, from the PPE's own matrix (Eqs. 20, 25) with the
 * face fluxes of the hydrostatic quadratic (interior and fixed-pressure
 * faces, below; zero where the velocity is prescribed, as u* there) and
 * pi's fixed face values (pi_d's are then zero, step_face_pressure); the
 * predictor then carries b - grad pi_b as R, what pi_b leaves of b at the
 * faces reconstructed in the cells and interpolated to the particles at
 * r^n (below), and the step's PPE gives pi_d, which the correction applies
 * as usual. At rest in a stable stratification R vanishes (exactly for
 * linear T on any mesh, for any profile along g on orthogonal meshes), so
 * the viscous predictor no longer damps the buoyancy near walls without
 * the pressure that balances it (the O(dt) spurious velocity of the source
 * splitting). b_f uses T_f, the mean of the two cells' T_P + grad T_P .
 * (x_f - x_P) (the LS gradient of Eq. 26; exact for linear T), on
 * fixed-pressure boundary faces the face's boundary-particle temperature.
 * (The MLS value of the particle temperatures at the face, as u*_f in
 * Step 8, was tried and measured worse: the annulus tutorial's Nu 4.12
 * instead of 4.20, OpenFOAM 4.90.) One more solve per step with the
 * factorization made at start-up. */
static ump_status balance_buoyancy(sol *S, double dt, sol_stats *stats, ump_err *err)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    const mesh2d *m = su->m;
    const sol_settings *set = &su->set;
    ump_idx ni = m->ninternal;
    double gx = set->g[m->ax[0]], gy = set->g[m->ax[1]], beta = set->beta;
    /* the gradient of b = -beta (T - TRef) g, symmetrised: pi_b's Hessian
     * where b is a gradient (a stratification: grad T along g) */
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
    for (ump_idx c = 0; c < m->ncells; c++) {
        st->hxx[c] = -beta * gx * st->gtx[c];
        st->hxy[c] = -0.5 * beta * (gx * st->gty[c] + gy * st->gtx[c]);
        st->hyy[c] = -beta * gy * st->gty[c];
    }
    /* The face flux is Eq. 25 applied to the quadratic with b_f and that
     * Hessian at x_f, not b_f . A_f: Eq. 25's two-point difference is the
     * derivative at the middle of A'B', not at the face, and its
     * non-orthogonal terms use LS gradients inexact for quadratics. So the
     * fluxes of a linear T along g are exactly those of the hydrostatic
     * pressure and the solve returns it: on cells graded 200:1, b_f . A_f
     * left 4e-5 m/s after one step of a fluid at rest (README, "Balanced
     * buoyancy on any mesh"). On a fixed-pressure face pi_b takes pi's
     * value (pi_d zero, step_face_pressure) and the flux is Eq. 25's
     * Dirichlet rule for the same quadratic, so at rest the hydrostatic
     * pressure meets an opening exactly. */
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
    for (ump_idx f = 0; f < m->nfaces; f++) {
        double Tf, H[3];
        ump_idx o = m->owner[f];
        if (f < ni) {
            ump_idx q = m->neigh[f];
            double sx = m->sepx ? m->sepx[f] : 0, sy = m->sepy ? m->sepy[f] : 0;
            double To = st->Tc[o] + st->gtx[o] * (m->fx[f] - m->cx[o]) + st->gty[o] * (m->fy[f] - m->cy[o]);
            double Tq = st->Tc[q] + st->gtx[q] * (m->fx[f] + sx - m->cx[q]) +
                        st->gty[q] * (m->fy[f] + sy - m->cy[q]);
            Tf = 0.5 * (To + Tq);
            H[0] = 0.5 * (st->hxx[o] + st->hxx[q]);
            H[1] = 0.5 * (st->hxy[o] + st->hxy[q]);
            H[2] = 0.5 * (st->hyy[o] + st->hyy[q]);
        } else if (su->p_dir[f]) {
            Tf = st->bp.T[f - ni];
            H[0] = st->hxx[o], H[1] = st->hxy[o], H[2] = st->hyy[o];
        } else {
            st->fluxb[f] = 0;
            continue;
        }
        double b = -beta * (Tf - set->t_ref); /* Eq. 4 per unit mass */
        double a[2] = {b * gx, b * gy};
        st->fluxb[f] = dt * ppe_face_quadratic_flux(su->pe, f, a, H);
    }
    UMP_CALL(ppe_solve(su->pe, st->fluxb, dt, st->pf, st->pib, err));
    if (su->need_ref) { /* the reference level belongs to pi_d */
        double r = st->pib[set->p_ref_cell] - set->p_ref_value;
        for (ump_idx c = 0; c < m->ncells; c++)
            st->pib[c] -= r;
    }
    /* What pi_b leaves of the buoyancy at each face, r_f = b_f-flux / dt -
     * grad pi_b . A_f (Eq. 25, the PPE's own face operator), reconstructed
     * in the cells: the particles' force. The balance is then exact face by
     * face where it holds in the PPE (a stratification along g of any
     * profile on an orthogonal mesh, a linear one on any mesh), not only up
     * to the difference of a particle's b and an MLS gradient of pi_b: that
     * difference, one-sided next to a wall, moved a box stratified from T
     * = 0.5 at 7.6e-5 m/s after 5 s (README, "Stratified rest while T
     * changes"). Walls (no flux of pi_b's): r_f = 0 */
    ppe_face_gradient_flux(su->pe, st->pib, st->pf, st->gflux);
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
    for (ump_idx c = 0; c < m->ncells; c++) {
        double bx = 0, by = 0;
        for (ump_idx k = m->cell_face_off[c]; k < m->cell_face_off[c + 1]; k++) {
            ump_idx f = m->cell_faces[k];
            if (f >= ni && !su->p_dir[f])
                continue;
            double r = st->fluxb[f] / dt - st->gflux[f];
            bx += m->nx[f] * r;
            by += m->ny[f] * r;
        }
        const double *ri = su->rinv + 3 * (size_t)c;
        st->rbx[c] = ri[0] * bx + ri[1] * by;
        st->rby[c] = ri[1] * bx + ri[2] * by;
    }
    stats->mls_fallbacks += (int)particle_cell_vector(S, st->rbx, st->rby, st->gpx, st->gpy, -1.0);
    return UMP_OK;
}

/* ---- Step 9: the pressure equation ----------------------------------------- */

/* No face fixes the pressure (su->need_ref): the PPE is a pure Neumann
 * problem, solvable only if the boundary fluxes sum to zero; a reference
 * cell would otherwise absorb their sum as a source. Faces of unfixed
 * velocity are refused with such a mesh (sol_create), so every boundary
 * flux is prescribed here: as OpenFOAM's adjustPhi, with nothing to adjust,
 * an inflow that differs from the prescribed outflow by more than 1e-8 of
 * the internal faces' total flux stops the run with OpenFOAM's message (an
 * inflow into a box whose other faces are walls). Serial over the faces,
 * in face order: the sums do not depend on the threads. */
static ump_status check_flux_balance(const sol *S, ump_err *err)
{
    const sol_setup *su = &S->su;
    const sol_state *st = &S->st;
    const mesh2d *m = su->m;
    double mass_in = 0, mass_out = 0, total = 1e-300; /* VSMALL */
    for (ump_idx f = 0; f < m->ninternal; f++)
        total += fabs(st->flux[f]);
    for (ump_idx f = m->ninternal; f < m->nfaces; f++) {
        double phi = st->flux[f];
        if (phi < 0)
            mass_in -= phi;
        else
            mass_out += phi;
    }
    if (fabs(mass_out - mass_in) / total > 1e-8)
        return UMP_FAIL(err, UMP_ERR_INPUT,
                        "continuity error cannot be removed by adjusting the outflow: no patch fixes the pressure, "
                        "and every boundary velocity is fixed. Check the velocity boundary conditions (fix the "
                        "pressure on an outlet). Total flux %g, specified mass inflow %g, specified mass outflow "
                        "%g (OpenFOAM's adjustPhi)", total, mass_in, mass_out);
    return UMP_OK;
}

static ump_status step9_pressure(sol *S, double dt, ump_err *err)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    const mesh2d *m = su->m;
    double th = su->set.p_theta;
    if (su->need_ref)
        UMP_CALL(check_flux_balance(S, err));
    if (th > 0) {
        /* pressureTheta: the predicted particles carry -th dt grad p^{n-1/2}
         * (path_pressure_kick); adding th dt G p^{n-1/2} to the fluxes makes
         * the solve return p^{n+1/2} itself, with its own boundary values
         * and reference, while the correction applies only the increment
         * phi = p^{n+1/2} - th p^{n-1/2} */
        ppe_face_gradient_flux(su->pe, st->pold, step_face_pressure(S), st->gflux);
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
        for (ump_idx f = 0; f < m->nfaces; f++)
            st->flux[f] += th * dt * st->gflux[f];
    }
    /* Eqs. 20, 22-25, one solve with the factorization made at start-up */
    UMP_CALL(ppe_solve(su->pe, st->flux, dt, step_face_pressure(S), st->p, err));
    ppe_face_gradient_flux(su->pe, st->p, step_face_pressure(S), st->gflux);
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
    for (ump_idx f = 0; f < m->nfaces; f++)
        st->flux[f] -= dt * st->gflux[f]; /* corrected face flux u^{n+1}_f . A_f */
    return UMP_OK;
}

/* ---- Step 10: correction ----------------------------------------------------- */

/* q_transpose (interpolationError transpose; on with anisotropicCells by
 * default): the interpolation error's pressure q by the transpose of the
 * fits (docs/METHOD.md section 8, "Walls in the correction" (f)).
 * Step 9's p = p_d + q, q the potential of
 * D eps / dt (interpolation_error). Eq. 10 gives every particle the whole
 * -dt grad q at its position, yet a particle that hardly enters its cells'
 * face fits of Step 8 hardly changes the fluxes that q corrects, so the
 * same kick returns at the next step: one particle of a large cell beside
 * thin ones gained 0.002 per step and reached twice the lid speed at
 * deltaT 0.00002 (README, "Smaller steps on the 8x8 graded cavity"). Here
 * each particle j gets q as it enters the fits, the transpose of Step 8's
 * interpolation:
 *     du_j = -(sum_f |c_fj| n_f n_f^T + F I)^-1 sum_f c_fj n_f dt (dq/dn)_f,
 * c_fj particle j's coefficient in face f's fit (Eq. 32 at r*, where the
 * particles still are), (dq/dn)_f the PPE's face gradient (Eq. 25), F =
 * SOL_TQ_FLOOR. The MLS coefficients sum to 1, so a uniform face
 * correction is returned whole. Deterministic with any thread count: the
 * fits (parallel over cells) store their coefficients in per-cell slots,
 * summed into the particles in cell order. Result in st->qx, st->qy. */
static ump_status transpose_q(sol *S, double dt, ump_err *err)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    const mesh2d *m = su->m;
    ump_idx nc = m->ncells, ni = m->ninternal;
    size_t n = st->P->n;
    ppe_face_gradient_flux(su->pe, st->q, st->fz, st->gq);
    /* slots: a cell's fluid samples times the faces it fits */
    st->tq_off[0] = 0;
    for (ump_idx c = 0; c < nc; c++)
        st->tq_off[c + 1] = st->tq_off[c] + (size_t)stencil_particles(su, &st->bins, c) *
                                                (size_t)(su->of_off[c + 1] - su->of_off[c]);
    size_t need = st->tq_off[nc];
    if (need > st->tq_cap || !st->tq) {
        size_t cap = need + need / 2 + 1024;
        struct tq_entry *q = ump_realloc_array(st->tq, cap, sizeof *q);
        if (!q)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "correction: out of memory (%zu fit entries)", cap);
        st->tq = q;
        st->tq_cap = cap;
    }
#pragma omp parallel num_threads(S->nthreads)
    {
        sol_work *w = &S->work[thread_id()];
#pragma omp for schedule(dynamic, 64)
        for (ump_idx c = 0; c < nc; c++) {
            st->tq_len[c] = 0;
            if (w->rc != UMP_OK)
                continue;
            size_t cnt;
            ump_err e;
            ump_status rc = gather_cell(su, st, w, c, &cnt, &e);
            if (rc != UMP_OK) {
                work_fail(w, rc, &e);
                continue;
            }
            size_t pos = st->tq_off[c];
            /* the fits of mls_to_mesh: the same faces, samples and supports */
            for (ump_idx a = su->of_off[c]; a < su->of_off[c + 1]; a++) {
                ump_idx fa = su->of_face[a];
                if (fa >= ni && velocity_prescribed(su, fa))
                    continue;
                int nn = offsets(w, cnt, m->fx[fa], m->fy[fa], fa >= ni ? fa - ni : -1);
                mls_weights(w->h, w->k, nn, su->fsx[fa], su->fsy[fa], w->c0, NULL, NULL, NULL);
                for (int j = 0; j < nn; j++)
                    if (w->sref[j] >= 0) /* fluid particles only */
                        st->tq[pos++] = (struct tq_entry){w->sref[j], fa, w->c0[j]};
            }
            st->tq_len[c] = (ump_idx)(pos - st->tq_off[c]);
        }
    }
    UMP_CALL(work_collect(S, NULL, err));
    for (size_t i = 0; i < n; i++)
        st->qa[i] = st->qb[i] = st->qc[i] = st->qx[i] = st->qy[i] = 0;
    for (ump_idx c = 0; c < nc; c++) /* in cell order: the same sums with any thread count */
        for (size_t e = st->tq_off[c]; e < st->tq_off[c] + (size_t)st->tq_len[c]; e++) {
            ump_idx j = st->tq[e].ref, f = st->tq[e].face;
            double cj = st->tq[e].c, ac = fabs(cj), nx = m->nx[f], ny = m->ny[f];
            double g = dt * st->gq[f] / m->len[f]; /* dt dq/dn at the face */
            st->qa[j] += ac * nx * nx;
            st->qb[j] += ac * nx * ny;
            st->qc[j] += ac * ny * ny;
            st->qx[j] += cj * nx * g;
            st->qy[j] += cj * ny * g;
        }
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
    for (size_t i = 0; i < n; i++) {
        double a = st->qa[i] + SOL_TQ_FLOOR, b = st->qb[i], d = st->qc[i] + SOL_TQ_FLOOR;
        double det = a * d - b * b, bx = st->qx[i], by = st->qy[i];
        st->qx[i] = -(d * bx - b * by) / det;
        st->qy[i] = -(a * by - b * bx) / det;
    }
    return UMP_OK;
}

/* anisotropicCells with boundedFits: the mesh velocity u_P of Eq. 36
 * within the range of the corrected velocities of its stencil's samples
 * (fluid particles and boundary particles), per component, counted as a
 * bounded value (docs/METHOD.md section 8, "Walls in the correction" (f)).
 * In an empty thin cell at the lid both terms of u*_P - dt grad p_P are
 * large and cancel imperfectly; with transpose_q the particles no longer
 * carry grad q whole and that cell read 1.14 x the lid speed while every
 * particle stayed below it (48^2 cavity graded (1000 1 1)). */
static ump_status bound_cell_velocity(sol *S, sol_stats *stats, ump_err *err)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    ump_idx nc = su->m->ncells;
    const double *f[2] = {st->P->u, st->P->v}, *g[2] = {st->bp.u, st->bp.v};
    double *out[2] = {st->uc, st->vc};
#pragma omp parallel num_threads(S->nthreads)
    {
        sol_work *w = &S->work[thread_id()];
        double margin = w->fit_margin < 0 ? w->fit_margin : 0.0; /* boundedFits no: off */
#pragma omp for schedule(dynamic, 64)
        for (ump_idx c = 0; c < nc; c++) {
            if (w->rc != UMP_OK)
                continue;
            size_t cnt;
            ump_err e;
            ump_status rc = gather_cell(su, st, w, c, &cnt, &e);
            if (rc != UMP_OK) {
                work_fail(w, rc, &e);
                continue;
            }
            gather_values(w, cnt, 2, f, g);
            for (int q = 0; q < 2; q++)
                out[q][c] = bound_fit(w, w->gv[q], cnt, out[q][c], margin);
        }
    }
    return work_collect(S, stats, err);
}

static ump_status step10_correct(sol *S, double dt, sol_stats *stats, ump_err *err)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    const mesh2d *m = su->m;
    part_set *P = st->P;
    ump_idx nc = m->ncells;
    size_t n = P->n;
    /* u^{n+1} = u* - dt grad p (Eq. 10), grad p at r* by the MLS
     * derivative (Eqs. 33-34) of the centroid pressures of the particle's
     * cell and its N2 stencil (balanced buoyancy: p = pi_d, the part the
     * predictor has not applied yet); gpx/gpy are free after the predictor.
     * pressureTheta th > 0: the increment phi = p - th p^{n-1/2}, the part
     * path_pressure_kick has not applied */
    double th = su->set.p_theta;
    const double *phi = st->p, *pfs = step_face_pressure(S), *phif = pfs;
    if (th > 0) {
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
        for (ump_idx c = 0; c < nc; c++)
            st->pold[c] = st->p[c] - th * st->pold[c];
        for (ump_idx f = m->ninternal; f < m->nfaces; f++)
            st->pfphi[f] = pfs[f] - th * st->pfprev[f];
        phi = st->pold;
        phif = st->pfphi;
    }
    int walls = walls_zero_gradient(su);
    /* q_transpose: Eq. 10 with p_d, and q by the transpose of the fits */
    int tq = su->set.q_transpose && st->split;
    const double *pg = phi;
    if (tq) {
        UMP_CALL(transpose_q(S, dt, err));
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
        for (ump_idx c = 0; c < nc; c++)
            st->pd[c] = phi[c] - st->q[c];
        pg = st->pd;
    }
    stats->mls_fallbacks += (int)particle_pressure_gradient(S, pg, phif, st->gpx, st->gpy, walls);
    /* walls: the correction damped as the predictor's row would damp it
     * next to a no-slip wall (st->wdamp, step6_rows; docs/METHOD.md section
     * 8, "Walls in the correction" (e)), q's part too */
    const double *kw = walls ? st->wdamp : NULL;
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
    for (size_t i = 0; i < n; i++) {
        double k = kw ? dt * kw[i] : dt;
        P->u[i] = st->us[i] - k * st->gpx[i];
        P->v[i] = st->vs[i] - k * st->gpy[i];
        if (tq) {
            double kq = kw ? kw[i] : 1.0;
            P->u[i] += kq * st->qx[i];
            P->v[i] += kq * st->qy[i];
        }
    }
    /* r* and its bins (Step 8's) are kept for refill_up */
    if (!st->uc_all) {
        memcpy(st->xs, P->x, n * sizeof *st->xs);
        memcpy(st->ys, P->y, n * sizeof *st->ys);
    }
    /* r^{n+1} = r^n + dt u^{n+1} (Eq. 7) */
    move_particles(S, P->u, P->v, dt, &stats->walled);
    if (th > 0) /* the face values that belong to p^{n+1/2}, the next step's pold */
        memcpy(st->pfprev, pfs, (size_t)m->nfaces * sizeof *st->pf);
    /* mesh velocity, Eq. 36, with the LS gradient of Eq. 26; with
     * anisotropicCells its walls carry the owner's value (su->gw,
     * docs/METHOD.md section 8, "Walls in the correction"): in a cell 6e-5
     * wide at a wall the gradient of the neighbours alone is the bulk's,
     * and u_P = u*_P - dt grad p_P left the wall at 1.14 x the lid speed
     * where u*_P = 0 */
    lsq_gradient(walls_zero_gradient(su) ? su->gw : su->g, phi, st->gx, st->gy);
    int bal = su->set.buoyant && su->set.balanced;
    /* pressureTheta: pi_d, the next step's pold (path_pressure_kick), whose
     * face values are step_face_pressure's (pfprev); p - pi_b there would
     * mix in the change of pi_b from this step to the next */
    int keep = bal && th > 0;
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
    for (ump_idx c = 0; c < nc; c++) {
        st->uc[c] = st->usc[c] - dt * st->gx[c];
        st->vc[c] = st->vsc[c] - dt * st->gy[c];
        if (keep)
            st->pold[c] = st->p[c];
        if (bal)
            st->p[c] += st->pib[c]; /* pi = pi_b + pi_d */
    }
    st->pold_pd = keep;
    if (tq)
        UMP_CALL(bound_cell_velocity(S, stats, err));
    return UMP_OK;
}

/* ---- Step 11: removal, mesh temperature, management ---------------------------- */

/* Refill values that keep carried velocities (docs/METHOD.md section 8,
 * "Refill"). [NSH16] Section 3.2.2.2 gives a particle added at the centroid
 * x_c of an empty cell the mesh velocity u_P of Eq. 36, an MLS fit: each
 * refill replaces a carried value by a smoothed one (the quadratic fit
 * lowers the peaks of a sine by O((k r)^4)), and at 5 % of the cells per
 * step this decayed the Taylor-Green vortex by 2.5 % at t = 5 (README,
 * "Refill"). Here the new particle takes, from each of the K fluid
 * particles j nearest x_c in the cell's stencil (before the deletion of
 * the step, so a surplus particle about to be deleted lends its value),
 * its carried value moved to x_c by the MLS increment of the others,
 * weighted by 1/|x_j - x_c|^2:
 *     u_c = sum_j w_j [ u_j + f_j(x_c) - f_j(x_j) ] / sum_j w_j,
 * f_j the MLS fit (Eqs. 28-35) of the stencil's samples without j. The fit
 * without j keeps j's own value out of the increment (with j in it, the
 * near-singular weight of Eq. 35 at x_j would return u_j). The values are
 * computed for the cells the deletion leaves empty (UMPPM may delete the
 * only particle of a cell, a neighbour's kept particle being too close),
 * from every particle before it (part_manage_refill). Cells whose stencil
 * has no fluid particle keep u_P. T likewise. The weight: an estimate
 * from a farther particle carries more noise (u_j's, and that of the
 * samples nearest x_j and x_c, where Eq. 35's weight is near-singular);
 * with equal weights over 5 particles the Re 1000 cavity (64^2 quads)
 * was 2.1x farther from Ghia than with 1/d^2 (README). */
static int refill_value(const sol_setup *su, sol_work *w, size_t cnt, ump_idx c, int nv, double *out)
{
    const mesh2d *m = su->m;
    enum { KMAX = 16 };
    int K = su->set.refill_k < KMAX ? su->set.refill_k : KMAX, nk = 0;
    size_t cand[KMAX];
    double cd[KMAX];
    double xc = m->cx[c], yc = m->cy[c];
    /* the K nearest fluid samples, by distance, then gathered order */
    for (size_t j = 0; j < cnt; j++) {
        if (w->ref[j] < 0)
            continue;
        double dx = w->px[j] - xc, dy = w->py[j] - yc, d = dx * dx + dy * dy;
        int q = nk < K ? nk++ : K;
        if (q == K) {
            if (!(d < cd[K - 1]))
                continue;
            q = K - 1;
        }
        for (; q > 0 && cd[q - 1] > d; q--) {
            cd[q] = cd[q - 1];
            cand[q] = cand[q - 1];
        }
        cd[q] = d;
        cand[q] = j;
    }
    if (nk == 0 || cnt < 2)
        return 0;
    /* each candidate's fits f_j(x_c) and f_j(x_j): its estimate is
     * u_j + f_j(x_c) - f_j(x_j) */
    double fc[KMAX][SOL_MAX_VALUES], fjj[KMAX][SOL_MAX_VALUES];
    size_t e = cnt - 1;
    for (int a = 0; a < nk; a++) {
        /* j to the end: the fits use the first cnt - 1 samples */
        size_t j = cand[a];
        sample_swap(w, j, e, nv);
        double xj = w->px[e], yj = w->py[e];
        for (int at = 0; at < 2; at++) { /* f_j(x_c), f_j(x_j) */
            double x = at ? xj : xc, y = at ? yj : yc;
            const double *restrict px = w->px, *restrict py = w->py;
            double *restrict h = w->h, *restrict k = w->k;
#pragma omp simd
            for (size_t i = 0; i < e; i++) {
                h[i] = px[i] - x;
                k[i] = py[i] - y;
            }
            if (mls_weights(w->h, w->k, (int)e, mls_extent(su, m->dx[c]), mls_extent(su, m->dy[c]), w->c0, NULL, NULL,
                            NULL) != MLS_QUADRATIC)
                w->mls_fallbacks++;
            for (int q = 0; q < nv; q++) {
                double f = 0;
                for (size_t i = 0; i < e; i++)
                    f += w->c0[i] * w->gv[q][i];
                (at ? fjj : fc)[a][q] = f;
            }
        }
        sample_swap(w, j, e, nv); /* back: the order of later candidates */
    }
    /* refillWeights increment: w_j = 1 / (|inc_j|^2 + (d_j / l)^2 eta^2),
     * the inverse of a modelled variance. The increment's error grows with
     * the increment (the fit's error in the gradient times the distance),
     * and a particle's own noise with its distance (the note above), eta =
     * SOL_REFILL_NOISE x the speed range of the stencil's samples, l^2 the
     * cell's area. Where the field is linear and isotropic both terms are
     * about |grad u|^2 d^2 and this is the distance weight; in a boundary
     * layer a particle across the layer has a large increment and lends
     * little, one along the flow lends most. On the Re 1000 40^2 cavity the
     * 1/d^2 weights thickened the lid's layer (its second and third rows
     * 3-10 % too fast); refilled with the converged flow's values instead,
     * the field's error fell from 0.0154 to 0.0047, the mesh's own floor.
     * refillWeights distance: 1/d^2, and also where anisotropicCells is on:
     * on cells stretched 15 491:1 the increment weights took the 8x8
     * graded cavity from 0.38 to 0.52 from the converged flow */
    int by_inc = su->set.refill_increment && !su->set.anisotropic;
    double eta2 = 0;
    if (by_inc) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t j = 0; j < cnt; j++) {
            double sp = hypot(w->gv[0][j], w->gv[1][j]);
            lo = sp < lo ? sp : lo;
            hi = sp > hi ? sp : hi;
        }
        eta2 = SOL_REFILL_NOISE * (hi - lo);
        eta2 *= eta2;
    }
    double sum[SOL_MAX_VALUES] = {0}, wsum = 0;
    for (int a = 0; a < nk; a++) {
        if (by_inc) {
            double du = fc[a][0] - fjj[a][0], dv = fc[a][1] - fjj[a][1];
            double wa = 1 / (du * du + dv * dv + cd[a] / m->area[c] * eta2 + 1e-300);
            wsum += wa;
            for (int q = 0; q < nv; q++)
                sum[q] += wa * (w->gv[q][cand[a]] + (fc[a][q] - fjj[a][q]));
        } else { /* 1/d^2, each term added in the order of its first
                  * version, so its results stay the same to the bit */
            double wa = 1 / (cd[a] + 1e-6 * m->area[c]);
            wsum += wa;
            for (int q = 0; q < nv; q++) {
                sum[q] += wa * fc[a][q];
                sum[q] += -wa * fjj[a][q];
                sum[q] += wa * w->gv[q][cand[a]];
            }
        }
    }
    /* anisotropicCells: within the samples' range itself, as the centroid
     * fit u*_P (centroid_fit; docs/METHOD.md section 8, "Walls in the
     * correction" (d)): with the margin's quarter the refills below the lid
     * of the 8x8 cavity graded toward all walls carried 1.19-1.27 x the lid
     * speed, 38 particles above 1.04 in 100 steps of the 10 000:1 mesh,
     * one after this (README, "Refills within their samples' range") */
    double margin = su->set.anisotropic && w->fit_margin > 0 ? 0.0 : w->fit_margin;
    for (int q = 0; q < nv; q++)
        out[q] = bound_fit(w, w->gv[q], cnt, sum[q] / wsum, margin);
    return 1;
}

typedef struct refill_ctx {
    sol *S;
    sol_stats *stats;
    double dt;
} refill_ctx;

/* u_P of Eq. 36 in cell c (u*_P - dt grad p_P), for a refill that falls
 * back to it in a cell Step 8 did not fit (mls_to_mesh): the same fit from
 * the same samples, the particles at r* (st->xs, ys in st->bins_star, the
 * numbering before Step 11's compaction, as st->us, vs) and the boundary
 * particles with Step 8's values, so the value is the one Step 8 would
 * have given, to the bit, and the solution does not depend on the steps
 * that compute the fields written. */
static ump_status refill_up(const sol *S, sol_work *w, ump_idx c, double dt, double *u, double *v, ump_err *err)
{
    const sol_setup *su = &S->su;
    const sol_state *st = &S->st;
    if (st->uc_all || su->uc_keep[c]) {
        *u = st->uc[c];
        *v = st->vc[c];
        return UMP_OK;
    }
    size_t cnt;
    UMP_CALL(gather_from(su, st->xs, st->ys, &st->bins_star, &st->bp, w, c, &cnt, err));
    const double *f[2] = {st->us, st->vs};
    const double *g[2] = {st->bp_shifted ? st->bpus : st->bp.u, st->bp_shifted ? st->bpvs : st->bp.v};
    gather_values(w, cnt, 2, f, g);
    double uv[2];
    centroid_fit(su, w, cnt, c, uv);
    *u = uv[0] - dt * st->gx[c]; /* as step10_correct */
    *v = uv[1] - dt * st->gy[c];
    return UMP_OK;
}

/* part_refill_fn of part_manage_refill: values for the cells that no
 * surviving particle occupies, from every particle before the deletion. */
static ump_status refill_carried(void *vctx, const unsigned char *alive, ump_err *err)
{
    refill_ctx *rc0 = vctx;
    sol *S = rc0->S;
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    const mesh2d *m = su->m;
    const part_set *P = st->P;
    ump_idx ne = 0;
    for (ump_idx c = 0; c < m->ncells; c++) {
        int occupied = 0;
        for (ump_idx k = st->bins.off[c]; k < st->bins.off[c + 1] && !occupied; k++)
            occupied = alive[st->bins.idx[k]] != 0;
        if (!occupied)
            st->empty[ne++] = c;
    }
    int nv = su->set.buoyant ? 3 : 2;
    const double *f[3] = {P->u, P->v, P->T}, *g[3] = {st->bp.u, st->bp.v, st->bp.T};
#pragma omp parallel num_threads(S->nthreads)
    {
        sol_work *w = &S->work[thread_id()];
#pragma omp for schedule(dynamic, 16)
        for (ump_idx a = 0; a < ne; a++) {
            if (w->rc != UMP_OK)
                continue;
            ump_idx c = st->empty[a];
            size_t cnt;
            ump_err e;
            ump_status rc = gather_cell(su, st, w, c, &cnt, &e);
            if (rc != UMP_OK) {
                work_fail(w, rc, &e);
                continue;
            }
            gather_values(w, cnt, nv, f, g);
            double o[SOL_MAX_VALUES];
            if (!refill_value(su, w, cnt, c, nv, o)) {
                if ((rc = refill_up(S, w, c, rc0->dt, &o[0], &o[1], &e)) != UMP_OK) {
                    work_fail(w, rc, &e);
                    continue;
                }
                o[2] = nv > 2 ? st->Tc[c] : 0;
            }
            st->fu[c] = o[0];
            st->fv[c] = o[1];
            if (nv > 2)
                st->fT[c] = o[2];
        }
    }
    return work_collect(S, rc0->stats, err);
}

static ump_status step11_manage(sol *S, double dt, sol_stats *stats, ump_err *err)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    const mesh2d *m = su->m;
    part_set *P = st->P;
    size_t before = P->n;
    part_compact(P, st->keep);
    stats->left = before - P->n;
    /* Step 8's bins (r*) to bins_star, for refill_up; the new ones are
     * built in the other's storage */
    part_bins t = st->bins;
    st->bins = st->bins_star;
    st->bins_star = t;
    UMP_CALL(part_bins_build(&st->bins, m, P, err));
    if (su->set.buoyant) {
        /* Step 10: mesh temperature T_P, MLS of the particle temperatures */
        const double *f[1] = {P->T}, *g[1] = {st->bp.T};
#pragma omp parallel num_threads(S->nthreads)
        {
            sol_work *w = &S->work[thread_id()];
#pragma omp for schedule(dynamic, 64)
            for (ump_idx c = 0; c < m->ncells; c++) {
                if (w->rc != UMP_OK)
                    continue;
                size_t cnt;
                ump_err e;
                ump_status rc = gather_cell(su, st, w, c, &cnt, &e);
                if (rc != UMP_OK) {
                    work_fail(w, rc, &e);
                    continue;
                }
                gather_values(w, cnt, 1, f, g);
                mls_fit_values(w, cnt, m->cx[c], m->cy[c], mls_extent(su, m->dx[c]), mls_extent(su, m->dy[c]), -1, 1,
                               w->fit_margin, &st->Tc[c]);
            }
        }
        UMP_CALL(work_collect(S, stats, err));
    }
    const double *fu = st->uc, *fv = st->vc, *fT = st->Tc;
    refill_ctx rctx = {S, stats, dt};
    int carried = su->set.refill == SOL_REFILL_CARRIED;
    if (carried) {
        fu = st->fu;
        fv = st->fv;
        fT = su->set.buoyant ? st->fT : NULL;
    }
    part_manage_stats ms;
    UMP_CALL(part_manage_refill(P, &st->bins, m, su->set.variant, su->set.alpha, carried ? refill_carried : NULL,
                                &rctx, fu, fv, fT, &ms, err));
    stats->added = ms.added;
    stats->deleted = ms.deleted_close + ms.deleted_extra;
    stats->np = P->n;
    st->steps++;
    int every = su->set.sort_interval;
    if (every > 0 && st->steps % every == 0)
        UMP_CALL(part_sort_by_cell(P, &st->bins, m, err));
    return grow_particle_work(st, P->n, err);
}

/* ---- diagnostics ------------------------------------------------------------- */

/* Per-cell flux sums (continuity) and |flux| sums (Courant) in parallel,
 * their totals serially in cell order. */
static void continuity_courant(sol *S, double dt, sol_stats *stats)
{
    const mesh2d *m = S->su.m;
    sol_state *st = &S->st;
    ump_idx nc = m->ncells;
    double mx = 0, comax = 0;
    double *gf = st->gflux; /* free after Step 9: per-cell sum |phi| */
#pragma omp parallel for schedule(static) num_threads(S->nthreads) reduction(max : mx, comax)
    for (ump_idx c = 0; c < nc; c++) {
        double d = 0, a = 0;
        for (ump_idx k = m->cell_face_off[c]; k < m->cell_face_off[c + 1]; k++) {
            ump_idx f = m->cell_faces[k];
            double phi = st->flux[f];
            d += m->owner[f] == c ? phi : -phi;
            a += fabs(phi);
        }
        st->div[c] = d;
        gf[c] = a;
        double r = fabs(d) / m->area[c], co = 0.5 * dt * a / m->area[c];
        mx = r > mx ? r : mx;
        comax = co > comax ? co : comax;
    }
    double atot = 0, sl = 0, sg = 0, sa = 0;
    for (ump_idx c = 0; c < nc; c++) {
        atot += m->area[c];
        sl += fabs(st->div[c]);
        sg += st->div[c];
        sa += gf[c];
    }
    stats->cont_local = dt * sl / atot;
    stats->cont_global = dt * sg / atot;
    stats->cont_max = dt * mx;
    stats->co_max = comax;
    stats->co_mean = 0.5 * dt * sa / atot;
}

/* ---- the step ------------------------------------------------------------------ */

ump_status sol_step(sol *S, double dt, sol_stats *stats, ump_err *err)
{
    sol_setup *su = &S->su;
    sol_state *st = &S->st;
    memset(stats, 0, sizeof *stats);
    stage_clock clk;
    stage_mark(&clk, NULL, -1);
    UMP_CALL(grow_particle_work(st, st->P->n, err));
    set_boundary_particles(su, st);
    stage_mark(&clk, stats, SOL_STAGE_BOUNDARY);
    if (su->set.buoyant && su->set.balanced)
        UMP_CALL(balance_buoyancy(S, dt, stats, err));
    if (su->set.p_theta > 0)
        path_pressure_kick(S, stats);
    stage_mark(&clk, stats, SOL_STAGE_BALANCE);
    /* q: for the pressure written, and with q_transpose for the correction
     * (transpose_q) at every step */
    int split = (st->want_fields || su->set.q_transpose) && st->have_flux;
    st->split = split;
    if (split) {
        interpolation_error(S, dt);
        UMP_CALL(work_collect(S, stats, err));
        stage_mark(&clk, stats, SOL_STAGE_PWRITE);
    }
    UMP_CALL(step6_rows(S, dt, err));
    UMP_CALL(work_collect(S, stats, err));
    stage_mark(&clk, stats, SOL_STAGE_ROWS);
    UMP_CALL(step6_solve(S, dt, stats, err));
    stage_mark(&clk, stats, SOL_STAGE_SOLVE);
    UMP_CALL(step7_intermediate(S, dt, &stats->walled, err));
    stage_mark(&clk, stats, SOL_STAGE_MOVE);
    step8_mls_velocity(S);
    UMP_CALL(work_collect(S, stats, err));
    stage_mark(&clk, stats, SOL_STAGE_MLS);
    UMP_CALL(step9_pressure(S, dt, err));
    if (split) { /* the potential of the interpolation error, same factorization */
        UMP_CALL(ppe_solve(su->pe, st->fluxe, dt, st->fz, st->q, err));
        if (su->need_ref) { /* the reference level belongs to p_d */
            double r = st->q[su->set.p_ref_cell];
            for (ump_idx c = 0; c < su->m->ncells; c++)
                st->q[c] -= r;
        }
    }
    stats->p_res0 = S->su.pe->res0;
    stats->p_res = S->su.pe->res;
    stats->p_solver = lsolve_name(S->su.pe->fac);
    stage_mark(&clk, stats, SOL_STAGE_PPE);
    UMP_CALL(step10_correct(S, dt, stats, err));
    if (st->want_fields) {
        ump_idx nc = su->m->ncells;
#pragma omp parallel for schedule(static) num_threads(S->nthreads)
        for (ump_idx c = 0; c < nc; c++)
            st->pout[c] = split ? st->p[c] - st->q[c] : st->p[c];
    }
    stats->fields_written = st->want_fields;
    st->have_flux = 1;
    stage_mark(&clk, stats, SOL_STAGE_CORRECT);
    UMP_CALL(step11_manage(S, dt, stats, err));
    stage_mark(&clk, stats, SOL_STAGE_MANAGE);
    continuity_courant(S, dt, stats);
    stage_mark(&clk, stats, SOL_STAGE_DIAG);
    return UMP_OK;
}

void sol_courant(const sol *S, double dt, double *mean, double *max)
{
    const mesh2d *m = S->su.m;
    const double *flux = S->st.flux;
    double mx = 0, s = 0, atot = 0;
    /* 0.5 dt sum_f |phi_f| / V per cell (OpenFOAM CourantNo.H) */
    for (ump_idx c = 0; c < m->ncells; c++) {
        double sum = 0;
        for (ump_idx k = m->cell_face_off[c]; k < m->cell_face_off[c + 1]; k++)
            sum += fabs(flux[m->cell_faces[k]]);
        double co = 0.5 * dt * sum / m->area[c];
        mx = co > mx ? co : mx;
        s += sum;
        atot += m->area[c];
    }
    *max = mx;
    *mean = 0.5 * dt * s / atot;
}

const double *sol_cell_u(const sol *S) { return S->st.uc; }

const unsigned char *sol_cell_u_current(const sol *S) { return S->st.uc_all ? NULL : S->su.uc_keep; }
const double *sol_cell_v(const sol *S) { return S->st.vc; }
const double *sol_cell_p(const sol *S) { return S->st.pout; }
const double *sol_cell_p_projection(const sol *S) { return S->st.p; }
const double *sol_face_flux(const sol *S) { return S->st.flux; }

/* [HNS16] Eqs. 13 and 22 per fluid particle, over the predictor's
 * neighbours (the same gather), r_e = re_factor * sqrt(cell area). */
ump_status sol_particle_quality(sol *S, double *uN, double *tau, size_t *nfail, ump_err *err)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    part_set *P = st->P;
    sol_work *w = &S->work[0];
    size_t bad = 0;
    /* the bins are current between steps: sol_set_particles and the
     * management of Step 11 rebuild them on exit */
    for (size_t i = 0; i < P->n; i++) {
        size_t cnt;
        ump_idx c = P->cell[i];
        UMP_CALL(gather_cell(su, st, w, c, &cnt, err));
        int nn = offsets_but(w, cnt, (ump_idx)i, P->x[i], P->y[i]);
        const double *off[2] = {w->h, w->k};
        lap_quality q;
        ump_err lerr;
        if (lap_quality_d(su->set.lap.re_factor, 2, off, nn, sqrt(su->m->area[c]), w->c0, &q, &lerr) !=
            UMP_OK) {
            memset(&q, 0, sizeof q);
            bad++;
        }
        uN[2 * i] = q.uN[0];
        uN[2 * i + 1] = q.uN[1];
        tau[3 * i] = q.tau[0];
        tau[3 * i + 1] = q.tau[1];
        tau[3 * i + 2] = q.tau[3];
    }
    if (nfail)
        *nfail = bad;
    return UMP_OK;
}

const part_set *sol_particles(const sol *S) { return S->st.P; }

void sol_face_values(const sol *S, ump_idx f, double *u, double *v, double *p)
{
    const sol_setup *su = &S->su;
    const sol_state *st = &S->st;
    const mesh2d *m = su->m;
    ump_idx o = m->owner[f];
    *u = st->uc[o];
    *v = st->vc[o];
    *p = st->pout[o];
    if (f < m->ninternal)
        return;
    boundary_velocity(su, st, f - m->ninternal, f, u, v);
    if (su->p_dir[f])
        *p = st->pf[f];
}

const double *sol_cell_T(const sol *S) { return S->st.Tc; }

double sol_face_T(const sol *S, ump_idx f)
{
    if (!S->su.set.buoyant || f < S->su.m->ninternal)
        return S->st.Tc ? S->st.Tc[S->su.m->owner[f]] : 0.0;
    return S->st.bp.T[f - S->su.m->ninternal];
}

void sol_buoyant_pressure(const sol *S, ump_idx c, ump_idx f, double *p, double *p_rgh)
{
    const sol_settings *s = &S->su.set;
    const sol_setup *su = &S->su;
    const sol_state *st = &S->st;
    double shift = 0;
    if (su->need_ref) { /* pEqn.H: p += pRefValue - p[pRefCell] */
        ump_idx r = s->p_ref_cell;
        shift = s->p_ref_value - (st->pout[r] + su->ghc[r]);
    }
    double pi, gh, T;
    if (f >= 0) {
        double u, v;
        sol_face_values(S, f, &u, &v, &pi);
        gh = su->ghf[f];
        T = sol_face_T(S, f);
    } else {
        pi = st->pout[c];
        gh = su->ghc[c];
        T = st->Tc[c];
    }
    double rhok = 1.0 - s->beta * (T - s->t_ref);
    *p = pi + gh + shift;
    *p_rgh = *p - rhok * gh;
}

ump_status sol_wall_dTdn(sol *S, ump_idx f, sol_grad_method how, double *dTdn, ump_err *err)
{
    const sol_setup *su = &S->su;
    sol_state *st = &S->st;
    const mesh2d *m = su->m;
    if (!su->set.buoyant || f < m->ninternal || f >= m->nfaces)
        return UMP_FAIL(err, UMP_ERR_INPUT, "wall heat flux: face %ld is not a boundary face of a buoyant case",
                        (long)f);
    ump_idx o = m->owner[f];
    double nx = m->nx[f], ny = m->ny[f];
    if (how == SOL_GRAD_SNGRAD) {
        double d = (m->fx[f] - m->cx[o]) * nx + (m->fy[f] - m->cy[o]) * ny;
        *dTdn = (sol_face_T(S, f) - st->Tc[o]) / d;
        return UMP_OK;
    }
    /* quadratic MLS derivative (Eqs. 33-34) at the face centre over the
     * fluid and boundary particles of the owner's stencil */
    sol_work *w = &S->work[0];
    size_t cnt;
    UMP_CALL(gather_cell(su, st, w, o, &cnt, err));
    int n = offsets(w, cnt, m->fx[f], m->fy[f], -1);
    mls_weights(w->h, w->k, n, m->dx[o], m->dy[o], w->c0, w->cx, w->cy, NULL);
    double gx = apply(w->cx, w->sref, n, st->P->T, st->bp.T);
    double gy = apply(w->cy, w->sref, n, st->P->T, st->bp.T);
    *dTdn = gx * nx + gy * ny;
    return UMP_OK;
}
