/* SPDX-License-Identifier: GPL-3.0-or-later
 * mlapp.c -- the meshlessFoam time loop, driven like interFoam.
 *
 * The case is an interFoam (laminar) case directory as it is:
 *   constant/polyMesh      the container: every `wall` patch is a wall
 *                          (solid particles behind it, mlseed.h); other
 *                          patches (the atmosphere) are open: particles
 *                          that leave through them are removed; the mesh
 *                          also carries the output fields;
 *   0/alpha.<liquid>       the initial liquid region (setFields), seeded on
 *                          a lattice of the meshless spacing; 0/U gives the
 *                          particles' initial velocity; 0/p_rgh is read
 *                          (as interFoam, which needs it) for its boundary
 *                          conditions, written back with every time so
 *                          that interFoam can restart there (the particles'
 *                          pressure needs none); p is written `calculated`,
 *                          as interFoam's;
 *   constant/transportProperties  phases (liquid gas): the liquid's nu and
 *                          rho; the gas and sigma are read and not
 *                          simulated (the log says so);
 *   constant/g             gravity (in the plane of the 2-D mesh);
 *   constant/turbulenceProperties  laminar only (features.c);
 *   system/controlDict     deltaT, adjustTimeStep (the meshless maxCo on
 *                          the particle spacing), writes, purgeWrite;
 *   system/fvSolution      the meshless sub-dictionary (case.h).
 *   constant/dynamicMeshDict  a container in rigid sway (solidBody
 *                          oscillatingLinearMotion: solved in its frame) or
 *                          wall patches moved by 0/pointDisplacement
 *                          (displacementLaplacian: wave makers), case.h;
 * Refused by name before the first step: moving walls given by U (a wall
 * patch whose U is not zero), inflow (a fixed non-zero U on an open patch), slip,
 * symmetry, cyclic and wedge patches, gravity out of the plane, 3-D meshes,
 * a restart time without the particle cloud.
 *
 * Output at write times, into a hidden directory renamed into place
 * (fieldio.h): the cloud lagrangian/<cloudName> (positions, U, p,
 * numberDensity n/n0, freeSurface 0/1) and the mesh fields in interFoam's
 * definitions: alpha.<liquid> = (particles in the cell) l0^2 / cell area,
 * at most 1; U the mean particle velocity of the cell; p the mean particle
 * pressure (gauge, 0 in cells without liquid); p_rgh = p - rho gh with
 * rho = alpha rho_liquid + (1 - alpha) rho_gas, gh = g.C - ghRef (as
 * interFoam's hydrostatic split; hRef from constant/hRef, default 0).
 */
#include "umppm/mlapp.h"
#include "umppm/app.h"
#include "umppm/case.h"
#include "umppm/features.h"
#include "umppm/field.h"
#include "umppm/fieldio.h"
#include "umppm/foam.h"
#include "umppm/fpm.h"
#include "umppm/funcobj.h"
#include "umppm/function1.h"
#include "umppm/mesh2d.h"
#include "umppm/mlseed.h"
#include "umppm/mps.h"
#include "umppm/particles.h"
#include "umppm/polymesh.h"
#include "umppm/runtime.h"
#include "umppm/stopsig.h"

#include <errno.h>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <time.h>

typedef struct mlapp {
    const char *case_dir;
    mlapp_options opt;
    /* runTimeModifiable: system/controlDict is watched while ctl_watch */
    int ctl_watch;
    int ctl_missing;         /* the last stat failed (warned once) */
    case_stamp ctl_stamp;    /* the version read last */
    char ctl_path[4200];     /* <case>/system/controlDict */
    case_control ctl;
    case_phases ph;
    case_buoyancy bu;
    case_meshless ml;
    pmesh *pm;
    mesh2d *m;
    fld_field *alpha, *U, *prgh, *p; /* written fields (structure of the case's) */
    unsigned char *wall_patch;       /* [npatches] */
    part_set *s;
    unsigned char *kinds;            /* [nsolid] */
    mps *solver;                     /* method MPS */
    mps_params prm;
    fpm *fpm;                        /* method FPM */
    fpm_params fprm;
    ump_idx *wall_face;              /* FPM: the wall face of each wall point [nwall] */
    double *wnx, *wny;               /* FPM: their outward normals at seeding [nwall] */
    double g2[2];                    /* gravity in the plane */
    case_motion mo;                  /* a moving container (case.h) */
    double amp2[2];                  /* its amplitude in the plane */
    double d0[2];                    /* its displacement at the start time */
    double vframe[2];                /* its velocity at the time being written */
    f1 **pmove;                      /* [npatches] displacement of a moving wall patch, NULL: fixed */
    int nmoving;                     /* patches that move */
    int *solid_patch;                /* [nsolid] the patch carrying each solid particle */
    double *sx0, *sy0;               /* [nsolid] their positions at displacement 0 */
    ump_idx *mface;                  /* [nmface] the boundary faces of the moving patches */
    size_t nmface;
    double reach;                    /* depth of the solid particles behind a wall [m] */
    unsigned char *hidden;           /* [nsolid] a static solid covered by a moving wall */
    char *pd_text;                   /* the start time's pointDisplacement, written with every time */
    size_t pd_len;
    size_t nhidden;
    double *pdisp, *pvel;            /* [2 npatches] displacement, velocity at the last time */
    double *prev_x, *prev_y;         /* fluid positions before the step [cap] */
    ump_idx *prev_cell;
    unsigned char *keep;
    size_t pcap;
    double *cnt, *su, *sv, *sp;      /* per-cell sums [ncells] */
    double u_bound;
    char **written;
    int nwritten;
} mlapp;

static double wall_seconds(void)
{
    struct timeval tv;
    gettimeofday(&tv, NULL);
    return (double)tv.tv_sec + 1e-6 * (double)tv.tv_usec;
}

static void mlapp_free(mlapp *a)
{
    fld_free(&a->alpha);
    fld_free(&a->U);
    fld_free(&a->prgh);
    fld_free(&a->p);
    free(a->wall_patch);
    mps_free(&a->solver);
    fpm_free(&a->fpm);
    free(a->wall_face);
    if (a->pmove)
        for (int p = 0; p < a->pm->npatches; p++)
            f1_free(&a->pmove[p]);
    free(a->pmove);
    free(a->solid_patch);
    free(a->mface);
    free(a->pd_text);
    free(a->hidden);
    free(a->sx0);
    free(a->sy0);
    free(a->pdisp);
    free(a->pvel);
    free(a->wnx);
    free(a->wny);
    part_free(&a->s);
    free(a->kinds);
    free(a->prev_x);
    free(a->prev_y);
    free(a->prev_cell);
    free(a->keep);
    free(a->cnt);
    free(a->su);
    free(a->sv);
    free(a->sp);
    for (int i = 0; i < a->nwritten; i++)
        free(a->written[i]);
    free(a->written);
    mesh_free(&a->m);
    pmesh_free(&a->pm);
}

/* The particle method's per-particle results, whichever it is. */
static size_t ml_nsolid(const mlapp *a) { return a->fpm ? fpm_nsolid(a->fpm) : mps_nsolid(a->solver); }
static const double *ml_pressure(const mlapp *a) { return a->fpm ? fpm_pressure(a->fpm) : mps_pressure(a->solver); }
static const double *ml_density(const mlapp *a) { return a->fpm ? fpm_density(a->fpm) : mps_density(a->solver); }
static const unsigned char *ml_surface(const mlapp *a)
{
    return a->fpm ? fpm_surface(a->fpm) : mps_surface(a->solver);
}
static void ml_compact(mlapp *a, const unsigned char *keep, size_t n_before)
{
    if (a->fpm)
        fpm_compact(a->fpm, keep, n_before);
    else
        mps_compact(a->solver, keep, n_before);
}

/* ---- set-up ---------------------------------------------------------------- */

static ump_status read_field(mlapp *a, const char *tname, const char *name, int ncomp, fld_field **out,
                             ump_err *err)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/%s/%s", a->case_dir, tname, name);
    printf("Reading field %s\n\n", name);
    return fio_read_field(path, a->pm, ncomp, out, err);
}

/* 1 if the face values of patch p of field f are all zero. */
static int patch_zero(const fld_field *f, int p)
{
    const fld_patch *fp = &f->patch[p];
    for (size_t k = 0; k < (size_t)fp->n * (size_t)f->ncomp; k++)
        if (fp->value[k] != 0)
            return 0;
    return 1;
}

/* The boundary: wall patches, open patches, and what is refused. */
static ump_status check_boundary(mlapp *a, ump_err *err)
{
    const pmesh *pm = a->pm;
    a->wall_patch = ump_alloc_array((size_t)pm->npatches + 1, 1);
    UMP_CHECK(a->wall_patch, err, UMP_ERR_NOMEM, "out of memory");
    int nwall = 0;
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pp = &pm->patch[p];
        const fld_patch *up = &a->U->patch[p];
        switch (pp->kind) {
        case PMESH_EMPTY:
            continue;
        case PMESH_WALL:
            /* movingWallVelocity: no-slip relative to the wall, which is
             * what a wall of the (moving or fixed) container is */
            if (!((up->type == FLD_BC_NOSLIP) || (up->type == FLD_BC_MOVINGWALLVELOCITY && patch_zero(a->U, p)) ||
                  (up->type == FLD_BC_FIXEDVALUE && patch_zero(a->U, p))))
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "%s/0/U: wall patch '%s' has U %s%s: meshlessFoam's walls are no-slip "
                                "(noSlip, movingWallVelocity or fixedValue (0 0 0)); moving walls and slip walls are not "
                                "implemented in this version; use interFoam", a->case_dir, pp->name,
                                fld_bc_name(up->type), up->type == FLD_BC_FIXEDVALUE ? " (not zero)" : "");
            a->wall_patch[p] = 1;
            nwall++;
            continue;
        case PMESH_PATCH:
            if (!fld_bc_is_fixed(up->type) || up->type == FLD_BC_TOTALPRESSURE)
                continue;
            /* a time-dependent U (flowRateInletVelocity, uniformFixedValue)
             * is inflow even where its value at the start is zero */
            if (!patch_zero(a->U, p) || up->type == FLD_BC_FLOWRATEINLETVELOCITY ||
                up->type == FLD_BC_UNIFORMFIXEDVALUE)
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "%s/0/U: patch '%s' has a fixed non-zero or time-dependent U (%s): inflow "
                                "boundaries are not implemented by meshlessFoam (open patches only let liquid "
                                "leave); use interFoam", a->case_dir, pp->name, fld_bc_name(up->type));
            /* a fixed zero U closes the patch in interFoam; here every open
             * patch lets the particles leave (they had left through such
             * patches until 2026-12-06) */
            return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                            "%s/0/U: patch '%s' is of type patch (open: meshlessFoam lets the liquid leave "
                            "through it) but its U is %s (0 0 0), a closed boundary: make it a wall patch "
                            "(type wall in constant/polyMesh/boundary)", a->case_dir, pp->name,
                            fld_bc_name(up->type));
        default:
            return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                            "%s/constant/polyMesh/boundary: patch '%s' of type %s: meshlessFoam implements wall "
                            "patches (solid particles) and open patches (type patch) only; symmetry, cyclic "
                            "and wedge patches are not implemented; use interFoam", a->case_dir, pp->name,
                            pp->type);
        }
    }
    UMP_CHECK(nwall > 0, err, UMP_ERR_INPUT,
              "%s/constant/polyMesh/boundary: no patch of type wall: meshlessFoam needs a container (its wall "
              "patches)", a->case_dir);
    return UMP_OK;
}

/* Wall patches moved by 0/pointDisplacement (case_motion deform): a wall
 * patch with uniformFixedValue moves rigidly by its uniformValue (a
 * Function1 of time: a wave maker's table); fixedValue (0 0 0),
 * zeroGradient, slip or fixedNormalSlip leave it in place (its points may
 * slide in OpenFOAM's mesh motion; the wall does not move). Anything else
 * is refused by name. Open patches are not read (no particles there). */
static ump_status read_wall_motion(mlapp *a, const char *tname, ump_err *err)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/%s/pointDisplacement", a->case_dir, tname);
    UMP_CHECK(foam_file_exists(path), err, UMP_ERR_INPUT,
              "%s: missing: constant/dynamicMeshDict has motionSolver displacementLaplacian, whose wall motion "
              "meshlessFoam reads from the point displacement", path);
    /* read once, parsed, and carried to every written time as it is (a
     * Function1 of time): a restart reads it there, as interFoam's */
    UMP_CALL(foam_read_text(path, &a->pd_text, &a->pd_len, err));
    foam_file *f = NULL;
    UMP_CALL(foam_file_parse(path, a->pd_text, a->pd_len, &f, err));
    ump_status rc = UMP_OK;
    const pmesh *pm = a->pm;
    a->pmove = ump_alloc_array((size_t)pm->npatches + 1, sizeof *a->pmove);
    a->pdisp = ump_alloc_array(2 * (size_t)pm->npatches + 2, sizeof *a->pdisp);
    a->pvel = ump_alloc_array(2 * (size_t)pm->npatches + 2, sizeof *a->pvel);
    const foam_entry *bf = foam_dict_find(f->dict, "boundaryField", 0);
    if (!a->pmove || !a->pdisp || !a->pvel) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "out of memory");
        goto done;
    }
    for (int p = 0; p < pm->npatches; p++) {
        a->pmove[p] = NULL;
        a->pdisp[2 * p] = a->pdisp[2 * p + 1] = a->pvel[2 * p] = a->pvel[2 * p + 1] = 0;
    }
    if (!bf || !bf->dict) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: no boundaryField dictionary", path);
        goto done;
    }
    for (int p = 0; p < pm->npatches && rc == UMP_OK; p++) {
        if (!a->wall_patch[p])
            continue;
        const char *name = pm->patch[p].name;
        const foam_entry *e = foam_dict_find(bf->dict, name, 0);
        if (!e || !e->dict) {
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: boundaryField has no dictionary for the wall patch '%s'", path,
                          name);
            break;
        }
        const char *type = NULL;
        if ((rc = foam_get_word(e->dict, "type", &type, err)) != UMP_OK)
            break;
        if (strcmp(type, "uniformFixedValue") == 0) {
            char what[5000];
            snprintf(what, sizeof what, "%s: patch '%s': uniformValue", path, name);
            if ((rc = f1_read(e->dict, "uniformValue", 3, F1_PATCH, what, &a->pmove[p], err)) != UMP_OK)
                break;
            a->nmoving++;
        } else if (strcmp(type, "fixedValue") == 0) {
            /* value uniform (0 0 0): the word, then three zero numbers */
            const foam_entry *ve = foam_dict_find(e->dict, "value", 0);
            int zero = ve && !ve->dict && ve->ntok >= 1 && ve->tok[0].type == FOAM_TOK_WORD &&
                       strcmp(ve->tok[0].v.str, "uniform") == 0, nnum = 0;
            for (size_t k = 1; zero && ve && k < ve->ntok; k++) {
                const foam_token *tk = &ve->tok[k];
                if (tk->type == FOAM_TOK_LABEL) {
                    zero = tk->v.label == 0;
                    nnum++;
                } else if (tk->type == FOAM_TOK_SCALAR) {
                    zero = tk->v.scalar == 0;
                    nnum++;
                } else {
                    zero = tk->type == FOAM_TOK_PUNCT;
                }
            }
            zero = zero && nnum == 3;
            if (!zero) {
                rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: patch '%s': fixedValue point displacement other "
                              "than uniform (0 0 0): a wall moves in meshlessFoam by uniformFixedValue (a "
                              "Function1 of time) only", e->file, e->line, name);
                break;
            }
        } else if (strcmp(type, "zeroGradient") != 0 && strcmp(type, "slip") != 0 &&
                   strcmp(type, "fixedNormalSlip") != 0) {
            rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: patch '%s': point displacement %s is not implemented "
                          "by meshlessFoam (wall patches: uniformFixedValue to move rigidly; fixedValue (0 0 0), "
                          "zeroGradient, slip or fixedNormalSlip to stay); use interFoam", e->file, e->line,
                          name, type);
            break;
        }
    }
done:
    foam_file_free(&f);
    return rc;
}

/* A scalar field of calculated patches (empty on empty ones), zero. */
static ump_status calculated_field(const mlapp *a, const char *name, fld_field **out, ump_err *err)
{
    ump_idx *sizes = ump_alloc_array((size_t)a->pm->npatches + 1, sizeof *sizes);
    UMP_CHECK(sizes, err, UMP_ERR_NOMEM, "out of memory");
    for (int p = 0; p < a->pm->npatches; p++)
        sizes[p] = a->pm->patch[p].n;
    ump_status rc = fld_create(name, 1, a->m->ncells, a->pm->npatches, sizes, out, err);
    free(sizes);
    UMP_CALL(rc);
    for (int p = 0; p < a->pm->npatches; p++)
        if (a->pm->patch[p].kind == PMESH_EMPTY)
            (*out)->patch[p].type = FLD_BC_EMPTY;
    return UMP_OK;
}

static ump_status read_case(mlapp *a, const char *tname, ump_err *err)
{
    printf("Reading transportProperties\n\n");
    UMP_CALL(case_read_phases(a->case_dir, &a->ph, err));
    UMP_CALL(case_read_buoyancy(a->case_dir, &a->bu, err));
    UMP_CHECK(a->bu.on, err, UMP_ERR_INPUT,
              "%s/constant/g: missing: meshlessFoam needs gravity (uniformDimensionedVectorField g, as interFoam)",
              a->case_dir);
    const mesh2d *m = a->m;
    if (fabs(a->bu.g[m->normal]) > 1e-12 * (fabs(a->bu.g[0]) + fabs(a->bu.g[1]) + fabs(a->bu.g[2]) + 1e-300))
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                        "%s/constant/g: gravity (%g %g %g) has a component normal to the plane of the 2-D mesh "
                        "(%c): meshlessFoam solves in the plane only", a->case_dir, a->bu.g[0], a->bu.g[1],
                        a->bu.g[2], "xyz"[m->normal]);
    a->g2[0] = a->bu.g[m->ax[0]];
    a->g2[1] = a->bu.g[m->ax[1]];
    UMP_CALL(case_read_meshless(a->case_dir, &a->ml, err));
    UMP_CALL(case_read_motion(a->case_dir, &a->mo, err));
    if (a->mo.on) {
        const double *A = a->mo.amplitude;
        if (fabs(A[m->normal]) > 1e-12 * (fabs(A[0]) + fabs(A[1]) + fabs(A[2])))
            return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                            "%s/constant/dynamicMeshDict: oscillatingLinearMotion amplitude (%g %g %g) has a "
                            "component normal to the plane of the 2-D mesh: meshlessFoam solves in the plane only",
                            a->case_dir, A[0], A[1], A[2]);
        a->amp2[0] = A[m->ax[0]];
        a->amp2[1] = A[m->ax[1]];
    }
    char name[128];
    snprintf(name, sizeof name, "alpha.%s", a->ph.name[0]);
    UMP_CALL(read_field(a, tname, name, 1, &a->alpha, err));
    UMP_CALL(read_field(a, tname, "U", 3, &a->U, err));
    /* interFoam's MULES leaves alpha outside [0, 1] by round-off (1e-6 in
     * its written times, refused until 2026-12-06): up to 1e-3 is accepted */
    for (ump_idx c = 0; c < m->ncells; c++)
        if (!(a->alpha->internal[c] >= -1e-3 && a->alpha->internal[c] <= 1 + 1e-3))
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s/%s/%s: cell %ld has the volume fraction %.17g, outside [0, 1] "
                            "by more than 1e-3", a->case_dir, tname, name, (long)c, a->alpha->internal[c]);
    UMP_CALL(check_boundary(a, err));
    if (a->mo.deform) {
        UMP_CHECK(a->pm->npatches <= 64, err, UMP_ERR_UNSUPPORTED,
                  "%s/constant/polyMesh/boundary: %d patches: meshlessFoam moves walls in meshes of at most 64 "
                  "patches", a->case_dir, a->pm->npatches);
        UMP_CALL(read_wall_motion(a, tname, err));
    }
    /* p_rgh: read for its boundary conditions, which are written back (the
     * values are the particles'; their pressure needs no conditions); it
     * had not been read until 2026-12-06, and the `calculated` patches
     * written stopped interFoam restarting there */
    static const double pa[7] = {1, -1, -2, 0, 0, 0, 0}; /* kg m^-1 s^-2, as interFoam */
    ump_err pe;
    ump_status prc = read_field(a, tname, "p_rgh", 1, &a->prgh, &pe);
    if (prc == UMP_ERR_UNSUPPORTED) {
        /* a condition the writer does not know (prghTotalPressure, ...):
         * meshlessFoam does not need it; p_rgh is written calculated */
        printf("--> meshlessFoam Warning: %s: p_rgh is written with calculated patches, on which interFoam "
               "cannot restart\n\n", pe.msg);
        UMP_CALL(calculated_field(a, "p_rgh", &a->prgh, err));
        memcpy(a->prgh->dims, pa, sizeof pa);
    } else if (prc != UMP_OK) {
        *err = pe;
        return prc;
    }
    for (int k = 0; k < 7; k++)
        if (a->prgh->dims[k] != pa[k])
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s/%s/p_rgh: dimensions [%g %g %g %g %g %g %g]; p_rgh must have "
                            "[1 -1 -2 0 0 0 0] (Pa, as interFoam)", a->case_dir, tname, a->prgh->dims[0],
                            a->prgh->dims[1], a->prgh->dims[2], a->prgh->dims[3], a->prgh->dims[4],
                            a->prgh->dims[5], a->prgh->dims[6]);
    /* p: calculated, as interFoam's (p_rgh + rho gh) */
    UMP_CALL(calculated_field(a, "p", &a->p, err));
    memcpy(a->p->dims, pa, sizeof pa);
    return UMP_OK;
}

/* runTimeModifiable, before each step, as umppmFoam's (app.c): a new
 * version of system/controlDict is re-read with the start-up checks and
 * applied to the time (rt_reread) and the write settings; a version that
 * fails them is a warning and the run goes on with the settings it has.
 * (Until 2026-12-06 meshlessFoam did not watch controlDict: stopAt
 * writeNow or a new endTime went unheeded, without a word.) The meshless
 * maxCo (the particle Courant number) stays the step's bound. */
static void reread_control(mlapp *a, rt_time *t, double t0, const char *tname)
{
    if (!app_control_modified(a->ctl_path, a->ctl_path, &a->ctl_stamp, &a->ctl_missing))
        return;
    case_control c;
    ump_err e;
    memset(&e, 0, sizeof e);
    if (case_read_control(a->case_dir, &c, &e) != UMP_OK || case_check_start(a->case_dir, &c, tname, t0, &e) != UMP_OK) {
        printf("--> meshlessFoam Warning: %s; the re-read controlDict is not used: the run continues with the "
               "settings it has\n\n", e.msg);
        return;
    }
    a->ctl_watch = app_control_apply(t, &a->ctl, &c);
    t->ctl.max_co = a->ml.max_co; /* the particle Courant number stays the bound */
    printf("\n");
}

/* Seeding fills the cells with alpha >= 1/2 (mlseed.h): where alpha is
 * fractional over a large region (alpha 0.5 everywhere had filled the
 * whole tank until 2026-12-06) the liquid seeded is not alpha's, so more
 * than 10 % between the two volumes is refused by name. */
static ump_status check_alpha_volume(const mlapp *a, const char *tname, ump_err *err)
{
    const mesh2d *m = a->m;
    double v_alpha = 0, v_cells = 0;
    for (ump_idx c = 0; c < m->ncells; c++) {
        v_alpha += a->alpha->internal[c] * m->area[c];
        v_cells += a->alpha->internal[c] >= 0.5 ? m->area[c] : 0;
    }
    if (fabs(v_cells - v_alpha) > 0.1 * v_alpha)
        return UMP_FAIL(err, UMP_ERR_INPUT,
                        "%s/%s/alpha.%s: the cells with alpha >= 0.5, which meshlessFoam fills with particles, "
                        "hold %g m^2 of the plane, but alpha holds %g m^2 (sum of alpha times cell area): alpha "
                        "is fractional over too large a region to seed; give the liquid as alpha 1 and the gas "
                        "as alpha 0 (setFields)", a->case_dir, tname, a->ph.name[0], v_cells, v_alpha);
    return UMP_OK;
}

/* The particles: seeded from alpha (start time without a cloud) or read
 * back from the start time's cloud (a restart). */
static ump_status make_particles(mlapp *a, const char *tname, ump_err *err)
{
    const mesh2d *m = a->m;
    double l0 = a->ml.spacing > 0 ? a->ml.spacing : mlseed_default_spacing(m);
    UMP_CHECK(l0 > 0, err, UMP_ERR_INPUT, "meshless: no particle spacing");
    mps_params *P = &a->prm;
    memset(P, 0, sizeof *P);
    P->l0 = l0;
    P->re_n = a->ml.re_n;
    P->re_lap = a->ml.re_lap;
    P->beta = a->ml.beta;
    P->lambda = a->ml.lambda;
    P->rho = a->ph.rho[0];
    P->nu = a->ph.nu[0];
    P->g[0] = a->g2[0];
    P->g[1] = a->g2[1];
    P->source = a->ml.source_mixed ? MPS_SOURCE_MIXED : MPS_SOURCE_DENSITY;
    P->gamma = a->ml.gamma;
    P->collision = a->ml.collision;
    P->restitution = a->ml.restitution;
    P->p_tol = a->ml.p_tol;
    P->u_tol = a->ml.u_tol;
    P->maxit = (int)(a->ml.maxit > 1000000000L ? 1000000000L : a->ml.maxit);
    int is_fpm = strcmp(a->ml.method, "FPM") == 0;
    /* MPS: wall particles within r_e(n) of the wall; dummies so that every
     * wall particle has a full neighbourhood and every fluid particle a
     * full Laplacian stencil (docs/METHOD.md section 9). FPM: points on the
     * wall faces (the boundary particles), then ghosts behind the walls as
     * deep as the free-surface test reaches (docs/METHOD.md section 11). */
    double wall_depth = P->re_n * l0, thick = fmax(2 * P->re_n, P->re_lap + 0.5) * l0;
    /* as umppmFoam's restart rule (a restart time without its cloud had
     * been seeded from alpha without a word until 2026-12-06) */
    int restart;
    char from[96];
    snprintf(from, sizeof from, "alpha.%s", a->ph.name[0]);
    UMP_CALL(app_restart_policy(a->case_dir, tname, a->ml.cloud_name, a->opt.reseed, from, &restart, err));
    char dir[4400];
    snprintf(dir, sizeof dir, "%s/%s", a->case_dir, tname);
    const fld_field *dig[2] = {a->alpha, a->U};
    if (!restart)
        UMP_CALL(check_alpha_volume(a, tname, err));
    else /* the fields read are those written with the cloud */
        UMP_CALL(app_check_digest(dir, tname, a->ml.cloud_name, a->ctl.write_binary, a->ctl.write_precision, dig,
                                  2, err));
    if (is_fpm)
        wall_depth = thick = (a->ml.re_s + 1) * l0;
    UMP_CALL(part_create(1024, &a->s, err));
    size_t nwp = 0;
    if (is_fpm)
        UMP_CALL(mlseed_wall_points(m, a->wall_patch, l0, a->s, &a->wnx, &a->wny, &a->wall_face, &nwp, err));
    double *uc = ump_alloc_array((size_t)m->ncells + 1, sizeof *uc), *vc = ump_alloc_array((size_t)m->ncells + 1,
                                                                                         sizeof *vc);
    if (!uc || !vc) {
        free(uc);
        free(vc);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "out of memory");
    }
    for (ump_idx c = 0; c < m->ncells; c++) {
        uc[c] = a->U->internal[3 * (size_t)c + (size_t)m->ax[0]];
        vc[c] = a->U->internal[3 * (size_t)c + (size_t)m->ax[1]];
    }
    mlseed_stats ss;
    ump_idx *sface = NULL;
    ump_status rc = mlseed_build(m, a->alpha->internal, uc, vc, a->wall_patch, l0, wall_depth, thick, a->s,
                                 &a->kinds, a->nmoving ? &sface : NULL, &ss, err);
    free(uc);
    free(vc);
    UMP_CALL(rc);
    size_t ns = nwp + ss.nwall + ss.ndummy;
    if (a->nmoving) {
        /* the patch of every solid particle and its place at displacement 0 */
        a->solid_patch = ump_alloc_array(ns + 1, sizeof *a->solid_patch);
        a->sx0 = ump_alloc_array(ns + 1, sizeof *a->sx0);
        a->sy0 = ump_alloc_array(ns + 1, sizeof *a->sy0);
        if (!a->solid_patch || !a->sx0 || !a->sy0) {
            free(sface);
            return UMP_FAIL(err, UMP_ERR_NOMEM, "out of memory");
        }
        a->hidden = ump_alloc_array(ns + 1, sizeof *a->hidden);
        a->mface = ump_alloc_array((size_t)(m->nfaces - m->ninternal) + 1, sizeof *a->mface);
        if (!a->hidden || !a->mface) {
            free(sface);
            return UMP_FAIL(err, UMP_ERR_NOMEM, "out of memory");
        }
        a->nmface = 0;
        for (ump_idx f = m->ninternal; f < m->nfaces; f++)
            if (a->pmove[m->face_patch[f]])
                a->mface[a->nmface++] = f;
        a->reach = thick;
        for (size_t i = 0; i < ns; i++) {
            ump_idx f = i < nwp ? a->wall_face[i] : sface[i - nwp];
            int p = f >= 0 ? m->face_patch[f] : -1;
            double x = a->s->x[i], y = a->s->y[i];
            /* a corner's solids, as near to a static wall face as to a
             * moving one, stay with the static wall: the floor goes on
             * under a piston that slides along it (moving with the piston
             * they would pile onto the floor's own) */
            if (p >= 0 && a->pmove[p] && i >= nwp) {
                double own = mlseed_seg_dist(x, y, m->vx[m->fv0[f]], m->vy[m->fv0[f]], m->vx[m->fv1[f]],
                                             m->vy[m->fv1[f]]);
                for (ump_idx g = m->ninternal; g < m->nfaces; g++) {
                    int q = m->face_patch[g];
                    if (!a->wall_patch[q] || a->pmove[q])
                        continue;
                    if (mlseed_seg_dist(x, y, m->vx[m->fv0[g]], m->vy[m->fv0[g]], m->vx[m->fv1[g]],
                                        m->vy[m->fv1[g]]) <= own + 1e-9 * l0) {
                        p = q;
                        break;
                    }
                }
            }
            a->solid_patch[i] = p;
            a->hidden[i] = 0;
            a->sx0[i] = x;
            a->sy0[i] = y;
        }
        free(sface);
    }
    /* a restart: the fluid particles of the start time's cloud */
    if (restart) {
        size_t n;
        double *pos = NULL, *vel = NULL;
        int64_t *id = NULL;
        ump_idx *cell = NULL;
        UMP_CALL(fio_read_cloud(dir, a->ml.cloud_name, &n, &pos, &vel, &id, &cell, err));
        a->s->n = ns;
        int64_t next = 0;
        for (size_t i = 0; i < n && rc == UMP_OK; i++) {
            /* (a swaying container's cloud is written where it is: back
             * into the container's frame) */
            double x = pos[3 * i + (size_t)m->ax[0]] - a->d0[0], y = pos[3 * i + (size_t)m->ax[1]] - a->d0[1];
            ump_idx c = -1, f = -1;
            part_where w = part_locate(m, cell[i], &x, &y, &c, &f);
            if (w != PART_INSIDE) {
                rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s/lagrangian/%s/positions: particle %zu at (%g %g) is not "
                              "inside the mesh", dir, a->ml.cloud_name, i, x, y);
                break;
            }
            size_t k;
            rc = part_add(a->s, x, y, vel[3 * i + (size_t)m->ax[0]], vel[3 * i + (size_t)m->ax[1]], 0, c, &k, err);
            if (rc == UMP_OK && id[i] >= 0) {
                a->s->id[k] = id[i];
                next = id[i] + 1 > next ? id[i] + 1 : next;
            }
        }
        a->s->next_id = next > a->s->next_id ? next : a->s->next_id;
        free(pos);
        free(vel);
        free(id);
        free(cell);
        UMP_CALL(rc);
    } else {
        /* ids count fluid particles from 0 */
        int64_t id = 0;
        for (size_t i = ns; i < a->s->n; i++)
            a->s->id[i] = id++;
        a->s->next_id = id;
    }
    printf("Particles: spacing l0 = %g m (%s), lattice origin (%g %g)\n", l0,
           a->ml.spacing > 0 ? "meshless spacing" : "half the median cell size", ss.x0, ss.y0);
    if (restart)
        printf("    fluid:  %zu from the cloud %s/lagrangian/%s (restart)\n", a->s->n - ns, tname,
               a->ml.cloud_name);
    else
        printf("    fluid:  %zu (lattice points in cells with alpha.%s >= 0.5)\n", ss.nfluid, a->ph.name[0]);
    if (is_fpm) {
        fpm_params *F = &a->fprm;
        memset(F, 0, sizeof *F);
        F->l0 = l0;
        F->h = a->ml.support * l0;
        F->weight = a->ml.weight == 4 ? MLS_WFUN_EXP : MLS_WFUN_SPLINE;
        F->rho = P->rho;
        F->nu = P->nu;
        F->g[0] = P->g[0];
        F->g[1] = P->g[1];
        F->re_s = a->ml.re_s;
        F->beta = a->ml.beta_s;
        F->shift = a->ml.shift_s;
        F->gamma = a->ml.gamma_fpm;
        F->stab = a->ml.stab_fpm;
        F->surf_damp = a->ml.surf_damp_fpm;
        F->p_tol = P->p_tol;
        F->maxit = P->maxit;
        UMP_CALL(fpm_create(F, a->s, nwp, ns, a->wnx, a->wny, &a->fpm, err));
        printf("    walls:  %zu points on the wall faces (Neumann pressure, no-slip), %zu ghost particles behind "
               "them (to %g m, for the free-surface test only)\n", nwp, ss.nwall + ss.ndummy, thick);
        printf("FPM: support radius h0 = %g l0 = %g m, weight %s; free surface where n < %g n0 (n0 = %.6g, "
               "radius %g l0) or the neighbours' centroid is off by > %g l0; time step Eqs. 26-27: dt <= %g h0/|U|max, dt <= %g sqrt(h0/|g|)%s\n",
               a->ml.support, F->h, F->weight == MLS_WFUN_SPLINE ? "spline (Eq. 5)" : "exponential (Eq. 4)",
               F->beta, fpm_n0(a->fpm), F->re_s, F->shift, a->ml.fpm_co, a->ml.fpm_cg,
               F->nu > 0 ? ", dt <= 0.1 l0^2/nu (explicit viscosity)" : "");
        if (F->stab > 0)
            printf("FPM: pressure Laplacian: MLS (Eqs. 16-18) + %g x the positive Laplacian of its quadratic fit's "
                   "residual (laplacianStabilization)\n", F->stab);
        else
            printf("FPM: pressure Laplacian: MLS (Eqs. 16-18) alone (laplacianStabilization 0, as the paper)\n");
        if (F->surf_damp > 0)
            printf("FPM: free-surface particles' velocity damped towards their fluid neighbours' with nu_s = %g m^2/s "
                   "(surfaceDampingFPM %g x l0 sqrt(|g| l0))\n",
                   F->surf_damp * l0 * sqrt(hypot(F->g[0], F->g[1]) * l0), F->surf_damp);
        return UMP_OK;
    }
    UMP_CALL(mps_create(P, a->s, ns, a->kinds, &a->solver, err));
    double n0n, n0l, lam;
    mps_constants(a->solver, &n0n, &n0l, &lam);
    printf("    walls:  %zu wall particles (within %g m of the wall patches), %zu dummy particles (to %g m)\n",
           ss.nwall, wall_depth, ss.ndummy, thick);
    printf("MPS: r_e = %g l0 (number density, gradient), %g l0 (Laplacian); n0 = %.6g, %.6g; lambda = %.6g m^2 "
           "(%s); beta %g; source %s", P->re_n, P->re_lap, n0n, n0l, lam, a->ml.lambda > 0 ? "given" : "Eq. 7",
           P->beta, P->source == MPS_SOURCE_DENSITY ? "density (Eq. 18)" : "mixed");
    if (P->source == MPS_SOURCE_MIXED)
        printf(" (gamma %g)", P->gamma);
    if (P->collision > 0)
        printf("; collisions below %g l0 (restitution %g)\n", P->collision, P->restitution);
    else
        printf("; no collision model\n");
    return UMP_OK;
}

/* ---- output ----------------------------------------------------------------- */

/* Mesh fields from the particles (see the top of the file). */
static ump_status fill_fields(mlapp *a, ump_err *err)
{
    const mesh2d *m = a->m;
    const part_set *s = a->s;
    size_t ns = ml_nsolid(a), nc = (size_t)m->ncells;
    if (!a->cnt) {
        a->cnt = ump_alloc_array(nc + 1, sizeof *a->cnt);
        a->su = ump_alloc_array(nc + 1, sizeof *a->su);
        a->sv = ump_alloc_array(nc + 1, sizeof *a->sv);
        a->sp = ump_alloc_array(3 * nc + 1, sizeof *a->sp);
        UMP_CHECK(a->cnt && a->su && a->sv && a->sp, err, UMP_ERR_NOMEM, "out of memory");
    }
    memset(a->cnt, 0, nc * sizeof *a->cnt);
    memset(a->su, 0, nc * sizeof *a->su);
    memset(a->sv, 0, nc * sizeof *a->sv);
    memset(a->sp, 0, nc * sizeof *a->sp);
    const double *pr = ml_pressure(a);
    for (size_t i = ns; i < s->n; i++) {
        ump_idx c = s->cell[i];
        if (c < 0)
            continue;
        a->cnt[c] += 1;
        a->su[c] += s->u[i];
        a->sv[c] += s->v[i];
        a->sp[c] += pr[i];
    }
    double l02 = a->prm.l0 * a->prm.l0, rl = a->ph.rho[0], rg = a->ph.rho[1];
    double gmag = sqrt(a->bu.g[0] * a->bu.g[0] + a->bu.g[1] * a->bu.g[1] + a->bu.g[2] * a->bu.g[2]);
    double ghref = -gmag * (a->bu.has_h_ref ? a->bu.h_ref : 0.0);
    /* alpha: the particles' area l0^2 per cell area. A cell holding more
     * than fit (the particles bunch: 5 in a cell of 4) passes the excess
     * to its neighbours N1 that have room, in proportion to it, so the
     * liquid area is kept instead of being cut at 1 (measured: the cut
     * lost 5-9 % of the liquid in the dam breaks) */
    double *al = a->sp + nc, *room = al + nc; /* scratch after sp (3 nc) */
    for (size_t c = 0; c < nc; c++) {
        al[c] = a->cnt[c] * l02 / m->area[c];
        room[c] = 0;
    }
    for (size_t c = 0; c < nc; c++) {
        if (al[c] <= 1)
            continue;
        double excess = (al[c] - 1) * m->area[c], space = 0;
        for (ump_idx q = m->n1_off[c]; q < m->n1_off[c + 1]; q++) {
            ump_idx d = m->n1[q];
            space += fmax(0.0, 1 - al[d]) * m->area[d];
        }
        if (space <= 0)
            continue;
        double f = fmin(1.0, excess / space);
        for (ump_idx q = m->n1_off[c]; q < m->n1_off[c + 1]; q++) {
            ump_idx d = m->n1[q];
            room[d] += f * fmax(0.0, 1 - al[d]); /* the alpha d receives */
        }
    }
    for (size_t c = 0; c < nc; c++) {
        double k = a->cnt[c], al_c = fmin(1.0, fmin(1.0, al[c]) + room[c]);
        double *U = a->U->internal + 3 * c;
        U[0] = U[1] = U[2] = 0;
        double p = 0;
        if (k > 0) {
            U[m->ax[0]] = a->su[c] / k + a->vframe[0];
            U[m->ax[1]] = a->sv[c] / k + a->vframe[1];
            p = a->sp[c] / k;
        }
        double C[3];
        mesh_to3d(m, m->cx[c], m->cy[c], C);
        double gh = a->bu.g[0] * C[0] + a->bu.g[1] * C[1] + a->bu.g[2] * C[2] - ghref;
        a->alpha->internal[c] = al_c;
        a->p->internal[c] = p;
        a->prgh->internal[c] = p - (al_c * rl + (1 - al_c) * rg) * gh;
    }
    /* boundary values: prescribed ones stay, the others take the cell's */
    fld_field *F[4] = {a->alpha, a->U, a->prgh, a->p};
    for (int q = 0; q < 4; q++) {
        fld_field *f = F[q];
        for (int p = 0; p < a->pm->npatches; p++) {
            fld_patch *fp = &f->patch[p];
            if (fp->type == FLD_BC_EMPTY || fld_bc_is_fixed(fp->type))
                continue;
            const pmesh_patch *pp = &a->pm->patch[p];
            for (ump_idx i = 0; i < fp->n; i++) {
                ump_idx c = a->pm->owner[pp->start + i];
                for (int k = 0; k < f->ncomp; k++)
                    fp->value[(size_t)i * (size_t)f->ncomp + (size_t)k] =
                        f->internal[(size_t)c * (size_t)f->ncomp + (size_t)k];
            }
        }
    }
    return UMP_OK;
}

/* A swaying container's displacement at time t, A sin(w t), in the plane
 * (0 for a fixed one). */
static void frame_disp(const mlapp *a, double t, double d[2])
{
    double sn = a->mo.on ? sin(a->mo.omega * t) : 0;
    d[0] = a->amp2[0] * sn;
    d[1] = a->amp2[1] * sn;
}

static ump_status write_time(mlapp *a, const rt_time *t, ump_err *err)
{
    /* velocities are written in the absolute frame, as interFoam's (the
     * container's velocity A w cos(w t) added; positions stay in its frame) */
    for (int d = 0; d < 2; d++)
        a->vframe[d] = a->mo.on ? a->amp2[d] * a->mo.omega * cos(a->mo.omega * t->value) : 0;
    UMP_CALL(fill_fields(a, err));
    fio_timedir td;
    fio_format fmt = {a->ctl.write_binary, a->ctl.write_precision, a->ctl.write_compression};
    UMP_CALL(fio_timedir_begin(a->case_dir, t->name, &td, err));
    const part_set *s = a->s;
    const mesh2d *m = a->m;
    size_t ns = ml_nsolid(a), nf = s->n - ns;
    double *pos = ump_alloc_array(3 * nf + 3, sizeof *pos), *vel = ump_alloc_array(3 * nf + 3, sizeof *vel);
    double *sc = ump_alloc_array(nf + 1, sizeof *sc);
    ump_status rc = UMP_OK;
    if (!pos || !vel || !sc) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "writing the cloud: out of memory");
        goto fail;
    }
    /* a swaying container: positions and the mesh are written where they
     * are, moved by D(t) = A sin(w t) (interFoam writes <time>/polyMesh/points) */
    double sn = a->mo.on ? sin(a->mo.omega * t->value) : 0, D2[2];
    frame_disp(a, t->value, D2);
    for (size_t k = 0; k < nf; k++) {
        size_t i = ns + k;
        mesh_to3d(m, s->x[i] + D2[0], s->y[i] + D2[1], pos + 3 * k);
        vel[3 * k + (size_t)m->normal] = 0;
        vel[3 * k + (size_t)m->ax[0]] = s->u[i] + a->vframe[0];
        vel[3 * k + (size_t)m->ax[1]] = s->v[i] + a->vframe[1];
    }
    fld_field *F[4] = {a->alpha, a->U, a->prgh, a->p};
    for (int q = 0; q < 4 && rc == UMP_OK; q++)
        rc = fio_write_field(td.tmp_dir, t->name, a->pm, F[q], &fmt, err);
    /* the cloud is the run's state: its positions and velocities are
     * written to 17 digits whatever writePrecision says (at interFoam's 6,
     * a restart had drifted from the run it continues: p_rgh 11 % apart at
     * 0.05 s later on the dam break, as the particle spacing's round-off
     * enters the number density) */
    if (rc == UMP_OK)
        rc = fio_write_cloud(td.tmp_dir, t->name, a->ml.cloud_name, nf, pos, vel, s->cell + ns, s->id + ns, 17,
                             err);
    if (rc == UMP_OK)
        rc = fio_write_cloud_field(td.tmp_dir, t->name, a->ml.cloud_name, "p", 1, nf, ml_pressure(a) + ns,
                                   a->ctl.write_precision, err);
    if (rc == UMP_OK)
        rc = fio_write_cloud_field(td.tmp_dir, t->name, a->ml.cloud_name, "numberDensity", 1, nf,
                                   ml_density(a) + ns, a->ctl.write_precision, err);
    if (rc == UMP_OK) {
        const unsigned char *fs = ml_surface(a);
        for (size_t k = 0; k < nf; k++)
            sc[k] = fs[ns + k];
        rc = fio_write_cloud_field(td.tmp_dir, t->name, a->ml.cloud_name, "freeSurface", 1, nf, sc,
                                   a->ctl.write_precision, err);
    }
    if (rc == UMP_OK && a->mo.on) {
        const pmesh *pm = a->pm;
        double *pts = ump_alloc_array(3 * (size_t)pm->npoints + 3, sizeof *pts);
        if (!pts) {
            rc = UMP_FAIL(err, UMP_ERR_NOMEM, "writing the moved mesh: out of memory");
        } else {
            for (size_t k = 0; k < 3 * (size_t)pm->npoints; k++)
                pts[k] = pm->points[k] + a->mo.amplitude[k % 3] * sn;
            char pdir[4400], loc[200];
            snprintf(pdir, sizeof pdir, "%s/polyMesh", td.tmp_dir);
            snprintf(loc, sizeof loc, "%s/polyMesh", t->name);
            rc = pmesh_write_points(pts, pm->npoints, pdir, loc, a->ctl.write_precision > 0 ? a->ctl.write_precision : 6,
                                    err);
            free(pts);
        }
    }
    if (rc == UMP_OK && a->pd_text)
        rc = fio_write_text(td.tmp_dir, "pointDisplacement", a->pd_text, a->pd_len, err);
    if (rc == UMP_OK)
        rc = fio_write_uniform_time(td.tmp_dir, t->name, t->value, t->name, t->index, t->delta_t, t->delta_t0,
                                    a->ctl.write_precision, a->ctl.time_format_fixed, err);
    /* alpha and U as written: a restart from this cloud checks them
     * (interFoam writing into this time afterwards) */
    const fld_field *dig[2] = {a->alpha, a->U};
    if (rc == UMP_OK)
        rc = app_write_digest(td.tmp_dir, t->name, a->ml.cloud_name, a->ctl.write_binary, a->ctl.write_precision,
                              dig, 2, err);
    if (rc == UMP_OK)
        rc = fio_timedir_commit(&td, err);
    if (rc != UMP_OK)
        goto fail;
    free(pos);
    free(vel);
    free(sc);
    if (a->ctl.purge_write > 0) {
        char **w = ump_realloc_array(a->written, (size_t)a->nwritten + 1, sizeof *w);
        UMP_CHECK(w, err, UMP_ERR_NOMEM, "out of memory");
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
    free(sc);
    fio_timedir_abort(&td);
    return rc;
}

/* ---- the step --------------------------------------------------------------- */

static ump_status reserve_prev(mlapp *a, ump_err *err)
{
    size_t n = a->s->n;
    if (n <= a->pcap)
        return UMP_OK;
    size_t nc = n + n / 2 + 16;
    double *x = ump_realloc_array(a->prev_x, nc, sizeof *x);
    UMP_CHECK(x, err, UMP_ERR_NOMEM, "out of memory");
    a->prev_x = x;
    double *y = ump_realloc_array(a->prev_y, nc, sizeof *y);
    UMP_CHECK(y, err, UMP_ERR_NOMEM, "out of memory");
    a->prev_y = y;
    ump_idx *c = ump_realloc_array(a->prev_cell, nc, sizeof *c);
    UMP_CHECK(c, err, UMP_ERR_NOMEM, "out of memory");
    a->prev_cell = c;
    unsigned char *k = ump_realloc_array(a->keep, nc, sizeof *k);
    UMP_CHECK(k, err, UMP_ERR_NOMEM, "out of memory");
    a->keep = k;
    a->pcap = nc;
    return UMP_OK;
}

/* Locate the moved fluid particles on the mesh. One that crossed a wall
 * face goes back to where it started the step and loses the part of its
 * velocity that points into that wall (the wall particles normally keep it
 * out; this is the safety net, counted in the log); one that left through
 * an open patch is removed. */
static ump_status relocate(mlapp *a, size_t *left, size_t *walled, size_t *lost, ump_err *err)
{
    part_set *s = a->s;
    const mesh2d *m = a->m;
    size_t ns = ml_nsolid(a), n = s->n, nl = 0, nw = 0, nx = 0;
    for (size_t i = 0; i < ns; i++)
        a->keep[i] = 1;
#pragma omp parallel for schedule(static) reduction(+ : nl, nw, nx)
    for (size_t i = ns; i < n; i++) {
        a->keep[i] = 1;
        double x = s->x[i], y = s->y[i];
        ump_idx c = -1, f = -1;
        part_where w = part_locate(m, a->prev_cell[i], &x, &y, &c, &f);
        if (w == PART_INSIDE) {
            s->cell[i] = c;
            continue;
        }
        if (w == PART_LEFT && a->wall_patch[m->face_patch[f]]) {
            s->x[i] = a->prev_x[i];
            s->y[i] = a->prev_y[i];
            s->cell[i] = a->prev_cell[i];
            double un = s->u[i] * m->nx[f] + s->v[i] * m->ny[f];
            if (un > 0) {
                s->u[i] -= un * m->nx[f];
                s->v[i] -= un * m->ny[f];
            }
            nw++;
            continue;
        }
        a->keep[i] = 0;
        if (w == PART_LEFT)
            nl++;
        else
            nx++;
    }
    if (nl + nx > 0) {
        size_t nb = s->n;
        part_compact(s, a->keep);
        ml_compact(a, a->keep, nb);
    }
    *left = nl;
    *walled = nw;
    *lost = nx;
    (void)err;
    return UMP_OK;
}

/* Wall patches moved by their point displacement (read_wall_motion): at
 * time t the solid particles of a moving patch sit at their reference
 * place + d(t), with the step's mean velocity (d(t) - d(t - dt))/dt and,
 * for FPM's Eq. 25, the acceleration from the change of that velocity.
 * first: the velocity before the run is taken as that of the first step. */
static void move_walls(mlapp *a, double t, double dt, int first)
{
    const mesh2d *m = a->m;
    const int np = a->pm->npatches;
    double acc[2 * 64 + 2], *ap = np <= 64 ? acc : NULL;
    if (!ap)
        return; /* (more than 64 patches: bounded below at read time) */
    for (int p = 0; p < np; p++) {
        ap[2 * p] = ap[2 * p + 1] = 0;
        if (!a->pmove[p])
            continue;
        double d3[3], d3o[3];
        f1_value(a->pmove[p], t, d3);
        f1_value(a->pmove[p], t - dt, d3o);
        for (int k = 0; k < 2; k++) {
            double d = d3[m->ax[k]], v = (d - d3o[m->ax[k]]) / dt;
            ap[2 * p + k] = first ? 0 : (v - a->pvel[2 * p + k]) / dt;
            a->pdisp[2 * p + k] = d;
            a->pvel[2 * p + k] = v;
        }
    }
    part_set *s = a->s;
    size_t ns = ml_nsolid(a), nw = a->fpm ? fpm_nwall(a->fpm) : 0;
    double *wacc = a->fpm ? fpm_wall_accel(a->fpm) : NULL;
    for (size_t i = 0; i < ns; i++) {
        int p = a->solid_patch[i];
        if (p < 0 || !a->pmove[p])
            continue;
        s->x[i] = a->sx0[i] + a->pdisp[2 * p];
        s->y[i] = a->sy0[i] + a->pdisp[2 * p + 1];
        s->u[i] = a->pvel[2 * p];
        s->v[i] = a->pvel[2 * p + 1];
        if (i < nw) {
            wacc[2 * i] = ap[2 * p];
            wacc[2 * i + 1] = ap[2 * p + 1];
        }
    }
    /* a static solid particle that a moving wall has passed over (behind
     * a moving face, within the solids' depth, its projection on the
     * face) is hidden: the floor's points under a piston are not wall for
     * the liquid in front of it (the floor's particles beneath the floor
     * project beyond the piston's face and stay) */
    double bx0 = HUGE_VAL, by0 = HUGE_VAL, bx1 = -HUGE_VAL, by1 = -HUGE_VAL;
    for (size_t k = 0; k < a->nmface; k++) {
        ump_idx g = a->mface[k];
        int p = m->face_patch[g];
        for (int e = 0; e < 2; e++) {
            ump_idx v = e ? m->fv1[g] : m->fv0[g];
            bx0 = fmin(bx0, m->vx[v] + a->pdisp[2 * p]);
            bx1 = fmax(bx1, m->vx[v] + a->pdisp[2 * p]);
            by0 = fmin(by0, m->vy[v] + a->pdisp[2 * p + 1]);
            by1 = fmax(by1, m->vy[v] + a->pdisp[2 * p + 1]);
        }
    }
    const double R = a->reach, tol = 1e-9 * a->prm.l0;
    size_t nh = 0;
#pragma omp parallel for schedule(static) reduction(+ : nh)
    for (size_t i = 0; i < ns; i++) {
        int p = a->solid_patch[i];
        unsigned char h = 0;
        double x = s->x[i], y = s->y[i];
        if (p >= 0 && !a->pmove[p] && x >= bx0 - R && x <= bx1 + R && y >= by0 - R && y <= by1 + R) {
            for (size_t k = 0; k < a->nmface && !h; k++) {
                ump_idx g = a->mface[k];
                int q = m->face_patch[g];
                double ox = a->pdisp[2 * q], oy = a->pdisp[2 * q + 1];
                double ax = m->vx[m->fv0[g]] + ox, ay = m->vy[m->fv0[g]] + oy;
                double ex = m->vx[m->fv1[g]] + ox - ax, ey = m->vy[m->fv1[g]] + oy - ay, l2 = ex * ex + ey * ey;
                double tp = l2 > 0 ? ((x - ax) * ex + (y - ay) * ey) / l2 : -1;
                double behind = (x - ax) * m->nx[g] + (y - ay) * m->ny[g]; /* outward normal */
                h = tp >= -1e-9 && tp <= 1 + 1e-9 && behind > tol && behind <= R;
            }
        }
        a->hidden[i] = h;
        nh += h;
    }
    a->nhidden = nh;
    if (a->fpm)
        fpm_hide(a->fpm, a->hidden);
    else
        mps_hide(a->solver, a->hidden);
}

/* FPM: particle management (fpm_manage): merged particles go, inserted
 * ones are located on the mesh from a neighbour's cell (one whose walk
 * leaves the mesh is dropped again). */
static ump_status manage(mlapp *a, int insert, fpm_manage_stats *ms, ump_err *err)
{
    fpm_manage_params mg = {a->ml.d_wall, a->ml.d_min, a->ml.r_hole, a->ml.shift_a, a->ml.d_rep, a->ml.c_rep, insert};
    const unsigned char *keep;
    UMP_CALL(fpm_manage(a->fpm, &mg, &keep, ms, err));
    size_t n1 = a->s->n; /* with the inserted ones */
    if (ms->merged > 0) {
        part_compact(a->s, keep);
        fpm_compact(a->fpm, keep, n1);
    }
    size_t first = a->s->n - ms->inserted, drop = 0;
    UMP_CALL(reserve_prev(a, err));
    for (size_t i = first; i < a->s->n; i++) {
        double x = a->s->x[i], y = a->s->y[i];
        ump_idx c = -1, f = -1;
        part_where w = part_locate(a->m, a->s->cell[i], &x, &y, &c, &f);
        a->keep[i] = w == PART_INSIDE;
        if (w == PART_INSIDE)
            a->s->cell[i] = c;
        else
            drop++;
    }
    if (drop) {
        for (size_t i = 0; i < first; i++)
            a->keep[i] = 1;
        size_t n2 = a->s->n;
        part_compact(a->s, a->keep);
        fpm_compact(a->fpm, a->keep, n2);
        ms->inserted -= drop;
    }
    return UMP_OK;
}

/* |U| max and mean of the fluid particles. */
static void speeds(const mlapp *a, double *umax, double *umean, size_t *imax)
{
    const part_set *s = a->s;
    size_t ns = ml_nsolid(a);
    double mx = 0, sum = 0;
    size_t im = ns;
    for (size_t i = ns; i < s->n; i++) {
        double q = hypot(s->u[i], s->v[i]);
        sum += q;
        if (q > mx || !(q == q)) {
            mx = q == q ? q : HUGE_VAL;
            im = i;
        }
    }
    *umax = mx;
    *umean = s->n > ns ? sum / (double)(s->n - ns) : 0;
    if (imax)
        *imax = im;
}

/* sqrt(|g| H), H the extent of the liquid along g. */
static double wave_speed(const mlapp *a)
{
    const part_set *s = a->s;
    double g = hypot(a->g2[0], a->g2[1]);
    if (g == 0)
        return 0;
    double ex = a->g2[0] / g, ey = a->g2[1] / g, lo = HUGE_VAL, hi = -HUGE_VAL;
    for (size_t i = ml_nsolid(a); i < s->n; i++) {
        double h = s->x[i] * ex + s->y[i] * ey;
        lo = fmin(lo, h);
        hi = fmax(hi, h);
    }
    return hi > lo ? sqrt(g * (hi - lo + a->prm.l0)) : 0;
}

ump_status mlapp_run(const char *case_dir, const mlapp_options *opt, ump_err *err)
{
    mlapp a;
    memset(&a, 0, sizeof a);
    a.case_dir = case_dir;
    a.opt = *opt;
    ump_status rc;
    char tname[256], pmdir[4096];
    double t0, wall0 = wall_seconds();
    clock_t cpu0 = clock();
    printf("Create time\n\n");
    /* the version of controlDict read here is the one runTimeModifiable
     * compares with */
    snprintf(a.ctl_path, sizeof a.ctl_path, "%s/system/controlDict", case_dir);
    (void)case_file_stamp(a.ctl_path, &a.ctl_stamp);
    if ((rc = app_recover(case_dir, err)) != UMP_OK || (rc = case_read_control(case_dir, &a.ctl, err)) != UMP_OK ||
        (rc = case_start_dir(case_dir, &a.ctl, tname, sizeof tname, &t0, err)) != UMP_OK ||
        (rc = case_check_start(case_dir, &a.ctl, tname, t0, err)) != UMP_OK ||
        (rc = feat_check_meshless(case_dir, err)) != UMP_OK)
        goto done;
    snprintf(pmdir, sizeof pmdir, "%s/constant/polyMesh", case_dir);
    printf("Create mesh for time = %s\n\n", tname);
    if ((rc = pmesh_read(pmdir, &a.pm, err)) != UMP_OK || (rc = mesh_build(a.pm, &a.m, err)) != UMP_OK ||
        (rc = read_case(&a, tname, err)) != UMP_OK)
        goto done;
    printf("Phases: %s (nu %g m^2/s, rho %g kg/m^3) is simulated as particles; %s (nu %g, rho %g) is not "
           "simulated: the gas is a void at pressure 0 (the free surface), its rho only enters p_rgh\n",
           a.ph.name[0], a.ph.nu[0], a.ph.rho[0], a.ph.name[1], a.ph.nu[1], a.ph.rho[1]);
    if (a.ph.has_sigma && a.ph.sigma != 0)
        printf("Surface tension: sigma %g is read and not simulated (not implemented by meshlessFoam)\n",
               a.ph.sigma);
    else if (a.ph.sigma_model[0])
        printf("Surface tension: sigma { type %s; } is read and not simulated (not implemented by "
               "meshlessFoam)\n", a.ph.sigma_model);
    char fos[512] = "";
    if (!a.opt.no_function_objects && (rc = fob_names(case_dir, fos, sizeof fos, err)) != UMP_OK)
        goto done;
    if (fos[0] && !a.opt.no_function_objects)
        printf("--> meshlessFoam Warning: function objects are not run by meshlessFoam (ignored): %s\n", fos);
    printf("Gravity: (%g %g) in the plane (%c %c)\n\n", a.g2[0], a.g2[1], "xyz"[a.m->ax[0]], "xyz"[a.m->ax[1]]);
    if (a.nmoving)
        for (int p = 0; p < a.pm->npatches; p++)
            if (a.pmove[p])
                printf("Moving wall: patch '%s' moves rigidly by its point displacement (0/pointDisplacement "
                       "uniformFixedValue, a %s of time); the mesh stays in place (particles need no mesh "
                       "motion): the fields are written on the mesh at its start position\n",
                       a.pm->patch[p].name, f1_kind_name(a.pmove[p]->kind));
    if (a.mo.on)
        printf("Container motion (constant/dynamicMeshDict): solidBody oscillatingLinearMotion, displacement "
               "(%g %g) sin(%g t) m: solved in the container's frame, where gravity becomes g - a(t); "
               "written in the absolute frame as interFoam's: positions moved with the container, the moved "
               "mesh in <time>/polyMesh/points, velocities absolute (0/U is absolute: a liquid at rest starts "
               "at -A w relative to the container)\n\n", a.amp2[0], a.amp2[1], a.mo.omega);
    double tb = wall_seconds();
    frame_disp(&a, t0, a.d0);
    if ((rc = make_particles(&a, tname, err)) != UMP_OK)
        goto done;
    if (a.mo.on) {
        /* 0/U and a written cloud hold absolute velocities (interFoam's):
         * into the container's frame, u - A w cos(w t0). A fluid at rest
         * thus starts at -A w relative to the container that sways from
         * x = 0 at speed A w, as in interFoam's impulsive start */
        double v0[2] = {a.amp2[0] * a.mo.omega * cos(a.mo.omega * t0), a.amp2[1] * a.mo.omega * cos(a.mo.omega * t0)};
        for (size_t i = ml_nsolid(&a); i < a.s->n; i++) {
            a.s->u[i] -= v0[0];
            a.s->v[i] -= v0[1];
        }
    }
    printf("Set-up: %.3g s\n", wall_seconds() - tb);
    printf("Threads: %d (OpenMP; set OMP_NUM_THREADS to change; 1 where other runs share these cores: README, "
           "\"Runs sharing the cores\")\n\n",
#ifdef _OPENMP
           omp_get_max_threads()
#else
           1
#endif
    );
    /* divergence guard: 10 x the free-fall speed over the container's height */
    {
        double ymin = HUGE_VAL, ymax = -HUGE_VAL, xmin = HUGE_VAL, xmax = -HUGE_VAL;
        for (ump_idx k = 0; k < a.m->nverts; k++) {
            ymin = fmin(ymin, a.m->vy[k]);
            ymax = fmax(ymax, a.m->vy[k]);
            xmin = fmin(xmin, a.m->vx[k]);
            xmax = fmax(xmax, a.m->vx[k]);
        }
        double g = hypot(a.g2[0], a.g2[1]), H = fmax(ymax - ymin, xmax - xmin);
        double umax, umean;
        speeds(&a, &umax, &umean, NULL);
        /* 10 x the fastest the liquid can move: falling through the
         * container, or its initial speed; at least 1 m/s (no gravity) */
        a.u_bound = a.ml.max_velocity > 0 ? a.ml.max_velocity : fmax(10 * fmax(sqrt(2 * g * H), umax), 1.0);
        printf("Divergence guard: |U| <= %g m/s (%s)\n", a.u_bound,
               a.ml.max_velocity > 0 ? "meshless maxVelocity"
                                     : "10 x max(the free-fall speed over the container, the initial |U|), "
                                       "at least 1 m/s");
    }
    rt_time t;
    rt_init(&t, &a.ctl, t0, tname);
    t.ctl.max_co = a.ml.max_co; /* adjustTimeStep keeps the particle Courant number */
    if (a.ctl.adjust_time_step) {
        /* a restart goes on with the deltaT of its uniform/time, as
         * OpenFOAM's Time (it had started from controlDict's until
         * 2026-12-06) */
        double dt;
        int has;
        if ((rc = case_read_time_delta_t(case_dir, tname, &dt, &has, err)) != UMP_OK)
            goto done;
        if (has) {
            rt_restore_delta_t(&t, dt);
            printf("deltaT = %g from %s/uniform/time (adjustTimeStep)\n", t.delta_t, tname);
        }
    }
    if (stopsig_install() != 0)
        printf("--> meshlessFoam Warning: cannot install the SIGINT/SIGTERM handler: %s\n", strerror(errno));
    /* The step's Courant number uses the speed max(|U|max, sqrt(|g| H)),
     * H the depth of the liquid along g: the celerity of shallow-water
     * gravity waves, which the explicit free surface must resolve even at
     * rest (measured: the hydrostatic tank, l0 = 5 mm, depth 0.3 m, is
     * stable at Co 0.17 on this speed and diverges at 0.34). */
    const double l0 = a.prm.l0;
    double umax, umean, u_g = wave_speed(&a);
    speeds(&a, &umax, &umean, NULL);
    /* FPM: the Courant number handed to adjustTimeStep is maxCo dt / dt_max
     * (Eqs. 26-27), so that the step becomes dt_max */
    if (a.ctl.adjust_time_step)
        rt_set_initial_delta_t(&t, a.fpm ? a.ml.max_co * t.delta_t / fpm_max_dt(a.fpm, a.ml.fpm_co, a.ml.fpm_cg, u_g)
                                         : fmax(umax, u_g) * t.delta_t / l0);
    if (a.ctl.adjust_time_step && a.fpm)
        printf("adjustTimeStep: the time step of Eqs. 26-27 (courantFPM %g, gravityStepFPM %g; controlDict's "
               "maxCo %g is interFoam's cell Courant number and is not used)\n", a.ml.fpm_co, a.ml.fpm_cg,
               a.ctl.max_co);
    else if (a.ctl.adjust_time_step)
        printf("adjustTimeStep: maxCo %g on the particle spacing (meshless maxCo; controlDict's maxCo %g is "
               "interFoam's cell Courant number and is not used), speed max(|U|, sqrt(|g| H) = %g m/s)\n",
               a.ml.max_co, a.ctl.max_co, u_g);
    printf("\nStarting time loop\n\n");
    long step = 0;
    size_t run_left = 0, run_walled = 0, run_lost = 0, run_merged = 0, run_inserted = 0, run_shifted = 0;
    /* FPM: the liquid's particles at the start, against which merging net of
     * insertion is measured (each particle stands for l0^2 of liquid) */
    const size_t nfluid0 = a.s->n - ml_nsolid(&a);
    int volume_warned[2] = {0, 0}; /* loss, gain */
    double stage_cpu[6] = {0}, stage_wall[6] = {0};
    static const char *const mps_stage[6] = {"neighbours, number density", "viscosity (implicit, CG)",
                                             "pressure (PPE, CG)", "correction", "locate on the mesh", ""};
    static const char *const fpm_stage[6] = {"neighbours, MLS coefficients", "predictor (explicit)",
                                             "pressure (PPE, BiCGSTAB)", "correction", "locate on the mesh",
                                             "particle management"};
    const int nstage = a.fpm ? 6 : 5;
    const char *const *stage_name = a.fpm ? fpm_stage : mps_stage;
    a.ctl_watch = a.ctl.run_time_modifiable;
    while (rt_running(&t)) {
        /* runTimeModifiable: Time::run re-reads controlDict before each step */
        if (a.ctl_watch) {
            reread_control(&a, &t, t0, tname);
            if (!rt_running(&t))
                break;
        }
        /* umax, umean: of the start fields, then of the step before */
        u_g = wave_speed(&a);
        printf("Courant Number mean: %g max: %g\n", umean * t.delta_t / l0, umax * t.delta_t / l0);
        if (a.ctl.adjust_time_step) {
            rt_adjust_delta_t(&t, a.fpm ? a.ml.max_co * t.delta_t / fpm_max_dt(a.fpm, a.ml.fpm_co, a.ml.fpm_cg, u_g)
                                        : fmax(umax, u_g) * t.delta_t / l0);
            printf("deltaT = %g\n", t.delta_t);
        }
        rt_advance(&t);
        if (t.precision_raised)
            printf("--> meshlessFoam Warning: increased the timePrecision to %d to distinguish between "
                   "timeNames at time %s\n", t.precision, t.name);
        printf("Time = %s\n\n", t.name);
        if ((rc = reserve_prev(&a, err)) != UMP_OK)
            goto done;
        size_t ns = ml_nsolid(&a);
        for (size_t i = ns; i < a.s->n; i++) {
            a.prev_x[i] = a.s->x[i];
            a.prev_y[i] = a.s->y[i];
            a.prev_cell[i] = a.s->cell[i];
        }
        if (a.nmoving)
            move_walls(&a, t.value, t.delta_t, step == 0);
        if (a.mo.on) {
            /* the container's frame: gravity minus its acceleration at the
             * end of the step, a = -A w^2 sin(w t) (Eq. 28 differentiated) */
            double w = a.mo.omega, sn = sin(w * t.value), geff[2];
            for (int d = 0; d < 2; d++)
                geff[d] = a.g2[d] + a.amp2[d] * w * w * sn;
            if (a.fpm)
                fpm_set_gravity(a.fpm, geff);
            else
                mps_set_gravity(a.solver, geff);
        }
        mps_stats st;
        fpm_stats fst;
        memset(&st, 0, sizeof st);
        if (a.fpm)
            rc = fpm_step(a.fpm, t.delta_t, &fst, err);
        else
            rc = mps_step(a.solver, t.delta_t, &st, err);
        if (rc != UMP_OK)
            goto done;
        if (a.fpm) {
            memcpy(st.cpu, fst.cpu, sizeof st.cpu);
            memcpy(st.wall, fst.wall, sizeof st.wall);
        }
        double c1 = (double)clock() / CLOCKS_PER_SEC, w1 = wall_seconds();
        size_t left, walled, lost;
        if ((rc = relocate(&a, &left, &walled, &lost, err)) != UMP_OK)
            goto done;
        for (int k = 0; k < 4; k++) {
            stage_cpu[k] += st.cpu[k];
            stage_wall[k] += st.wall[k];
        }
        stage_cpu[4] += (double)clock() / CLOCKS_PER_SEC - c1;
        stage_wall[4] += wall_seconds() - w1;
        run_left += left;
        run_walled += walled;
        run_lost += lost;
        fpm_manage_stats ms = {0, 0, 0, 0};
        if (a.fpm) {
            c1 = (double)clock() / CLOCKS_PER_SEC, w1 = wall_seconds();
            if ((rc = manage(&a, (step + 1) % a.ml.manage_interval == 0, &ms, err)) != UMP_OK)
                goto done;
            stage_cpu[5] += (double)clock() / CLOCKS_PER_SEC - c1;
            stage_wall[5] += wall_seconds() - w1;
            run_merged += ms.merged;
            run_inserted += ms.inserted;
            run_shifted += ms.shifted;
        }
        if (a.fpm)
            printf("FPM: %zu fluid particles, %zu on the free surface, %zu pressure unknowns (%zu wet wall points), "
                   "%zu linear MLS fits; n/n0 min %.4g max %.4g\n", fst.nfluid, fst.nsurface, fst.nunknowns,
                   fst.nneumann, fst.nlinear, fst.n_min, fst.n_max);
        else
            printf("MPS: %zu fluid particles, %zu on the free surface, %zu pressure unknowns, %zu collisions; "
                   "n*/n0 min %.4g max %.4g\n", st.nfluid, st.nsurface, st.nunknowns, st.collisions, st.n_min,
                   st.n_max);
        /* the speeds after the step: logged, checked by the guard, and the
         * Courant number of the next step */
        size_t imax;
        speeds(&a, &umax, &umean, &imax);
        if (imax < a.s->n)
            printf("Velocity: |U| mean %g max %g m/s (particle %lld at (%g %g)%s)\n", umean, umax,
                   (long long)a.s->id[imax], a.s->x[imax], a.s->y[imax],
                   ml_surface(&a)[imax] ? ", free surface" : "");
        if (a.fpm) {
            printf("BiCGSTAB:  Solving for p, Initial residual = %g, Final residual = %g, No Iterations %d%s\n",
                   fst.pres.res0, fst.pres.res, fst.pres.iterations,
                   fst.pres.converged ? "" : " (not converged)");
            st.p_min = fst.p_min;
            st.p_max = fst.p_max;
        } else if (a.prm.nu > 0)
            for (int d = 0; d < 2; d++)
                printf("DICPCG:  Solving for %s, Initial residual = %g, Final residual = %g, No Iterations %d\n",
                       a.m->ax[d] == 0 ? "Ux" : a.m->ax[d] == 1 ? "Uy" : "Uz", st.visc[d].res0, st.visc[d].res,
                       st.visc[d].iterations);
        if (!a.fpm)
            printf("DICPCG:  Solving for p, Initial residual = %g, Final residual = %g, No Iterations %d\n",
                   st.pres.res0, st.pres.res, st.pres.iterations);
        printf("Pressure: min %g max %g Pa\n", st.p_min, st.p_max);
        printf("Particles: %zu (left through open boundaries %zu, stopped at walls %zu%s)\n",
               a.s->n - ml_nsolid(&a), left, walled, lost ? ", LOST" : "");
        if (a.nmoving)
            printf("Moving walls: %zu solid particles of static walls covered (hidden)\n", a.nhidden);
        if (a.fpm)
            printf("Particle management: %zu merged, %zu inserted, %zu moved off walls; largest shift %g l0\n",
                   ms.merged, ms.inserted, ms.shifted, ms.max_shift);
        if (lost)
            printf("--> meshlessFoam Warning: %zu particles could not be located on the mesh and were removed\n",
                   lost);
        if (a.fpm && run_merged != run_inserted && nfluid0 > 0) {
            /* no silent change of the liquid's volume: a merge that no
             * insertion makes up for removes l0^2 of liquid, an insertion
             * at a Voronoi hole that no merge balances (where the cloud
             * spreads, in a thinning jet or a splash) adds it */
            const int gain = run_inserted > run_merged;
            const size_t net = gain ? run_inserted - run_merged : run_merged - run_inserted;
            const double frac = (double)net / (double)nfluid0, limit = gain ? a.ml.max_gain : a.ml.max_loss;
            const char *did = gain ? "added" : "removed", *prep = gain ? "to" : "of";
            if (frac > limit) {
                rc = UMP_FAIL(err, UMP_ERR_INPUT,
                              "FPM particle management has %s %.1f %% %s the liquid's %zu particles by time %s "
                              "(%zu merged, %zu inserted): the liquid's volume is no longer conserved (the particle "
                              "distribution has degenerated); nothing of this step was written (meshless "
                              "%s %g)", did, 100 * frac, prep, nfluid0, t.name, run_merged, run_inserted,
                              gain ? "maxParticleGain" : "maxParticleLoss", limit);
                goto done;
            }
            if (!volume_warned[gain] && frac > 0.05) {
                printf("--> meshlessFoam Warning: FPM particle management has %s %.1f %% %s the liquid's "
                       "particles (%zu merged, %zu inserted): the liquid's volume %s by as much\n",
                       did, 100 * frac, prep, run_merged, run_inserted, gain ? "grows" : "shrinks");
                volume_warned[gain] = 1;
            }
        }
        if (!(umax <= a.u_bound)) {
            rc = UMP_FAIL(err, UMP_ERR_INPUT,
                          "the run has diverged at time %s: particle %lld at (%g %g) has |U| = %g m/s > %g "
                          "(meshless maxVelocity, or its default); nothing of this step was "
                          "written. Reduce deltaT or meshless maxCo", t.name, (long long)a.s->id[imax],
                          a.s->x[imax], a.s->y[imax], umax, a.u_bound);
            goto done;
        }
        step++;
        int sig = stopsig_pending();
        if (sig)
            t.write_time = 1;
        if (t.write_time && (rc = write_time(&a, &t, err)) != UMP_OK)
            goto done;
        printf("ExecutionTime = %.4g s  ClockTime = %.0f s\n\n", (double)(clock() - cpu0) / CLOCKS_PER_SEC,
               wall_seconds() - wall0);
        if (sig)
            printf("sigStopAtWriteNow : %s received: time %s written, stopping (stopAt writeNow)\n\n",
                   stopsig_name(sig), t.name);
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
        double tc = 0, tw = 0;
        for (int k = 0; k < nstage; k++) {
            tc += stage_cpu[k];
            tw += stage_wall[k];
        }
        printf("Time by stage over %ld steps (CPU s, wall s, share of wall):\n", step);
        for (int k = 0; k < nstage; k++)
            printf("    %-34s %9.3f %9.3f %5.1f %%\n", stage_name[k], stage_cpu[k], stage_wall[k],
                   tw > 0 ? 100 * stage_wall[k] / tw : 0.0);
        printf("    %-34s %9.3f %9.3f\n\n", "total", tc, tw);
        printf("Particles over %ld steps: %zu left through open boundaries, %zu moves stopped at walls "
               "(none lost through walls)%s\n\n", step, run_left, run_walled,
               run_lost ? "; some could not be located (see the warnings)" : "");
        if (a.fpm)
            printf("Particle management over %ld steps: %zu merged, %zu inserted, %zu moved off walls\n\n", step,
                   run_merged, run_inserted, run_shifted);
    }
    rc = UMP_OK;
done:
    mlapp_free(&a);
    return rc;
}
