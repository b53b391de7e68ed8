/* SPDX-License-Identifier: GPL-3.0-or-later
 * field.h -- cell-centred fields with OpenFOAM boundary conditions, in memory
 * (module prefix fld_). No file I/O here: fieldio.h reads and writes them.
 *
 * Values are stored with their full OpenFOAM component count (vectors have 3
 * components, whatever the mesh dimension), cell-major: internal[c*ncomp+k].
 * One fld_patch per polyMesh patch, in pmesh patch order; patch face values
 * follow the patch's polyMesh face order.
 */
#ifndef UMPPM_FIELD_H
#define UMPPM_FIELD_H

#include "umppm/function1.h"
#include "umppm/ump.h"

typedef enum fld_bc_type {
    FLD_BC_CALCULATED,
    FLD_BC_FIXEDVALUE,
    FLD_BC_NOSLIP,               /* fixed zero vector */
    FLD_BC_MOVINGWALLVELOCITY,   /* fixed value (wall velocity), flux-corrected in FV */
    FLD_BC_ZEROGRADIENT,
    FLD_BC_EMPTY,
    FLD_BC_CYCLIC,
    FLD_BC_SYMMETRYPLANE,
    FLD_BC_SYMMETRY,
    FLD_BC_FIXEDFLUXPRESSURE,    /* pressure: gradient set so the flux matches */
    FLD_BC_INLETOUTLET,          /* zeroGradient out, inletValue in */
    FLD_BC_SLIP,                 /* zero normal component, zero tangential gradient */
    FLD_BC_UNIFORMFIXEDVALUE,    /* fixed value uniformValue(t), a Function1 of time */
    FLD_BC_FLOWRATEINLETVELOCITY, /* U = -Q(t)/A n, Q = volumetricFlowRate(t) */
    FLD_BC_OUTLETINLET,          /* outletValue out, zeroGradient in */
    FLD_BC_TOTALPRESSURE,        /* p = p0 out, p0 - |U|^2/2 in (kinematic) */
    FLD_BC_PRESSUREINLETOUTLETVELOCITY, /* zeroGradient out; in: normal part of
                                    the cell value + tangentialVelocity */
    FLD_BC_NTYPES
} fld_bc_type;

/* OpenFOAM type word of t ("fixedValue", ...). */
const char *fld_bc_name(fld_bc_type t);
/* Parse a type word; returns -1 when unsupported. */
int fld_bc_parse(const char *word);
/* The keyword of type t's second value list (inletValue, gradient,
 * outletValue, p0, tangentialVelocity), or NULL: one table for the reader
 * and the writer. */
const char *fld_bc_aux_key(fld_bc_type t);

/* An extra keyword of a boundary entry that umppmFoam keeps but does not
 * interpret (e.g. "rho rhok;" of fixedFluxPressure), written back verbatim. */
typedef struct fld_extra {
    char *key;
    char *text;      /* the value tokens re-serialised on one line */
} fld_extra;

typedef struct fld_patch {
    fld_bc_type type;
    ump_idx n;           /* faces of the patch */
    double *value;       /* [n*ncomp] face values (all types but empty; cyclic and
                            symmetry values are the adjacent cell values), never
                            NULL when n > 0 and type != EMPTY */
    int value_given;     /* 1: "value" was in the file */
    double *aux;         /* [n*ncomp] inletValue (inletOutlet), gradient
                            (fixedFluxPressure), outletValue (outletInlet), p0
                            (totalPressure), tangentialVelocity
                            (pressureInletOutletVelocity, NULL when not
                            given); NULL otherwise */
    f1 *fn;              /* uniformValue (uniformFixedValue), volumetricFlowRate
                            (flowRateInletVelocity); NULL otherwise */
    fld_extra *extra;    /* other keys, in file order */
    int nextra;
} fld_patch;

typedef struct fld_field {
    char *name;          /* object name: U, p, T ... */
    int ncomp;           /* 1 (scalar) or 3 (vector) */
    double dims[7];      /* [kg m s K mol A cd] */
    ump_idx ncells;
    double *internal;    /* [ncells*ncomp] */
    int npatches;
    fld_patch *patch;    /* [npatches] */
} fld_field;

/* Allocate a field with zero values, every patch `calculated` sized from
 * patch_sizes [npatches]. */
ump_status fld_create(const char *name, int ncomp, ump_idx ncells, int npatches,
                      const ump_idx *patch_sizes, fld_field **out, ump_err *err);
/* Deep copy. */
ump_status fld_copy(const fld_field *src, fld_field **out, ump_err *err);
void fld_free(fld_field **f);

/* 1 if the type prescribes the face value (fixedValue, noSlip,
 * movingWallVelocity, uniformFixedValue, flowRateInletVelocity,
 * totalPressure); 0 otherwise. */
int fld_bc_is_fixed(fld_bc_type t);

/* Face values at time t of a boundary condition given by a function of time:
 *   uniformFixedValue      uniformValue(t) on every face;
 *   flowRateInletVelocity  -Q(t)/area n_i on face i (OpenFOAM v1912's
 *                          flowRateInletVelocity without extrapolateProfile:
 *                          a uniform speed into the patch), Q =
 *                          volumetricFlowRate(t), area the patch's total face
 *                          area (3-D: a 2-D case's faces have the mesh's
 *                          depth), nrm [3*n] the faces' outward unit normals.
 * out [n*ncomp]. Other types: nothing is written, returns 0; else 1. */
int fld_bc_eval(const fld_patch *p, int ncomp, double t, const double *nrm, double area, double *out);

#endif
