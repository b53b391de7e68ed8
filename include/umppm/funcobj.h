/* SPDX-License-Identifier: GPL-3.0-or-later
 * funcobj.h -- function objects of system/controlDict's `functions`
 * dictionary that umppmFoam runs (module prefix fob_). File reading and
 * writing live here; the numbers come from the solver (sol_wall_dTdn,
 * sol_face_T) through the application.
 *
 * One type so far, the wall Nusselt number of Eqs. 43-45 of seed 000:
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
 * Entries of other types are listed in fob_list.ignored for a warning
 * (OpenFOAM's own function objects do not run in umppmFoam).
 */
#ifndef UMPPM_FUNCOBJ_H
#define UMPPM_FUNCOBJ_H

#include <stdio.h>
#include "umppm/ump.h"

typedef struct fob_nusselt {
    char name[128];
    char patch[128];
    double length, kappa;
    double T1, T2;
    int has_T1, has_T2;
    int snGrad;              /* 0: MLS gradient (default), 1: snGrad */
    int on_write_time;       /* writeControl writeTime */
    long interval;           /* writeControl timeStep: every interval steps */
    FILE *fp;                /* the open time series */
    char path[4400];
} fob_nusselt;

typedef struct fob_list {
    fob_nusselt *nu;
    int n;
    char ignored[512];       /* "name (type), ..." of entries not run here */
} fob_list;

/* Read the functions dictionary of <case>/system/controlDict (absent: an
 * empty list). Missing or bad entries are errors naming file and line. */
ump_status fob_read(const char *case_dir, fob_list *L, ump_err *err);
void fob_free(fob_list *L);

/* Per-face data of a patch for one evaluation. */
typedef struct fob_faces {
    size_t n;
    const double *x3;        /* [3n] face centres */
    const double *area;      /* [n] face areas (lengths in 2-D) */
    const double *dTdn;      /* [n] wall-normal gradient, outward */
    const double *Tf;        /* [n] face temperatures */
} fob_faces;

typedef struct fob_result {
    double Nu_avg, h_avg, q_avg, Nu_min, Nu_max, T1, T2;
} fob_result;

/* Eqs. 43-45 over the faces (T1, T2 defaults: area-mean Tf and t_ref). */
fob_result fob_nusselt_eval(const fob_nusselt *f, const fob_faces *d, double t_ref);
/* Does this step (1-based index) write the time series? */
int fob_due(const fob_nusselt *f, long step, int write_time);
/* Append one line to postProcessing/<name>/<start_time>/nusseltNumber.dat
 * (created with its header on the first call; an existing file of an
 * earlier run is kept and the new one gets the suffix _<start_time>, as
 * OpenFOAM's writeFile). */
ump_status fob_nusselt_append(fob_nusselt *f, const char *case_dir, const char *start_time, double t,
                              const fob_result *r, int precision, ump_err *err);
/* postProcessing/<name>/<time>/<patch>.dat with the local values. */
ump_status fob_nusselt_local(const fob_nusselt *f, const char *case_dir, const char *time_name,
                             const fob_faces *d, const fob_result *r, int precision, ump_err *err);

#endif
