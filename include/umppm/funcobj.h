/* SPDX-License-Identifier: GPL-3.0-or-later
 * funcobj.h -- function objects of system/controlDict's `functions`
 * dictionary that umppmFoam runs (module prefix fob_). File reading and
 * writing live here; the numbers come from the solver (sol_wall_dTdn,
 * sol_face_T) through the application.
 *
 * Two types. The wall Nusselt number of Eqs. 43-45 of Ng, Sheu & Hwang
 * (2016) [NSH16] (docs/METHOD.md section 6):
 *
 *   functions
 *   {
 *       NuInner
 *       {
 *           type          nusseltNumber;
 *           patch         inner;        // the wall
 *           length        0.0628319;    // S of Eq. 45 [m]
 *           kappa         0.02816;      // conductivity k [W/m/K], for q and h
 *           T1            301.5518;     // Eq. 44: h = -k dT/dn / (T1 - T2);
 *           T2            300;          //   defaults: patch mean T, TRef
 *           gradient      mls;          // mls (default) or snGrad
 *           writeControl  timeStep;     // timeStep (default) or writeTime
 *           writeInterval 1;
 *       }
 *   }
 *
 * q = k dT/dn (n out of the fluid, into the wall: the heat flux into the
 * fluid, Eq. 43), h = q / (T1 - T2) (Eq. 44), Nu = h S / k (Eq. 45); the
 * patch averages are weighted by face area. Output as OpenFOAM's function
 * objects: postProcessing/<name>/<startTime>/nusseltNumber.dat (time
 * series: Time Nu_avg h_avg q_avg Nu_min Nu_max), and at every write time
 * postProcessing/<name>/<time>/<patch>.dat (per face: x y z dT/dn q h Nu).
 *
 * And OpenFOAM's surfaceFieldValue on a patch, so that one controlDict
 * entry gives the same time series from umppmFoam and from icoFoam:
 *
 *       pInlet
 *       {
 *           type          surfaceFieldValue;
 *           libs          ("libfieldFunctionObjects.so");   // for OpenFOAM
 *           regionType    patch;        // the only region type here
 *           name          inlet;
 *           operation     areaAverage;  // sum average areaAverage
 *                                       // areaIntegrate min max none
 *           fields        (p U);        // p U, and T p_rgh when buoyant
 *           writeFields   false;        // must be false (or absent)
 *           writeControl  timeStep;
 *           writeInterval 1;
 *       }
 *
 * -> postProcessing/<name>/<startTime>/surfaceFieldValue.dat, OpenFOAM's
 * layout: "# Region type : patch <name>", "# Faces : n", "# Area : A",
 * "# Time <TAB> areaAverage(p) ...", then one row per evaluation (vectors
 * as "(x y z)"). Face areas are 3-D (edge length x mesh thickness), as
 * OpenFOAM's.
 * Entries of other types are listed in fob_list.ignored for a warning
 * (OpenFOAM's other function objects do not run in umppmFoam).
 */
#ifndef UMPPM_FUNCOBJ_H
#define UMPPM_FUNCOBJ_H

#include <stdio.h>
#include "umppm/ump.h"

/* What every function object has: its name, when it writes, its file, and
 * its patch's faces (mesh-only: resolved once by fob_set_faces). */
typedef struct fob_common {
    char name[128];
    char patch[128];         /* the patch it works on */
    int on_write_time;       /* writeControl writeTime */
    long interval;           /* writeControl timeStep: every interval steps */
    FILE *fp;                /* the open time series */
    char path[4400];
    char suffix[64];         /* suffix of a new series file when one of the
                                name is there: "" = the start time (at
                                start-up); a function object made by a
                                controlDict re-read: that time's name */
    int continued;           /* made by a re-read, continuing the series of
                                the same unchanged function object */
    size_t nface;            /* the patch's 2-D boundary faces: */
    ump_idx *face;           /*   [nface] face indices of the 2-D mesh */
    double *area;            /*   [nface] 3-D face areas */
    double *x3;              /*   [3 nface] face centres */
} fob_common;

typedef struct fob_nusselt {
    fob_common c;
    double length, kappa;
    double T1, T2;
    int has_T1, has_T2;
    int snGrad;              /* 0: MLS gradient (default), 1: snGrad */
} fob_nusselt;

typedef enum fob_op {
    FOB_NONE, FOB_SUM, FOB_AVERAGE, FOB_AREA_AVERAGE, FOB_AREA_INTEGRATE, FOB_MIN, FOB_MAX
} fob_op;

/* The fields a surfaceFieldValue can take (T and p_rgh: buoyant runs). */
typedef enum fob_field { FOB_FIELD_U, FOB_FIELD_P, FOB_FIELD_T, FOB_FIELD_P_RGH } fob_field;

#define FOB_MAX_FIELDS 8
typedef struct fob_sfv {
    fob_common c;
    fob_op op;
    int nfields;
    fob_field field[FOB_MAX_FIELDS];
} fob_sfv;

typedef struct fob_list {
    fob_nusselt *nu;
    int n;
    fob_sfv *sf;
    int nsf;
    char ignored[512];       /* "name (type), ..." of entries not run here */
} fob_list;

/* Read the functions dictionary of <case>/system/controlDict (absent: an
 * empty list). Missing or bad entries are errors naming file and line. */
ump_status fob_read(const char *case_dir, fob_list *L, ump_err *err);
void fob_free(fob_list *L);
/* "name (type), ..." of every enabled entry of the functions dictionary
 * into buf ("" where there is none): for a solver that runs none of them. */
ump_status fob_names(const char *case_dir, char *buf, size_t size, ump_err *err);
/* Give function object c its patch's faces (copies of the n entries of
 * face, area, x3). */
ump_status fob_set_faces(fob_common *c, size_t n, const ump_idx *face, const double *area, const double *x3,
                         ump_err *err);

/* runTimeModifiable, after a re-read of the functions dictionary into nw:
 * each function object of nw that has a namesake in old of the same type
 * and the same series header (surfaceFieldValue: patch, operation, fields;
 * nusseltNumber: patch, length, kappa, T1, T2, gradient) takes over its
 * open series, which continues in the same file (continued = 1), as
 * OpenFOAM's functionObjectList::read keeps such an object. The others
 * start a new series at their first write; an existing file of the name
 * then gets the suffix _<time_name>, the time of the re-read, as
 * OpenFOAM's writeFile names a file made mid-run. A series taken over is
 * no longer old's; fob_free(old) closes the others. */
void fob_take_over(fob_list *nw, fob_list *old, const char *time_name);

/* Per-face data of a patch for one evaluation. */
typedef struct fob_faces {
    size_t n;
    const double *x3;        /* [3n] face centres */
    const double *area;      /* [n] face areas */
    const double *dTdn;      /* [n] wall-normal gradient, outward */
    const double *Tf;        /* [n] face temperatures */
} fob_faces;

typedef struct fob_result {
    double Nu_avg, h_avg, q_avg, Nu_min, Nu_max, T1, T2;
} fob_result;

/* Eqs. 43-45 over the faces (T1, T2 defaults: area-mean Tf and t_ref). */
fob_result fob_nusselt_eval(const fob_nusselt *f, const fob_faces *d, double t_ref);
/* Does this step (1-based index) write the time series? */
int fob_due(const fob_common *f, long step, int write_time);
/* Append one line to postProcessing/<name>/<start_time>/nusseltNumber.dat
 * (created with its header on the first call; an existing file of an
 * earlier run is kept and the new one gets the suffix _<start_time>, as
 * OpenFOAM's writeFile). */
ump_status fob_nusselt_append(fob_nusselt *f, const char *case_dir, const char *start_time, double t,
                              const fob_result *r, int precision, ump_err *err);
/* postProcessing/<name>/<time>/<patch>.dat with the local values. */
ump_status fob_nusselt_local(const fob_nusselt *f, const char *case_dir, const char *time_name,
                             const fob_faces *d, const fob_result *r, int precision, ump_err *err);

/* One field on the faces of a surfaceFieldValue's patch. */
typedef struct fob_patch_field {
    size_t n;
    int ncomp;               /* 1 scalar, 3 vector */
    const double *area;      /* [n] 3-D face areas */
    const double *v;         /* [n*ncomp] face values */
} fob_patch_field;

/* Append one row (time, then the operation on each field in order; vals
 * [k] holds field k) to postProcessing/<name>/<start_time>/
 * surfaceFieldValue.dat, created with OpenFOAM's header on the first call. */
ump_status fob_sfv_append(fob_sfv *f, const char *case_dir, const char *start_time, double t,
                          const fob_patch_field *vals, int precision, ump_err *err);
/* The operation's result on one field (out[ncomp]). */
void fob_sfv_eval(const fob_sfv *f, const fob_patch_field *d, double *out);
const char *fob_op_name(fob_op op);
const char *fob_field_name(fob_field f);

#endif
