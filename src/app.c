/* SPDX-License-Identifier: GPL-3.0-or-later
 * app.c -- the umppmFoam time loop, driven like an OpenFOAM solver.
 *
 * Reads system/controlDict, system/fvSolution (PISO/PIMPLE pRefCell and the
 * UMPPM sub-dictionary), constant/transportProperties, the mesh and the
 * start-time U and p (and, on a restart, the particle cloud of the start
 * time), then loops: Courant number, deltaT (fixed, or adjustTimeStep with
 * maxCo as setDeltaT.H), Time = ..., one UMPPM step, log, and at write
 * times U, p, the cloud and uniform/time into a time directory written under
 * a temporary name and renamed into place.
 *
 * Buoyant cases are recognised by constant/g, as buoyantBoussinesqPimpleFoam
 * sets them up: transportProperties then needs beta, TRef and Pr, the start
 * time T, p_rgh and U (p and alphat optional), and T, p_rgh and p (p =
 * p_rgh + rhok gh) are written, with the particle temperature in the cloud.
 * alphat is zero in laminar flow: buoyantBoussinesqPimpleFoam sets it to
 * nut/Prt = 0 at every step except on patches that keep their own value
 * (fixedValue, fixedGradient, ...), where it adds to the wall's heat
 * conduction; such a non-zero value is refused (check_alphat), and the start
 * time's alphat is written, as read, at every write time (that solver needs
 * it to restart). p_rgh zeroGradient on a patch of fixed U is refused
 * (check_prgh_walls).
 * Without constant/g the case is isothermal (icoFoam's U and p).
 * constant/turbulenceProperties, if present, must say laminar.
 *
 * Nothing lost (README "Nothing lost"): hidden directories of killed runs
 * are recovered or removed first (fio_recover, before startFrom latestTime
 * picks a time); a restart needs its cloud unless -reseed; a file in the way
 * of a write time known in advance is refused before the first step; after
 * each step the divergence guard (|U| of cells and particles against
 * maxVelocity or 100 x speed_scale()) runs before anything is written, the
 * log is flushed and checked, and a SIGINT/SIGTERM (stopsig) makes that step
 * a write time and the last one.
 *
 * runTimeModifiable (README "Editing controlDict during a run"): before each
 * step system/controlDict's stamp (case_file_stamp) is compared with the
 * version read last; a new version is re-read and checked as at start-up
 * (reread_control) and applied to the time (rt_reread), the write settings
 * and the function objects, or refused with a warning, the run going on
 * with its settings. The solver is not involved: it gets deltaT per step.
 */
#include "umppm/app.h"
#include "umppm/case.h"
#include "umppm/features.h"
#include "umppm/field.h"
#include "umppm/foam.h"
#include "umppm/fieldio.h"
#include "umppm/funcobj.h"
#include "umppm/mesh2d.h"
#include "umppm/polymesh.h"
#include "umppm/runtime.h"
#include "umppm/solver.h"
#include "umppm/stopsig.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <time.h>

typedef struct app {
    const char *case_dir;
    case_control ctl;
    case_transport tr;
    case_solution so;
    case_umppm um;
    case_buoyancy bu;
    pmesh *pm;
    mesh2d *m;
    fld_field *U, *p, *T, *prgh;   /* T, p_rgh: buoyant only */
    char *alphat_text;              /* the start time's alphat (buoyant), written with every time */
    size_t alphat_len;
    sol *S;
    fob_list fo;                    /* controlDict function objects */
    double *fo_dTdn, *fo_Tf;        /* per-face scratch [fo_cap] */
    double *fo_val;                 /* [3 * FOB_MAX_FIELDS * fo_cap] */
    size_t fo_cap;                  /* the largest function-object patch */
    ump_idx p_ref_point_cell;       /* the cell holding pRefPoint, if given */
    double aspect;                  /* the most stretched cell's aspect ratio ... */
    ump_idx aspect_cell;            /* ... and that cell (most_stretched, once) */
    char ddt[128];                  /* the ddt scheme of U (system/fvSchemes) */
    char **written;          /* purgeWrite bookkeeping */
    int nwritten;
    app_options opt;
    double u_scale;          /* divergence guard: the speed scale ... */
    double u_bound;          /* ... and the bound on |U| (maxVelocity) */
    double u_bound_p;        /* ... and on a particle's |U| */
    int closed;              /* driven by its walls alone (closed_flow) */
    int star;                /* the variant of this run: 1 UMPPM*, 0 UMPPM
                                (variant auto decided once: app_variant_star) */
    ump_idx stretched_quads; /* quadrilaterals stretched beyond
                                APP_QUAD_SQUARE (stretched_quads, once) */
    unsigned char *corner;   /* [ncells] closed: 1 at a corner of walls of
                                different velocity (corner_cells), or NULL */
    /* runTimeModifiable: system/controlDict is watched while ctl_watch */
    int ctl_watch;
    int ctl_missing;         /* the last stat failed (warned once) */
    case_stamp ctl_stamp;    /* the version read last */
    char ctl_path[4200];     /* <case>/system/controlDict */
    char ctl_abs[4200];      /* the same, absolute, for the log */
} app;

/* Cells stretched beyond APP_ASPECT_WARN (bounding-box extents): the
 * paper's LS gradient, CPM fit and MLS pressure derivative fail there
 * (README, "Anisotropic cells": max |U| 25 against icoFoam's 0.70 on a
 * 199:1 graded cavity; diverged at 1 700:1), so anisotropicCells auto (the
 * default) turns the anisotropic operators on for such meshes. */
#define APP_ASPECT_WARN 20.0
/* The most stretched cell's aspect ratio (bounding box), its index in *wc. */
static double most_stretched(const mesh2d *m, ump_idx *wc)
{
    double worst = 1;
    *wc = -1;
    for (ump_idx c = 0; c < m->ncells; c++) {
        double dx = m->dx[c], dy = m->dy[c];
        if (!(dx > 0 && dy > 0))
            continue;
        double r = dx > dy ? dx / dy : dy / dx;
        if (r > worst)
            worst = r, *wc = c;
    }
    return worst;
}

/* Said once, before the first step, with the worst cell (worst, wc from
 * most_stretched): what the stretched cells get (anisotropic: 1 on, 0 off;
 * automatic: by auto). */
static void report_stretched(const mesh2d *m, double worst, ump_idx wc, int anisotropic, int automatic)
{
    if (!(worst > APP_ASPECT_WARN))
        return;
    if (anisotropic)
        printf("Stretched cells: cell %ld at (%g %g) is stretched %.0f:1 (bounding box %g x %g); "
               "anisotropicCells %s: LS weights 1/|d|^2, CPM in cell units, particle "
               "gradient from the cell gradients (README, \"Anisotropic cells\")\n\n",
               (long)wc, m->cx[wc], m->cy[wc], worst, m->dx[wc], m->dy[wc],
               automatic ? "on (auto: above 20:1)" : "yes");
    else
        printf("--> umppmFoam Warning: cell %ld at (%g %g) is stretched %.0f:1 (bounding box %g x %g); "
               "with anisotropicCells no, above about %.0f:1 umppmFoam can be wrong without diverging "
               "(README, \"Anisotropic cells\"); anisotropicCells auto (the default) handles such meshes\n\n",
               (long)wc, m->cx[wc], m->cy[wc], worst, m->dx[wc], m->dy[wc], APP_ASPECT_WARN);
}

static double wall_seconds(void)
{
    struct timeval tv;
    gettimeofday(&tv, NULL);
    return (double)tv.tv_sec + 1e-6 * (double)tv.tv_usec;
}

static void app_free(app *a)
{
    sol_free(&a->S);
    fld_free(&a->U);
    fld_free(&a->p);
    fld_free(&a->T);
    fld_free(&a->prgh);
    free(a->alphat_text);
    fob_free(&a->fo);
    free(a->fo_dTdn);
    free(a->fo_Tf);
    free(a->fo_val);
    free(a->corner);
    mesh_free(&a->m);
    pmesh_free(&a->pm);
    for (int i = 0; i < a->nwritten; i++)
        free(a->written[i]);
    free(a->written);
}

/* The mesh has boundary faces besides its empty and cyclic patches: a
 * wall, inlet, outlet or symmetry plane. */
static int app_has_boundaries(const app *a) { return a->m->nfaces > a->m->ninternal; }

/* laplacian auto (the default): chosen by the mesh in settings() */
static int app_laplacian_auto(const app *a) { return strcmp(a->um.laplacian, "auto") == 0; }

/* anisotropicCells as this run has it: auto turns it on where a cell is
 * stretched beyond APP_ASPECT_WARN (README, "Anisotropic cells") */
static int app_anisotropic(const app *a)
{
    return a->um.anisotropic < 0 ? a->aspect > APP_ASPECT_WARN : a->um.anisotropic;
}

/* What a flow driven by its walls alone that leaves their speed is told to
 * try: the adaptive variant with the stretched-cell operators (README,
 * "Unbounded on coarse stretched cells at high Re"), or, to a run that
 * already has them, the mesh alone */
static const char *closed_remedy(const app *a)
{
    return !a->star && app_anisotropic(a)
               ? "refine the mesh (this run already has UMPPM { variant UMPPM; anisotropicCells on; })"
               : "refine the mesh, or try UMPPM { variant UMPPM; anisotropicCells yes; }";
}

/* How many cells are triangles (the count of -checkMesh) */
static size_t triangles(const mesh2d *m)
{
    mesh_stats st;
    mesh_compute_stats(m, &st);
    return (size_t)st.ntri;
}

/* Most cells triangles (more than half) */
static int mostly_triangles(const mesh2d *m) { return 2 * triangles(m) > (size_t)m->ncells; }

/* A quadrilateral is square for variant auto up to this ratio of the
 * summed lengths of its two pairs of opposite edges (rotation does not
 * change it; a rhombus is square by it) */
#define APP_QUAD_SQUARE 1.15
/* How many cells are quadrilaterals stretched beyond APP_QUAD_SQUARE */
static ump_idx stretched_quads(const mesh2d *m)
{
    ump_idx n = 0;
    for (ump_idx c = 0; c < m->ncells; c++) {
        if (m->cell_off[c + 1] - m->cell_off[c] != 4)
            continue;
        const ump_idx *v = m->cell_verts + m->cell_off[c];
        double e[4];
        for (int k = 0; k < 4; k++)
            e[k] = hypot(m->vx[v[(k + 1) % 4]] - m->vx[v[k]], m->vy[v[(k + 1) % 4]] - m->vy[v[k]]);
        double a = e[0] + e[2], b = e[1] + e[3];
        if ((a > b ? a : b) > APP_QUAD_SQUARE * (a < b ? a : b))
            n++;
    }
    return n;
}

/* variant auto: the adaptive UMPPM in a flow driven by its walls alone
 * whose cells are mostly quadrilaterals that are not square (more than
 * half the cells stretched beyond APP_QUAD_SQUARE) and not so stretched
 * that anisotropicCells is on; UMPPM* (one particle per cell) elsewhere.
 * Measured on the Re 1000 cavity (README, "Non-square cells at Re 1000";
 * RMS from Ghia, u / v, t = 40, deltaT 0.005): with UMPPM* the error grows
 * with the cells' aspect ratio, 40 x 40 0.0158 / 0.0116, 40 x 44 (1.1:1)
 * 0.0127 / 0.0121, 40 x 48 (1.2:1) 0.0138 / 0.0570, 40 x 80 (2:1) 0.0461 /
 * 0.1339 (icoFoam 0.0207 / 0.0222), 20 x 40 diverged; UMPPM 0.0198 /
 * 0.0173, 0.0198 / 0.0159, 0.0191 / 0.0168, 0.0137 / 0.0124, 0.0538 /
 * 0.0591. The carried refills of UMPPM* put energy into the flow there
 * (the vortex too strong at every one of Ghia's points). Triangles keep
 * UMPPM* (with pressureTheta 0.5 it is the better one on them: README,
 * "Triangles at icoFoam's step"); stretched beyond 20:1 the graded meshes
 * keep the UMPPM* of their own measurements ("Anisotropic cells"); flows
 * with inlets, outlets or buoyancy, or without walls (Taylor-Green), are
 * not measured and keep UMPPM*. */
static int app_variant_star(const app *a)
{
    if (a->um.variant_star >= 0)
        return a->um.variant_star;
    return !(a->closed && app_has_boundaries(a) && !app_anisotropic(a) &&
             2 * (size_t)a->stretched_quads > (size_t)a->m->ncells);
}

/* pressureTheta auto: 0.5, the trapezoidal pressure along the path, where
 * the mesh has no wall, inlet or outlet (below), and in a flow driven by
 * its walls alone on a mesh of triangles; 0 (the paper's Eq. 10)
 * elsewhere. On triangles the default's vortex was uniformly too weak at
 * icoFoam's step: the Re 1000 cavity on 3 550 gmsh triangles at deltaT
 * 0.01 (Courant number 0.8) 0.0275 / 0.0230 from Ghia with 0, 0.0149 /
 * 0.0078 with 0.5 (icoFoam 0.0155 / 0.0128); 1 476 triangles 0.0554 /
 * 0.0547 and 0.0493 / 0.0477 (icoFoam 0.0596 / 0.0511). Not on quads,
 * where 0.5 over-corrects next to walls (the 40^2 cavity's vortex too
 * strong), nor with inlets or outlets: on OpenFOAM's elbow (918
 * triangles) at a quarter of its step the inlet pressures fell to 0.59 /
 * 0.77 of the converged flow's (0.93 / 0.86 with 0). README, "Triangles
 * at icoFoam's step". */
static double p_theta_auto(const app *a, int walled)
{
    return !walled || (a->closed && mostly_triangles(a->m)) ? 0.5 : 0;
}

/* faceSupport auto at the faces beside a triangle: 3 cell extents
 * (SOL_FACE_SUPPORT_TRI) in a flow driven by its walls alone (the
 * divergence guard's closed flows; Taylor-Green's cyclic box among them),
 * mlsSupport elsewhere and with mlsSupport 0 (the paper's Eq. 35 scales
 * everywhere). Measured (README, "Face fits on triangles"): the Re 1000
 * cavity on 944 gmsh triangles 0.0728 / 0.0664 from Ghia against 0.1147 /
 * 0.0925 with 2 (icoFoam 0.0706 / 0.0605), 1 476 triangles 0.0279 / 0.0244
 * against 0.0610 / 0.0513; Taylor-Green's 1 600 crossed triangles L2 0.0117
 * against 0.0168. Not with inlets or outlets: on OpenFOAM's elbow (918
 * triangles) at a quarter of its step the inlet pressures fell to -0.24 /
 * 0.57 of the converged flow's (0.93 / 0.86 with 2). Not on
 * quadrilaterals: the 40^2 cavity's v went from 0.0110 to 0.0374. */
static double face_support_tri_auto(const app *a)
{
    return a->closed && a->um.mls_support > 0 ? SOL_FACE_SUPPORT_TRI : a->um.mls_support;
}

static ump_status settings(const app *a, sol_settings *s, ump_err *err)
{
    sol_default_settings(s);
    s->nu = a->tr.nu;
    s->variant = a->star ? PART_UMPPM_STAR : PART_UMPPM;
    s->alpha = a->um.alpha;
    /* laplacian auto and pressureTheta auto: the quartic row and the
     * trapezoidal pressure along the path where the mesh has no wall, inlet
     * or outlet (every patch empty or cyclic), the paper's CPM and Eq. 10
     * elsewhere. Measured (README, "Settings for flows without walls"): on
     * Taylor-Green they remove the Laplacian's O(h^2) and the path's O(dt)
     * errors, which otherwise cancel by chance; next to walls pressureTheta
     * 0.5 over-corrects (the Re 1000 cavity's vortex too strong) and a
     * quartic row costs +37 % for no gain */
    int walled = app_has_boundaries(a);
    s->lap.model = app_laplacian_auto(a) ? (walled ? LAP_CPM : LAP_CPM4) : (lap_model)lap_parse(a->um.laplacian);
    s->lap.re_factor = a->um.re_factor;
    s->ppe_solver = strcmp(a->um.ppe_solver, "UMFPACK") == 0 ? LSOLVE_UMFPACK
                    : strcmp(a->um.ppe_solver, "KLU") == 0   ? LSOLVE_KLU
                    : strcmp(a->um.ppe_solver, "CHOLMOD") == 0 ? LSOLVE_CHOLMOD : LSOLVE_AUTO;
    s->pred_pc = strcmp(a->um.pred_pc, "Jacobi") == 0 ? LSOLVE_PC_JACOBI
                 : strcmp(a->um.pred_pc, "none") == 0 ? LSOLVE_PC_NONE : LSOLVE_PC_ILU0;
    s->pred_tol = a->um.pred_tol;
    s->pred_maxit = (int)a->um.pred_maxit;
    s->sort_interval = (int)a->um.sort_interval;
    s->balanced = a->um.buoyancy_balanced;
    /* refill auto: carried values with UMPPM*, u_P with UMPPM, where carried
     * values from several particles grew noise on the Taylor-Green vortex
     * (README, "Refill that keeps carried values") */
    int carried = a->um.refill_carried < 0 ? a->star : a->um.refill_carried;
    s->refill = carried ? SOL_REFILL_CARRIED : SOL_REFILL_CENTROID;
    s->refill_k = (int)a->um.refill_k;
    s->refill_increment = a->um.refill_increment;
    s->mls_support = a->um.mls_support;
    s->face_support = a->um.face_support < 0 ? a->um.mls_support : a->um.face_support;
    s->face_support_tri = a->um.face_support < 0 ? face_support_tri_auto(a) : a->um.face_support;
    s->p_theta = a->um.p_theta < 0 ? p_theta_auto(a, walled) : a->um.p_theta;
    s->positive = a->um.positive_rows;
    s->bounded_fits = a->um.bounded_fits;
    s->anisotropic = app_anisotropic(a);
    s->q_transpose = a->um.q_transpose; /* -1: auto, resolved by sol_q_transpose (solver.c) */
    s->p_ref_cell = (ump_idx)a->so.p_ref_cell;
    s->p_ref_value = a->so.p_ref_value;
    if (a->bu.on) {
        s->buoyant = 1;
        memcpy(s->g, a->bu.g, sizeof s->g);
        /* readhRef.H: ghRef = -mag(g) hRef */
        s->gh_ref = -sqrt(s->g[0] * s->g[0] + s->g[1] * s->g[1] + s->g[2] * s->g[2]) * a->bu.h_ref;
        s->beta = a->tr.beta;
        s->t_ref = a->tr.TRef;
        s->kappa = a->tr.nu / a->tr.Pr; /* alphaEff = nu/Pr + alphat, alphat = 0 (laminar) */
    }
    if (a->so.has_p_ref_point)
        s->p_ref_cell = a->p_ref_point_cell;
    if ((int)s->lap.model < 0)
        return UMP_FAIL(err, UMP_ERR_INPUT, "system/fvSolution: unknown laplacian '%s'", a->um.laplacian);
    /* CPM and CPM4 have no influence radius: a reFactor would do nothing */
    if ((s->lap.model == LAP_CPM || s->lap.model == LAP_CPM4) && a->um.re_factor != 0)
        return UMP_FAIL(err, UMP_ERR_INPUT,
                        "system/fvSolution: UMPPM reFactor %g is the influence radius of laplacian MPS, PS or "
                        "IPS; laplacian %s%s has none (remove reFactor)",
                        a->um.re_factor, lap_name(s->lap.model),
                        app_laplacian_auto(a) ? " (auto)" : "");
    return UMP_OK;
}

/* Copy the solver state into the U and p fields (types and extra keys kept). */
static void fill_fields(app *a)
{
    const mesh2d *m = a->m;
    const double *uc = sol_cell_u(a->S), *vc = sol_cell_v(a->S), *pc = sol_cell_p(a->S);
    for (ump_idx c = 0; c < m->ncells; c++) {
        double *U = a->U->internal + 3 * (size_t)c;
        U[m->normal] = 0;
        U[m->ax[0]] = uc[c];
        U[m->ax[1]] = vc[c];
        a->p->internal[c] = pc[c];
    }
    for (int p = 0; p < a->pm->npatches; p++) {
        const pmesh_patch *pp = &a->pm->patch[p];
        for (ump_idx i = 0; i < pp->n; i++) {
            ump_idx f = m->pmface_to_face[pp->start + i];
            if (f < 0)
                continue;
            double u, v, pv;
            if (f < m->ninternal) { /* cyclic: neighbour-side values are the adjacent cell's */
                ump_idx c = a->pm->owner[pp->start + i];
                u = uc[c];
                v = vc[c];
                pv = pc[c];
            } else {
                sol_face_values(a->S, f, &u, &v, &pv);
            }
            double *Uv = a->U->patch[p].value + 3 * (size_t)i;
            Uv[m->normal] = 0;
            Uv[m->ax[0]] = u;
            Uv[m->ax[1]] = v;
            a->p->patch[p].value[i] = pv;
            if (a->T) {
                ump_idx c = a->pm->owner[pp->start + i];
                if (f < m->ninternal) {
                    a->T->patch[p].value[i] = sol_cell_T(a->S)[c];
                    sol_buoyant_pressure(a->S, c, -1, &a->p->patch[p].value[i], &a->prgh->patch[p].value[i]);
                } else {
                    a->T->patch[p].value[i] = sol_face_T(a->S, f);
                    sol_buoyant_pressure(a->S, -1, f, &a->p->patch[p].value[i], &a->prgh->patch[p].value[i]);
                }
            }
        }
    }
    if (a->T)
        for (ump_idx c = 0; c < m->ncells; c++) {
            a->T->internal[c] = sol_cell_T(a->S)[c];
            sol_buoyant_pressure(a->S, c, -1, &a->p->internal[c], &a->prgh->internal[c]);
        }
}

/* writeQuality: the particle fields uN (vector, Hwang, Ng & Sheu 2016
 * [HNS16] Eq. 13) and tau (symmTensor, [HNS16] Eq. 22) in the mesh's 3-D
 * axes. */
static ump_status write_quality(app *a, const char *dir, const char *tname, ump_err *err)
{
    const part_set *P = sol_particles(a->S);
    size_t n = P->n, nfail = 0;
    double *uN = ump_alloc_array(2 * n + 1, sizeof *uN), *tau = ump_alloc_array(3 * n + 1, sizeof *tau);
    double *u3 = ump_alloc_array(3 * n + 1, sizeof *u3), *t6 = ump_alloc_array(6 * n + 1, sizeof *t6);
    ump_status rc = UMP_OK;
    if (!uN || !tau || !u3 || !t6) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "writing particle quality: out of memory");
        goto done;
    }
    if ((rc = sol_particle_quality(a->S, uN, tau, &nfail, err)) != UMP_OK)
        goto done;
    /* symmTensor slot of the 3-D axes pair (d, e) */
    static const int slot[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
    int X = a->m->ax[0], Y = a->m->ax[1];
    for (size_t i = 0; i < n; i++) {
        double *u = u3 + 3 * i, *T = t6 + 6 * i;
        memset(u, 0, 3 * sizeof *u);
        memset(T, 0, 6 * sizeof *T);
        u[X] = uN[2 * i];
        u[Y] = uN[2 * i + 1];
        T[slot[X][X]] = tau[3 * i];
        T[slot[X][Y]] = tau[3 * i + 1];
        T[slot[Y][Y]] = tau[3 * i + 2];
    }
    if (nfail)
        printf("writeQuality: %zu particles with a singular IPS matrix written as 0\n", nfail);
    if ((rc = fio_write_cloud_field(dir, tname, a->um.cloud_name, "uN", 3, n, u3,
                                    a->ctl.write_precision, err)) != UMP_OK)
        goto done;
    rc = fio_write_cloud_field(dir, tname, a->um.cloud_name, "tau", 6, n, t6, a->ctl.write_precision, err);
done:
    free(uN);
    free(tau);
    free(u3);
    free(t6);
    return rc;
}

/* phi: the corrected face fluxes of the last step over the polyMesh faces
 * (2-D flux per unit thickness times the thickness, signed by the polyMesh
 * face's own orientation; both faces of a cyclic pair). */
static ump_status write_phi(app *a, const char *dir, const char *tname, const fio_format *fmt, ump_err *err)
{
    const mesh2d *m = a->m;
    const pmesh *pm = a->pm;
    const double *flux = sol_face_flux(a->S);
    double thick = m->zmax - m->zmin;
    double *phi = ump_alloc_array((size_t)pm->nfaces, sizeof *phi);
    if (!phi)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "writing phi: out of memory");
    for (ump_idx F = 0; F < pm->nfaces; F++)
        phi[F] = 0;
    for (ump_idx f = 0; f < m->nfaces; f++) {
        ump_idx F[2] = {m->face_pm[f], f < m->ninternal ? m->face_pm2[f] : -1};
        for (int k = 0; k < 2; k++)
            if (F[k] >= 0)
                phi[F[k]] = (pm->owner[F[k]] == m->owner[f] ? 1 : -1) * flux[f] * thick;
    }
    ump_status rc = fio_write_phi(dir, tname, pm, phi, fmt, err);
    free(phi);
    return rc;
}

/* the fields app_write_digest records: U (and T) */
static const fld_field *const *digest_fields(const app *a, const fld_field *dig[2])
{
    dig[0] = a->U;
    dig[1] = a->T;
    return dig;
}

static ump_status write_time(app *a, const rt_time *t, ump_err *err)
{
    const fld_field *dig[2];
    fio_timedir td;
    fio_format fmt = {a->ctl.write_binary, a->ctl.write_precision, a->ctl.write_compression};
    fill_fields(a);
    UMP_CALL(fio_timedir_begin(a->case_dir, t->name, &td, err));
    ump_status rc;
    const part_set *P = sol_particles(a->S);
    double *pos = ump_alloc_array(3 * P->n, sizeof *pos), *vel = ump_alloc_array(3 * P->n, sizeof *vel);
    if (!pos || !vel) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "writing the cloud: out of memory");
        goto fail;
    }
    for (size_t i = 0; i < P->n; i++) {
        mesh_to3d(a->m, P->x[i], P->y[i], pos + 3 * i);
        vel[3 * i + (size_t)a->m->normal] = 0;
        vel[3 * i + (size_t)a->m->ax[0]] = P->u[i];
        vel[3 * i + (size_t)a->m->ax[1]] = P->v[i];
    }
    /* The mesh fields and the cloud are separate files: formatted and
     * written by two threads into the hidden directory, which is committed
     * (or removed) once both are done. The first failure in the serial
     * order (fields, then cloud) is the one reported. */
    ump_status rcf = UMP_OK, rcc = UMP_OK;
    ump_err ef, ec;
#pragma omp parallel sections num_threads(2) if (sol_threads() > 1)
    {
#pragma omp section
        {
            if ((rcf = fio_write_field(td.tmp_dir, t->name, a->pm, a->U, &fmt, &ef)) == UMP_OK &&
                (rcf = fio_write_field(td.tmp_dir, t->name, a->pm, a->p, &fmt, &ef)) == UMP_OK &&
                (!a->T || (rcf = fio_write_field(td.tmp_dir, t->name, a->pm, a->T, &fmt, &ef)) == UMP_OK) &&
                (!a->T || (rcf = fio_write_field(td.tmp_dir, t->name, a->pm, a->prgh, &fmt, &ef)) == UMP_OK) &&
                (!a->alphat_text ||
                 (rcf = fio_write_text(td.tmp_dir, "alphat", a->alphat_text, a->alphat_len, &ef)) == UMP_OK))
                rcf = write_phi(a, td.tmp_dir, t->name, &fmt, &ef);
        }
#pragma omp section
        {
            if ((rcc = fio_write_cloud(td.tmp_dir, t->name, a->um.cloud_name, P->n, pos, vel, P->cell, P->id,
                                       a->ctl.write_precision, &ec)) == UMP_OK &&
                (!a->T || (rcc = fio_write_cloud_field(td.tmp_dir, t->name, a->um.cloud_name, "T", 1, P->n,
                                                       P->T, a->ctl.write_precision, &ec)) == UMP_OK) &&
                a->um.write_quality)
                rcc = write_quality(a, td.tmp_dir, t->name, &ec);
        }
    }
    if (rcf != UMP_OK || rcc != UMP_OK) {
        rc = rcf != UMP_OK ? rcf : rcc;
        *err = rcf != UMP_OK ? ef : ec;
        goto fail;
    }
    if ((rc = fio_write_uniform_time(td.tmp_dir, t->name, t->value, t->name, t->index, t->delta_t,
                                     t->delta_t0, a->ctl.write_precision, a->ctl.time_format_fixed,
                                     err)) != UMP_OK ||
        (rc = app_write_digest(td.tmp_dir, t->name, a->um.cloud_name, a->ctl.write_binary,
                               a->ctl.write_precision, digest_fields(a, dig), a->T ? 2 : 1, err)) != UMP_OK || (rc = fio_timedir_commit(&td, err)) != UMP_OK)
        goto fail;
    free(pos);
    free(vel);
    /* purgeWrite N: keep the last N written time directories */
    if (a->ctl.purge_write > 0) {
        char **w = ump_realloc_array(a->written, (size_t)a->nwritten + 1, sizeof *w);
        if (!w)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "out of memory");
        a->written = w;
        w[a->nwritten++] = ump_strdup(t->name);
        while (a->nwritten > a->ctl.purge_write) {
            UMP_CALL(fio_remove_timedir(a->case_dir, w[0], err));
            free(w[0]);
            memmove(w, w + 1, (size_t)(a->nwritten - 1) * sizeof *w);
            a->nwritten--;
        }
    }
    return UMP_OK;
fail:
    free(pos);
    free(vel);
    fio_timedir_abort(&td);
    return rc;
}

/* The fields' digest written beside the cloud (uniform/<solver>): the sums
 * of each component of the fields over the cells and of their squares. A
 * restart compares it with the fields it reads: fields that another solver
 * (icoFoam or interFoam writing into the same time directory), mapFields or
 * setFields changed after the cloud was written do not go with the
 * particles, which would continue the old run (umppmFoam: U 20 % off,
 * without a word, until 2026-12-06; meshlessFoam until 2026-12-07). */
static void field_digest(const fld_field *f, double sum[3], double *sumsq)
{
    sum[0] = sum[1] = sum[2] = *sumsq = 0;
    for (ump_idx c = 0; c < f->ncells; c++)
        for (int k = 0; k < f->ncomp; k++) {
            double v = f->internal[(size_t)c * (size_t)f->ncomp + (size_t)k];
            sum[k] += v;
            *sumsq += v * v;
        }
}

ump_status app_write_digest(const char *dir, const char *tname, const char *cloud, int binary, int precision,
                            const fld_field *const *fields, int nfields, ump_err *err)
{
    char body[4096];
    int n = snprintf(body, sizeof body,
                     "// the fields written with the cloud: a restart from its particles checks that they are\n"
                     "// still these (sums over the cells), else it needs -reseed\n"
                     "cloudName       %s;\nwriteFormat     %s;\nwritePrecision  %d;\nnCells          %ld;\n",
                     cloud, binary ? "binary" : "ascii", precision, nfields ? (long)fields[0]->ncells : 0L);
    for (int q = 0; q < nfields && n > 0 && (size_t)n < sizeof body; q++) {
        const fld_field *f = fields[q];
        double s[3], sq;
        field_digest(f, s, &sq);
        char ks[300], kq[300];
        snprintf(ks, sizeof ks, "%s_sum", f->name);
        snprintf(kq, sizeof kq, "%s_sumSqr", f->name);
        if (f->ncomp == 3)
            n += snprintf(body + n, sizeof body - (size_t)n, "%-15s (%.17g %.17g %.17g);\n", ks, s[0], s[1], s[2]);
        else
            n += snprintf(body + n, sizeof body - (size_t)n, "%-15s %.17g;\n", ks, s[0]);
        if ((size_t)n < sizeof body)
            n += snprintf(body + n, sizeof body - (size_t)n, "%-15s %.17g;\n", kq, sq);
    }
    UMP_CHECK(n > 0 && (size_t)n < sizeof body, err, UMP_ERR_INPUT, "%s/uniform/%s: cloudName or field names too long", dir,
              ump_solver);
    return fio_write_uniform_dict(dir, tname, ump_solver, body, err);
}

/* Round-off of a field written at writePrecision p (binary: none). */
static double digest_tol(int binary, int prec)
{
    return binary ? 1e-12 : 2 * pow(10, 1 - (prec > 0 ? prec : 6));
}

ump_status app_check_digest(const char *dir, const char *tname, const char *cloud, int binary, int precision,
                            const fld_field *const *fields, int nfields, ump_err *err)
{
    char path[4600];
    snprintf(path, sizeof path, "%s/uniform/%s", dir, ump_solver);
    if (!foam_file_exists(path))
        return UMP_OK; /* written before the digest was, or not by this solver */
    foam_file *f = NULL;
    UMP_CALL(foam_file_read(path, &f, err));
    const char *fmt = NULL, *written_cloud = NULL;
    int64_t prec = 6, nc = 0;
    ump_status rc;
    if ((rc = foam_get_word_or(f->dict, "cloudName", cloud, &written_cloud, err)) != UMP_OK ||
        (rc = foam_get_word_or(f->dict, "writeFormat", "ascii", &fmt, err)) != UMP_OK ||
        (rc = foam_get_label_or(f->dict, "writePrecision", 6, &prec, err)) != UMP_OK ||
        (rc = foam_get_label(f->dict, "nCells", &nc, err)) != UMP_OK)
        goto done;
    if (strcmp(written_cloud, cloud) != 0) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT,
                      "%s/lagrangian/%s: the fields of time %s were written with the cloud '%s', not with this "
                      "one (cloudName changed?); its particles would not go with these fields; run with -reseed "
                      "to seed new particles from the fields of time %s", dir, cloud, tname, written_cloud,
                      tname);
        goto done;
    }
    /* the round-off of the writes: the one recorded, or a conversion since
     * (foamFormatConvert) at this controlDict's precision */
    double tol = fmax(digest_tol(strcmp(fmt, "binary") == 0, (int)prec), digest_tol(binary, precision));
    for (int q = 0; q < nfields; q++) {
        const fld_field *F = fields[q];
        char ks[300], kq[300];
        snprintf(ks, sizeof ks, "%s_sum", F->name);
        snprintf(kq, sizeof kq, "%s_sumSqr", F->name);
        if (q > 0 && !foam_dict_find(f->dict, ks, 0))
            continue; /* a field the writer did not record (T of an isothermal run) */
        double s[3] = {0, 0, 0}, sq, r[3], rq;
        if ((rc = F->ncomp == 3 ? foam_get_vector(f->dict, ks, s, err) : foam_get_scalar(f->dict, ks, s, err)) !=
                UMP_OK ||
            (rc = foam_get_scalar(f->dict, kq, &sq, err)) != UMP_OK)
            goto done;
        field_digest(F, r, &rq);
        double n = (double)F->ncells, scale = sqrt(n * fmax(sq, rq)) + 1e-300;
        int same = (int64_t)F->ncells == nc && fabs(rq - sq) <= 2 * tol * fmax(sq, rq) + 1e-300;
        for (int k = 0; k < F->ncomp; k++)
            same &= fabs(r[k] - s[k]) <= tol * scale;
        if (!same) {
            rc = UMP_FAIL(err, UMP_ERR_INPUT,
                          "%s/lagrangian/%s: the fields of time %s are not those written with this particle "
                          "cloud (another solver writing into the time directory, mapFields or setFields changed "
                          "them: sum of %s^2 %.9g, written %.9g); its particles would continue the run that "
                          "wrote them; run with -reseed to seed new particles from the fields of time %s", dir,
                          cloud, tname, F->name, rq, sq, tname);
            goto done;
        }
    }
done:
    foam_file_free(&f);
    return rc;
}

/* Restart: particles of the start time's cloud replace the seeded ones. */
ump_status app_restart_policy(const char *case_dir, const char *tname, const char *cloud, int reseed,
                              const char *seed_from, int *restart, ump_err *err)
{
    char dir[4400], cl[4600], path[4700], co[4700], ut[4600];
    snprintf(dir, sizeof dir, "%s/%s", case_dir, tname);
    snprintf(cl, sizeof cl, "%s/lagrangian/%s", dir, cloud);
    snprintf(path, sizeof path, "%s/positions", cl);
    snprintf(co, sizeof co, "%s/coordinates", cl);
    snprintf(ut, sizeof ut, "%s/uniform/time", dir);
    int has = foam_file_exists(path);
    *restart = has && !reseed;
    if (reseed) {
        printf("Restart: -reseed: particles seeded from the fields of time %s%s\n\n", tname,
               has ? " (its cloud is not read)" : "");
        return UMP_OK;
    }
    if (has)
        return UMP_OK;
    /* a time some solver wrote (uniform/time) or one with the cloud's
     * directory is a restart: its particles are part of the state */
    struct stat st;
    if (foam_file_exists(co)) /* v1912's barycentric cloud: needs the mesh's tet decomposition */
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                        "%s: not found: the cloud '%s' of time %s has only 'coordinates', OpenFOAM's barycentric "
                        "format (as mapFields and decomposePar write it), which %s does not read; run with "
                        "-reseed to seed new particles from %s of time %s", path, cloud, tname, ump_solver,
                        seed_from, tname);
    if (stat(ut, &st) == 0 || stat(cl, &st) == 0)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: not found: the restart from time %s has no particle cloud '%s' "
                        "(cloudName); run with -reseed to seed new particles from %s", path, tname, cloud,
                        seed_from);
    return UMP_OK; /* a first start (e.g. 0/): the particles are seeded */
}

static ump_status restart_cloud(app *a, const char *tname, ump_err *err)
{
    char dir[4400], path[4600];
    snprintf(dir, sizeof dir, "%s/%s", a->case_dir, tname);
    int restart;
    UMP_CALL(app_restart_policy(a->case_dir, tname, a->um.cloud_name, a->opt.reseed, "the fields", &restart,
                                err));
    if (!restart)
        return UMP_OK;
    size_t n = 0, dropped = 0;
    double *pos = NULL, *vel = NULL, *xy = NULL, *T = NULL;
    int64_t *id = NULL;
    ump_idx *cell = NULL;
    const fld_field *dig[2];
    UMP_CALL(app_check_digest(dir, tname, a->um.cloud_name, a->ctl.write_binary, a->ctl.write_precision,
                              digest_fields(a, dig), a->T ? 2 : 1, err));
    UMP_CALL(fio_read_cloud(dir, a->um.cloud_name, &n, &pos, &vel, &id, &cell, err));
    ump_status rc = UMP_OK;
    snprintf(path, sizeof path, "%s/lagrangian/%s/T", dir, a->um.cloud_name);
    if (a->T && foam_file_exists(path))
        rc = fio_read_cloud_field(dir, a->um.cloud_name, "T", 1, n, &T, err);
    xy = rc == UMP_OK ? ump_alloc_array(4 * n, sizeof *xy) : NULL;
    if (rc != UMP_OK) {
        /* the message is set */
    } else if (!xy) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
    } else {
        const int *ax = a->m->ax;
        for (size_t i = 0; i < n; i++) {
            xy[i] = pos[3 * i + (size_t)ax[0]];
            xy[n + i] = pos[3 * i + (size_t)ax[1]];
            xy[2 * n + i] = vel[3 * i + (size_t)ax[0]];
            xy[3 * n + i] = vel[3 * i + (size_t)ax[1]];
        }
        rc = sol_set_particles(a->S, n, xy, xy + n, xy + 2 * n, xy + 3 * n, T, id, cell, &dropped, err);
        if (rc == UMP_OK)
            printf("Restart: %zu particles read from %s/lagrangian/%s (%zu outside the mesh dropped)%s\n\n",
                   n - dropped, tname, a->um.cloud_name, dropped,
                   a->T && !T ? "; no particle T: the cell temperature" : "");
    }
    free(xy);
    free(T);
    free(pos);
    free(vel);
    free(id);
    free(cell);
    return rc;
}

/* The divergence guard's speed scale, from the start fields: the largest
 * of the boundary |U|, the initial |U|, nu/L, the Bernoulli speed
 * sqrt(2 dp) and the creeping-flow speed dp L / nu of the pressure
 * differences dp over the start p (p_rgh when buoyant), and, when buoyant,
 * the free-fall speed sqrt(|g| beta dT L) (L: the larger side of the mesh's
 * bounding box, dT: the range of the start T). */
/* The larger side of the bounding box of the cell centres (1 if none). */
static double mesh_extent(const mesh2d *m)
{
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (ump_idx c = 0; c < m->ncells; c++) {
        xmin = fmin(xmin, m->cx[c]);
        xmax = fmax(xmax, m->cx[c]);
        ymin = fmin(ymin, m->cy[c]);
        ymax = fmax(ymax, m->cy[c]);
    }
    double L = fmax(xmax - xmin, ymax - ymin);
    return L > 0 ? L : 1;
}

/* The largest |v|^2 of n vectors stored (x y z) in v (0 if v is NULL). */
static double largest_speed2(const double *v, size_t n)
{
    double u2 = 0;
    for (size_t i = 0; v && i < n; i++, v += 3)
        u2 = fmax(u2, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return u2;
}

static double speed_scale(const app *a)
{
    const mesh2d *m = a->m;
    double L = mesh_extent(m);
    const fld_field *U = a->U, *P = a->bu.on ? a->prgh : a->p;
    double u2 = largest_speed2(U->internal, (size_t)U->ncells);
    for (int p = 0; p < U->npatches; p++) {
        u2 = fmax(u2, largest_speed2(U->patch[p].value, (size_t)U->patch[p].n));
        /* boundary velocities that change in time: their bound over all t
         * (uniformValue; volumetricFlowRate / patch area) */
        const fld_patch *fp = &U->patch[p];
        if (fp->fn && fp->type == FLD_BC_UNIFORMFIXEDVALUE)
            u2 = fmax(u2, pow(f1_max_abs(fp->fn), 2));
        if (fp->fn && fp->type == FLD_BC_FLOWRATEINLETVELOCITY) {
            double area = mesh_patch_area(m, p, NULL);
            if (area > 0)
                u2 = fmax(u2, pow(f1_max_abs(fp->fn) / area, 2));
        }
    }
    double scale = fmax(sqrt(u2), a->tr.nu / L);
    const fld_field *rng[2] = {P, a->T};
    double dp = 0, dT = 0;
    for (int k = 0; k < 2; k++) {
        const fld_field *f = rng[k];
        if (!f)
            continue;
        double lo = INFINITY, hi = -INFINITY;
        for (ump_idx c = 0; c < f->ncells; c++) {
            lo = fmin(lo, f->internal[c]);
            hi = fmax(hi, f->internal[c]);
        }
        for (int p = 0; p < f->npatches; p++) {
            const fld_patch *fp = &f->patch[p];
            for (ump_idx i = 0; fp->value && i < fp->n; i++) {
                lo = fmin(lo, fp->value[i]);
                hi = fmax(hi, fp->value[i]);
            }
            /* totalPressure's p0; a uniformFixedValue's range over all t */
            for (ump_idx i = 0; fp->type == FLD_BC_TOTALPRESSURE && fp->aux && i < fp->n; i++) {
                lo = fmin(lo, fp->aux[i]);
                hi = fmax(hi, fp->aux[i]);
            }
            if (fp->fn && fp->type == FLD_BC_UNIFORMFIXEDVALUE && fp->n > 0) {
                lo = fmin(lo, -f1_max_abs(fp->fn));
                hi = fmax(hi, f1_max_abs(fp->fn));
            }
        }
        double d = hi > lo ? hi - lo : 0;
        if (k == 0)
            dp = d;
        else
            dT = d;
    }
    scale = fmax(scale, fmax(sqrt(2 * dp), a->tr.nu > 0 ? dp * L / a->tr.nu : 0));
    if (a->bu.on) {
        double g = sqrt(a->bu.g[0] * a->bu.g[0] + a->bu.g[1] * a->bu.g[1] + a->bu.g[2] * a->bu.g[2]);
        scale = fmax(scale, sqrt(g * fabs(a->tr.beta) * dT * L));
    }
    return scale;
}

/* A flow driven by its walls alone: no face lets fluid in or out (every
 * patch's U is noSlip, slip, a symmetry, empty, cyclic, or a fixed value
 * along the wall: movingWallVelocity, fixedValue with a zero normal part at
 * every face) and no buoyancy. Its velocities stay below the walls' and
 * the start field's largest speed, up to the overshoot of a singular
 * corner (1.28 x the lid speed in one cell of the Re 1000 cavity on 40^2,
 * 1.51 at Re 10 000 on 64^2 by t = 36):
 * closed_flow_factor x the speed scale is the divergence guard's default
 * there. Found by a user trial (2026-12-06): at Re 1000 on cells of aspect
 * ratio 2 to 5, and on graded cavities, UMPPM's velocities grew to 2-23 x
 * the lid speed and the runs ended without a word (README, "Unbounded on
 * coarse stretched cells at high Re"); a bound of 100 x let them. */
#define CLOSED_FLOW_FACTOR 2.0
/* a particle's own velocity, before Eq. 36's fit: at the impulsive start of
 * the skewed cavity one near the lid's corner had 1.52 x the lid speed */
#define CLOSED_PARTICLE_FACTOR 3.0
/* Below the guard, a closed flow's cell velocity above this factor of its
 * walls' speed is reported (a warning at the first step, the run's largest
 * at its end) rather than left silent: the bound for the graded
 * cavities, and what a run between it and CLOSED_FLOW_FACTOR had ended
 * with before, without a word (1.95 x the lid speed on 20 x 5 cells at
 * Re 1000; on the 8^2 cavity graded 1000:1 toward all walls at deltaT
 * 5e-5 1.19 in the fields written, 1.24 at a step between). One cell at a
 * lid's corner crosses it in converged runs too (1.28 at Re 1000 on 40^2):
 * such cells are left out of the warning (corner_cells), not of the
 * guard. */
#define CLOSED_WARN_FACTOR 1.05

/* The speed closed_flow's bound multiplies: the walls' largest speed and
 * nu/L, and the start field's largest speed on a first start or where no
 * wall moves. Not the pressure terms of speed_scale, nor a restart's start
 * field where walls move: that is the run's own, and its pressure range
 * (0.5 in the developed Re 1000 cavity, 500 as dp L / nu) or a velocity
 * already grown would lift the bound with the run it is there to stop. */
static double closed_speed(const app *a, const char *tname)
{
    const fld_field *U = a->U;
    double w2 = 0, u2 = largest_speed2(U->internal, (size_t)U->ncells);
    for (int p = 0; p < U->npatches; p++) {
        const fld_patch *fp = &U->patch[p];
        /* (not an empty patch: its values are its cells') */
        if (fp->type == FLD_BC_FIXEDVALUE || fp->type == FLD_BC_MOVINGWALLVELOCITY)
            w2 = fmax(w2, largest_speed2(fp->value, (size_t)fp->n));
    }
    char ut[4600];
    snprintf(ut, sizeof ut, "%s/%s/uniform/time", a->case_dir, tname);
    double s = sqrt(w2);
    if (!(s > 0) || !foam_file_exists(ut))
        s = fmax(s, sqrt(u2));
    return fmax(s, a->tr.nu / mesh_extent(a->m));
}

/* The 3-vector of U's value on boundary face f where its patch is a
 * fixedValue or movingWallVelocity with a value for that face, else NULL */
static const double *face_value(const app *a, ump_idx f)
{
    const mesh2d *m = a->m;
    int p = m->face_patch[f];
    const fld_patch *fp = &a->U->patch[p];
    if ((fp->type != FLD_BC_FIXEDVALUE && fp->type != FLD_BC_MOVINGWALLVELOCITY) || !fp->value)
        return NULL;
    ump_idx i = m->face_pm[f] - a->pm->patch[p].start;
    return i >= 0 && i < fp->n ? fp->value + 3 * (size_t)i : NULL;
}

static int closed_flow(const app *a)
{
    if (a->bu.on)
        return 0;
    const mesh2d *m = a->m;
    const fld_field *U = a->U;
    for (int p = 0; p < U->npatches; p++)
        switch (U->patch[p].type) {
        case FLD_BC_NOSLIP: case FLD_BC_SLIP: case FLD_BC_EMPTY: case FLD_BC_CYCLIC:
        case FLD_BC_SYMMETRYPLANE: case FLD_BC_SYMMETRY: case FLD_BC_FIXEDVALUE:
        case FLD_BC_MOVINGWALLVELOCITY:
            break;
        default:
            return 0; /* inflow, outflow, or a velocity that changes in time */
        }
    for (ump_idx f = m->ninternal; f < m->nfaces; f++) {
        int t = U->patch[m->face_patch[f]].type;
        if (t != FLD_BC_FIXEDVALUE && t != FLD_BC_MOVINGWALLVELOCITY)
            continue;
        const double *v = face_value(a, f);
        if (!v)
            return 0;
        double un = v[m->ax[0]] * m->nx[f] + v[m->ax[1]] * m->ny[f];
        /* (a tangential velocity on a curved wall written at 6 digits) */
        if (fabs(un) > 1e-5 * sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]))
            return 0;
    }
    return 1;
}

/* The prescribed velocity of boundary face f in *ux, *uy (noSlip: 0);
 * returns 0 where the velocity is not prescribed (slip, symmetry, empty,
 * cyclic) */
static int wall_velocity(const app *a, ump_idx f, double *ux, double *uy)
{
    *ux = *uy = 0;
    if (a->U->patch[a->m->face_patch[f]].type == FLD_BC_NOSLIP)
        return 1;
    const double *v = face_value(a, f);
    if (v) {
        *ux = v[a->m->ax[0]];
        *uy = v[a->m->ax[1]];
    }
    return v != NULL;
}

/* Closed flows: a->corner[c] = 1 for the cells with a vertex where faces
 * of two patches with different prescribed velocities meet (a lid's
 * corners; not the faces of one patch whose velocity turns along a curved
 * wall). Vertices by their representative after cyclic identification
 * (vert_id), so a corner on a cyclic seam is one vertex.
 * The velocity jumps there, and the one cell at it overshoots the wall's
 * speed in converged runs too (1.28 at the lid's downstream corner of the
 * Re 1000 cavity on 40^2 cells): the warning above 1.05 x the walls' speed
 * does not count those cells; the divergence guard does. */
static ump_status corner_cells(app *a, ump_err *err)
{
    const mesh2d *m = a->m;
    ump_idx nv = m->nverts;
    unsigned char *jump = calloc((size_t)nv, 1);
    double *vel = malloc(2 * (size_t)nv * sizeof *vel);
    int *patch = malloc((size_t)nv * sizeof *patch); /* of the face that set vel; -1: none yet */
    a->corner = calloc((size_t)m->ncells, 1);
    ump_status rc = UMP_OK;
    if (!jump || !vel || !patch || !a->corner) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "out of memory for the corner cells (%ld vertices)", (long)nv);
        goto out;
    }
    for (ump_idx v = 0; v < nv; v++)
        patch[v] = -1;
    for (ump_idx f = m->ninternal; f < m->nfaces; f++) {
        double ux, uy;
        if (!wall_velocity(a, f, &ux, &uy))
            continue;
        ump_idx ends[2] = {m->vert_id[m->fv0[f]], m->vert_id[m->fv1[f]]};
        for (int k = 0; k < 2; k++) {
            ump_idx v = ends[k];
            if (patch[v] < 0) {
                vel[2 * v] = ux;
                vel[2 * v + 1] = uy;
                patch[v] = m->face_patch[f];
            } else if (patch[v] != m->face_patch[f] &&
                       fabs(vel[2 * v] - ux) + fabs(vel[2 * v + 1] - uy) > 1e-9 * a->u_scale) {
                jump[v] = 1;
            }
        }
    }
    for (ump_idx c = 0; c < m->ncells; c++)
        for (ump_idx k = m->cell_off[c]; k < m->cell_off[c + 1]; k++)
            a->corner[c] |= jump[m->vert_id[m->cell_verts[k]]];
out:
    free(jump);
    free(vel);
    free(patch);
    return rc;
}

/* After a step: every particle velocity finite and within a->u_bound_p,
 * every cell's p and T finite, and the velocity of every cell that the
 * step computed (sol_cell_u_current: every cell at the steps that compute
 * the fields written, else the owners of boundary faces) within the bound
 * too; else an error naming the cell (or particle), the value, the bound
 * and the time. The other cells' velocities are not current (solver.h);
 * Eq. 36 fits them from the particles, which every step checks. *umax and
 * *cmax: the largest |U| of the cells checked but the corner cells
 * (corner_cells), and its cell; *every: all cells were checked. */
static ump_status check_divergence(const app *a, const char *tname, double *umax, ump_idx *cmax, int *every,
                                   ump_err *err)
{
    const double *u = sol_cell_u(a->S), *v = sol_cell_v(a->S), *p = sol_cell_p_projection(a->S);
    const double *T = sol_cell_T(a->S);
    const unsigned char *cur = sol_cell_u_current(a->S);
    const mesh2d *m = a->m;
    const double b2 = a->u_bound * a->u_bound;
    const double b2p = a->u_bound_p * a->u_bound_p;
    char why[160], whyp[160];
    if (a->um.max_velocity > 0) {
        snprintf(why, sizeof why, "UMPPM maxVelocity");
        snprintf(whyp, sizeof whyp, "UMPPM maxVelocity");
    } else if (a->closed) {
        snprintf(why, sizeof why, "%g x the largest wall or start speed %g of a flow driven by its walls alone; "
                 "UMPPM maxVelocity sets it", CLOSED_FLOW_FACTOR, a->u_scale);
        snprintf(whyp, sizeof whyp, "%g x the largest wall or start speed %g of a flow driven by its walls alone, "
                 "for a particle; UMPPM maxVelocity sets it", CLOSED_PARTICLE_FACTOR, a->u_scale);
    } else {
        snprintf(why, sizeof why, "100 x the speed scale %g; UMPPM maxVelocity sets it", a->u_scale);
        snprintf(whyp, sizeof whyp, "%s", why);
    }
    /* a smaller step does not help on the coarse stretched cells of
     * closed_flow's trial: there it made things worse */
    char fix[256];
    if (a->closed && a->um.max_velocity <= 0)
        snprintf(fix, sizeof fix, "%s (coarse or stretched cells at high Re: README, \"Unbounded on coarse "
                 "stretched cells at high Re\")", closed_remedy(a));
    else
        snprintf(fix, sizeof fix, "reduce deltaT or maxCo");
    double top = 0;
    ump_idx ctop = 0;
    for (ump_idx c = 0; c < m->ncells; c++) {
        double s2 = !cur || cur[c] ? u[c] * u[c] + v[c] * v[c] : 0.0;
        if (s2 > top && !(a->corner && a->corner[c])) {
            top = s2;
            ctop = c;
        }
        if (!(s2 <= b2))
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s: the solution diverged at time %s: |U| = %g in cell %ld at "
                            "(%g %g) exceeds the bound %g (%s); time %s is not written; %s", a->case_dir, tname,
                            sqrt(s2), (long)c, m->cx[c], m->cy[c], a->u_bound, why, tname, fix);
        if (!isfinite(p[c]) || (T && !isfinite(T[c])))
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s: the solution diverged at time %s: %s = %g in cell %ld at "
                            "(%g %g); time %s is not written; reduce deltaT or maxCo", a->case_dir, tname,
                            isfinite(p[c]) ? "T" : "p", isfinite(p[c]) ? T[c] : p[c], (long)c, m->cx[c],
                            m->cy[c], tname);
    }
    const part_set *P = sol_particles(a->S);
    for (size_t i = 0; i < P->n; i++) {
        double s2 = P->u[i] * P->u[i] + P->v[i] * P->v[i];
        if (!(s2 <= b2p))
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s: the solution diverged at time %s: |U| = %g of particle %lld "
                            "at (%g %g) exceeds the bound %g (%s); time %s is not written; %s", a->case_dir,
                            tname, sqrt(s2), (long long)P->id[i], P->x[i], P->y[i], a->u_bound_p, whyp, tname,
                            fix);
    }
    *umax = sqrt(top);
    *cmax = ctop;
    *every = cur == NULL;
    return UMP_OK;
}

/* Numbers-named non-directories in the case directory (files in the way of
 * time directories): their names, NUL-separated in *names (caller-freed),
 * and their count. */
static int blocking_files(const char *case_dir, char **names)
{
    *names = NULL;
    DIR *d = opendir(case_dir);
    if (!d)
        return 0;
    size_t len = 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        char *end;
        if (e->d_name[0] == '.' || e->d_name[0] == '\0')
            continue;
        (void)strtod(e->d_name, &end);
        if (*end != '\0')
            continue;
        char path[4400];
        struct stat st;
        snprintf(path, sizeof path, "%s/%s", case_dir, e->d_name);
        if (lstat(path, &st) != 0 || S_ISDIR(st.st_mode))
            continue;
        size_t k = strlen(e->d_name) + 1;
        char *grow = realloc(*names, len + k + 1);
        if (!grow)
            break;
        *names = grow;
        memcpy(grow + len, e->d_name, k);
        len += k;
        grow[len] = '\0';
        n++;
    }
    closedir(d);
    return n;
}

/* Before the run: when the write times can be known in advance (no
 * adjustTimeStep; writeControl timeStep, runTime or adjustableRunTime), a
 * file in the way of one of them is an error now rather than after the
 * steps before it. Otherwise fio_timedir_begin refuses it at write time. */
static ump_status check_planned_writes(const app *a, const rt_time *t0, ump_err *err)
{
    char *names = NULL;
    if (blocking_files(a->case_dir, &names) == 0)
        return UMP_OK;
    ump_status rc = UMP_OK;
    int known = !a->ctl.adjust_time_step && (a->ctl.write_control == CASE_WRITE_TIMESTEP ||
                                             a->ctl.write_control == CASE_WRITE_RUNTIME ||
                                             a->ctl.write_control == CASE_WRITE_ADJUSTABLERUNTIME);
    rt_time t = *t0;
    for (long k = 0; known && rc == UMP_OK && rt_running(&t) && k < 10000000; k++) {
        rt_advance(&t);
        if (!t.write_time)
            continue;
        for (const char *n = names; *n && rc == UMP_OK; n += strlen(n) + 1)
            if (strcmp(n, t.name) == 0)
                rc = fio_timedir_check(a->case_dir, t.name, err);
    }
    free(names);
    return rc;
}

/* The dimensions a field read must have, as OpenFOAM's solvers check them
 * (icoFoam stops with "incompatible dimensions"): U m/s, p and p_rgh the
 * kinematic pressure m^2/s^2 (p/rho), T K. */
static ump_status check_dimensions(const fld_field *f, const char *path, const char *name, ump_err *err)
{
    static const struct { const char *name, *units; double d[7]; } want[] = {
        {"U", "m/s", {0, 1, -1, 0, 0, 0, 0}},
        {"p", "kinematic pressure m^2/s^2, p/rho, as icoFoam", {0, 2, -2, 0, 0, 0, 0}},
        {"p_rgh", "kinematic pressure m^2/s^2, as buoyantBoussinesqPimpleFoam", {0, 2, -2, 0, 0, 0, 0}},
        {"T", "K", {0, 0, 0, 1, 0, 0, 0}},
    };
    for (size_t k = 0; k < sizeof want / sizeof want[0]; k++) {
        if (strcmp(name, want[k].name) != 0)
            continue;
        const double *d = f->dims, *w = want[k].d;
        int same = 1;
        for (int j = 0; j < 7; j++)
            same &= d[j] == w[j];
        if (same)
            return UMP_OK;
        return UMP_FAIL(err, UMP_ERR_INPUT,
                        "%s: dimensions [%g %g %g %g %g %g %g]; %s must have [%g %g %g %g %g %g %g] (%s)", path,
                        d[0], d[1], d[2], d[3], d[4], d[5], d[6], name, w[0], w[1], w[2], w[3], w[4], w[5], w[6],
                        want[k].units);
    }
    return UMP_OK;
}

/* setRefCell.C: where no patch fixes the solved pressure (fixedValue,
 * uniformFixedValue, totalPressure) its level needs pRefCell or pRefPoint
 * and pRefValue, which icoFoam and buoyantBoussinesqPimpleFoam require
 * then ("Unable to set reference cell", "Entry 'pRefValue' not found"). */
static ump_status check_reference(const app *a, const fld_field *pf, const char *name, ump_err *err)
{
    for (int p = 0; p < a->pm->npatches; p++)
        if (a->pm->patch[p].n > 0 && fld_bc_is_fixed(pf->patch[p].type))
            return UMP_OK;
    if (!a->so.has_p_ref_cell && !a->so.has_p_ref_point)
        return UMP_FAIL(err, UMP_ERR_INPUT,
                        "%s/system/fvSolution: %s: unable to set reference cell for field %s: no patch fixes %s, "
                        "so its level needs either pRefCell or pRefPoint (and pRefValue), as in icoFoam",
                        a->case_dir, a->so.algo, name, name);
    if (!a->so.has_p_ref_value)
        return UMP_FAIL(err, UMP_ERR_INPUT,
                        "%s/system/fvSolution: %s: entry 'pRefValue' not found: no patch fixes %s, so its level "
                        "needs pRefValue, as in icoFoam", a->case_dir, a->so.algo, name);
    return UMP_OK;
}

/* Read a start-time field; a missing optional one gets `calculated`
 * patches (values from like) instead. */
static ump_status read_start_field(app *a, const char *tname, const char *name, int ncomp, int optional,
                                   fld_field **out, ump_err *err)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/%s/%s", a->case_dir, tname, name);
    if (optional && !foam_file_exists(path)) {
        ump_idx *sizes = ump_alloc_array((size_t)a->pm->npatches + 1, sizeof *sizes);
        if (!sizes)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "out of memory");
        for (int p = 0; p < a->pm->npatches; p++)
            sizes[p] = a->pm->patch[p].n;
        ump_status rc = fld_create(name, ncomp, a->m->ncells, a->pm->npatches, sizes, out, err);
        free(sizes);
        if (rc == UMP_OK)
            for (int p = 0; p < a->pm->npatches; p++)
                if (a->pm->patch[p].kind == PMESH_EMPTY || a->pm->patch[p].kind == PMESH_CYCLIC)
                    (*out)->patch[p].type = a->pm->patch[p].kind == PMESH_EMPTY ? FLD_BC_EMPTY
                                                                                  : FLD_BC_CYCLIC;
        return rc;
    }
    printf("Reading field %s\n\n", name);
    UMP_CALL(fio_read_field(path, a->pm, ncomp, out, err));
    return check_dimensions(*out, path, name, err);
}

/* 1 if the tokens of a value (uniform x, nonuniform List<scalar> n (...),
 * binary or not, a Function1 `constant x` or `table ((t x) ...)`) hold no
 * number but zeros (the list's size n and a table's times aside). */
static int tokens_zero(const foam_token *t, size_t n)
{
    int table = n > 0 && t[0].type == FOAM_TOK_WORD && strcmp(t[0].v.str, "table") == 0;
    int depth = 0, elem = 0;
    for (size_t i = 0; i < n; i++) {
        if (t[i].type == FOAM_TOK_PUNCT && t[i].v.punct == '(') {
            depth++, elem = 0;
            continue;
        }
        if (t[i].type == FOAM_TOK_PUNCT && t[i].v.punct == ')') {
            depth--;
            continue;
        }
        if (table && depth == 2 && elem++ == 0)
            continue; /* a table row's time */
        if (t[i].type == FOAM_TOK_LABEL && i > 0 && t[i - 1].type == FOAM_TOK_WORD &&
            strncmp(t[i - 1].v.str, "List", 4) == 0)
            continue; /* the size of a nonuniform list */
        if ((t[i].type == FOAM_TOK_LABEL && t[i].v.label != 0) ||
            (t[i].type == FOAM_TOK_SCALAR && t[i].v.scalar != 0))
            return 0;
        if (t[i].type == FOAM_TOK_BLOB)
            for (size_t k = 0; k < t[i].v.blob.n * (size_t)t[i].v.blob.ncomp; k++)
                if (t[i].v.blob.is_label ? ((const int64_t *)t[i].v.blob.data)[k] != 0
                                         : ((const double *)t[i].v.blob.data)[k] != 0)
                    return 0;
        if (t[i].type == FOAM_TOK_DICT)
            return 0; /* a Function1 dictionary: not a plain zero */
    }
    return 1;
}

/* alphat in laminar flow (see the top of the file): a patch that keeps its
 * own value must keep zero. */
static ump_status check_alphat(const foam_file *f, const char *path, ump_err *err)
{
    const foam_dict *bf = foam_dict_sub(f->dict, "boundaryField");
    if (!bf)
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s: boundaryField dictionary is missing", path);
    static const char *const reset[] = {"calculated", "zeroGradient", "empty", "cyclic", "symmetryPlane",
                                        "symmetry", "wedge", "processor"};
    static const char *const keys[] = {"value", "gradient", "uniformValue", "refValue", "refGradient", "inletValue"};
    for (size_t i = 0; i < bf->n; i++) {
        const foam_entry *e = &bf->e[i];
        const char *type = NULL;
        if (!e->dict)
            continue;
        UMP_CALL(foam_get_word(e->dict, "type", &type, err));
        /* wall functions recompute alphat from nut, zero in laminar flow */
        int keeps = !strstr(type, "WallFunction");
        for (size_t k = 0; k < sizeof reset / sizeof *reset; k++)
            keeps &= strcmp(type, reset[k]) != 0;
        for (size_t k = 0; keeps && k < sizeof keys / sizeof *keys; k++) {
            const foam_entry *v = foam_dict_find(e->dict, keys[k], 0);
            if (v && (v->dict || !tokens_zero(v->tok, v->ntok)))
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "%s:%d: patch '%s': alphat %s with a non-zero %s: buoyantBoussinesqPimpleFoam "
                                "keeps it and adds it to the heat conduction there (alphaEff = nu/Pr + alphat); "
                                "umppmFoam solves laminar flow with alphat = 0 (set it to 0, or use calculated)",
                                v->file, v->line, e->key, type, keys[k]);
        }
    }
    return UMP_OK;
}

/* p_rgh zeroGradient where U is fixed: buoyantBoussinesqPimpleFoam then
 * lets the buoyancy flux phig = -gh_f snGrad(rhok) |S_f| cross the patch
 * (non-zero at a wall hotter or colder than its cells); umppmFoam's
 * pressure equation is in fluxes and keeps the flux U_b . S_f, i.e.
 * fixedFluxPressure: a different answer, so refused by name where T is
 * fixed there (fixedValue, inletOutlet). Where T is zeroGradient (an
 * adiabatic wall) snGrad(rhok) = 0 and the two conditions agree. */
static ump_status check_prgh_walls(const app *a, const char *tname, ump_err *err)
{
    for (int p = 0; p < a->pm->npatches; p++)
        if (a->pm->patch[p].n > 0 && a->prgh->patch[p].type == FLD_BC_ZEROGRADIENT &&
            fld_bc_is_fixed(a->U->patch[p].type) &&
            (fld_bc_is_fixed(a->T->patch[p].type) || a->T->patch[p].type == FLD_BC_INLETOUTLET))
            return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                            "%s/%s/p_rgh: patch '%s': zeroGradient p_rgh where U (%s) and T are fixed is not implemented "
                            "by umppmFoam: buoyantBoussinesqPimpleFoam lets the buoyancy flux through such a "
                            "patch, umppmFoam keeps the flux of U as fixedFluxPressure does; use "
                            "fixedFluxPressure, as OpenFOAM's buoyant tutorials do", a->case_dir,
                            tname, a->pm->patch[p].name, fld_bc_name(a->U->patch[p].type));
    return UMP_OK;
}

/* A restart with adjustTimeStep goes on with the deltaT of the start time's
 * uniform/time, as OpenFOAM's Time (it had started from controlDict's
 * deltaT, growing by 1.2 per step, until 2026-12-06: U 1.6 % from the
 * uninterrupted run on the cavity). */
static ump_status restore_delta_t(const app *a, rt_time *t, const char *tname, ump_err *err)
{
    double dt;
    int has;
    if (!a->ctl.adjust_time_step)
        return UMP_OK;
    UMP_CALL(case_read_time_delta_t(a->case_dir, tname, &dt, &has, err));
    if (has) {
        rt_restore_delta_t(t, dt);
        printf("deltaT = %g from %s/uniform/time (adjustTimeStep)\n", t->delta_t, tname);
    }
    return UMP_OK;
}

/* The buoyant part of the set-up: g, Boussinesq constants, T, p_rgh, p,
 * alphat (see the top of the file). */
static ump_status read_buoyant(app *a, const char *tname, ump_err *err)
{
    char path[4400];
    UMP_CALL(case_require_boussinesq(a->case_dir, &a->tr, err));
    printf("Reading field T\n\n");
    snprintf(path, sizeof path, "%s/%s/T", a->case_dir, tname);
    if (!foam_file_exists(path))
        return UMP_FAIL(err, UMP_ERR_IO, "%s: not found: a buoyant case (constant/g present) needs the "
                        "temperature field T", path);
    UMP_CALL(fio_read_field(path, a->pm, 1, &a->T, err));
    UMP_CALL(check_dimensions(a->T, path, "T", err));
    UMP_CALL(read_start_field(a, tname, "p_rgh", 1, 0, &a->prgh, err));
    snprintf(path, sizeof path, "%s/%s/alphat", a->case_dir, tname);
    if (foam_file_exists(path)) {
        foam_file *f = NULL;
        printf("Reading field alphat (laminar: zero, written as read)\n\n");
        UMP_CALL(foam_read_text(path, &a->alphat_text, &a->alphat_len, err));
        UMP_CALL(foam_file_parse(path, a->alphat_text, a->alphat_len, &f, err));
        ump_status rc = check_alphat(f, path, err);
        foam_file_free(&f);
        UMP_CALL(rc);
    }
    printf("Calculating field g.h (g = (%g %g %g), hRef = %g)\n\n", a->bu.g[0], a->bu.g[1], a->bu.g[2],
           a->bu.h_ref);
    return UMP_OK;
}

/* Mesh-only, at the start and at a re-read of controlDict: function object
 * c's patch, its 2-D boundary faces (f >= ninternal), their 3-D areas and
 * centres; *cap grows to the number of faces. */
static ump_status fo_resolve(app *a, fob_common *c, size_t *cap_faces, ump_err *err)
{
    int pi = -1;
    for (int p = 0; p < a->pm->npatches; p++)
        if (strcmp(a->pm->patch[p].name, c->patch) == 0)
            pi = p;
    if (pi < 0)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s/system/controlDict: function object '%s': no patch '%s' "
                        "in constant/polyMesh/boundary", a->case_dir, c->name, c->patch);
    const pmesh_patch *pp = &a->pm->patch[pi];
    const mesh2d *m = a->m;
    size_t cap = (size_t)pp->n, n = 0;
    ump_idx *face = ump_alloc_array(cap ? cap : 1, sizeof *face);
    double *area = ump_alloc_array(cap ? cap : 1, sizeof *area), *x3 = ump_alloc_array(3 * cap + 3, sizeof *x3);
    ump_status rc = UMP_OK;
    if (!face || !area || !x3) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (ump_idx i = 0; i < pp->n; i++) {
        ump_idx f = m->pmface_to_face[pp->start + i];
        if (f < m->ninternal)
            continue;
        face[n] = f;
        mesh_to3d(m, m->fx[f], m->fy[f], x3 + 3 * n);
        area[n] = m->len[f] * (m->zmax - m->zmin);
        n++;
    }
    if (n == 0)
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s/system/controlDict: function object '%s': patch '%s' has no "
                      "boundary faces in 2-D (empty or cyclic)", a->case_dir, c->name, c->patch);
    else
        rc = fob_set_faces(c, n, face, area, x3, err);
    if (n > *cap_faces)
        *cap_faces = n;
done:
    free(face);
    free(area);
    free(x3);
    return rc;
}

/* Resolve every function object's patch of L and check its fields; *cap
 * gets the largest patch (faces). */
static ump_status fo_resolve_list(app *a, fob_list *L, size_t *cap, ump_err *err)
{
    *cap = 0;
    for (int i = 0; i < L->n; i++)
        UMP_CALL(fo_resolve(a, &L->nu[i].c, cap, err));
    for (int i = 0; i < L->nsf; i++) {
        fob_sfv *f = &L->sf[i];
        UMP_CALL(fo_resolve(a, &f->c, cap, err));
        for (int j = 0; j < f->nfields; j++)
            if (!a->bu.on && (f->field[j] == FOB_FIELD_T || f->field[j] == FOB_FIELD_P_RGH))
                return UMP_FAIL(err, UMP_ERR_INPUT, "%s/system/controlDict: function object '%s': field '%s' "
                                "exists only in a buoyant case (constant/g)", a->case_dir, f->c.name,
                                fob_field_name(f->field[j]));
    }
    return UMP_OK;
}

/* The per-face scratch of the function objects, for patches of up to cap
 * faces (grown, never shrunk: a->fo_cap is what it holds). */
static ump_status fo_scratch(app *a, size_t cap, ump_err *err)
{
    if (cap <= a->fo_cap && a->fo_val)
        return UMP_OK;
    size_t c = cap > a->fo_cap ? cap : a->fo_cap;
    if (c == 0)
        c = 1;
    double *d = ump_alloc_array(c, sizeof(double)), *T = ump_alloc_array(c, sizeof(double));
    double *v = ump_alloc_array(3 * FOB_MAX_FIELDS * c, sizeof(double));
    if (!d || !T || !v) {
        free(d);
        free(T);
        free(v);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "out of memory");
    }
    free(a->fo_dTdn);
    free(a->fo_Tf);
    free(a->fo_val);
    a->fo_dTdn = d;
    a->fo_Tf = T;
    a->fo_val = v;
    a->fo_cap = c;
    return UMP_OK;
}

/* Resolve the function objects' patches, check their fields, size the
 * per-face scratch. */
static ump_status fo_setup(app *a, ump_err *err)
{
    size_t cap;
    UMP_CALL(fo_resolve_list(a, &a->fo, &cap, err));
    return fo_scratch(a, cap, err);
}

/* Patch data of a Nusselt function object for this step. */
static ump_status fo_nusselt_faces(app *a, const fob_nusselt *f, fob_faces *d, ump_err *err)
{
    const fob_common *c = &f->c;
    for (size_t k = 0; k < c->nface; k++) {
        UMP_CALL(sol_wall_dTdn(a->S, c->face[k], f->snGrad ? SOL_GRAD_SNGRAD : SOL_GRAD_MLS, &a->fo_dTdn[k],
                               err));
        a->fo_Tf[k] = sol_face_T(a->S, c->face[k]);
    }
    d->n = c->nface;
    d->x3 = c->x3;
    d->area = c->area;
    d->dTdn = a->fo_dTdn;
    d->Tf = a->fo_Tf;
    return UMP_OK;
}

/* The face values of surfaceFieldValue f's fields, as written in the time
 * directories (p and p_rgh of a buoyant run as buoyantBoussinesqPimpleFoam
 * defines them). */
static void fo_sfv_values(app *a, const fob_sfv *f, fob_patch_field *vals)
{
    const fob_common *c = &f->c;
    for (int j = 0; j < f->nfields; j++) {
        vals[j].n = c->nface;
        vals[j].ncomp = f->field[j] == FOB_FIELD_U ? 3 : 1;
        vals[j].area = c->area;
        vals[j].v = a->fo_val + 3 * (size_t)j * a->fo_cap;
    }
    for (size_t k = 0; k < c->nface; k++) {
        ump_idx fc = c->face[k];
        double u, w, p, prgh = 0;
        sol_face_values(a->S, fc, &u, &w, &p);
        if (a->T)
            sol_buoyant_pressure(a->S, -1, fc, &p, &prgh);
        for (int j = 0; j < f->nfields; j++) {
            double *v = (double *)vals[j].v;
            switch (f->field[j]) {
            case FOB_FIELD_U:
                v[3 * k + (size_t)a->m->normal] = 0;
                v[3 * k + (size_t)a->m->ax[0]] = u;
                v[3 * k + (size_t)a->m->ax[1]] = w;
                break;
            case FOB_FIELD_P: v[k] = p; break;
            case FOB_FIELD_P_RGH: v[k] = prgh; break;
            case FOB_FIELD_T: v[k] = sol_face_T(a->S, fc); break;
            }
        }
    }
}

/* Run the function objects after a step (and at the start, step 0). With
 * only_new, only those a re-read of controlDict has just made (not
 * continued), at the time of the re-read: OpenFOAM's Time::run executes
 * them right after readModifiedObjects. */
static ump_status run_functions(app *a, const rt_time *t, long step, const char *start_name, int only_new,
                                ump_err *err)
{
    for (int i = 0; i < a->fo.n; i++) {
        fob_nusselt *f = &a->fo.nu[i];
        if (only_new && f->c.continued)
            continue;
        int series = step == 0 || fob_due(&f->c, step, t->write_time), local = t->write_time && step > 0;
        if (!series && !local)
            continue;
        fob_faces d;
        UMP_CALL(fo_nusselt_faces(a, f, &d, err));
        fob_result r = fob_nusselt_eval(f, &d, a->tr.TRef);
        if (series) {
            UMP_CALL(fob_nusselt_append(f, a->case_dir, start_name, t->value, &r, a->ctl.write_precision, err));
            printf("nusseltNumber %s: patch %s Nu_avg = %g (min %g, max %g)\n", f->c.name, f->c.patch,
                   r.Nu_avg, r.Nu_min, r.Nu_max);
        }
        if (local)
            UMP_CALL(fob_nusselt_local(f, a->case_dir, t->name, &d, &r, a->ctl.write_precision, err));
    }
    for (int i = 0; i < a->fo.nsf; i++) {
        fob_sfv *f = &a->fo.sf[i];
        if (step == 0 || !fob_due(&f->c, step, t->write_time) || /* OpenFOAM's: not at the start */
            (only_new && f->c.continued))
            continue;
        fob_patch_field vals[FOB_MAX_FIELDS];
        fo_sfv_values(a, f, vals);
        UMP_CALL(fob_sfv_append(f, a->case_dir, start_name, t->value, vals, a->ctl.write_precision, err));
        if (f->op == FOB_NONE)
            continue;
        printf("surfaceFieldValue %s write:\n", f->c.name); /* as OpenFOAM logs it */
        for (int j = 0; j < f->nfields; j++) {
            double out[3];
            fob_sfv_eval(f, &vals[j], out);
            printf("    %s(%s) of %s = ", fob_op_name(f->op), f->c.patch, fob_field_name(f->field[j]));
            if (vals[j].ncomp == 1)
                printf("%g\n", out[0]);
            else
                printf("(%g %g %g)\n", out[0], out[1], out[2]);
        }
    }
    return UMP_OK;
}

/* A surfaceFieldValue that reads p or p_rgh runs after step `step`
 * (run_functions' rule). */
static int functions_read_p(const app *a, const rt_time *t, long step)
{
    for (int i = 0; i < a->fo.nsf; i++) {
        const fob_sfv *f = &a->fo.sf[i];
        if (step == 0 || !fob_due(&f->c, step, t->write_time))
            continue;
        for (int j = 0; j < f->nfields; j++)
            if (f->field[j] == FOB_FIELD_P || f->field[j] == FOB_FIELD_P_RGH)
                return 1;
    }
    return 0;
}

/* The cell of the mesh holding pRefPoint (setRefCell.C: the point must be
 * in a cell, else "Unable to set reference cell"). The normal coordinate
 * must lie in the one-cell-thick slab. */
static ump_status locate_p_ref_point(app *a, ump_err *err)
{
    const double *P = a->so.p_ref_point;
    const mesh2d *m = a->m;
    double X = P[m->ax[0]], Y = P[m->ax[1]], Z = P[m->normal];
    a->p_ref_point_cell = -1;
    if (Z >= m->zmin && Z <= m->zmax)
        for (ump_idx c = 0; c < m->ncells && a->p_ref_point_cell < 0; c++)
            if (part_in_cell(m, c, X, Y))
                a->p_ref_point_cell = c;
    if (a->p_ref_point_cell < 0)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s/system/fvSolution: Unable to set reference cell for field p. "
                        "Reference point pRefPoint (%g %g %g) found on 0 domains (it is outside the mesh)",
                        a->case_dir, P[0], P[1], P[2]);
    return UMP_OK;
}

/* Everything read before the fields: transportProperties, fvSolution
 * (PISO/PIMPLE/SIMPLE and UMPPM), gravity, the function objects, the
 * pRefPoint cell. */
static ump_status read_settings(app *a, ump_err *err)
{
    const char *case_dir = a->case_dir;
    UMP_CALL(case_read_transport(case_dir, &a->tr, err));
    UMP_CALL(case_read_solution(case_dir, &a->so, err));
    UMP_CALL(case_read_umppm(case_dir, &a->um, err));
    UMP_CALL(case_read_buoyancy(case_dir, &a->bu, err));
    if (a->bu.on)
        UMP_CALL(case_require_boussinesq(case_dir, &a->tr, err));
    UMP_CALL(fob_read(case_dir, &a->fo, err));
    UMP_CALL(feat_ddt_scheme(case_dir, a->ddt, sizeof a->ddt, err));
    if (a->so.has_p_ref_point)
        UMP_CALL(locate_p_ref_point(a, err));
    return UMP_OK;
}

ump_status app_check_case(const char *case_dir, const case_control *c, const char *tname, double t0,
                          ump_err *err)
{
    UMP_CALL(case_check_start(case_dir, c, tname, t0, err));
    return feat_check_case(case_dir, tname, err);
}

ump_status app_check_settings(const char *case_dir, pmesh *pm, mesh2d *m, ump_err *err)
{
    app a;
    memset(&a, 0, sizeof a);
    a.case_dir = case_dir;
    a.pm = pm; /* borrowed */
    a.m = m;
    ump_status rc = read_settings(&a, err);
    if (rc == UMP_OK)
        rc = fo_setup(&a, err);
    a.pm = NULL;
    a.m = NULL;
    app_free(&a);
    return rc;
}

static void recover_report(void *ctx, fio_recovery what, const char *hidden, const char *tname, long pid)
{
    (void)ctx;
    switch (what) {
    case FIO_RECOVERED:
        printf("Recovered time %s from %s (a run was killed during its overwrite)\n", tname, hidden);
        break;
    case FIO_REMOVED_TMP:
        printf("Removed incomplete %s (process %ld was killed while writing time %s)\n", hidden, pid, tname);
        break;
    case FIO_REMOVED_OLD:
        printf("Removed %s (the previous version of time %s; the new one is in place)\n", hidden, tname);
        break;
    case FIO_REMOVED_DEL:
        printf("Removed %s (process %ld was killed while purgeWrite deleted time %s)\n", hidden, pid, tname);
        break;
    case FIO_LEFT_BLOCKED:
        printf("--> umppmFoam Warning: %s kept: it is time %s of a run killed during its overwrite, and a "
               "non-directory named %s is in the way of recovering it\n", hidden, tname, tname);
        break;
    case FIO_LEFT_RUNNING:
        printf("--> umppmFoam Warning: %s left alone: process %ld is running (another run in this case?)\n",
               hidden, pid);
        break;
    }
}

ump_status app_recover(const char *case_dir, ump_err *err)
{
    return fio_recover(case_dir, recover_report, NULL, err);
}


/* runTimeModifiable, at the start of each time step (Time::run calls
 * readModifiedObjects): when system/controlDict is another version than
 * the one read last (case_stamp), re-read it with every check of the
 * start-up (case_read_control, endTime not before the run's start time
 * t0, the function objects and their patches). A file that fails them is
 * a warning naming the file, the line and the entry, and the run goes on
 * with the settings it has; otherwise t, a->ctl and the function objects
 * take the new settings. Only running out of memory, or a file in the way
 * of a write time the new settings plan, is an error. */
int app_control_modified(const char *path, const char *shown, case_stamp *stamp, int *missing)
{
    case_stamp now;
    if (case_file_stamp(path, &now) != 0) {
        if (!*missing)
            printf("--> %s Warning: %s: cannot read (%s); the run continues with the settings it has\n",
                   ump_solver, shown, strerror(errno));
        *missing = 1;
        return 0;
    }
    *missing = 0;
    if (case_stamp_equal(&now, stamp))
        return 0;
    *stamp = now;
    printf("regIOobject::readIfModified() : Re-reading object controlDict from file \"%s\"\n", shown);
    return 1;
}

int app_control_apply(rt_time *t, case_control *ctl, const case_control *c)
{
    char what[2048];
    case_control_changes(ctl, c, t->delta_t_changed, what, sizeof what);
    printf("controlDict: %s\n", what[0] ? what : "no setting changed");
    rt_reread(t, c);
    *ctl = *c;
    if (!c->run_time_modifiable)
        printf("runTimeModifiable false: system/controlDict is no longer watched\n");
    if (!rt_running(t))
        printf("endTime %g is not after the current time %s: the run ends\n", t->ctl.end_time, t->name);
    return c->run_time_modifiable;
}

static ump_status reread_control(app *a, rt_time *t, double t0, const char *tname, long step, ump_err *err)
{
    if (!app_control_modified(a->ctl_path, a->ctl_abs, &a->ctl_stamp, &a->ctl_missing))
        return UMP_OK;
    case_control c;
    fob_list fo;
    memset(&fo, 0, sizeof fo);
    size_t cap = 0;
    ump_err e;
    memset(&e, 0, sizeof e);
    ump_status rc;
    if ((rc = case_read_control(a->case_dir, &c, &e)) != UMP_OK ||
        (rc = case_check_start(a->case_dir, &c, tname, t0, &e)) != UMP_OK ||
        (rc = fob_read(a->case_dir, &fo, &e)) != UMP_OK || (rc = fo_resolve_list(a, &fo, &cap, &e)) != UMP_OK) {
        fob_free(&fo);
        if (rc == UMP_ERR_NOMEM) {
            *err = e;
            return rc;
        }
        printf("--> umppmFoam Warning: %s; the re-read controlDict is not used: the run continues with the "
               "settings it has\n\n", e.msg);
        return UMP_OK;
    }
    a->ctl_watch = app_control_apply(t, &a->ctl, &c);
    /* the function objects: the new list replaces the old one (not run
     * with -noFunctionObjects, but checked) */
    if (a->opt.no_function_objects) {
        fob_free(&fo);
    } else {
        if ((rc = fo_scratch(a, cap, err)) != UMP_OK) {
            fob_free(&fo);
            return rc;
        }
        fob_take_over(&fo, &a->fo, t->name);
        if (fo.n + fo.nsf + a->fo.n + a->fo.nsf > 0) {
            printf("Function objects:");
            for (int i = 0; i < fo.n + fo.nsf; i++) {
                const fob_common *fc = i < fo.n ? &fo.nu[i].c : &fo.sf[i - fo.n].c;
                printf("%s %s (%s, %s)", i ? "," : "", fc->name, i < fo.n ? "nusseltNumber" : "surfaceFieldValue",
                       fc->continued ? "continued" : "new");
            }
            printf("%s\n", fo.n + fo.nsf ? "" : " none");
        }
        fob_free(&a->fo);
        a->fo = fo;
        /* the new ones run now, on the state of the current time */
        if ((rc = run_functions(a, t, step, tname, 1, err)) != UMP_OK)
            return rc;
    }
    if (fo.ignored[0])
        printf("--> umppmFoam Warning: function objects not run by umppmFoam (ignored): %s\n", fo.ignored);
    printf("\n");
    return check_planned_writes(a, t, err);
}

ump_status app_run(const char *case_dir, const app_options *opt, ump_err *err)
{
    app a;
    memset(&a, 0, sizeof a);
    a.case_dir = case_dir;
    if (opt)
        a.opt = *opt;
    ump_status rc;
    char tname[256], pmdir[4096];
    double t0, wall0 = wall_seconds();
    clock_t cpu0 = clock();
    sol_settings s;
    printf("Create time\n\n");
    snprintf(a.ctl_path, sizeof a.ctl_path, "%s/system/controlDict", case_dir);
    {
        char abs[4096];
        if (realpath(case_dir, abs))
            snprintf(a.ctl_abs, sizeof a.ctl_abs, "%s/system/controlDict", abs);
        else
            snprintf(a.ctl_abs, sizeof a.ctl_abs, "%s", a.ctl_path);
    }
    /* the version read now: taken before the read, so an edit in between
     * is seen at the first step */
    (void)case_file_stamp(a.ctl_path, &a.ctl_stamp);
    if ((rc = app_recover(case_dir, err)) != UMP_OK ||
        (rc = case_read_control(case_dir, &a.ctl, err)) != UMP_OK ||
        (rc = case_start_dir(case_dir, &a.ctl, tname, sizeof tname, &t0, err)) != UMP_OK ||
        (rc = app_check_case(case_dir, &a.ctl, tname, t0, err)) != UMP_OK)
        goto done;
    snprintf(pmdir, sizeof pmdir, "%s/constant/polyMesh", case_dir);
    printf("Create mesh for time = %s\n\n", tname);
    if ((rc = pmesh_read(pmdir, &a.pm, err)) != UMP_OK || (rc = mesh_build(a.pm, &a.m, err)) != UMP_OK)
        goto done;
    a.aspect = most_stretched(a.m, &a.aspect_cell);
    printf("Reading transportProperties\n\n");
    if ((rc = read_settings(&a, err)) != UMP_OK)
        goto done;
    if (a.opt.no_function_objects && (a.fo.n || a.fo.nsf)) {
        /* -noFunctionObjects: read (so a broken entry is still refused), not run */
        printf("Function objects: %d in system/controlDict, not run (-noFunctionObjects)\n\n",
               a.fo.n + a.fo.nsf);
        fob_free(&a.fo);
        memset(&a.fo, 0, sizeof a.fo);
    }
    if (a.bu.on && (rc = read_buoyant(&a, tname, err)) != UMP_OK)
        goto done;
    if ((rc = read_start_field(&a, tname, "p", 1, a.bu.on, &a.p, err)) != UMP_OK ||
        (rc = read_start_field(&a, tname, "U", 3, 0, &a.U, err)) != UMP_OK ||
        (rc = check_reference(&a, a.bu.on ? a.prgh : a.p, a.bu.on ? "p_rgh" : "p", err)) != UMP_OK ||
        (a.bu.on && (rc = check_prgh_walls(&a, tname, err)) != UMP_OK))
        goto done;
    a.closed = closed_flow(&a); /* for the autos and the divergence guard */
    a.stretched_quads = stretched_quads(a.m);
    a.star = app_variant_star(&a);
    if ((rc = settings(&a, &s, err)) != UMP_OK)
        goto done;
    s.t_start = t0; /* time-dependent boundary conditions without a value start here */
    if (a.fo.ignored[0])
        printf("--> umppmFoam Warning: function objects not run by umppmFoam (ignored): %s\n\n",
               a.fo.ignored);
    int lap_auto = app_laplacian_auto(&a), theta_auto = a.um.p_theta < 0;
    int variant_auto = a.um.variant_star < 0;
    printf("UMPPM: variant %s%s, alpha %g, laplacian %s%s", a.star ? "UMPPM*" : "UMPPM",
           variant_auto ? " (auto)" : "", a.um.alpha, lap_name(s.lap.model), lap_auto ? " (auto)" : "");
    if (s.lap.model != LAP_CPM && s.lap.model != LAP_CPM4)
        printf(" (r_e = %g x spacing)", lap_re_factor(&s.lap));
    if (s.p_theta > 0)
        printf(", pressureTheta %g%s", s.p_theta, theta_auto ? " (auto)" : "");
    if (sol_q_transpose(&s))
        printf(", interpolationError transpose%s", a.um.q_transpose < 0 ? " (auto)" : "");
    if (a.bu.on)
        printf(", buoyancy %s", a.um.buoyancy_balanced ? "balanced" : "source");
    printf(", PPE solver %s, predictor BiCGSTAB/%s tolerance %g\n", a.um.ppe_solver, a.um.pred_pc,
           a.um.pred_tol);
    if (theta_auto && s.p_theta > 0 && app_has_boundaries(&a))
        printf("A flow driven by its walls alone on a mesh of triangles: pressureTheta auto (0.5), the "
               "trapezoidal pressure along the path (README, \"Triangles at icoFoam's step\"); "
               "pressureTheta 0 is the paper's Eq. 10\n");
    else if ((lap_auto && s.lap.model == LAP_CPM4) || (theta_auto && s.p_theta > 0))
        printf("The mesh has no wall, inlet or outlet (every patch empty or cyclic): %s%s%s %s the "
               "settings for flows without walls (README, \"Settings for flows without walls\"); "
               "laplacian CPM and pressureTheta 0 are the paper's method\n",
               lap_auto ? "laplacian auto (CPM4)" : "", lap_auto && theta_auto ? " and " : "",
               theta_auto ? "pressureTheta auto (0.5)" : "", lap_auto && theta_auto ? "take" : "takes");
    if (a.um.face_support < 0 && s.face_support_tri != s.face_support && triangles(a.m) > 0)
        printf("A flow driven by its walls alone on a mesh with triangles: faceSupport auto (%g cell extents "
               "at the faces beside a triangle, %g elsewhere: the fits of u* at the faces; README, \"Face fits "
               "on triangles\"); faceSupport %g is mlsSupport's\n",
               s.face_support_tri, s.face_support, s.face_support);
    if (variant_auto && !a.star)
        printf("A flow driven by its walls alone on quadrilaterals that are not square (%ld of %ld cells "
               "stretched beyond %g:1): variant auto (UMPPM, the adaptive variant; README, \"Non-square "
               "cells at Re 1000\"); variant UMPPMstar, one particle per cell, is the paper's UMPPM*\n",
               (long)a.stretched_quads, (long)a.m->ncells, APP_QUAD_SQUARE);
    printf("Time scheme: ddtSchemes %s; umppmFoam runs its first-order implicit UMPPM step (Eq. 14) "
           "for Euler and backward alike\n", a.ddt);
    printf("Threads: %d (OpenMP; set OMP_NUM_THREADS to change; 1 where other runs share these cores: README, "
           "\"Runs sharing the cores\")\n\n", sol_threads());
    double tb = wall_seconds();
    if (a.bu.on)
        printf("Boussinesq buoyancy: beta %g, TRef %g, Pr %g (thermal diffusivity nu/Pr = %g); "
               "energy on the particles (Eq. 37)\n\n", a.tr.beta, a.tr.TRef, a.tr.Pr, s.kappa);
    if ((rc = sol_create(a.m, &s, a.U, a.bu.on ? a.prgh : a.p, a.T, &a.S, err)) != UMP_OK ||
        (rc = restart_cloud(&a, tname, err)) != UMP_OK)
        goto done;
    printf("Pressure mesh: %ld cells; PPE matrix assembled and factorized once (%.3g s); "
           "%zu particles\n\n", (long)a.m->ncells, wall_seconds() - tb, sol_particles(a.S)->n);
    report_stretched(a.m, a.aspect, a.aspect_cell, s.anisotropic, a.um.anisotropic < 0);

    rt_time t;
    rt_init(&t, &a.ctl, t0, tname);
    if ((rc = restore_delta_t(&a, &t, tname, err)) != UMP_OK || (rc = check_planned_writes(&a, &t, err)) != UMP_OK)
        goto done;
    a.u_scale = a.closed ? closed_speed(&a, tname) : speed_scale(&a);
    if (a.closed && (rc = corner_cells(&a, err)) != UMP_OK)
        goto done;
    a.u_bound = a.um.max_velocity > 0 ? a.um.max_velocity : (a.closed ? CLOSED_FLOW_FACTOR : 100) * a.u_scale;
    a.u_bound_p = a.um.max_velocity > 0 || !a.closed ? a.u_bound : CLOSED_PARTICLE_FACTOR * a.u_scale;
    if (a.closed && a.um.max_velocity <= 0)
        printf("Divergence guard: |U| <= %g in the cells, %g of a particle (%g and %g x the largest wall or start "
               "speed: a flow driven by its walls alone)\n", a.u_bound, a.u_bound_p, CLOSED_FLOW_FACTOR,
               CLOSED_PARTICLE_FACTOR);
    else
        printf("Divergence guard: |U| <= %g (%s)\n", a.u_bound,
               a.um.max_velocity > 0 ? "UMPPM maxVelocity" : "100 x the speed scale of the start fields");
    if (stopsig_install() != 0)
        printf("--> umppmFoam Warning: cannot install the SIGINT/SIGTERM handler: %s\n", strerror(errno));
    double co_mean, co_max;
    if (a.ctl.adjust_time_step) {
        sol_courant(a.S, t.delta_t, &co_mean, &co_max);
        rt_set_initial_delta_t(&t, co_max);
    }
    printf("\nStarting time loop\n\n");
    long step = 0;
    double cont_cumulative = 0;
    double stage_cpu[SOL_NSTAGES] = {0}, stage_wall[SOL_NSTAGES] = {0};
    size_t run_left = 0, run_walled = 0; /* particles: over the run */
    long co_over = 0;                     /* steps at a Courant number above 1 */
    double co_peak = 0;
    long fast_over = 0;                   /* closed flow: steps above CLOSED_WARN_FACTOR */
    double fast_peak = 0;                 /* ... the largest cell |U| of those steps */
    ump_idx fast_cell = 0;
    char fast_time[64] = "";
    int fast_partial = 0;                 /* ... some steps checked the cells at boundaries only */
    if ((rc = fo_setup(&a, err)) != UMP_OK || (rc = run_functions(&a, &t, 0, tname, 0, err)) != UMP_OK)
        goto done;
    a.ctl_watch = a.ctl.run_time_modifiable;
    while (rt_running(&t)) {
        /* runTimeModifiable: Time::run re-reads controlDict before each step */
        if (a.ctl_watch) {
            if ((rc = reread_control(&a, &t, t0, tname, step, err)) != UMP_OK)
                goto done;
            if (!rt_running(&t))
                break;
        }
        sol_courant(a.S, t.delta_t, &co_mean, &co_max);
        printf("Courant Number mean: %g max: %g\n", co_mean, co_max);
        double dt_co = t.delta_t;
        if (a.ctl.adjust_time_step) {
            rt_adjust_delta_t(&t, co_max);
            printf("deltaT = %g\n", t.delta_t);
        }
        /* the step's own Courant number (after adjustTimeStep); above 1 the
         * particles cross more than a cell per step (README, "Defaults by
         * accuracy per CPU second") */
        double co_step = dt_co > 0 ? co_max * t.delta_t / dt_co : co_max;
        rt_advance(&t);
        sol_set_time(a.S, t.value); /* time-dependent boundary conditions at the new time */
        if (t.precision_raised)
            printf("--> umppmFoam Warning: increased the timePrecision to %d to distinguish between "
                   "timeNames at time %s\n", t.precision, t.name);
        printf("Time = %s\n\n", t.name);
        if (co_step > 1) {
            if (co_over++ == 0)
                printf("--> umppmFoam Warning: Courant number %g > 1 in this step: particles cross more than one "
                       "cell per step, and umppmFoam's results then depend strongly on the step (README, "
                       "\"Defaults by accuracy per CPU second\": Co 0.5 where there are walls); reduce deltaT, or "
                       "set adjustTimeStep yes; maxCo 0.5; (the steps above 1 are counted at the end of the "
                       "run)\n\n", co_step);
            co_peak = co_step > co_peak ? co_step : co_peak;
        }
        /* the fields written cost a pass of their own (solver.h): only at
         * the steps that write them, feed a function object with p, may
         * stop on a signal, or end the run (a signal during the last step
         * writes it) (the function objects read the velocity of boundary
         * faces only, which every step computes) */
        sol_want_fields(a.S, t.write_time || functions_read_p(&a, &t, step + 1) || stopsig_pending() ||
                                 !rt_running(&t));
        sol_stats st;
        if ((rc = sol_step(a.S, t.delta_t, &st, err)) != UMP_OK)
            goto done;
        run_left += st.left;
        run_walled += st.walled;
        for (int k = 0; k < SOL_NSTAGES; k++) {
            stage_cpu[k] += st.stage_cpu[k];
            stage_wall[k] += st.stage_wall[k];
        }
        printf("Particles: %zu (added %zu, deleted %zu, left through outlets %zu, stopped at walls %zu)\n",
               st.np, st.added, st.deleted, st.left, st.walled);
        for (int k = 0; k < (a.bu.on ? 3 : 2); k++)
            printf("BiCGSTAB:  Solving for %s, Initial residual = %g, Final residual = %g, "
                   "No Iterations %d\n", k == 2 ? "T" : a.m->ax[k] == 0 ? "Ux" : a.m->ax[k] == 1 ? "Uy" : "Uz",
                   st.pred[k].res0, st.pred[k].res, st.pred[k].iterations);
        if (st.lap_fallbacks || st.mls_fallbacks)
            printf("Fallbacks: %d particle Laplacian rows (another row form), %d MLS fits (linear/Shepard)\n",
                   st.lap_fallbacks, st.mls_fallbacks);
        if (st.positive_rows)
            printf("Positive rows: %d particle Laplacians made positive\n", st.positive_rows);
        if (st.bounded_values)
            printf("Bounded fits: %d interpolated values limited to their samples' range\n", st.bounded_values);
        /* OpenFOAM's solver-line form (foamLog parses it): the direct solve,
         * factorized once, is one "iteration" */
        printf("%s:  Solving for %s, Initial residual = %g, Final residual = %g, No Iterations 1\n",
               st.p_solver, a.bu.on ? "p_rgh" : "p", st.p_res0, st.p_res);
        cont_cumulative += st.cont_global;
        printf("time step continuity errors : sum local = %g, global = %g, cumulative = %g\n",
               st.cont_local, st.cont_global, cont_cumulative);
        printf("time step continuity errors : max = %g\n", st.cont_max);
        double umax = 0;
        ump_idx cmax = 0;
        int every = 1;
        if ((rc = check_divergence(&a, t.name, &umax, &cmax, &every, err)) != UMP_OK)
            goto done;
        fast_partial |= !every;
        if (a.closed && umax > CLOSED_WARN_FACTOR * a.u_scale) {
            if (fast_over++ == 0)
                printf("--> umppmFoam Warning: |U| = %g in cell %ld at (%g %g) is %.3f x the largest wall or "
                       "start speed %g of this flow driven by its walls alone (above %g x; the cells at corners "
                       "where walls of different velocity meet are not counted): velocities faster than the "
                       "walls are those of a flow the mesh does not resolve (coarse or stretched cells at high "
                       "Re: README, \"Unbounded on coarse stretched cells at high Re\"); %s; the steps above "
                       "%g x and the largest are counted at the end of the run\n\n",
                       umax, (long)cmax, a.m->cx[cmax], a.m->cy[cmax], umax / a.u_scale, a.u_scale,
                       CLOSED_WARN_FACTOR, closed_remedy(&a), CLOSED_WARN_FACTOR);
            if (umax > fast_peak) {
                fast_peak = umax;
                fast_cell = cmax;
                snprintf(fast_time, sizeof fast_time, "%s", t.name);
            }
        }
        step++;
        int sig = stopsig_pending();
        if (sig && !st.fields_written && rt_running(&t))
            sig = 0; /* arrived during a step without its pressure: the next step is written */
        if (sig)
            t.write_time = 1; /* stopAt writeNow: this step is written, the run ends */
        if ((rc = run_functions(&a, &t, step, tname, 0, err)) != UMP_OK)
            goto done;
        if (t.write_time) {
            if ((rc = write_time(&a, &t, err)) != UMP_OK)
                goto done;
        }
        printf("ExecutionTime = %.4g s  ClockTime = %.0f s\n\n",
               (double)(clock() - cpu0) / CLOCKS_PER_SEC, wall_seconds() - wall0);
        if (sig)
            printf("sigStopAtWriteNow : %s received: time %s written, stopping (stopAt writeNow)\n\n",
                   stopsig_name(sig), t.name);
        else if (!rt_running(&t) && t.ctl.stop_at != CASE_STOP_ENDTIME)
            printf("stopAt %s: time %s %s, stopping\n\n", case_stop_at_name(t.ctl.stop_at), t.name,
                   t.write_time ? "written" : "not written");
        errno = 0;
        if (fflush(stdout) != 0 || ferror(stdout)) {
            rc = UMP_FAIL(err, UMP_ERR_IO, "standard output: cannot write the log (%s); stopped after time %s",
                          errno ? strerror(errno) : "write error", t.name);
            goto done;
        }
        if (sig)
            break;
    }
    if (step > 0) {
        /* where the time went, per stage of the step (CPU of all threads) */
        double tc = 0, tw = 0;
        for (int k = 0; k < SOL_NSTAGES; k++) {
            tc += stage_cpu[k];
            tw += stage_wall[k];
        }
        printf("Time by stage over %ld steps, %d threads (CPU s, wall s, share of wall):\n", step,
               sol_threads());
        for (int k = 0; k < SOL_NSTAGES; k++)
            printf("    %-34s %9.3f %9.3f %5.1f %%\n", sol_stage_name(k), stage_cpu[k], stage_wall[k],
                   tw > 0 ? 100 * stage_wall[k] / tw : 0.0);
        printf("    %-34s %9.3f %9.3f\n\n", "total", tc, tw);
        /* walls stop particles (src/solver.c wall_stop): none is lost there */
        printf("Particles over %ld steps: %zu left through outlets, %zu moves stopped at walls "
               "(none lost through walls)\n\n", step, run_left, run_walled);
        if (co_over)
            printf("--> umppmFoam Warning: Courant number above 1 in %ld of %ld steps (largest %g)\n\n", co_over,
                   step, co_peak);
        if (fast_over)
            printf("--> umppmFoam Warning: |U| above %g x the largest wall or start speed %g in %ld of %ld steps "
                   "(%s); largest %g (%.3f x) in cell %ld at (%g %g), time %s\n\n", CLOSED_WARN_FACTOR, a.u_scale,
                   fast_over, step,
                   fast_partial ? "checked in the cells at boundaries every step, in all cells at the write "
                                  "steps, but the corner cells"
                                : "checked in all cells every step but the corner cells",
                   fast_peak, fast_peak / a.u_scale, (long)fast_cell, a.m->cx[fast_cell], a.m->cy[fast_cell],
                   fast_time);
    }
    rc = UMP_OK;
done:
    app_free(&a);
    return rc;
}
